//! The one entry point that chooses how a set of constraints is solved: the dense factorization
//! or the iterative solver, memory checked before anything large is built, progress reported.
//! The CLI, the Python package and the conversions all go through it.

use rbf_core::{Constraint, Fit, FitError, FitSettings, Interpolant, System};

use crate::fast::{
    IterativeOptions, IterativeProgress, Kept, check_iterative_fits, solve_iterative_from,
};
use crate::fit::{DENSE_LIMIT, SolveOptions, solve};
use crate::memory::check_constraints_fit;

/// Which solver [`fit_with`] uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Method {
    /// Dense up to [`DENSE_LIMIT`] rows, iterative above.
    #[default]
    Auto,
    /// The dense factorization (O(K²) memory, O(K³) time, residual near rounding).
    Dense,
    /// Flexible GMRES with the domain-decomposition preconditioner (O(K) memory).
    Iterative,
}

/// Everything [`fit_with`] can be told.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FitOptions {
    /// The solver.
    pub method: Method,
    /// Options of the dense factorization.
    pub dense: SolveOptions,
    /// Options of the iterative solver.
    pub iterative: IterativeOptions,
}

/// Where [`fit_with`] is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FitProgress {
    /// The constraints are checked and the system built.
    Checking {
        /// Rows of the system.
        rows: usize,
    },
    /// A dense system is being factored.
    Factoring {
        /// Rows of the system.
        rows: usize,
    },
    /// The iterative solver reports.
    Iterative(IterativeProgress),
}

/// Fits `constraints` by the chosen method: refuses at once (with what it needs) a system that
/// would not fit in memory, builds and checks the system, solves it.
///
/// ```
/// use rbf_core::{FitSettings, shapes};
/// use rbf_solve::{FitOptions, FitProgress, Method, fit_with};
/// let options = FitOptions { method: Method::Iterative, ..FitOptions::default() };
/// let mut steps = 0;
/// let fit = fit_with(&shapes::sphere(300), &FitSettings::default(), &options, |p| {
///     if let FitProgress::Iterative(_) = p { steps += 1; }
/// })
/// .unwrap();
/// assert!(steps > 0 && fit.report.residual < 1e-6);
/// ```
pub fn fit_with<const D: usize>(
    constraints: &[Constraint<D>],
    settings: &FitSettings,
    options: &FitOptions,
    progress: impl FnMut(FitProgress),
) -> Result<Fit<D>, FitError> {
    fit_from_with(constraints, settings, options, None, None, progress)
}

/// Fits `constraints` (as [`crate::fit`] does) that add to those `previous` was fitted to: an
/// iterative solve starts from `previous` (its weights where the centres are the same, 0 for
/// the new ones), which leaves only the new constraints' misses to reduce. The greedy fit's
/// rounds and a scan's outside constraints go this way (a clean sword scan: its greedy rounds
/// 3–5 iterations instead of 5–6, its refits after 185 and 182 more outside constraints 23 and
/// 19 instead of 26). The dense solver has no use for it.
///
/// ```
/// use rbf_core::{Constraint, FitSettings, shapes};
/// let settings = FitSettings::default();
/// let cs = shapes::sphere(200);
/// let first = rbf_solve::fit(&cs, &settings).unwrap();
/// let mut more = cs.clone();
/// more.push(Constraint::exterior([3.0, 0.0, 0.0], -1.0));
/// let fit = rbf_solve::fit_from(&more, &settings, &first.interpolant).unwrap();
/// assert!(fit.interpolant.value(&[3.0, 0.0, 0.0]) < 0.0);
/// ```
pub fn fit_from<const D: usize>(
    constraints: &[Constraint<D>],
    settings: &FitSettings,
    previous: &Interpolant<f64, D>,
) -> Result<Fit<D>, FitError> {
    fit_from_with(
        constraints,
        settings,
        &FitOptions::default(),
        Some(previous),
        None,
        |_| {},
    )
}

