//! Exact distances from a few voxels to the nearest of a set of voxels, without a distance
//! transform over the whole volume.
//!
//! The error of one iteration needs, at every goal boundary voxel, the distance to the nearest
//! boundary voxel of the current surface: a thin set queried from a thin set. The sources are
//! binned into cubes of [`CELL`] voxels, and each query searches rings of cubes outward until
//! no farther ring can hold anything closer.

use rayon::prelude::*;

/// Side of a bin, in voxels.
const CELL: usize = 4;

/// Voxels binned into cubes, in compressed rows: bin b holds `voxels[start[b]..start[b + 1]]`.
pub(crate) struct VoxelBins {
    bins: [usize; 3],
    start: Vec<u32>,
    voxels: Vec<[i32; 3]>,
}

impl VoxelBins {
    /// Bins `sources` (linear indices into a volume of `shape`, C order).
    pub(crate) fn new(shape: [usize; 3], sources: &[usize]) -> Self {
        let bins = shape.map(|n| n.div_ceil(CELL).max(1));
        let coords = |v: usize| {
            let [_, ny, nz] = shape;
            [v / (ny * nz), (v / nz) % ny, v % nz]
        };
        let bin_of =
            |c: [usize; 3]| ((c[0] / CELL) * bins[1] + c[1] / CELL) * bins[2] + c[2] / CELL;
        let mut start = vec![0u32; bins[0] * bins[1] * bins[2] + 1];
        for &v in sources {
            start[bin_of(coords(v)) + 1] += 1;
        }
        for b in 1..start.len() {
            start[b] += start[b - 1];
        }
        let mut next = start.clone();
        let mut voxels = vec![[0i32; 3]; sources.len()];
        for &v in sources {
            let c = coords(v);
            let b = bin_of(c);
            voxels[next[b] as usize] = c.map(|x| x as i32);
            next[b] += 1;
        }
        Self {
            bins,
            start,
            voxels,
        }
    }

    /// The Euclidean distance, in voxels, from each of `queries` (linear indices into a volume
    /// of `shape`) to the nearest binned voxel; infinite when there is none.
    pub(crate) fn distances(&self, shape: [usize; 3], queries: &[usize]) -> Vec<f64> {
        let [_, ny, nz] = shape;
        queries
            .par_iter()
            .map(|&v| self.nearest([v / (ny * nz), (v / nz) % ny, v % nz]))
            .collect()
    }

    fn nearest(&self, c: [usize; 3]) -> f64 {
        if self.voxels.is_empty() {
            return f64::INFINITY;
        }
        let home = c.map(|x| (x / CELL) as i64);
        let q = c.map(|x| x as i64);
        let most = (0..3)
            .map(|d| home[d].max(self.bins[d] as i64 - 1 - home[d]))
            .max()
            .unwrap_or(0);
        let mut best = i64::MAX;
        for ring in 0..=most {
            self.visit_ring(home, ring, |p| {
                let d2 = (0..3).map(|d| (p[d] as i64 - q[d]).pow(2)).sum::<i64>();
                best = best.min(d2);
            });
            // Every bin of a farther ring is at least `ring` whole bins away.
            let reach = ring * CELL as i64;
            if best <= reach * reach {
                break;
            }
        }
        (best as f64).sqrt()
    }

    /// Calls `f` on every voxel in the bins at Chebyshev distance `ring` from `home`.
    fn visit_ring(&self, home: [i64; 3], ring: i64, mut f: impl FnMut([i32; 3])) {
        let range = |d: usize| {
            let lo = (home[d] - ring).max(0);
            let hi = (home[d] + ring).min(self.bins[d] as i64 - 1);
            lo..=hi
        };
        let mut visit_bin = |i: i64, j: i64, k: i64| {
            let b = (i as usize * self.bins[1] + j as usize) * self.bins[2] + k as usize;
            let (s, e) = (self.start[b] as usize, self.start[b + 1] as usize);
            self.voxels[s..e].iter().for_each(|&p| f(p));
        };
        for i in range(0) {
            let on_i = (i - home[0]).abs() == ring;
            for j in range(1) {
                if on_i || (j - home[1]).abs() == ring {
                    range(2).for_each(|k| visit_bin(i, j, k));
                } else {
                    // Inside the ring in x and y: only its two faces along z.
                    for k in [home[2] - ring, home[2] + ring] {
                        if (0..self.bins[2] as i64).contains(&k) {
                            visit_bin(i, j, k);
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rbf_mesh::squared_distance_transform;

    /// Brute force over all pairs.
    fn brute(shape: [usize; 3], sources: &[usize], queries: &[usize]) -> Vec<f64> {
        let [_, ny, nz] = shape;
        let c = |v: usize| [v / (ny * nz), (v / nz) % ny, v % nz].map(|x| x as f64);
        queries
            .iter()
            .map(|&q| {
                sources
                    .iter()
                    .map(|&s| {
                        (0..3)
                            .map(|d| (c(s)[d] - c(q)[d]).powi(2))
                            .sum::<f64>()
                            .sqrt()
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .collect()
    }

    fn pseudo_random(seed: &mut u64, n: usize) -> usize {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((*seed >> 33) as usize) % n
    }

    #[test]
    fn matches_brute_force_and_the_distance_transform() {
        let mut seed = 7;
        for (shape, count) in [
            ([9, 5, 13], 3),
            ([17, 17, 17], 1),
            ([30, 12, 7], 40),
            ([1, 1, 23], 2),
        ] {
            let n = shape[0] * shape[1] * shape[2];
            let sources: Vec<usize> = (0..count).map(|_| pseudo_random(&mut seed, n)).collect();
            let queries: Vec<usize> = (0..n).collect();
            let got = VoxelBins::new(shape, &sources).distances(shape, &queries);
            assert_eq!(got, brute(shape, &sources, &queries), "{shape:?}");
            let mut cost = vec![f64::INFINITY; n];
            for &s in &sources {
                cost[s] = 0.0;
            }
            squared_distance_transform(shape, &mut cost);
            let edt: Vec<f64> = cost.into_iter().map(f64::sqrt).collect();
            assert_eq!(got, edt, "{shape:?}");
        }
    }

    #[test]
    fn no_sources_means_infinitely_far() {
        let d = VoxelBins::new([4, 4, 4], &[]).distances([4, 4, 4], &[0, 63]);
        assert_eq!(d, vec![f64::INFINITY; 2]);
    }
}
