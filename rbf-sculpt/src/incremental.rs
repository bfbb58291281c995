//! A fit that is updated, not redone, when one row changes: the null-space method with a local
//! basis. D + 1 affinely independent rows S (the pivots) carry the polynomial; every other row i
//! gets the basis vector zᵢ = eᵢ − Σₛ λᵢₛ eₛ, with λᵢ the barycentric coordinates of its point
//! in the simplex S, so that Pᵀzᵢ = 0. The matrix M = σ ZᵀΦZ is positive definite for the
//! conditionally definite kernels, and adding a row adds one row and column to M: its Cholesky
//! factor grows by one row (a bordered update, O(n²)); removing a row deletes one and restores
//! the triangle with Givens rotations (O(n²)). Changing a pivot refactors (O(n³/3)).

use rayon::prelude::*;
use rbf_core::{Interpolant, Kernel};

use crate::SculptError;

/// Rows per block of the triangular solves.
const BLOCK: usize = 256;

/// One row of the system: f(position) = value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row<const D: usize> {
    /// The constrained point, in the caller's coordinates.
    pub position: [f64; D],
    /// The value f must take at `position` (0 on the surface, positive inside).
    pub value: f64,
}

/// An interpolation problem kept factored under row insertions and deletions.
///
/// ```
/// use rbf_core::Kernel;
/// use rbf_sculpt::{IncrementalFit, Row};
/// let s = 0.57735;
/// let rows = [[s, s, s], [s, -s, -s], [-s, s, -s], [-s, -s, s]]
///     .map(|p| Row { position: p, value: 0.0 });
/// let mut fit = IncrementalFit::new(Kernel::Cubic, &rows).unwrap();
/// let centre = fit.push(Row { position: [0.0; 3], value: 1.0 }).unwrap();
/// let f = fit.interpolant().unwrap();
/// assert!((f.value(&[0.0; 3]) - 1.0).abs() < 1e-12);
/// fit.remove(centre).unwrap(); // back to four rows: f = 0 everywhere
/// assert!(fit.interpolant().unwrap().value(&[0.0; 3]).abs() < 1e-12);
/// ```
#[derive(Clone, Debug)]
pub struct IncrementalFit<const D: usize> {
    kernel: Kernel,
    sigma: f64,
    /// Rows by id (`None` once removed).
    rows: Vec<Option<Row<D>>>,
    /// Pivot row ids.
    pivots: Vec<usize>,
    /// Inverse of the pivots' matrix B (columns [1, xₛ]), to get barycentric coordinates.
    inverse: Vec<[f64; 4]>,
    /// Non-pivot row ids in factor order, with their barycentric coordinates.
    free: Vec<(usize, Vec<f64>)>,
    /// Per free row: φ between its point and each pivot.
    to_pivots: Vec<Vec<f64>>,
    /// Cholesky factor of M, row k holding columns 0..=k.
    factor: Vec<Vec<f64>>,
    /// y = L⁻¹ σZᵀh, kept up to date with the factor.
    forward: Vec<f64>,
}

impl<const D: usize> IncrementalFit<D> {
    /// Factors the rows (at least D + 1, not all on one hyperplane).
    pub fn new(kernel: Kernel, rows: &[Row<D>]) -> Result<Self, SculptError> {
        let mut fit = Self {
            kernel,
            sigma: kernel.definiteness(),
            rows: rows.iter().copied().map(Some).collect(),
            pivots: Vec::new(),
            inverse: Vec::new(),
            free: Vec::new(),
            to_pivots: Vec::new(),
            factor: Vec::new(),
            forward: Vec::new(),
        };
        fit.refactor(None)?;
        Ok(fit)
    }

    /// Live rows.
    pub fn len(&self) -> usize {
        self.pivots.len() + self.free.len()
    }

    /// True when no row is live (never, once constructed).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The row with this id, if live.
    pub fn row(&self, id: usize) -> Option<Row<D>> {
        self.rows.get(id).copied().flatten()
    }

