//! What a user needs to know about a mesh before trusting it.

use super::hash::FastMap;

use crate::TriMesh;
use rbf_core::vec3::norm;

/// The checks of a mesh. A mesh is watertight when it has no boundary or non-manifold edges
/// and a consistent orientation.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshReport {
    /// Vertices referenced by triangles.
    pub vertices: usize,
    /// Vertices no triangle refers to (ignored by every other count).
    pub unused_vertices: usize,
    /// All triangles, degenerate and duplicate ones included.
    pub triangles: usize,
    /// Distinct undirected edges.
    pub edges: usize,
    /// Edges with one triangle (holes).
    pub boundary_edges: usize,
    /// Edges with more than two triangles.
    pub non_manifold_edges: usize,
    /// Vertices whose triangles form more than one fan.
    pub non_manifold_vertices: usize,
    /// Edges shared by two triangles that traverse it in the same direction.
    pub inconsistent_edges: usize,
    /// Triangles with a repeated vertex or exactly zero area.
    pub degenerate_triangles: usize,
    /// Triangles with the same three vertices as an earlier one.
    pub duplicate_triangles: usize,
    /// Connected components (through shared vertices).
    pub components: usize,
    /// V − E + F over referenced vertices, edges and triangles: 2 for one closed sphere-like mesh.
    pub euler_characteristic: i64,
    /// Σ (2 − χᵢ)/2 over components, when the mesh is a closed orientable manifold.
    pub genus: Option<i64>,
    /// Bounding box (min, max).
    pub bounding_box: ([f64; 3], [f64; 3]),
    /// Signed volume (positive when triangles face outward), meaningful when watertight.
    pub volume: f64,
}

impl MeshReport {
    /// No holes, no non-manifold edges or vertices, orientation consistent.
    pub fn is_watertight(&self) -> bool {
        self.boundary_edges == 0
            && self.non_manifold_edges == 0
            && self.non_manifold_vertices == 0
            && self.inconsistent_edges == 0
    }
}

/// Disjoint sets of vertex indices.
pub(crate) struct UnionFind(Vec<u32>);

impl UnionFind {
    pub(crate) fn new(n: usize) -> Self {
        Self((0..n as u32).collect())
    }
    /// Makes this `n` singletons again, keeping the allocation.
    pub(crate) fn reset(&mut self, n: usize) {
        self.0.clear();
        self.0.extend(0..n as u32);
    }
    pub(crate) fn find(&mut self, mut x: u32) -> u32 {
        while self.0[x as usize] != x {
            let parent = self.0[self.0[x as usize] as usize];
            self.0[x as usize] = parent;
            x = parent;
        }
        x
    }
    pub(crate) fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.0[ra.max(rb) as usize] = ra.min(rb);
        }
    }
}

impl TriMesh {
    /// Runs every check.
    pub fn check(&self) -> MeshReport {
        let n = self.positions().len();
        let tris = self.triangles();
        // Undirected edge → (triangle count, forward traversals a→b with a < b).
        let mut edges: FastMap<(u32, u32), (u32, u32)> = FastMap::default();
        edges.reserve(tris.len() * 2);
        let mut used = vec![false; n];
        let mut degenerate = 0;
        let (lo, hi) = self.bounding_box();
        let mut seen = FastMap::default();
        seen.reserve(tris.len());
        let mut duplicates = 0;
        for (t, tri) in tris.iter().enumerate() {
            let [a, b, c] = *tri;
            for &v in tri {
                used[v as usize] = true;
            }
            if a == b || b == c || a == c || norm(self.area_vector(t)) == 0.0 {
                degenerate += 1;
            }
            let mut key = *tri;
            key.sort_unstable();
            if seen.insert(key, t).is_some() {
                duplicates += 1;
            }
            for (u, v) in [(a, b), (b, c), (c, a)] {
                if u == v {
                    continue;
                }
                let e = edges.entry((u.min(v), u.max(v))).or_insert((0, 0));
                e.0 += 1;
                if u < v {
                    e.1 += 1;
                }
            }
        }
        let mut boundary = 0;
        let mut non_manifold = 0;
        let mut inconsistent = 0;
        for &(count, forward) in edges.values() {
            match count {
                1 => boundary += 1,
                2 if forward != 1 => inconsistent += 1,
                2 => {}
                _ => non_manifold += 1,
            }
        }

        // Fans around each vertex: triangles at v joined when they share an edge at v. The
        // triangles at each vertex are laid out one vertex after another (`first[v]..first[v + 1]`).
        let mut first = vec![0u32; n + 1];
        for tri in tris {
            for &v in tri {
                first[v as usize + 1] += 1;
            }
        }
        for v in 0..n {
            first[v + 1] += first[v];
        }
        let mut fill = first.clone();
        let mut at_vertex = vec![0u32; 3 * tris.len()];
        for (t, tri) in tris.iter().enumerate() {
            for &v in tri {
                at_vertex[fill[v as usize] as usize] = t as u32;
                fill[v as usize] += 1;
            }
        }
        let mut non_manifold_vertices = 0;
        let mut by_other: Vec<(u32, u32)> = Vec::new();
        let mut fan = UnionFind::new(0);
        for v in 0..n {
            let faces = &at_vertex[first[v] as usize..first[v + 1] as usize];
            if faces.len() < 2 {
                continue;
            }
            fan.reset(faces.len());
            by_other.clear();
            for (i, &f) in faces.iter().enumerate() {
                for &w in &tris[f as usize] {
                    if w as usize == v {
                        continue;
                    }
                    match by_other.iter().find(|&&(o, _)| o == w) {
                        Some(&(_, j)) => fan.union(i as u32, j),
                        None => by_other.push((w, i as u32)),
                    }
                }
            }
            let roots = (0..faces.len() as u32)
                .filter(|&i| fan.find(i) == i)
                .count();
            if roots > 1 {
                non_manifold_vertices += 1;
            }
        }

        let mut uf = UnionFind::new(n);
        for &[a, b, c] in tris {
            uf.union(a, b);
            uf.union(b, c);
        }
        let vertices = used.iter().filter(|&&u| u).count();
        // Vertices, edges and triangles of each component, at its root.
        let mut per_root: Vec<(i64, i64, i64)> = vec![(0, 0, 0); n];
        for (v, &u) in used.iter().enumerate() {
            if u {
                per_root[uf.find(v as u32) as usize].0 += 1;
            }
        }
        for &(a, _) in edges.keys() {
            per_root[uf.find(a) as usize].1 += 1;
        }
        for &[a, _, _] in tris {
            per_root[uf.find(a) as usize].2 += 1;
        }
        let per_component: Vec<(i64, i64, i64)> =
            per_root.into_iter().filter(|c| c.0 > 0).collect();
        let euler = vertices as i64 - edges.len() as i64 + tris.len() as i64;
        let closed =
            boundary == 0 && non_manifold == 0 && non_manifold_vertices == 0 && inconsistent == 0;
        let genus = closed.then(|| {
            per_component
                .iter()
                .map(|(v, e, f)| (2 - (v - e + f)) / 2)
                .sum()
        });
        MeshReport {
            vertices,
            unused_vertices: n - vertices,
            triangles: tris.len(),
            edges: edges.len(),
            boundary_edges: boundary,
            non_manifold_edges: non_manifold,
            non_manifold_vertices,
            inconsistent_edges: inconsistent,
            degenerate_triangles: degenerate,
            duplicate_triangles: duplicates,
            components: per_component.len(),
            euler_characteristic: euler,
            genus,
            bounding_box: (lo, hi),
            volume: self.volume(),
        }
    }
}
