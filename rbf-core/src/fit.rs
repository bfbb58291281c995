//! What a fit returns: the interpolant and an honest account of how it was obtained.

use crate::Interpolant;

/// How the linear system was factored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "kebab-case"))]
#[non_exhaustive]
pub enum SolveMethod {
    /// Partial-pivot LU of the whole system (rbf-core's small dense solver, or the last
    /// fallback of rbf-solve).
    Lu,
    /// Cholesky of the kernel block projected onto polynomial-free weights.
    ProjectedCholesky,
    /// Symmetric-indefinite LBLᵀ (Bunch–Kaufman) of the projected kernel block.
    ProjectedLblt,
}

/// Figures of a fit.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FitReport {
    /// Rows K of the kernel block (constraint points).
    pub rows: usize,
    /// The factorization that produced the weights.
    pub method: SolveMethod,
    /// max |f(cᵢ) + λᵢwᵢ − hᵢ| / max |hᵢ|, measured on the returned interpolant.
    pub residual: f64,
    /// An estimate of the 1-norm condition number of the (normalized) system.
    pub condition: f64,
    /// Steps of iterative refinement taken.
    pub refinements: usize,
}

/// An interpolant and the figures of the fit that produced it.
#[derive(Clone, Debug, PartialEq)]
pub struct Fit<const D: usize> {
    /// The interpolant, in the caller's coordinates.
    pub interpolant: Interpolant<f64, D>,
    /// Rows, factorization, residual, condition estimate and refinement steps of the fit.
    pub report: FitReport,
}