    /// Adds a row; returns its id.
    pub fn push(&mut self, row: Row<D>) -> Result<usize, SculptError> {
        check(&row)?;
        let id = self.rows.len();
        self.rows.push(Some(row));
        if let Err(e) = self.append(id) {
            self.rows[id] = None;
            return Err(e);
        }
        Ok(id)
    }

    /// The ids of the D + 1 rows that carry the linear polynomial (the pivots). Replacing or
    /// removing one of them refactors the whole system (O(n³)); any other edit is O(n²).
    pub fn pivots(&self) -> &[usize] {
        &self.pivots
    }

    /// Removes a row.
    pub fn remove(&mut self, id: usize) -> Result<(), SculptError> {
        if self.row(id).is_none() {
            return Err(SculptError::NoSuchItem(id));
        }
        if self.pivots.contains(&id) {
            let old = self.rows[id].take();
            return self.refactor(None).inspect_err(|_| self.rows[id] = old);
        }
        let k = self
            .free
            .iter()
            .position(|(r, _)| *r == id)
            .ok_or(SculptError::NoSuchItem(id))?;
        self.rows[id] = None;
        self.free.remove(k);
        self.to_pivots.remove(k);
        self.delete_factor_row(k);
        Ok(())
    }

    /// Replaces a row's position and value (keeping its id).
    pub fn replace(&mut self, id: usize, row: Row<D>) -> Result<(), SculptError> {
        check(&row)?;
        let old = self.row(id).ok_or(SculptError::NoSuchItem(id))?;
        if self.pivots.contains(&id) {
            // The pivots are chosen again without this row where the others allow: a handle
            // being dragged then refactors once, not at every step.
            self.rows[id] = Some(row);
            return self.refactor(Some(id)).inspect_err(|_| {
                self.rows[id] = Some(old);
                let _ = self.refactor(None);
            });
        }
        self.remove(id)?;
        self.rows[id] = Some(row);
        if let Err(e) = self.append(id) {
            self.rows[id] = Some(old);
            self.append(id)?;
            return Err(e);
        }
        Ok(())
    }

    fn phi(&self, a: usize, b: usize) -> f64 {
        let (p, q) = (self.position(a), self.position(b));
        let r2: f64 = (0..D).map(|d| (p[d] - q[d]) * (p[d] - q[d])).sum();
        self.kernel.phi(r2.sqrt())
    }

    fn position(&self, id: usize) -> [f64; D] {
        self.rows[id].map_or([0.0; D], |r| r.position)
    }

    fn value(&self, id: usize) -> f64 {
        self.rows[id].map_or(0.0, |r| r.value)
    }

    /// Barycentric coordinates of p in the pivots' simplex.
    fn barycentric(&self, p: [f64; D]) -> Vec<f64> {
        (0..=D)
            .map(|s| {
                let row = &self.inverse[s];
                row[0] + (0..D).map(|d| row[d + 1] * p[d]).sum::<f64>()
            })
            .collect()
    }

    /// σ zₐᵀ Φ z_a for a free row: its diagonal entry of M.
    fn diagonal(&self, a: usize, la: &[f64], pa: &[f64], q: &[f64]) -> f64 {
        let mut v = self.phi(a, a);
        for s in 0..self.pivots.len() {
            v += -2.0 * la[s] * pa[s] + la[s] * q[s];
        }
        self.sigma * v
    }

    /// The right-hand side σ zₐᵀ h of a free row.
    fn rhs(&self, a: usize, la: &[f64]) -> f64 {
        let h = self.value(a)
            - self
                .pivots
                .iter()
                .enumerate()
                .map(|(s, &p)| la[s] * self.value(p))
                .sum::<f64>();
        self.sigma * h
    }

