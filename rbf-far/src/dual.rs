//! Far sums by a dual tree traversal (after Wilson, Vaughn & Krasny's barycentric Lagrange dual
//! tree traversal, "A GPU-accelerated fast multipole method based on barycentric Lagrange
//! interpolation and dual tree traversal", Comput. Phys. Commun. 265, 2021): pairs of a target
//! cluster and a source cluster are walked down together, and each pair far enough apart
//! interacts in whichever of four ways costs the fewest kernel evaluations:
//!
//! - targets with centres (direct),
//! - targets with the source cluster's proxies (the treecode's way),
//! - the target cluster's grid points with centres, or with proxies: far sums taken once at a
//!   grid over the targets, then handed down the target tree by interpolation and read off at
//!   every target.
//!
//! The last two serve every target of a large cluster at the cost of its grid, so the kernel
//! evaluations per target stay about constant as the model grows.

use rayon::prelude::*;
use rbf_core::{InterpolantView, Kernel, LengthMismatch};

use crate::clusters::Clusters;
use crate::tensor::{contract, interpolate_values};
use crate::tree::box_gap2;

/// What a source cluster contributes: its centres with their weights (a run of the sorted
/// centres), or its proxies with their charges.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Source {
    Centres(usize, usize),
    Proxies(usize),
}

/// The interactions of every target cluster, found once for a pair of trees.
#[derive(Clone, Debug)]
pub(crate) struct Plan {
    /// Sources summed at a target cluster's own targets (every target below it).
    at_targets: Vec<Vec<Source>>,
    /// Sources summed at a target cluster's grid points.
    at_grid: Vec<Vec<Source>>,
    /// Whether a target cluster's grid holds far sums (its own, or handed down).
    has_local: Vec<bool>,
}

impl Plan {
    /// Walks the target and source trees down together from their roots. A pair whose boxes
    /// are apart by at least their longest side over θ interacts in the cheapest allowed way;
    /// a pair of leaves too close, directly; otherwise the larger cluster is split.
    pub(crate) fn new<const D: usize>(
        targets: &Clusters<D>,
        sources: &Clusters<D>,
        theta: f64,
    ) -> Self {
        Self::above(targets, sources, theta, &[])
    }

