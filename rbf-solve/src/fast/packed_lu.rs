//! An LU factorization with partial pivoting kept in one matrix (L strictly below the diagonal,
//! U on and above it) and its row permutation: half the memory of faer's `PartialPivLu`, which
//! keeps L and U apart. The preconditioner holds one per subdomain, so this halves its memory.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::perm::PermRef;
use faer::{Mat, MatMut, Par};

/// P A = L U, packed.
pub(crate) struct PackedLu {
    lu: Mat<f64>,
    forward: Vec<usize>,
    backward: Vec<usize>,
}

impl PackedLu {
    /// Factors `matrix` in place (`par`: the parallelism of the factorization).
    pub(crate) fn new(matrix: Mat<f64>, par: Par) -> Self {
        let mut lu = matrix;
        let n = lu.nrows();
        let (mut forward, mut backward) = (vec![0usize; n], vec![0usize; n]);
        let mut scratch = MemBuffer::new(factor::lu_in_place_scratch::<usize, f64>(
            n,
            n,
            par,
            Default::default(),
        ));
        factor::lu_in_place(
            lu.as_mut(),
            &mut forward,
            &mut backward,
            par,
            MemStack::new(&mut scratch),
            Default::default(),
        );
        Self {
            lu,
            forward,
            backward,
        }
    }

    /// rhs ← A⁻¹ rhs.
    pub(crate) fn solve_in_place(&self, rhs: MatMut<'_, f64>) {
        let n = self.lu.nrows();
        let mut scratch = MemBuffer::new(solve::solve_in_place_scratch::<usize, f64>(
            n,
            rhs.ncols(),
            Par::Seq,
        ));
        // The permutation and its inverse were made together by the factorization.
        let perm = PermRef::new_checked(&self.forward, &self.backward, n);
        solve::solve_in_place(
            self.lu.as_ref(),
            self.lu.as_ref(),
            perm,
            rhs,
            Par::Seq,
            MemStack::new(&mut scratch),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_like_the_matrix_it_factored() {
        let n = 37;
        let a = Mat::<f64>::from_fn(n, n, |i, j| {
            let x = (i * 7 + j * 13) % 11;
            x as f64 - 5.0 + if i == j { 0.5 } else { 0.0 }
        });
        let b = Mat::<f64>::from_fn(n, 2, |i, j| (i + 3 * j) as f64 - 10.0);
        let lu = PackedLu::new(a.clone(), Par::Seq);
        let mut x = b.clone();
        lu.solve_in_place(x.as_mut());
        let r = &a * &x - &b;
        let worst = (0..n)
            .flat_map(|i| (0..2).map(move |j| (i, j)))
            .map(|(i, j)| r[(i, j)].abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-9, "{worst}");
    }
}
