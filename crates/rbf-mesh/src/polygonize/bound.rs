//! Whether the surface can cross a box: a Taylor bound on f over the box from the kernel's
//! derivatives, so that the grid polygonizer skips empty space without sampling it.

use rbf_core::{InterpolantView, Kernel};

/// Bounds on the kernel's slope |φ′| and Hessian norm ‖∇²φ(|x|)‖ for distances in [lo, hi];
/// infinite where they do not exist.
fn kernel_bounds(kernel: Kernel, lo: f64, hi: f64) -> (f64, f64) {
    match kernel {
        // φ′ = 3r², Hessian eigenvalues 6r and 3r.
        Kernel::Cubic => (3.0 * hi * hi, 6.0 * hi),
        // φ′ = 1, Hessian eigenvalues 0 and 1/r.
        Kernel::Linear => (1.0, if lo > 0.0 { 1.0 / lo } else { f64::INFINITY }),
        // φ′ = r(2 ln r + 1), Hessian eigenvalues 2 ln r + 3 and 2 ln r + 1.
        _ => {
            if lo <= 0.0 {
                let slope = hi * (2.0 * hi.ln().abs() + 1.0) + 1.0;
                return (slope, f64::INFINITY);
            }
            let l = lo.ln().abs().max(hi.ln().abs());
            (hi * (2.0 * l + 1.0), 2.0 * l + 3.0)
        }
    }
}

/// True when f has one sign (strictly, with f > 0 or f ≤ 0 throughout) in the ball of radius
/// `radius` around `centre`, proved from f(c), ∇f(c) and bounds on the kernel's derivatives.
pub(crate) fn one_sign_in_ball(
    f: &InterpolantView<'_, f64, 3>,
    centre: [f64; 3],
    radius: f64,
) -> bool {
    let (v, g) = f.value_and_gradient(&centre);
    let kernel = f.kernel();
    let mut slope_sum = 0.0;
    let mut curvature_sum = 0.0;
    for (c, w) in f.centres().iter().zip(f.weights()) {
        let d = crate::mesh::norm(crate::mesh::sub(centre, *c));
        let (s, h) = kernel_bounds(kernel, (d - radius).max(0.0), d + radius);
        slope_sum += w.abs() * s;
        curvature_sum += w.abs() * h;
    }
    // Taylor with a second-order remainder where the Hessian is bounded, first order otherwise.
    let change = if curvature_sum.is_finite() {
        crate::mesh::norm(g) * radius + 0.5 * curvature_sum * radius * radius
    } else {
        (slope_sum + crate::mesh::norm(f.linear())) * radius
    };
    // A little slack for the rounding of f itself.
    v.abs() > change * (1.0 + 1e-9) + 1e-12 * v.abs().max(1e-300)
}
