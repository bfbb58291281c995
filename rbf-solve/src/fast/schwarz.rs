//! The domain-decomposition preconditioner of Beatson, Light & Billings ("Fast solution of the
//! radial basis function interpolation equations: domain decomposition methods", SIAM J. Sci.
//! Comput. 22(5), 2000), with as many levels as the rows need.
//!
//! Fine level: the rows are split into the leaves of a k-d tree; each leaf grows into an
//! overlapping subdomain of its nearest rows, whose small saddle-point system (kernel block,
//! polynomial block) is factored once and kept as the map from a residual at its rows to its
//! leaf's weights. A residual is solved on every subdomain at once and each keeps the weights of
//! its own leaf only (restricted additive Schwarz). Coarse level: a spread
//! subset of one row in 24, with the whole affine part, solves the residual first, then what the
//! fine level left behind at its rows (multiplicative between the levels, symmetric: one
//! iteration fewer on 10⁵ rows of the peers' problem, 8 instead of 9), and supplies the
//! polynomial. A coarse level too large to factor whole (above twice
//! [`SchwarzSettings::coarse`]) is itself a level of the same preconditioner, over its own
//! subdomains and coarse level, with the products between the levels through a far field
//! (as Polatory's multilevel preconditioner does). Two levels with a coarse level capped at 4096
//! rows stall at 10⁶ rows: one row in 244 cannot carry the kernel's global coupling. Measured on
//! 10⁵ rows of the peers' surface problem with the coarse level capped at 400 rows (one in 250):
//! 30 iterations with two levels, 11 with three, 8 with 4096 rows factored whole; at 2·10⁵ rows
//! with the defaults, 19 iterations (69 s) with two levels, 10 (43 s) with three; on 2·10⁵ rows
//! of the peers' cube problem (scattered values in a volume), 13 iterations (50 s) with three
//! levels where two had not converged after 40. Measured and rejected: subsets of one row in 8
//! or 12 (as Polatory's one in 8): 6 and 9 iterations on the surface, but no convergence within
//! 40 on the cube.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{
    LltRegularization, cholesky_in_place, cholesky_in_place_scratch,
};
use faer::{Mat, Par};

use super::packed_lu::PackedLu;
use super::products::affine;
use rayon::prelude::*;
use rbf_core::{InterpolantView, System};

use rbf_far::{FarField, FarFieldSettings, Tree, bounds};

/// Sizes of the preconditioner's pieces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SchwarzSettings {
    /// Rows whose weights a subdomain keeps (the k-d tree's leaf size).
    pub inner: usize,
    /// Rows a subdomain solves for: its leaf and the nearest rows around it. The overlap they
    /// add decides the iterations on real geometry; 512 / 768 / 1024 rows (256 kept): 70 004
    /// rows of normal constraints of a real bust (nefertiti) 78 / 40 / 29 iterations (68 / 38 /
    /// 32 s), 10⁵ rows of the peers' surface problem 8 / 7 / 7 (11.2 / 11.1 / 14.2 s). Above a
    /// nested coarse level, solved only approximately, 512 rows stalled 10⁶ rows of the surface
    /// near 5e-4 of max|h|, 768 converged to 4.4e-6 in eight iterations.
    pub extended: usize,
    /// Most rows of the coarse level factored whole: it takes one row in 24, but at least 2048
    /// (or all).
    pub coarse: usize,
    /// Most levels, the top one and the one factored whole included: while one row in 24 is
    /// more than twice `coarse`, the coarse level is another level of the same preconditioner
    /// (2: Beatson, Light & Billings's two levels).
    pub levels: usize,
}

impl Default for SchwarzSettings {
    fn default() -> Self {
        Self {
            inner: 256,
            extended: 768,
            coarse: 4096,
            levels: 4,
        }
    }
}

/// The coarse level factored whole: a small dense saddle-point system on some rows of the whole
/// one.
struct Local {
    /// Rows of the whole system.
    rows: Vec<usize>,
    /// Polynomial columns of the local system: 1, x.
    poly: usize,
    lu: PackedLu,
}

impl Local {
    /// Factors the rows' system (in the system's coordinates, with the columns 1, x), on every
    /// core.
    fn new<const D: usize>(system: &System<D>, rows: Vec<usize>) -> Option<Self> {
        // Unscaled, the weights are the whole system's.
        let (matrix, poly) = local_matrix(system, &rows);
        let lu = PackedLu::new(matrix, faer::get_global_parallelism());
        let m = rows.len();
        let local = Self { rows, poly, lu };
        // A singular block shows as non-finite numbers.
        let probe = local.solve(&vec![1.0; m], &vec![0.0; poly]);
        probe.iter().all(|v| v.is_finite()).then_some(local)
    }

    /// Solves for right-hand side (h on the rows, g on the polynomial columns); returns the
    /// weights followed by the polynomial coefficients.
    fn solve(&self, h: &[f64], g: &[f64]) -> Vec<f64> {
        let m = self.rows.len();
        let mut rhs =
            Mat::<f64>::from_fn(m + self.poly, 1, |i, _| if i < m { h[i] } else { g[i - m] });
        self.lu.solve_in_place(rhs.as_mut());
        rhs.col(0).iter().copied().collect()
    }
}

