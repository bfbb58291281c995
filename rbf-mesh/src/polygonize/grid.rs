//! Marching tetrahedra over every cell of a box, coarse to fine: f and ∇f are sampled on a
//! coarse lattice (every fourth point), and only the blocks of 4³ cubes that the surface may
//! cross are sampled in full, each lattice point once (a point on a face between two such
//! blocks is sampled by one of them).

use rayon::prelude::*;
use rbf_core::ScalarField;

use super::BlockSkip;
use super::lattice::{CrossedEdge, Lattice, cell_triangles};

/// Cells along each side of a block.
const BLOCK: i64 = 4;

/// Crossed edges (an edge once for each triangle on it), triangles on their indices, lattice
/// points sampled and blocks skipped.
pub(crate) fn cells(
    f: &dyn ScalarField<3>,
    lattice: &Lattice,
    skip: BlockSkip,
) -> (Vec<CrossedEdge>, Vec<[u32; 3]>, usize, usize) {
    let blocks: [i64; 3] = core::array::from_fn(|d| (lattice.cells[d] + BLOCK - 1) / BLOCK);
    let coarse_n: [i64; 3] = core::array::from_fn(|d| blocks[d] + 1);
    let coarse_point = |i: [i64; 3]| -> [i64; 3] {
        core::array::from_fn(|d| (i[d] * BLOCK).min(lattice.cells[d]))
    };
    // f and ∇f at the block corners.
    let count = (coarse_n[0] * coarse_n[1] * coarse_n[2]) as usize;
    let points: Vec<[f64; 3]> = (0..count as i64)
        .map(|c| {
            let i = [
                c % coarse_n[0],
                (c / coarse_n[0]) % coarse_n[1],
                c / (coarse_n[0] * coarse_n[1]),
            ];
            lattice.point(coarse_point(i))
        })
        .collect();
    let mut values = vec![0.0; count];
    let mut gradients = vec![[0.0; 3]; count];
    // Equal lengths by construction.
    let _ = f.field_values_and_gradients(&points, &mut values, &mut gradients);
    let coarse = |i: [i64; 3]| (i[0] + coarse_n[0] * (i[1] + coarse_n[1] * i[2])) as usize;

    let total = (blocks[0] * blocks[1] * blocks[2]) as usize;
    let block_of = |b: usize| {
        let b = b as i64;
        [
            b % blocks[0],
            (b / blocks[0]) % blocks[1],
            b / (blocks[0] * blocks[1]),
        ]
    };
    // What the corners say of each block.
    let mut verdicts: Vec<Verdict> = (0..total)
        .into_par_iter()
        .map(|b| {
            let block = block_of(b);
            let lo = coarse_point(block);
            let hi = coarse_point([block[0] + 1, block[1] + 1, block[2] + 1]);
            let (a, c) = (lattice.point(lo), lattice.point(hi));
            let half_diagonal = 0.5 * rbf_core::vec3::norm(rbf_core::vec3::sub(c, a));
            let corners = (0..8).map(|k: i64| {
                coarse([
                    block[0] + (k & 1),
                    block[1] + ((k >> 1) & 1),
                    block[2] + (k >> 2),
                ])
            });
            match skip {
                BlockSkip::Never => Verdict::Sample,
                BlockSkip::Proven => {
                    let centre = core::array::from_fn(|d| 0.5 * (a[d] + c[d]));
                    if f.direct().ball_bound(&centre, half_diagonal).one_sign() {
                        Verdict::Skip
                    } else {
                        Verdict::Sample
                    }
                }
                BlockSkip::Estimated => {
                    // Every point of the block is within half a diagonal of a corner.
                    let (mut slope, mut smallest, mut positive) = (0.0_f64, f64::INFINITY, 0);
                    for k in corners {
                        slope = slope.max(rbf_core::vec3::norm(gradients[k]));
                        smallest = smallest.min(values[k].abs());
                        positive += usize::from(values[k] > 0.0);
                    }
                    let one_sign = positive == 0 || positive == 8;
                    let whole = (0..3).all(|d| hi[d] - lo[d] == BLOCK);
                    if one_sign && smallest > 1.5 * slope * half_diagonal {
                        Verdict::Skip
                    } else if one_sign && whole {
                        Verdict::AskCentre {
                            positive: positive == 8,
                            smallest,
                            slope,
                        }
                    } else {
                        Verdict::Sample
                    }
                }
            }
        })
        .collect();
    // Blocks whose corners have one sign but lie close to the surface: f and ∇f at their
    // centres, in one batch. Every point of a block of 4³ cubes is within √5 cubes of a corner
    // or the centre (half a diagonal is 2√3 cubes), so the same test with the centre skips
    // blocks up to 1.5 times closer to the surface.
    let asked: Vec<usize> = (0..total)
        .filter(|&b| matches!(verdicts[b], Verdict::AskCentre { .. }))
        .collect();
    let centres: Vec<[f64; 3]> = asked
        .iter()
        .map(|&b| {
            let lo = coarse_point(block_of(b));
            lattice
                .point(lo)
                .map(|v| v + 0.5 * BLOCK as f64 * lattice.h)
        })
        .collect();
    let mut centre_values = vec![0.0; centres.len()];
    let mut centre_gradients = vec![[0.0; 3]; centres.len()];
    // Equal lengths by construction.
    let _ = f.field_values_and_gradients(&centres, &mut centre_values, &mut centre_gradients);
    let reach = 5.0_f64.sqrt() * lattice.h;
    for (i, &b) in asked.iter().enumerate() {
        if let Verdict::AskCentre {
            positive,
            smallest,
            slope,
        } = verdicts[b]
        {
            let v = centre_values[i];
            let slope = slope.max(rbf_core::vec3::norm(centre_gradients[i]));
            let skip = (v > 0.0) == positive && smallest.min(v.abs()) > 1.5 * slope * reach;
            verdicts[b] = if skip { Verdict::Skip } else { Verdict::Sample };
        }
    }
    // The blocks that may hold surface, in order of their number.
    let sampled: Vec<usize> = (0..total)
        .filter(|&b| matches!(verdicts[b], Verdict::Sample))
        .collect();
    let count = count + centres.len();
    let blocks_sampled: Vec<SampledBlock> = sampled
        .par_iter()
        .map(|&b| {
            let block = block_of(b);
            let lo = coarse_point(block);
            let hi = coarse_point([block[0] + 1, block[1] + 1, block[2] + 1]);
            let neighbours = core::array::from_fn(|k| {
                let k = k as i64;
                let n = [
                    block[0] + k % 3 - 1,
                    block[1] + (k / 3) % 3 - 1,
                    block[2] + k / 9 - 1,
                ];
                if (0..3).any(|d| n[d] < 0 || n[d] >= blocks[d]) {
                    return None;
                }
                let id = (n[0] + blocks[0] * (n[1] + blocks[1] * n[2])) as usize;
                sampled.binary_search(&id).ok().map(|i| i as u32)
            });
            SampledBlock {
                lo,
                n: [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]],
                neighbours,
            }
        })
        .collect();
    // Each block samples the lattice points it owns (a point on a face between sampled blocks
    // is sampled once, by one of them).
    let owned: Vec<Vec<f64>> = blocks_sampled
        .par_iter()
        .map(|block| block.sample_owned(f, lattice))
        .collect();
    let samples = count + owned.iter().flatten().filter(|v| !v.is_nan()).count();
    let results: Vec<(Vec<CrossedEdge>, Vec<[u32; 3]>)> = blocks_sampled
        .par_iter()
        .map(|block| {
            let values = block.gather(&blocks_sampled, &owned);
            let (mut edges, mut tris) = (Vec::new(), Vec::new());
            block.cells(&values, &mut edges, &mut tris);
            (edges, tris)
        })
        .collect();
    let mut edges = Vec::new();
    let mut tris = Vec::new();
    for (e, t) in results {
        // Each block numbers the edges it lists from 0.
        let offset = edges.len() as u32;
        edges.extend(e);
        tris.extend(t.into_iter().map(|t| t.map(|i| i + offset)));
    }
    (edges, tris, samples, total - sampled.len())
}

