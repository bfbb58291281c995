//! Estimating ‖M⁻¹‖₁ from a few solves (Hager 1984, Higham 1988), for condition estimates.

use alloc::vec;

/// Estimates ‖M⁻¹‖₁ of a symmetric n × n matrix M, given `solve` that overwrites its argument
/// b with M⁻¹b (returning false on failure). Costs at most five solves. Multiply by ‖M‖₁ for an
/// estimate of the condition number κ₁(M) (a lower bound, usually within a factor of 3).
/// Stops early when the estimate stops growing (usually after two rounds).
///
/// ```
/// // M = diag(1, 1e-3): ‖M⁻¹‖₁ = 1000.
/// let est = rbf_core::estimate_inverse_norm1(2, |b| {
///     b[1] *= 1e3;
///     true
/// });
/// assert_eq!(est, 1000.0);
/// ```
#[doc(hidden)]
pub fn estimate_inverse_norm1(n: usize, mut solve: impl FnMut(&mut [f64]) -> bool) -> f64 {
    if n == 0 {
        return 0.0;
    }
    let mut x = vec![1.0 / n as f64; n];
    let mut estimate = 0.0;
    let mut last_index = usize::MAX;
    for _ in 0..5 {
        let mut y = x.clone();
        if !solve(&mut y) {
            return f64::INFINITY;
        }
        estimate = y.iter().map(|v| v.abs()).sum::<f64>();
        if !estimate.is_finite() {
            return f64::INFINITY;
        }
        // z = M⁻ᵀ sign(y) = M⁻¹ sign(y) for symmetric M.
        let mut z: alloc::vec::Vec<f64> = y
            .iter()
            .map(|v| if *v >= 0.0 { 1.0 } else { -1.0 })
            .collect();
        if !solve(&mut z) {
            return f64::INFINITY;
        }
        let (j, zmax) = z.iter().enumerate().fold((0, 0.0_f64), |(bj, bm), (i, v)| {
            if v.abs() > bm { (i, v.abs()) } else { (bj, bm) }
        });
        let ztx: f64 = z.iter().zip(&x).map(|(a, b)| a * b).sum();
        if zmax <= ztx || j == last_index {
            break;
        }
        last_index = j;
        x.iter_mut().for_each(|v| *v = 0.0);
        x[j] = 1.0;
    }
    estimate
}