/// A subdomain of a level: its leaf's rows and the nearest rows around them, with its local
/// saddle-point system [A, P; Pᵀ, 0] solved on the weights that meet the moment conditions
/// (null-space method): with Q = [Q₁ Q₂] orthogonal and Q₁ spanning P, the weights for a
/// residual r are w = Q₂ S⁻¹ Q₂ᵀ r, where S = Q₂ᵀ A Q₂ is definite (the kernel is conditionally
/// definite) and kept as its Cholesky factor (its diagonal raised a little where rounding
/// leaves a nearly singular patch not quite definite). Only the leaf's weights are used. The factor costs a
/// quarter of the flops of an LU of the saddle-point system at 512 rows (a seventh of an LU
/// turned into the map from r to the leaf's weights), so wide subdomains are affordable: 10⁵ rows
/// of the peers' surface problem at 768 rows take 11.1 s (14.1 s with LUs turned into maps).
struct Subdomain {
    /// Rows of the whole system; the first `keep` are the leaf's.
    rows: Vec<usize>,
    keep: usize,
    /// Householder reflectors I − τvvᵀ whose product is Q, each as (τ, v) with v of `rows.len()`.
    reflectors: Vec<(f64, Vec<f64>)>,
    /// Lower Cholesky factor L of σS (σ the kernel's definiteness): its diagonal, and below it
    /// packed row by row in single precision: a preconditioner need not be exact (iterations
    /// unchanged on the surface problem and a real bust, 7 and 33 → 34; peak memory at 10⁵
    /// rows 1.43 → 0.86 GB).
    diagonal: Vec<f64>,
    lower: Vec<f32>,
    /// σ times the factor from local weights to the whole system's.
    scale: f64,
}

impl Subdomain {
    /// Factors the rows' system (moved to their box's centre, scaled to unit size, polynomial
    /// columns an orthonormal basis of what they span of (1, x)); `None` if that fails (it shows
    /// as non-finite numbers).
    fn new<const D: usize>(system: &System<D>, rows: Vec<usize>, keep: usize) -> Option<Self> {
        // Rounding may leave a nearly singular patch (near-duplicate points, no smoothing) not
        // quite definite: it is factored again with its diagonal raised by 1e-10 of its largest
        // entry (the preconditioner only needs to approximate).
        let (reflectors, diagonal, lower, scale) =
            Self::factor(system, &rows, 0.0).or_else(|| Self::factor(system, &rows, 1e-10))?;
        Some(Self {
            rows,
            keep,
            reflectors,
            diagonal,
            lower,
            scale,
        })
    }

    /// The reflectors, the factor's diagonal and lower part, and the weights' scale of the rows'
    /// system with σS's diagonal raised by `shift` of its largest entry; `None` if Cholesky finds
    /// it not definite or the numbers are not finite.
    #[allow(clippy::type_complexity)]
    fn factor<const D: usize>(
        system: &System<D>,
        rows: &[usize],
        shift: f64,
    ) -> Option<(Vec<(f64, Vec<f64>)>, Vec<f64>, Vec<f32>, f64)> {
        let m = rows.len();
        let (points, scale_beta) = local_points(system, rows, true);
        let basis = orthonormal_affine_basis(&points);
        let poly = basis.len();
        let sigma = system.kernel().definiteness();
        let mut a = kernel_block(system, rows, &points, scale_beta);
        let mut p = Mat::<f64>::from_fn(m, poly, |i, j| basis[j][i]);
        let reflectors = householder(&mut p);
        project(&mut a, &reflectors);
        let n = m - poly;
        let mut s = a.as_mut().submatrix_mut(poly, poly, n, n);
        if sigma < 0.0 {
            for j in 0..n {
                for i in j..n {
                    s[(i, j)] = -s[(i, j)];
                }
            }
        }
        if shift > 0.0 {
            let largest = (0..n).map(|i| s[(i, i)].abs()).fold(0.0, f64::max);
            for i in 0..n {
                s[(i, i)] += shift * largest;
            }
        }
        let mut scratch = MemBuffer::new(cholesky_in_place_scratch::<f64>(
            n,
            Par::Seq,
            Default::default(),
        ));
        cholesky_in_place(
            s.as_mut(),
            LltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut scratch),
            Default::default(),
        )
        .ok()?;
        let diagonal: Vec<f64> = (0..n).map(|i| s[(i, i)]).collect();
        let mut lower = Vec::with_capacity(n * n.saturating_sub(1) / 2);
        for i in 0..n {
            // Single precision keeps 24 bits; the factor's entries are far inside its range.
            lower.extend((0..i).map(|j| s[(i, j)] as f32));
        }
        let finite = diagonal.iter().all(|v| v.is_finite() && *v > 0.0)
            && lower.iter().all(|v| v.is_finite());
        finite.then_some((reflectors, diagonal, lower, sigma / scale_beta))
    }

    /// The kept rows' weights for the residual `h` (whole-system length, read at the rows).
    fn solve(&self, h: &[f64]) -> Vec<f64> {
        let mut t: Vec<f64> = self.rows.iter().map(|&i| h[i]).collect();
        // t ← Qᵀ r = H_q ⋯ H₁ r.
        for (tau, v) in &self.reflectors {
            reflect(&mut t, *tau, v);
        }
        let q = self.reflectors.len();
        let y = &mut t[q..];
        // L Lᵀ y = t₂: forward by rows, then back by the same rows.
        let row = |i: usize| &self.lower[i * i.saturating_sub(1) / 2..][..i];
        for i in 0..y.len() {
            let dot: f64 = row(i)
                .iter()
                .zip(&y[..i])
                .map(|(a, b)| f64::from(*a) * b)
                .sum();
            y[i] = (y[i] - dot) / self.diagonal[i];
        }
        for i in (0..y.len()).rev() {
            y[i] /= self.diagonal[i];
            let yi = y[i];
            y[..i]
                .iter_mut()
                .zip(row(i))
                .for_each(|(a, l)| *a -= f64::from(*l) * yi);
        }
        // w = Q [0; y] = H₁ ⋯ H_q [0; y].
        t[..q].iter_mut().for_each(|v| *v = 0.0);
        for (tau, v) in self.reflectors.iter().rev() {
            reflect(&mut t, *tau, v);
        }
        t.truncate(self.keep);
        t.iter_mut().for_each(|v| *v *= self.scale);
        t
    }
}

