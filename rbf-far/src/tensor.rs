//! Tensor grids of Chebyshev points: their points, charges spread onto them, and values moved
//! between grids or read off at a point, one axis at a time.

use crate::chebyshev::Axis;

/// The grid's number of points.
pub(crate) fn grid_len<const D: usize>(axes: &[Axis; D]) -> usize {
    axes.iter().map(|a| a.points().len()).product()
}

/// The grid's points, row-major (the last axis fastest).
pub(crate) fn grid_points<const D: usize>(axes: &[Axis; D]) -> Vec<[f64; D]> {
    let mut out = vec![[0.0; D]];
    for d in 0..D {
        let mut next = Vec::with_capacity(out.len() * axes[d].points().len());
        for p in &out {
            for &x in axes[d].points() {
                let mut q = *p;
                q[d] = x;
                next.push(q);
            }
        }
        out = next;
    }
    out
}

/// q += w · basis[0] ⊗ basis[1] ⊗ … (row-major).
pub(crate) fn add_outer<const D: usize>(basis: &[Vec<f64>; D], w: f64, q: &mut [f64]) {
    let mut t = vec![w];
    for b in basis {
        let mut next = Vec::with_capacity(t.len() * b.len());
        for &x in &t {
            next.extend(b.iter().map(|&y| x * y));
        }
        t = next;
    }
    for (a, b) in q.iter_mut().zip(t) {
        *a += b;
    }
}

/// Charges on the grid `from` moved to the grid `to` (a parent's): each charge spread by `to`'s
/// Lagrange basis at its point, one axis at a time.
pub(crate) fn move_charges<const D: usize>(
    to: &[Axis; D],
    from: &[Axis; D],
    q: &[f64],
) -> Vec<f64> {
    let matrices: [Vec<f64>; D] = core::array::from_fn(|d| to[d].matrix_from(&from[d]));
    apply_by_axis(&matrices, to, from, q)
}

/// Values on the grid `from` (a parent's) interpolated at the points of the grid `to`.
pub(crate) fn interpolate_values<const D: usize>(
    to: &[Axis; D],
    from: &[Axis; D],
    values: &[f64],
) -> Vec<f64> {
    let matrices: [Vec<f64>; D] = core::array::from_fn(|d| from[d].basis_rows(&to[d]));
    apply_by_axis(&matrices, to, from, values)
}

/// t ← A_d t along every axis d, A_d of `to[d]`'s length × `from[d]`'s (row-major).
fn apply_by_axis<const D: usize>(
    matrices: &[Vec<f64>; D],
    to: &[Axis; D],
    from: &[Axis; D],
    q: &[f64],
) -> Vec<f64> {
    let mut dims: [usize; D] = core::array::from_fn(|d| from[d].points().len());
    let mut t = q.to_vec();
    for d in 0..D {
        let a = &matrices[d];
        let (m, n) = (to[d].points().len(), dims[d]);
        let pre: usize = dims[..d].iter().product();
        let post: usize = dims[d + 1..].iter().product();
        let mut next = vec![0.0; pre * m * post];
        for p in 0..pre {
            for r in 0..m {
                let out = &mut next[(p * m + r) * post..(p * m + r + 1) * post];
                for i in 0..n {
                    let coefficient = a[r * n + i];
                    if coefficient == 0.0 {
                        continue;
                    }
                    let src = &t[(p * n + i) * post..(p * n + i + 1) * post];
                    for (o, s) in out.iter_mut().zip(src) {
                        *o += coefficient * s;
                    }
                }
            }
        }
        dims[d] = m;
        t = next;
    }
    t
}

/// Σₖ Πd basis[d][k_d] · values[k] (row-major): the grid's interpolant where `basis` was taken;
/// `scratch` is reused between calls.
pub(crate) fn contract<const D: usize>(
    basis: &[Vec<f64>; D],
    values: &[f64],
    scratch: &mut Vec<f64>,
) -> f64 {
    scratch.clear();
    scratch.extend_from_slice(values);
    for b in basis.iter().rev() {
        let n = b.len();
        let m = scratch.len() / n;
        // In place: entry j is written after entries j·n … j·n + n − 1 were read, and later
        // entries read from j·n on.
        for j in 0..m {
            let s: f64 = b
                .iter()
                .zip(&scratch[j * n..j * n + n])
                .map(|(x, y)| x * y)
                .sum();
            scratch[j] = s;
        }
        scratch.truncate(m);
    }
    scratch.first().copied().unwrap_or(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axes(lo: [f64; 3], hi: [f64; 3], n: [usize; 3]) -> [Axis; 3] {
        core::array::from_fn(|d| Axis::new(lo[d], hi[d], n[d]))
    }

    /// A polynomial of degree below every grid's size per axis.
    fn g(p: &[f64; 3]) -> f64 {
        1.0 + p[0] - 2.0 * p[1] * p[2] + 0.5 * p[0] * p[0] * p[2] - p[1].powi(3)
    }

    #[test]
    fn values_interpolated_to_a_child_grid_and_read_at_a_point_are_exact_for_polynomials() {
        let parent = axes([-1.0, 0.0, 2.0], [1.0, 3.0, 2.5], [5, 6, 4]);
        let child = axes([-0.5, 1.0, 2.1], [0.2, 2.0, 2.4], [4, 4, 3]);
        let at_parent: Vec<f64> = grid_points(&parent).iter().map(g).collect();
        let at_child = interpolate_values(&child, &parent, &at_parent);
        for (p, v) in grid_points(&child).iter().zip(&at_child) {
            assert!((v - g(p)).abs() < 1e-12, "{v} {}", g(p));
        }
        let x = [0.1, 1.3, 2.2];
        let basis: [Vec<f64>; 3] = core::array::from_fn(|d| {
            let mut b = vec![0.0; child[d].points().len()];
            child[d].basis(x[d], &mut b);
            b
        });
        let v = contract(&basis, &at_child, &mut Vec::new());
        assert!((v - g(&x)).abs() < 1e-12);
    }

    #[test]
    fn charges_moved_to_a_parent_keep_their_moments() {
        let parent = axes([-1.0, 0.0, 2.0], [1.0, 3.0, 2.5], [5, 6, 4]);
        let child = axes([-0.5, 1.0, 2.1], [0.2, 2.0, 2.4], [3, 3, 3]);
        let q: Vec<f64> = (0..27).map(|i| (i as f64 * 0.37).sin()).collect();
        let moved = move_charges(&parent, &child, &q);
        // Σ q g over the points is kept for every g the parent's grid interpolates exactly.
        let before: f64 = grid_points(&child)
            .iter()
            .zip(&q)
            .map(|(p, q)| q * g(p))
            .sum();
        let after: f64 = grid_points(&parent)
            .iter()
            .zip(&moved)
            .map(|(p, q)| q * g(p))
            .sum();
        assert!((before - after).abs() < 1e-12, "{before} {after}");
    }
}
