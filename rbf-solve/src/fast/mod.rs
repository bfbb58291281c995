//! The iterative solver for large systems: flexible GMRES on the whole saddle-point system,
//! preconditioned by multilevel restricted additive Schwarz, with the kernel products on every
//! core. Memory grows linearly with the rows; convergence is judged by the true residual, or by
//! GMRES's own residual certified by direct sums at sampled rows.

mod gmres;
mod packed_lu;
mod products;
mod schwarz;

use rbf_core::{Fit, FitError, FitSettings, Solution, SolveMethod, System};

use crate::probe::memory_budget;
use gmres::{Acceptance, GmresLimits, Residual, fgmres_from};
use products::{FAR_FIELD_ROWS, Products, RELAXED_ROWS};
use schwarz::Schwarz;
pub use schwarz::SchwarzSettings;

/// The share of the tolerance that the error of one relaxed product may cost.
const RELAXATION: f64 = 0.1;

/// Iterations (and three checks) without halving the true residual after which the solver
/// stops.
const STALL: usize = 9;

/// How the iterative solver runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IterativeOptions {
    /// The residual to reach, max|f(cᵢ) + λᵢwᵢ − hᵢ| relative to max|hᵢ|; `None` means
    /// `FitSettings::max_residual` (the residual is measured, not estimated, so no margin is
    /// needed). A solve that stalls (rounding) or reaches `max_iterations` above a smaller
    /// tolerance is still accepted within `FitSettings::max_residual`.
    pub tolerance: Option<f64>,
    /// Most iterations (products with the whole system); 300 by default.
    pub max_iterations: usize,
    /// Krylov vectors kept before a restart; 40 by default (two vectors of K numbers each).
    pub restart: usize,
    /// The preconditioner's subdomain and coarse-level sizes.
    pub schwarz: SchwarzSettings,
    /// Rows from which the products go through the far field (rbf-far) instead of direct sums;
    /// 400 000 by default (below, direct products are about as fast and GMRES needs fewer).
    pub far_field_rows: usize,
    /// Rows from which a Krylov product whose direction reduces an already small residual may
    /// go through a cheaper, less accurate far field (inexact Krylov), while the products are
    /// direct sums (below `far_field_rows`); 175 000 by default. The
    /// error allowed grows as the residual falls: a tenth of the tolerance over the relative
    /// residual. Checks after relaxed products measure the true residual with exact ones.
    pub relaxed_rows: usize,
    /// The limit an iterative solve aims at and accepts where the caller left both `tolerance`
    /// and `FitSettings::max_residual` at their defaults: `Some(1e-5)` (relative to max|hᵢ|) by
    /// default, ten times the dense method's limit and 17 times tighter than what tuned
    /// ferreus-rbf reaches on the peers' surface problem; `None` keeps the dense method's (1e-6).
    /// On 10⁵ rows of that problem it saves the last of seven iterations (14.5 s against 16.9 s,
    /// residual 1.8e-6 reached); through the far field (10⁶ rows) it is what the far field
    /// reaches in eight iterations (its error stays near 5e-6 at orders 12–16, so 1e-6 would
    /// need direct sums, two minutes a product). Said by [`IterativeProgress::DefaultLimit`].
    pub default_limit: Option<f64>,
    /// Accept a solve that stalls above `FitSettings::max_residual` but within the rounding
    /// floor of its products (see [`IterativeProgress::RoundingFloor`]); on by default, off
    /// where the caller asked for that limit explicitly.
    pub accept_rounding_floor: bool,
    /// Return a fit that did not reach the tolerance in `max_iterations` (its report says how
    /// far it got) instead of [`FitError::NotConverged`], whatever its residual.
    pub allow_unconverged: bool,
}

impl Default for IterativeOptions {
    fn default() -> Self {
        Self {
            tolerance: None,
            max_iterations: 300,
            restart: 40,
            schwarz: SchwarzSettings::default(),
            far_field_rows: FAR_FIELD_ROWS,
            relaxed_rows: RELAXED_ROWS,
            default_limit: Some(1e-5),
            accept_rounding_floor: true,
            allow_unconverged: false,
        }
    }
}