/// The iterative solver's preconditioner, kept from one fit for the next fit of the same
/// constraints followed by a few more ([`fit_from_keeping`]): the next solve factors
/// subdomains for the added rows only, and leaves the rest of the preconditioner as it was
/// (its coarse level and the subdomains of the rows before; they overlap the added ones
/// without them). A scan's last outside refits and a greedy fit's last rounds add a few
/// rows to thousands.
///
/// Empty at first and after a dense solve; it serves a system whose first rows are exactly
/// those it was built on (points, smoothing, kernel and normalization) and that adds at most
/// a twentieth of them, and is built anew for any other.
pub struct KeptPreconditioner<const D: usize> {
    kept: Option<Kept<D>>,
}

impl<const D: usize> Default for KeptPreconditioner<D> {
    fn default() -> Self {
        Self { kept: None }
    }
}

impl<const D: usize> KeptPreconditioner<D> {
    /// Whether a preconditioner is kept.
    pub fn is_kept(&self) -> bool {
        self.kept.is_some()
    }
}

/// [`fit_from`], keeping the iterative solver's preconditioner in `kept` for the next fit and
/// using the one kept there where it serves (see [`KeptPreconditioner`]). Constraints added
/// since must come after the earlier ones, in the same order.
///
/// ```
/// use rbf_core::{Constraint, FitSettings, shapes};
/// use rbf_solve::{KeptPreconditioner, fit_from_keeping};
/// let settings = FitSettings::default();
/// let mut cs = shapes::sphere(3000); // 6000 rows: iterative
/// let mut kept = KeptPreconditioner::default();
/// let first = rbf_solve::fit(&cs, &settings).unwrap();
/// let first = fit_from_keeping(&cs, &settings, &first.interpolant, &mut kept).unwrap();
/// assert!(kept.is_kept());
/// cs.push(Constraint::exterior([3.0, 0.0, 0.0], -1.0));
/// let fit = fit_from_keeping(&cs, &settings, &first.interpolant, &mut kept).unwrap();
/// assert!(fit.interpolant.value(&[3.0, 0.0, 0.0]) < 0.0);
/// ```
pub fn fit_from_keeping<const D: usize>(
    constraints: &[Constraint<D>],
    settings: &FitSettings,
    previous: &Interpolant<f64, D>,
    kept: &mut KeptPreconditioner<D>,
) -> Result<Fit<D>, FitError> {
    fit_from_with(
        constraints,
        settings,
        &FitOptions::default(),
        Some(previous),
        Some(&mut kept.kept),
        |_| {},
    )
}

