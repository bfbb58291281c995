//! Guaranteed bounds on f over a ball, from the kernel's derivatives and the weights: how fast
//! f can change there (a Lipschitz constant) and whether it can reach zero. Sphere tracers step
//! by them; polygonizers skip empty space with them.

use crate::math::{ln, sqrt};
use crate::{InterpolantView, Kernel};

/// What is proved about f over a ball.
#[derive(Clone, Copy, Debug, PartialEq)]
#[doc(hidden)]
pub struct BallBound {
    /// f at the centre.
    pub value: f64,
    /// |∇f| at the centre.
    pub gradient_norm: f64,
    /// |∇f| ≤ `lipschitz` everywhere in the ball.
    pub lipschitz: f64,
    /// |f(x) − f(centre)| ≤ `change` everywhere in the ball.
    pub change: f64,
}

impl BallBound {
    /// True when f cannot vanish in the ball (f keeps the sign of its centre value), with a
    /// little slack for the rounding of f itself.
    pub fn one_sign(&self) -> bool {
        self.value.abs() > self.change * (1.0 + 1e-9) + 1e-12 * self.value.abs().max(1e-300)
    }
}

impl Kernel {
    /// Upper bounds on the slope |φ′(r)| and on the Hessian norm ‖∇²φ(|x|)‖ for distances r in
    /// [lo, hi]; infinite where none exists.
    ///
    /// ```
    /// use rbf_core::Kernel;
    /// assert_eq!(Kernel::Cubic.derivative_bounds(1.0, 2.0), (12.0, 12.0)); // 3r², 6r
    /// assert_eq!(Kernel::Linear.derivative_bounds(0.0, 2.0), (1.0, f64::INFINITY));
    /// ```
    #[doc(hidden)]
    pub fn derivative_bounds(self, lo: f64, hi: f64) -> (f64, f64) {
        match self {
            // φ′ = 3r², Hessian eigenvalues 6r and 3r.
            Kernel::Cubic => (3.0 * hi * hi, 6.0 * hi),
            // φ′ = 1, Hessian eigenvalues 0 and 1/r.
            Kernel::Linear => (1.0, if lo > 0.0 { 1.0 / lo } else { f64::INFINITY }),
            // φ′ = r(2 ln r + 1), Hessian eigenvalues 2 ln r + 3 and 2 ln r + 1.
            Kernel::ThinPlate => {
                if lo <= 0.0 {
                    // |r (2 ln r + 1)| ≤ r (2 |ln r| + 1) on (0, hi], and r |ln r| ≤ 1/e < 1.
                    let slope = hi * (2.0 * ln(hi).abs() + 1.0) + 2.0;
                    return (slope, f64::INFINITY);
                }
                let l = ln(lo).abs().max(ln(hi).abs());
                (hi * (2.0 * l + 1.0), 2.0 * l + 3.0)
            }
        }
    }
}

impl<const D: usize> InterpolantView<'_, f64, D> {
    /// Guaranteed bounds on f over the ball of `radius` around `centre`: the smaller of a
    /// first-order bound (Σ|wⱼ| max|φ′| + |b|) and a second-order one (|∇f(c)| plus
    /// Σ|wⱼ| max‖∇²φ‖ times the radius).
    ///
    /// ```
    /// use rbf_core::{InterpolantView, Kernel};
    /// // f = 1 − r³: the unit sphere.
    /// let f = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
    /// let b = f.ball_bound(&[2.5, 0.0, 0.0], 0.5);
    /// // The slope 3r² is at most 3 · 3² = 27 in the ball.
    /// assert!(b.lipschitz >= 27.0 && b.lipschitz < 27.5);
    /// assert!(b.one_sign()); // f < 0 throughout: the sphere is farther than 0.5
    /// assert!(!f.ball_bound(&[1.2, 0.0, 0.0], 0.5).one_sign());
    /// ```
    #[doc(hidden)]
    pub fn ball_bound(&self, centre: &[f64; D], radius: f64) -> BallBound {
        let (value, gradient) = self.value_and_gradient(centre);
        let norm = |v: &[f64; D]| sqrt(v.iter().map(|x| x * x).sum::<f64>());
        let gradient_norm = norm(&gradient);
        let kernel = self.kernel();
        let mut slope_sum = 0.0;
        let mut curvature_sum = 0.0;
        for (c, w) in self.centres().iter().zip(self.weights()) {
            let mut d2 = 0.0;
            for k in 0..D {
                d2 += (centre[k] - c[k]) * (centre[k] - c[k]);
            }
            let d = sqrt(d2);
            let (s, h) = kernel.derivative_bounds((d - radius).max(0.0), d + radius);
            slope_sum += w.abs() * s;
            curvature_sum += w.abs() * h;
        }
        let first = slope_sum + norm(&self.linear());
        let second = gradient_norm + curvature_sum * radius;
        let lipschitz = first.min(second);
        let taylor = gradient_norm * radius + 0.5 * curvature_sum * radius * radius;
        BallBound {
            value,
            gradient_norm,
            lipschitz,
            change: (lipschitz * radius).min(taylor),
        }
    }
}

