//! Flexible GMRES (Saad, "A flexible inner-outer preconditioned GMRES algorithm", SIAM J. Sci.
//! Comput. 14(2), 1993) with restarts: right preconditioning, modified Gram–Schmidt, Givens
//! rotations. The caller judges convergence by the true residual at each restart.

use rayon::prelude::*;

/// What one run of the iteration needs besides the operator and the preconditioner.
pub(crate) struct GmresLimits {
    /// Krylov vectors kept before a restart.
    pub(crate) restart: usize,
    /// Most operator applications in all.
    pub(crate) max_iterations: usize,
}

/// The caller's verdict on an iterate x, given its true residual and the iterations so far.
pub(crate) type Judge<'a> = dyn FnMut(&[f64], &[f64], usize) -> Acceptance + 'a;

/// The end of a run.
pub(crate) struct GmresEnd {
    pub(crate) x: Vec<f64>,
    pub(crate) iterations: usize,
    /// Whether `accept` took the last true residual.
    pub(crate) converged: bool,
}

/// Solves A x = b from x = 0.
///
/// - `apply(v, out)`: out = A v;
/// - `precondition(v)`: an approximation of A⁻¹ v (it may change between calls);
/// - `accept(x, r, iterations)`: given the iterate, its true residual r = b − A x and the
///   iterations so far, says whether it is
///   good enough; asked at every restart and whenever the recurrence's residual estimate falls
///   below `target(iteration)`, a 2-norm the caller may tighten after a refused check;
/// - `progress(iteration, estimate)`: after every iteration.
pub(crate) fn fgmres(
    b: &[f64],
    limits: &GmresLimits,
    apply: &(dyn Fn(&[f64], &mut [f64]) + Sync),
    precondition: &(dyn Fn(&[f64]) -> Vec<f64> + Sync),
    accept: &mut Judge<'_>,
    progress: &mut dyn FnMut(usize, f64),
) -> GmresEnd {
    let n = b.len();
    let m = limits.restart.max(1);
    let mut x = vec![0.0; n];
    let mut r = b.to_vec();
    let mut iterations = 0;
    let mut scratch = vec![0.0; n];
    loop {
        let target = match accept(&x, &r, iterations) {
            Acceptance::Done => {
                return GmresEnd {
                    x,
                    iterations,
                    converged: true,
                };
            }
            Acceptance::Continue { target } => target,
            Acceptance::GiveUp => {
                return GmresEnd {
                    x,
                    iterations,
                    converged: false,
                };
            }
        };
        let beta = norm(&r);
        if iterations >= limits.max_iterations || !beta.is_finite() || beta == 0.0 {
            return GmresEnd {
                x,
                iterations,
                converged: false,
            };
        }
        // Arnoldi basis V, preconditioned directions Z, Hessenberg H (column-wise), rotations.
        let mut v: Vec<Vec<f64>> = vec![r.iter().map(|x| x / beta).collect()];
        let mut z: Vec<Vec<f64>> = Vec::with_capacity(m);
        let mut h: Vec<Vec<f64>> = Vec::with_capacity(m);
        let mut cs: Vec<(f64, f64)> = Vec::with_capacity(m);
        let mut s = vec![beta];
        for j in 0..m {
            let zj = precondition(&v[j]);
            apply(&zj, &mut scratch);
            z.push(zj);
            let mut w = scratch.clone();
            let mut col = vec![0.0; j + 2];
            for (i, vi) in v.iter().enumerate() {
                let dot = dot(&w, vi);
                col[i] = dot;
                axpy(-dot, vi, &mut w);
            }
            let wn = norm(&w);
            col[j + 1] = wn;
            for (i, &(c, sn)) in cs.iter().enumerate() {
                let (a, bb) = (col[i], col[i + 1]);
                col[i] = c * a + sn * bb;
                col[i + 1] = -sn * a + c * bb;
            }
            let (a, bb) = (col[j], col[j + 1]);
            let rho = a.hypot(bb);
            let (c, sn) = if rho == 0.0 {
                (1.0, 0.0)
            } else {
                (a / rho, bb / rho)
            };
            col[j] = rho;
            col[j + 1] = 0.0;
            cs.push((c, sn));
            let sj = s[j];
            s[j] = c * sj;
            s.push(-sn * sj);
            h.push(col);
            iterations += 1;
            let estimate = s[j + 1].abs();
            progress(iterations, estimate);
            let breakdown = wn <= 1e-14 * beta;
            if estimate <= target || breakdown || iterations >= limits.max_iterations || j + 1 == m
            {
                break;
            }
            v.push(w.iter().map(|x| x / wn).collect());
        }
        // y = H⁻¹ s by back substitution; x += Z y.
        let k = h.len();
        let mut y = vec![0.0; k];
        for i in (0..k).rev() {
            let mut t = s[i];
            for (jj, yj) in y.iter().enumerate().skip(i + 1) {
                t -= h[jj][i] * yj;
            }
            y[i] = if h[i][i] != 0.0 { t / h[i][i] } else { 0.0 };
        }
        for (zj, yj) in z.iter().zip(&y) {
            axpy(*yj, zj, &mut x);
        }
        apply(&x, &mut scratch);
        r.par_iter_mut()
            .zip(b.par_iter().zip(&scratch))
            .for_each(|(ri, (bi, ax))| *ri = bi - ax);
    }
}

