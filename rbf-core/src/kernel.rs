//! Radial kernels φ(r) and their derivatives.

use crate::Real;

/// The radial basis function φ of an interpolant.
///
/// Each kernel is the fundamental solution of a thin-plate energy, so the interpolant minimizes
/// that energy among all functions meeting the constraints (Turk & O'Brien 2002, §3):
///
/// | kernel | φ(r) | natural dimension | definiteness on polynomial-free weights |
/// |---|---|---|---|
/// | [`Kernel::Cubic`] | r³ | 3D (the papers' choice) | positive |
/// | [`Kernel::Linear`] | r | 3D (the biharmonic one of Carr et al. 2001) | negative |
/// | [`Kernel::ThinPlate`] | r² log r | 2D | positive |
///
/// ```
/// use rbf_core::Kernel;
/// let k = Kernel::Cubic;
/// assert_eq!(k.phi(2.0_f64), 8.0);
/// assert_eq!(k.dphi(2.0_f64), 12.0);
/// assert_eq!(k.d2phi(2.0_f64), 12.0);
/// assert_eq!(Kernel::ThinPlate.phi(0.0_f64), 0.0); // safe at r = 0
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "kebab-case"))]
#[non_exhaustive]
pub enum Kernel {
    /// φ(r) = r³, the triharmonic kernel: smooth (C²) surfaces in 3D. The default.
    #[default]
    Cubic,
    /// φ(r) = r, the biharmonic kernel in 3D.
    Linear,
    /// φ(r) = r² log r, the thin-plate spline of 2D.
    ThinPlate,
}

impl Kernel {
    /// The usual kernel for a dimension: r² log r in 2D, r³ otherwise.
    ///
    /// ```
    /// use rbf_core::Kernel;
    /// assert_eq!(Kernel::for_dimension(2), Kernel::ThinPlate);
    /// assert_eq!(Kernel::for_dimension(3), Kernel::Cubic);
    /// ```
    pub const fn for_dimension(dim: usize) -> Kernel {
        if dim == 2 {
            Kernel::ThinPlate
        } else {
            Kernel::Cubic
        }
    }

    /// A short lowercase name (`cubic`, `linear`, `thin-plate`).
    pub const fn name(self) -> &'static str {
        match self {
            Kernel::Cubic => "cubic",
            Kernel::Linear => "linear",
            Kernel::ThinPlate => "thin-plate",
        }
    }

    /// φ(r). Zero at r = 0 for every kernel.
    #[inline]
    pub fn phi<T: Real>(self, r: T) -> T {
        match self {
            Kernel::Cubic => r * r * r,
            Kernel::Linear => r,
            Kernel::ThinPlate => {
                if r > T::ZERO {
                    r * r * r.ln()
                } else {
                    T::ZERO
                }
            }
        }
    }

    /// φ′(r). Zero at r = 0 except for the linear kernel (1, its one-sided slope).
    #[inline]
    pub fn dphi<T: Real>(self, r: T) -> T {
        match self {
            Kernel::Cubic => T::from_f64(3.0) * r * r,
            Kernel::Linear => T::ONE,
            Kernel::ThinPlate => {
                if r > T::ZERO {
                    T::from_f64(2.0) * r * r.ln() + r
                } else {
                    T::ZERO
                }
            }
        }
    }

    /// φ″(r). For r² log r it diverges like 2 log r as r → 0; at r = 0 it returns −∞, the limit.
    #[inline]
    pub fn d2phi<T: Real>(self, r: T) -> T {
        match self {
            Kernel::Cubic => T::from_f64(6.0) * r,
            Kernel::Linear => T::ZERO,
            Kernel::ThinPlate => {
                if r > T::ZERO {
                    T::from_f64(2.0) * r.ln() + T::from_f64(3.0)
                } else {
                    T::from_f64(f64::NEG_INFINITY)
                }
            }
        }
    }

    /// The power of `s` by which φ scales when every distance is scaled by `s`
    /// (exactly for r³ and r; for r² log r up to a term that the linear polynomial absorbs).
    #[doc(hidden)]
    pub const fn scale_exponent(self) -> i32 {
        match self {
            Kernel::Cubic => 3,
            Kernel::Linear => 1,
            Kernel::ThinPlate => 2,
        }
    }

    /// The sign `σ` such that `σ · wᵀ Φ w > 0` for every non-zero weight vector `w` orthogonal
    /// to the linear polynomials: +1 for r³ and r² log r, −1 for r.
    #[doc(hidden)]
    pub const fn definiteness(self) -> f64 {
        match self {
            Kernel::Linear => -1.0,
            _ => 1.0,
        }
    }
}

/// Radial terms of one kernel as a function of the squared distance, with the kernel chosen at
/// compile time so that hot loops hold no branch on it.
pub(crate) trait Radial {
    /// φ as a function of r².
    fn phi_r2<T: Real>(r2: T) -> T;
    /// (φ, φ′/r, (φ″ − φ′/r)/r²) as functions of r², each set to 0 where it is singular at r = 0.
    fn terms_r2<T: Real>(r2: T) -> (T, T, T);
    /// (φ, φ′/r) as functions of r², the second set to 0 where it is singular at r = 0.
    fn slope_r2<T: Real>(r2: T) -> (T, T);
}