/// Householder QR of the columns of `p` (destroyed): the reflectors (τ, v), one per column, with
/// v zero above its column's index, whose product's first columns span those of `p`.
fn householder(p: &mut Mat<f64>) -> Vec<(f64, Vec<f64>)> {
    let (m, q) = (p.nrows(), p.ncols());
    let mut reflectors = Vec::with_capacity(q);
    for k in 0..q.min(m) {
        let norm = (k..m).map(|i| p[(i, k)].powi(2)).sum::<f64>().sqrt();
        let mut v = vec![0.0; m];
        if norm == 0.0 {
            reflectors.push((0.0, v));
            continue;
        }
        let alpha = if p[(k, k)] > 0.0 { -norm } else { norm };
        for i in k..m {
            v[i] = p[(i, k)];
        }
        v[k] -= alpha;
        let vv: f64 = v.iter().map(|x| x * x).sum();
        let tau = 2.0 / vv;
        for c in k..q {
            let dot: f64 = (k..m).map(|i| v[i] * p[(i, c)]).sum();
            for i in k..m {
                p[(i, c)] -= tau * dot * v[i];
            }
        }
        reflectors.push((tau, v));
    }
    reflectors
}

/// x ← (I − τvvᵀ) x.
fn reflect(x: &mut [f64], tau: f64, v: &[f64]) {
    let dot: f64 = x.iter().zip(v).map(|(a, b)| a * b).sum();
    x.iter_mut().zip(v).for_each(|(a, b)| *a -= tau * dot * b);
}

/// a ← Qᵀ a Q for the symmetric `a` (its lower triangle, read and written) and Q = H₁ ⋯ H_q,
/// the reflectors' product, in two passes over it (compact WY form, Schreiber & Van Loan 1989): Q = I − V T Vᵀ with T upper
/// triangular, W = aV, and then Qᵀ a Q = a − X Vᵀ − V Xᵀ with X = W T − ½ V Tᵀ(VᵀW)T.
fn project(a: &mut Mat<f64>, reflectors: &[(f64, Vec<f64>)]) {
    let q = reflectors.len();
    let m = a.nrows();
    let v = |c: usize| &reflectors[c].1;
    let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(a, b)| a * b).sum::<f64>();
    // T: T[k][k] = τ_k, T[..k][k] = −τ_k T[..k][..k] V[..k]ᵀ v_k (row-major, q × q).
    let mut t = vec![vec![0.0; q]; q];
    for k in 0..q {
        let tau = reflectors[k].0;
        let vk: Vec<f64> = (0..k).map(|j| dot(v(j), v(k))).collect();
        for i in 0..k {
            t[i][k] = -tau * (i..k).map(|j| t[i][j] * vk[j]).sum::<f64>();
        }
        t[k][k] = tau;
    }
    // W = aV, one pass over a's lower triangle (a[i][j] for i > j also stands for a[j][i]).
    let mut w = vec![vec![0.0; m]; q];
    for j in 0..m {
        let col = &column(a, j)[j..];
        for c in 0..q {
            let vc = &v(c)[j..];
            let wc = &mut w[c][j..];
            let f = vc[0];
            wc[0] += col[0] * f;
            wc[1..]
                .iter_mut()
                .zip(&col[1..])
                .for_each(|(wi, ai)| *wi += ai * f);
            // Eight partial sums, so that the dot product vectorizes.
            let mut partial = [0.0; 8];
            let (ac, vc) = (col[1..].chunks_exact(8), vc[1..].chunks_exact(8));
            let (ar, vr) = (ac.remainder(), vc.remainder());
            for (a8, v8) in ac.zip(vc) {
                for k in 0..8 {
                    partial[k] += a8[k] * v8[k];
                }
            }
            wc[0] +=
                partial.iter().sum::<f64>() + ar.iter().zip(vr).map(|(a, v)| a * v).sum::<f64>();
        }
    }
    // M = Tᵀ (VᵀW) T, then X = W T − ½ V M.
    let g: Vec<Vec<f64>> = (0..q)
        .map(|r| (0..q).map(|c| dot(v(r), &w[c])).collect())
        .collect();
    // (A B)[r][c] = Σₖ a(r, k) B[k][c] for q × q matrices.
    let times = |a: &dyn Fn(usize, usize) -> f64, b: &[Vec<f64>]| -> Vec<Vec<f64>> {
        (0..q)
            .map(|r| {
                (0..q)
                    .map(|c| (0..q).map(|k| a(r, k) * b[k][c]).sum())
                    .collect()
            })
            .collect()
    };
    let gt = times(&|r, k| g[r][k], &t);
    let mm = times(&|r, k| t[k][r], &gt);
    let x: Vec<Vec<f64>> = (0..q)
        .map(|c| {
            (0..m)
                .map(|i| {
                    (0..q).map(|k| w[k][i] * t[k][c]).sum::<f64>()
                        - 0.5 * (0..q).map(|k| v(k)[i] * mm[k][c]).sum::<f64>()
                })
                .collect()
        })
        .collect();
    // a ← a − X Vᵀ − V Xᵀ on and below the diagonal, the second pass.
    for j in 0..m {
        let (xj, vj): (Vec<f64>, Vec<f64>) = (0..q).map(|c| (x[c][j], v(c)[j])).unzip();
        let col = &mut column_mut(a, j)[j..];
        for c in 0..q {
            let (xc, vc) = (&x[c][j..], &v(c)[j..]);
            let (xjc, vjc) = (xj[c], vj[c]);
            col.iter_mut()
                .zip(xc.iter().zip(vc))
                .for_each(|(a, (xi, vi))| *a -= xi * vjc + vi * xjc);
        }
    }
}