/// What the caller says of an iterate.
pub(crate) enum Acceptance {
    Done,
    /// Go on; check again when the estimated 2-norm of the residual is below `target`.
    Continue {
        target: f64,
    },
    /// Stop: the iterate will not get better (rounding has the last word).
    GiveUp,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.par_chunks(4096)
        .zip(b.par_chunks(4096))
        .map(|(x, y)| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>())
        .sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

fn axpy(alpha: f64, x: &[f64], y: &mut [f64]) {
    y.par_chunks_mut(4096)
        .zip(x.par_chunks(4096))
        .for_each(|(yy, xx)| yy.iter_mut().zip(xx).for_each(|(a, b)| *a += alpha * b));
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A non-symmetric, diagonally dominant tridiagonal operator.
    fn apply(v: &[f64], out: &mut [f64]) {
        let n = v.len();
        for i in 0..n {
            let mut t = 4.0 * v[i];
            if i > 0 {
                t -= 1.0 * v[i - 1];
            }
            if i + 1 < n {
                t += 2.0 * v[i + 1];
            }
            out[i] = t;
        }
    }

    #[test]
    fn solves_a_nonsymmetric_system_through_restarts() {
        let n = 200;
        let b: Vec<f64> = (0..n).map(|i| ((i * 7) % 13) as f64 - 6.0).collect();
        let mut checks = 0;
        let end = fgmres(
            &b,
            &GmresLimits {
                restart: 5,
                max_iterations: 500,
            },
            &apply,
            &|v| v.iter().map(|x| x / 4.0).collect(),
            &mut |_, r, _| {
                checks += 1;
                if norm(r) < 1e-12 * norm(&b) {
                    Acceptance::Done
                } else {
                    Acceptance::Continue {
                        target: 1e-13 * norm(&b),
                    }
                }
            },
            &mut |_, _| {},
        );
        assert!(end.converged);
        assert!(checks > 2, "restarts happened");
        let mut ax = vec![0.0; n];
        apply(&end.x, &mut ax);
        let err = ax
            .iter()
            .zip(&b)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(err < 1e-10, "{err}");
    }

    #[test]
    fn stops_unconverged_at_the_iteration_cap() {
        let b = vec![1.0; 100];
        let end = fgmres(
            &b,
            &GmresLimits {
                restart: 3,
                max_iterations: 4,
            },
            &apply,
            &|v| v.to_vec(),
            &mut |_, _, _| Acceptance::Continue { target: 0.0 },
            &mut |_, _| {},
        );
        assert!(!end.converged);
        assert_eq!(end.iterations, 4);
    }
}
