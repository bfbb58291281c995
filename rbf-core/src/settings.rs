//! What a fit can be told.

use crate::{Kernel, NormalOffset};

/// Settings of a fit. Every field has the papers' value as its default.
///
/// ```
/// use rbf_core::{FitSettings, Kernel};
/// let s = FitSettings { lambda: 1e-3, kernel: Some(Kernel::Linear), ..Default::default() };
/// assert_eq!(s.kernel_for(3), Kernel::Linear);
/// assert_eq!(FitSettings::default().kernel_for(2), Kernel::ThinPlate);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitSettings {
    /// The kernel; `None` picks r² log r in 2D and r³ in 3D.
    pub kernel: Option<Kernel>,
    /// Global regularization λ ≥ 0 on every diagonal entry of the kernel block (Yngve & Turk
    /// 2002, §6.3), with the sign that makes the block more definite: +λ for r³ and r² log r,
    /// −λ for r (Carr et al. 2001 subtract it for the biharmonic r). 0 interpolates exactly;
    /// larger values trade exactness for smoothness. The same quantity as scipy's
    /// `RBFInterpolator(smoothing=λ)`, whose linear kernel is −r.
    pub lambda: f64,
    /// The default distance from a normal constraint's point to its offset point.
    pub normal_offset: NormalOffset,
    /// Two constraint points closer than this fraction of the bounding box's longest side are
    /// coincident, an error. 1e-9 by default.
    pub min_separation: f64,
    /// The largest accepted residual max|f(cᵢ) + λᵢwᵢ − hᵢ| relative to max|hᵢ|; a fit that
    /// cannot reach it is reported as ill-conditioned instead of returned. 1e-6 by default;
    /// finite and at least [`FitSettings::SMALLEST_MAX_RESIDUAL`].
    pub max_residual: f64,
}

impl Default for FitSettings {
    fn default() -> Self {
        Self {
            kernel: None,
            lambda: 0.0,
            normal_offset: NormalOffset::default(),
            min_separation: 1e-9,
            max_residual: 1e-6,
        }
    }
}

impl FitSettings {
    /// The smallest `max_residual` accepted: a relative residual below about 5ε cannot be
    /// measured, let alone met.
    pub const SMALLEST_MAX_RESIDUAL: f64 = 1e-15;

    /// Whether `r` is an acceptable `max_residual`: finite and at least
    /// [`Self::SMALLEST_MAX_RESIDUAL`].
    ///
    /// ```
    /// use rbf_core::FitSettings;
    /// assert!(FitSettings::max_residual_is_valid(1e-6));
    /// assert!(!FitSettings::max_residual_is_valid(0.0) && !FitSettings::max_residual_is_valid(f64::NAN));
    /// ```
    pub fn max_residual_is_valid(r: f64) -> bool {
        r.is_finite() && r >= Self::SMALLEST_MAX_RESIDUAL
    }

    /// The kernel used in `dim` dimensions.
    pub const fn kernel_for(&self, dim: usize) -> Kernel {
        match self.kernel {
            Some(k) => k,
            None => Kernel::for_dimension(dim),
        }
    }
}