fn fit_from_with<const D: usize>(
    constraints: &[Constraint<D>],
    settings: &FitSettings,
    options: &FitOptions,
    previous: Option<&Interpolant<f64, D>>,
    kept: Option<&mut Option<Kept<D>>>,
    mut progress: impl FnMut(FitProgress),
) -> Result<Fit<D>, FitError> {
    let rows: usize = constraints.iter().map(Constraint::rows).sum();
    let dense = match options.method {
        Method::Auto => rows <= DENSE_LIMIT,
        Method::Dense => true,
        Method::Iterative => false,
    };
    // Too many constraints for memory: say so before the checks, which take time too.
    if dense {
        check_constraints_fit(constraints)?;
    } else {
        check_iterative_fits(rows, D, &options.iterative)?;
    }
    progress(FitProgress::Checking { rows });
    let system = System::new(constraints, settings)?;
    if dense {
        if let Some(kept) = kept {
            *kept = None;
        }
        progress(FitProgress::Factoring { rows });
        solve(&system, settings, &options.dense)
    } else {
        let start = previous.map(|f| system.normalized_unknowns(f));
        solve_iterative_from(&system, settings, &options.iterative, start, kept, |p| {
            progress(FitProgress::Iterative(p))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rbf_core::shapes;

    /// `n` oriented points of the unit sphere on its circle at height 0.8, between those of
    /// `shapes::sphere`: a fit of the sphere nearly meets them already, as a greedy round's
    /// worst-met points nearly are.
    fn on_the_circle_at_height_0_8(n: usize) -> impl Iterator<Item = Constraint<3>> {
        (0..n).map(move |i| {
            let t = core::f64::consts::TAU * (i as f64 + 0.37) / n as f64;
            let p = [0.6 * t.cos(), 0.6 * t.sin(), 0.8];
            Constraint::normal(p, p)
        })
    }

    /// `cs` fitted from `earlier` with the default settings, keeping a preconditioner in `kept`.
    fn from_earlier(
        cs: &[Constraint<3>],
        options: &FitOptions,
        earlier: &Interpolant<f64, 3>,
        kept: Option<&mut Option<Kept<3>>>,
    ) -> Fit<3> {
        fit_from_with(
            cs,
            &FitSettings::default(),
            options,
            Some(earlier),
            kept,
            |_| {},
        )
        .unwrap()
    }

    /// Constraints added to a fitted set, which nearly meets them: solved from the earlier fit,
    /// the iterative solver meets the same limit in fewer iterations than from zero, and the
    /// surfaces agree.
    #[test]
    fn a_solve_from_an_earlier_fit_takes_fewer_iterations() {
        let settings = FitSettings::default();
        // Small subdomains and coarse level, so that the solve takes several iterations.
        let options = FitOptions {
            method: Method::Iterative,
            iterative: crate::IterativeOptions {
                schwarz: crate::SchwarzSettings {
                    inner: 32,
                    extended: 64,
                    coarse: 64,
                    ..Default::default()
                },
                ..Default::default()
            },
            ..FitOptions::default()
        };
        let cs = shapes::sphere(800);
        let first = fit_from_with(&cs, &settings, &options, None, None, |_| {}).unwrap();
        let mut more = cs.clone();
        // More points of the same sphere, between the others: the earlier fit nearly meets
        // them already, as a greedy round's worst-met points nearly are.
        more.extend(on_the_circle_at_height_0_8(12));
        let cold = fit_from_with(&more, &settings, &options, None, None, |_| {}).unwrap();
        let warm = from_earlier(&more, &options, &first.interpolant, None);
        assert!(
            warm.report.iterations < cold.report.iterations,
            "{} iterations from the earlier fit, {} from zero",
            warm.report.iterations,
            cold.report.iterations
        );
        // Both within the iterative solver's own limit (its default).
        let limit = options.iterative.default_limit.unwrap();
        assert!(warm.report.residual <= limit && cold.report.residual <= limit);
        for c in &more {
            let (a, b) = (
                cold.interpolant.value(&c.position),
                warm.interpolant.value(&c.position),
            );
            assert!((a - b).abs() < 1e-4, "{a} against {b} at {:?}", c.position);
        }
    }

    /// A kept preconditioner serves the same constraints with a few appended: the fit agrees
    /// with one whose preconditioner is built anew, the kept one is still the first system's
    /// (its subdomains and coarse level reused, the added rows' own beside them), and a system
    /// whose first rows differ (normalization moved by a far point) gets one of its own.
    #[test]
    fn a_kept_preconditioner_serves_appended_constraints() {
        let settings = FitSettings::default();
        let options = FitOptions {
            method: Method::Iterative,
            ..FitOptions::default()
        };
        let cs = shapes::sphere(1500);
        let mut kept = None;
        let first = fit_from_with(&cs, &settings, &options, None, Some(&mut kept), |_| {}).unwrap();
        assert_eq!(kept.as_ref().map(|k| k.rows()), Some(3000));
        let mut more = cs.clone();
        more.extend(on_the_circle_at_height_0_8(40));
        more.push(Constraint::interior([0.0, 0.2, 0.5], 0.5));
        let reused = from_earlier(&more, &options, &first.interpolant, Some(&mut kept));
        assert_eq!(kept.as_ref().map(|k| k.rows()), Some(3000), "built anew");
        let fresh = from_earlier(&more, &options, &first.interpolant, None);
        let limit = options.iterative.default_limit.unwrap();
        assert!(
            reused.report.residual <= limit,
            "{}",
            reused.report.residual
        );
        for c in &more {
            let (a, b) = (
                fresh.interpolant.value(&c.position),
                reused.interpolant.value(&c.position),
            );
            assert!((a - b).abs() < 1e-4, "{a} against {b} at {:?}", c.position);
        }
        // A point far out moves the normalization: the kept preconditioner does not serve.
        more.push(Constraint::exterior([0.0, 0.0, 9.0], -8.0));
        fit_from_with(
            &more,
            &settings,
            &options,
            Some(&reused.interpolant),
            Some(&mut kept),
            |_| {},
        )
        .unwrap();
        assert_eq!(kept.as_ref().map(|k| k.rows()), Some(3082));
    }
}