/// Column `j` of a column-major matrix, as a slice.
fn column(a: &Mat<f64>, j: usize) -> &[f64] {
    a.col(j).try_as_col_major().map_or(&[], |c| c.as_slice())
}

/// Column `j` of a column-major matrix, as a mutable slice.
fn column_mut(a: &mut Mat<f64>, j: usize) -> &mut [f64] {
    a.col_mut(j)
        .try_as_col_major_mut()
        .map_or(&mut [], |c| c.as_slice_mut())
}

/// Some rows' points, and s^β for the scale s they were divided by: with `rescale`, moved to
/// their box's centre and scaled to unit size (their weights scale back by s^-β); without, as
/// the system has them (s = 1).
fn local_points<const D: usize>(
    system: &System<D>,
    rows: &[usize],
    rescale: bool,
) -> (Vec<[f64; D]>, f64) {
    let all = system.normalized_points();
    let (lo, hi) = bounds(all, rows);
    let (centre, s) = if rescale {
        let half = (0..D).map(|d| 0.5 * (hi[d] - lo[d])).fold(0.0, f64::max);
        let c: [f64; D] = core::array::from_fn(|d| 0.5 * (lo[d] + hi[d]));
        (c, if half > 0.0 { half } else { 1.0 })
    } else {
        ([0.0; D], 1.0)
    };
    let points = rows
        .iter()
        .map(|&i| core::array::from_fn(|d| (all[i][d] - centre[d]) / s))
        .collect();
    (points, s.powi(system.kernel().scale_exponent()))
}

/// The kernel block Φ + Λ of some rows at their (local) points, on and below the diagonal only
/// (what the Cholesky factorization reads).
fn kernel_block<const D: usize>(
    system: &System<D>,
    rows: &[usize],
    points: &[[f64; D]],
    scale_beta: f64,
) -> Mat<f64> {
    let m = rows.len();
    let kernel = system.kernel();
    let mut a = Mat::<f64>::zeros(m, m);
    for j in 0..m {
        let pj = points[j];
        let col = column_mut(&mut a, j);
        for (i, pi) in points.iter().enumerate().skip(j + 1) {
            let r2: f64 = (0..D).map(|d| (pi[d] - pj[d]).powi(2)).sum();
            col[i] = kernel.phi(r2.sqrt());
        }
        col[j] = kernel.phi(0.0) + system.normalized_smoothing(rows[j]) / scale_beta;
    }
    a
}

/// The saddle-point matrix [Φ + Λ, P; Pᵀ, 0] of some rows in the system's coordinates, with the
/// polynomial columns 1, x, and its number of polynomial columns.
fn local_matrix<const D: usize>(system: &System<D>, rows: &[usize]) -> (Mat<f64>, usize) {
    let (points, _) = local_points(system, rows, false);
    let block = kernel_block(system, rows, &points, 1.0);
    let (m, q) = (rows.len(), D + 1);
    let poly = |i: usize, c: usize| if c == 0 { 1.0 } else { points[i][c - 1] };
    let matrix = Mat::<f64>::from_fn(m + q, m + q, |i, j| match (i < m, j < m) {
        (true, true) => block[(i.max(j), i.min(j))],
        (true, false) => poly(i, j - m),
        (false, true) => poly(j, i - m),
        (false, false) => 0.0,
    });
    (matrix, q)
}

/// Gram–Schmidt (twice) on the columns 1, x₁ … x_D over the points, dropping a column that the
/// earlier ones nearly span.
fn orthonormal_affine_basis<const D: usize>(points: &[[f64; D]]) -> Vec<Vec<f64>> {
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for c in 0..=D {
        let mut v: Vec<f64> = points
            .iter()
            .map(|p| if c == 0 { 1.0 } else { p[c - 1] })
            .collect();
        let before = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        for _ in 0..2 {
            for b in &basis {
                let dot: f64 = v.iter().zip(b).map(|(x, y)| x * y).sum();
                v.iter_mut().zip(b).for_each(|(x, y)| *x -= dot * y);
            }
        }
        let after = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if after > 1e-8 * before.max(f64::MIN_POSITIVE) {
            v.iter_mut().for_each(|x| *x /= after);
            basis.push(v);
        }
    }
    basis
}