/// What a block's corners say.
#[derive(Clone, Copy)]
enum Verdict {
    /// The surface cannot cross it.
    Skip,
    /// It may hold surface.
    Sample,
    /// Its corners have one sign (`positive` or not) but are too close to the surface to
    /// skip it: ask f at its centre. The smallest |f| and largest |∇f| at its corners.
    AskCentre {
        positive: bool,
        smallest: f64,
        slope: f64,
    },
}

/// A block that may hold surface.
struct SampledBlock {
    /// Its lowest lattice point.
    lo: [i64; 3],
    /// Cells along each side (4, or fewer at the box's upper faces).
    n: [i64; 3],
    /// The sampled blocks among its 27 neighbours (itself included), as indices into the list
    /// of sampled blocks; neighbour (dx, dy, dz) ∈ {−1, 0, 1}³ at (dx + 1) + 3 (dy + 1) +
    /// 9 (dz + 1).
    neighbours: [Option<u32>; 27],
}

impl SampledBlock {
    /// Lattice points along each side.
    fn points(&self) -> [i64; 3] {
        [self.n[0] + 1, self.n[1] + 1, self.n[2] + 1]
    }

    /// The offset of the block that owns this block's local point `l`: of the sampled blocks
    /// that hold the point (up to eight, on faces, edges and corners of blocks), the one
    /// numbered highest, so that every block holding the point agrees.
    fn owner(&self, l: [i64; 3]) -> [i64; 3] {
        let choices = |d: usize| -> [i64; 2] {
            if l[d] == self.n[d] {
                [1, 0]
            } else if l[d] == 0 {
                [0, -1]
            } else {
                [0, 0]
            }
        };
        // Block numbers grow with z, then y, then x: the first sampled offset in that order
        // is the highest numbered.
        for dz in choices(2) {
            for dy in choices(1) {
                for dx in choices(0) {
                    if self.neighbours[offset_index([dx, dy, dz])].is_some() {
                        return [dx, dy, dz];
                    }
                }
            }
        }
        [0, 0, 0]
    }

