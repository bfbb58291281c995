//! What every consumer of a model evaluates through: batches of values, of values and gradients,
//! and the direct view that proofs over balls read. The direct view implements it here; a far
//! field (rbf-far's `Evaluator`) implements it for models of 10⁵ centres and more, and the front
//! ends pick which.

use crate::{InterpolantView, LengthMismatch};

/// A scalar field f: ℝᴰ → ℝ evaluated in batches (object safe: polygonizers and tracers take
/// `&dyn ScalarField<3>`).
///
/// With the `rayon` feature the direct view's batches run on every core.
///
/// ```
/// use rbf_core::{InterpolantView, Kernel, ScalarField};
/// let view = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
/// let f: &dyn ScalarField<3> = &view;
/// let (mut v, mut g) = ([0.0; 2], [[0.0; 3]; 2]);
/// f.field_values_and_gradients(&[[1.0, 0.0, 0.0], [0.0, 2.0, 0.0]], &mut v, &mut g).unwrap();
/// assert_eq!((v, g), ([0.0, -7.0], [[-3.0, 0.0, 0.0], [0.0, -12.0, 0.0]]));
/// assert_eq!(f.direct().centres().len(), 1);
/// ```
pub trait ScalarField<const D: usize>: Sync {
    /// The model summed directly: its centres, weights, kernel and affine part, for what must
    /// be proved (bounds over balls, the surface's box) rather than evaluated.
    fn direct(&self) -> InterpolantView<'_, f64, D>;

    /// `out[i] = f(points[i])`.
    fn field_values(&self, points: &[[f64; D]], out: &mut [f64]) -> Result<(), LengthMismatch>;

    /// f and ∇f at every point.
    fn field_values_and_gradients(
        &self,
        points: &[[f64; D]],
        values: &mut [f64],
        gradients: &mut [[f64; D]],
    ) -> Result<(), LengthMismatch>;

    /// A cheaper evaluation of the same field within a looser absolute error, for work whose
    /// results only steer exact evaluations (a tracer's bounds and samples, each hit confirmed
    /// through `self`): that field and the largest error measured for it. `None` (the default)
    /// when there is nothing cheaper than `self`.
    ///
    /// ```
    /// use rbf_core::{InterpolantView, Kernel, ScalarField};
    /// let view = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
    /// assert!(view.coarse().is_none());
    /// ```
    fn coarse(&self) -> Option<(&dyn ScalarField<D>, f64)> {
        None
    }
}

impl<const D: usize> ScalarField<D> for InterpolantView<'_, f64, D> {
    fn direct(&self) -> InterpolantView<'_, f64, D> {
        *self
    }

    fn field_values(&self, points: &[[f64; D]], out: &mut [f64]) -> Result<(), LengthMismatch> {
        #[cfg(feature = "rayon")]
        return self.par_values(points, out);
        #[cfg(not(feature = "rayon"))]
        return self.values(points, out);
    }

    fn field_values_and_gradients(
        &self,
        points: &[[f64; D]],
        values: &mut [f64],
        gradients: &mut [[f64; D]],
    ) -> Result<(), LengthMismatch> {
        #[cfg(feature = "rayon")]
        return self.par_values_and_gradients(points, values, gradients);
        #[cfg(not(feature = "rayon"))]
        return self.values_and_gradients(points, values, gradients);
    }
}
