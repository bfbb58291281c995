//! The kernel block projected onto polynomial-free weights, factored.
//!
//! With P = Q [R; 0] and B = Qᵀ(Φ + Λ)Q, the constraint Pᵀw = 0 says w = Q [0; u], and the
//! system reduces to B₂₂ u = (Qᵀh)₂, where σB₂₂ (σ the kernel's sign of definiteness) is
//! positive definite whenever the kernel block is conditionally definite: Cholesky solves it
//! in a third of the flops of LU of the whole system. The general right-hand side (h, g) used
//! by refinement is handled too.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{LltError, cholesky_in_place, cholesky_in_place_scratch};
use faer::linalg::matmul::matmul;
use faer::linalg::solvers::{Lblt, Solve};
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{Accum, Mat, MatMut, MatRef, Par, Side};
use rayon::prelude::*;
use rbf_core::{FitError, System};

use crate::householder::Reflector;
use crate::memory::{check_fits, filled_matrix};

/// How the projected block was factored.
enum Factor {
    /// The lower triangle of B₂₂ in `data` holds L with σB₂₂ = LLᵀ.
    Cholesky,
    /// Bunch–Kaufman LBLᵀ of B₂₂ (a separate copy).
    Lblt(Lblt<f64>),
}

/// A factored projected system, ready to solve any right-hand side of the full system.
pub(crate) struct Projected {
    k: usize,
    m: usize,
    sign: f64,
    /// B = Qᵀ(Φ + Λ)Q, column-major K × K; see [`Factor`] for what the B₂₂ block holds.
    data: Vec<f64>,
    reflector: Reflector,
    factor: Factor,
    /// max over columns of Σᵢ |Mᵢⱼ| for the whole normalized system M.
    pub(crate) norm1: f64,
}

/// Which factorization to attempt first.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Attempt {
    Cholesky,
    Lblt,
}

impl Projected {
    /// Assembles, projects and factors. `Err(None)` means Cholesky found the block indefinite
    /// (the caller may retry with LBLᵀ).
    pub(crate) fn new<const D: usize>(
        system: &System<D>,
        attempt: Attempt,
        par: Par,
    ) -> Result<Self, Option<FitError>> {
        let k = system.rows();
        let m = D + 1;
        let extra = if attempt == Attempt::Lblt { 2 } else { 1 };
        check_fits(k, extra).map_err(Some)?;
        let mut data =
            filled_matrix(k, k, |j, col| system.kernel_column(j, 0..k, col)).map_err(Some)?;
        let col_sums: Vec<f64> = data
            .par_chunks(k)
            .enumerate()
            .map(|(j, col)| {
                let poly = 1.0
                    + system
                        .polynomial_row(j)
                        .iter()
                        .map(|v| v.abs())
                        .sum::<f64>();
                col.iter().map(|v| v.abs()).sum::<f64>() + poly
            })
            .collect();
        let poly_cols = (0..m).map(|c| {
            (0..k)
                .map(|i| {
                    if c == 0 {
                        1.0
                    } else {
                        system.polynomial_row(i)[c - 1].abs()
                    }
                })
                .sum::<f64>()
        });
        let norm1 = col_sums
            .iter()
            .copied()
            .chain(poly_cols)
            .fold(0.0, f64::max);

        let mut p = vec![0.0; k * m];
        for i in 0..k {
            p[i] = 1.0;
            for (d, x) in system.polynomial_row(i).iter().enumerate() {
                p[(d + 1) * k + i] = *x;
            }
        }
        let reflector = Reflector::new(p, k, m);
        project(&mut data, k, m, &reflector, par);

        let sign = system.kernel().definiteness();
        let n2 = k - m;
        let mut a = MatMut::from_column_major_slice_mut(&mut data, k, k);
        let mut b22 = a.rb_mut().submatrix_mut(m, m, n2, n2);
        let factor = match attempt {
            Attempt::Cholesky => {
                if sign < 0.0 {
                    for j in 0..n2 {
                        for i in j..n2 {
                            b22[(i, j)] = -b22[(i, j)];
                        }
                    }
                }
                let mut buf = MemBuffer::new(cholesky_in_place_scratch::<f64>(
                    n2,
                    par,
                    Default::default(),
                ));
                let stack = MemStack::new(&mut buf);
                match cholesky_in_place(b22, Default::default(), par, stack, Default::default()) {
                    Ok(_) => Factor::Cholesky,
                    Err(LltError::NonPositivePivot { .. }) => return Err(None),
                }
            }
            Attempt::Lblt => Factor::Lblt(Lblt::new(b22.rb(), Side::Lower)),
        };
        Ok(Self {
            k,
            m,
            sign,
            data,
            reflector,
            factor,
            norm1,
        })
    }

