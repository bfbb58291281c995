//! The one entry point that chooses how a set of constraints is solved: the dense factorization
//! or the iterative solver, memory checked before anything large is built, progress reported.
//! The CLI, the Python package and the conversions all go through it.

use rbf_core::{Constraint, Fit, FitError, FitSettings, System};

use crate::fast::{IterativeOptions, IterativeProgress, check_iterative_fits, solve_iterative};
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
        progress(FitProgress::Factoring { rows });
        solve(&system, settings, &options.dense)
    } else {
        solve_iterative(&system, settings, &options.iterative, |p| {
            progress(FitProgress::Iterative(p))
        })
    }
}
