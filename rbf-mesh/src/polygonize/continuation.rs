//! Continuation (Bloomenthal 1988): start at cells near points on the surface and crawl across
//! the lattice through faces the surface crosses, evaluating f only near the surface.

use rbf_core::ScalarField;

use super::lattice::{CrossedEdge, EdgeTriangle, Lattice, cell_triangles};
use crate::meshes::hash::{FastMap, FastSet};

/// The six face neighbours of a cell, and the corners (bits) on the shared face.
const FACES: [([i64; 3], [u8; 4]); 6] = [
    ([-1, 0, 0], [0, 2, 4, 6]),
    ([1, 0, 0], [1, 3, 5, 7]),
    ([0, -1, 0], [0, 1, 4, 5]),
    ([0, 1, 0], [2, 3, 6, 7]),
    ([0, 0, -1], [0, 1, 2, 3]),
    ([0, 0, 1], [4, 5, 6, 7]),
];

/// Crossed edges and triangles of the cells reachable from the seeds, and how many lattice
/// points were evaluated.
pub(crate) fn cells(
    f: &dyn ScalarField<3>,
    lattice: &Lattice,
    seeds: &[[f64; 3]],
) -> (Vec<CrossedEdge>, Vec<EdgeTriangle>, usize) {
    let mut values: FastMap<[i64; 3], f64> = FastMap::default();
    let mut visited: FastSet<[i64; 3]> = FastSet::default();
    let mut frontier: Vec<[i64; 3]> = Vec::new();
    // Each seed starts the cells around it: a seed on the surface lies in or next to a cell
    // the surface crosses.
    for s in seeds {
        let c = lattice.cell_of(*s);
        for n in 0..27_i64 {
            let cell = [c[0] + n % 3 - 1, c[1] + (n / 3) % 3 - 1, c[2] + n / 9 - 1];
            if lattice.contains_cell(cell) && visited.insert(cell) {
                frontier.push(cell);
            }
        }
    }
    let (mut edges, mut tris) = (Vec::new(), Vec::new());
    while !frontier.is_empty() {
        let mut needed: Vec<[i64; 3]> = Vec::new();
        let mut queued: FastSet<[i64; 3]> = FastSet::default();
        for cell in &frontier {
            for c in 0..8_i64 {
                let p = [
                    cell[0] + (c & 1),
                    cell[1] + ((c >> 1) & 1),
                    cell[2] + (c >> 2),
                ];
                if !values.contains_key(&p) && queued.insert(p) {
                    needed.push(p);
                }
            }
        }
        let points: Vec<[f64; 3]> = needed.iter().map(|&p| lattice.point(p)).collect();
        let mut found = vec![0.0; points.len()];
        // Equal lengths by construction.
        let _ = f.field_values(&points, &mut found);
        for (p, v) in needed.into_iter().zip(found) {
            values.insert(p, v);
        }
        let mut next = Vec::new();
        for cell in frontier {
            let corners: [f64; 8] = core::array::from_fn(|c| {
                let c = c as i64;
                values[&[
                    cell[0] + (c & 1),
                    cell[1] + ((c >> 1) & 1),
                    cell[2] + (c >> 2),
                ]]
            });
            cell_triangles(cell, &corners, &mut tris, &mut edges);
            for (step, face) in FACES {
                let signs = face.map(|c| corners[c as usize] > 0.0);
                if signs.iter().all(|&s| s) || signs.iter().all(|&s| !s) {
                    continue;
                }
                let n = [cell[0] + step[0], cell[1] + step[1], cell[2] + step[2]];
                if lattice.contains_cell(n) && visited.insert(n) {
                    next.push(n);
                }
            }
        }
        frontier = next;
    }
    (edges, tris, values.len())
}