    /// As [`Plan::new`], for the targets of the target `leaves` only (all of them if empty):
    /// pairs with a target cluster above none of them are dropped.
    pub(crate) fn above<const D: usize>(
        targets: &Clusters<D>,
        sources: &Clusters<D>,
        theta: f64,
        leaves: &[usize],
    ) -> Self {
        let needed = needed_by(targets, leaves);
        let t_nodes = targets.tree.nodes.len();
        let mut plan = Self {
            at_targets: vec![Vec::new(); t_nodes],
            at_grid: vec![Vec::new(); t_nodes],
            has_local: vec![false; t_nodes],
        };
        if t_nodes == 0 || sources.tree.nodes.is_empty() {
            return plan;
        }
        let theta2 = theta * theta;
        let mut stack = vec![(0usize, 0usize)];
        while let Some((t, s)) = stack.pop() {
            if !needed.is_empty() && !needed[t] {
                continue;
            }
            let (tn, sn) = (&targets.tree.nodes[t], &sources.tree.nodes[s]);
            let gap2 = box_gap2(&tn.lo, &tn.hi, &sn.lo, &sn.hi);
            let (t_side, s_side) = (targets.side(t), sources.side(s));
            let t_apart = t_side * t_side <= theta2 * gap2;
            let s_apart = s_side * s_side <= theta2 * gap2;
            let (nt, ns) = (targets.count(t), sources.count(s));
            let (pt, ps) = (targets.proxies[t].len(), sources.proxies[s].len());
            let (t_grid, s_grid) = (targets.grids[t].is_some(), sources.grids[s].is_some());
            let (t_leaf, s_leaf) = (tn.children.is_none(), sn.children.is_none());
            let centres = Source::Centres(sn.start, sn.end);
            // The ways allowed, with their kernel evaluations (a grid exists only where it has
            // fewer points than its cluster, so a proxy way beats the direct one it replaces).
            let ways = [
                ((t_apart && s_apart) || (t_leaf && s_leaf)).then_some((nt * ns, false, centres)),
                (s_apart && s_grid).then_some((nt * ps, false, Source::Proxies(s))),
                (t_apart && t_grid).then_some((pt * ns, true, centres)),
                (t_apart && s_apart && t_grid && s_grid).then_some((
                    pt * ps,
                    true,
                    Source::Proxies(s),
                )),
            ];
            // Apart on both sides, or one side cannot be split and the other is apart
            // enough for its own way: interact; else split.
            let settle = (t_apart && s_apart)
                || (t_leaf && s_leaf)
                || (t_leaf && s_apart && s_grid)
                || (s_leaf && t_apart && t_grid);
            if let Some(&(_, on_grid, source)) =
                ways.iter().flatten().filter(|_| settle).min_by_key(|w| w.0)
            {
                if on_grid {
                    push_merged(&mut plan.at_grid[t], source);
                    plan.has_local[t] = true;
                } else {
                    push_merged(&mut plan.at_targets[t], source);
                }
                continue;
            }
            let split_target = match (tn.children, sn.children) {
                (Some(_), None) => true,
                (None, _) => false,
                (Some(_), Some(_)) => t_side >= s_side,
            };
            match (split_target, tn.children, sn.children) {
                (true, Some((a, b)), _) => stack.extend([(a, s), (b, s)]),
                // The left child popped first: a cluster's runs of centres come in order and
                // merge as they come (with θ = 0 nothing is ever apart, and every pair of
                // leaves would otherwise be kept apart).
                (false, _, Some((a, b))) => stack.extend([(t, b), (t, a)]),
                // Both leaves: settled above.
                _ => {}
            }
        }
        for list in &mut plan.at_targets {
            merge_runs(list);
        }
        for list in &mut plan.at_grid {
            merge_runs(list);
        }
        // Far sums flow down from a cluster with a grid to each child with one.
        for level in &targets.levels {
            for &t in level {
                if targets.parent[t].is_some_and(|p| plan.has_local[p])
                    && targets.grids[t].is_some()
                {
                    plan.has_local[t] = true;
                }
            }
        }
        plan
    }
}

/// Whether each target cluster is a leaf of `leaves` or above one (empty: `leaves` is).
fn needed_by<const D: usize>(targets: &Clusters<D>, leaves: &[usize]) -> Vec<bool> {
    if leaves.is_empty() {
        return Vec::new();
    }
    let mut needed = vec![false; targets.tree.nodes.len()];
    for &leaf in leaves {
        let mut at = Some(leaf);
        while let Some(t) = at.filter(|&t| !needed[t]) {
            needed[t] = true;
            at = targets.parent[t];
        }
    }
    needed
}

/// Appends `source`, joined to the last run of centres if it follows on from it.
fn push_merged(list: &mut Vec<Source>, source: Source) {
    match (list.last_mut(), source) {
        (Some(Source::Centres(_, end)), Source::Centres(a, b)) if *end == a => *end = b,
        _ => list.push(source),
    }
}

/// Sorts runs of centres and joins those that meet; proxies stay as they are.
fn merge_runs(list: &mut Vec<Source>) {
    list.sort_unstable_by_key(|s| match *s {
        Source::Centres(a, _) => (0, a),
        Source::Proxies(n) => (1, n),
    });
    let mut merged: Vec<Source> = Vec::with_capacity(list.len());
    for &s in list.iter() {
        match (merged.last_mut(), s) {
            (Some(Source::Centres(_, end)), Source::Centres(a, b)) if *end == a => *end = b,
            _ => merged.push(s),
        }
    }
    *list = merged;
}

/// The sources and what they carry.
pub(crate) struct Weighted<'a, const D: usize> {
    pub(crate) kernel: Kernel,
    pub(crate) clusters: &'a Clusters<D>,
    /// The centres in the tree's order, and their weights.
    pub(crate) centres: &'a [[f64; D]],
    pub(crate) weights: &'a [f64],
    /// Each cluster's proxy charges.
    pub(crate) charges: &'a [Vec<f64>],
}

