//! f at a model's own centres, on every core, with each pair of centres evaluated once: the
//! kernel matrix is symmetric, so one tile of it gives the sums of its rows and of its columns
//! together, for half the kernel evaluations of [`InterpolantView::par_values_compensated`]
//! at the centres (the product an iterative solver takes at every step).

use alloc::vec;
use alloc::vec::Vec;

use rayon::prelude::*;

use crate::kernel::{Radial, with_radial};
use crate::parallel::neumaier;
use crate::{InterpolantView, LengthMismatch};

/// Targets evaluated side by side (one AVX-512 register of doubles).
const LANES: usize = 8;

/// Centres along a tile's side: its targets (coordinates, weights and sums, 20 kB in 3D) stay
/// in the first-level cache while the tile's centres stream past them.
const TILE: usize = 512;

/// Centres from which the tiles pay: below, too few tiles share out among the cores (1000
/// centres: 0.8 ms by tiles, 0.3 ms by [`InterpolantView::par_values_compensated`] on two
/// cores; 4000: 3.5 and 5 ms).
const SMALLEST: usize = 4 * TILE;

/// Shares of the tiles, each summing into rows of its own (two numbers a row: 128 bytes a row in
/// all): enough for a core done early to take over work on a machine of a few cores, and a
/// number fixed whatever the cores, so that the sums, rounded alike, give the same products
/// everywhere (and the iterative solver the same iterations).
const SHARES: usize = 8;

/// Lane groups along a tile's side.
const GROUPS: usize = TILE / LANES;

impl<const D: usize> InterpolantView<'_, f64, D> {
    /// `out[i] = f(cᵢ)` at the model's own centres, on every core: the same numbers as
    /// [`InterpolantView::par_values_compensated`] at the centres, to rounding, from 2048
    /// centres (below, it is that function) in 0.55–0.7 of its time (10⁵ centres: 1.45 s
    /// against 3.0 s on two cores; 4000: 3.5 against 5 ms). Off the diagonal tiles each pair of
    /// centres is evaluated once, φ(|cᵢ − cⱼ|) serving row i and row j; partial sums over 512
    /// centres are added with Neumaier's compensation, so rounding grows with the tile, not
    /// with K.
    ///
    /// ```
    /// use rbf_core::{InterpolantView, Kernel};
    /// let centres = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
    /// let f = InterpolantView::new(Kernel::Cubic, &centres, &[1.0, -1.0, 0.5], 1.0, [0.0; 3])
    ///     .unwrap();
    /// let mut out = [0.0; 3];
    /// f.par_values_at_centres(&mut out).unwrap();
    /// // f(c₀) = 1·0³ − 1·1³ + 0.5·2³ + 1 = 4
    /// assert_eq!(out[0], 4.0);
    /// ```
    pub fn par_values_at_centres(&self, out: &mut [f64]) -> Result<(), LengthMismatch> {
        let (centres, weights) = (self.centres(), self.weights());
        LengthMismatch::check("output", centres.len(), out.len())?;
        let k = centres.len();
        if k < SMALLEST {
            return self.par_values_compensated(centres, out);
        }
        let lanes = Lanes::new(centres, weights);
        let sides = k.div_ceil(TILE);
        // The tiles on and above the diagonal, in shares that sum into rows of their own.
        let tiles: Vec<(usize, usize)> = (0..sides)
            .flat_map(|a| (a..sides).map(move |b| (a, b)))
            .collect();
        let per_share = tiles.len().div_ceil(SHARES).max(1);
        let kernel = self.kernel();
        let partials: Vec<Compensated> = tiles
            .par_chunks(per_share)
            .map(|share| {
                let mut sums = Compensated::new(k);
                let mut rows = [[0.0; LANES]; GROUPS];
                let mut cols = [0.0; TILE];
                for &(a, b) in share {
                    let targets = a * GROUPS..((a + 1) * GROUPS).min(lanes.coords.len());
                    let sources = b * TILE..((b + 1) * TILE).min(k);
                    let (lo, n) = (targets.start, targets.len());
                    rows[..n].fill([0.0; LANES]);
                    tile(
                        kernel,
                        &lanes.coords[targets.clone()],
                        &lanes.weights[targets],
                        &centres[sources.clone()],
                        &weights[sources.clone()],
                        &mut rows[..n],
                        (a != b).then_some(&mut cols[..sources.len()]),
                    );
                    let rows_of_a = (lo * LANES..((lo + n) * LANES).min(k)).len();
                    sums.add(a * TILE, &rows.as_flattened()[..rows_of_a]);
                    if a != b {
                        sums.add(b * TILE, &cols[..sources.len()]);
                    }
                }
                sums
            })
            .collect();
        out.par_iter_mut()
            .zip(centres.par_iter())
            .enumerate()
            .for_each(|(i, (o, c))| {
                let (mut sum, mut compensation) = (0.0, 0.0);
                for part in &partials {
                    neumaier(&mut sum, &mut compensation, part.sum[i]);
                    compensation += part.compensation[i];
                }
                *o = sum + compensation + self.affine(c);
            });
        Ok(())
    }
}

/// The centres lane by lane, the last group padded with weightless copies of the last centre.
struct Lanes<const D: usize> {
    coords: Vec<[[f64; LANES]; D]>,
    weights: Vec<[f64; LANES]>,
}

