//! From crossed lattice edges to a mesh: vertices found on the surface by safeguarded Newton
//! iteration along each edge, normals from the gradient of f.

use rbf_core::ScalarField;

use super::lattice::{CrossedEdge, Lattice, edge_of};
use super::simplify;
use crate::{MeshError, TriMesh};

/// Keeps vertices this fraction of an edge away from its ends, so that no triangle collapses
/// where f is exactly zero at a lattice point (the surface then touches that point).
const END_MARGIN: f64 = 1e-6;

/// A Newton step shorter than this fraction of an edge ends the search (its error is of the
/// order of its square).
const NEWTON_DONE: f64 = 1e-3;

/// Where the root search along one edge stands.
#[derive(Clone, Copy)]
struct Search {
    /// Bracket [lo, hi] in edge parameter, f(lo) > 0 ≥ f(hi) or the reverse.
    lo: f64,
    f_lo: f64,
    hi: f64,
    f_hi: f64,
    /// Edge parameter in [0, 1] of the next point to evaluate (0 at one end, 1 at the other).
    t: f64,
    /// The gradient at the last point evaluated.
    gradient: [f64; 3],
    /// Lengths of the last step and of the one before (edge parameter).
    step: f64,
    step_before: f64,
}

/// Builds the mesh: one vertex per crossed edge, placed where f = 0. The first round evaluates
/// f at every edge's secant point and takes a secant step within the bracket; each
/// later round evaluates f and ∇f at every unfinished edge's current point in one batch and
/// takes a Newton step along the edge, or halves the bracket when Newton would leave it or
/// does not converge fast enough.
/// An edge is done when |f| is below 1e-8 of the change of f along it, or its Newton step is
/// below 1e-3 of its length (Newton's error is then of the order of the step's square: the
/// vertex is within about 1e-6 of an edge length of the surface), after at most
/// `settings.root_iterations` rounds. With none, f is not evaluated again: each vertex stays
/// at the secant point of its edge (where the linear interpolation of f between the edge's
/// ends is zero), the mesh is simplified as usual, and its vertices carry no normals. That
/// surface has the topology of f's signs at the lattice points, for a fraction of the cost.
/// Without `settings.simplify`, no edge is collapsed (nor any triangle unfolded after).
///
/// `unique` lists each crossed edge once; `triangles` are on its indices.
pub(crate) fn assemble(
    f: &dyn ScalarField<3>,
    lattice: &Lattice,
    unique: Vec<CrossedEdge>,
    triangles: Vec<[u32; 3]>,
    settings: &super::PolygonizeSettings,
) -> Result<TriMesh, MeshError> {
    let iterations = settings.root_iterations;
    let collapse = |positions: &[[f64; 3]], triangles: Vec<[u32; 3]>, target: usize| {
        if settings.simplify {
            simplify::collapse(positions, triangles, lattice.h, target)
        } else {
            ((0..positions.len() as u32).collect(), triangles)
        }
    };
    let ends: Vec<([f64; 3], [f64; 3])> = unique
        .iter()
        .map(|&(key, _, _)| {
            let (p, o) = edge_of(key);
            (
                lattice.point(p),
                lattice.point([p[0] + o[0], p[1] + o[1], p[2] + o[2]]),
            )
        })
        .collect();
    let at = |(a, b): ([f64; 3], [f64; 3]), t: f64| -> [f64; 3] {
        core::array::from_fn(|d| a[d] + t * (b[d] - a[d]))
    };
    let secant = |lo: f64, f_lo: f64, hi: f64, f_hi: f64| {
        let t = if f_lo != f_hi {
            lo + (hi - lo) * f_lo / (f_lo - f_hi)
        } else {
            0.5 * (lo + hi)
        };
        t.clamp(lo.min(hi), lo.max(hi))
    };
    let tolerance: Vec<f64> = unique
        .iter()
        .map(|&(_, a, b)| 1e-8 * (a - b).abs())
        .collect();
    let mut searches: Vec<Search> = unique
        .iter()
        .map(|&(_, a, b)| Search {
            lo: 0.0,
            f_lo: a,
            hi: 1.0,
            f_hi: b,
            t: secant(0.0, a, 1.0, b).clamp(END_MARGIN, 1.0 - END_MARGIN),
            gradient: [0.0; 3],
            step: 1.0,
            step_before: 1.0,
        })
        .collect();
    // Collapse first, at the secant points (within a small fraction of a cell of the roots),
    // so that root finding runs on the vertices that stay.
    let estimates: Vec<[f64; 3]> = searches
        .iter()
        .zip(&ends)
        .map(|(s, &e)| at(e, s.t))
        .collect();
    // Marching cubes puts one vertex on each crossed axis edge.
    let axis_edges = unique
        .iter()
        .filter(|e| matches!(e.0 & 7, 1 | 2 | 4))
        .count();
    let target = axis_edges + axis_edges / 8;
    let (merged, triangles) = collapse(&estimates, triangles, target);
    let kept: Vec<usize> = (0..merged.len())
        .filter(|&v| merged[v] as usize == v)
        .collect();
    if iterations == 0 {
        let triangles = reindex(&merged, &kept, triangles);
        return TriMesh::new(kept.iter().map(|&v| estimates[v]).collect(), triangles);
    }
    let mut pending: Vec<usize> = kept.clone();
    for round in 0..iterations.max(1) {
        let points: Vec<[f64; 3]> = pending
            .iter()
            .map(|&i| at(ends[i], searches[i].t))
            .collect();
        let mut values = vec![0.0; points.len()];
        let mut gradients = vec![[0.0; 3]; points.len()];
        // The first round takes values only (half the cost), for a secant step; every vertex
        // then gets a gradient, for its normal, in the rounds after.
        let first = round == 0 && iterations > 1;
        // Equal lengths by construction.
        let _ = if first {
            f.field_values(&points, &mut values)
        } else {
            f.field_values_and_gradients(&points, &mut values, &mut gradients)
        };
        let last = round + 1 == iterations.max(1);
        let mut still = Vec::with_capacity(pending.len());
        for ((&i, &v), &g) in pending.iter().zip(&values).zip(&gradients) {
            let s = &mut searches[i];
            s.gradient = g;
            if !first && (v.abs() <= tolerance[i] || last) {
                continue;
            }
            // Shrink the bracket to the side where the sign changes.
            let t = s.t;
            if (v > 0.0) == (s.f_lo > 0.0) {
                s.lo = t;
                s.f_lo = v;
            } else {
                s.hi = t;
                s.f_hi = v;
            }
            // Newton along the edge: d f / d t = ∇f · (b − a).
            let (a, b) = ends[i];
            let slope: f64 = (0..3).map(|d| g[d] * (b[d] - a[d])).sum();
            let newton = if first { f64::NAN } else { t - v / slope };
            let (lo, hi) = (s.lo.min(s.hi), s.lo.max(s.hi));
            // Newton is taken while it stays in the bracket and its steps at least halve every
            // other round (as they do near a simple root); else the bracket is halved, as where
            // the surface grazes the edge and f is nearly flat along it.
            let inside = newton.is_finite()
                && newton > lo
                && newton < hi
                && (newton - t).abs() <= 0.5 * s.step_before;
            let next = if inside {
                newton
            } else if first {
                secant(s.lo, s.f_lo, s.hi, s.f_hi)
            } else {
                0.5 * (lo + hi)
            };
            s.step_before = s.step;
            s.step = (next - t).abs();
            s.t = next.clamp(END_MARGIN, 1.0 - END_MARGIN);
            // A Newton step this small leaves an error of the order of its square: accept it
            // without another evaluation (the gradient kept is from 1e-3 of an edge away).
            if inside && (newton - t).abs() < NEWTON_DONE {
                continue;
            }
            if (hi - lo) < 1e-12 && !first {
                continue;
            }
            still.push(i);
        }
        pending = still;
        if pending.is_empty() {
            break;
        }
    }
    let positions: Vec<[f64; 3]> = (0..merged.len())
        .map(|v| at(ends[v], searches[v].t))
        .collect();
    let normals: Vec<[f64; 3]> = searches
        .iter()
        .map(|s| {
            let l = rbf_core::vec3::norm(s.gradient);
            if l > 0.0 {
                s.gradient.map(|c| -c / l)
            } else {
                [0.0; 3]
            }
        })
        .collect();
    let triangles: Vec<[u32; 3]> = triangles
        .into_iter()
        .map(|t| t.map(|v| merged[v as usize]))
        .collect();
    // Root finding moved the vertices a little: collapse what became short, flip what became
    // a cap (no evaluation needed).
    let (merged, triangles) = collapse(&positions, triangles, kept.len());
    let kept: Vec<usize> = kept
        .into_iter()
        .filter(|&v| merged[v] as usize == v)
        .collect();
    let mut triangles = reindex(&merged, &kept, triangles);
    let positions: Vec<[f64; 3]> = kept.iter().map(|&v| positions[v]).collect();
    let normals: Vec<[f64; 3]> = kept.iter().map(|&v| normals[v]).collect();
    // Root finding moved vertices after the first collapses: flip back any triangle that
    // turned over.
    if settings.simplify {
        simplify::unfold(&positions, &normals, &mut triangles);
    }
    TriMesh::new(positions, triangles)?.with_normals(normals)
}

/// `triangles` on the vertices that a collapse `merged` into the `kept` ones, numbered as
/// `kept` orders them.
fn reindex(merged: &[u32], kept: &[usize], triangles: Vec<[u32; 3]>) -> Vec<[u32; 3]> {
    let mut new_index = vec![u32::MAX; merged.len()];
    for (i, &v) in kept.iter().enumerate() {
        new_index[v] = i as u32;
    }
    triangles
        .into_iter()
        .map(|t| t.map(|v| new_index[merged[v as usize] as usize]))
        .collect()
}
