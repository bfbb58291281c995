//! Chebyshev–Lobatto points on an interval and their Lagrange basis in barycentric form
//! (Berrut & Trefethen, "Barycentric Lagrange interpolation", SIAM Review 46(3), 2004).

use core::f64::consts::PI;

/// `n` Chebyshev points of the second kind on [lo, hi] (both ends included, from hi down to
/// lo), or the midpoint alone when `n == 1`.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    points: Vec<f64>,
}

impl Axis {
    /// The points; `n` is at least 1.
    pub fn new(lo: f64, hi: f64, n: usize) -> Self {
        let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
        let points = if n <= 1 {
            vec![mid]
        } else {
            (0..n)
                .map(|k| mid + half * (PI * k as f64 / (n - 1) as f64).cos())
                .collect()
        };
        Self { points }
    }

    /// The interpolation points.
    pub fn points(&self) -> &[f64] {
        &self.points
    }

    /// ℓₖ(x) for every k, written to `out` (of the axis's length): the Lagrange basis, so that
    /// Σₖ ℓₖ(x) g(xₖ) interpolates g. Exact (a unit vector) at the points themselves.
    pub fn basis(&self, x: f64, out: &mut [f64]) {
        let n = self.points.len();
        if n == 1 {
            out[0] = 1.0;
            return;
        }
        if let Some(k) = self.points.iter().position(|&p| p == x) {
            out.fill(0.0);
            out[k] = 1.0;
            return;
        }
        let mut sum = 0.0;
        for (k, (o, &p)) in out.iter_mut().zip(&self.points).enumerate() {
            let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
            let end = if k == 0 || k == n - 1 { 0.5 } else { 1.0 };
            *o = sign * end / (x - p);
            sum += *o;
        }
        for o in out.iter_mut() {
            *o /= sum;
        }
    }

    /// The matrix B (row-major, `at`'s length × this axis's length) with B[c][a] = ℓₐ(x_c), x_c
    /// the points of `at`: it reads values on this axis's points off at `at`'s points.
    pub fn basis_rows(&self, at: &Axis) -> Vec<f64> {
        let n = self.points.len();
        let mut b = vec![0.0; at.points.len() * n];
        for (row, &x) in b.chunks_exact_mut(n).zip(&at.points) {
            self.basis(x, row);
        }
        b
    }

    /// The matrix A (row-major, this axis's length × `from`'s length) with A[a][i] = ℓₐ(xᵢ),
    /// xᵢ the points of `from`: it moves charges on `from`'s points to this axis's points.
    pub fn matrix_from(&self, from: &Axis) -> Vec<f64> {
        let (m, n) = (self.points.len(), from.points.len());
        let mut a = vec![0.0; m * n];
        let mut column = vec![0.0; m];
        for (i, &x) in from.points.iter().enumerate() {
            self.basis(x, &mut column);
            for (r, &v) in column.iter().enumerate() {
                a[r * n + i] = v;
            }
        }
        a
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolates_polynomials_of_degree_below_the_points_exactly() {
        let axis = Axis::new(-0.3, 1.7, 6);
        let g = |x: f64| 1.0 - 2.0 * x + 0.5 * x.powi(3) - x.powi(5);
        let mut l = vec![0.0; 6];
        for x in [-0.3, 0.1, 0.77, 1.7, 2.5] {
            axis.basis(x, &mut l);
            let v: f64 = l.iter().zip(axis.points()).map(|(l, &p)| l * g(p)).sum();
            assert!(
                (v - g(x)).abs() < 1e-11 * (1.0 + g(x).abs()),
                "{v} {}",
                g(x)
            );
        }
    }

    #[test]
    fn one_point_is_the_midpoint_with_basis_one() {
        let axis = Axis::new(2.0, 4.0, 1);
        assert_eq!(axis.points(), &[3.0]);
        let mut l = [0.0];
        axis.basis(10.0, &mut l);
        assert_eq!(l, [1.0]);
    }
}
