//! Evaluation of an interpolant over borrowed slices: no allocator needed.

use crate::kernel::{Radial, with_radial};
use crate::{Kernel, Real};

/// Points evaluated together by the batch routines: enough to fill a 512-bit vector of `f64`.
const LANES: usize = 8;

/// An interpolant f(x) = Σⱼ wⱼ φ(|x − cⱼ|) + a + b·x over borrowed data.
///
/// This is what a device with no heap evaluates: centres and weights can be `static` arrays in
/// flash. [`crate::Interpolant::view`] gives one over an owned model.
///
/// ```
/// use rbf_core::{InterpolantView, Kernel};
/// // f(x) = 1 − |x|³: one centre at the origin with weight −1, and the constant 1.
/// // Its zero set is the unit sphere.
/// static CENTRES: [[f32; 3]; 1] = [[0.0, 0.0, 0.0]];
/// static WEIGHTS: [f32; 1] = [-1.0];
/// let f = InterpolantView::new(Kernel::Cubic, &CENTRES, &WEIGHTS, 1.0, [0.0; 3]).unwrap();
/// assert_eq!(f.value(&[0.0, 0.0, 0.0]), 1.0); // inside: positive
/// assert_eq!(f.value(&[1.0, 0.0, 0.0]), 0.0); // on the surface
/// assert!(f.value(&[2.0, 0.0, 0.0]) < 0.0); // outside: negative
/// ```
#[derive(Clone, Copy, Debug)]
pub struct InterpolantView<'a, T: Real, const D: usize> {
    pub(crate) kernel: Kernel,
    pub(crate) centres: &'a [[T; D]],
    pub(crate) weights: &'a [T],
    pub(crate) constant: T,
    pub(crate) linear: [T; D],
}

/// Two slices that must have the same length do not.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("length mismatch: {what} has {found} entries where {expected} were expected")]
pub struct LengthMismatch {
    /// Name of the slice with the wrong length: `"weights"`, `"output"`, `"values"` or
    /// `"gradients"`.
    pub what: &'static str,
    /// The length it needed: the number of centres (weights) or of points (outputs).
    pub expected: usize,
    /// The length the caller passed.
    pub found: usize,
}

impl LengthMismatch {
    /// `Ok` when `found == expected`, else the mismatch naming `what`.
    ///
    /// ```
    /// use rbf_core::LengthMismatch;
    /// assert!(LengthMismatch::check("output", 3, 3).is_ok());
    /// assert_eq!(LengthMismatch::check("output", 3, 2).unwrap_err().found, 2);
    /// ```
    pub const fn check(what: &'static str, expected: usize, found: usize) -> Result<(), Self> {
        if expected == found {
            Ok(())
        } else {
            Err(Self {
                what,
                expected,
                found,
            })
        }
    }
}

impl<'a, T: Real, const D: usize> InterpolantView<'a, T, D> {
    /// A view over centres, one weight per centre, and the affine part `constant + linear·x`.
    ///
    /// `const`, so that a model baked into constant arrays is itself a constant.
    pub const fn new(
        kernel: Kernel,
        centres: &'a [[T; D]],
        weights: &'a [T],
        constant: T,
        linear: [T; D],
    ) -> Result<Self, LengthMismatch> {
        // `?` is not allowed in a const fn.
        if let Err(e) = LengthMismatch::check("weights", centres.len(), weights.len()) {
            return Err(e);
        }
        Ok(Self {
            kernel,
            centres,
            weights,
            constant,
            linear,
        })
    }

