//! A model: constraints, the settings they were fitted with, and the interpolant.

use alloc::vec::Vec;

use crate::{Constraint, FitReport, FitSettings, Interpolant};

/// Everything a model file holds: the constraints (so that a model can be refitted, blended or
/// edited), the settings of the fit, the interpolant, and the fit's figures.
///
/// With the `serde` feature, [`Model::to_json`] and [`crate::AnyModel::from_json`] write and
/// read it as versioned JSON.
#[derive(Clone, Debug, PartialEq)]
pub struct Model<const D: usize> {
    /// The constraints, in the caller's order.
    pub constraints: Vec<Constraint<D>>,
    /// The settings the constraints were fitted with (kernel, λ, normal offset, checks).
    pub settings: FitSettings,
    /// The fitted f, in the constraints' coordinates.
    pub interpolant: Interpolant<f64, D>,
    /// The fit's figures, when known.
    pub report: Option<FitReport>,
}
