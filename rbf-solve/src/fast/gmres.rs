//! Flexible GMRES (Saad, "A flexible inner-outer preconditioned GMRES algorithm", SIAM J. Sci.
//! Comput. 14(2), 1993) with restarts: right preconditioning, modified Gram–Schmidt, Givens
//! rotations. The caller judges convergence when the recurrence's residual vector (free from the
//! Arnoldi relation) says it may be met: first on that vector itself, which it may accept as it
//! is, then on the true residual, computed without leaving the cycle: a refused check costs one
//! product, not a restart (unless the caller asks for one, as when inexact products have taken
//! the recurrence off course).

use rayon::prelude::*;

/// What one run of the iteration needs besides the operator and the preconditioner.
pub(crate) struct GmresLimits {
    /// Krylov vectors kept before a restart.
    pub(crate) restart: usize,
    /// Most operator applications in all.
    pub(crate) max_iterations: usize,
}

/// out = A v, given what the product is for (see [`fgmres_from`]).
pub(crate) type Operator<'a> = dyn Fn(&[f64], &mut [f64], Option<f64>) + Sync + 'a;

/// The caller's verdict on an iterate x, given a residual of it (of the kind `Residual` says),
/// the iterations so far and what the recurrence claimed for it (the largest entry of its
/// residual vector).
pub(crate) type Judge<'a> = dyn FnMut(&[f64], &[f64], usize, f64, Residual) -> Acceptance + 'a;

/// What a residual given to the judge is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Residual {
    /// b − A x by a product of the operator.
    Measured,
    /// The recurrence's residual vector: b − A x up to what the cycle's products erred, with no
    /// product taken. The judge answers [`Acceptance::Done`] or [`Acceptance::Measure`].
    Recurrence,
}

/// The end of a run.
pub(crate) struct GmresEnd {
    pub(crate) x: Vec<f64>,
    pub(crate) iterations: usize,
    /// Whether `accept` took the last residual it was given.
    pub(crate) converged: bool,
}

