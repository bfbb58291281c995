//! The triangle mesh.

use rbf_core::vec3::{cross, dot, sub};

use crate::MeshError;

/// A triangle mesh: positions, triangles (counter-clockwise seen from outside), and optional
/// per-vertex normals.
///
/// ```
/// use rbf_mesh::TriMesh;
/// let m = TriMesh::new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
/// )
/// .unwrap();
/// let report = m.check();
/// assert!(report.is_watertight());
/// assert_eq!(report.genus, Some(0));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct TriMesh {
    pub(crate) positions: Vec<[f64; 3]>,
    pub(crate) triangles: Vec<[u32; 3]>,
    pub(crate) normals: Option<Vec<[f64; 3]>>,
}

impl TriMesh {
    /// A mesh from positions and triangles; errors on no triangles, non-finite positions, or
    /// indices out of range.
    pub fn new(positions: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> Result<Self, MeshError> {
        if triangles.is_empty() {
            return Err(MeshError::Empty);
        }
        if let Some(v) = positions
            .iter()
            .position(|p| !p.iter().all(|c| c.is_finite()))
        {
            return Err(MeshError::NonFinite { vertex: v });
        }
        let n = positions.len();
        for (f, t) in triangles.iter().enumerate() {
            if let Some(&i) = t.iter().find(|&&i| i as usize >= n) {
                return Err(MeshError::IndexOutOfRange {
                    triangle: f,
                    index: i as usize,
                    vertices: n,
                });
            }
        }
        Ok(Self {
            positions,
            triangles,
            normals: None,
        })
    }

    /// Attaches per-vertex normals (one per position, finite).
    pub fn with_normals(mut self, normals: Vec<[f64; 3]>) -> Result<Self, MeshError> {
        if normals.len() != self.positions.len() {
            return Err(MeshError::Invalid(format!(
                "{} normals for {} vertices",
                normals.len(),
                self.positions.len()
            )));
        }
        if let Some(v) = normals
            .iter()
            .position(|p| !p.iter().all(|c| c.is_finite()))
        {
            return Err(MeshError::NonFinite { vertex: v });
        }
        self.normals = Some(normals);
        Ok(self)
    }

    /// Vertex positions.
    pub fn positions(&self) -> &[[f64; 3]] {
        &self.positions
    }
    /// Triangles as vertex indices.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }
    /// Per-vertex normals, if any.
    pub fn normals(&self) -> Option<&[[f64; 3]]> {
        self.normals.as_deref()
    }

    /// The axis-aligned bounding box (min, max) of the vertices used by triangles.
    pub fn bounding_box(&self) -> ([f64; 3], [f64; 3]) {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for t in &self.triangles {
            for &i in t {
                let p = self.positions[i as usize];
                for d in 0..3 {
                    lo[d] = lo[d].min(p[d]);
                    hi[d] = hi[d].max(p[d]);
                }
            }
        }
        (lo, hi)
    }

    /// The three corners of triangle `t`.
    pub fn corners(&self, t: usize) -> [[f64; 3]; 3] {
        self.triangles[t].map(|i| self.positions[i as usize])
    }

    /// Twice the area vector (cross product of two edges) of triangle `t`.
    pub fn area_vector(&self, t: usize) -> [f64; 3] {
        let [a, b, c] = self.corners(t);
        cross(sub(b, a), sub(c, a))
    }

    /// One normal per vertex: the mesh's own normals when it has them, otherwise the sum of
    /// the area vectors of the triangles around the vertex (area-weighted, not normalized);
    /// zero for a vertex that no triangle uses or whose triangles cancel.
    ///
    /// ```
    /// let ico = rbf_mesh::TriMesh::icosphere(0);
    /// let n = ico.vertex_normals();
    /// let p = ico.positions()[0];
    /// let cos = (0..3).map(|d| n[0][d] * p[d]).sum::<f64>()
    ///     / (n[0].iter().map(|x| x * x).sum::<f64>() * p.iter().map(|x| x * x).sum::<f64>()).sqrt();
    /// assert!(cos > 0.999); // outward, along the radius
    /// ```
    pub fn vertex_normals(&self) -> Vec<[f64; 3]> {
        if let Some(n) = &self.normals {
            return n.clone();
        }
        let mut normals = vec![[0.0; 3]; self.positions.len()];
        for t in 0..self.triangles.len() {
            let a = self.area_vector(t);
            for &v in &self.triangles[t] {
                normals[v as usize] = rbf_core::vec3::add(normals[v as usize], a);
            }
        }
        normals
    }

    /// The enclosed volume (signed: positive when triangles face outward).
    pub fn volume(&self) -> f64 {
        (0..self.triangles.len())
            .map(|t| {
                let [a, b, c] = self.corners(t);
                dot(a, cross(b, c))
            })
            .sum::<f64>()
            / 6.0
    }

    /// Reverses every triangle (flips the orientation).
    pub fn flip(&mut self) {
        for t in &mut self.triangles {
            t.swap(1, 2);
        }
        if let Some(n) = &mut self.normals {
            for v in n {
                *v = v.map(|c| -c);
            }
        }
    }
}
