//! The far field of radial basis function sums: Σⱼ wⱼ φ(|x − cⱼ|) over 10⁵–10⁶ centres at as
//! many points, in time that grows about as K log K instead of K², to a chosen accuracy.
//!
//! [`FarField`] puts the centres in a k-d [`Tree`]; each cluster far enough from a group of
//! targets is replaced by charges on a small grid of Chebyshev points over its box
//! ([`Charges`]), and what is near is summed directly, all through rbf-core's vectorized
//! evaluator.

#![warn(missing_docs)]

mod chebyshev;
mod clusters;
mod dual;
mod evaluator;
mod field;
mod settings;
mod tensor;
mod tree;

pub use evaluator::{Evaluator, FAR_FIELD_CENTRES, Method, default_accuracy};
pub use field::{Calibrated, Charges, FarField, calibrated, calibrated_product};
pub use settings::FarFieldSettings;
pub use tree::{Node, Tree, bounds, box_gap2, point_gap2};