/// Solves A x = b from `start` (where its residual b − A x, one product, is smaller than b's;
/// from x = 0 otherwise): a solve of rows added to a fitted system, from that fit's solution
/// with zeros for the new rows, has only the new rows' misses left to reduce.
///
/// - `apply(v, out, residual)`: out = A v. For a Krylov direction, `residual` is the largest
///   entry of the residual that the direction is to reduce (the recurrence's, before this
///   iteration): the product may be taken less accurately the smaller that is (inexact Krylov
///   methods: Simoncini & Szyld, SIAM J. Sci. Comput. 25(2), 2003). `None` asks for a true
///   residual, which must be as exact as the caller can make it;
/// - `precondition(v)`: an approximation of A⁻¹ v (it may change between calls);
/// - `accept(x, r, iterations, claimed, kind)`: given the iterate, a residual r of it, the
///   iterations so far and the recurrence's claim, says whether it is good enough; asked at
///   the start and at every restart with the true residual r = b − A x, and whenever the
///   largest entry of the recurrence's residual vector falls below the `target` it last
///   returned (lowered by how far the recurrence was from the truth at a refused check): first
///   with the recurrence's residual vector, which the judge may accept as it is (checked in
///   its own way, for example by direct sums at sampled rows: a product saved), then, unless it
///   did, with the true residual;
/// - `progress(iteration, estimate)`: after every iteration, with the largest entry of the
///   recurrence's residual vector.
pub(crate) fn fgmres_from(
    b: &[f64],
    start: Option<Vec<f64>>,
    limits: &GmresLimits,
    apply: &Operator<'_>,
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
    if let Some(start) = start.filter(|s| s.len() == n) {
        apply(&start, &mut scratch, None);
        let from: Vec<f64> = b.par_iter().zip(&scratch).map(|(bi, ax)| bi - ax).collect();
        if norm(&from) < norm(b) {
            (x, r) = (start, from);
        }
    }
    // The recurrence's residual over the true one at the last refused check (at most 1).
    let mut trust = 1.0_f64;
    let end = |x: Vec<f64>, iterations: usize, converged: bool| GmresEnd {
        x,
        iterations,
        converged,
    };
    let initial = r.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    let mut target = match accept(&x, &r, iterations, initial, Residual::Measured) {
        Acceptance::Done => return end(x, iterations, true),
        Acceptance::GiveUp => return end(x, iterations, false),
        // Not an answer to a measured residual: check at every iteration.
        Acceptance::Measure => f64::INFINITY,
        Acceptance::Continue { target }
        | Acceptance::Restart { target }
        | Acceptance::Remeasure { target } => target,
    };
    'cycles: loop {
        let beta = norm(&r);
        if iterations >= limits.max_iterations || !beta.is_finite() || beta == 0.0 {
            return end(x, iterations, false);
        }
        // Arnoldi basis V, preconditioned directions Z, Hessenberg H (column-wise, rotated
        // into R), rotations, and the rotated right-hand side s.
        let mut v: Vec<Vec<f64>> = vec![r.iter().map(|x| x / beta).collect()];
        let mut z: Vec<Vec<f64>> = Vec::with_capacity(m);
        let mut h: Vec<Vec<f64>> = Vec::with_capacity(m);
        let mut cs: Vec<(f64, f64)> = Vec::with_capacity(m);
        let mut s = vec![beta];
        // The largest entry of the residual the next direction is to reduce.
        let mut reducing = r.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        for j in 0..m {
            let zj = precondition(&v[j]);
            apply(&zj, &mut scratch, Some(reducing));
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
            let breakdown = wn <= 1e-14 * beta;
            if !breakdown {
                v.push(w.iter().map(|x| x / wn).collect());
            }
            // The recurrence's residual vector b − A x_j = s_{j+1} V_{j+1} Qᵀ e_{j+1}.
            let estimate = recurrence_residual(&v, &cs, s[j + 1]);
            let largest = estimate.iter().fold(0.0_f64, |a, r| a.max(r.abs()));
            progress(iterations, largest);
            reducing = largest;
            let last = breakdown || iterations >= limits.max_iterations || j + 1 == m;
            if largest > target * trust && !last {
                continue;
            }
            let xj = iterate(&x, &z, &h, &s);
            // On breakdown the estimate may leave out the last direction: measured instead.
            if !breakdown
                && let Acceptance::Done =
                    accept(&xj, &estimate, iterations, largest, Residual::Recurrence)
            {
                return end(xj, iterations, true);
            }
            apply(&xj, &mut scratch, None);
            let rj: Vec<f64> = b.par_iter().zip(&scratch).map(|(bi, ax)| bi - ax).collect();
            match accept(&xj, &rj, iterations, largest, Residual::Measured) {
                Acceptance::Done => return end(xj, iterations, true),
                Acceptance::GiveUp => return end(xj, iterations, false),
                // Not an answer to a measured residual: go on as asked last.
                Acceptance::Measure => {}
                Acceptance::Continue { target: t } => {
                    target = t;
                    let truth = rj.iter().fold(0.0_f64, |a, r| a.max(r.abs()));
                    if truth > 0.0 && largest < truth {
                        trust = trust.min(largest / truth);
                    }
                }
                Acceptance::Restart { target: t } => {
                    (target, trust) = (t, 1.0);
                    x = xj;
                    r = rj;
                    continue 'cycles;
                }
                Acceptance::Remeasure { target: t } => {
                    (target, trust) = (t, 1.0);
                    apply(&xj, &mut scratch, None);
                    r = b.par_iter().zip(&scratch).map(|(bi, ax)| bi - ax).collect();
                    x = xj;
                    continue 'cycles;
                }
            }
            if last {
                // Restart from the cycle's last iterate, whose true residual was just measured.
                x = xj;
                r = rj;
                continue 'cycles;
            }
        }
        // Not reached: the cycle's last step is always `last`.
        return end(x, iterations, false);
    }
}

/// x + Z y, with y = R⁻¹ s by back substitution (R the rotated Hessenberg columns).
fn iterate(x: &[f64], z: &[Vec<f64>], h: &[Vec<f64>], s: &[f64]) -> Vec<f64> {
    let k = h.len();
    let mut y = vec![0.0; k];
    for i in (0..k).rev() {
        let mut t = s[i];
        for (jj, yj) in y.iter().enumerate().skip(i + 1) {
            t -= h[jj][i] * yj;
        }
        y[i] = if h[i][i] != 0.0 { t / h[i][i] } else { 0.0 };
    }
    let mut out = x.to_vec();
    for (zj, yj) in z.iter().zip(&y) {
        axpy(*yj, zj, &mut out);
    }
    out
}