impl IterativeOptions {
    /// These options for a caller that set `FitSettings::max_residual` itself (`given`): the
    /// limit is then kept, neither raised to the far field's nor relaxed to a rounding floor
    /// (missing it is an error); otherwise both stay as they are.
    ///
    /// ```
    /// use rbf_solve::IterativeOptions;
    /// let kept = IterativeOptions::default().with_limit_given(true);
    /// assert!(kept.default_limit.is_none() && !kept.accept_rounding_floor);
    /// assert_eq!(IterativeOptions::default().with_limit_given(false), IterativeOptions::default());
    /// ```
    pub fn with_limit_given(self, given: bool) -> Self {
        if given {
            Self {
                default_limit: None,
                accept_rounding_floor: false,
                ..self
            }
        } else {
            self
        }
    }
}

/// Where the iterative solver is, for progress bars.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum IterativeProgress {
    /// The preconditioner is being factored.
    Preconditioning,
    /// The products go through the far field at this order (chosen so that its error at
    /// sampled rows is within a quarter of the tolerance); sent again when a check finds it
    /// less accurate than that on the iterate and a higher order takes its place.
    FarField {
        /// Chebyshev points along a cluster's longest side.
        order: usize,
    },
    /// A check found the far field less accurate at sampled rows than it claimed, and no higher
    /// order is accurate enough: the products are direct sums from here on.
    DirectSums,
    /// The solve stalled above `FitSettings::max_residual` but within what double precision
    /// allows for products of its weights (`floor`, relative to max|hᵢ|: 8ε · max over sampled
    /// rows of Σⱼ|wⱼ|φ(|cᵢ − cⱼ|)); the fit is accepted with this residual.
    RoundingFloor {
        /// The residual reached.
        residual: f64,
        /// The rounding floor.
        floor: f64,
    },
    /// The caller left the limit at its default: the solve aims at and accepts `limit` instead
    /// (see [`IterativeOptions::default_limit`]).
    DefaultLimit {
        /// The limit, relative to max|hᵢ|.
        limit: f64,
    },
    /// After an iteration: its number and the recurrence's estimate of the relative residual
    /// (the largest entry of its residual vector over max|hᵢ|; the true residual is measured
    /// only when this says the tolerance may be met).
    Iteration {
        /// Iterations so far.
        iteration: usize,
        /// The estimate.
        estimate: f64,
    },
    /// At the end, if any Krylov product went through a cheaper far field (inexact Krylov; see
    /// [`IterativeOptions::relaxed_rows`]): how many did, of all.
    Relaxed {
        /// Products taken through a relaxed far field.
        products: usize,
        /// All the solve's products.
        of: usize,
    },
    /// The residual at a check (max norm, relative to max|hᵢ|): at the start, at every
    /// restart, when the estimate says the tolerance may be met, and at the end; measured by a
    /// product, or GMRES's own with what sampled rows found it off by (`from_recurrence`).
    Checked {
        /// Iterations so far.
        iteration: usize,
        /// The residual.
        residual: f64,
        /// Whether it was taken from the recurrence's residual vector, within the tolerance
        /// with twice its largest error at sampled rows (measured there by compensated direct
        /// sums) to spare, instead of a product at every row.
        from_recurrence: bool,
    },
}

/// Solves a checked system by FGMRES with the domain-decomposition preconditioner: memory and
/// time grow with K instead of K² and K³, so it takes systems far beyond the dense solver's.
///
/// ```
/// use rbf_core::{FitSettings, System, shapes};
/// use rbf_solve::{IterativeOptions, solve_iterative};
/// let settings = FitSettings::default();
/// let system = System::new(&shapes::sphere(600), &settings).unwrap();
/// let fit = solve_iterative(&system, &settings, &IterativeOptions::default(), |_| {}).unwrap();
/// assert!(fit.report.residual < 1e-7);
/// assert!(fit.interpolant.value(&[0.0; 3]) > 0.0);
/// ```
pub fn solve_iterative<const D: usize>(
    system: &System<D>,
    settings: &FitSettings,
    options: &IterativeOptions,
    progress: impl FnMut(IterativeProgress),
) -> Result<Fit<D>, FitError> {
    solve_iterative_from(system, settings, options, None, None, progress)
}

