//! The owned interpolant: what a fit returns and a model file holds.

use alloc::vec::Vec;

use crate::{InterpolantView, Kernel, LengthMismatch, Real};

/// f(x) = Σⱼ wⱼ φ(|x − cⱼ|) + a + b·x, owning its centres and weights.
///
/// Evaluation goes through [`Interpolant::view`] (or the same methods here, which forward to
/// it). Fit in `f64`, then [`Interpolant::cast`] to `f32` for a device.
///
/// ```
/// use rbf_core::{Interpolant, Kernel};
/// let f = Interpolant::new(Kernel::Cubic, vec![[0.0; 3]], vec![-1.0], 1.0, [0.0; 3]).unwrap();
/// assert_eq!(f.value(&[1.0, 0.0, 0.0]), 0.0);
/// let g = f.cast::<f32>();
/// assert_eq!(g.value(&[1.0, 0.0, 0.0]), 0.0_f32);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Interpolant<T: Real, const D: usize> {
    kernel: Kernel,
    centres: Vec<[T; D]>,
    weights: Vec<T>,
    constant: T,
    linear: [T; D],
}

impl<T: Real, const D: usize> Interpolant<T, D> {
    /// An interpolant from its parts; one weight per centre.
    pub fn new(
        kernel: Kernel,
        centres: Vec<[T; D]>,
        weights: Vec<T>,
        constant: T,
        linear: [T; D],
    ) -> Result<Self, LengthMismatch> {
        InterpolantView::new(kernel, &centres, &weights, constant, linear)?;
        Ok(Self::from_parts(kernel, centres, weights, constant, linear))
    }

    pub(crate) fn from_parts(
        kernel: Kernel,
        centres: Vec<[T; D]>,
        weights: Vec<T>,
        constant: T,
        linear: [T; D],
    ) -> Self {
        Self {
            kernel,
            centres,
            weights,
            constant,
            linear,
        }
    }

    /// A borrowed view, for evaluation.
    pub fn view(&self) -> InterpolantView<'_, T, D> {
        // Lengths were checked on construction and never change.
        InterpolantView {
            kernel: self.kernel,
            centres: &self.centres,
            weights: &self.weights,
            constant: self.constant,
            linear: self.linear,
        }
    }

    /// The same interpolant in another precision.
    pub fn cast<U: Real>(&self) -> Interpolant<U, D> {
        let c = |x: T| U::from_f64(x.to_f64());
        Interpolant {
            kernel: self.kernel,
            centres: self.centres.iter().map(|p| p.map(c)).collect(),
            weights: self.weights.iter().map(|&w| c(w)).collect(),
            constant: c(self.constant),
            linear: self.linear.map(c),
        }
    }

    /// The kernel φ the weights were fitted for.
    pub fn kernel(&self) -> Kernel {
        self.kernel
    }
    /// Centres cⱼ of the radial basis functions, one per weight, in the model's coordinates.
    pub fn centres(&self) -> &[[T; D]] {
        &self.centres
    }
    /// Weights wⱼ, one per centre, in the same order.
    pub fn weights(&self) -> &[T] {
        &self.weights
    }
    /// Constant term a of the affine part a + b·x.
    pub fn constant(&self) -> T {
        self.constant
    }
    /// Linear coefficients b of the affine part, one per coordinate.
    pub fn linear(&self) -> [T; D] {
        self.linear
    }

    /// f(x); see [`InterpolantView::value`].
    pub fn value(&self, x: &[T; D]) -> T {
        self.view().value(x)
    }
    /// f(x) and ∇f(x); see [`InterpolantView::value_and_gradient`].
    pub fn value_and_gradient(&self, x: &[T; D]) -> (T, [T; D]) {
        self.view().value_and_gradient(x)
    }
    /// ∇f(x); see [`InterpolantView::gradient`].
    pub fn gradient(&self, x: &[T; D]) -> [T; D] {
        self.view().gradient(x)
    }
    /// f, ∇f and ∇²f at x; see [`InterpolantView::value_gradient_hessian`].
    pub fn value_gradient_hessian(&self, x: &[T; D]) -> (T, [T; D], [[T; D]; D]) {
        self.view().value_gradient_hessian(x)
    }
    /// f at many points; see [`InterpolantView::values`].
    pub fn values(&self, points: &[[T; D]], out: &mut [T]) -> Result<(), LengthMismatch> {
        self.view().values(points, out)
    }
}
