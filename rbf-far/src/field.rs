//! Sums Σⱼ wⱼ φ(|x − cⱼ|) over many centres at many points, with the far field of every cluster
//! of centres replaced by charges on a tensor grid of Chebyshev points over its box: a
//! barycentric Lagrange treecode (Wang, Tlupova & Krasny, "A kernel-independent treecode based
//! on barycentric Lagrange interpolation", Commun. Comput. Phys. 28, 2020), with targets taken a
//! leaf at a time so that each leaf's near centres and far proxies go through rbf-core's
//! vectorized evaluator in one pass.

use rayon::prelude::*;
use rbf_core::{InterpolantView, Kernel, LengthMismatch};

use std::sync::OnceLock;

use crate::clusters::{Clusters, side};
use crate::dual::{Plan, Weighted, evaluate};
use crate::settings::FarFieldSettings;
use crate::tensor::{add_outer, grid_len, move_charges};
use crate::tree::{Tree, box_gap2};

/// The geometry of a far field over fixed centres: the tree, each cluster's Chebyshev grid and
/// proxy points. Built once; [`FarField::charges`] then takes any weights.
///
/// ```
/// use rbf_core::Kernel;
/// use rbf_far::{FarField, FarFieldSettings};
/// let centres: Vec<[f64; 3]> = (0..3000)
///     .map(|i| { let t = i as f64 * 0.01; [t.cos(), t.sin(), 0.3 * (3.0 * t).sin()] })
///     .collect();
/// let weights: Vec<f64> = (0..3000).map(|i| ((i * 37 % 101) as f64 - 50.0) / 50.0).collect();
/// let field = FarField::new(Kernel::Cubic, &centres, &FarFieldSettings::default());
/// let charges = field.charges(&weights).unwrap();
/// let x = [[0.1, 0.2, 0.3]];
/// let mut far = [0.0];
/// field.values(&charges, &x, &mut far).unwrap();
/// assert!(field.values(&charges, &x, &mut [0.0; 2]).is_err()); // one output per point
/// let direct: f64 = centres.iter().zip(&weights)
///     .map(|(c, w)| w * (0..3).map(|d| (x[0][d] - c[d]).powi(2)).sum::<f64>().powf(1.5))
///     .sum();
/// assert!((far[0] - direct).abs() < 1e-7 * weights.iter().map(|w| w.abs()).sum::<f64>());
/// ```
#[derive(Clone, Debug)]
pub struct FarField<const D: usize> {
    kernel: Kernel,
    settings: FarFieldSettings,
    /// The tree over the centres and each cluster's grid of proxies.
    clusters: Clusters<D>,
    /// The centres in the tree's order.
    centres: Vec<[f64; D]>,
    /// The interactions of the product at the centres themselves, found on its first use.
    self_plan: OnceLock<Plan>,
}

/// Targets from which [`FarField::values`] may take the dual traversal (if there are at least
/// as many as centres): below, few target clusters are large enough for a grid, and the
/// treecode's leaves of 512 targets share their interaction lists more widely. The targets'
/// grids have one point more per side than the sources': on the weights of a 10⁵-centre fit of
/// the peers' surface problem, at 3.7·10⁵ points within 0.03 of the surface, that took 3.6 s at
/// order 10 and 6.7 s at order 12 against 6.5 s and 8.9 s by the treecode, erring 7.0e-7 and
/// 2.9e-9 (at 1000 of them, against compensated direct sums) where the treecode erred 1.5e-6
/// and 7.4e-9; with grids as fine as the sources', 4.2e-6 and 4.5e-8. With fewer targets than
/// centres it lost: a render's 3.7·10⁵ band samples of a 10⁶-centre model took 21.2 s against
/// the treecode's 18.9 s (and those of the 10⁵-centre model 5.3 s against 6.1 s).
pub(crate) const DUAL_TARGETS: usize = 4096;

/// The weights of a [`FarField`]'s centres moved onto its proxies.
#[derive(Clone, Debug)]
pub struct Charges {
    /// The weights in the tree's order.
    weights: Vec<f64>,
    /// Each node's proxy charges (empty without a grid).
    proxy: Vec<Vec<f64>>,
}

