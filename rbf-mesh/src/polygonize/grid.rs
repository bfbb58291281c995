//! Marching tetrahedra over every cell of a box, coarse to fine: f and ∇f are sampled on a
//! coarse lattice (every fourth point), and only the blocks of 4³ cubes that the surface may
//! cross are sampled in full.

use rayon::prelude::*;
use rbf_core::ScalarField;

use super::BlockSkip;
use super::lattice::{CrossedEdge, EdgeTriangle, Lattice, cell_triangles};

/// Cells along each side of a block.
const BLOCK: i64 = 4;

/// What a block that was not skipped gives: crossed edges, triangles, samples taken.
type BlockResult = (Vec<CrossedEdge>, Vec<EdgeTriangle>, usize);

/// Crossed edges, triangles, lattice points sampled and blocks skipped.
pub(crate) fn cells(
    f: &dyn ScalarField<3>,
    lattice: &Lattice,
    skip: BlockSkip,
) -> (Vec<CrossedEdge>, Vec<EdgeTriangle>, usize, usize) {
    let blocks: [i64; 3] = core::array::from_fn(|d| (lattice.cells[d] + BLOCK - 1) / BLOCK);
    let coarse_n: [i64; 3] = core::array::from_fn(|d| blocks[d] + 1);
    let coarse_point = |i: [i64; 3]| -> [i64; 3] {
        core::array::from_fn(|d| (i[d] * BLOCK).min(lattice.cells[d]))
    };
    // f and ∇f at the block corners.
    let count = (coarse_n[0] * coarse_n[1] * coarse_n[2]) as usize;
    let points: Vec<[f64; 3]> = (0..count as i64)
        .map(|c| {
            let i = [
                c % coarse_n[0],
                (c / coarse_n[0]) % coarse_n[1],
                c / (coarse_n[0] * coarse_n[1]),
            ];
            lattice.point(coarse_point(i))
        })
        .collect();
    let mut values = vec![0.0; count];
    let mut gradients = vec![[0.0; 3]; count];
    // Equal lengths by construction.
    let _ = f.field_values_and_gradients(&points, &mut values, &mut gradients);
    let coarse = |i: [i64; 3]| (i[0] + coarse_n[0] * (i[1] + coarse_n[1] * i[2])) as usize;

    let total = (blocks[0] * blocks[1] * blocks[2]) as usize;
    let results: Vec<Option<BlockResult>> = (0..total)
        .into_par_iter()
        .map(|b| {
            let b = b as i64;
            let block = [
                b % blocks[0],
                (b / blocks[0]) % blocks[1],
                b / (blocks[0] * blocks[1]),
            ];
            let lo = coarse_point(block);
            let hi = coarse_point([block[0] + 1, block[1] + 1, block[2] + 1]);
            let (a, c) = (lattice.point(lo), lattice.point(hi));
            let half_diagonal = 0.5 * rbf_core::vec3::norm(rbf_core::vec3::sub(c, a));
            let corners = (0..8).map(|k: i64| {
                coarse([
                    block[0] + (k & 1),
                    block[1] + ((k >> 1) & 1),
                    block[2] + (k >> 2),
                ])
            });
            let skipped = match skip {
                BlockSkip::Never => false,
                BlockSkip::Proven => {
                    let centre = core::array::from_fn(|d| 0.5 * (a[d] + c[d]));
                    f.direct().ball_bound(&centre, half_diagonal).one_sign()
                }
                BlockSkip::Estimated => {
                    // Every point of the block is within half a diagonal of a corner.
                    let (mut slope, mut smallest, mut positive) = (0.0_f64, f64::INFINITY, 0);
                    for k in corners {
                        slope = slope.max(rbf_core::vec3::norm(gradients[k]));
                        smallest = smallest.min(values[k].abs());
                        positive += usize::from(values[k] > 0.0);
                    }
                    (positive == 0 || positive == 8) && smallest > 1.5 * slope * half_diagonal
                }
            };
            if skipped {
                return None;
            }
            let n = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
            let (mut edges, mut tris) = (Vec::new(), Vec::new());
            let samples = block_cells(f, lattice, lo, n, &mut edges, &mut tris);
            Some((edges, tris, samples))
        })
        .collect();
    let mut edges = Vec::new();
    let mut tris = Vec::new();
    let mut samples = count;
    let mut skipped = 0;
    for r in results {
        match r {
            Some((e, t, s)) => {
                edges.extend(e);
                tris.extend(t);
                samples += s;
            }
            None => skipped += 1,
        }
    }
    (edges, tris, samples, skipped)
}

/// Samples a block's lattice points and polygonizes its cells; returns the samples taken.
fn block_cells(
    f: &dyn ScalarField<3>,
    lattice: &Lattice,
    lo: [i64; 3],
    n: [i64; 3],
    edges: &mut Vec<CrossedEdge>,
    tris: &mut Vec<EdgeTriangle>,
) -> usize {
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
    let _ = f.field_values(&points, &mut values);
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
    points.len()
}
