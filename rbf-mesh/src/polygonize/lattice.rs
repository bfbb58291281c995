//! The cube lattice both polygonizers walk, and its Kuhn decomposition into tetrahedra.

/// A regular lattice: point (i, j, k) is at `origin + h·(i, j, k)`, for 0 ≤ i ≤ cells[0] etc.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lattice {
    pub(crate) origin: [f64; 3],
    pub(crate) h: f64,
    pub(crate) cells: [i64; 3],
}

impl Lattice {
    pub(crate) fn point(&self, p: [i64; 3]) -> [f64; 3] {
        [
            self.origin[0] + self.h * p[0] as f64,
            self.origin[1] + self.h * p[1] as f64,
            self.origin[2] + self.h * p[2] as f64,
        ]
    }

    /// The cell containing x, clamped to the lattice.
    pub(crate) fn cell_of(&self, x: [f64; 3]) -> [i64; 3] {
        core::array::from_fn(|d| {
            let c = ((x[d] - self.origin[d]) / self.h).floor();
            (c.max(0.0) as i64).min(self.cells[d] - 1)
        })
    }

    pub(crate) fn contains_cell(&self, c: [i64; 3]) -> bool {
        (0..3).all(|d| c[d] >= 0 && c[d] < self.cells[d])
    }
}

/// Key of a lattice edge from point p to p + offset (offset bits x = 1, y = 2, z = 4).
pub(crate) fn edge_key(p: [i64; 3], offset: u8) -> u64 {
    ((p[0] as u64) << 43) | ((p[1] as u64) << 23) | ((p[2] as u64) << 3) | offset as u64
}

/// The lower end and offset of an edge key.
pub(crate) fn edge_of(key: u64) -> ([i64; 3], [i64; 3]) {
    let mask = (1u64 << 20) - 1;
    let p = [
        ((key >> 43) & mask) as i64,
        ((key >> 23) & mask) as i64,
        ((key >> 3) & mask) as i64,
    ];
    let o = key & 7;
    (
        p,
        [(o & 1) as i64, ((o >> 1) & 1) as i64, ((o >> 2) & 1) as i64],
    )
}

/// The largest lattice index an edge key can hold.
pub(crate) const MAX_CELLS: i64 = (1 << 20) - 2;

/// Corner c (bits x = 1, y = 2, z = 4) of a cube.
fn corner(c: u8) -> [i64; 3] {
    [(c & 1) as i64, ((c >> 1) & 1) as i64, ((c >> 2) & 1) as i64]
}

/// The six Kuhn tetrahedra of a cube, as corner numbers: each walks from corner 0 to corner 7
/// adding one axis at a time. Neighbouring cubes split their shared face along the same diagonal,
/// so the tetrahedra of the whole lattice fit together.
const KUHN: [[u8; 4]; 6] = [
    [0, 1, 3, 7],
    [0, 1, 5, 7],
    [0, 2, 3, 7],
    [0, 2, 6, 7],
    [0, 4, 5, 7],
    [0, 4, 6, 7],
];

/// A triangle given by three lattice edges.
pub(crate) type EdgeTriangle = [u64; 3];

/// A lattice edge crossed by the surface, with f at its lower and upper ends.
pub(crate) type CrossedEdge = (u64, f64, f64);

/// Appends the triangles of the cell at `cell` (lowest corner) given its eight corner values
/// (index = corner bits) to `out`, oriented so that their normals point from inside (f > 0) to
/// outside, and the edges they lie on to `edges` (possibly more than once).
pub(crate) fn cell_triangles(
    cell: [i64; 3],
    values: &[f64; 8],
    out: &mut Vec<EdgeTriangle>,
    edges: &mut Vec<CrossedEdge>,
) {
    let inside: [bool; 8] = core::array::from_fn(|c| values[c] > 0.0);
    if inside.iter().all(|&s| s) || inside.iter().all(|&s| !s) {
        return;
    }
    for tet in KUHN {
        // The tetrahedron's corners inside (f > 0) and outside, without allocating.
        let (mut ins, mut n_in) = ([0u8; 4], 0);
        let (mut outs, mut n_out) = ([0u8; 4], 0);
        for c in tet {
            if inside[c as usize] {
                ins[n_in] = c;
                n_in += 1;
            } else {
                outs[n_out] = c;
                n_out += 1;
            }
        }
        let (ins, outs) = (&ins[..n_in], &outs[..n_out]);
        let mut edge = |a: u8, b: u8| {
            // Kuhn tetrahedra have comparable corners: one is below the other on every axis.
            let (lo, hi) = if a & b == a { (a, b) } else { (b, a) };
            let p = corner(lo);
            let key = edge_key([cell[0] + p[0], cell[1] + p[1], cell[2] + p[2]], hi & !lo);
            edges.push((key, values[lo as usize], values[hi as usize]));
            key
        };
        let mid = |a: u8, b: u8| {
            let (pa, pb) = (corner(a), corner(b));
            core::array::from_fn::<f64, 3, _>(|d| 0.5 * (pa[d] + pb[d]) as f64)
        };
        let centre = |cs: &[u8]| {
            core::array::from_fn::<f64, 3, _>(|d| {
                cs.iter().map(|&c| corner(c)[d] as f64).sum::<f64>() / cs.len() as f64
            })
        };
        // Triangles as pairs of corners (the edges their vertices lie on).
        let (tris, count): ([[(u8, u8); 3]; 2], usize) = match (ins.len(), outs.len()) {
            (1, 3) => {
                let a = ins[0];
                let t = [(a, outs[0]), (a, outs[1]), (a, outs[2])];
                ([t, t], 1)
            }
            (3, 1) => {
                let d = outs[0];
                let t = [(ins[0], d), (ins[1], d), (ins[2], d)];
                ([t, t], 1)
            }
            (2, 2) => {
                let (a, b, c, d) = (ins[0], ins[1], outs[0], outs[1]);
                ([[(a, c), (a, d), (b, d)], [(a, c), (b, d), (b, c)]], 2)
            }
            _ => continue,
        };
        let (from, to) = (centre(ins), centre(outs));
        let direction = [to[0] - from[0], to[1] - from[1], to[2] - from[2]];
        for &t in &tris[..count] {
            let [p, q, r] = t.map(|(a, b)| mid(a, b));
            let n = rbf_core::vec3::cross(rbf_core::vec3::sub(q, p), rbf_core::vec3::sub(r, p));
            let keys = t.map(|(a, b)| edge(a, b));
            if rbf_core::vec3::dot(n, direction) >= 0.0 {
                out.push(keys);
            } else {
                out.push([keys[0], keys[2], keys[1]]);
            }
        }
    }
}