/// A preconditioner kept from one iterative solve for the next of the same rows followed by a
/// few more (see [`crate::KeptPreconditioner`]).
pub(crate) struct Kept<const D: usize> {
    schwarz: Schwarz<D>,
    /// Its rows' normalized points and smoothing, and the normalization's scale: a later
    /// system whose first rows have them all is the same system with rows added.
    points: Vec<[f64; D]>,
    smoothing: Vec<f64>,
    scale: f64,
    kernel: rbf_core::Kernel,
}

/// Rows added to a kept preconditioner's are solved by subdomains of their own up to this share
/// of its rows; beyond it, the preconditioner is built anew.
const MOST_ADDED: f64 = 0.05;

/// Iterations a solve with a kept preconditioner may take before it gives way to one with a
/// preconditioner of its own (the clean sword's took 7–25).
const REUSED_ITERATIONS: usize = 60;

impl<const D: usize> Kept<D> {
    fn new(schwarz: Schwarz<D>, system: &System<D>) -> Self {
        let k = system.rows();
        Self {
            schwarz,
            points: system.normalized_points().to_vec(),
            smoothing: (0..k).map(|i| system.normalized_smoothing(i)).collect(),
            scale: system.scale(),
            kernel: system.kernel(),
        }
    }

    /// The rows it was built on (the system's first).
    #[cfg(test)]
    pub(crate) fn rows(&self) -> usize {
        self.points.len()
    }

    /// Whether `system` is this one's with at most [`MOST_ADDED`] of its rows added after them.
    fn serves(&self, system: &System<D>) -> bool {
        let k = self.points.len();
        let n = system.rows();
        n >= k
            && (n - k) as f64 <= MOST_ADDED * k as f64
            && system.scale() == self.scale
            && system.kernel() == self.kernel
            && system.normalized_points()[..k] == self.points[..]
            && (0..k).all(|i| system.normalized_smoothing(i) == self.smoothing[i])
    }
}

/// [`solve_iterative`] from `start`, the system's normalized unknowns (weights, then the
/// polynomial) of an earlier fit ([`System::normalized_unknowns`]), where that is closer than
/// zero. With `kept`, its preconditioner is used if it serves this system (the rows it was
/// built on, then a few more: see [`Kept`]) and left there for the next solve; a solve with it
/// that does not converge within [`REUSED_ITERATIONS`] is solved again with a preconditioner of
/// its own (its progress then reports a second solve).
pub(crate) fn solve_iterative_from<const D: usize>(
    system: &System<D>,
    settings: &FitSettings,
    options: &IterativeOptions,
    start: Option<Vec<f64>>,
    kept: Option<&mut Option<Kept<D>>>,
    progress: impl FnMut(IterativeProgress),
) -> Result<Fit<D>, FitError> {
    let mut progress = progress;
    let Some(kept) = kept else {
        return solve_with(system, settings, options, start, None, &mut progress)
            .map(|(fit, _)| fit);
    };
    let reused = kept.take().filter(|k| k.serves(system));
    if let Some(reused) = reused {
        // A few iterations more than a preconditioner of its own would take, not hundreds.
        let bounded = IterativeOptions {
            max_iterations: options.max_iterations.min(REUSED_ITERATIONS),
            allow_unconverged: false,
            ..*options
        };
        // Not converged within the bound, or an iterate that is not finite: again below with a
        // preconditioner of its own, from the same start (any other error recurs there).
        if let Ok((fit, schwarz)) = solve_with(
            system,
            settings,
            &bounded,
            start.clone(),
            Some(reused),
            &mut progress,
        ) {
            *kept = schwarz;
            return Ok(fit);
        }
    }
    let (fit, schwarz) = solve_with(system, settings, options, start, None, &mut progress)?;
    *kept = schwarz;
    Ok(fit)
}