impl<const D: usize> FarField<D> {
    /// The tree over `centres` and every cluster's grid.
    pub fn new(kernel: Kernel, centres: &[[f64; D]], settings: &FarFieldSettings) -> Self {
        let tree = Tree::new(centres, settings.leaf);
        let sorted: Vec<[f64; D]> = tree.order.iter().map(|&i| centres[i]).collect();
        let root = tree.nodes.first().map_or(1.0, |n| side(&n.lo, &n.hi));
        Self {
            kernel,
            settings: *settings,
            clusters: Clusters::over(tree, settings, root),
            centres: sorted,
            self_plan: OnceLock::new(),
        }
    }

    /// The number of centres.
    pub fn len(&self) -> usize {
        self.centres.len()
    }

    /// Whether there are no centres.
    pub fn is_empty(&self) -> bool {
        self.centres.is_empty()
    }

    /// The settings the field was built with.
    pub fn settings(&self) -> &FarFieldSettings {
        &self.settings
    }

    /// Moves `weights` (one per centre, in the caller's order) onto every cluster's proxies:
    /// leaves from their centres, parents from their children's proxies (interpolation along
    /// one axis at a time), deepest level first, each level on every core.
    /// A `weights` of another length than the centres is refused.
    pub fn charges(&self, weights: &[f64]) -> Result<Charges, LengthMismatch> {
        LengthMismatch::check("weights", self.len(), weights.len())?;
        let sorted: Vec<f64> = self
            .clusters
            .tree
            .order
            .iter()
            .map(|&i| weights[i])
            .collect();
        let mut proxy: Vec<Vec<f64>> = vec![Vec::new(); self.clusters.tree.nodes.len()];
        for level in self.clusters.levels.iter().rev() {
            let computed: Vec<(usize, Vec<f64>)> = level
                .par_iter()
                .filter(|&&n| self.clusters.grids[n].is_some())
                .map(|&n| (n, self.node_charges(n, &sorted, &proxy)))
                .collect();
            for (n, q) in computed {
                proxy[n] = q;
            }
        }
        Ok(Charges {
            weights: sorted,
            proxy,
        })
    }

    /// Refuses charges made by another field (their lengths differ from this one's).
    fn check_charges(&self, charges: &Charges) -> Result<(), LengthMismatch> {
        LengthMismatch::check("charges", self.len(), charges.weights.len())?;
        LengthMismatch::check(
            "charges",
            self.clusters.tree.nodes.len(),
            charges.proxy.len(),
        )
    }

    /// Node `n`'s proxy charges from its children's (or its own centres where a child has no
    /// grid, or `n` is a leaf).
    fn node_charges(&self, n: usize, weights: &[f64], proxy: &[Vec<f64>]) -> Vec<f64> {
        let Some(axes) = self.clusters.grids[n].as_ref() else {
            return Vec::new();
        };
        let mut q = vec![0.0; grid_len(axes)];
        let node = &self.clusters.tree.nodes[n];
        let parts: Vec<usize> = match node.children {
            Some((a, b)) => vec![a, b],
            None => vec![n],
        };
        let mut basis: [Vec<f64>; D] = core::array::from_fn(|d| vec![0.0; axes[d].points().len()]);
        for part in parts {
            match (&self.clusters.grids[part], part != n) {
                (Some(child), true) => {
                    let moved = move_charges(axes, child, &proxy[part]);
                    for (a, b) in q.iter_mut().zip(moved) {
                        *a += b;
                    }
                }
                _ => {
                    let p = &self.clusters.tree.nodes[part];
                    for i in p.start..p.end {
                        for d in 0..D {
                            axes[d].basis(self.centres[i][d], &mut basis[d]);
                        }
                        add_outer(&basis, weights[i], &mut q);
                    }
                }
            }
        }
        q
    }