/// Cycles of a nested level per solve, each on the residual the ones before left at its rows
/// (measured on 2·10⁵ rows of the peers' cube problem: 28 iterations with one, 13 with two, 12
/// with three; the surface problem 10 with each).
const NESTED_CYCLES: usize = 2;

/// Products above this many source–target pairs between two levels go through a far field.
const FAR_PAIRS: usize = 1_000_000_000;

/// The far field of the transfers between levels: order 10 errs about 2e-4 of max|h| on the
/// weights of a 10⁵-row fit of the peers' surface problem, far below what a preconditioner needs.
const TRANSFER_ORDER: usize = 10;

/// One level of the factored preconditioner: every row at the top, a spread subset of the level
/// above's rows below it.
pub(crate) struct Schwarz<const D: usize> {
    /// This level's rows of the whole system.
    rows: Vec<usize>,
    fine: Vec<Subdomain>,
    coarse: Coarse<D>,
    /// Weights on the coarse rows to values at this level's rows.
    down: Transfer<D>,
    /// Weights on this level's rows to values at the coarse rows.
    up: Transfer<D>,
}

/// What solves for the global part of a level's residual.
enum Coarse<const D: usize> {
    /// A spread subset of the level's rows, few enough to factor whole, with the affine part.
    Direct(Local),
    /// Too many rows to factor whole: another level of the same preconditioner on them, and
    /// the product of its rows' weights at its rows.
    Nested(Box<Schwarz<D>>, Transfer<D>),
}

impl<const D: usize> Coarse<D> {
    fn rows(&self) -> &[usize] {
        match self {
            Coarse::Direct(local) => &local.rows,
            Coarse::Nested(level, _) => &level.rows,
        }
    }

    /// Weights on the coarse rows (whole-system length, zero elsewhere) and the affine part for
    /// the residual `h` at those rows and `g` of the moment conditions.
    fn solve(&self, system: &System<D>, h: &[f64], g: &[f64]) -> Vec<f64> {
        match self {
            Coarse::Direct(local) => {
                let n = h.len();
                let mut z = vec![0.0; n + D + 1];
                if local.rows.is_empty() {
                    return z;
                }
                let hc: Vec<f64> = local.rows.iter().map(|&i| h[i]).collect();
                let y = local.solve(&hc, g);
                for (k, &i) in local.rows.iter().enumerate() {
                    z[i] = y[k];
                }
                z[n..].copy_from_slice(&y[local.rows.len()..]);
                z
            }
            Coarse::Nested(level, product) => {
                // Cycles of the level, each on what the ones before left.
                let mut z = level.apply(system, h, g);
                for _ in 1..NESTED_CYCLES {
                    let f = product.values(system, &z);
                    let r = leftover(system, &level.rows, &f, h, &z);
                    let dz = level.apply(system, &r, &moments_left(system, &level.rows, g, &z));
                    z.iter_mut().zip(&dz).for_each(|(a, b)| *a += b);
                }
                z
            }
        }
    }
}

/// Values at some rows of weights on others (plus the affine part): by direct sums when there
/// are few pairs, else through a far field over the sources built once.
struct Transfer<const D: usize> {
    sources: Vec<usize>,
    sums: Sums<D>,
    target_points: Vec<[f64; D]>,
}

/// How a [`Transfer`] sums its sources.
enum Sums<const D: usize> {
    /// Directly, over these source points.
    Direct(Vec<[f64; D]>),
    /// Through this far field (which keeps the source points itself).
    Far(Box<FarField<D>>),
}

impl<const D: usize> Transfer<D> {
    fn new(system: &System<D>, sources: &[usize], targets: &[usize]) -> Self {
        let points = system.normalized_points();
        let source_points: Vec<[f64; D]> = sources.iter().map(|&i| points[i]).collect();
        let sums = if sources.len().saturating_mul(targets.len()) > FAR_PAIRS {
            let settings = FarFieldSettings {
                order: TRANSFER_ORDER,
                ..FarFieldSettings::default()
            };
            Sums::Far(Box::new(FarField::new(
                system.kernel(),
                &source_points,
                &settings,
            )))
        } else {
            Sums::Direct(source_points)
        };
        Self {
            sources: sources.to_vec(),
            sums,
            target_points: targets.iter().map(|&i| points[i]).collect(),
        }
    }

    /// f at the targets of the weights `z` (whole-system length, then the affine part) has at
    /// the sources.
    fn values(&self, system: &System<D>, z: &[f64]) -> Vec<f64> {
        let n = system.rows();
        let weights: Vec<f64> = self.sources.iter().map(|&i| z[i]).collect();
        let mut out = vec![0.0; self.target_points.len()];
        match &self.sums {
            Sums::Far(field) => {
                if let Ok(charges) = field.charges(&weights) {
                    let _ = field.values(&charges, &self.target_points, &mut out);
                }
                for (o, p) in out.iter_mut().zip(&self.target_points) {
                    *o += affine(&z[n..], p);
                }
            }
            Sums::Direct(source_points) => {
                let linear: [f64; D] = core::array::from_fn(|d| z[n + 1 + d]);
                let view =
                    InterpolantView::new(system.kernel(), source_points, &weights, z[n], linear);
                if let Ok(view) = view {
                    let _ = view.par_values(&self.target_points, &mut out);
                }
            }
        }
        out
    }
}