    /// Appends free row `id` to the factor (a bordered Cholesky update, O(n²)).
    fn append(&mut self, id: usize) -> Result<(), SculptError> {
        let lambda = self.barycentric(self.position(id));
        // φ to the pivots, and q = Φ_SS λ.
        let pa: Vec<f64> = self.pivots.iter().map(|&p| self.phi(id, p)).collect();
        let q: Vec<f64> = (0..self.pivots.len())
            .map(|s| {
                (0..self.pivots.len())
                    .map(|t| self.phi(self.pivots[s], self.pivots[t]) * lambda[t])
                    .sum()
            })
            .collect();
        // M column: σ [φ(a, b) − λ_b·pa − λ_a·φ(S, b) + λ_b·q] for every free row b.
        let mut l: Vec<f64> = self
            .free
            .iter()
            .zip(&self.to_pivots)
            .map(|((b, lb), pb)| {
                let mut v = self.phi(id, *b);
                for s in 0..self.pivots.len() {
                    v += -lb[s] * pa[s] - lambda[s] * pb[s] + lb[s] * q[s];
                }
                self.sigma * v
            })
            .collect();
        let diagonal = self.diagonal(id, &lambda, &pa, &q);
        self.forward_solve(&mut l);
        let rest = diagonal - dot(&l, &l);
        if !(rest > 1e-13 * diagonal.abs().max(1e-300)) {
            return Err(SculptError::Singular(
                "the new point coincides with, or is too close to, an existing one".into(),
            ));
        }
        let d = rest.sqrt();
        let y = (self.rhs(id, &lambda) - dot(&l, &self.forward)) / d;
        l.push(d);
        self.factor.push(l);
        self.forward.push(y);
        self.free.push((id, lambda));
        self.to_pivots.push(pa);
        Ok(())
    }

    /// Solves L x = b in place, in blocks of rows: the part of each block's rows left of the
    /// block is a matrix–vector product, done in parallel; the block's triangle in turn.
    fn forward_solve(&self, x: &mut [f64]) {
        let n = x.len();
        let mut k0 = 0;
        while k0 < n {
            let k1 = (k0 + BLOCK).min(n);
            let (done, block) = x.split_at_mut(k0);
            let done: &[f64] = done;
            block[..k1 - k0]
                .par_iter_mut()
                .enumerate()
                .for_each(|(i, v)| *v -= dot(&self.factor[k0 + i][..k0], done));
            for i in k0..k1 {
                let row = &self.factor[i];
                x[i] = (x[i] - dot(&row[k0..i], &x[k0..i])) / row[i];
            }
            k0 = k1;
        }
    }

    /// Solves Lᵀ x = b in place, in blocks of rows from the bottom: each block's triangle in
    /// turn, then its rows' effect on the unknowns to their left, in parallel column chunks.
    fn back_solve(&self, x: &mut [f64]) {
        let n = x.len();
        let mut k1 = n;
        while k1 > 0 {
            let k0 = k1.saturating_sub(BLOCK);
            for k in (k0..k1).rev() {
                let row = &self.factor[k];
                x[k] /= row[k];
                let v = x[k];
                for j in k0..k {
                    x[j] -= row[j] * v;
                }
            }
            let (left, block) = x.split_at_mut(k0);
            let block: &[f64] = &block[..k1 - k0];
            left.par_chunks_mut(512).enumerate().for_each(|(c, chunk)| {
                let a = c * 512;
                for (k, &v) in (k0..k1).zip(block) {
                    let row = &self.factor[k][a..a + chunk.len()];
                    for (y, l) in chunk.iter_mut().zip(row) {
                        *y -= l * v;
                    }
                }
            });
            k1 = k0;
        }
    }

    /// Deletes row and column k of M from the factor: Givens rotations on neighbouring
    /// columns restore the triangle.
    fn delete_factor_row(&mut self, k: usize) {
        self.factor.remove(k);
        let n = self.factor.len();
        for c in k..n {
            let (a, b) = (self.factor[c][c], self.factor[c][c + 1]);
            let r = a.hypot(b);
            let (cs, sn) = if r > 0.0 { (a / r, b / r) } else { (1.0, 0.0) };
            for row in &mut self.factor[c..] {
                let (x, y) = (row[c], row[c + 1]);
                row[c] = cs * x + sn * y;
                row[c + 1] = -sn * x + cs * y;
            }
            self.factor[c].truncate(c + 1);
            // With row k gone, L y = b still holds for the other rows; it stays true as
            // (L Q)(Qᵀ y) = b.
            let (x, y) = (self.forward[c], self.forward[c + 1]);
            self.forward[c] = cs * x + sn * y;
            self.forward[c + 1] = -sn * x + cs * y;
        }
        // The last column is now zero: its unknown drops out.
        self.forward.truncate(n);
    }