    /// Σⱼ wⱼ φ(|xᵢ − cⱼ|) at every target (no affine part): by the treecode (each leaf of
    /// targets sums its near centres and far proxies), or, from 4096 targets and at least as
    /// many as centres, by a dual traversal of a tree over the targets with the field's own, far
    /// sums taken on grids over clusters of targets and interpolated to them.
    pub fn values(
        &self,
        charges: &Charges,
        targets: &[[f64; D]],
        out: &mut [f64],
    ) -> Result<(), LengthMismatch> {
        LengthMismatch::check("output", targets.len(), out.len())?;
        self.check_charges(charges)?;
        if self.takes_dual(targets.len()) {
            return self.dual_values(charges, targets, out);
        }
        let target_tree = Tree::new(targets, self.settings.target_leaf);
        let parts: Vec<(usize, Vec<f64>)> = target_tree
            .leaves()
            .par_iter()
            .map(|&leaf| {
                let node = &target_tree.nodes[leaf];
                let idx = target_tree.points_of(leaf);
                let points: Vec<[f64; D]> = idx.iter().map(|&i| targets[i]).collect();
                let mut v = vec![0.0; points.len()];
                self.leaf_values(charges, &node.lo, &node.hi, &points, &mut v)?;
                Ok((leaf, v))
            })
            .collect::<Result<_, LengthMismatch>>()?;
        for (leaf, v) in parts {
            for (&i, x) in target_tree.points_of(leaf).iter().zip(v) {
                out[i] = x;
            }
        }
        Ok(())
    }

    /// The dual traversal's sums at the targets of the target leaves `only` of `clusters` (every
    /// leaf if empty; a tree over `sorted`, the targets in its order), as [`evaluate`] gives them.
    fn dual_sums(
        &self,
        charges: &Charges,
        clusters: &Clusters<D>,
        sorted: &[[f64; D]],
        only: &[usize],
    ) -> Result<Vec<(usize, Vec<f64>)>, LengthMismatch> {
        let plan = Plan::above(clusters, &self.clusters, self.settings.theta, only);
        let all = clusters.tree.leaves();
        let leaves = if only.is_empty() { &all } else { only };
        evaluate(&plan, clusters, sorted, &self.weighted(charges), leaves)
    }

    /// Whether [`FarField::values`] at `targets` points takes the dual traversal: from
    /// [`DUAL_TARGETS`] points and at least as many as there are centres.
    fn takes_dual(&self, targets: usize) -> bool {
        targets >= DUAL_TARGETS.max(self.len())
    }

    /// A tree over `targets` with grids one point finer per side than the sources' (measured:
    /// see [`DUAL_TARGETS`]), and the targets in its order.
    fn target_clusters(&self, targets: &[[f64; D]]) -> (Clusters<D>, Vec<[f64; D]>) {
        let tree = Tree::new(targets, self.settings.leaf);
        let sorted: Vec<[f64; D]> = tree.order.iter().map(|&i| targets[i]).collect();
        let root = self
            .clusters
            .tree
            .nodes
            .first()
            .map_or(1.0, |n| side(&n.lo, &n.hi));
        let finer = FarFieldSettings {
            order: self.settings.order + 1,
            ..self.settings
        };
        (Clusters::over(tree, &finer, root), sorted)
    }

    /// [`FarField::values`] by a dual traversal of a tree over the targets with the field's own.
    fn dual_values(
        &self,
        charges: &Charges,
        targets: &[[f64; D]],
        out: &mut [f64],
    ) -> Result<(), LengthMismatch> {
        let (clusters, sorted) = self.target_clusters(targets);
        for (start, v) in self.dual_sums(charges, &clusters, &sorted, &[])? {
            for (&i, x) in clusters.tree.order[start..].iter().zip(v) {
                out[i] = x;
            }
        }
        Ok(())
    }

