//! # rbf-solve
//!
//! Fitting variational implicit surfaces at scale. rbf-core builds and checks the system of
//! equation (8) in Greg Turk and James F. O'Brien, "Modelling with Implicit Surfaces that
//! Interpolate", ACM Transactions on Graphics 21(4), 2002; this crate solves it fast and honestly:
//!
//! - coordinates are centred and scaled into [−1, 1]ᴰ before assembly (conditioning);
//! - the affine part is eliminated with the Householder QR of the polynomial block, leaving a
//!   definite (K − D − 1)² block that Cholesky factors in a third of the flops of LU of the whole
//!   system; an indefinite block (the r kernel with λ > 0, say) falls back to Bunch–Kaufman
//!   LBLᵀ, and a residual that is still poor to LU of the whole system;
//! - assembly and evaluation run on every core (rayon), the factorization through faer;
//! - the solution is refined iteratively, its residual measured on the returned interpolant,
//!   and its condition estimated (Hager–Higham); a fit that misses its residual limit is an
//!   error, never a model;
//! - memory is checked before the matrix is allocated.
//!
//! ```
//! use rbf_core::{Constraint, FitSettings};
//! use rbf_solve::{SolveOptions, Strategy};
//!
//! let cs = [
//!     Constraint::boundary([1.0, 0.0, 0.0]),
//!     Constraint::boundary([0.0, 1.0, 0.0]),
//!     Constraint::boundary([0.0, 0.0, 1.0]),
//!     Constraint::boundary([-1.0, -1.0, -1.0]),
//!     Constraint::interior([0.0, 0.0, 0.0], 1.0),
//! ];
//! let settings = FitSettings { lambda: 0.0, ..Default::default() };
//! let system = rbf_core::System::new(&cs, &settings).unwrap();
//! let fit = rbf_solve::solve(&system, &settings, &SolveOptions::default()).unwrap();
//! println!("{:?}: residual {:e}, condition ≈ {:e}", fit.report.method, fit.report.residual, fit.report.condition);
//! assert!(fit.interpolant.value(&[0.0; 3]) > 0.0);
//! ```

mod dispatch;
mod fast;
mod fit;
mod greedy;
mod householder;
mod lu;
mod memory;
mod probe;
mod projected;

pub use dispatch::{
    FitOptions, FitProgress, KeptPreconditioner, Method, fit_from, fit_from_keeping, fit_with,
};
pub use fast::{
    IterativeOptions, IterativeProgress, SchwarzSettings, check_iterative_fits, solve_iterative,
};
pub use fit::{DENSE_LIMIT, SolveOptions, Strategy, fit, solve};
pub use greedy::{GreedyReport, GreedyRound, GreedySettings, fit_greedy};
pub use memory::{check_constraints_fit, check_fits};
pub use probe::{available_memory, memory_budget};