    /// Solves the full normalized system [Φ+Λ, P; Pᵀ, 0] [w; p] = [h; g].
    pub(crate) fn solve(&self, h: &[f64], g: &[f64], par: Par) -> (Vec<f64>, Vec<f64>) {
        let (k, m) = (self.k, self.m);
        let b = MatRef::from_column_major_slice(&self.data, k, k);
        let mut c = h.to_vec();
        self.reflector.apply_qt(&mut c);
        // a = R⁻ᵀ g.
        let mut a = vec![0.0; m];
        for i in 0..m {
            let s: f64 = (0..i).map(|j| self.reflector.r(j, i) * a[j]).sum();
            a[i] = (g[i] - s) / self.reflector.r(i, i);
        }
        // σ B₂₂ u = σ (c₂ − B₂₁ a).
        let mut rhs = Mat::<f64>::zeros(k - m, 1);
        for i in 0..k - m {
            let s: f64 = (0..m).map(|j| b[(m + i, j)] * a[j]).sum();
            rhs[(i, 0)] = c[m + i] - s;
        }
        match &self.factor {
            Factor::Cholesky => {
                if self.sign < 0.0 {
                    for i in 0..k - m {
                        rhs[(i, 0)] = -rhs[(i, 0)];
                    }
                }
                let l = b.submatrix(m, m, k - m, k - m);
                solve_lower_triangular_in_place(l, rhs.as_mut(), par);
                solve_upper_triangular_in_place(l.transpose(), rhs.as_mut(), par);
            }
            Factor::Lblt(f) => f.solve_in_place(rhs.as_mut()),
        }
        let u: Vec<f64> = (0..k - m).map(|i| rhs[(i, 0)]).collect();
        // R p = c₁ − B₁₁ a − B₁₂ u, with B₁₂ = B₂₁ᵀ.
        let mut top = vec![0.0; m];
        for i in 0..m {
            let col = &self.data[i * k + m..(i + 1) * k];
            let b12u: f64 = col.iter().zip(&u).map(|(x, y)| x * y).sum();
            let b11a: f64 = (0..m).map(|j| b[(i.max(j), i.min(j))] * a[j]).sum();
            top[i] = c[i] - b11a - b12u;
        }
        let mut p = vec![0.0; m];
        for i in (0..m).rev() {
            let s: f64 = (i + 1..m).map(|j| self.reflector.r(i, j) * p[j]).sum();
            p[i] = (top[i] - s) / self.reflector.r(i, i);
        }
        let mut w: Vec<f64> = a.into_iter().chain(u).collect();
        self.reflector.apply_q(&mut w);
        (w, p)
    }
}

/// data ← Qᵀ data Q for symmetric data (K × K), Q = I − V T Vᵀ, in two passes over the matrix:
/// Y = A V, then A ← A − V Wᵀ − W Vᵀ with W = Y T − ½ V (Tᵀ Vᵀ Y T).
fn project(data: &mut [f64], k: usize, m: usize, q: &Reflector, par: Par) {
    let v = MatRef::from_column_major_slice(q.v(), k, m);
    let t = Mat::<f64>::from_fn(m, m, |i, j| q.t()[i * m + j]);
    let mut a = MatMut::from_column_major_slice_mut(data, k, k);
    let mut y = Mat::<f64>::zeros(k, m);
    matmul(y.as_mut(), Accum::Replace, a.rb(), v, 1.0, par);
    let mut z = Mat::<f64>::zeros(m, m);
    matmul(
        z.as_mut(),
        Accum::Replace,
        v.transpose(),
        y.as_ref(),
        1.0,
        Par::Seq,
    );
    let mut zt = Mat::<f64>::zeros(m, m);
    matmul(
        zt.as_mut(),
        Accum::Replace,
        z.as_ref(),
        t.as_ref(),
        1.0,
        Par::Seq,
    );
    let mut mm = Mat::<f64>::zeros(m, m);
    matmul(
        mm.as_mut(),
        Accum::Replace,
        t.transpose(),
        zt.as_ref(),
        1.0,
        Par::Seq,
    );
    // left = [V W], right = [W V], so left · rightᵀ = V Wᵀ + W Vᵀ.
    let mut left = Mat::<f64>::zeros(k, 2 * m);
    let mut right = Mat::<f64>::zeros(k, 2 * m);
    {
        let mut w = left.as_mut().submatrix_mut(0, m, k, m);
        matmul(
            w.rb_mut(),
            Accum::Replace,
            y.as_ref(),
            t.as_ref(),
            1.0,
            Par::Seq,
        );
        matmul(w.rb_mut(), Accum::Add, v, mm.as_ref(), -0.5, Par::Seq);
    }
    for j in 0..m {
        for i in 0..k {
            left[(i, j)] = v[(i, j)];
            right[(i, m + j)] = v[(i, j)];
            right[(i, j)] = left[(i, m + j)];
        }
    }
    matmul(
        a.rb_mut(),
        Accum::Add,
        left.as_ref(),
        right.transpose(),
        -1.0,
        par,
    );
}