    /// The dual traversal's sums at about `count` of `targets` (every target of leaves spread
    /// over a tree over them, as [`FarField::values`] takes all of them): which targets, and
    /// the sums there.
    fn dual_sample(
        &self,
        charges: &Charges,
        targets: &[[f64; D]],
        count: usize,
    ) -> Result<(Vec<usize>, Vec<f64>), LengthMismatch> {
        let (clusters, sorted) = self.target_clusters(targets);
        let leaves = spread_leaves(&clusters.tree, count);
        let mut rows = Vec::new();
        let mut sums = Vec::new();
        for (start, v) in self.dual_sums(charges, &clusters, &sorted, &leaves)? {
            rows.extend_from_slice(&clusters.tree.order[start..start + v.len()]);
            sums.extend(v);
        }
        Ok((rows, sums))
    }

    /// Σⱼ wⱼ φ(|xᵢ − cⱼ|) and its gradient at every target (no affine part), by the treecode
    /// whatever their number (gradients read off target grids erred 20 times more, at order 10
    /// on 7·10⁴ points near a 10⁵-centre model's surface, and took as long).
    pub fn values_and_gradients(
        &self,
        charges: &Charges,
        targets: &[[f64; D]],
        values: &mut [f64],
        gradients: &mut [[f64; D]],
    ) -> Result<(), LengthMismatch> {
        LengthMismatch::check("values", targets.len(), values.len())?;
        LengthMismatch::check("gradients", targets.len(), gradients.len())?;
        self.check_charges(charges)?;
        let target_tree = Tree::new(targets, self.settings.target_leaf);
        let parts: Vec<(usize, Vec<f64>, Vec<[f64; D]>)> = target_tree
            .leaves()
            .par_iter()
            .map(|&leaf| {
                let node = &target_tree.nodes[leaf];
                let points: Vec<[f64; D]> = target_tree
                    .points_of(leaf)
                    .iter()
                    .map(|&i| targets[i])
                    .collect();
                let mut v = vec![0.0; points.len()];
                let mut g = vec![[0.0; D]; points.len()];
                self.leaf_values_and_gradients(
                    charges, &node.lo, &node.hi, &points, &mut v, &mut g,
                )?;
                Ok((leaf, v, g))
            })
            .collect::<Result<_, LengthMismatch>>()?;
        for (leaf, v, g) in parts {
            for ((&i, x), y) in target_tree.points_of(leaf).iter().zip(v).zip(g) {
                values[i] = x;
                gradients[i] = y;
            }
        }
        Ok(())
    }

    /// Σⱼ wⱼ φ(|cᵢ − cⱼ|) at every centre, in the caller's order: the product of the kernel
    /// matrix with the weights, by a dual traversal of the field's tree with itself (its
    /// interactions found on the first call and kept).
    pub fn self_values(&self, charges: &Charges, out: &mut [f64]) -> Result<(), LengthMismatch> {
        LengthMismatch::check("output", self.len(), out.len())?;
        self.check_charges(charges)?;
        let leaves = self.clusters.tree.leaves();
        for (start, v) in self.self_sums(charges, &leaves)? {
            for (&i, x) in self.clusters.tree.order[start..].iter().zip(v) {
                out[i] = x;
            }
        }
        Ok(())
    }

    /// The product at the centres of the field's `leaves`, by the plan kept for it.
    fn self_sums(
        &self,
        charges: &Charges,
        leaves: &[usize],
    ) -> Result<Vec<(usize, Vec<f64>)>, LengthMismatch> {
        let plan = self
            .self_plan
            .get_or_init(|| Plan::new(&self.clusters, &self.clusters, self.settings.theta));
        let sources = self.weighted(charges);
        evaluate(plan, &self.clusters, &self.centres, &sources, leaves)
    }

    /// The centres and proxies with what `charges` puts on them.
    fn weighted<'s>(&'s self, charges: &'s Charges) -> Weighted<'s, D> {
        Weighted {
            kernel: self.kernel,
            clusters: &self.clusters,
            centres: &self.centres,
            weights: &charges.weights,
            charges: &charges.proxy,
        }
    }

