//! The two-level domain-decomposition preconditioner of Beatson, Light & Billings ("Fast solution
//! of the radial basis function interpolation equations: domain decomposition methods", SIAM J.
//! Sci. Comput. 22(5), 2000).
//!
//! Fine level: the rows are split into the leaves of a k-d tree; each leaf grows into an
//! overlapping subdomain of its nearest rows, whose small saddle-point system (kernel block,
//! polynomial block) is factored once. A residual is solved on every subdomain at once and each
//! keeps the weights of its own leaf only (restricted additive Schwarz). Coarse level: a spread
//! subset of the rows, with the whole affine part, solves the residual first, then what the
//! fine level left behind at its rows (multiplicative between the levels, symmetric: one
//! iteration fewer on 10⁵ rows of the peers' problem, 8 instead of 9), and supplies the
//! polynomial.

use faer::{Mat, Par};

use super::packed_lu::PackedLu;
use rayon::prelude::*;
use rbf_core::{InterpolantView, System};

use rbf_far::{Tree, bounds};

/// Sizes of the preconditioner's pieces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SchwarzSettings {
    /// Rows whose weights a subdomain keeps (the k-d tree's leaf size).
    pub inner: usize,
    /// Rows a subdomain solves for: its leaf and the nearest rows around it.
    pub extended: usize,
    /// Most rows of the coarse level: it takes one row in 24, but at least 2048 (or all).
    pub coarse: usize,
}

impl Default for SchwarzSettings {
    fn default() -> Self {
        Self {
            inner: 256,
            extended: 512,
            coarse: 4096,
        }
    }
}

/// A small dense saddle-point system on some rows of the whole one, factored.
struct Local {
    /// Rows of the whole system; the first `keep` are those whose weights are kept.
    rows: Vec<usize>,
    keep: usize,
    /// Polynomial columns of the local system.
    poly: usize,
    /// Local weights times this are weights of the whole system.
    weight_scale: f64,
    lu: PackedLu,
}

impl Local {
    /// Factors the rows' system. With `rescale`, the rows are moved to their box's centre and
    /// scaled to unit size (their weights scale back by s^-β), and the polynomial columns are
    /// an orthonormal basis of what the rows span of (1, x): a flat patch gets fewer columns.
    /// Without, the columns are (1, x) in the system's coordinates.
    fn new<const D: usize>(
        system: &System<D>,
        rows: Vec<usize>,
        keep: usize,
        rescale: bool,
    ) -> Option<Self> {
        let all = system.normalized_points();
        let (lo, hi) = bounds(all, &rows);
        let (centre, s) = if rescale {
            let half = (0..D).map(|d| 0.5 * (hi[d] - lo[d])).fold(0.0, f64::max);
            let c: [f64; D] = core::array::from_fn(|d| 0.5 * (lo[d] + hi[d]));
            (c, if half > 0.0 { half } else { 1.0 })
        } else {
            ([0.0; D], 1.0)
        };
        let points: Vec<[f64; D]> = rows
            .iter()
            .map(|&i| core::array::from_fn(|d| (all[i][d] - centre[d]) / s))
            .collect();
        let m = rows.len();
        let basis = if rescale {
            orthonormal_affine_basis(&points)
        } else {
            (0..=D)
                .map(|c| {
                    points
                        .iter()
                        .map(|p| if c == 0 { 1.0 } else { p[c - 1] })
                        .collect()
                })
                .collect()
        };
        let q = basis.len();
        let beta = system.kernel().scale_exponent();
        let scale_beta = s.powi(beta);
        let kernel = system.kernel();
        let matrix = Mat::<f64>::from_fn(m + q, m + q, |i, j| match (i < m, j < m) {
            (true, true) => {
                let r2: f64 = (0..D).map(|d| (points[i][d] - points[j][d]).powi(2)).sum();
                let mut v = kernel.phi(r2.sqrt());
                if i == j {
                    v += system.normalized_smoothing(rows[i]) / scale_beta;
                }
                v
            }
            (true, false) => basis[j - m][i],
            (false, true) => basis[i - m][j],
            (false, false) => 0.0,
        });
        // Subdomains (rescaled) are factored many at once, one per core; the coarse level alone,
        // on every core.
        let par = if rescale {
            Par::Seq
        } else {
            faer::get_global_parallelism()
        };
        let lu = PackedLu::new(matrix, par);
        let local = Self {
            rows,
            keep,
            poly: q,
            weight_scale: 1.0 / scale_beta,
            lu,
        };
        // A singular block shows as non-finite numbers; such a subdomain is left out.
        let probe = local.solve(&vec![1.0; m], &vec![0.0; q]);
        probe.iter().all(|v| v.is_finite()).then_some(local)
    }

