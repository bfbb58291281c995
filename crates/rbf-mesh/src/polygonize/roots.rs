//! From crossed lattice edges to a mesh: vertices found on the surface by root finding along
//! each edge, normals from the gradient of f.

use std::collections::HashMap;

use rayon::prelude::*;
use rbf_core::InterpolantView;

use super::lattice::{CrossedEdge, EdgeTriangle, Lattice, edge_of};
use crate::{MeshError, TriMesh};

/// Keeps vertices this fraction of an edge away from its ends, so that no triangle collapses
/// where f is exactly zero at a lattice point (the surface then touches that point).
const END_MARGIN: f64 = 1e-6;

/// f at many points, in parallel.
pub(crate) fn par_values(f: &InterpolantView<'_, f64, 3>, points: &[[f64; 3]]) -> Vec<f64> {
    let mut out = vec![0.0; points.len()];
    points
        .par_chunks(256)
        .zip(out.par_chunks_mut(256))
        .for_each(|(p, o)| {
            // Equal lengths by construction.
            let _ = f.values(p, o);
        });
    out
}

/// Builds the mesh: one vertex per crossed edge, placed where f = 0 by Illinois regula falsi
/// (`iterations` rounds, each one batched evaluation of every unfinished edge).
pub(crate) fn assemble(
    f: &InterpolantView<'_, f64, 3>,
    lattice: &Lattice,
    edges: Vec<CrossedEdge>,
    triangles: Vec<EdgeTriangle>,
    iterations: usize,
) -> Result<TriMesh, MeshError> {
    let mut index: HashMap<u64, u32> = HashMap::with_capacity(edges.len() / 2);
    let mut unique: Vec<CrossedEdge> = Vec::with_capacity(edges.len() / 2);
    for e in edges {
        index.entry(e.0).or_insert_with(|| {
            unique.push(e);
            (unique.len() - 1) as u32
        });
    }
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
    // Bracket [t0, t1] with values (f0, f1) of opposite classes; `side` remembers which end
    // moved last, for the Illinois halving.
    let mut state: Vec<(f64, f64, f64, f64, i8)> = unique
        .iter()
        .map(|&(_, a, b)| (0.0, a, 1.0, b, 0))
        .collect();
    let at = |(a, b): ([f64; 3], [f64; 3]), t: f64| -> [f64; 3] {
        core::array::from_fn(|d| a[d] + t * (b[d] - a[d]))
    };
    let guess = |&(t0, f0, t1, f1, _): &(f64, f64, f64, f64, i8)| {
        let t = if f0 != f1 {
            t0 + (t1 - t0) * f0 / (f0 - f1)
        } else {
            0.5 * (t0 + t1)
        };
        t.clamp(END_MARGIN, 1.0 - END_MARGIN)
    };
    for _ in 0..iterations {
        let ts: Vec<f64> = state.iter().map(guess).collect();
        let points: Vec<[f64; 3]> = ts.iter().zip(&ends).map(|(&t, &e)| at(e, t)).collect();
        let values = par_values(f, &points);
        for ((s, &t), &v) in state.iter_mut().zip(&ts).zip(&values) {
            let (t0, f0, t1, f1, side) = *s;
            if v == 0.0 || (t1 - t0) < 1e-12 {
                *s = (t, v, t, v, 0);
            } else if (v > 0.0) == (f0 > 0.0) {
                let f1 = if side == -1 { 0.5 * f1 } else { f1 };
                *s = (t, v, t1, f1, -1);
            } else {
                let f0 = if side == 1 { 0.5 * f0 } else { f0 };
                *s = (t0, f0, t, v, 1);
            }
        }
    }
    let positions: Vec<[f64; 3]> = state
        .iter()
        .zip(&ends)
        .map(|(s, &e)| at(e, if s.0 == s.2 { s.0 } else { guess(s) }))
        .collect();
    let triangles: Vec<[u32; 3]> = triangles
        .into_iter()
        .map(|t| t.map(|k| index[&k]))
        .collect();
    let normals: Vec<[f64; 3]> = positions
        .par_iter()
        .map(|p| {
            let g = f.gradient(p);
            let l = crate::mesh::norm(g);
            if l > 0.0 { g.map(|c| -c / l) } else { [0.0; 3] }
        })
        .collect();
    TriMesh::new(positions, triangles)?.with_normals(normals)
}
