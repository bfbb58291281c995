//! Consistent orientation of unoriented normals: a minimum spanning tree of the neighbour graph
//! grown from one seed per connected piece, each normal taking the sign its tree parent
//! predicts (Hoppe et al. 1992). An edge's weight is König & Gumhold's (2009): a smooth surface
//! through two points has normals mirrored across the plane that bisects the edge between
//! them, so the parent's normal mirrored so predicts the child's; the tree follows the edges
//! where that prediction is most certain, which keeps it off the edges across thin parts and
//! sharp creases, where the plain angle between the normals misleads.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use crate::Neighbours;

/// Normals with consistent signs, and what it took.
#[derive(Clone, Debug)]
pub struct Orientation {
    /// The normals, each the given one or its negation.
    pub normals: Vec<[f64; 3]>,
    /// How many of the given normals were negated.
    pub flipped: usize,
    /// Connected pieces of the neighbour graph (each oriented from its own seed).
    pub components: usize,
}

/// Orients `normals` (unit or zero vectors at `points`) consistently over the graph of
/// `neighbours` (propagated from each connected piece's point farthest from its centroid), and
/// outward: each piece as a whole points away from its centroid (Σ (p − c)·n > 0, which is
/// three times the enclosed volume for a closed surface sampled evenly).
///
/// ```
/// use rbf_cloud::{Neighbours, orient_normals};
/// // A circle of points in the plane z = 0, its radial normals with every other one flipped.
/// let points: Vec<[f64; 3]> = (0..60).map(|i| {
///     let t = i as f64 * std::f64::consts::TAU / 60.0;
///     [t.cos(), t.sin(), 0.0]
/// }).collect();
/// let given: Vec<[f64; 3]> = points.iter().enumerate()
///     .map(|(i, p)| if i % 2 == 0 { *p } else { [-p[0], -p[1], 0.0] }).collect();
/// let oriented = orient_normals(&points, &given, &Neighbours::new(&points, 4));
/// assert_eq!(oriented.flipped, 30);
/// assert!(oriented.normals.iter().zip(&points).all(|(n, p)| n[0] * p[0] + n[1] * p[1] > 0.99));
/// ```
pub fn orient_normals(
    points: &[[f64; 3]],
    normals: &[[f64; 3]],
    neighbours: &Neighbours,
) -> Orientation {
    let n = points.len().min(normals.len());
    let graph = Graph::new(neighbours, n);
    let mut sign = vec![0.0_f64; n];
    let mut components = 0;
    let mut heap: BinaryHeap<(Reverse<Weight>, u32, u32, bool)> = BinaryHeap::new();
    // Pieces are found in index order; each is seeded at its point farthest from its centroid.
    for start in 0..n {
        if sign[start] != 0.0 {
            continue;
        }
        components += 1;
        let piece = graph.piece(start);
        let seed = farthest_from_centroid(points, &piece);
        let centre = centroid(points, &piece);
        let outward = dot(normals[seed], sub(points[seed], centre));
        sign[seed] = if outward < 0.0 { -1.0 } else { 1.0 };
        graph.push_edges(points, normals, seed, &mut heap);
        while let Some((_, parent, child, agrees)) = heap.pop() {
            let (parent, child) = (parent as usize, child as usize);
            if sign[child] != 0.0 {
                continue;
            }
            sign[child] = if agrees { sign[parent] } else { -sign[parent] };
            graph.push_edges(points, normals, child, &mut heap);
        }
        // The whole piece points out if Σ (p − c)·n > 0: over a closed surface ∫ (x − c)·n dA
        // is three times the volume. One seed's normal may be nearly tangent (noise), the sum
        // is not.
        let flux: f64 = piece
            .iter()
            .map(|&i| sign[i] * dot(normals[i], sub(points[i], centre)))
            .sum();
        if flux < 0.0 {
            piece.iter().for_each(|&i| sign[i] = -sign[i]);
        }
        // A piece the graph could not reach from its seed cannot happen: `piece` is the
        // seed's own component.
    }
    let flipped = sign.iter().filter(|&&s| s < 0.0).count();
    let oriented = normals[..n]
        .iter()
        .zip(&sign)
        .map(|(v, &s)| [v[0] * s, v[1] * s, v[2] * s])
        .collect();
    Orientation {
        normals: oriented,
        flipped,
        components,
    }
}