impl<const D: usize> Weighted<'_, D> {
    /// out += Σ over `sources` at `points`; `part` is scratch.
    fn add(
        &self,
        sources: &[Source],
        points: &[[f64; D]],
        part: &mut Vec<f64>,
        out: &mut [f64],
    ) -> Result<(), LengthMismatch> {
        part.resize(points.len(), 0.0);
        for &source in sources {
            let (c, w) = match source {
                Source::Centres(a, b) => (&self.centres[a..b], &self.weights[a..b]),
                Source::Proxies(n) => (
                    self.clusters.proxies[n].as_slice(),
                    self.charges[n].as_slice(),
                ),
            };
            InterpolantView::new(self.kernel, c, w, 0.0, [0.0; D])?.values(points, part)?;
            for (o, p) in out.iter_mut().zip(part.iter()) {
                *o += p;
            }
        }
        Ok(())
    }
}

/// The sums of `sources` at the targets of the target `leaves` (`points` are every target, in
/// the target tree's order), as `plan` says: for each leaf, the position of its first target
/// and the sums at its targets. Far sums are taken only on the grids the leaves need.
pub(crate) fn evaluate<const D: usize>(
    plan: &Plan,
    targets: &Clusters<D>,
    points: &[[f64; D]],
    sources: &Weighted<'_, D>,
    leaves: &[usize],
) -> Result<Vec<(usize, Vec<f64>)>, LengthMismatch> {
    let nodes = targets.tree.nodes.len();
    LengthMismatch::check("targets", targets.tree.order.len(), points.len())?;
    if leaves.is_empty() {
        return Ok(Vec::new());
    }
    let needed = needed_by(targets, leaves);
    // Far sums at the grid points of every needed target cluster that has its own.
    let mut local: Vec<Vec<f64>> = vec![Vec::new(); nodes];
    let own: Vec<(usize, Vec<f64>)> = (0..nodes)
        .into_par_iter()
        .filter(|&t| needed[t] && !plan.at_grid[t].is_empty())
        .map(|t| {
            let grid = &targets.proxies[t];
            let mut v = vec![0.0; grid.len()];
            sources.add(&plan.at_grid[t], grid, &mut Vec::new(), &mut v)?;
            Ok((t, v))
        })
        .collect::<Result<_, LengthMismatch>>()?;
    for (t, v) in own {
        local[t] = v;
    }
    // Handed down, a level at a time.
    for level in targets.levels.iter().skip(1) {
        let inherited: Vec<(usize, Vec<f64>)> = level
            .par_iter()
            .filter(|&&t| needed[t])
            .filter_map(|&t| {
                let p = targets.parent[t]?;
                let (to, from) = (targets.grids[t].as_ref()?, targets.grids[p].as_ref()?);
                plan.has_local[p].then(|| (t, interpolate_values(to, from, &local[p])))
            })
            .collect();
        for (t, v) in inherited {
            if local[t].is_empty() {
                local[t] = v;
            } else {
                for (a, b) in local[t].iter_mut().zip(v) {
                    *a += b;
                }
            }
        }
    }
    // Every leaf: what its clusters sum at its targets, and the far sums read off the grids.
    leaves
        .par_iter()
        .map(|&leaf| {
            let node = &targets.tree.nodes[leaf];
            let at = &points[node.start..node.end];
            let mut v = vec![0.0; at.len()];
            let mut path = vec![leaf];
            let mut up = targets.parent[leaf];
            while let Some(p) = up {
                path.push(p);
                up = targets.parent[p];
            }
            path.reverse();
            let mut part = Vec::new();
            let mut scratch = Vec::new();
            for (i, &t) in path.iter().enumerate() {
                sources.add(&plan.at_targets[t], at, &mut part, &mut v)?;
                let next_has_grid = path.get(i + 1).is_some_and(|&c| targets.grids[c].is_some());
                if let (true, false, Some(axes)) =
                    (plan.has_local[t], next_has_grid, targets.grids[t].as_ref())
                {
                    let mut basis: [Vec<f64>; D] =
                        core::array::from_fn(|d| vec![0.0; axes[d].points().len()]);
                    for (o, x) in v.iter_mut().zip(at) {
                        for d in 0..D {
                            axes[d].basis(x[d], &mut basis[d]);
                        }
                        *o += contract(&basis, &local[t], &mut scratch);
                    }
                }
            }
            Ok((node.start, v))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::FarFieldSettings;
    use crate::tree::Tree;

    /// Points on a wavy sheet, weights that cancel in neighbouring pairs.
    fn sheet(n: usize) -> (Vec<[f64; 3]>, Vec<f64>) {
        let side = (n as f64).sqrt().ceil() as usize;
        let points = (0..n)
            .map(|i| {
                let (u, v) = (
                    (i % side) as f64 / side as f64,
                    (i / side) as f64 / side as f64,
                );
                [u, v, 0.1 * (6.0 * u).sin() * (4.0 * v).cos()]
            })
            .collect();
        let weights = (0..n)
            .map(|i| if i % 2 == 0 { 1.0 } else { -1.0 } * (1.0 + (i as f64 * 0.7).sin().abs()))
            .collect();
        (points, weights)
    }

    #[test]
    fn with_nothing_apart_every_leaf_sums_all_centres_in_one_run() {
        // θ = 0: no pair is ever apart, so the plan is direct sums, one merged run a leaf.
        let (points, _) = sheet(5000);
        let settings = FarFieldSettings {
            theta: 0.0,
            leaf: 16,
            ..FarFieldSettings::default()
        };
        let clusters = Clusters::over(Tree::new(&points, settings.leaf), &settings, 1.0);
        let plan = Plan::new(&clusters, &clusters, settings.theta);
        for t in clusters.tree.leaves() {
            assert_eq!(
                plan.at_targets[t],
                vec![Source::Centres(0, 5000)],
                "leaf {t}"
            );
        }
        assert!(plan.at_grid.iter().all(Vec::is_empty));
        assert!(
            plan.at_targets.iter().filter(|l| !l.is_empty()).count()
                == clusters.tree.leaves().len()
        );
    }

    #[test]
    fn every_kind_of_interaction_is_used_and_the_sums_match_direct_ones() {
        let (points, weights) = sheet(20_000);
        let settings = FarFieldSettings {
            order: 10,
            leaf: 32,
            ..FarFieldSettings::default()
        };
        let tree = Tree::new(&points, settings.leaf);
        let sorted: Vec<[f64; 3]> = tree.order.iter().map(|&i| points[i]).collect();
        let sorted_w: Vec<f64> = tree.order.iter().map(|&i| weights[i]).collect();
        let clusters = Clusters::over(tree, &settings, 1.0);
        let plan = Plan::new(&clusters, &clusters, settings.theta);
        let count = |list: &[Vec<Source>], proxies: bool| {
            list.iter()
                .flatten()
                .filter(|s| matches!(s, Source::Proxies(_)) == proxies)
                .count()
        };
        assert!(count(&plan.at_targets, false) > 0, "targets with centres");
        assert!(count(&plan.at_targets, true) > 0, "targets with proxies");
        assert!(count(&plan.at_grid, false) > 0, "grids with centres");
        assert!(count(&plan.at_grid, true) > 0, "grids with proxies");
        // Charges on every grid, as the far field makes them.
        let field = crate::FarField::new(Kernel::Cubic, &points, &settings);
        let charges = field.charges(&weights).unwrap();
        let mut far = vec![0.0; points.len()];
        field.self_values(&charges, &mut far).unwrap();
        let direct =
            InterpolantView::new(Kernel::Cubic, &sorted, &sorted_w, 0.0, [0.0; 3]).unwrap();
        let scale: f64 = weights.iter().map(|w| w.abs()).sum::<f64>() * 8.0;
        for i in (0..points.len()).step_by(97) {
            let exact = direct.value(&points[i]);
            assert!(
                (far[i] - exact).abs() <= 1e-9 * scale,
                "{i}: {} {exact}",
                far[i]
            );
        }
    }
}