/// s_{j+1} V_{j+1} Qᵀ e_{j+1}: the residual of the cycle's current least-squares iterate, from
/// the basis and the rotations (Q = G_j ⋯ G_0), without a product. On breakdown V has j + 1
/// vectors and the residual is 0 up to rounding.
fn recurrence_residual(v: &[Vec<f64>], rotations: &[(f64, f64)], last: f64) -> Vec<f64> {
    let k = rotations.len();
    let mut q = vec![0.0; k + 1];
    q[k] = 1.0;
    for (i, &(c, sn)) in rotations.iter().enumerate().rev() {
        let (a, bb) = (q[i], q[i + 1]);
        q[i] = c * a - sn * bb;
        q[i + 1] = sn * a + c * bb;
    }
    let n = v[0].len();
    let mut out = vec![0.0; n];
    for (vi, qi) in v.iter().zip(&q) {
        axpy(last * qi, vi, &mut out);
    }
    out
}

/// What the caller says of an iterate.
pub(crate) enum Acceptance {
    Done,
    /// Go on; check again when the largest entry of the recurrence's residual vector is below
    /// `target`.
    Continue {
        target: f64,
    },
    /// Start a new cycle from this iterate and its true residual, then as `Continue`: the
    /// recurrence has run ahead of the truth (inexact products took it off course), and only a
    /// new Krylov space built on the true residual can close the gap.
    Restart {
        target: f64,
    },
    /// The products changed (a far field gave way to a more accurate one): start a new cycle
    /// from this iterate and its residual measured again with the new products, then as
    /// `Continue`.
    Remeasure {
        target: f64,
    },
    /// Stop: the iterate will not get better (rounding has the last word).
    GiveUp,
    /// To a residual of the recurrence: not accepted as it is; measure the true one and ask
    /// again.
    Measure,
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
    fn apply(v: &[f64], out: &mut [f64], _: Option<f64>) {
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

    /// A right-hand side of n entries with no structure the operator favours.
    fn right_hand_side(n: usize) -> Vec<f64> {
        (0..n).map(|i| ((i * 5) % 11) as f64 - 5.0).collect()
    }

    /// FGMRES on `apply` (restarts after 100, at most 500 iterations, Jacobi preconditioner)
    /// with `accept` as the judge: the end, and how many products it took.
    fn counted_run(b: &[f64], accept: &mut Judge<'_>) -> (GmresEnd, usize) {
        let products = std::sync::atomic::AtomicUsize::new(0);
        let counted = |v: &[f64], out: &mut [f64], residual: Option<f64>| {
            products.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            apply(v, out, residual);
        };
        let end = fgmres_from(
            b,
            None,
            &GmresLimits {
                restart: 100,
                max_iterations: 500,
            },
            &counted,
            &|v| v.iter().map(|x| x / 4.0).collect(),
            accept,
            &mut |_, _| {},
        );
        (end, products.into_inner())
    }

    /// max |b − A x| for the tridiagonal operator.
    fn true_residual(x: &[f64], b: &[f64]) -> f64 {
        let mut ax = vec![0.0; x.len()];
        apply(x, &mut ax, None);
        ax.iter()
            .zip(b)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    }

    /// Runs FGMRES on `apply` with products 1 % wrong for Krylov directions until the first
    /// check the recurrence runs ahead of, after which they are exact; the judge answers that
    /// check with `on_ahead`. Returns whether it converged to 1e-10 and the true residual.
    fn inexact_then_exact(on_ahead: fn(f64) -> Acceptance) -> (bool, f64) {
        let n = 120;
        let b: Vec<f64> = (0..n).map(|i| ((i * 5) % 11) as f64 - 5.0).collect();
        let exact = std::sync::atomic::AtomicBool::new(false);
        let product = |v: &[f64], out: &mut [f64], residual: Option<f64>| {
            apply(v, out, residual);
            if residual.is_some() && !exact.load(std::sync::atomic::Ordering::Relaxed) {
                for (i, o) in out.iter_mut().enumerate() {
                    *o *= 1.0 + 0.01 * (((i * 3) % 7) as f64 - 3.0) / 3.0;
                }
            }
        };
        let end = fgmres_from(
            &b,
            None,
            &GmresLimits {
                restart: 200,
                max_iterations: 60,
            },
            &product,
            &|v| v.iter().map(|x| x / 4.0).collect(),
            &mut |_, r, iterations, claimed, kind| {
                if kind == Residual::Recurrence {
                    return Acceptance::Measure;
                }
                let truth = r.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
                if truth < 1e-10 {
                    Acceptance::Done
                } else if iterations > 0 && claimed < 0.1 * truth {
                    exact.store(true, std::sync::atomic::Ordering::Relaxed);
                    on_ahead(1e-11)
                } else {
                    Acceptance::Continue { target: 1e-11 }
                }
            },
            &mut |_, _| {},
        );
        let truth = true_residual(&end.x, &b);
        (end.converged, truth)
    }

    #[test]
    fn a_restart_closes_the_gap_inexact_products_leave() {
        // Going on in the same cycle, the recurrence cannot see the error that the inexact
        // products put into its basis; a new cycle on the true residual can.
        let (converged, truth) = inexact_then_exact(|target| Acceptance::Continue { target });
        assert!(!converged && truth > 1e-6, "{truth:e}");
        let (converged, truth) = inexact_then_exact(|target| Acceptance::Restart { target });
        assert!(converged && truth < 1e-10, "{truth:e}");
    }

    #[test]
    fn solves_a_nonsymmetric_system_through_restarts() {
        let n = 200;
        let b: Vec<f64> = (0..n).map(|i| ((i * 7) % 13) as f64 - 6.0).collect();
        let mut checks = 0;
        let end = fgmres_from(
            &b,
            None,
            &GmresLimits {
                restart: 5,
                max_iterations: 500,
            },
            &apply,
            &|v| v.iter().map(|x| x / 4.0).collect(),
            &mut |_, r, _, _, kind| {
                if kind == Residual::Recurrence {
                    return Acceptance::Measure;
                }
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
        let err = true_residual(&end.x, &b);
        assert!(err < 1e-10, "{err}");
    }

    #[test]
    fn the_recurrence_claims_the_true_residual_and_checks_cost_one_product_each() {
        let b = right_hand_side(300);
        let (mut checks, mut worst_gap) = (0, 0.0_f64);
        let (end, used) = counted_run(&b, &mut |_, r, iterations, claimed, kind| {
            if kind == Residual::Recurrence {
                return Acceptance::Measure;
            }
            checks += 1;
            let truth = r.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
            worst_gap = worst_gap.max((truth - claimed).abs());
            // Refuse the first two checks after the start: the cycle must go on.
            if iterations > 0 && checks > 3 && truth < 1e-10 {
                Acceptance::Done
            } else {
                Acceptance::Continue { target: 1e-11 }
            }
        });
        assert!(end.converged);
        assert!(worst_gap < 1e-9, "recurrence off the truth by {worst_gap}");
        // One product per iteration and one per check after the start; no restart happened.
        assert_eq!(used, end.iterations + checks - 1);
        assert!(end.iterations < 100);
    }

    #[test]
    fn a_recurrence_residual_taken_as_it_is_saves_the_check_product_and_holds() {
        let b = right_hand_side(300);
        let mut kinds = Vec::new();
        let (end, used) = counted_run(&b, &mut |x, r, _, claimed, kind| {
            kinds.push(kind);
            let largest = r.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
            if kind == Residual::Recurrence {
                // The recurrence's own vector, and b − A x entry by entry.
                assert_eq!(largest, claimed);
                let mut ax = vec![0.0; x.len()];
                apply(x, &mut ax, None);
                for ((ri, bi), axi) in r.iter().zip(&b).zip(&ax) {
                    assert!((ri - (bi - axi)).abs() < 1e-12, "{ri:e} {:e}", bi - axi);
                }
            }
            if largest < 1e-10 {
                Acceptance::Done
            } else {
                Acceptance::Continue { target: 1e-11 }
            }
        });
        assert!(end.converged);
        assert_eq!(kinds, [Residual::Measured, Residual::Recurrence]);
        // One product per iteration: none for the check.
        assert_eq!(used, end.iterations);
        let truth = true_residual(&end.x, &b);
        assert!(truth < 1e-10, "{truth:e}");
    }

    #[test]
    fn stops_unconverged_at_the_iteration_cap() {
        let b = vec![1.0; 100];
        let end = fgmres_from(
            &b,
            None,
            &GmresLimits {
                restart: 3,
                max_iterations: 4,
            },
            &apply,
            &|v| v.to_vec(),
            &mut |_, _, _, _, _| Acceptance::Continue { target: 0.0 },
            &mut |_, _| {},
        );
        assert!(!end.converged);
        assert_eq!(end.iterations, 4);
    }
}
