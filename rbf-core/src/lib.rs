//! # rbf-core
//!
//! Variational implicit surfaces after Greg Turk and James F. O'Brien, "Modelling with Implicit
//! Surfaces that Interpolate", ACM Transactions on Graphics 21(4), 2002 (Turk & O'Brien 2002
//! below): a function f(x) = Σⱼ wⱼ φ(|x − cⱼ|) + a + b·x that takes given values
//! at given points (0 on the surface, positive inside, negative outside) and is as smooth as
//! possible elsewhere. Its zero set is the surface (3D) or curve (2D).
//!
//! This crate is `#![no_std]`. Without any feature it evaluates models over borrowed slices
//! ([`InterpolantView`]) in `f32` or `f64`, with no allocator: a model baked into flash as
//! constant arrays runs on a microcontroller. The `alloc` feature adds constraints, the linear
//! system, a small dense solver ([`fit`]) and knot insertion; `serde` adds versioned JSON model
//! files; `std` (the default) only switches square roots to the hardware instruction, which
//! gives the same bits; `rayon` evaluates batches on every core
//! ([`InterpolantView::par_values`]). For large systems use the `rbf-solve` crate, which solves the same
//! [`System`] with faer.
//!
//! The regularization λ (`FitSettings::lambda`) is from §6.3 of Gary Yngve and Greg Turk, "Robust
//! Creation of Implicit Surfaces from Polygonal Meshes", IEEE Transactions on Visualization and
//! Computer Graphics 8(4), 2002 (Yngve & Turk 2002 below).
//!
//! ```
//! use rbf_core::{Constraint, FitSettings, fit};
//!
//! // A closed curve through four points around an interior point (Turk & O'Brien 2002, Figure 1).
//! let constraints = [
//!     Constraint::boundary([1.0, 0.0]),
//!     Constraint::boundary([0.0, 1.0]),
//!     Constraint::boundary([-1.0, 0.0]),
//!     Constraint::boundary([0.0, -1.0]),
//!     Constraint::interior([0.0, 0.0], 1.0),
//! ];
//! let fit = fit(&constraints, &FitSettings::default()).unwrap();
//! let f = fit.interpolant.view();
//! assert!(f.value(&[1.0, 0.0]).abs() < 1e-12); // on the curve
//! assert!(f.value(&[0.2, 0.1]) > 0.0); // inside
//! assert!(f.value(&[2.0, 2.0]) < 0.0); // outside
//!
//! // The same model in f32, as a device would evaluate it.
//! let g = fit.interpolant.cast::<f32>();
//! assert!((g.value(&[0.2, 0.1]) as f64 - f.value(&[0.2, 0.1])).abs() < 1e-5);
//! ```
#![no_std]
#![deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
#![warn(
    clippy::std_instead_of_core,
    clippy::std_instead_of_alloc,
    clippy::alloc_instead_of_core
)]

#[cfg(feature = "alloc")]
extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

mod bound;
mod field;
mod kernel;
mod math;
mod real;
mod view;

#[doc(hidden)]
pub mod vec3;

#[cfg(feature = "rayon")]
mod parallel;
#[cfg(feature = "rayon")]
mod symmetric;

pub use bound::BallBound;
pub use field::ScalarField;
pub use kernel::Kernel;
pub use real::Real;
pub use view::{InterpolantView, LengthMismatch};

/// Items that need an allocator: built only with the `alloc` feature.
macro_rules! with_alloc {
    ($($item:item)*) => { $( #[cfg(feature = "alloc")] $item )* };
}

with_alloc! {
    mod condition;
    mod constraint;
    mod dense;
    mod error;
    mod fit;
    mod interpolant;
    mod knot;
    mod model;
    mod settings;
    pub mod shapes;
    mod system;
    mod text;
}

#[cfg(feature = "alloc")]
pub use {
    condition::estimate_inverse_norm1,
    constraint::{Constraint, ConstraintKind, NormalOffset, RowSource},
    dense::{fit, solve_dense},
    error::FitError,
    fit::{Fit, FitReport, Solution, SolveMethod},
    interpolant::Interpolant,
    knot::{KnotError, insert_knot, project_to_surface},
    model::Model,
    settings::FitSettings,
    system::System,
    text::{ParseError, parse_constraints, parse_points},
};

#[cfg(feature = "serde")]
mod file;
#[cfg(feature = "serde")]
pub use file::{
    AnyModel, ConstraintFile, ConstraintRecord, FileError, MODEL_FORMAT, MODEL_VERSION,
};