    /// [`FarField::self_values`] at the centres `rows` only (indices in the caller's order;
    /// `out[i]` for `rows[i]`), taking only the leaves that hold them. Rows out of range are
    /// refused.
    pub fn self_values_at(
        &self,
        charges: &Charges,
        rows: &[usize],
        out: &mut [f64],
    ) -> Result<(), LengthMismatch> {
        LengthMismatch::check("output", rows.len(), out.len())?;
        self.check_charges(charges)?;
        if let Some(&bad) = rows.iter().find(|&&r| r >= self.len()) {
            return Err(LengthMismatch {
                what: "rows",
                expected: self.len(),
                found: bad + 1,
            });
        }
        let order = &self.clusters.tree.order;
        let mut position = vec![0usize; order.len()];
        for (p, &i) in order.iter().enumerate() {
            position[i] = p;
        }
        let all = self.clusters.tree.leaves();
        let nodes = &self.clusters.tree.nodes;
        let leaf_of = |p: usize| all[all.partition_point(|&l| nodes[l].end <= p)];
        let mut leaves: Vec<usize> = rows.iter().map(|&r| leaf_of(position[r])).collect();
        leaves.sort_unstable();
        leaves.dedup();
        let mut at_position = vec![f64::NAN; order.len()];
        for (start, v) in self.self_sums(charges, &leaves)? {
            at_position[start..start + v.len()].copy_from_slice(&v);
        }
        for (o, &r) in out.iter_mut().zip(rows) {
            *o = at_position[position[r]];
        }
        Ok(())
    }

    /// About `count` rows (indices in the caller's order) at which to measure the product at
    /// the centres cheaply: every centre of leaves spread over the tree (the product is taken a
    /// leaf at a time, so whole leaves cost what single rows in them would).
    pub fn sample_rows(&self, count: usize) -> Vec<usize> {
        spread_leaves(&self.clusters.tree, count)
            .into_iter()
            .flat_map(|leaf| self.clusters.tree.points_of(leaf).iter().copied())
            .collect()
    }

    fn leaf_values(
        &self,
        charges: &Charges,
        lo: &[f64; D],
        hi: &[f64; D],
        points: &[[f64; D]],
        out: &mut [f64],
    ) -> Result<(), LengthMismatch> {
        out.fill(0.0);
        let mut part = vec![0.0; points.len()];
        for (c, w) in self.interactions(charges, lo, hi) {
            InterpolantView::new(self.kernel, c, w, 0.0, [0.0; D])?.values(points, &mut part)?;
            for (o, p) in out.iter_mut().zip(&part) {
                *o += p;
            }
        }
        Ok(())
    }

    fn leaf_values_and_gradients(
        &self,
        charges: &Charges,
        lo: &[f64; D],
        hi: &[f64; D],
        points: &[[f64; D]],
        values: &mut [f64],
        gradients: &mut [[f64; D]],
    ) -> Result<(), LengthMismatch> {
        values.fill(0.0);
        gradients.fill([0.0; D]);
        let (mut v, mut g) = (vec![0.0; points.len()], vec![[0.0; D]; points.len()]);
        for (c, w) in self.interactions(charges, lo, hi) {
            InterpolantView::new(self.kernel, c, w, 0.0, [0.0; D])?
                .values_and_gradients(points, &mut v, &mut g)?;
            for (o, p) in values.iter_mut().zip(&v) {
                *o += p;
            }
            for (o, p) in gradients.iter_mut().zip(&g) {
                for d in 0..D {
                    o[d] += p[d];
                }
            }
        }
        Ok(())
    }