impl<const D: usize> Lanes<D> {
    fn new(centres: &[[f64; D]], weights: &[f64]) -> Self {
        let groups = centres.len().div_ceil(LANES);
        let last = centres.last().copied().unwrap_or([0.0; D]);
        let mut coords = vec![[[0.0; LANES]; D]; groups];
        let mut lane_weights = vec![[0.0; LANES]; groups];
        for g in 0..groups {
            for l in 0..LANES {
                let i = g * LANES + l;
                let c = centres.get(i).copied().unwrap_or(last);
                for d in 0..D {
                    coords[g][d][l] = c[d];
                }
                lane_weights[g][l] = weights.get(i).copied().unwrap_or(0.0);
            }
        }
        Self {
            coords,
            weights: lane_weights,
        }
    }
}

/// Sums with Neumaier's compensation, one per row.
struct Compensated {
    sum: Vec<f64>,
    compensation: Vec<f64>,
}

impl Compensated {
    fn new(rows: usize) -> Self {
        Self {
            sum: vec![0.0; rows],
            compensation: vec![0.0; rows],
        }
    }

    /// Adds `terms` to the rows from `first` on.
    fn add(&mut self, first: usize, terms: &[f64]) {
        let rows = first..first + terms.len();
        for ((s, c), &t) in self.sum[rows.clone()]
            .iter_mut()
            .zip(&mut self.compensation[rows])
            .zip(terms)
        {
            neumaier(s, c, t);
        }
    }
}

/// One tile: `rows` (the targets' lane groups) gain Σⱼ wⱼ φ(|tᵢ − cⱼ|) over the tile's centres,
/// and, off the diagonal, `cols[j]` gets Σᵢ wᵢ φ(|tᵢ − cⱼ|) over its targets. Runs the loop
/// compiled for AVX-512 or AVX2 when the CPU has them.
#[inline(always)]
fn tile<const D: usize>(
    kernel: crate::Kernel,
    targets: &[[[f64; LANES]; D]],
    target_weights: &[[f64; LANES]],
    centres: &[[f64; D]],
    weights: &[f64],
    rows: &mut [[f64; LANES]],
    cols: Option<&mut [f64]>,
) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::is_x86_feature_detected!("avx512f")
            && std::is_x86_feature_detected!("avx512vl")
            && std::is_x86_feature_detected!("avx2")
            && std::is_x86_feature_detected!("fma")
        {
            // SAFETY: the CPU supports every feature the function enables, checked just above.
            unsafe {
                tile_avx512(
                    kernel,
                    targets,
                    target_weights,
                    centres,
                    weights,
                    rows,
                    cols,
                )
            };
            return;
        }
        if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
            // SAFETY: the CPU supports AVX2 and FMA, checked just above.
            unsafe {
                tile_avx2(
                    kernel,
                    targets,
                    target_weights,
                    centres,
                    weights,
                    rows,
                    cols,
                )
            };
            return;
        }
    }
    tile_portable(
        kernel,
        targets,
        target_weights,
        centres,
        weights,
        rows,
        cols,
    );
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
fn tile_avx512<const D: usize>(
    kernel: crate::Kernel,
    targets: &[[[f64; LANES]; D]],
    target_weights: &[[f64; LANES]],
    centres: &[[f64; D]],
    weights: &[f64],
    rows: &mut [[f64; LANES]],
    cols: Option<&mut [f64]>,
) {
    tile_portable(
        kernel,
        targets,
        target_weights,
        centres,
        weights,
        rows,
        cols,
    );
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn tile_avx2<const D: usize>(
    kernel: crate::Kernel,
    targets: &[[[f64; LANES]; D]],
    target_weights: &[[f64; LANES]],
    centres: &[[f64; D]],
    weights: &[f64],
    rows: &mut [[f64; LANES]],
    cols: Option<&mut [f64]>,
) {
    tile_portable(
        kernel,
        targets,
        target_weights,
        centres,
        weights,
        rows,
        cols,
    );
}

#[inline(always)]
fn tile_portable<const D: usize>(
    kernel: crate::Kernel,
    targets: &[[[f64; LANES]; D]],
    target_weights: &[[f64; LANES]],
    centres: &[[f64; D]],
    weights: &[f64],
    rows: &mut [[f64; LANES]],
    cols: Option<&mut [f64]>,
) {
    match cols {
        Some(cols) => with_radial!(kernel, K => tile_with::<K, D, true>(
            targets, target_weights, centres, weights, rows, cols
        )),
        None => with_radial!(kernel, K => tile_with::<K, D, false>(
            targets, target_weights, centres, weights, rows, &mut []
        )),
    }
}

/// [`tile`] for one kernel; `COLUMNS` false on the diagonal, where every row is summed whole.
#[inline(always)]
fn tile_with<K: Radial, const D: usize, const COLUMNS: bool>(
    targets: &[[[f64; LANES]; D]],
    target_weights: &[[f64; LANES]],
    centres: &[[f64; D]],
    weights: &[f64],
    rows: &mut [[f64; LANES]],
    cols: &mut [f64],
) {
    for (j, (c, &w)) in centres.iter().zip(weights).enumerate() {
        let mut col = [0.0; LANES];
        for ((t, tw), row) in targets.iter().zip(target_weights).zip(rows.iter_mut()) {
            let mut r2 = [0.0; LANES];
            for d in 0..D {
                for l in 0..LANES {
                    let x = t[d][l] - c[d];
                    r2[l] += x * x;
                }
            }
            for l in 0..LANES {
                let phi = K::phi_r2(r2[l]);
                row[l] += w * phi;
                if COLUMNS {
                    col[l] += tw[l] * phi;
                }
            }
        }
        if COLUMNS {
            cols[j] = col.iter().sum();
        }
    }
}
