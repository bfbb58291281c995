//! A bounding hierarchy of oriented area elements (a mesh's triangles, a scan's points taken as
//! small patches of surface), each cluster with the far-field expansion of its solid angle to
//! second order (after Barill et al. 2018): what winding numbers are summed through, exactly
//! for near elements and by expansion for far clusters.

use rbf_core::vec3::{dot, norm, sub};

/// A node of the hierarchy: its elements are `order[start..end]`.
struct Node {
    start: usize,
    end: usize,
    /// Children, or none for a leaf.
    children: Option<(usize, usize)>,
    /// Σ area vectors.
    area: [f64; 3],
    /// Area-weighted centroid.
    centre: [f64; 3],
    /// Σ area vector ⊗ (element centroid − centre), for the second-order term.
    moment: [[f64; 3]; 3],
    /// Largest distance from `centre` to a point of the node's elements.
    radius: f64,
}

/// Elements per leaf.
const LEAF: usize = 8;

/// Where a cluster's expansion stands in for its elements, in radii of the cluster from its
/// centre to the query: closer in, its elements are summed exactly.
#[derive(Clone, Copy)]
pub(crate) struct Reach {
    /// A cluster counts as far from this many radii.
    pub(crate) far: f64,
    /// Far clusters nearer than this many radii also get the second-order term.
    pub(crate) second_order: f64,
}

/// What the hierarchy needs of each element.
pub(crate) struct Elements<'a> {
    /// The area vector (area times unit normal, outward).
    pub(crate) area: &'a dyn Fn(usize) -> [f64; 3],
    /// The centroid.
    pub(crate) centroid: &'a dyn Fn(usize) -> [f64; 3],
    /// The largest distance from a point to the element.
    pub(crate) reach: &'a dyn Fn(usize, [f64; 3]) -> f64,
}

/// The hierarchy over `count` elements.
pub(crate) struct Clusters {
    order: Vec<usize>,
    nodes: Vec<Node>,
}

impl Clusters {
    /// Builds the hierarchy (median splits of the centroids along the widest axis).
    pub(crate) fn new(count: usize, elements: &Elements) -> Self {
        let mut clusters = Self {
            order: (0..count).collect(),
            nodes: Vec::new(),
        };
        if count > 0 {
            clusters.build(0, count, elements);
        }
        clusters
    }

    fn build(&mut self, start: usize, end: usize, elements: &Elements) -> usize {
        let mut area = [0.0; 3];
        let mut weighted = [0.0; 3];
        let mut total = 0.0;
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for &t in &self.order[start..end] {
            let av = (elements.area)(t);
            let centroid = (elements.centroid)(t);
            let w = norm(av);
            for d in 0..3 {
                area[d] += av[d];
                weighted[d] += w * centroid[d];
                lo[d] = lo[d].min(centroid[d]);
                hi[d] = hi[d].max(centroid[d]);
            }
            total += w;
        }
        let centre = if total > 0.0 {
            weighted.map(|x| x / total)
        } else {
            core::array::from_fn(|d| 0.5 * (lo[d] + hi[d]))
        };
        let mut moment = [[0.0; 3]; 3];
        for &t in &self.order[start..end] {
            let av = (elements.area)(t);
            let offset = sub((elements.centroid)(t), centre);
            for i in 0..3 {
                for j in 0..3 {
                    moment[i][j] += av[i] * offset[j];
                }
            }
        }
        let radius = self.order[start..end]
            .iter()
            .map(|&t| (elements.reach)(t, centre))
            .fold(0.0, f64::max);
        let id = self.nodes.len();
        self.nodes.push(Node {
            start,
            end,
            children: None,
            area,
            centre,
            moment,
            radius,
        });
        if end - start > LEAF {
            let axis = (0..3)
                .max_by(|&x, &y| (hi[x] - lo[x]).total_cmp(&(hi[y] - lo[y])))
                .unwrap_or(0);
            let mid = (start + end) / 2;
            let key = |t: &usize| (elements.centroid)(*t)[axis];
            self.order[start..end]
                .select_nth_unstable_by(mid - start, |x, y| key(x).total_cmp(&key(y)));
            let left = self.build(start, mid, elements);
            let right = self.build(mid, end, elements);
            self.nodes[id].children = Some((left, right));
        }
        id
    }

    /// The solid angle the elements subtend at p (4π times the winding number): `exact` of
    /// each element of the leaves near p, the expansions of the clusters beyond `reach`.
    pub(crate) fn solid_angle(
        &self,
        p: [f64; 3],
        reach: Reach,
        exact: impl Fn(usize) -> f64,
    ) -> f64 {
        if self.nodes.is_empty() {
            return 0.0;
        }
        let mut sum = 0.0;
        // The tree is balanced, so its depth is about log2(elements / LEAF): 64 is plenty.
        let mut stack = [0usize; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let n = stack[top];
            let node = &self.nodes[n];
            let r = sub(node.centre, p);
            let d = norm(r);
            if d > reach.far * node.radius {
                let d3 = d * d * d;
                sum += dot(node.area, r) / d3;
                // Each element's solid angle ≈ A·g(c) with g(x) = (x − p)/|x − p|³, expanded
                // about the cluster's centre: N·g + Σ J:M with J = ∇g. The second-order term
                // falls off as (radius / distance)², so far clusters skip it.
                if d < reach.second_order * node.radius {
                    let d5 = d3 * d * d;
                    let m = &node.moment;
                    let trace = m[0][0] + m[1][1] + m[2][2];
                    let mut rmr = 0.0;
                    for i in 0..3 {
                        rmr += r[i] * (m[i][0] * r[0] + m[i][1] * r[1] + m[i][2] * r[2]);
                    }
                    sum += trace / d3 - 3.0 * rmr / d5;
                }
                continue;
            }
            match node.children {
                Some((a, b)) if top + 2 <= stack.len() => {
                    stack[top] = a;
                    stack[top + 1] = b;
                    top += 2;
                }
                Some(_) => {
                    // Deeper than the stack: count the cluster by its expansion.
                    sum += dot(node.area, r) / (d * d * d);
                }
                None => {
                    for &t in &self.order[node.start..node.end] {
                        sum += exact(t);
                    }
                }
            }
        }
        sum
    }

    /// The root node, if there are elements.
    pub(crate) fn root(&self) -> Option<usize> {
        (!self.nodes.is_empty()).then_some(0)
    }

    /// A node's bounding sphere.
    pub(crate) fn bounds(&self, n: usize) -> ([f64; 3], f64) {
        (self.nodes[n].centre, self.nodes[n].radius)
    }

    /// A node's children, or none for a leaf.
    pub(crate) fn children(&self, n: usize) -> Option<(usize, usize)> {
        self.nodes[n].children
    }

    /// The elements of a node.
    pub(crate) fn elements(&self, n: usize) -> &[usize] {
        let node = &self.nodes[n];
        &self.order[node.start..node.end]
    }
}