impl<const D: usize> Schwarz<D> {
    /// Builds and factors every subdomain and the coarse levels (in parallel).
    pub(crate) fn new(system: &System<D>, settings: &SchwarzSettings) -> Self {
        Self::level(system, (0..system.rows()).collect(), settings, 1)
    }

    /// Level `depth` (the top is 1), over `rows`: subdomains of its rows, and below it a spread
    /// subset of one row in 24, factored whole if that is at most twice `settings.coarse` or
    /// the levels are used up (then at most `settings.coarse` rows, at least 2048), else
    /// another level.
    fn level(
        system: &System<D>,
        rows: Vec<usize>,
        settings: &SchwarzSettings,
        depth: usize,
    ) -> Self {
        let all = system.normalized_points();
        let points: Vec<[f64; D]> = rows.iter().map(|&i| all[i]).collect();
        let m = rows.len();
        let tree = Tree::new(&points, settings.inner);
        let nested = m / 24 > 2 * settings.coarse && depth + 2 <= settings.levels;
        let extended = settings.extended.max(settings.inner);
        let fine = tree
            .leaves()
            .into_par_iter()
            .filter_map(|leaf| {
                let inner = tree.points_of(leaf);
                let near = grow(&tree, &points, leaf, extended.min(m));
                let mut ordered: Vec<usize> = inner.iter().map(|&i| rows[i]).collect();
                ordered.extend(
                    near.into_iter()
                        .filter(|i| !inner.contains(i))
                        .map(|i| rows[i]),
                );
                Subdomain::new(system, ordered, inner.len())
            })
            .collect();
        let coarse = if nested {
            let subset: Vec<usize> = spread_subset(&points, m / 24)
                .into_iter()
                .map(|i| rows[i])
                .collect();
            let product = Transfer::new(system, &subset, &subset);
            Coarse::Nested(
                Box::new(Self::level(system, subset, settings, depth + 1)),
                product,
            )
        } else {
            let wanted = settings.coarse.min((m / 24).max(2048)).max(D + 1);
            let subset: Vec<usize> = spread_subset(&points, wanted)
                .into_iter()
                .map(|i| rows[i])
                .collect();
            let local = Local::new(system, subset)
                .or_else(|| Local::new(system, rows.clone()))
                .unwrap_or_else(|| {
                    // Not reached for a system that passed rbf-core's checks; an empty coarse
                    // level only weakens the preconditioner.
                    empty_local::<D>()
                });
            Coarse::Direct(local)
        };
        let down = Transfer::new(system, coarse.rows(), &rows);
        let up = Transfer::new(system, &rows, coarse.rows());
        Self {
            rows,
            fine,
            coarse,
            down,
            up,
        }
    }

    /// z ≈ A⁻¹ (h, g) on this level's rows (`h` of the whole system's length, read at them):
    /// the coarse level on h, the fine level on what it leaves, then the coarse level again on
    /// what is left at its rows. Returns weights of the whole system's length (zero off this
    /// level's rows) followed by D + 1 polynomial coefficients.
    pub(crate) fn apply(&self, system: &System<D>, h: &[f64], g: &[f64]) -> Vec<f64> {
        self.apply_extended(system, h, g, None)
    }

    /// [`Schwarz::apply`] on a system that has the rows of `extension` besides this level's
    /// (the top level's): their own subdomains solve for them beside this level's, and the
    /// products with the coarse level take them in.
    pub(crate) fn apply_extended(
        &self,
        system: &System<D>,
        h: &[f64],
        g: &[f64],
        extension: Option<&Extension<D>>,
    ) -> Vec<f64> {
        let n = h.len();
        let coarse_rows = self.coarse.rows();
        // Pre-step on the coarse level: the global part first, so that the subdomains solve
        // only what it leaves.
        let mut z = self.coarse.solve(system, h, g);
        let mut h_fine = leftover(system, &self.rows, &self.down.values(system, &z), h, &z);
        if let Some(added) = extension {
            let left = leftover(system, &added.rows, &added.down.values(system, &z), h, &z);
            for &i in &added.rows {
                h_fine[i] = left[i];
            }
        }
        let added_fine: &[Subdomain] = extension.map_or(&[], |e| &e.fine);
        let parts: Vec<Vec<f64>> = (self.fine.par_iter())
            .chain(added_fine.par_iter())
            .map(|subdomain| subdomain.solve(&h_fine))
            .collect();
        for (subdomain, part) in self.fine.iter().chain(added_fine).zip(&parts) {
            for (&i, &v) in subdomain.rows[..subdomain.keep].iter().zip(part) {
                z[i] += v;
            }
        }
        if coarse_rows.is_empty() {
            return z;
        }
        // What the weights so far leave at the coarse rows, and of the moment conditions.
        let mut f = self.up.values(system, &z);
        let mut gc = moments_left(system, &self.rows, g, &z);
        if let Some(added) = extension {
            // The added rows' weights alone: the affine part is in `f` already.
            let mut weights = z.clone();
            weights[n..].iter_mut().for_each(|v| *v = 0.0);
            let more = added.up.values(system, &weights);
            f.iter_mut().zip(&more).for_each(|(a, b)| *a += b);
            gc = moments_left(system, &added.rows, &gc, &z);
        }
        let hc = leftover(system, coarse_rows, &f, h, &z);
        let y = self.coarse.solve(system, &hc, &gc);
        for &i in coarse_rows {
            z[i] += y[i];
        }
        z[n..].iter_mut().zip(&y[n..]).for_each(|(a, b)| *a += b);
        z
    }