/// An edge weight, ordered (1 − certainty, in [0, 1]).
#[derive(Clone, Copy, Debug)]
struct Weight(f64);

impl PartialEq for Weight {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other).is_eq()
    }
}

impl Eq for Weight {}

impl PartialOrd for Weight {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Weight {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// The neighbour graph made symmetric, as adjacency lists.
struct Graph {
    starts: Vec<usize>,
    targets: Vec<u32>,
}

impl Graph {
    fn new(neighbours: &Neighbours, n: usize) -> Self {
        let mut pairs: Vec<(u32, u32)> = Vec::with_capacity(2 * n * neighbours.k());
        for i in 0..n.min(neighbours.len()) {
            for &j in neighbours.of(i) {
                if (j as usize) < n && j as usize != i {
                    pairs.push((i as u32, j));
                    pairs.push((j, i as u32));
                }
            }
        }
        pairs.sort_unstable();
        pairs.dedup();
        let mut starts = vec![0; n + 1];
        for &(i, _) in &pairs {
            starts[i as usize + 1] += 1;
        }
        for i in 0..n {
            starts[i + 1] += starts[i];
        }
        Self {
            starts,
            targets: pairs.into_iter().map(|(_, j)| j).collect(),
        }
    }

    fn of(&self, i: usize) -> &[u32] {
        &self.targets[self.starts[i]..self.starts[i + 1]]
    }

    /// Every point connected to `start`.
    fn piece(&self, start: usize) -> Vec<usize> {
        let mut seen = vec![false; self.starts.len() - 1];
        let mut stack = vec![start];
        let mut out = Vec::new();
        seen[start] = true;
        while let Some(i) = stack.pop() {
            out.push(i);
            for &j in self.of(i) {
                if !seen[j as usize] {
                    seen[j as usize] = true;
                    stack.push(j as usize);
                }
            }
        }
        out
    }

    /// Queues the edges from `i` with their weights and predicted agreement.
    fn push_edges(
        &self,
        points: &[[f64; 3]],
        normals: &[[f64; 3]],
        i: usize,
        heap: &mut BinaryHeap<(Reverse<Weight>, u32, u32, bool)>,
    ) {
        for &j in self.of(i) {
            let (certainty, agrees) = prediction(points, normals, i, j as usize);
            heap.push((Reverse(Weight(1.0 - certainty)), i as u32, j, agrees));
        }
    }
}

/// How surely, and with which sign, normal i (mirrored across the plane bisecting the edge
/// from i to j) predicts normal j.
fn prediction(points: &[[f64; 3]], normals: &[[f64; 3]], i: usize, j: usize) -> (f64, bool) {
    let e = sub(points[j], points[i]);
    let length = dot(e, e).sqrt();
    let ni = normals[i];
    let mirrored = if length > 0.0 {
        let e = [e[0] / length, e[1] / length, e[2] / length];
        let along = 2.0 * dot(ni, e);
        [
            ni[0] - along * e[0],
            ni[1] - along * e[1],
            ni[2] - along * e[2],
        ]
    } else {
        ni
    };
    let c = dot(mirrored, normals[j]);
    (c.abs().min(1.0), c >= 0.0)
}

fn centroid(points: &[[f64; 3]], piece: &[usize]) -> [f64; 3] {
    let mut c = [0.0; 3];
    for &i in piece {
        (0..3).for_each(|d| c[d] += points[i][d]);
    }
    let count = piece.len().max(1) as f64;
    [c[0] / count, c[1] / count, c[2] / count]
}

fn farthest_from_centroid(points: &[[f64; 3]], piece: &[usize]) -> usize {
    let c = centroid(points, piece);
    piece
        .iter()
        .copied()
        .max_by(|&a, &b| {
            let da = sub(points[a], c);
            let db = sub(points[b], c);
            dot(da, da).total_cmp(&dot(db, db))
        })
        .unwrap_or(0)
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
