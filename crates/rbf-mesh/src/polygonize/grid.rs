//! Marching tetrahedra over every cell of a box, in blocks that are skipped when the surface
//! provably cannot cross them.

use rayon::prelude::*;
use rbf_core::InterpolantView;

use super::BlockSkip;
use super::bound::one_sign_in_ball;
use super::lattice::{CrossedEdge, EdgeTriangle, Lattice, cell_triangles};

/// Cells along each side of a block.
const BLOCK: i64 = 8;

/// Crossed edges and triangles of every cell of the lattice.
pub(crate) fn cells(
    f: &InterpolantView<'_, f64, 3>,
    lattice: &Lattice,
    skip: BlockSkip,
) -> (Vec<CrossedEdge>, Vec<EdgeTriangle>, usize) {
    let blocks: [i64; 3] = core::array::from_fn(|d| (lattice.cells[d] + BLOCK - 1) / BLOCK);
    let count = (blocks[0] * blocks[1] * blocks[2]) as usize;
    let results: Vec<(Vec<CrossedEdge>, Vec<EdgeTriangle>, bool)> = (0..count)
        .into_par_iter()
        .map(|b| {
            let b = b as i64;
            let block = [
                b % blocks[0],
                (b / blocks[0]) % blocks[1],
                b / (blocks[0] * blocks[1]),
            ];
            let lo: [i64; 3] = core::array::from_fn(|d| block[d] * BLOCK);
            let n: [i64; 3] = core::array::from_fn(|d| BLOCK.min(lattice.cells[d] - lo[d]));
            let a = lattice.point(lo);
            let c = lattice.point([lo[0] + n[0], lo[1] + n[1], lo[2] + n[2]]);
            let centre = core::array::from_fn(|d| 0.5 * (a[d] + c[d]));
            let radius = 0.5 * crate::mesh::norm(crate::mesh::sub(c, a));
            let skipped = match skip {
                BlockSkip::Never => false,
                BlockSkip::Proven => one_sign_in_ball(f, centre, radius),
                BlockSkip::Estimated => {
                    one_sign_in_ball(f, centre, radius) || corners_say_empty(f, a, c)
                }
            };
            if skipped {
                return (Vec::new(), Vec::new(), true);
            }
            let (mut edges, mut tris) = (Vec::new(), Vec::new());
            block_cells(f, lattice, lo, n, &mut edges, &mut tris);
            (edges, tris, false)
        })
        .collect();
    let skipped = results.iter().filter(|r| r.2).count();
    let mut edges = Vec::new();
    let mut tris = Vec::new();
    for (e, t, _) in results {
        edges.extend(e);
        tris.extend(t);
    }
    (edges, tris, skipped)
}

/// The sampled-gradient test of [`BlockSkip::Estimated`] on the box from `a` to `c`.
fn corners_say_empty(f: &InterpolantView<'_, f64, 3>, a: [f64; 3], c: [f64; 3]) -> bool {
    let diagonal = crate::mesh::norm(crate::mesh::sub(c, a));
    let mut slope = 0.0_f64;
    let mut smallest = f64::INFINITY;
    let mut positive = 0;
    for k in 0..8 {
        let p = [
            if k & 1 == 0 { a[0] } else { c[0] },
            if k & 2 == 0 { a[1] } else { c[1] },
            if k & 4 == 0 { a[2] } else { c[2] },
        ];
        let (v, g) = f.value_and_gradient(&p);
        slope = slope.max(crate::mesh::norm(g));
        smallest = smallest.min(v.abs());
        positive += usize::from(v > 0.0);
    }
    (positive == 0 || positive == 8) && smallest > 2.0 * slope * diagonal
}

/// Samples a block's lattice points and polygonizes its cells.
fn block_cells(
    f: &InterpolantView<'_, f64, 3>,
    lattice: &Lattice,
    lo: [i64; 3],
    n: [i64; 3],
    edges: &mut Vec<CrossedEdge>,
    tris: &mut Vec<EdgeTriangle>,
) {
    let m = [n[0] + 1, n[1] + 1, n[2] + 1];
    let mut points = Vec::with_capacity((m[0] * m[1] * m[2]) as usize);
    for k in 0..m[2] {
        for j in 0..m[1] {
            for i in 0..m[0] {
                points.push(lattice.point([lo[0] + i, lo[1] + j, lo[2] + k]));
            }
        }
    }
    let mut values = vec![0.0; points.len()];
    let _ = f.values(&points, &mut values);
    let at = |i: i64, j: i64, k: i64| values[(i + m[0] * (j + m[1] * k)) as usize];
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                let corners: [f64; 8] = core::array::from_fn(|c| {
                    at(
                        i + (c & 1) as i64,
                        j + ((c >> 1) & 1) as i64,
                        k + ((c >> 2) & 1) as i64,
                    )
                });
                cell_triangles([lo[0] + i, lo[1] + j, lo[2] + k], &corners, tris, edges);
            }
        }
    }
}
