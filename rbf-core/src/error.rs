//! Why a fit can fail.

use crate::{ConstraintKind, RowSource};

/// Why constraints could not be turned into an interpolant. Each variant names the culprit.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FitError {
    /// The linear polynomial has `needed` coefficients; fewer rows cannot determine it.
    #[error(
        "{rows} constraint point(s) cannot determine a surface in {dim}D: at least {needed} are needed (the linear part alone has {needed} coefficients)"
    )]
    TooFewConstraints {
        /// Rows of the system (normal constraints count twice).
        rows: usize,
        /// D + 1: the constant and the D linear coefficients.
        needed: usize,
        /// Dimension D of the constraints, 2 or 3.
        dim: usize,
    },
    /// A coordinate, value, normal, offset or smoothing is NaN or infinite.
    #[error("constraint {constraint}: its {field} is not a finite number")]
    NonFinite {
        /// Index of the constraint in the caller's list, 0-based.
        constraint: usize,
        /// The field that is not finite: `"position"`, `"value"`, `"smoothing"`, `"normal"`,
        /// `"offset"`, or `"offset point"` (the point the offset moves inside).
        field: &'static str,
    },
    /// A value contradicts the kind (an interior point with f ≤ 0, say), or a smoothing or
    /// offset is negative.
    #[error("constraint {constraint} ({}): {field} = {value} but {rule}", kind.name())]
    InvalidValue {
        /// Index of the constraint in the caller's list, 0-based.
        constraint: usize,
        /// Kind of that constraint, which decides the sign its value must have.
        kind: ConstraintKind,
        /// The offending field: `"value"`, `"smoothing"` or `"offset"`.
        field: &'static str,
        /// The field's value as the caller gave it.
        value: f64,
        /// The rule it breaks, as a phrase for the message ("smoothing must be ≥ 0").
        rule: &'static str,
    },
    /// A setting is out of its range.
    #[error("setting {name} = {value}: {rule}")]
    InvalidSetting {
        /// Name of the setting in messages: `"lambda"`, `"normal offset"`, `"max_residual"`.
        name: &'static str,
        /// The setting's value as given.
        value: f64,
        /// The rule it breaks, as a phrase for the message ("λ must be finite and ≥ 0").
        rule: &'static str,
    },
    /// A normal constraint's normal has zero length.
    #[error("normal constraint {constraint}: the normal has zero length, so it gives no direction")]
    ZeroNormal {
        /// Index of the constraint in the caller's list, 0-based.
        constraint: usize,
    },
    /// Two constraint points coincide (or nearly): the system would be singular.
    #[error(
        "{first} and {second} are {distance:e} apart, closer than the minimum separation {minimum:e} (a fraction of the constraints' extent): merge them, move one, or lower the minimum separation"
    )]
    Coincident {
        /// The row with the smaller index of the pair (a constraint, or a normal constraint's
        /// offset point).
        first: RowSource,
        /// The row with the larger index.
        second: RowSource,
        /// Distance between the two points, in the constraints' own units.
        distance: f64,
        /// The smallest distance allowed: `FitSettings::min_separation` times the extent of the
        /// constraints (so a single far-away point makes every other pair "coincide").
        minimum: f64,
    },
    /// All points lie on a plane (3D) or a line (2D) or lower: the linear part is undetermined.
    #[error(
        "all {rows} constraint points lie in a subspace of dimension {} (a {}) so the linear part of f is undetermined: add a constraint off it, e.g. an interior or normal constraint",
        rank.saturating_sub(1),
        match rank { 0 | 1 => "point", 2 => "line", 3 => "plane", _ => "hyperplane" }
    )]
    AffinelyDependent {
        /// Rows of the system.
        rows: usize,
        /// Rank of the polynomial block [1 x]: at most D.
        rank: usize,
    },
    /// Every value is zero, so f ≡ 0 and there is no surface.
    #[error(
        "all {rows} constraints have value 0, so f would be 0 everywhere: add an interior, exterior or normal constraint"
    )]
    NoNonZeroValue {
        /// Rows of the system.
        rows: usize,
    },
    /// The dense system would not fit in memory.
    #[error(
        "a system of {rows} rows needs {} MiB{}: use fewer constraints (a subset, or a coarser conversion)",
        bytes / (1 << 20),
        AvailableNote(*available)
    )]
    TooLarge {
        /// Rows of the system.
        rows: usize,
        /// Bytes the dense matrix of the system needs.
        bytes: u64,
        /// Bytes that may be used (`rbf_solve::memory_budget`), when known.
        available: Option<u64>,
    },
    /// The solve produced non-finite weights: the system is singular.
    #[error(
        "the system is singular (condition estimate {condition:e}): look for redundant or contradictory constraints, or set λ > 0"
    )]
    Singular {
        /// Estimated condition number (may be infinite).
        condition: f64,
    },
    /// The solve's residual stayed above the limit after refinement.
    #[error(
        "the system is too ill-conditioned to meet the constraints (residual {residual:e} > {limit:e}, condition estimate {condition:e}): spread the constraints out or set λ > 0"
    )]
    IllConditioned {
        /// Residual reached, max|f(cᵢ) + λᵢwᵢ − hᵢ| relative to max|hᵢ|.
        residual: f64,
        /// The largest accepted residual, `FitSettings::max_residual` (1e-6 by default).
        limit: f64,
        /// Estimated condition number.
        condition: f64,
    },
    /// The iterative solver stopped (at its iteration cap, or stalled) above the residual limit.
    #[error(
        "the iterative solver did not converge: residual {residual:.1e} after {iterations} iterations, above the limit {tolerance:.1e}: allow more iterations, give the preconditioner larger subdomains, or set λ > 0"
    )]
    NotConverged {
        /// Iterations made.
        iterations: usize,
        /// The true residual reached, max|f(cᵢ) + λᵢwᵢ − hᵢ| relative to max|hᵢ|.
        residual: f64,
        /// The largest accepted residual, `FitSettings::max_residual`.
        tolerance: f64,
    },
}

struct AvailableNote(Option<u64>);

impl core::fmt::Display for AvailableNote {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self.0 {
            Some(a) => write!(f, " but only {} MiB can be spared", a >> 20),
            None => Ok(()),
        }
    }
}