/// One iterative solve, with the preconditioner `reused` (extended to the rows added since) or
/// one of its own; returns the fit and the preconditioner to keep.
fn solve_with<const D: usize>(
    system: &System<D>,
    settings: &FitSettings,
    options: &IterativeOptions,
    start: Option<Vec<f64>>,
    reused: Option<Kept<D>>,
    progress: &mut dyn FnMut(IterativeProgress),
) -> Result<(Fit<D>, Option<Kept<D>>), FitError> {
    let k = system.rows();
    let m = D + 1;
    check_iterative_fits(k, D, options)?;
    // A limit left at its default is the iterative solver's own.
    let raised = options.default_limit.filter(|&limit| {
        options.tolerance.is_none()
            && settings.max_residual == FitSettings::default().max_residual
            && limit > settings.max_residual
    });
    let settings = &FitSettings {
        max_residual: raised.unwrap_or(settings.max_residual),
        ..*settings
    };
    if let Some(limit) = raised {
        progress(IterativeProgress::DefaultLimit { limit });
    }
    let tolerance = options.tolerance.unwrap_or(settings.max_residual);
    if !(tolerance > 0.0 && tolerance.is_finite()) {
        return Err(FitError::InvalidSetting {
            name: "tolerance",
            value: tolerance,
            rule: "the tolerance must be finite and > 0",
        });
    }
    progress(IterativeProgress::Preconditioning);
    let preconditioner = match reused {
        Some(kept) => kept,
        None => Kept::new(Schwarz::new(system, &options.schwarz), system),
    };
    let schwarz = &preconditioner.schwarz;
    let extension = (k > schwarz.row_count()).then(|| schwarz.extension(system, &options.schwarz));
    let hmax = system.values().iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    let mut b = system.values().to_vec();
    b.extend(std::iter::repeat_n(0.0, m));

    // From `far_field_rows` the products go through the far field, its order chosen on the
    // first preconditioned direction (an approximation of the solution, with its
    // cancellations) so that its error stays within a quarter of the tolerance; from
    // `relaxed_rows`, cheaper far fields measured on it too.
    let trial = (k >= options.far_field_rows.min(options.relaxed_rows))
        .then(|| schwarz.apply_extended(system, &b[..k], &b[k..], extension.as_ref()));
    let mut products = match &trial {
        Some(trial) if k >= options.far_field_rows => {
            Products::far(system, &trial[..k], tolerance * hmax)
        }
        _ => Products::direct(system),
    };
    // Relaxed products only beside direct sums: measured on the trial, they err more on the
    // Krylov directions than they claim, and beside a far field they slowed 10⁶ rows of the
    // peers' surface problem from 4.0e-3 → 1.3e-6 in three iterations to 2.7e-3 → 2.7e-4 in five.
    if let Some(trial) = trial.filter(|_| k >= options.relaxed_rows && !products.is_far()) {
        products = products.relaxed(&trial[..k], hmax);
    }
    if let Some(order) = products.order() {
        progress(IterativeProgress::FarField { order });
    }
    // A direction that reduces a residual of r (largest entry) changes the solution by about
    // r over the size of its product, so an error of e in that product costs about e · r at the
    // end: a tenth of the tolerance is allowed for each (Simoncini & Szyld's relaxation).
    let apply = |x: &[f64], out: &mut [f64], residual: Option<f64>| {
        let allowed = residual.map_or(0.0, |r| RELAXATION * tolerance * hmax / r);
        products.apply(x, out, allowed);
    };
    let precondition =
        |v: &[f64]| schwarz.apply_extended(system, &v[..k], &v[k..], extension.as_ref());
    let progress = std::cell::RefCell::new(progress);
    let mut last = f64::INFINITY;
    // The residual last halved at this iteration.
    let (mut best, mut improved_at, mut checks_since) = (f64::INFINITY, 0, 0);
    let mut stalled = false;
    // The rounding floor of the iterate the solve stopped at, where it stopped for that.
    let mut floor_at_stop: Option<f64> = None;
    // The best iterate checked, and whether the recurrence ran ahead of the truth at the last
    // check (claimed a tenth of it or less).
    let mut kept: Option<(f64, Vec<f64>)> = None;
    let mut ahead = false;
    let mut refined = false;
    let mut accept = |x: &[f64], r: &[f64], iteration: usize, claimed: f64, kind: Residual| {
        let rh = r[..k].iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        // The moment conditions' residual, from the weights themselves (a few sums, exact
        // whatever kind of residual was given).
        let rg = moments_residual(system, &x[..k]);
        let wsum: f64 = x[..k].iter().map(|v| v.abs()).sum();
        let moments_met = rg <= (tolerance * hmax).max(64.0 * f64::EPSILON * wsum);
        if kind == Residual::Recurrence {
            // The recurrence's residual is b − A x up to what the products erred: rounding, or
            // the far field's error, which direct sums at sampled rows measure. Within the
            // tolerance with twice the largest error found there to spare, it is accepted as
            // the fast residual at every row, certified at the sampled ones, and the product
            // of a true residual is saved (1.5 s of 17 at 10⁵ rows of the peers' problem). The
            // residual reported is that bound. After relaxed products it is always measured:
            // their far fields were chosen by their error at the very rows that certify, so
            // an error elsewhere could pass unseen.
            if products.counts().0 > 0 || !moments_met || rh > tolerance * hmax {
                return Acceptance::Measure;
            }
            let certified = products.certify(x, &r[..k]);
            let bound = (rh + 2.0 * certified.deviation).max(certified.residual);
            if !(bound <= tolerance * hmax) {
                return Acceptance::Measure;
            }
            last = bound / hmax;
            (progress.borrow_mut())(IterativeProgress::Checked {
                iteration,
                residual: last,
                from_recurrence: true,
            });
            return Acceptance::Done;
        }
        last = rh / hmax;
        if products.is_far() {
            // The far field's residual, certified by direct sums at sampled rows; a far field
            // that misses what it claims there gives way to direct sums.
            let certified = products.certify(x, &r[..k]).residual / hmax;
            if certified > tolerance.max(2.0 * last) {
                let event = match products.refine(x) {
                    Some(order) => IterativeProgress::FarField { order },
                    None => IterativeProgress::DirectSums,
                };
                (progress.borrow_mut())(event);
                refined = true;
            }
            last = last.max(certified);
        }
        (progress.borrow_mut())(IterativeProgress::Checked {
            iteration,
            residual: last,
            from_recurrence: false,
        });
        let halved = last < 0.5 * best;
        if halved {
            (best, improved_at, checks_since) = (last, iteration, 0);
        } else {
            checks_since += 1;
        }
        if kept.as_ref().is_none_or(|(r, _)| last < *r) {
            kept = Some((last, x.to_vec()));
        }
        let was_ahead = ahead;
        ahead = claimed <= 0.1 * rh;
        let done = last <= tolerance && moments_met;
        // The rounding floor, measured only where the recurrence ran ahead of the truth.
        let floor = (!done && ahead && moments_met && options.accept_rounding_floor)
            .then(|| rounding_floor(system, &x[..k]) / hmax);
        if done {
            Acceptance::Done
        } else if let Some(floor) = floor.filter(|&f| last <= f) {
            // The recurrence ran ahead of a measured residual that rounding alone explains: no
            // iteration can lower it, with relaxed products or exact ones (on normal
            // constraints of a real bust this ends the solve 10–24 iterations sooner).
            stalled = true;
            floor_at_stop = Some(floor);
            Acceptance::GiveUp
        } else if std::mem::take(&mut refined) {
            // The products changed: a new cycle from this iterate's residual measured with them
            // (continuing, the recurrence would go on solving with the old ones: at 5·10⁵ rows
            // it fell to 2e-8 while the truth stayed at 1.2e-5).
            Acceptance::Remeasure {
                target: 0.5 * tolerance * hmax,
            }
        } else if iteration > 0 && products.stop_relaxing() {
            // The recurrence said the tolerance may be met and the truth did not: relaxed
            // products may have taken it off course. Exact products from here on, in a new
            // cycle from this iterate's true residual (continuing the cycle, the recurrence
            // stayed twenty times ahead of a residual that no longer fell: 4.7e-5 at 10⁵ rows
            // asked for 1e-5).
            ahead = false;
            Acceptance::Restart {
                target: 0.5 * tolerance * hmax,
            }
        } else if (was_ahead && ahead && !halved)
            || (checks_since >= 3 && iteration >= improved_at + STALL)
        {
            // The products' rounding has the last word: the recurrence runs ten times ahead
            // of the measured residual at two checks in a row while that does not halve, or the
            // measured residual stopped falling for many iterations.
            stalled = true;
            Acceptance::GiveUp
        } else {
            // Check again when the recurrence puts every row at half the tolerance.
            Acceptance::Continue {
                target: 0.5 * tolerance * hmax,
            }
        }
    };
    let mut report = |it: usize, estimate: f64| {
        (progress.borrow_mut())(IterativeProgress::Iteration {
            iteration: it,
            estimate: estimate / hmax,
        });
    };
    let limits = GmresLimits {
        restart: options.restart,
        max_iterations: options.max_iterations,
    };
    let mut end = fgmres_from(
        &b,
        start,
        &limits,
        &apply,
        &precondition,
        &mut accept,
        &mut report,
    );
    let (relaxed, all) = products.counts();
    if relaxed > 0 {
        (progress.borrow_mut())(IterativeProgress::Relaxed {
            products: relaxed,
            of: all,
        });
    }
    // A solve that did not converge returns the best iterate it measured, not the last.
    if !end.converged
        && let Some((residual, x)) = kept.take()
        && residual < last
    {
        (last, end.x) = (residual, x);
        floor_at_stop = None;
    }
    // Stopped short of the tolerance (when one below the limit was asked for) but within the limit:
    // as good as a dense solve would have been allowed to be.
    let mut good_enough = last <= settings.max_residual;
    let mut limit = settings.max_residual;
    if !end.converged && !good_enough && stalled && options.accept_rounding_floor {
        // Stalled above the limit: if that is where double precision leaves products of these
        // weights, no solver does better; accept, and say so.
        let floor = floor_at_stop.unwrap_or_else(|| rounding_floor(system, &end.x[..k]) / hmax);
        if last <= floor {
            (progress.borrow_mut())(IterativeProgress::RoundingFloor {
                residual: last,
                floor,
            });
            good_enough = true;
            limit = floor;
        }
    }
    if !end.converged && !good_enough && !options.allow_unconverged {
        return Err(FitError::NotConverged {
            iterations: end.iterations,
            residual: last,
            tolerance: settings.max_residual,
        });
    }
    let relaxed = FitSettings {
        max_residual: f64::INFINITY,
        ..*settings
    };
    let accepted = FitSettings {
        max_residual: limit,
        ..*settings
    };
    // The last check measured the returned iterate: by a product (direct sums, or the far field
    // and direct sums at sampled rows), or as GMRES's residual certified at sampled rows.
    let fit = system.accept_measured(
        if end.converged || good_enough {
            &accepted
        } else {
            &relaxed
        },
        &Solution {
            weights: &end.x[..k],
            polynomial: &end.x[k..],
            method: SolveMethod::Iterative,
            condition: f64::NAN,
            refinements: 0,
            iterations: end.iterations,
        },
        |_| last,
    )?;
    Ok((fit, Some(preconditioner)))
}