    /// Chooses pivots (spread out: each farthest from the span of the previous), if possible
    /// not `avoid`, and factors every other row.
    fn refactor(&mut self, avoid: Option<usize>) -> Result<(), SculptError> {
        let live: Vec<usize> = (0..self.rows.len())
            .filter(|&i| self.rows[i].is_some())
            .collect();
        if live.len() < D + 1 {
            return Err(SculptError::Singular(format!(
                "{} points cannot hold a {D}D linear polynomial: keep at least {}",
                live.len(),
                D + 1
            )));
        }
        let others: Vec<usize> = live.iter().copied().filter(|&i| Some(i) != avoid).collect();
        let pivots = self.spread_pivots(if others.len() > D { &others } else { &live });
        match self.factor_with(pivots, &live) {
            // The others alone lie on one plane: the avoided row is needed as a pivot.
            Err(SculptError::Singular(_)) if avoid.is_some() => {
                let pivots = self.spread_pivots(&live);
                self.factor_with(pivots, &live)
            }
            result => result,
        }
    }

    /// D + 1 of `candidates` (at least that many), the first and then each farthest from the
    /// span of those before.
    fn spread_pivots(&self, candidates: &[usize]) -> Vec<usize> {
        let mut pivots = vec![candidates[0]];
        while pivots.len() < D + 1 {
            let next = candidates
                .iter()
                .copied()
                .filter(|i| !pivots.contains(i))
                .max_by(|&a, &b| {
                    self.span_distance(&pivots, a)
                        .total_cmp(&self.span_distance(&pivots, b))
                })
                .unwrap_or(candidates[0]);
            pivots.push(next);
        }
        pivots
    }

    /// Factors the `live` rows on these pivots.
    fn factor_with(&mut self, pivots: Vec<usize>, live: &[usize]) -> Result<(), SculptError> {
        // B has columns [1, xₛ]; invert it by Gauss–Jordan with partial pivoting.
        let mut b: Vec<Vec<f64>> = (0..=D)
            .map(|r| {
                let mut row: Vec<f64> = pivots
                    .iter()
                    .map(|&p| if r == 0 { 1.0 } else { self.position(p)[r - 1] })
                    .collect();
                row.extend((0..=D).map(|c| if c == r { 1.0 } else { 0.0 }));
                row
            })
            .collect();
        let scale = b
            .iter()
            .flat_map(|r| r[..=D].iter())
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        for c in 0..=D {
            let p = (c..=D)
                .max_by(|&x, &y| b[x][c].abs().total_cmp(&b[y][c].abs()))
                .unwrap_or(c);
            if !(b[p][c].abs() > 1e-12 * scale) {
                return Err(SculptError::Singular(
                    "every point lies on one plane (or line): the linear part is undetermined"
                        .into(),
                ));
            }
            b.swap(c, p);
            let div = b[c][c];
            b[c].iter_mut().for_each(|v| *v /= div);
            for r in 0..=D {
                if r != c {
                    let m = b[r][c];
                    if m != 0.0 {
                        let pivot_row = b[c].clone();
                        b[r].iter_mut()
                            .zip(pivot_row)
                            .for_each(|(v, p)| *v -= m * p);
                    }
                }
            }
        }
        // Rows of B⁻¹: λ = B⁻¹ [1; x].
        self.inverse = (0..=D)
            .map(|r| {
                let mut row = [0.0; 4];
                for c in 0..=D {
                    row[c] = b[r][D + 1 + c];
                }
                row
            })
            .collect();
        self.pivots = pivots;
        self.free.clear();
        self.to_pivots.clear();
        self.factor.clear();
        self.forward.clear();
        for &id in live {
            if !self.pivots.contains(&id) {
                self.append(id)?;
            }
        }
        Ok(())
    }

