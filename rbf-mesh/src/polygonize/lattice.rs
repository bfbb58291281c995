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

/// A lattice edge crossed by the surface, with f at its lower and upper ends.
pub(crate) type CrossedEdge = (u64, f64, f64);

/// The triangles of one sign case of a cube: each as its three edges, an edge as its lower and
/// upper corner, oriented from inside to outside.
#[derive(Clone, Copy)]
struct CubeCase {
    count: u8,
    triangles: [[(u8, u8); 3]; 12],
}

/// The triangles of each of the 256 sign cases (bit c set when corner c is inside), made once.
fn cube_cases() -> &'static [CubeCase; 256] {
    static CASES: std::sync::OnceLock<Box<[CubeCase; 256]>> = std::sync::OnceLock::new();
    CASES.get_or_init(|| {
        let mut cases = Box::new(
            [CubeCase {
                count: 0,
                triangles: [[(0, 0); 3]; 12],
            }; 256],
        );
        for (bits, case) in cases.iter_mut().enumerate() {
            for t in case_triangles(bits as u8) {
                case.triangles[case.count as usize] = t;
                case.count += 1;
            }
        }
        cases
    })
}

/// The triangles of the Kuhn tetrahedra of a cube whose inside corners are the set bits, each
/// as three (lower, upper) corner pairs, oriented so that its normal points from the inside
/// corners of its tetrahedron to the outside ones.
fn case_triangles(bits: u8) -> Vec<[(u8, u8); 3]> {
    let inside = |c: u8| bits & (1 << c) != 0;
    let mid = |a: u8, b: u8| {
        let (pa, pb) = (corner(a), corner(b));
        core::array::from_fn::<f64, 3, _>(|d| 0.5 * (pa[d] + pb[d]) as f64)
    };
    let centre = |cs: &[u8]| {
        core::array::from_fn::<f64, 3, _>(|d| {
            cs.iter().map(|&c| corner(c)[d] as f64).sum::<f64>() / cs.len() as f64
        })
    };
    // Kuhn tetrahedra have comparable corners: one is below the other on every axis.
    let ordered = |(a, b): (u8, u8)| if a & b == a { (a, b) } else { (b, a) };
    let mut found = Vec::new();
    for tet in KUHN {
        let ins: Vec<u8> = tet.into_iter().filter(|&c| inside(c)).collect();
        let outs: Vec<u8> = tet.into_iter().filter(|&c| !inside(c)).collect();
        // Triangles as pairs of corners (the edges their vertices lie on).
        let tris: Vec<[(u8, u8); 3]> = match (ins.len(), outs.len()) {
            (1, 3) => vec![[(ins[0], outs[0]), (ins[0], outs[1]), (ins[0], outs[2])]],
            (3, 1) => vec![[(ins[0], outs[0]), (ins[1], outs[0]), (ins[2], outs[0])]],
            (2, 2) => {
                let (a, b, c, d) = (ins[0], ins[1], outs[0], outs[1]);
                vec![[(a, c), (a, d), (b, d)], [(a, c), (b, d), (b, c)]]
            }
            _ => continue,
        };
        let (from, to) = (centre(&ins), centre(&outs));
        let direction = rbf_core::vec3::sub(to, from);
        for t in tris {
            let [p, q, r] = t.map(|(a, b)| mid(a, b));
            let n = rbf_core::vec3::cross(rbf_core::vec3::sub(q, p), rbf_core::vec3::sub(r, p));
            let t = t.map(ordered);
            found.push(if rbf_core::vec3::dot(n, direction) >= 0.0 {
                t
            } else {
                [t[0], t[2], t[1]]
            });
        }
    }
    found
}

/// Appends the triangles of the cell at `cell` (lowest corner) given its eight corner values
/// (index = corner bits) to `out`, oriented so that their normals point from inside (f > 0) to
/// outside. A triangle's corners are the numbers `vertex` gives its edges: `vertex(key, f at
/// the lower end, f at the upper end)`.
pub(crate) fn cell_triangles(
    cell: [i64; 3],
    values: &[f64; 8],
    out: &mut Vec<[u32; 3]>,
    mut vertex: impl FnMut(u64, f64, f64) -> u32,
) {
    let bits = (0..8).fold(0u8, |b, c| b | (((values[c] > 0.0) as u8) << c));
    if bits == 0 || bits == u8::MAX {
        return;
    }
    let case = &cube_cases()[bits as usize];
    for t in &case.triangles[..case.count as usize] {
        out.push(t.map(|(lo, hi)| {
            let p = corner(lo);
            let key = edge_key([cell[0] + p[0], cell[1] + p[1], cell[2] + p[2]], hi & !lo);
            vertex(key, values[lo as usize], values[hi as usize])
        }));
    }
}

/// One vertex per distinct edge: `edges` may list an edge more than once and `triangles`
/// index into it; returns each edge once, and the triangles on those numbers.
pub(crate) fn number_edges(
    edges: Vec<CrossedEdge>,
    triangles: Vec<[u32; 3]>,
) -> (Vec<CrossedEdge>, Vec<[u32; 3]>) {
    use rayon::prelude::*;
    // Sort the keys with where they came from (in parallel when many), then number them, dropping
    // repeats.
    let mut order: Vec<(u64, u32)> = edges
        .iter()
        .enumerate()
        .map(|(i, e)| (e.0, i as u32))
        .collect();
    if order.len() >= super::simplify::PARALLEL_SORT {
        order.par_sort_unstable();
    } else {
        order.sort_unstable();
    }
    let mut unique: Vec<CrossedEdge> = Vec::new();
    let mut vertex_of = vec![0u32; edges.len()];
    for &(key, i) in &order {
        if unique.last().is_none_or(|e| e.0 != key) {
            unique.push(edges[i as usize]);
        }
        vertex_of[i as usize] = (unique.len() - 1) as u32;
    }
    let triangles = triangles
        .into_par_iter()
        .map(|t| t.map(|i| vertex_of[i as usize]))
        .collect();
    (unique, triangles)
}
