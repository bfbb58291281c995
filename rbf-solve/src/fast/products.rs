//! The iterative solver's products with the whole system, [Φ + Λ, P; Pᵀ, 0] x: by compensated
//! direct sums on small systems, through the far field (rbf-far) on large ones, with its order
//! chosen against the tolerance and every claimed convergence certified by direct sums at
//! sampled rows.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{PoisonError, RwLock};

use rbf_core::{InterpolantView, System};
use rbf_far::{FarField, FarFieldSettings, calibrated_product};

/// Rows from which the far field is tried by default. The solver's accuracy takes order 12 on
/// the peers' surface problem, where one far product costs about what compensated direct sums
/// do up to 3·10⁵ rows (1.15 s at 10⁵, 3.2 s against 4.6 s at 2·10⁵, 8.9 s against 10 s at
/// 3·10⁵), and GMRES needs more iterations with it (3·10⁵ rows: 25 iterations, 366 s, against
/// 17 and 329 s by direct sums); at 10⁶ a direct product takes about two minutes.
pub(crate) const FAR_FIELD_ROWS: usize = 400_000;

/// Rows from which Krylov products may go through a cheaper, less accurate far field once the
/// residual they reduce is small. Below, direct sums cost too little to gain from it: relaxed,
/// a check must take a product at every row (the recurrence's residual is off course), and
/// the far fields take time to build and measure. On the peers' surface problem, every
/// default, run in turn: 10⁵ rows 19.2 s relaxed against 17.4 s exact, 1.5·10⁵ rows 40.9 s
/// against 37.8 s, 2·10⁵ rows 46.9 s against 57.0 s.
pub(crate) const RELAXED_ROWS: usize = 175_000;

/// The far fields tried for relaxed products, cheapest first (order, θ). On the weights of a
/// 10⁵-row fit of the peers' surface problem (one product, 2 cores): 0.50 s at an error of 8e-3
/// of max|h|, 0.75 s at 5e-4, 0.93 s at 4e-5, against 1.5 s by compensated direct sums.
const RELAXED: [(usize, f64); 3] = [(10, 0.8), (12, 0.9), (12, 0.7)];

/// Rows at which a far field's product is measured against compensated direct sums before it
/// is used: every row of leaves spread over the tree.
const CALIBRATION_ROWS: usize = 2 * CERTIFIED_ROWS;

/// Rows at which direct sums certify a residual: the worst of the fast residual, and as many
/// spread over the rows.
const CERTIFIED_ROWS: usize = 1000;

/// How the products are taken.
pub(crate) struct Products<'a, const D: usize> {
    system: &'a System<D>,
    /// The far field of the products; none for direct sums. A far field that fails a
    /// certification gives way to a more accurate one, or to direct sums.
    far: RwLock<Option<FarField<D>>>,
    /// The tolerance (absolute): the far field chosen on the trial may err a quarter of it at
    /// sampled rows, one chosen on an iterate checked near the solution half.
    accuracy: f64,
    /// Far fields for products that may be less accurate, cheapest first, each with its error
    /// at sampled rows on the trial weights relative to max|hᵢ|; each more accurate than those
    /// before it.
    relaxed: Vec<(FarField<D>, f64)>,
    /// Set once relaxed products took the solve off course: no more of them.
    exact_only: AtomicBool,
    /// Products taken through a relaxed far field, and all products.
    relaxed_count: AtomicUsize,
    count: AtomicUsize,
}

impl<'a, const D: usize> Products<'a, D> {
    /// Direct sums.
    pub(crate) fn direct(system: &'a System<D>) -> Self {
        Self {
            system,
            far: RwLock::new(None),
            accuracy: 0.0,
            relaxed: Vec::new(),
            exact_only: AtomicBool::new(false),
            relaxed_count: AtomicUsize::new(0),
            count: AtomicUsize::new(0),
        }
    }

    /// The far field at the lowest order whose error on `trial` weights (a first approximation
    /// of the solution, of its size and cancellations) is within `accuracy` (absolute, in the
    /// values' units) at sampled rows; direct sums if no order is.
    pub(crate) fn far(system: &'a System<D>, trial: &[f64], accuracy: f64) -> Self {
        let points = system.normalized_points();
        let field = calibrated_product(
            system.kernel(),
            points,
            trial,
            0.25 * accuracy,
            0,
            CALIBRATION_ROWS,
        );
        Self {
            far: RwLock::new(field.map(|(field, _)| field)),
            accuracy,
            ..Self::direct(system)
        }
    }

    /// After the far field failed a certification on the weights `x`: the next higher order
    /// whose error on them is within half the tolerance at sampled rows takes its place (the
    /// iterate is near the solution, so what the far field errs on it is what the final residual
    /// will see; the other half is the solver's), else direct sums. Returns the new order
    /// (`None`: direct sums). On 5·10⁵ rows of the peers' surface problem, order 12 chosen on
    /// the first approximation erred 1.2e-5 of max|h| on the solution, where 1e-5 was asked;
    /// on 10⁶ rows 4.2e-5, and order 14 certified 4.4e-6.
    pub(crate) fn refine(&self, x: &[f64]) -> Option<usize> {
        let system = self.system;
        let points = system.normalized_points();
        let weights = &x[..points.len()];
        let better = calibrated_product(
            system.kernel(),
            points,
            weights,
            0.5 * self.accuracy,
            self.order()?,
            CALIBRATION_ROWS,
        )
        .map(|(field, _)| field);
        let order = better.as_ref().map(|f| f.settings().order);
        *self.far.write().unwrap_or_else(PoisonError::into_inner) = better;
        order
    }

