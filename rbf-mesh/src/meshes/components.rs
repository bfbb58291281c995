//! A mesh's connected pieces, and a mesh of some of them.

use super::check::UnionFind;
use crate::{MeshError, TriMesh};

impl TriMesh {
    /// The triangles of each connected piece (triangles that share a vertex are connected),
    /// largest piece first.
    ///
    /// ```
    /// use rbf_mesh::TriMesh;
    /// let mesh = TriMesh::new(
    ///     vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [5.0, 0.0, 0.0], [6.0, 0.0, 0.0], [5.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [3, 4, 5]],
    /// ).unwrap();
    /// assert_eq!(mesh.components(), vec![vec![0], vec![1]]);
    /// ```
    pub fn components(&self) -> Vec<Vec<usize>> {
        let mut sets = UnionFind::new(self.positions.len());
        for &[a, b, c] in &self.triangles {
            sets.union(a, b);
            sets.union(b, c);
        }
        let mut index = vec![usize::MAX; self.positions.len()];
        let mut pieces: Vec<Vec<usize>> = Vec::new();
        for (t, &[a, _, _]) in self.triangles.iter().enumerate() {
            let root = sets.find(a) as usize;
            if index[root] == usize::MAX {
                index[root] = pieces.len();
                pieces.push(Vec::new());
            }
            pieces[index[root]].push(t);
        }
        pieces.sort_by_key(|p| std::cmp::Reverse(p.len()));
        pieces
    }

    /// The mesh of the given triangles only, with the vertices they use (and their normals).
    ///
    /// ```
    /// use rbf_mesh::TriMesh;
    /// let mesh = TriMesh::new(
    ///     vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [5.0, 0.0, 0.0], [6.0, 0.0, 0.0], [5.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [3, 4, 5]],
    /// ).unwrap();
    /// let second = mesh.with_triangles(&[1]).unwrap();
    /// assert_eq!(second.positions()[0], [5.0, 0.0, 0.0]);
    /// assert_eq!(second.triangles(), &[[0, 1, 2]]);
    /// ```
    pub fn with_triangles(&self, keep: &[usize]) -> Result<TriMesh, MeshError> {
        let mut map = vec![u32::MAX; self.positions.len()];
        let mut positions = Vec::new();
        let mut normals = Vec::new();
        let mut triangles = Vec::with_capacity(keep.len());
        for &t in keep {
            let Some(triangle) = self.triangles.get(t) else {
                return Err(MeshError::Invalid(format!(
                    "triangle {t} of a mesh of {}",
                    self.triangles.len()
                )));
            };
            triangles.push(triangle.map(|v| {
                let v = v as usize;
                if map[v] == u32::MAX {
                    map[v] = positions.len() as u32;
                    positions.push(self.positions[v]);
                    if let Some(n) = &self.normals {
                        normals.push(n[v]);
                    }
                }
                map[v]
            }));
        }
        let mesh = TriMesh::new(positions, triangles)?;
        if self.normals.is_some() {
            mesh.with_normals(normals)
        } else {
            Ok(mesh)
        }
    }
}
