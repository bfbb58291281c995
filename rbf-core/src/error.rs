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
        /// D + 1.
        needed: usize,
        /// The dimension.
        dim: usize,
    },
    /// A coordinate, value, normal, offset or smoothing is NaN or infinite.
    #[error("constraint {constraint}: its {field} is not a finite number")]
    NonFinite {
        /// Index of the constraint.
        constraint: usize,
        /// Which field.
        field: &'static str,
    },
    /// A value contradicts the kind (an interior point with f ≤ 0, say), or a smoothing or
    /// offset is negative.
    #[error("constraint {constraint} ({}): {field} = {value} but {rule}", kind.name())]
    InvalidValue {
        /// Index of the constraint.
        constraint: usize,
        /// Its kind.
        kind: ConstraintKind,
        /// Which field.
        field: &'static str,
        /// The value given.
        value: f64,
        /// What the value must satisfy.
        rule: &'static str,
    },
    /// A setting is out of its range.
    #[error("setting {name} = {value}: {rule}")]
    InvalidSetting {
        /// Which setting.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What it must satisfy.
        rule: &'static str,
    },
    /// A normal constraint's normal has zero length.
    #[error("normal constraint {constraint}: the normal has zero length, so it gives no direction")]
    ZeroNormal {
        /// Index of the constraint.
        constraint: usize,
    },
    /// Two constraint points coincide (or nearly): the system would be singular.
    #[error(
        "{first} and {second} are {distance:e} apart, closer than the minimum separation {minimum:e} (a fraction of the constraints' extent): merge them, move one, or lower the minimum separation"
    )]
    Coincident {
        /// The first of the pair.
        first: RowSource,
        /// The second.
        second: RowSource,
        /// Their distance.
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
        /// Bytes it needs.
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
        /// Relative residual reached.
        residual: f64,
        /// The accepted limit.
        limit: f64,
        /// Estimated condition number.
        condition: f64,
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