    /// f at the lattice points this block owns; NaN at the others.
    fn sample_owned(&self, f: &dyn ScalarField<3>, lattice: &Lattice) -> Vec<f64> {
        let m = self.points();
        let mut owned = vec![f64::NAN; (m[0] * m[1] * m[2]) as usize];
        let mut at = Vec::new();
        let mut points = Vec::new();
        for k in 0..m[2] {
            for j in 0..m[1] {
                for i in 0..m[0] {
                    if self.owner([i, j, k]) == [0, 0, 0] {
                        at.push((i + m[0] * (j + m[1] * k)) as usize);
                        points.push(lattice.point([
                            self.lo[0] + i,
                            self.lo[1] + j,
                            self.lo[2] + k,
                        ]));
                    }
                }
            }
        }
        let mut values = vec![0.0; points.len()];
        // Equal lengths by construction.
        let _ = f.field_values(&points, &mut values);
        for (i, v) in at.into_iter().zip(values) {
            owned[i] = v;
        }
        owned
    }

    /// f at every lattice point of the block, from the blocks that own them.
    fn gather(&self, blocks: &[SampledBlock], owned: &[Vec<f64>]) -> Vec<f64> {
        let m = self.points();
        let mut values = Vec::with_capacity((m[0] * m[1] * m[2]) as usize);
        for k in 0..m[2] {
            for j in 0..m[1] {
                for i in 0..m[0] {
                    let l = [i, j, k];
                    let d = self.owner(l);
                    let Some(o) = self.neighbours[offset_index(d)] else {
                        values.push(f64::NAN);
                        continue;
                    };
                    let owner = &blocks[o as usize];
                    let q: [i64; 3] = core::array::from_fn(|a| self.lo[a] + l[a] - owner.lo[a]);
                    let om = owner.points();
                    values.push(owned[o as usize][(q[0] + om[0] * (q[1] + om[1] * q[2])) as usize]);
                }
            }
        }
        values
    }

    /// Polygonizes the block's cells from f at its lattice points.
    /// Triangles on indices into `edges`, which lists an edge once for each triangle on it.
    fn cells(&self, values: &[f64], edges: &mut Vec<CrossedEdge>, tris: &mut Vec<[u32; 3]>) {
        let m = self.points();
        let at = |i: i64, j: i64, k: i64| values[(i + m[0] * (j + m[1] * k)) as usize];
        for k in 0..self.n[2] {
            for j in 0..self.n[1] {
                for i in 0..self.n[0] {
                    let corners: [f64; 8] = core::array::from_fn(|c| {
                        at(
                            i + (c & 1) as i64,
                            j + ((c >> 1) & 1) as i64,
                            k + ((c >> 2) & 1) as i64,
                        )
                    });
                    let cell = [self.lo[0] + i, self.lo[1] + j, self.lo[2] + k];
                    cell_triangles(cell, &corners, tris, |key, lo, hi| {
                        edges.push((key, lo, hi));
                        (edges.len() - 1) as u32
                    });
                }
            }
        }
    }
}

/// The index of block offset d ∈ {−1, 0, 1}³ among a block's 27 neighbours.
fn offset_index(d: [i64; 3]) -> usize {
    ((d[0] + 1) + 3 * (d[1] + 1) + 9 * (d[2] + 1)) as usize
}
