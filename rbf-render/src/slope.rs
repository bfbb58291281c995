//! How fast a model can change, for sizing the tracer's steps: per-cell estimates from the
//! gradient at a cell's corners and centre, the sampled estimate of Turk & O'Brien (2002), and
//! the weights' spread that proves steps for the r³ kernel.

use rbf_core::vec3::{Vec3, norm, sub};
use rbf_core::{InterpolantView, Kernel, ScalarField};

/// What bounds a model's change around a point.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Slope {
    /// r³: |∇f| at the point, Σ|wⱼ| |p − cⱼ| and Σ|wⱼ|.
    Cubic {
        /// |∇f| at the point.
        gradient: f64,
        /// Σ|wⱼ| |p − cⱼ|.
        spread: f64,
        /// Σ|wⱼ|.
        total: f64,
    },
    /// A bound L on |∇f| around the point: f moves by at most L·s within distance s.
    Constant(f64),
}

/// Σ|wⱼ| |x − cⱼ| as an interpolant with φ = r, and Σ|wⱼ|: the curvature bound of an r³ model.
pub(crate) struct Spread {
    centres: Vec<Vec3>,
    weights: Vec<f64>,
    /// Σ|wⱼ|.
    pub(crate) total: f64,
}

impl Spread {
    pub(crate) fn new(f: &InterpolantView<'_, f64, 3>) -> Self {
        let weights: Vec<f64> = f.weights().iter().map(|w| w.abs()).collect();
        Self {
            centres: f.centres().to_vec(),
            total: weights.iter().sum(),
            weights,
        }
    }

    pub(crate) fn view(&self) -> InterpolantView<'_, f64, 3> {
        InterpolantView::new(Kernel::Linear, &self.centres, &self.weights, 0.0, [0.0; 3])
            .unwrap_or_else(|_| unreachable!("as many weights as centres"))
    }
}

/// Per cell: 1.5 times the largest |∇f| at its eight corners and its centre; and f at its
/// centre.
pub(crate) fn estimate_cells(
    f: &dyn ScalarField<3>,
    lo: Vec3,
    cell: Vec3,
    n: [usize; 3],
) -> (Vec<f64>, Vec<f64>) {
    let m = [n[0] + 1, n[1] + 1, n[2] + 1];
    let corners: Vec<Vec3> = (0..m[0] * m[1] * m[2])
        .map(|i| {
            let c = [i / (m[1] * m[2]), (i / m[2]) % m[1], i % m[2]];
            core::array::from_fn(|d| lo[d] + c[d] as f64 * cell[d])
        })
        .collect();
    let centres: Vec<Vec3> = (0..n[0] * n[1] * n[2])
        .map(|i| {
            let c = [i / (n[1] * n[2]), (i / n[2]) % n[1], i % n[2]];
            core::array::from_fn(|d| lo[d] + (c[d] as f64 + 0.5) * cell[d])
        })
        .collect();
    let evaluate = |points: &[Vec3]| -> (Vec<f64>, Vec<f64>) {
        let mut values = vec![0.0; points.len()];
        let mut gradients = vec![[0.0; 3]; points.len()];
        // Equal lengths by construction.
        let _ = f.field_values_and_gradients(points, &mut values, &mut gradients);
        (values, gradients.into_iter().map(norm).collect())
    };
    let (_, corner_slopes) = evaluate(&corners);
    let (centre_values, centre_slopes) = evaluate(&centres);
    let slopes = (0..centres.len())
        .map(|i| {
            let c = [i / (n[1] * n[2]), (i / n[2]) % n[1], i % n[2]];
            let mut most = centre_slopes[i];
            for k in 0..8 {
                let q = [c[0] + (k & 1), c[1] + ((k >> 1) & 1), c[2] + (k >> 2)];
                most = most.max(corner_slopes[(q[0] * m[1] + q[1]) * m[2] + q[2]]);
            }
            1.5 * most
        })
        .collect();
    (slopes, centre_values)
}

/// The paper's estimate: the largest |∇f| over `count` points spread through the box (a
/// low-discrepancy sequence, so that the result does not depend on a random seed).
pub(crate) fn sampled_slope(
    f: &InterpolantView<'_, f64, 3>,
    lo: Vec3,
    hi: Vec3,
    count: usize,
) -> f64 {
    let size = sub(hi, lo);
    (0..count.max(1))
        .map(|i| {
            // Additive recurrence with the plastic number's powers (R3 sequence).
            let g = 1.220_744_084_605_759_5_f64;
            let alpha = [1.0 / g, 1.0 / (g * g), 1.0 / (g * g * g)];
            let p: Vec3 = core::array::from_fn(|d| {
                lo[d] + size[d] * (0.5 + alpha[d] * (i + 1) as f64).fract()
            });
            norm(f.gradient(&p))
        })
        .fold(0.0, f64::max)
}
