//! # rbf-cloud
//!
//! The geometry of point clouds that surface reconstruction needs before any fitting: each
//! point's nearest neighbours ([`Neighbours`], one k-d tree, kiddo's), repeated points
//! ([`distinct_points`]), statistical outliers
//! ([`statistical_outliers`]), normals from local planes ([`estimate_normals`]) and their
//! consistent orientation over a minimum spanning tree of the neighbour graph
//! ([`orient_normals`], Hoppe et al. 1992 with König & Gumhold 2009's edge weights), how far
//! off the surface each point may place constraints ([`clear_offsets`]), and how far points
//! are from the cloud ([`distances_to_cloud`]), all through one k-d tree type ([`PointTree`],
//! which other crates' searches share). No solver
//! lives here: the reconstruction pipeline takes these and fits.
//!
//! ```
//! use rbf_cloud::{Neighbours, estimate_normals, orient_normals};
//! // Points on the unit sphere.
//! let points: Vec<[f64; 3]> = (0..400)
//!     .map(|i| {
//!         let z = 1.0 - (2 * i + 1) as f64 / 400.0;
//!         let t = 2.399963 * i as f64;
//!         let s = (1.0 - z * z).sqrt();
//!         [s * t.cos(), s * t.sin(), z]
//!     })
//!     .collect();
//! let near = Neighbours::new(&points, 10);
//! let normals = estimate_normals(&points, &near);
//! let oriented = orient_normals(&points, &normals, &near);
//! // Every normal points away from the centre.
//! assert!(points.iter().zip(&oriented.normals).all(|(p, n)| p[0] * n[0] + p[1] * n[1] + p[2] * n[2] > 0.9));
//! ```

mod distance;
mod duplicates;
mod neighbours;
mod normals;
mod offsets;
mod orientation;
mod outliers;
mod tree;

pub use distance::distances_to_cloud;
pub use duplicates::distinct_points;
pub use neighbours::Neighbours;
pub use normals::{estimate_normals, estimate_normals_spanning_lines, line_share, normal_of};
pub use offsets::{clear_offsets, clear_offsets_with_tree};
pub use orientation::{Orientation, orient_normals};
pub use outliers::statistical_outliers;
pub use tree::PointTree;