    /// Rows of the top level: the system's first this many.
    pub(crate) fn row_count(&self) -> usize {
        self.rows.len()
    }

    /// What rows added to the system after these (the top level's, which stay its first) need:
    /// a small subdomain around each (its [`ADDED_SUBDOMAIN`] nearest rows, old and new),
    /// keeping its weight, and the products between them and the coarse level. Added rows lie
    /// anywhere (the worst-met constraints of a greedy round): a subdomain over a group of
    /// them would span the model and solve for none of them well.
    pub(crate) fn extension(&self, system: &System<D>, settings: &SchwarzSettings) -> Extension<D> {
        let n = system.rows();
        let rows: Vec<usize> = (self.rows.len()..n).collect();
        let all = system.normalized_points();
        let tree = Tree::new(all, settings.inner);
        let size = ADDED_SUBDOMAIN.min(n);
        let fine = rows
            .par_iter()
            .filter_map(|&row| {
                let p = all[row];
                let mut ordered = vec![row];
                ordered.extend(
                    grow_box(&tree, all, &p, &p, size)
                        .into_iter()
                        .filter(|&i| i != row),
                );
                Subdomain::new(system, ordered, 1)
            })
            .collect();
        let down = Transfer::new(system, self.coarse.rows(), &rows);
        let up = Transfer::new(system, &rows, self.coarse.rows());
        Extension {
            rows,
            fine,
            down,
            up,
        }
    }
}

/// Rows of the subdomain around each added row (see [`Schwarz::extension`]).
const ADDED_SUBDOMAIN: usize = 128;

/// Rows added to a system after its preconditioner was built (see [`Schwarz::extension`]).
pub(crate) struct Extension<const D: usize> {
    /// The added rows of the whole system.
    rows: Vec<usize>,
    fine: Vec<Subdomain>,
    /// Weights on the coarse rows to values at the added rows.
    down: Transfer<D>,
    /// Weights on the added rows to values at the coarse rows.
    up: Transfer<D>,
}

/// What weights `z` leave of `h` at `rows`, given f there (`f`, in the order of `rows`): h − f −
/// λz at those rows, zero elsewhere.
fn leftover<const D: usize>(
    system: &System<D>,
    rows: &[usize],
    f: &[f64],
    h: &[f64],
    z: &[f64],
) -> Vec<f64> {
    let mut r = vec![0.0; h.len()];
    for (&i, fi) in rows.iter().zip(f) {
        r[i] = h[i] - fi - system.normalized_smoothing(i) * z[i];
    }
    r
}

/// What weights `z` on `rows` leave of the moment conditions' right-hand side `g`: g − Pᵀz.
fn moments_left<const D: usize>(
    system: &System<D>,
    rows: &[usize],
    g: &[f64],
    z: &[f64],
) -> Vec<f64> {
    let points = system.normalized_points();
    let mut left = g.to_vec();
    for &i in rows {
        left[0] -= z[i];
        for d in 0..D {
            left[d + 1] -= z[i] * points[i][d];
        }
    }
    left
}

fn empty_local<const D: usize>() -> Local {
    Local {
        rows: Vec::new(),
        poly: 0,
        lu: PackedLu::new(Mat::<f64>::identity(1, 1), Par::Seq),
    }
}

/// The `size` rows nearest to a leaf's box (the leaf's own among them), by growing a search
/// radius around the box.
fn grow<const D: usize>(
    tree: &Tree<D>,
    points: &[[f64; D]],
    leaf: usize,
    size: usize,
) -> Vec<usize> {
    let node = &tree.nodes[leaf];
    grow_box(tree, points, &node.lo, &node.hi, size)
}

/// The `size` rows of `tree` nearest to the box from `lo` to `hi`, by growing a search radius
/// around it.
fn grow_box<const D: usize>(
    tree: &Tree<D>,
    points: &[[f64; D]],
    lo: &[f64; D],
    hi: &[f64; D],
    size: usize,
) -> Vec<usize> {
    let diagonal = (0..D).map(|d| (hi[d] - lo[d]).powi(2)).sum::<f64>().sqrt();
    let mut radius = (0.5 * diagonal).max(1e-6);
    let mut found = Vec::new();
    loop {
        found.clear();
        tree.near_box(points, lo, hi, radius, &mut found);
        if found.len() >= size || radius > 8.0 {
            break;
        }
        radius *= 1.5;
    }
    found.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    found.truncate(size);
    found.into_iter().map(|(_, i)| i).collect()
}

