//! Sums Σⱼ wⱼ φ(|x − cⱼ|) over many centres at many points, with the far field of every cluster
//! of centres replaced by charges on a tensor grid of Chebyshev points over its box: a
//! barycentric Lagrange treecode (Wang, Tlupova & Krasny, "A kernel-independent treecode based
//! on barycentric Lagrange interpolation", Commun. Comput. Phys. 28, 2020), with targets taken a
//! leaf at a time so that each leaf's near centres and far proxies go through rbf-core's
//! vectorized evaluator in one pass.

use rayon::prelude::*;
use rbf_core::{InterpolantView, Kernel, LengthMismatch};

use crate::chebyshev::Axis;
use crate::settings::FarFieldSettings;
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
    tree: Tree<D>,
    /// The centres in the tree's order.
    centres: Vec<[f64; D]>,
    /// Each node's Chebyshev axes, or `None` where the node has no more centres than proxies
    /// (its centres are then always summed directly).
    grids: Vec<Option<[Axis; D]>>,
    /// Each node's proxy points (empty without a grid), row-major over its axes.
    proxies: Vec<Vec<[f64; D]>>,
    /// Nodes by depth, the root's level first.
    levels: Vec<Vec<usize>>,
}

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
        let grids: Vec<Option<[Axis; D]>> = tree
            .nodes
            .iter()
            .map(|node| {
                let order = settings.order_for(root, side(&node.lo, &node.hi));
                let sizes = settings.grid_sizes(order, &node.lo, &node.hi);
                let count: usize = sizes.iter().product();
                (count < node.end - node.start)
                    .then(|| core::array::from_fn(|d| Axis::new(node.lo[d], node.hi[d], sizes[d])))
            })
            .collect();
        let proxies = grids
            .iter()
            .map(|g| g.as_ref().map_or_else(Vec::new, grid_points))
            .collect();
        let mut depth = vec![0usize; tree.nodes.len()];
        let mut levels: Vec<Vec<usize>> = Vec::new();
        for (i, node) in tree.nodes.iter().enumerate() {
            if levels.len() <= depth[i] {
                levels.push(Vec::new());
            }
            levels[depth[i]].push(i);
            if let Some((a, b)) = node.children {
                depth[a] = depth[i] + 1;
                depth[b] = depth[i] + 1;
            }
        }
        Self {
            kernel,
            settings: *settings,
            tree,
            centres: sorted,
            grids,
            proxies,
            levels,
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
        let sorted: Vec<f64> = self.tree.order.iter().map(|&i| weights[i]).collect();
        let mut proxy: Vec<Vec<f64>> = vec![Vec::new(); self.tree.nodes.len()];
        for level in self.levels.iter().rev() {
            let computed: Vec<(usize, Vec<f64>)> = level
                .par_iter()
                .filter(|&&n| self.grids[n].is_some())
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
        LengthMismatch::check("charges", self.tree.nodes.len(), charges.proxy.len())
    }

    /// Node `n`'s proxy charges from its children's (or its own centres where a child has no
    /// grid, or `n` is a leaf).
    fn node_charges(&self, n: usize, weights: &[f64], proxy: &[Vec<f64>]) -> Vec<f64> {
        let Some(axes) = self.grids[n].as_ref() else {
            return Vec::new();
        };
        let mut q = vec![0.0; grid_len(axes)];
        let node = &self.tree.nodes[n];
        let parts: Vec<usize> = match node.children {
            Some((a, b)) => vec![a, b],
            None => vec![n],
        };
        let mut basis: [Vec<f64>; D] = core::array::from_fn(|d| vec![0.0; axes[d].points().len()]);
        for part in parts {
            match (&self.grids[part], part != n) {
                (Some(child), true) => {
                    let moved = interpolate_grid(axes, child, &proxy[part]);
                    for (a, b) in q.iter_mut().zip(moved) {
                        *a += b;
                    }
                }
                _ => {
                    let p = &self.tree.nodes[part];
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

    /// Σⱼ wⱼ φ(|xᵢ − cⱼ|) at every target (no affine part).
    pub fn values(
        &self,
        charges: &Charges,
        targets: &[[f64; D]],
        out: &mut [f64],
    ) -> Result<(), LengthMismatch> {
        LengthMismatch::check("output", targets.len(), out.len())?;
        self.check_charges(charges)?;
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

    /// Σⱼ wⱼ φ(|xᵢ − cⱼ|) and its gradient at every target (no affine part).
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
    /// matrix with the weights, the targets grouped by the field's own leaves.
    pub fn self_values(&self, charges: &Charges, out: &mut [f64]) -> Result<(), LengthMismatch> {
        LengthMismatch::check("output", self.len(), out.len())?;
        self.check_charges(charges)?;
        let leaves = self.tree.leaves();
        let parts: Vec<(usize, Vec<f64>)> = leaves
            .par_iter()
            .map(|&leaf| {
                let node = &self.tree.nodes[leaf];
                let points = &self.centres[node.start..node.end];
                let mut v = vec![0.0; points.len()];
                self.leaf_values(charges, &node.lo, &node.hi, points, &mut v)?;
                Ok((leaf, v))
            })
            .collect::<Result<_, LengthMismatch>>()?;
        for (leaf, v) in parts {
            for (&i, x) in self.tree.points_of(leaf).iter().zip(v) {
                out[i] = x;
            }
        }
        Ok(())
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
        let mut stack: Vec<usize> = (0..self.tree.nodes.len().min(1)).collect();
        while let Some(n) = stack.pop() {
            let node = &self.tree.nodes[n];
            let direct = match (&self.grids[n], node.children) {
                (None, _) => true,
                _ if side(&node.lo, &node.hi).powi(2)
                    <= theta2 * box_gap2(&node.lo, &node.hi, lo, hi) =>
                {
                    far.push((self.proxies[n].as_slice(), charges.proxy[n].as_slice()));
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

/// The longest side of the box [lo, hi].
fn side<const D: usize>(lo: &[f64; D], hi: &[f64; D]) -> f64 {
    (0..D).map(|d| hi[d] - lo[d]).fold(0.0, f64::max)
}

/// Orders tried by [`calibrated`], lowest first.
const ORDERS: [usize; 5] = [8, 10, 12, 14, 16];

/// The far field of `weights` on `centres` at the lowest order whose largest error at the
/// `sample` points, against compensated direct sums, is at most `error` (absolute); with its
/// charges and that measured error. `None` if no order up to 16 is that accurate.
///
/// ```
/// use rbf_core::Kernel;
/// let centres: Vec<[f64; 3]> = (0..5000).map(|i| [i as f64 * 1e-3, (i % 7) as f64, 0.0]).collect();
/// let weights = vec![1e-3; 5000];
/// let sample = [[0.5, 0.5, 0.5], [3.0, -1.0, 2.0]];
/// let (field, _, measured) = rbf_far::calibrated(Kernel::Cubic, &centres, &weights, &sample, 1e-8).unwrap();
/// assert!(measured <= 1e-8 && field.settings().order >= 8);
/// ```
pub fn calibrated<const D: usize>(
    kernel: Kernel,
    centres: &[[f64; D]],
    weights: &[f64],
    sample: &[[f64; D]],
    error: f64,
) -> Option<(FarField<D>, Charges, f64)> {
    calibrated_above(kernel, centres, weights, sample, error, 0)
}

/// As [`calibrated`], trying only orders above `above` (a far field found less accurate than
/// needed gives way to a higher order).
///
/// ```
/// use rbf_core::Kernel;
/// let centres: Vec<[f64; 3]> = (0..5000).map(|i| [i as f64 * 1e-3, (i % 7) as f64, 0.0]).collect();
/// let weights = vec![1e-3; 5000];
/// let sample = [[0.5, 0.5, 0.5], [3.0, -1.0, 2.0]];
/// let (field, _, _) = rbf_far::calibrated_above(Kernel::Cubic, &centres, &weights, &sample, 1.0, 12).unwrap();
/// assert_eq!(field.settings().order, 14);
/// ```
pub fn calibrated_above<const D: usize>(
    kernel: Kernel,
    centres: &[[f64; D]],
    weights: &[f64],
    sample: &[[f64; D]],
    error: f64,
    above: usize,
) -> Option<(FarField<D>, Charges, f64)> {
    let mut exact = vec![0.0; sample.len()];
    InterpolantView::new(kernel, centres, weights, 0.0, [0.0; D])
        .and_then(|f| f.par_values_compensated(sample, &mut exact))
        .ok()?;
    for order in ORDERS.into_iter().filter(|&o| o > above) {
        let settings = FarFieldSettings {
            order,
            ..FarFieldSettings::default()
        };
        let field = FarField::new(kernel, centres, &settings);
        let (charges, measured) = field.error_at(weights, sample, &exact)?;
        if measured <= error {
            return Some((field, charges, measured));
        }
    }
    None
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

fn grid_len<const D: usize>(axes: &[Axis; D]) -> usize {
    axes.iter().map(|a| a.points().len()).product()
}

/// The grid's points, row-major (the last axis fastest).
fn grid_points<const D: usize>(axes: &[Axis; D]) -> Vec<[f64; D]> {
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
fn add_outer<const D: usize>(basis: &[Vec<f64>; D], w: f64, q: &mut [f64]) {
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

/// Charges on the grid `from` moved to the grid `to`: one axis at a time, q ← Aₐ q along axis d.
fn interpolate_grid<const D: usize>(to: &[Axis; D], from: &[Axis; D], q: &[f64]) -> Vec<f64> {
    let mut dims: [usize; D] = core::array::from_fn(|d| from[d].points().len());
    let mut t = q.to_vec();
    for d in 0..D {
        let a = to[d].matrix_from(&from[d]);
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
