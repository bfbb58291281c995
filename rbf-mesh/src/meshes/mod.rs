//! Triangle meshes: the mesh itself, its checks (holes, non-manifold edges, orientation,
//! components, genus), its pieces, built-in shapes, and the hash maps they share.

mod check;
mod closed_topology;
mod components;
pub(crate) mod hash;
mod mesh;
mod shapes;

pub use check::MeshReport;
pub use mesh::TriMesh;
