//! How far a model's surface lies from a mesh, measured both ways on points spread over each.
//!
//! The loop's own error (Yngve & Turk 2002, eq. 6–7) compares sets of boundary voxels, so it moves
//! in whole voxels. This is the geometric distance instead: points spread by area over the mesh
//! are measured to the model's surface, and points spread over the model's surface to the
//! mesh, each to the nearest point of the other.

use rayon::prelude::*;
use rbf_core::InterpolantView;
use rbf_mesh::{
    PolygonizeSettings, Resolution, TriMesh, WindingTree, polygonize_grid, sample_surface,
};

use crate::ConvertError;

/// Settings of [`surface_distance`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CompareSettings {
    /// Points spread over each surface: 20 000.
    pub samples: usize,
    /// Cubes across the longest side of the mesh's box for polygonizing the model, whose
    /// triangles stand in for its surface: 256. The polygon's distance from the true surface
    /// falls with the square of the cube size.
    pub resolution: usize,
    /// Seed of the sample positions: 1.
    pub seed: u64,
}

impl Default for CompareSettings {
    fn default() -> Self {
        Self {
            samples: 20_000,
            resolution: 256,
            seed: 1,
        }
    }
}

/// Mean, root-mean-square and largest of a set of distances.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DistanceStats {
    /// Mean distance.
    pub mean: f64,
    /// Root-mean-square distance.
    pub rms: f64,
    /// Largest distance.
    pub max: f64,
}

impl DistanceStats {
    fn of(distances: &[f64]) -> Self {
        let n = distances.len().max(1) as f64;
        Self {
            mean: distances.iter().sum::<f64>() / n,
            rms: (distances.iter().map(|d| d * d).sum::<f64>() / n).sqrt(),
            max: distances.iter().copied().fold(0.0, f64::max),
        }
    }
}

/// The two-way distance between a model's surface and a mesh, in the model's units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceDistance {
    /// From points on the mesh to the model's surface.
    pub mesh_to_surface: DistanceStats,
    /// From points on the model's surface to the mesh.
    pub surface_to_mesh: DistanceStats,
    /// Points measured each way.
    pub samples: usize,
    /// Cube size of the polygonization that stands in for the model's surface.
    pub cell_size: f64,
}

impl SurfaceDistance {
    /// The larger of the two largest distances: the sampled two-way Hausdorff distance.
    pub fn hausdorff(&self) -> f64 {
        self.mesh_to_surface.max.max(self.surface_to_mesh.max)
    }
}

/// Measures how far the zero set of `f` lies from `mesh`, both ways.
///
/// ```
/// use rbf_convert::{CompareSettings, surface_distance};
/// use rbf_core::{Constraint, FitSettings, fit};
/// use rbf_mesh::TriMesh;
/// // A sphere through the 42 vertices of an icosphere, against a finer icosphere.
/// let mut constraints: Vec<Constraint<3>> =
///     TriMesh::icosphere(1).positions().iter().map(|&p| Constraint::boundary(p)).collect();
/// constraints.push(Constraint::interior([0.0; 3], 1.0));
/// let f = fit(&constraints, &FitSettings::default()).unwrap().interpolant;
/// let settings = CompareSettings { samples: 2000, resolution: 64, ..Default::default() };
/// let d = surface_distance(&f.view(), &TriMesh::icosphere(3), &settings).unwrap();
/// assert!(d.hausdorff() < 0.1, "{d:?}");
/// ```
pub fn surface_distance(
    f: &InterpolantView<'_, f64, 3>,
    mesh: &TriMesh,
    settings: &CompareSettings,
) -> Result<SurfaceDistance, ConvertError> {
    let mesh_points = sample_surface(mesh, settings.samples, settings.seed);
    if mesh_points.is_empty() {
        return Err(ConvertError::NoArea);
    }
    let (lo, hi) = mesh.bounding_box();
    let longest = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
    let cell_size = longest / settings.resolution.max(1) as f64;
    let polygonize = PolygonizeSettings {
        resolution: Resolution::CellSize(cell_size),
        ..Default::default()
    };
    let (surface, _) = polygonize_grid(f, &polygonize)?;
    let surface_points = sample_surface(&surface, settings.samples, settings.seed);
    if surface_points.is_empty() {
        return Err(ConvertError::NoSurface);
    }
    let to = |tree: &WindingTree, points: &[[f64; 3]]| -> Vec<f64> {
        points
            .par_iter()
            .map(|&p| {
                tree.closest_point(p, f64::INFINITY)
                    .map_or(f64::INFINITY, |(_, d)| d)
            })
            .collect()
    };
    let to_surface = to(&WindingTree::new(&surface), &mesh_points);
    let to_mesh = to(&WindingTree::new(mesh), &surface_points);
    Ok(SurfaceDistance {
        mesh_to_surface: DistanceStats::of(&to_surface),
        surface_to_mesh: DistanceStats::of(&to_mesh),
        samples: settings.samples,
        cell_size,
    })
}
