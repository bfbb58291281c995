//! Continuation (Bloomenthal 1988): start at cells near points on the surface and crawl across
//! the lattice through faces the surface crosses, evaluating f only near the surface.

use rbf_core::ScalarField;

use super::lattice::{CrossedEdge, Lattice, cell_triangles, edge_of, number_edges};
use crate::meshes::hash::FastMap;

/// The six face neighbours of a cell, and the corners (bits) on the shared face.
const FACES: [([i64; 3], [u8; 4]); 6] = [
    ([-1, 0, 0], [0, 2, 4, 6]),
    ([1, 0, 0], [1, 3, 5, 7]),
    ([0, -1, 0], [0, 1, 4, 5]),
    ([0, 1, 0], [2, 3, 6, 7]),
    ([0, 0, -1], [0, 1, 2, 3]),
    ([0, 0, 1], [4, 5, 6, 7]),
];

/// Lattice points (and cells) are stored in blocks of `BLOCK`³, so that a lookup hashes once
/// per block rather than once per point.
const BLOCK: i64 = 8;

/// Lattice points in a block.
const POINTS: usize = (BLOCK * BLOCK * BLOCK) as usize;

/// Per block: f at its lattice points (NaN where not yet sampled, +∞ while queued for
/// sampling), which of its cells have been visited (a bit each), and the vertex on each of the
/// seven lattice edges that leave each point upward (x, y, xy, z, xz, yz, xyz), `u32::MAX` if
/// none yet (made when the block first has one).
struct Block {
    values: [f64; POINTS],
    visited: [u64; POINTS / 64],
    vertices: Vec<u32>,
}

/// Lattice points, cells and edges by block.
struct Blocks {
    index: BlockIndex,
    blocks: Vec<Block>,
    /// The block looked up last, by packed key: consecutive lookups mostly fall in one block.
    last: Option<(u64, u32)>,
}

/// Where each block is in `Blocks::blocks`: a dense array over the lattice's blocks when it
/// is small (at most [`DENSE_BLOCKS`]), else a hash map of the blocks made.
enum BlockIndex {
    Dense { side: [i64; 3], at: Vec<u32> },
    Sparse(FastMap<u64, u32>),
}

/// The most blocks indexed densely (16 MB of indices).
const DENSE_BLOCKS: i64 = 1 << 22;

impl Blocks {
    fn new(lattice: &Lattice) -> Self {
        // Lattice points run from 0 to cells[d] along each axis.
        let side = lattice.cells.map(|c| c / BLOCK + 1);
        let count = side[0].saturating_mul(side[1]).saturating_mul(side[2]);
        let index = if count <= DENSE_BLOCKS {
            BlockIndex::Dense {
                side,
                at: vec![u32::MAX; count as usize],
            }
        } else {
            BlockIndex::Sparse(FastMap::default())
        };
        Self {
            index,
            blocks: Vec::new(),
            last: None,
        }
    }

    /// The block holding lattice point (or cell) p, made if new, and p's index in it.
    fn slot(&mut self, p: [i64; 3]) -> (&mut Block, usize) {
        let (b, i) = self.locate(p);
        (&mut self.blocks[b as usize], i)
    }

    /// The number of the block holding lattice point (or cell) p, made if new, and p's index
    /// in it.
    #[inline]
    fn locate(&mut self, p: [i64; 3]) -> (u32, usize) {
        let key = p.map(|c| c.div_euclid(BLOCK));
        let local = p.map(|c| c.rem_euclid(BLOCK));
        // Lattice indices are below 2²⁰, so a block's three fit in one word (compared in one
        // instruction, where three stored words read back as one would stall).
        let packed = ((key[0] as u64) << 42) | ((key[1] as u64) << 21) | key[2] as u64;
        let b = match self.last {
            Some((k, b)) if k == packed => b,
            _ => {
                let next = self.blocks.len() as u32;
                let b = match &mut self.index {
                    BlockIndex::Dense { side, at } => {
                        let i = (key[0] + side[0] * (key[1] + side[1] * key[2])) as usize;
                        if at[i] == u32::MAX {
                            at[i] = next;
                        }
                        at[i]
                    }
                    BlockIndex::Sparse(map) => *map.entry(packed).or_insert(next),
                };
                if b == next {
                    self.blocks.push(Block {
                        values: [f64::NAN; POINTS],
                        visited: [0; POINTS / 64],
                        vertices: Vec::new(),
                    });
                }
                self.last = Some((packed, b));
                b
            }
        };
        let i = (local[0] + BLOCK * (local[1] + BLOCK * local[2])) as usize;
        (b, i)
    }

    /// Where the eight corners of a cell are (by corner bits, as [`Blocks::locate`] gives
    /// them): one lookup when the cell is not on the upper faces of its block.
    fn corners(&mut self, cell: [i64; 3]) -> [(u32, usize); 8] {
        if cell.iter().all(|&c| c.rem_euclid(BLOCK) < BLOCK - 1) {
            let (b, i) = self.locate(cell);
            core::array::from_fn(|c| {
                let step =
                    (c & 1) as i64 + BLOCK * (((c >> 1) & 1) as i64 + BLOCK * (c >> 2) as i64);
                (b, i + step as usize)
            })
        } else {
            corners_of(cell).map(|p| self.locate(p))
        }
    }