    /// Solves for right-hand side (h on the rows, g on the polynomial columns); returns the
    /// kept weights (scaled back) followed by the polynomial coefficients.
    fn solve(&self, h: &[f64], g: &[f64]) -> Vec<f64> {
        let m = self.rows.len();
        let mut rhs =
            Mat::<f64>::from_fn(m + self.poly, 1, |i, _| if i < m { h[i] } else { g[i - m] });
        self.lu.solve_in_place(rhs.as_mut());
        let mut out: Vec<f64> = (0..self.keep)
            .map(|i| rhs[(i, 0)] * self.weight_scale)
            .collect();
        out.extend((0..self.poly).map(|i| rhs[(m + i, 0)]));
        out
    }
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

/// The factored preconditioner of a system.
pub(crate) struct Schwarz {
    fine: Vec<Local>,
    coarse: Local,
}

impl Schwarz {
    /// Builds and factors every subdomain and the coarse level (in parallel).
    pub(crate) fn new<const D: usize>(system: &System<D>, settings: &SchwarzSettings) -> Self {
        let points = system.normalized_points();
        let n = points.len();
        let tree = Tree::new(points, settings.inner);
        let extended = settings.extended.max(settings.inner);
        let fine = tree
            .leaves()
            .into_par_iter()
            .filter_map(|leaf| {
                let inner = tree.points_of(leaf);
                let rows = grow(&tree, points, leaf, extended.min(n));
                let mut ordered = inner.to_vec();
                ordered.extend(rows.into_iter().filter(|i| !inner.contains(i)));
                Local::new(system, ordered, inner.len(), true)
            })
            .collect();
        let wanted = settings.coarse.min((n / 24).max(2048)).max(D + 1);
        let coarse_rows = spread_subset(points, wanted);
        let keep = coarse_rows.len();
        let coarse = Local::new(system, coarse_rows, keep, false)
            .or_else(|| Local::new(system, (0..n).collect(), n, false))
            .unwrap_or_else(|| {
                // Not reached for a system that passed rbf-core's checks; an empty coarse level
                // only weakens the preconditioner.
                empty_local::<D>()
            });
        Self { fine, coarse }
    }

    /// z ≈ A⁻¹ (h, g): the fine level on h, then the coarse level on what is left at its rows.
    /// Returns K weights followed by D + 1 polynomial coefficients.
    pub(crate) fn apply<const D: usize>(
        &self,
        system: &System<D>,
        h: &[f64],
        g: &[f64],
    ) -> Vec<f64> {
        let points = system.normalized_points();
        let n = points.len();
        let mut z = vec![0.0; n + D + 1];
        let coarse = &self.coarse;
        // Pre-step on the coarse level: the global part first, so that the subdomains solve
        // only what it leaves (its weights sit on few rows: evaluating them everywhere is cheap).
        let mut h_fine = h.to_vec();
        if !coarse.rows.is_empty() {
            let hc: Vec<f64> = coarse.rows.iter().map(|&i| h[i]).collect();
            let y = coarse.solve(&hc, g);
            let centres: Vec<[f64; D]> = coarse.rows.iter().map(|&i| points[i]).collect();
            let linear: [f64; D] = core::array::from_fn(|d| y[coarse.keep + 1 + d]);
            let mut fy = vec![0.0; n];
            if let Ok(view) = InterpolantView::new(
                system.kernel(),
                &centres,
                &y[..coarse.keep],
                y[coarse.keep],
                linear,
            ) {
                let _ = view.par_values(points, &mut fy);
            }
            for (k, &i) in coarse.rows.iter().enumerate() {
                z[i] = y[k];
                fy[i] += system.normalized_smoothing(i) * y[k];
            }
            z[n..].copy_from_slice(&y[coarse.keep..]);
            h_fine.iter_mut().zip(&fy).for_each(|(a, b)| *a -= b);
        }
        let parts: Vec<Vec<f64>> = self
            .fine
            .par_iter()
            .map(|local| {
                let hl: Vec<f64> = local.rows.iter().map(|&i| h_fine[i]).collect();
                local.solve(&hl, &vec![0.0; local.poly])
            })
            .collect();
        for (local, part) in self.fine.iter().zip(&parts) {
            for (&i, &v) in local.rows[..local.keep].iter().zip(part) {
                z[i] += v;
            }
        }
        if coarse.rows.is_empty() {
            return z;
        }
        // What the fine weights leave at the coarse rows, and of the moment conditions.
        let targets: Vec<[f64; D]> = coarse.rows.iter().map(|&i| points[i]).collect();
        let mut fz = vec![0.0; targets.len()];
        let linear: [f64; D] = core::array::from_fn(|d| z[n + 1 + d]);
        let view = InterpolantView::new(system.kernel(), points, &z[..n], z[n], linear);
        if let Ok(view) = view {
            let _ = view.par_values(&targets, &mut fz);
        }
        let hc: Vec<f64> = coarse
            .rows
            .iter()
            .zip(&fz)
            .map(|(&i, f)| h[i] - f - system.normalized_smoothing(i) * z[i])
            .collect();
        let mut gc = g.to_vec();
        for (wi, p) in z[..n].iter().zip(points) {
            gc[0] -= wi;
            for d in 0..D {
                gc[d + 1] -= wi * p[d];
            }
        }
        let y = coarse.solve(&hc, &gc);
        for (k, &i) in coarse.rows.iter().enumerate() {
            z[i] += y[k];
        }
        z[n..]
            .iter_mut()
            .zip(&y[coarse.keep..])
            .for_each(|(a, b)| *a += b);
        z
    }
}

fn empty_local<const D: usize>() -> Local {
    Local {
        rows: Vec::new(),
        keep: 0,
        poly: 0,
        weight_scale: 1.0,
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
    let diagonal = (0..D)
        .map(|d| (node.hi[d] - node.lo[d]).powi(2))
        .sum::<f64>()
        .sqrt();
    let mut radius = (0.5 * diagonal).max(1e-6);
    let mut found = Vec::new();
    loop {
        found.clear();
        tree.near_box(points, &node.lo, &node.hi, radius, &mut found);
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