    /// The kernel φ the weights were fitted for.
    pub const fn kernel(&self) -> Kernel {
        self.kernel
    }
    /// Centres cⱼ of the radial basis functions, one per weight, in the model's coordinates.
    pub const fn centres(&self) -> &'a [[T; D]] {
        self.centres
    }
    /// Weights wⱼ, one per centre, in the same order.
    pub const fn weights(&self) -> &'a [T] {
        self.weights
    }
    /// The constant term a of the affine part.
    pub const fn constant(&self) -> T {
        self.constant
    }
    /// The linear coefficients b of the affine part.
    pub const fn linear(&self) -> [T; D] {
        self.linear
    }

    #[inline(always)]
    pub(crate) fn affine(&self, x: &[T; D]) -> T {
        let mut v = self.constant;
        for d in 0..D {
            v += self.linear[d] * x[d];
        }
        v
    }

    /// f(x). Positive inside, negative outside, zero on the surface.
    pub fn value(&self, x: &[T; D]) -> T {
        with_radial!(self.kernel, K => self.value_with::<K>(x))
    }

    #[inline(always)]
    fn value_with<K: Radial>(&self, x: &[T; D]) -> T {
        let mut sum = T::ZERO;
        for (c, &w) in self.centres.iter().zip(self.weights) {
            let mut r2 = T::ZERO;
            for d in 0..D {
                let t = x[d] - c[d];
                r2 += t * t;
            }
            sum += w * K::phi_r2(r2);
        }
        sum + self.affine(x)
    }

    /// f(x) and its gradient ∇f(x). At a centre of the r kernel the centre's own (undefined)
    /// term is left out of the gradient.
    ///
    /// ```
    /// # use rbf_core::{InterpolantView, Kernel};
    /// let f = InterpolantView::new(Kernel::Cubic, &[[0.0, 0.0]], &[-1.0], 1.0, [0.0; 2]).unwrap();
    /// let (v, g) = f.value_and_gradient(&[1.0, 0.0]);
    /// assert_eq!((v, g), (0.0, [-3.0, 0.0])); // ∇(1 − r³) = −3r² x̂
    /// ```
    pub fn value_and_gradient(&self, x: &[T; D]) -> (T, [T; D]) {
        with_radial!(self.kernel, K => self.value_gradient_with::<K>(x))
    }

    #[inline(always)]
    fn value_gradient_with<K: Radial>(&self, x: &[T; D]) -> (T, [T; D]) {
        let mut sum = T::ZERO;
        let mut grad = [T::ZERO; D];
        for (c, &w) in self.centres.iter().zip(self.weights) {
            let (t, r2) = offset(x, c);
            let (phi, slope) = K::slope_r2(r2);
            sum += w * phi;
            let ws = w * slope;
            for d in 0..D {
                grad[d] += ws * t[d];
            }
        }
        for d in 0..D {
            grad[d] += self.linear[d];
        }
        (sum + self.affine(x), grad)
    }

    /// The gradient ∇f(x) alone.
    pub fn gradient(&self, x: &[T; D]) -> [T; D] {
        self.value_and_gradient(x).1
    }

    /// f(x), ∇f(x) and the Hessian ∇²f(x) (row-major, symmetric). At a centre of the r and
    /// r² log r kernels, where φ has no second derivative, that centre's term is left out.
    ///
    /// ```
    /// # use rbf_core::{InterpolantView, Kernel};
    /// let f = InterpolantView::new(Kernel::Cubic, &[[0.0, 0.0]], &[1.0], 0.0, [0.0; 2]).unwrap();
    /// let (_, _, h) = f.value_gradient_hessian(&[2.0, 0.0]);
    /// assert_eq!(h, [[12.0, 0.0], [0.0, 6.0]]); // φ″ = 6r along x̂, φ′/r = 3r across
    /// ```
    pub fn value_gradient_hessian(&self, x: &[T; D]) -> (T, [T; D], [[T; D]; D]) {
        with_radial!(self.kernel, K => self.hessian_with::<K>(x))
    }

    #[inline(always)]
    fn hessian_with<K: Radial>(&self, x: &[T; D]) -> (T, [T; D], [[T; D]; D]) {
        let mut sum = T::ZERO;
        let mut grad = self.linear;
        let mut hess = [[T::ZERO; D]; D];
        for (c, &w) in self.centres.iter().zip(self.weights) {
            let (t, r2) = offset(x, c);
            let (phi, g, h) = K::terms_r2(r2);
            sum += w * phi;
            let wg = w * g;
            let wh = w * h;
            for a in 0..D {
                grad[a] += wg * t[a];
                hess[a][a] += wg;
                let wta = wh * t[a];
                for b in a..D {
                    hess[a][b] += wta * t[b];
                }
            }
        }
        for a in 0..D {
            for b in 0..a {
                hess[a][b] = hess[b][a];
            }
        }
        (sum + self.affine(x), grad, hess)
    }

    /// f at many points: `out[i] = f(points[i])`. Points are taken eight at a time so that the
    /// compiler can vectorize across them (with `std` on x86-64, in AVX-512 or AVX2 when the CPU
    /// has them). Allocation-free.
    ///
    /// ```
    /// # use rbf_core::{InterpolantView, Kernel};
    /// let f = InterpolantView::new(Kernel::Cubic, &[[0.0, 0.0, 0.0]], &[-1.0], 1.0, [0.0; 3]).unwrap();
    /// let pts = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
    /// let mut out = [0.0; 3];
    /// f.values(&pts, &mut out).unwrap();
    /// assert_eq!(out, [1.0, 0.0, -7.0]);
    /// ```
    pub fn values(&self, points: &[[T; D]], out: &mut [T]) -> Result<(), LengthMismatch> {
        LengthMismatch::check("output", points.len(), out.len())?;
        self.values_dispatch(points, out);
        Ok(())
    }

    /// With `std` on x86-64, runs the batch loop compiled for AVX-512 or AVX2 when the CPU has
    /// them (detected at run time), so a portable binary uses the machine's full width.
    #[inline(always)]
    fn values_dispatch(&self, points: &[[T; D]], out: &mut [T]) {
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        {
            if std::is_x86_feature_detected!("avx512f")
                && std::is_x86_feature_detected!("avx512vl")
                && std::is_x86_feature_detected!("avx2")
                && std::is_x86_feature_detected!("fma")
            {
                // SAFETY: the CPU supports every feature the function enables, checked above.
                unsafe { self.values_avx512(points, out) };
                return;
            }
            if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
                // SAFETY: the CPU supports AVX2 and FMA, checked just above.
                unsafe { self.values_avx2(points, out) };
                return;
            }
        }
        self.values_portable(points, out);
    }

    #[inline(always)]
    fn values_portable(&self, points: &[[T; D]], out: &mut [T]) {
        with_radial!(self.kernel, K => self.values_with::<K>(points, out));
    }

    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
    fn values_avx512(&self, points: &[[T; D]], out: &mut [T]) {
        self.values_portable(points, out);
    }

    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[target_feature(enable = "avx2,fma")]
    fn values_avx2(&self, points: &[[T; D]], out: &mut [T]) {
        self.values_portable(points, out);
    }

    #[inline(always)]
    fn values_with<K: Radial>(&self, points: &[[T; D]], out: &mut [T]) {
        for (pts, o) in points.chunks(LANES).zip(out.chunks_mut(LANES)) {
            if pts.len() == 1 {
                o[0] = self.value_with::<K>(&pts[0]);
                continue;
            }
            let sums = self.block_sums::<K>(&lanes_of(pts));
            for (l, p) in pts.iter().enumerate() {
                o[l] = sums[l] + self.affine(p);
            }
        }
    }

    /// Σⱼ wⱼ φ(|xₗ − cⱼ|) for a block of points given coordinate by coordinate.
    #[inline(always)]
    fn block_sums<K: Radial>(&self, lanes: &[[T; LANES]; D]) -> [T; LANES] {
        let mut acc = [T::ZERO; LANES];
        for (c, &w) in self.centres.iter().zip(self.weights) {
            let mut r2 = [T::ZERO; LANES];
            for d in 0..D {
                for l in 0..LANES {
                    let t = lanes[d][l] - c[d];
                    r2[l] += t * t;
                }
            }
            for l in 0..LANES {
                acc[l] += w * K::phi_r2(r2[l]);
            }
        }
        acc
    }

    /// f and ∇f at many points, eight at a time (vectorized like [`InterpolantView::values`]).
    /// Allocation-free.
    ///
    /// ```
    /// # use rbf_core::{InterpolantView, Kernel};
    /// let f = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
    /// let (mut v, mut g) = ([0.0; 2], [[0.0; 3]; 2]);
    /// f.values_and_gradients(&[[1.0, 0.0, 0.0], [0.0, 2.0, 0.0]], &mut v, &mut g).unwrap();
    /// assert_eq!((v, g), ([0.0, -7.0], [[-3.0, 0.0, 0.0], [0.0, -12.0, 0.0]]));
    /// ```
    pub fn values_and_gradients(
        &self,
        points: &[[T; D]],
        values: &mut [T],
        gradients: &mut [[T; D]],
    ) -> Result<(), LengthMismatch> {
        LengthMismatch::check("values", points.len(), values.len())?;
        LengthMismatch::check("gradients", points.len(), gradients.len())?;
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        {
            if std::is_x86_feature_detected!("avx512f")
                && std::is_x86_feature_detected!("avx512vl")
                && std::is_x86_feature_detected!("avx2")
                && std::is_x86_feature_detected!("fma")
            {
                // SAFETY: the CPU supports every feature the function enables, checked above.
                unsafe { self.gradients_avx512(points, values, gradients) };
                return Ok(());
            }
            if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
                // SAFETY: the CPU supports AVX2 and FMA, checked just above.
                unsafe { self.gradients_avx2(points, values, gradients) };
                return Ok(());
            }
        }
        self.gradients_portable(points, values, gradients);
        Ok(())
    }

    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[target_feature(enable = "avx512f,avx512vl,avx2,fma")]
    fn gradients_avx512(&self, points: &[[T; D]], values: &mut [T], gradients: &mut [[T; D]]) {
        self.gradients_portable(points, values, gradients);
    }

    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[target_feature(enable = "avx2,fma")]
    fn gradients_avx2(&self, points: &[[T; D]], values: &mut [T], gradients: &mut [[T; D]]) {
        self.gradients_portable(points, values, gradients);
    }

    #[inline(always)]
    fn gradients_portable(&self, points: &[[T; D]], values: &mut [T], gradients: &mut [[T; D]]) {
        with_radial!(self.kernel, K => self.gradients_with::<K>(points, values, gradients));
    }

    #[inline(always)]
    fn gradients_with<K: Radial>(
        &self,
        points: &[[T; D]],
        values: &mut [T],
        gradients: &mut [[T; D]],
    ) {
        let blocks = points
            .chunks(LANES)
            .zip(values.chunks_mut(LANES))
            .zip(gradients.chunks_mut(LANES));
        for ((pts, v), g) in blocks {
            if pts.len() == 1 {
                (v[0], g[0]) = self.value_gradient_with::<K>(&pts[0]);
                continue;
            }
            let (sums, grad) = self.block_gradients::<K>(&lanes_of(pts));
            for (l, p) in pts.iter().enumerate() {
                v[l] = sums[l] + self.affine(p);
                for d in 0..D {
                    g[l][d] = grad[d][l] + self.linear[d];
                }
            }
        }
    }

    /// [`InterpolantView::block_sums`] and the sums' gradients, axis by axis.
    #[inline(always)]
    fn block_gradients<K: Radial>(&self, lanes: &[[T; LANES]; D]) -> ([T; LANES], [[T; LANES]; D]) {
        let mut acc = [T::ZERO; LANES];
        let mut grad = [[T::ZERO; LANES]; D];
        for (c, &w) in self.centres.iter().zip(self.weights) {
            let mut t = [[T::ZERO; LANES]; D];
            let mut r2 = [T::ZERO; LANES];
            for d in 0..D {
                for l in 0..LANES {
                    t[d][l] = lanes[d][l] - c[d];
                    r2[l] += t[d][l] * t[d][l];
                }
            }
            for l in 0..LANES {
                let (phi, slope) = K::slope_r2(r2[l]);
                acc[l] += w * phi;
                let ws = w * slope;
                for d in 0..D {
                    grad[d][l] += ws * t[d][l];
                }
            }
        }
        // Handed over through memory, axis by axis: stored straight into the points' gradients
        // (point by point), the accumulators were grouped by point and shuffled in the loop
        // over the centres, at twice the cost.
        (acc, core::hint::black_box(grad))
    }
}

/// A block of up to [`LANES`] points coordinate by coordinate, the last point repeated in the
/// lanes left over (their sums are computed and dropped: a block of eight costs about what two
/// single points do).
#[inline(always)]
fn lanes_of<T: Real, const D: usize>(points: &[[T; D]]) -> [[T; LANES]; D] {
    let mut lanes = [[T::ZERO; LANES]; D];
    let last = points.len() - 1;
    for (d, lane) in lanes.iter_mut().enumerate() {
        for (l, x) in lane.iter_mut().enumerate() {
            *x = points[l.min(last)][d];
        }
    }
    lanes
}

/// x − c and its squared length.
#[inline(always)]
fn offset<T: Real, const D: usize>(x: &[T; D], c: &[T; D]) -> ([T; D], T) {
    let mut t = [T::ZERO; D];
    let mut r2 = T::ZERO;
    for d in 0..D {
        t[d] = x[d] - c[d];
        r2 += t[d] * t[d];
    }
    (t, r2)
}
