//! How fine a far field is: the interpolation order, the separation at which a cluster's proxies
//! stand in for its centres, and the tree's leaf sizes.

/// The far field's accuracy and granularity.
///
/// A cluster whose box has longest side s is replaced by its proxies for targets at distance
/// at least s/θ from the box; along that side it has `order` Chebyshev points, and along a
/// shorter side t as many as give the same interpolation error there (fewer: a flat cluster of
/// a surface gets a flat grid, and a side of zero length one point).
///
/// ```
/// use rbf_far::FarFieldSettings;
/// let s = FarFieldSettings::default();
/// assert_eq!(s.grid_sizes(8, &[0.0, 0.0, 0.0], &[1.0, 1.0, 0.0]), [8, 8, 1]);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FarFieldSettings {
    /// Chebyshev points along a cluster's longest side.
    pub order: usize,
    /// The separation ratio θ: side over distance.
    pub theta: f64,
    /// Most centres in a leaf of the source tree.
    pub leaf: usize,
    /// Most targets in a leaf of the target tree (targets in a leaf share one interaction list).
    pub target_leaf: usize,
}

impl Default for FarFieldSettings {
    fn default() -> Self {
        Self {
            order: 8,
            theta: 0.5,
            leaf: 64,
            target_leaf: 512,
        }
    }
}

impl FarFieldSettings {
    /// Chebyshev points along the longest side of a cluster whose longest side is `side`, in a
    /// tree whose root's is `root_side`.
    ///
    /// A cluster's proxies err like φ at the distance they are seen from (for r³, the side
    /// cubed, since the distance is side/θ) times ρ⁻ⁿ, with ρ the Bernstein ellipse's
    /// parameter of a singularity s/θ from a box of side s (x₀ + √(x₀² − 1), x₀ = 1 + 2/θ).
    /// The root gets `order` points; every smaller cluster as few as keep its error at the
    /// root's: fewer by 3 ln(root side / side) / ln ρ. (Scaling by the cluster's count of
    /// centres too was measured and rejected: weights cancel within a cluster, so large
    /// clusters err far less than their count says, and small ones were starved.)
    ///
    /// ```
    /// use rbf_far::FarFieldSettings;
    /// let s = FarFieldSettings { order: 12, ..FarFieldSettings::default() };
    /// assert_eq!(s.order_for(1.0, 1.0), 12);
    /// assert!(s.order_for(1.0, 0.01) < 12);
    /// assert!(s.order_for(1.0, 1e-9) >= 2);
    /// ```
    pub fn order_for(&self, root_side: f64, side: f64) -> usize {
        // Interpolation takes two points at least, whatever was asked.
        let order = self.order.max(2);
        let x0 = 1.0 + 2.0 / self.theta;
        let rho = x0 + (x0 * x0 - 1.0).sqrt();
        let ratio = (root_side / side).powi(3);
        if !(ratio.is_finite() && ratio >= 1.0) {
            return order;
        }
        let fewer = ratio.ln() / rho.ln();
        ((order as f64 - fewer).ceil() as usize).clamp(2, order)
    }

    /// Chebyshev points along each side of the box [lo, hi].
    ///
    /// Interpolation along a side of length t, seen from distance s/θ, converges like (θt/4s)ⁿ
    /// (the Bernstein ellipse of a singularity that far), so n = order·ln(θ/4)/ln(θt/4s) points
    /// give the error of `order` points along the longest side.
    pub fn grid_sizes<const D: usize>(
        &self,
        order: usize,
        lo: &[f64; D],
        hi: &[f64; D],
    ) -> [usize; D] {
        let longest = (0..D).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
        let reference = (0.25 * self.theta).ln();
        core::array::from_fn(|d| {
            let ratio = (hi[d] - lo[d]) / longest;
            if !(ratio > 1e-12) {
                1
            } else {
                let n = order as f64 * reference / (0.25 * self.theta * ratio).ln();
                (n.ceil() as usize).clamp(2, order.max(2))
            }
        })
    }
}