    /// Distance of row a's point from the affine span of the pivots so far (by Gram–Schmidt).
    fn span_distance(&self, pivots: &[usize], a: usize) -> f64 {
        let origin = self.position(pivots[0]);
        let mut basis: Vec<[f64; D]> = Vec::new();
        for &p in &pivots[1..] {
            let mut v: [f64; D] = core::array::from_fn(|d| self.position(p)[d] - origin[d]);
            for e in &basis {
                let dot: f64 = (0..D).map(|d| v[d] * e[d]).sum();
                (0..D).for_each(|d| v[d] -= dot * e[d]);
            }
            let n = (0..D).map(|d| v[d] * v[d]).sum::<f64>().sqrt();
            if n > 0.0 {
                basis.push(v.map(|x| x / n));
            }
        }
        let mut v: [f64; D] = core::array::from_fn(|d| self.position(a)[d] - origin[d]);
        for e in &basis {
            let dot: f64 = (0..D).map(|d| v[d] * e[d]).sum();
            (0..D).for_each(|d| v[d] -= dot * e[d]);
        }
        (0..D).map(|d| v[d] * v[d]).sum::<f64>().sqrt()
    }

    /// Solves for the weights and the linear polynomial: the current interpolant, its centres in
    /// the order of the rows' ids.
    pub fn interpolant(&self) -> Result<Interpolant<f64, D>, SculptError> {
        // M u = σ Zᵀ h: L y = σ Zᵀ h is kept in `forward`; back substitution gives u.
        let mut u = self.forward.clone();
        self.back_solve(&mut u);
        // Weights: u on the free rows, −Σ λ u on the pivots.
        let mut centres: Vec<[f64; D]> = Vec::with_capacity(self.len());
        let mut weights: Vec<f64> = Vec::with_capacity(self.len());
        let mut pivot_weights = vec![0.0; D + 1];
        for ((i, l), &w) in self.free.iter().zip(&u) {
            centres.push(self.position(*i));
            weights.push(w);
            for s in 0..=D {
                pivot_weights[s] -= l[s] * w;
            }
        }
        for (s, &p) in self.pivots.iter().enumerate() {
            centres.push(self.position(p));
            weights.push(pivot_weights[s]);
        }
        // Centres in the order of their row ids, so that they follow the caller's order.
        let mut ids: Vec<usize> = self.free.iter().map(|(i, _)| *i).collect();
        ids.extend(&self.pivots);
        let mut order: Vec<usize> = (0..ids.len()).collect();
        order.sort_by_key(|&k| ids[k]);
        let centres: Vec<[f64; D]> = order.iter().map(|&k| centres[k]).collect();
        let weights: Vec<f64> = order.iter().map(|&k| weights[k]).collect();
        // The polynomial from the pivot rows: [1, xₛ]·c = hₛ − (Φw)ₛ, i.e. Bᵀ c = r.
        let residual: Vec<f64> = self
            .pivots
            .iter()
            .map(|&p| {
                let x = self.position(p);
                let phi_w: f64 = centres
                    .iter()
                    .zip(&weights)
                    .map(|(c, w)| {
                        let r2: f64 = (0..D).map(|d| (x[d] - c[d]) * (x[d] - c[d])).sum();
                        w * self.kernel.phi(r2.sqrt())
                    })
                    .sum();
                self.value(p) - phi_w
            })
            .collect();
        // c = B⁻ᵀ r.
        let c: Vec<f64> = (0..=D)
            .map(|k| (0..=D).map(|s| self.inverse[s][k] * residual[s]).sum())
            .collect();
        let linear: [f64; D] = core::array::from_fn(|d| c[d + 1]);
        Interpolant::new(self.kernel, centres, weights, c[0], linear)
            .map_err(|_| SculptError::Singular("inconsistent lengths".into()))
    }
}

fn check<const D: usize>(row: &Row<D>) -> Result<(), SculptError> {
    if row.position.iter().all(|v| v.is_finite()) && row.value.is_finite() {
        Ok(())
    } else {
        Err(SculptError::NotFinite)
    }
}

/// a·b with eight independent sums, so that the compiler can vectorize it.
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut sums = [0.0; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        for k in 0..8 {
            sums[k] += x[k] * y[k];
        }
    }
    sums.iter().sum::<f64>() + tail
}