    /// What targets in the box [lo, hi] see, as slices of centres (or proxies) with their
    /// weights (or charges): the centres of every cluster too close to the box, and the proxies
    /// of every cluster far enough (its longest side at most θ times its distance to the box).
    /// Neighbouring runs of centres are merged, so the slices are long and nothing is copied.
    fn interactions<'s>(
        &'s self,
        charges: &'s Charges,
        lo: &[f64; D],
        hi: &[f64; D],
    ) -> Vec<(&'s [[f64; D]], &'s [f64])> {
        let theta2 = self.settings.theta * self.settings.theta;
        let mut near: Vec<(usize, usize)> = Vec::new();
        let mut far = Vec::new();
        // The root, unless there are no centres at all.
        let mut stack: Vec<usize> = (0..self.clusters.tree.nodes.len().min(1)).collect();
        while let Some(n) = stack.pop() {
            let node = &self.clusters.tree.nodes[n];
            let direct = match (&self.clusters.grids[n], node.children) {
                (None, _) => true,
                _ if side(&node.lo, &node.hi).powi(2)
                    <= theta2 * box_gap2(&node.lo, &node.hi, lo, hi) =>
                {
                    far.push((
                        self.clusters.proxies[n].as_slice(),
                        charges.proxy[n].as_slice(),
                    ));
                    false
                }
                (Some(_), Some((a, b))) => {
                    // Left child first: runs of centres come out in order and merge.
                    stack.extend([b, a]);
                    false
                }
                (Some(_), None) => true,
            };
            if direct {
                match near.last_mut() {
                    Some(run) if run.1 == node.start => run.1 = node.end,
                    _ => near.push((node.start, node.end)),
                }
            }
        }
        near.into_iter()
            .map(|(a, b)| (&self.centres[a..b], &charges.weights[a..b]))
            .chain(far)
            .collect()
    }
}

/// Orders tried by [`calibrated`], lowest first.
const ORDERS: [usize; 5] = [8, 10, 12, 14, 16];

/// The far field of `weights` on `centres` at the lowest order whose largest error at sampled
/// `points`, against compensated direct sums, is at most `error` (absolute); with its charges
/// and that measured error. Both ways [`FarField::values`] takes sums are measured: the
/// treecode at up to 1000 points spread over `points`, and, where there are enough of them
/// for [`FarField::values`] to take it, the dual traversal at every point of leaves spread over
/// a tree over them (about 2000). `None`
/// if no order up to 16 is that accurate.
///
/// ```
/// use rbf_core::Kernel;
/// let centres: Vec<[f64; 3]> = (0..5000).map(|i| [i as f64 * 1e-3, (i % 7) as f64, 0.0]).collect();
/// let weights = vec![1e-3; 5000];
/// let points = [[0.5, 0.5, 0.5], [3.0, -1.0, 2.0]];
/// let (field, _, measured) = rbf_far::calibrated(Kernel::Cubic, &centres, &weights, &points, 1e-8).unwrap();
/// assert!(measured <= 1e-8 && field.settings().order >= 8);
/// ```
pub fn calibrated<const D: usize>(
    kernel: Kernel,
    centres: &[[f64; D]],
    weights: &[f64],
    points: &[[f64; D]],
    error: f64,
) -> Option<Calibrated<D>> {
    calibrated_with_coarse(kernel, centres, weights, points, error, error).0
}

/// A far field with its charges and the largest error measured for it.
pub type Calibrated<const D: usize> = (FarField<D>, Charges, f64);

/// [`calibrated`] within `error`, and, on the way, the lowest order within the looser
/// `coarse_error` when that order is lower (the orders are measured in turn, so the coarse
/// field costs no extra measurement).
pub(crate) fn calibrated_with_coarse<const D: usize>(
    kernel: Kernel,
    centres: &[[f64; D]],
    weights: &[f64],
    points: &[[f64; D]],
    error: f64,
    coarse_error: f64,
) -> (Option<Calibrated<D>>, Option<Calibrated<D>>) {
    let mut coarse = None;
    let exact = |at: &[[f64; D]]| {
        let mut sums = vec![0.0; at.len()];
        InterpolantView::new(kernel, centres, weights, 0.0, [0.0; D])
            .and_then(|f| f.par_values_compensated(at, &mut sums))
            .ok()
            .map(|_| sums)
    };
    let spread = SPREAD_POINTS.min(points.len());
    let sample: Vec<[f64; D]> = (0..spread)
        .map(|i| points[i * points.len() / spread])
        .collect();
    let Some(sample_sums) = exact(&sample) else {
        return (None, None);
    };
    // The dual traversal's rows are the same at every order (the tree over the points is).
    let mut dual: Option<(Vec<usize>, Vec<f64>)> = None;
    for order in ORDERS {
        let settings = FarFieldSettings {
            order,
            ..FarFieldSettings::default()
        };
        let field = FarField::new(kernel, centres, &settings);
        let Some((charges, mut measured)) = field.error_at(weights, &sample, &sample_sums) else {
            break;
        };
        if field.takes_dual(points.len()) {
            let Ok((rows, approx)) = field.dual_sample(&charges, points, DUAL_SAMPLE) else {
                break;
            };
            if dual.is_none() {
                let at: Vec<[f64; D]> = rows.iter().map(|&i| points[i]).collect();
                let Some(sums) = exact(&at) else { break };
                dual = Some((rows, sums));
            }
            let Some((_, sums)) = dual.as_ref() else {
                break;
            };
            measured = approx
                .iter()
                .zip(sums)
                .map(|(a, e)| (a - e).abs())
                .fold(measured, f64::max);
        }
        if measured <= error {
            return (Some((field, charges, measured)), coarse);
        }
        if coarse.is_none() && measured <= coarse_error {
            coarse = Some((field, charges, measured));
        }
    }
    (None, coarse)
}