/// max over the moment conditions of |Σᵢ wᵢ pⱼ(cᵢ)| (p = 1, x): what the weights leave of them
/// (their right-hand side is zero).
fn moments_residual<const D: usize>(system: &System<D>, weights: &[f64]) -> f64 {
    let mut sums = vec![0.0; D + 1];
    for (w, p) in weights.iter().zip(system.normalized_points()) {
        sums[0] += w;
        for d in 0..D {
            sums[d + 1] += w * p[d];
        }
    }
    sums.iter().fold(0.0_f64, |a, v| a.max(v.abs()))
}

/// 8ε · max over 2000 sampled rows of Σⱼ|wⱼ|φ(|cᵢ − cⱼ|) (normalized): how far rounding alone
/// leaves a product of these weights from the truth, and so the lowest residual any solver
/// working in double precision can certify.
fn rounding_floor<const D: usize>(system: &System<D>, weights: &[f64]) -> f64 {
    let points = system.normalized_points();
    let magnitudes: Vec<f64> = weights.iter().map(|w| w.abs()).collect();
    let rows: Vec<[f64; D]> = products::spread_rows(points.len(), 2000)
        .into_iter()
        .map(|i| points[i])
        .collect();
    let mut sums = vec![0.0; rows.len()];
    let evaluated =
        rbf_core::InterpolantView::new(system.kernel(), points, &magnitudes, 0.0, [0.0; D])
            .and_then(|f| f.par_values(&rows, &mut sums));
    if evaluated.is_err() {
        return 0.0;
    }
    // Exact for r³ and r (φ ≥ 0); for r² log r the magnitudes' sum may cancel, which only
    // lowers the floor and makes acceptance stricter.
    let worst = sums.iter().fold(0.0_f64, |a, s| a.max(s.abs()));
    8.0 * f64::EPSILON * worst
}