pub(crate) struct CubicRadial;
pub(crate) struct LinearRadial;
pub(crate) struct ThinPlateRadial;

impl Radial for CubicRadial {
    #[inline(always)]
    fn phi_r2<T: Real>(r2: T) -> T {
        r2 * r2.sqrt()
    }
    #[inline(always)]
    fn terms_r2<T: Real>(r2: T) -> (T, T, T) {
        let r = r2.sqrt();
        let h = if r > T::ZERO {
            T::from_f64(3.0) / r
        } else {
            T::ZERO
        };
        (r2 * r, T::from_f64(3.0) * r, h)
    }
    #[inline(always)]
    fn slope_r2<T: Real>(r2: T) -> (T, T) {
        let r = r2.sqrt();
        (r2 * r, T::from_f64(3.0) * r)
    }
}

impl Radial for LinearRadial {
    #[inline(always)]
    fn phi_r2<T: Real>(r2: T) -> T {
        r2.sqrt()
    }
    #[inline(always)]
    fn terms_r2<T: Real>(r2: T) -> (T, T, T) {
        let r = r2.sqrt();
        if r > T::ZERO {
            let g = T::ONE / r;
            (r, g, -g / r2)
        } else {
            (T::ZERO, T::ZERO, T::ZERO)
        }
    }
    #[inline(always)]
    fn slope_r2<T: Real>(r2: T) -> (T, T) {
        let r = r2.sqrt();
        if r > T::ZERO {
            (r, T::ONE / r)
        } else {
            (T::ZERO, T::ZERO)
        }
    }
}

impl Radial for ThinPlateRadial {
    #[inline(always)]
    fn phi_r2<T: Real>(r2: T) -> T {
        if r2 > T::ZERO {
            T::from_f64(0.5) * r2 * r2.ln()
        } else {
            T::ZERO
        }
    }
    #[inline(always)]
    fn terms_r2<T: Real>(r2: T) -> (T, T, T) {
        if r2 > T::ZERO {
            let l = r2.ln();
            (T::from_f64(0.5) * r2 * l, l + T::ONE, T::from_f64(2.0) / r2)
        } else {
            (T::ZERO, T::ZERO, T::ZERO)
        }
    }
    #[inline(always)]
    fn slope_r2<T: Real>(r2: T) -> (T, T) {
        if r2 > T::ZERO {
            let l = r2.ln();
            (T::from_f64(0.5) * r2 * l, l + T::ONE)
        } else {
            (T::ZERO, T::ZERO)
        }
    }
}

/// Calls `$body` with `$K` bound to the zero-sized [`Radial`] type of `$kernel`.
macro_rules! with_radial {
    ($kernel:expr, $K:ident => $body:expr) => {
        match $kernel {
            $crate::Kernel::Cubic => {
                type $K = $crate::kernel::CubicRadial;
                $body
            }
            $crate::Kernel::Linear => {
                type $K = $crate::kernel::LinearRadial;
                $body
            }
            $crate::Kernel::ThinPlate => {
                type $K = $crate::kernel::ThinPlateRadial;
                $body
            }
        }
    };
}
pub(crate) use with_radial;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radial_terms_match_the_public_derivatives() {
        for k in [Kernel::Cubic, Kernel::Linear, Kernel::ThinPlate] {
            for &r in &[0.3_f64, 1.0, 2.5] {
                let (phi, g, h) = with_radial!(k, K => K::terms_r2(r * r));
                let (phi3, g3) = with_radial!(k, K => K::slope_r2(r * r));
                assert_eq!((phi3, g3), (phi, g), "{k:?}");
                let phi2 = with_radial!(k, K => K::phi_r2(r * r));
                assert!((phi - k.phi(r)).abs() < 1e-12, "{k:?}");
                assert!((phi2 - k.phi(r)).abs() < 1e-12, "{k:?}");
                assert!((g - k.dphi(r) / r).abs() < 1e-12, "{k:?}");
                assert!(
                    (h - (k.d2phi(r) - k.dphi(r) / r) / (r * r)).abs() < 1e-12,
                    "{k:?}"
                );
            }
        }
    }

    #[test]
    fn derivatives_match_central_differences() {
        for k in [Kernel::Cubic, Kernel::Linear, Kernel::ThinPlate] {
            for &r in &[0.2_f64, 0.9, 3.0] {
                let e = 1e-6;
                let d1 = (k.phi(r + e) - k.phi(r - e)) / (2.0 * e);
                let d2 = (k.dphi(r + e) - k.dphi(r - e)) / (2.0 * e);
                assert!((d1 - k.dphi(r)).abs() < 1e-6, "{k:?} φ′ at {r}");
                assert!((d2 - k.d2phi(r)).abs() < 1e-6, "{k:?} φ″ at {r}");
            }
        }
    }

    #[test]
    fn safe_at_zero() {
        for k in [Kernel::Cubic, Kernel::Linear, Kernel::ThinPlate] {
            assert_eq!(k.phi(0.0_f64), 0.0);
            assert!(!k.dphi(0.0_f64).is_nan());
            assert!(!k.d2phi(0.0_f64).is_nan());
            let (a, b, c) = with_radial!(k, K => K::terms_r2(0.0_f64));
            assert_eq!((a, b, c), (0.0, 0.0, 0.0));
        }
    }
}