impl<const D: usize> InterpolantView<'_, f64, D> {
    /// A box that holds the surface: the centres' bounding box grown by `margin` times its
    /// longest side, then by a quarter (up to eight times) while f > 0 somewhere on a 16ᴰ⁻¹
    /// sample grid of its faces, and once more by a tenth for bulges between the samples.
    /// The box is found by sampling, not proved: a closed surface around the centres lies
    /// inside it, while a surface that is not closed, or a detached bubble of a fit wholly
    /// outside the grown box, is cut by it.
    ///
    /// ```
    /// use rbf_core::{InterpolantView, Kernel};
    /// // The unit sphere, from a single centre: the box grows until it holds the sphere.
    /// let f = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
    /// let (lo, hi) = f.surface_box(0.1);
    /// assert!(lo.iter().all(|&v| v < -1.0) && hi.iter().all(|&v| v > 1.0));
    /// ```
    pub fn surface_box(&self, margin: f64) -> ([f64; D], [f64; D]) {
        const N: usize = 16;
        let mut lo = [f64::INFINITY; D];
        let mut hi = [f64::NEG_INFINITY; D];
        for c in self.centres() {
            for d in 0..D {
                lo[d] = lo[d].min(c[d]);
                hi[d] = hi[d].max(c[d]);
            }
        }
        if self.centres().is_empty() {
            (lo, hi) = ([-1.0; D], [1.0; D]);
        }
        let side = (0..D).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
        let side = if side > 0.0 { side } else { 1.0 };
        lo = lo.map(|v| v - margin * side);
        hi = hi.map(|v| v + margin * side);
        let face_points = N.pow(D as u32 - 1);
        // Face points are evaluated in batches (the vectorized loop), until one is inside.
        const BATCH: usize = 64;
        let mut batch = [[0.0; D]; BATCH];
        let mut values = [0.0; BATCH];
        for _ in 0..8 {
            let mut outside = true;
            let mut filled = 0;
            'faces: for axis in 0..D {
                for end in [lo[axis], hi[axis]] {
                    for i in 0..face_points {
                        // Digit k of i in base N places the point along the k-th other axis.
                        let mut p = [end; D];
                        let mut rest = i;
                        for d in (0..D).filter(|&d| d != axis) {
                            let t = (rest % N) as f64 / (N - 1) as f64;
                            rest /= N;
                            p[d] = lo[d] + (hi[d] - lo[d]) * t;
                        }
                        batch[filled] = p;
                        filled += 1;
                        let last = axis == D - 1 && end == hi[axis] && i == face_points - 1;
                        if filled == BATCH || last {
                            // Equal lengths by construction.
                            let _ = self.values(&batch[..filled], &mut values[..filled]);
                            if values[..filled].iter().any(|&v| v > 0.0) {
                                outside = false;
                                break 'faces;
                            }
                            filled = 0;
                        }
                    }
                }
            }
            let by = if outside { 0.1 } else { 0.25 };
            let grow: [f64; D] = core::array::from_fn(|d| by * (hi[d] - lo[d]));
            lo = core::array::from_fn(|d| lo[d] - grow[d]);
            hi = core::array::from_fn(|d| hi[d] + grow[d]);
            if outside {
                break;
            }
        }
        (lo, hi)
    }
}
