//! Evaluation of a large model at many points to a stated accuracy: the far field where it is
//! faster and its error, measured against compensated direct sums at sampled points, is within
//! what was asked; direct sums otherwise.

use rbf_core::{InterpolantView, LengthMismatch, ScalarField};

use crate::field::{Calibrated, Charges, FarField, calibrated_with_coarse};

/// Centres below which direct sums are used whatever the number of points (the far field does
/// not pay there). Measured polygonizing reconstructed scans (`rbf mesh`, 3·10⁵–5·10⁵
/// samples, default accuracy): 1.3·10⁴ centres 3.27 s direct, 3.11 s through the far field;
/// 2·10⁴ centres 6.1 s and 4.7 s.
pub const FAR_FIELD_CENTRES: usize = 15_000;

/// Points at which the far field's error is measured before it is trusted.
const SAMPLED_POINTS: usize = 1000;

/// The coarse field ([`ScalarField::coarse`]) of [`Evaluator::with_coarse`] erred at most this
/// many times the accuracy asked at the sampled points: at the default accuracy, 10⁻³ of the
/// diagonal (for a distance-like f, a fraction of a pixel at the sizes rendered), for samples
/// that only steer evaluations taken at the accuracy asked.
const COARSE_FACTOR: f64 = 1e3;

/// The error a coarse field states: twice the largest seen at the sampled points (the fine
/// field is chosen with the same spare: within half the accuracy there).
const COARSE_SPARE: f64 = 2.0;

/// How an [`Evaluator`] evaluates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Direct sums over every centre.
    Direct,
    /// The far field at this order, with the error measured at sampled points.
    FarField {
        /// Chebyshev points along a cluster's longest side.
        order: usize,
        /// The largest error seen at the sampled points, in the model's units.
        sampled_error: f64,
    },
}

impl core::fmt::Display for Method {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Method::Direct => write!(f, "direct sums"),
            Method::FarField {
                order,
                sampled_error,
            } => write!(
                f,
                "far field of order {order} (largest error at the sampled points {sampled_error:.1e})"
            ),
        }
    }
}

/// f and ∇f of a model at many points, within an absolute accuracy.
///
/// ```
/// use rbf_core::{InterpolantView, Kernel};
/// use rbf_far::{Evaluator, Method};
/// let centres: Vec<[f64; 3]> = (0..30_000)
///     .map(|i| { let t = i as f64 * 1e-3; [t.cos(), t.sin(), (5.0 * t).sin()] })
///     .collect();
/// let weights: Vec<f64> = (0..30_000).map(|i| if i % 2 == 0 { 1e-4 } else { -1e-4 }).collect();
/// let f = InterpolantView::new(Kernel::Cubic, &centres, &weights, 1.0, [0.0; 3]).unwrap();
/// let points: Vec<[f64; 3]> = (0..20_000).map(|i| [0.0, 0.0, i as f64 * 1e-4]).collect();
/// let evaluator = Evaluator::new(f, &points, 1e-9);
/// assert!(matches!(evaluator.method(), Method::FarField { .. }));
/// let mut out = vec![0.0; points.len()];
/// evaluator.values(&points, &mut out).unwrap();
/// let mut exact = [0.0];
/// f.values(&points[123..124], &mut exact).unwrap();
/// assert!((out[123] - exact[0]).abs() <= 1e-9);
/// ```
pub struct Evaluator<'a, const D: usize> {
    view: InterpolantView<'a, f64, D>,
    far: Option<(FarField<D>, Charges)>,
    method: Method,
    /// A far field of lower order within [`COARSE_FACTOR`] times the accuracy, if there is one.
    coarse: Option<Box<Evaluator<'a, D>>>,
}

impl<'a, const D: usize> Evaluator<'a, D> {
    /// Chooses the method for evaluating `view` at `points` (or points like them) within
    /// `accuracy` (absolute, in the model's units): the far field at the lowest order whose
    /// error at sampled points of `points` is within half the accuracy, when the model is large
    /// enough for it to pay; direct sums otherwise.
    pub fn new(view: InterpolantView<'a, f64, D>, points: &[[f64; D]], accuracy: f64) -> Self {
        Self::build(view, points, accuracy, false)
    }

    /// [`Evaluator::new`], keeping beside it the far field of the lowest order its calibration
    /// found within a thousand times the accuracy, when that order is lower: the
    /// [`ScalarField::coarse`] companion that a renderer's bounds and samples take (it costs
    /// no extra measurement, only the memory of a second far field).
    ///
    /// ```
    /// use rbf_core::{InterpolantView, Kernel, ScalarField};
    /// use rbf_far::Evaluator;
    /// let centres: Vec<[f64; 3]> = (0..30_000)
    ///     .map(|i| { let t = i as f64 * 1e-3; [t.cos(), t.sin(), (5.0 * t).sin()] })
    ///     .collect();
    /// let weights: Vec<f64> = (0..30_000).map(|i| if i % 2 == 0 { 1e-4 } else { -1e-4 }).collect();
    /// let f = InterpolantView::new(Kernel::Cubic, &centres, &weights, 1.0, [0.0; 3]).unwrap();
    /// let evaluator = Evaluator::with_coarse(f, &centres, 1e-12);
    /// if let Some((coarse, error)) = evaluator.coarse() {
    ///     let (mut rough, mut exact) = ([0.0], [0.0]);
    ///     coarse.field_values(&[[0.1, 0.2, 0.3]], &mut rough).unwrap();
    ///     f.values(&[[0.1, 0.2, 0.3]], &mut exact).unwrap();
    ///     assert!(error <= 2e-9 && (rough[0] - exact[0]).abs() <= error);
    /// }
    /// assert!(Evaluator::new(f, &centres, 1e-12).coarse().is_none());
    /// ```
    pub fn with_coarse(
        view: InterpolantView<'a, f64, D>,
        points: &[[f64; D]],
        accuracy: f64,
    ) -> Self {
        Self::build(view, points, accuracy, true)
    }