/// Refuses an iterative solve of `rows` rows in `dim` dimensions whose factored subdomains and
/// Krylov vectors would not fit in the [`crate::memory_budget`]: what [`solve_iterative`]
/// checks first, for callers that want to know before building the system.
///
/// ```
/// use rbf_solve::{IterativeOptions, check_iterative_fits};
/// assert!(check_iterative_fits(100_000, 3, &IterativeOptions::default()).is_ok()); // 0.7 GB
/// assert!(check_iterative_fits(1 << 40, 3, &IterativeOptions::default()).is_err());
/// ```
#[doc(hidden)]
pub fn check_iterative_fits(
    rows: usize,
    dim: usize,
    options: &IterativeOptions,
) -> Result<(), FitError> {
    let s = &options.schwarz;
    // Each subdomain keeps the packed Cholesky factor of its system, about ext²/2 numbers in
    // single precision (ext²/4 in double), for `inner` rows of its level: a level holds its rows
    // × ext² / (4 inner) doubles. Levels go down by one row in 24 to the one factored whole.
    let ext = s.extended.max(s.inner) as u64;
    let per_row = ext * ext / (4 * s.inner.max(1) as u64);
    let (mut kept, mut level_rows, mut depth) = (0u64, rows, 1);
    loop {
        kept = kept.saturating_add((level_rows as u64).saturating_mul(per_row));
        let nested = level_rows / 24 > 2 * s.coarse && depth + 2 <= s.levels;
        if !nested {
            break;
        }
        (level_rows, depth) = (level_rows / 24, depth + 1);
    }
    let coarse = (s.coarse.min(rows) + dim + 1) as u64;
    // The factors and a tenth more for the allocator, and on every core one subdomain's
    // kernel block being factored; the coarse level; two Krylov vectors per step of a restart
    // cycle, and the direct products' sums by shares of tiles (16 a row, rbf-core's
    // `par_values_at_centres`) (measured peaks of the whole `rbf fit` on the peers' surface problem with the
    // default settings: 0.85 GB at 10⁵ rows, 0.72 GB by this estimate; 6.06 GB at 10⁶ rows,
    // 6.1 GB by this estimate).
    let cores = std::thread::available_parallelism().map_or(1, |c| c.get()) as u64;
    let vectors = 2 * (options.restart as u64 + 2) + 16;
    let numbers = kept.saturating_mul(11) / 10;
    let numbers = numbers
        .saturating_add(cores.saturating_mul((ext + dim as u64 + 1).pow(2)))
        .saturating_add(coarse * coarse)
        .saturating_add(vectors.saturating_mul((rows + dim + 1) as u64));
    let bytes = numbers.saturating_mul(8);
    let available = memory_budget();
    if bytes > available.unwrap_or(u64::MAX) {
        return Err(FitError::TooLarge {
            rows,
            bytes,
            available,
        });
    }
    Ok(())
}