/// Points at which [`calibrated`] measures the treecode.
const SPREAD_POINTS: usize = 1000;

/// About as many points at which [`calibrated`] measures the dual traversal (whole leaves).
const DUAL_SAMPLE: usize = 2000;

/// The far field whose product at the centres (as the iterative solver takes it:
/// [`FarField::self_values`]) errs at most `error` (absolute) on `weights` at the lowest order
/// above `above`, measured against compensated direct sums at rows of whole leaves spread over
/// the tree ([`FarField::sample_rows`], about `rows` of them); with that measured error. `None`
/// if no order up to 16 is that accurate.
///
/// ```
/// use rbf_core::Kernel;
/// let centres: Vec<[f64; 3]> = (0..5000).map(|i| [i as f64 * 1e-3, (i % 7) as f64, 0.0]).collect();
/// let weights = vec![1e-3; 5000];
/// let (field, measured) = rbf_far::calibrated_product(Kernel::Cubic, &centres, &weights, 1e-8, 0, 500).unwrap();
/// assert!(measured <= 1e-8 && field.settings().order >= 8);
/// ```
pub fn calibrated_product<const D: usize>(
    kernel: Kernel,
    centres: &[[f64; D]],
    weights: &[f64],
    error: f64,
    above: usize,
    rows: usize,
) -> Option<(FarField<D>, f64)> {
    let mut exact: Option<(Vec<usize>, Vec<f64>)> = None;
    for order in ORDERS.into_iter().filter(|&o| o > above) {
        let settings = FarFieldSettings {
            order,
            ..FarFieldSettings::default()
        };
        let field = FarField::new(kernel, centres, &settings);
        // Every order has the same tree (its leaves' size is the same), so the same rows.
        let (sample, sums) = match exact.take() {
            Some(e) => e,
            None => {
                let sample = field.sample_rows(rows);
                let points: Vec<[f64; D]> = sample.iter().map(|&i| centres[i]).collect();
                let mut sums = vec![0.0; sample.len()];
                InterpolantView::new(kernel, centres, weights, 0.0, [0.0; D])
                    .and_then(|f| f.par_values_compensated(&points, &mut sums))
                    .ok()?;
                (sample, sums)
            }
        };
        let measured = field.product_error(weights, &sample, &sums)?;
        if measured <= error {
            return Some((field, measured));
        }
        exact = Some((sample, sums));
    }
    None
}