    /// Marks the cell visited; whether it was not before.
    fn visit(&mut self, cell: [i64; 3]) -> bool {
        let (block, i) = self.slot(cell);
        let (word, bit) = (i / 64, 1u64 << (i % 64));
        let new = block.visited[word] & bit == 0;
        block.visited[word] |= bit;
        new
    }

    /// The vertex on the edge with this key, numbered next (and listed in `edges`) if new.
    fn vertex(&mut self, key: u64, lo: f64, hi: f64, edges: &mut Vec<CrossedEdge>) -> u32 {
        let (p, _) = edge_of(key);
        let next = edges.len() as u32;
        let (block, i) = self.slot(p);
        if block.vertices.is_empty() {
            block.vertices = vec![u32::MAX; 7 * POINTS];
        }
        let slot = &mut block.vertices[7 * i + (key & 7) as usize - 1];
        if *slot == u32::MAX {
            *slot = next;
            edges.push((key, lo, hi));
        }
        *slot
    }

    /// Lattice points sampled.
    fn samples(&self) -> usize {
        self.blocks
            .iter()
            .map(|b| b.values.iter().filter(|v| !v.is_nan()).count())
            .sum()
    }
}

/// The eight corners of a cell, by corner bits (x = 1, y = 2, z = 4).
fn corners_of(cell: [i64; 3]) -> [[i64; 3]; 8] {
    core::array::from_fn(|c| {
        let c = c as i64;
        [
            cell[0] + (c & 1),
            cell[1] + ((c >> 1) & 1),
            cell[2] + (c >> 2),
        ]
    })
}

/// The crossed edges of the cells reachable from the seeds, each once, the triangles on their
/// indices, and how many lattice points were evaluated.
pub(crate) fn cells(
    f: &dyn ScalarField<3>,
    lattice: &Lattice,
    seeds: &[[f64; 3]],
) -> (Vec<CrossedEdge>, Vec<[u32; 3]>, usize) {
    let mut blocks = Blocks::new(lattice);
    let mut frontier: Vec<[i64; 3]> = Vec::new();
    // Each seed starts the cells around it: a seed on the surface lies in or next to a cell
    // the surface crosses.
    for s in seeds {
        let c = lattice.cell_of(*s);
        for n in 0..27_i64 {
            let cell = [c[0] + n % 3 - 1, c[1] + (n / 3) % 3 - 1, c[2] + n / 9 - 1];
            if lattice.contains_cell(cell) && blocks.visit(cell) {
                frontier.push(cell);
            }
        }
    }
    let (mut edges, mut tris) = (Vec::new(), Vec::new());
    let mut needed: Vec<[i64; 3]> = Vec::new();
    let mut needed_at: Vec<(u32, usize)> = Vec::new();
    let mut points: Vec<[f64; 3]> = Vec::new();
    let mut found: Vec<f64> = Vec::new();
    while !frontier.is_empty() {
        needed.clear();
        needed_at.clear();
        for &cell in &frontier {
            for (c, (b, i)) in blocks.corners(cell).into_iter().enumerate() {
                let value = &mut blocks.blocks[b as usize].values[i];
                if value.is_nan() {
                    *value = f64::INFINITY;
                    needed.push(corners_of(cell)[c]);
                    needed_at.push((b, i));
                }
            }
        }
        points.clear();
        points.extend(needed.iter().map(|&p| lattice.point(p)));
        found.clear();
        found.resize(points.len(), 0.0);
        // Equal lengths by construction.
        let _ = f.field_values(&points, &mut found);
        for (&(b, i), &v) in needed_at.iter().zip(&found) {
            blocks.blocks[b as usize].values[i] = v;
        }
        let mut next = Vec::new();
        for cell in frontier {
            let corners: [f64; 8] = blocks
                .corners(cell)
                .map(|(b, i)| blocks.blocks[b as usize].values[i]);
            cell_triangles(cell, &corners, &mut tris, |key, lo, hi| {
                blocks.vertex(key, lo, hi, &mut edges)
            });
            for (step, face) in FACES {
                let signs = face.map(|c| corners[c as usize] > 0.0);
                if signs.iter().all(|&s| s) || signs.iter().all(|&s| !s) {
                    continue;
                }
                let n = [cell[0] + step[0], cell[1] + step[1], cell[2] + step[2]];
                if lattice.contains_cell(n) && blocks.visit(n) {
                    next.push(n);
                }
            }
        }
        frontier = next;
    }
    let samples = blocks.samples();
    drop(blocks);
    // Renumbered in the order of their keys (along x, then y, then z), which the
    // simplification's parts rely on (see `simplify::collapse_in_parts`).
    let (edges, tris) = number_edges(edges, tris);
    (edges, tris, samples)
}