    /// Adds the far fields of [`RELAXED`] for products that may be less accurate, each measured
    /// against compensated direct sums at sampled rows on `trial` weights (a first
    /// approximation of the solution, whose products are of the size of `hmax`).
    pub(crate) fn relaxed(mut self, trial: &[f64], hmax: f64) -> Self {
        let system = self.system;
        let points = system.normalized_points();
        if !(hmax > 0.0) {
            return self;
        }
        // Every far field here has the same tree (the leaves' size is the default), so the
        // same sampled rows.
        let mut exact: Option<(Vec<usize>, Vec<f64>)> = None;
        for (order, theta) in RELAXED {
            let settings = FarFieldSettings {
                order,
                theta,
                ..FarFieldSettings::default()
            };
            let field = FarField::new(system.kernel(), points, &settings);
            if exact.is_none() {
                let rows = field.sample_rows(CALIBRATION_ROWS);
                let at: Vec<[f64; D]> = rows.iter().map(|&i| points[i]).collect();
                let mut sums = vec![0.0; rows.len()];
                let measured = InterpolantView::new(system.kernel(), points, trial, 0.0, [0.0; D])
                    .and_then(|f| f.par_values_compensated(&at, &mut sums));
                if measured.is_err() {
                    return self;
                }
                exact = Some((rows, sums));
            }
            let Some((rows, sums)) = exact.as_ref() else {
                return self;
            };
            let Some(error) = field.product_error(trial, rows, sums) else {
                continue;
            };
            let error = error / hmax;
            if error < 0.1 && self.relaxed.last().is_none_or(|&(_, e)| error < e) {
                self.relaxed.push((field, error));
            }
        }
        self
    }

    /// No relaxed products from now on; whether there were any to stop.
    pub(crate) fn stop_relaxing(&self) -> bool {
        !self.relaxed.is_empty() && !self.exact_only.swap(true, Ordering::Relaxed)
    }

    /// Products taken through a relaxed far field, and all products, so far.
    pub(crate) fn counts(&self) -> (usize, usize) {
        (
            self.relaxed_count.load(Ordering::Relaxed),
            self.count.load(Ordering::Relaxed),
        )
    }

    /// Whether products go through the far field now.
    pub(crate) fn is_far(&self) -> bool {
        self.order().is_some()
    }

    /// The far field's order, while it is in use.
    pub(crate) fn order(&self) -> Option<usize> {
        self.far
            .read()
            .unwrap_or_else(PoisonError::into_inner)
            .as_ref()
            .map(|f| f.settings().order)
    }

    /// out = A x (normalized), with an error at most `allowed` times the size of the product
    /// (0 for the most accurate product there is): through the cheapest relaxed far field that
    /// measured within it, else as [`Self::is_far`] says.
    pub(crate) fn apply(&self, x: &[f64], out: &mut [f64], allowed: f64) {
        let system = self.system;
        let points = system.normalized_points();
        let k = points.len();
        let (w, c) = x.split_at(k);
        let relaxed = self
            .relaxed
            .iter()
            .filter(|_| !self.exact_only.load(Ordering::Relaxed))
            .find(|&&(_, error)| error <= allowed)
            .map(|(field, _)| field);
        self.count.fetch_add(1, Ordering::Relaxed);
        if relaxed.is_some() {
            self.relaxed_count.fetch_add(1, Ordering::Relaxed);
        }
        let far = self.far.read().unwrap_or_else(PoisonError::into_inner);
        match relaxed.or(far.as_ref()) {
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
                    .and_then(|f| f.par_values_at_centres(&mut out[..k]));
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

    /// The largest |(A x)ᵢ − bᵢ| by compensated direct sums at the rows where `residual` (a fast
    /// one: the far field's, or the recurrence's) is largest and at rows spread over all, and the
    /// largest difference there between that and `residual`: what certifies a fast residual.
    pub(crate) fn certify(&self, x: &[f64], residual: &[f64]) -> Certified {
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
            return Certified {
                residual: f64::NAN,
                deviation: f64::NAN,
            };
        }
        let mut certified = Certified {
            residual: 0.0,
            deviation: 0.0,
        };
        for (&i, f) in rows.iter().zip(&fx) {
            let truth = system.values()[i] - f - system.normalized_smoothing(i) * w[i];
            certified.residual = certified.residual.max(truth.abs());
            certified.deviation = certified.deviation.max((truth - residual[i]).abs());
        }
        certified
    }
}

/// A fast residual checked by compensated direct sums at sampled rows.
pub(crate) struct Certified {
    /// The largest true residual there.
    pub(crate) residual: f64,
    /// The largest difference there between the true residual and the fast one.
    pub(crate) deviation: f64,
}

/// The affine part at p: c₀ + Σ c_{d+1} p_d.
pub(crate) fn affine<const D: usize>(c: &[f64], p: &[f64; D]) -> f64 {
    c[0] + (0..D).map(|d| c[d + 1] * p[d]).sum::<f64>()
}

/// About `count` row indices spread evenly over 0..k (all of them if k ≤ count).
pub(crate) fn spread_rows(k: usize, count: usize) -> Vec<usize> {
    if k <= count {
        return (0..k).collect();
    }
    (0..count).map(|i| i * k / count).collect()
}
