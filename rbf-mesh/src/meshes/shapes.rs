//! Test shapes.

use std::collections::HashMap;

use crate::TriMesh;

impl TriMesh {
    /// The unit icosphere: an icosahedron whose triangles are split in four `subdivisions`
    /// times, projected on the unit sphere (20 · 4ⁿ faces; the mesh of
    /// `trimesh.creation.icosphere(n)`). Closed, genus 0, faces outward.
    ///
    /// ```
    /// let s = rbf_mesh::TriMesh::icosphere(2);
    /// assert_eq!(s.triangles().len(), 320);
    /// assert!(s.check().is_watertight() && s.volume() > 0.0);
    /// ```
    pub fn icosphere(subdivisions: usize) -> TriMesh {
        let t = (1.0 + 5f64.sqrt()) / 2.0;
        let mut positions: Vec<[f64; 3]> = [
            [-1.0, t, 0.0],
            [1.0, t, 0.0],
            [-1.0, -t, 0.0],
            [1.0, -t, 0.0],
            [0.0, -1.0, t],
            [0.0, 1.0, t],
            [0.0, -1.0, -t],
            [0.0, 1.0, -t],
            [t, 0.0, -1.0],
            [t, 0.0, 1.0],
            [-t, 0.0, -1.0],
            [-t, 0.0, 1.0],
        ]
        .to_vec();
        let mut faces: Vec<[u32; 3]> = vec![
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ];
        for _ in 0..subdivisions {
            let mut midpoint = HashMap::new();
            let mut next = Vec::with_capacity(faces.len() * 4);
            for [a, b, c] in faces {
                let mut mid = |u: u32, v: u32| {
                    *midpoint.entry((u.min(v), u.max(v))).or_insert_with(|| {
                        let (p, q) = (positions[u as usize], positions[v as usize]);
                        positions.push(core::array::from_fn(|d| 0.5 * (p[d] + q[d])));
                        (positions.len() - 1) as u32
                    })
                };
                let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
                next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
            }
            faces = next;
        }
        for p in &mut positions {
            let l = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            *p = p.map(|x| x / l);
        }
        TriMesh {
            positions,
            triangles: faces,
            normals: None,
        }
    }
}
