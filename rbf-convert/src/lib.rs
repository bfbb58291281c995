//! # rbf-convert
//!
//! Polygon meshes to variational implicit surfaces, and blends of implicit surfaces ([`blend`]),
//! after two papers: Greg Turk and James F. O'Brien, "Modelling with Implicit Surfaces that
//! Interpolate", ACM Transactions on Graphics 21(4), 2002 (Turk & O'Brien 2002: normal
//! constraints, §4.3, and blending, §6); and Gary Yngve and Greg Turk, "Robust Creation of
//! Implicit Surfaces from Polygonal Meshes", IEEE Transactions on Visualization and Computer
//! Graphics 8(4), 2002 (Yngve & Turk 2002: the iterative conversion).
//!
//! [`convert_normals`] is the method of Turk & O'Brien (2002, §4.3): a boundary constraint at
//! each vertex and a normal constraint a small distance inside, against the vertex normal. For
//! meshes with more vertices than a dense solve should take, an evenly spread subset of the
//! vertices (Poisson-disk on the surface) is used, and the report says so.
//!
//! ```
//! use rbf_convert::{NormalSettings, convert_normals};
//! use rbf_mesh::TriMesh;
//! // An octahedron: six vertices, each with an outward normal.
//! let mesh = TriMesh::new(
//!     vec![[1., 0., 0.], [-1., 0., 0.], [0., 1., 0.], [0., -1., 0.], [0., 0., 1.], [0., 0., -1.]],
//!     vec![[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]],
//! )
//! .unwrap();
//! let (model, report) = convert_normals(&mesh, &NormalSettings::default(), |_| {}).unwrap();
//! assert_eq!(report.vertices_used, 6);
//! assert!(model.interpolant.value(&[0.0; 3]) > 0.0); // inside
//! assert!(model.interpolant.value(&[1.0, 0.0, 0.0]).abs() < 1e-9); // through the vertices
//! ```

mod blend;
mod compare;
mod error;
mod iterative;
mod normals;
mod poisson;
mod scans;

pub use blend::{BlendReport, blend};
pub use compare::{CompareSettings, DistanceStats, SurfaceDistance, surface_distance};
pub use error::ConvertError;
pub use iterative::{
    IterationReport, IterativeReport, IterativeSettings, RivalReport, TopologyReport,
    convert_iterative, convert_iterative_2d,
};
pub use normals::{NormalReport, NormalSettings, convert_normals};
#[doc(hidden)]
pub use poisson::poisson_subset;
pub use scans::{
    LARGEST_COORDINATE, ReconstructReport, ReconstructSettings, ScanSurface, mesh_resolution,
    reconstruct, scan_mesh, scan_surface, smoothing_for_noise, supported_pieces, trimmed,
};