/// About `count` rows spread over the points: one per leaf of a k-d tree with that many
/// leaves, the row nearest its leaf's centroid.
fn spread_subset<const D: usize>(points: &[[f64; D]], count: usize) -> Vec<usize> {
    if count >= points.len() {
        return (0..points.len()).collect();
    }
    let leaf = points.len().div_ceil(count);
    let tree = Tree::new(points, leaf);
    tree.leaves()
        .into_iter()
        .map(|l| {
            let idx = tree.points_of(l);
            let mean: [f64; D] = core::array::from_fn(|d| {
                idx.iter().map(|&i| points[i][d]).sum::<f64>() / idx.len() as f64
            });
            let gap = |i: usize| {
                (0..D)
                    .map(|d| (points[i][d] - mean[d]).powi(2))
                    .sum::<f64>()
            };
            idx.iter()
                .copied()
                .min_by(|&a, &b| gap(a).total_cmp(&gap(b)))
                .unwrap_or(idx[0])
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rbf_core::{Constraint, FitSettings};

    /// `n` rows on a bumpy sphere, with values that are not affine.
    fn bumpy(n: usize) -> System<3> {
        let constraints: Vec<Constraint<3>> = (0..n)
            .map(|i| {
                let t = i as f64 * 2.399_963;
                let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
                let r = (1.0 - z * z).sqrt() * (1.0 + 0.1 * (5.0 * t).sin());
                let p = [r * t.cos(), r * t.sin(), z];
                Constraint::interior(p, 1.2 + (3.0 * p[0]).sin() * p[2])
            })
            .collect();
        System::new(&constraints, &FitSettings::default()).unwrap()
    }

    #[test]
    fn a_subdomain_keeping_every_row_solves_its_system_with_no_moments() {
        let system = bumpy(60);
        let rows: Vec<usize> = (0..60).collect();
        let subdomain = Subdomain::new(&system, rows, 60).unwrap();
        let h = system.values();
        let w = subdomain.solve(h);
        let points = system.normalized_points();
        // Moment conditions: Σ w = Σ w x = 0.
        let scale = w.iter().map(|v| v.abs()).sum::<f64>();
        for d in 0..=3 {
            let moment: f64 = (0..60)
                .map(|i| w[i] * if d == 0 { 1.0 } else { points[i][d - 1] })
                .sum();
            assert!(moment.abs() < 1e-9 * scale, "moment {d}: {moment:e}");
        }
        // What the kernel part leaves of h is affine: its least-squares affine fit leaves nothing.
        let left: Vec<f64> = (0..60)
            .map(|i| {
                let f: f64 = (0..60)
                    .map(|j| {
                        let r2: f64 = (0..3).map(|d| (points[i][d] - points[j][d]).powi(2)).sum();
                        w[j] * system.kernel().phi(r2.sqrt())
                    })
                    .sum();
                h[i] - f
            })
            .collect();
        let column = |c: usize, i: usize| if c == 0 { 1.0 } else { points[i][c - 1] };
        let normal = Mat::<f64>::from_fn(4, 4, |a, b| {
            (0..60).map(|i| column(a, i) * column(b, i)).sum()
        });
        let mut c = Mat::<f64>::from_fn(4, 1, |a, _| (0..60).map(|i| column(a, i) * left[i]).sum());
        PackedLu::new(normal, Par::Seq).solve_in_place(c.as_mut());
        let worst = (0..60)
            .map(|i| (left[i] - (0..4).map(|a| c[(a, 0)] * column(a, i)).sum::<f64>()).abs())
            .fold(0.0, f64::max);
        // The factor is kept in single precision: the solve is that accurate (values near 1;
        // measured 1.1e-7), and a wrong one would leave values of their own size.
        assert!(worst < 1e-5, "{worst:e}");
    }

    #[test]
    fn a_nearly_singular_subdomain_is_still_factored() {
        // Two points 3e-9 apart, near the smallest separation `System::new` accepts (2e-9
        // here): the subdomain is still factored and gives finite weights that meet the moment
        // conditions (measured: Cholesky succeeds without the raised diagonal even here).
        let mut constraints: Vec<Constraint<3>> = (0..40)
            .map(|i| {
                let t = i as f64 * 2.399_963;
                let z = 1.0 - 2.0 * (i as f64 + 0.5) / 40.0;
                let r = (1.0 - z * z).sqrt();
                Constraint::interior([r * t.cos(), r * t.sin(), z], 1.0 + 0.1 * z)
            })
            .collect();
        let p = constraints[3].position;
        constraints.push(Constraint::interior([p[0] + 3e-9, p[1], p[2]], 1.05));
        let system = System::new(&constraints, &FitSettings::default()).unwrap();
        let rows: Vec<usize> = (0..41).collect();
        let subdomain = Subdomain::new(&system, rows, 41).expect("factored");
        let w = subdomain.solve(system.values());
        assert!(w.iter().all(|v| v.is_finite()));
        let scale = w.iter().map(|v| v.abs()).sum::<f64>();
        let moment: f64 = w.iter().sum();
        assert!(moment.abs() <= 1e-9 * scale, "{moment:e}");
    }

    #[test]
    fn a_subdomain_keeps_the_weights_its_whole_solve_gives_its_leaf() {
        let system = bumpy(80);
        let rows: Vec<usize> = (0..80).rev().collect();
        let whole = Subdomain::new(&system, rows.clone(), 80).unwrap();
        let leaf = Subdomain::new(&system, rows, 25).unwrap();
        let (all, kept) = (whole.solve(system.values()), leaf.solve(system.values()));
        assert_eq!(kept.len(), 25);
        for (a, b) in kept.iter().zip(&all) {
            assert!((a - b).abs() <= 1e-9 * b.abs().max(1.0), "{a} against {b}");
        }
    }
}
