//! The iterative solver's products with the whole system, [Φ + Λ, P; Pᵀ, 0] x: by compensated
//! direct sums on small systems, through the far field (rbf-far) on large ones, with its order
//! chosen against the tolerance and every claimed convergence certified by direct sums at
//! sampled rows.

use std::sync::atomic::{AtomicBool, Ordering};

use rbf_core::{InterpolantView, System};
use rbf_far::{FarField, calibrated};

/// Rows from which the far field is tried by default. The solver's accuracy takes order 12 on
/// the peers' surface problem, where one far product costs about what compensated direct sums
/// do up to 3·10⁵ rows (1.15 s at 10⁵, 3.2 s against 4.6 s at 2·10⁵, 8.9 s against 10 s at
/// 3·10⁵), and GMRES needs more iterations with it (3·10⁵ rows: 25 iterations, 366 s, against
/// 17 and 329 s by direct sums); at 10⁶ a direct product takes about two minutes.
pub(crate) const FAR_FIELD_ROWS: usize = 400_000;

/// Rows at which direct sums certify a residual: the worst of the fast residual, and as many
/// spread over the rows.
const CERTIFIED_ROWS: usize = 1000;

/// How the products are taken.
pub(crate) struct Products<'a, const D: usize> {
    system: &'a System<D>,
    far: Option<FarField<D>>,
    /// Set once the far field failed a certification: direct sums from then on.
    direct: AtomicBool,
}

impl<'a, const D: usize> Products<'a, D> {
    /// Direct sums.
    pub(crate) fn direct(system: &'a System<D>) -> Self {
        Self {
            system,
            far: None,
            direct: AtomicBool::new(true),
        }
    }

    /// The far field at the lowest order whose error on `trial` weights (a first approximation
    /// of the solution, of its size and cancellations) is within `accuracy` (absolute, in the
    /// values' units) at sampled rows; direct sums if no order is.
    pub(crate) fn far(system: &'a System<D>, trial: &[f64], accuracy: f64) -> Self {
        let points = system.normalized_points();
        let rows = spread_rows(points.len(), 2 * CERTIFIED_ROWS);
        let sample: Vec<[f64; D]> = rows.iter().map(|&i| points[i]).collect();
        match calibrated(system.kernel(), points, trial, &sample, 0.25 * accuracy) {
            Some((field, _, _)) => Self {
                system,
                far: Some(field),
                direct: AtomicBool::new(false),
            },
            None => Self::direct(system),
        }
    }

    /// Whether products go through the far field now.
    pub(crate) fn is_far(&self) -> bool {
        self.far.is_some() && !self.direct.load(Ordering::Relaxed)
    }

    /// The far field's order, while it is in use.
    pub(crate) fn order(&self) -> Option<usize> {
        self.far
            .as_ref()
            .filter(|_| self.is_far())
            .map(|f| f.settings().order)
    }

    /// Direct sums from now on.
    pub(crate) fn use_direct(&self) {
        self.direct.store(true, Ordering::Relaxed);
    }

    /// out = A x (normalized).
    pub(crate) fn apply(&self, x: &[f64], out: &mut [f64]) {
        let system = self.system;
        let points = system.normalized_points();
        let k = points.len();
        let (w, c) = x.split_at(k);
        match self.far.as_ref().filter(|_| self.is_far()) {
            Some(field) => {
                // Lengths match by construction; a mismatch would show as NaN, like direct sums.
                let product = field
                    .charges(w)
                    .and_then(|charges| field.self_values(&charges, &mut out[..k]));
                if product.is_err() {
                    out.fill(f64::NAN);
                    return;
                }
                for (o, p) in out[..k].iter_mut().zip(points) {
                    *o += affine(c, p);
                }
            }
            None => {
                let linear: [f64; D] = core::array::from_fn(|d| c[d + 1]);
                let evaluated = InterpolantView::new(system.kernel(), points, w, c[0], linear)
                    .and_then(|f| f.par_values_compensated(points, &mut out[..k]));
                if evaluated.is_err() {
                    out.fill(f64::NAN);
                    return;
                }
            }
        }
        for (i, (o, wi)) in out[..k].iter_mut().zip(w).enumerate() {
            *o += system.normalized_smoothing(i) * wi;
        }
        let g = &mut out[k..];
        g.fill(0.0);
        for (wi, p) in w.iter().zip(points) {
            g[0] += wi;
            for d in 0..D {
                g[d + 1] += wi * p[d];
            }
        }
    }

    /// The largest |(A x)ᵢ − bᵢ| by compensated direct sums at the rows where `residual` (the
    /// far field's) is largest and at rows spread over all: what certifies a far-field solve.
    pub(crate) fn certify(&self, x: &[f64], residual: &[f64]) -> f64 {
        let system = self.system;
        let points = system.normalized_points();
        let k = points.len();
        let mut rows = spread_rows(k, CERTIFIED_ROWS);
        let mut by_size: Vec<usize> = (0..k).collect();
        let worst = CERTIFIED_ROWS.min(k);
        if worst > 0 && worst < k {
            by_size.select_nth_unstable_by(worst - 1, |&a, &b| {
                residual[b].abs().total_cmp(&residual[a].abs())
            });
        }
        rows.extend_from_slice(&by_size[..worst]);
        rows.sort_unstable();
        rows.dedup();
        let (w, c) = x.split_at(k);
        let targets: Vec<[f64; D]> = rows.iter().map(|&i| points[i]).collect();
        let mut fx = vec![0.0; rows.len()];
        let linear: [f64; D] = core::array::from_fn(|d| c[d + 1]);
        let evaluated = InterpolantView::new(system.kernel(), points, w, c[0], linear)
            .and_then(|f| f.par_values_compensated(&targets, &mut fx));
        if evaluated.is_err() {
            return f64::NAN;
        }
        rows.iter()
            .zip(&fx)
            .map(|(&i, f)| (f + system.normalized_smoothing(i) * w[i] - system.values()[i]).abs())
            .fold(0.0, f64::max)
    }
}

fn affine<const D: usize>(c: &[f64], p: &[f64; D]) -> f64 {
    c[0] + (0..D).map(|d| c[d + 1] * p[d]).sum::<f64>()
}

/// About `count` row indices spread evenly over 0..k (all of them if k ≤ count).
pub(crate) fn spread_rows(k: usize, count: usize) -> Vec<usize> {
    if k <= count {
        return (0..k).collect();
    }
    (0..count).map(|i| i * k / count).collect()
}