impl<const D: usize> FarField<D> {
    /// The largest error of the product at the centres on `weights` ([`FarField::self_values`])
    /// at `rows` (the caller's order) against `exact` sums there; `None` on mismatched lengths
    /// or no rows.
    ///
    /// ```
    /// use rbf_core::{InterpolantView, Kernel};
    /// use rbf_far::{FarField, FarFieldSettings};
    /// let centres: Vec<[f64; 3]> = (0..3000).map(|i| [i as f64 * 1e-3, (i % 7) as f64, 0.0]).collect();
    /// let weights = vec![1e-3; 3000];
    /// let field = FarField::new(Kernel::Cubic, &centres, &FarFieldSettings { order: 12, ..Default::default() });
    /// let rows = field.sample_rows(300);
    /// let at: Vec<[f64; 3]> = rows.iter().map(|&i| centres[i]).collect();
    /// let mut exact = vec![0.0; rows.len()];
    /// InterpolantView::new(Kernel::Cubic, &centres, &weights, 0.0, [0.0; 3]).unwrap()
    ///     .values(&at, &mut exact).unwrap();
    /// assert!(field.product_error(&weights, &rows, &exact).unwrap() < 1e-6);
    /// ```
    pub fn product_error(&self, weights: &[f64], rows: &[usize], exact: &[f64]) -> Option<f64> {
        // No rows measure nothing: no error is claimed.
        if rows.is_empty() || exact.len() != rows.len() {
            return None;
        }
        let charges = self.charges(weights).ok()?;
        let mut approx = vec![0.0; rows.len()];
        self.self_values_at(&charges, rows, &mut approx).ok()?;
        Some(
            approx
                .iter()
                .zip(exact)
                .map(|(a, e)| (a - e).abs())
                .fold(0.0, f64::max),
        )
    }
}

impl<const D: usize> FarField<D> {
    /// The charges of `weights` and the largest error of their sums at the `sample` points
    /// against `exact` values there (as [`calibrated`] measures); `None` on mismatched lengths.
    ///
    /// ```
    /// use rbf_core::{InterpolantView, Kernel};
    /// use rbf_far::{FarField, FarFieldSettings};
    /// let centres: Vec<[f64; 3]> = (0..3000).map(|i| [i as f64 * 1e-3, (i % 7) as f64, 0.0]).collect();
    /// let weights = vec![1e-3; 3000];
    /// let sample = [[0.5, 0.5, 0.5], [3.0, -1.0, 2.0]];
    /// let mut exact = [0.0; 2];
    /// InterpolantView::new(Kernel::Cubic, &centres, &weights, 0.0, [0.0; 3]).unwrap()
    ///     .values(&sample, &mut exact).unwrap();
    /// let field = FarField::new(Kernel::Cubic, &centres, &FarFieldSettings { order: 12, ..Default::default() });
    /// let (_, error) = field.error_at(&weights, &sample, &exact).unwrap();
    /// assert!(error < 1e-6);
    /// ```
    pub fn error_at(
        &self,
        weights: &[f64],
        sample: &[[f64; D]],
        exact: &[f64],
    ) -> Option<(Charges, f64)> {
        let charges = self.charges(weights).ok()?;
        let mut approx = vec![0.0; sample.len()];
        self.values(&charges, sample, &mut approx).ok()?;
        if exact.len() != sample.len() {
            return None;
        }
        let error = approx
            .iter()
            .zip(exact)
            .map(|(a, e)| (a - e).abs())
            .fold(0.0, f64::max);
        Some((charges, error))
    }
}

/// Leaves spread evenly over `tree` holding at least `count` points between them (all of them if
/// there are fewer).
fn spread_leaves<const D: usize>(tree: &Tree<D>, count: usize) -> Vec<usize> {
    let leaves = tree.leaves();
    if leaves.is_empty() {
        return Vec::new();
    }
    // Leaves hold between half the leaf size and all of it: as many as hold `count` on
    // average, spread evenly, then more from a second pass if they fell short.
    let average = (tree.order.len() / leaves.len()).max(1);
    let wanted = count.div_ceil(average).clamp(1, leaves.len());
    let mut taken = vec![false; leaves.len()];
    let (mut chosen, mut held) = (Vec::new(), 0);
    let spread = (0..wanted).map(|i| i * leaves.len() / wanted);
    for i in spread.chain(0..leaves.len()) {
        if held >= count {
            break;
        }
        if !std::mem::replace(&mut taken[i], true) {
            held += tree.points_of(leaves[i]).len();
            chosen.push(leaves[i]);
        }
    }
    chosen
}