    fn build(
        view: InterpolantView<'a, f64, D>,
        points: &[[f64; D]],
        accuracy: f64,
        keep_coarse: bool,
    ) -> Self {
        let direct = Self::direct(view);
        let k = view.centres().len();
        if k < FAR_FIELD_CENTRES || points.len() < SAMPLED_POINTS || !(accuracy > 0.0) {
            return direct;
        }
        let (fine, coarse) = calibrated_with_coarse(
            view.kernel(),
            view.centres(),
            view.weights(),
            points,
            0.5 * accuracy,
            if keep_coarse {
                COARSE_FACTOR * accuracy
            } else {
                0.5 * accuracy
            },
        );
        let coarse = coarse.map(|c| Box::new(Self::far(view, c, None)));
        match fine {
            Some(fine) => Self::far(view, fine, coarse),
            None => Self { coarse, ..direct },
        }
    }

    /// The far field `far` with its coarse companion.
    fn far(
        view: InterpolantView<'a, f64, D>,
        (field, charges, sampled_error): Calibrated<D>,
        coarse: Option<Box<Self>>,
    ) -> Self {
        Self {
            view,
            method: Method::FarField {
                order: field.settings().order,
                sampled_error,
            },
            far: Some((field, charges)),
            coarse,
        }
    }

    /// [`Evaluator::new`] at the default accuracy, 1e-6 of the diagonal of the centres'
    /// bounding box (what `rbf eval`, `rbf mesh`, `rbf render` and rbfsurf use unless told).
    pub fn with_default_accuracy(view: InterpolantView<'a, f64, D>, points: &[[f64; D]]) -> Self {
        Self::new(view, points, default_accuracy(view.centres()))
    }

    /// Direct sums over every centre.
    pub fn direct(view: InterpolantView<'a, f64, D>) -> Self {
        Self {
            view,
            far: None,
            method: Method::Direct,
            coarse: None,
        }
    }

    /// The method chosen.
    pub fn method(&self) -> Method {
        self.method
    }

    /// `out[i] = f(points[i])`.
    pub fn values(&self, points: &[[f64; D]], out: &mut [f64]) -> Result<(), LengthMismatch> {
        match &self.far {
            None => self.view.par_values(points, out),
            Some((field, charges)) => {
                field.values(charges, points, out)?;
                for (o, p) in out.iter_mut().zip(points) {
                    *o += self.affine(p);
                }
                Ok(())
            }
        }
    }

    /// f and ∇f at every point.
    pub fn values_and_gradients(
        &self,
        points: &[[f64; D]],
        values: &mut [f64],
        gradients: &mut [[f64; D]],
    ) -> Result<(), LengthMismatch> {
        match &self.far {
            None => self
                .view
                .par_values_and_gradients(points, values, gradients),
            Some((field, charges)) => {
                field.values_and_gradients(charges, points, values, gradients)?;
                let linear = self.view.linear();
                for ((v, g), p) in values.iter_mut().zip(gradients.iter_mut()).zip(points) {
                    *v += self.affine(p);
                    for d in 0..D {
                        g[d] += linear[d];
                    }
                }
                Ok(())
            }
        }
    }

    fn affine(&self, p: &[f64; D]) -> f64 {
        let linear = self.view.linear();
        self.view.constant() + (0..D).map(|d| linear[d] * p[d]).sum::<f64>()
    }
}

/// 1e-6 of the diagonal of the points' bounding box (1e-6 if there are none, or all coincide).
///
/// ```
/// assert!((rbf_far::default_accuracy(&[[0.0, 0.0], [3.0, 4.0]]) - 5e-6).abs() < 1e-20);
/// ```
pub fn default_accuracy<const D: usize>(centres: &[[f64; D]]) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; D], [f64::NEG_INFINITY; D]);
    for c in centres {
        for d in 0..D {
            (lo[d], hi[d]) = (lo[d].min(c[d]), hi[d].max(c[d]));
        }
    }
    let d = (0..D).map(|d| (hi[d] - lo[d]).powi(2)).sum::<f64>().sqrt();
    1e-6 * if d > 0.0 && d.is_finite() { d } else { 1.0 }
}

impl<const D: usize> ScalarField<D> for Evaluator<'_, D> {
    fn direct(&self) -> InterpolantView<'_, f64, D> {
        self.view
    }

    fn field_values(&self, points: &[[f64; D]], out: &mut [f64]) -> Result<(), LengthMismatch> {
        self.values(points, out)
    }

    fn field_values_and_gradients(
        &self,
        points: &[[f64; D]],
        values: &mut [f64],
        gradients: &mut [[f64; D]],
    ) -> Result<(), LengthMismatch> {
        self.values_and_gradients(points, values, gradients)
    }

    fn coarse(&self) -> Option<(&dyn ScalarField<D>, f64)> {
        let coarse = self.coarse.as_deref()?;
        match coarse.method {
            Method::FarField { sampled_error, .. } => Some((coarse, COARSE_SPARE * sampled_error)),
            Method::Direct => None,
        }
    }
}
