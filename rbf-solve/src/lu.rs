//! The last resort: partial-pivot LU of the whole saddle-point system.

use faer::linalg::solvers::{PartialPivLu, Solve};
use faer::{Mat, MatRef};
use rbf_core::{FitError, System};

use crate::memory::{check_fits, filled_matrix};

/// LU of [Φ+Λ, P; Pᵀ, 0] (normalized).
pub(crate) struct FullLu {
    k: usize,
    lu: PartialPivLu<f64>,
    pub(crate) norm1: f64,
}

impl FullLu {
    pub(crate) fn new<const D: usize>(system: &System<D>) -> Result<Self, FitError> {
        let k = system.rows();
        let n = system.size();
        check_fits(n, 2)?;
        let data = filled_matrix(n, n, |j, col| system.system_column(j, col))?;
        let norm1 = data
            .chunks_exact(n)
            .map(|c| c.iter().map(|v| v.abs()).sum::<f64>())
            .fold(0.0, f64::max);
        let lu = PartialPivLu::new(MatRef::from_column_major_slice(&data, n, n));
        Ok(Self { k, lu, norm1 })
    }

    pub(crate) fn solve(&self, h: &[f64], g: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let n = h.len() + g.len();
        let mut rhs =
            Mat::<f64>::from_fn(n, 1, |i, _| if i < self.k { h[i] } else { g[i - self.k] });
        self.lu.solve_in_place(rhs.as_mut());
        let x: Vec<f64> = (0..n).map(|i| rhs[(i, 0)]).collect();
        (x[..self.k].to_vec(), x[self.k..].to_vec())
    }
}
