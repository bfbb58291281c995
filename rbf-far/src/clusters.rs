//! A tree over points with a Chebyshev grid on every cluster large enough to gain from one:
//! the source side of a far field (proxies that carry the centres' weights) and, for products
//! by a dual traversal, the target side too (grid points where far sums are taken and then
//! interpolated to the targets).

use crate::chebyshev::Axis;
use crate::settings::FarFieldSettings;
use crate::tensor::grid_points;
use crate::tree::Tree;

/// The tree and each cluster's grid.
#[derive(Clone, Debug)]
pub(crate) struct Clusters<const D: usize> {
    pub(crate) tree: Tree<D>,
    /// Each node's Chebyshev axes, or `None` where the node has no more points than a grid
    /// would have (its points then always stand for themselves).
    pub(crate) grids: Vec<Option<[Axis; D]>>,
    /// Each node's grid points (empty without a grid), row-major over its axes.
    pub(crate) proxies: Vec<Vec<[f64; D]>>,
    /// Nodes by depth, the root's level first.
    pub(crate) levels: Vec<Vec<usize>>,
    /// Each node's parent (`None` for the root).
    pub(crate) parent: Vec<Option<usize>>,
}

impl<const D: usize> Clusters<D> {
    /// The grids of `tree`'s clusters, their orders set by `settings` relative to a cluster of
    /// side `root_side` (the source tree's root: what a grid errs scales with the sources'
    /// extent, whichever side it is on).
    pub(crate) fn over(tree: Tree<D>, settings: &FarFieldSettings, root_side: f64) -> Self {
        let grids: Vec<Option<[Axis; D]>> = tree
            .nodes
            .iter()
            .map(|node| {
                let order = settings.order_for(root_side, side(&node.lo, &node.hi));
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
        let mut parent = vec![None; tree.nodes.len()];
        let mut levels: Vec<Vec<usize>> = Vec::new();
        for (i, node) in tree.nodes.iter().enumerate() {
            if levels.len() <= depth[i] {
                levels.push(Vec::new());
            }
            levels[depth[i]].push(i);
            if let Some((a, b)) = node.children {
                for c in [a, b] {
                    depth[c] = depth[i] + 1;
                    parent[c] = Some(i);
                }
            }
        }
        Self {
            tree,
            grids,
            proxies,
            levels,
            parent,
        }
    }

    /// The longest side of node `n`'s box.
    pub(crate) fn side(&self, n: usize) -> f64 {
        let node = &self.tree.nodes[n];
        side(&node.lo, &node.hi)
    }

    /// The number of points under node `n`.
    pub(crate) fn count(&self, n: usize) -> usize {
        self.tree.nodes[n].end - self.tree.nodes[n].start
    }
}

/// The longest side of the box [lo, hi].
pub(crate) fn side<const D: usize>(lo: &[f64; D], hi: &[f64; D]) -> f64 {
    (0..D).map(|d| hi[d] - lo[d]).fold(0.0, f64::max)
}
