//! Polygonizers (Turk & O'Brien 2002, §7.1): from an interpolant to a triangle mesh
//! of its zero set.
//!
//! Both walk the same cube lattice and split each cube into six Kuhn tetrahedra, which fit
//! together across cubes and have no ambiguous cases: the output is watertight and manifold
//! wherever the surface is closed inside the box, with triangles facing outward (toward
//! f < 0). Vertices are placed on the surface by root finding along lattice edges, normals are
//! the normalized −∇f. Short edges are then collapsed and caps flipped (never moving a vertex,
//! always keeping the topology): about 0.8 times the triangles of marching cubes on the same
//! lattice, no angle under 5°, no two vertices nearly coincident.

mod continuation;
mod fans;
mod grid;
mod lattice;
mod roots;
mod simplify;

use rbf_core::{ConstraintKind, Model, ScalarField};

use crate::{MeshError, TriMesh};
use lattice::{Lattice, MAX_CELLS};

/// How fine the lattice is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Resolution {
    /// Edge length of a lattice cube, in the model's units.
    CellSize(f64),
    /// Cubes across the longest side of the box.
    Cells(usize),
}

/// Settings of both polygonizers.
///
/// ```
/// use rbf_mesh::{PolygonizeSettings, Resolution};
/// let s = PolygonizeSettings { resolution: Resolution::Cells(128), ..Default::default() };
/// assert_eq!(s.margin, 0.1);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PolygonizeSettings {
    /// Lattice resolution; 64 cubes across by default.
    pub resolution: Resolution,
    /// The box to polygonize. By default the centres' bounding box grown by `margin`, then
    /// grown further (up to eight times) while f > 0 anywhere on its faces, so that a closed
    /// surface lies inside it.
    pub bounds: Option<([f64; 3], [f64; 3])>,
    /// Growth of the default box on each side, as a fraction of its longest side. 0.1.
    pub margin: f64,
    /// How the grid method decides that a block of 4³ cubes holds no surface.
    pub skip: BlockSkip,
    /// Rounds of root finding along each edge (a secant step, then safeguarded Newton). 8.
    /// 0 leaves each vertex where the linear interpolation of f along its edge is zero, with
    /// no normal: the topology of f's signs at the lattice points, without evaluating f again.
    pub root_iterations: usize,
    /// Collapse the lattice's short edges and needle triangles (about half its vertices go;
    /// see the simplification's rules in `simplify.rs`). `false` keeps every vertex of the
    /// lattice's tetrahedra: the same topology, about twice the triangles, needles among them,
    /// in less time, for a caller that only measures the surface. `true`.
    pub simplify: bool,
}

impl Default for PolygonizeSettings {
    fn default() -> Self {
        Self {
            resolution: Resolution::Cells(64),
            bounds: None,
            margin: 0.1,
            skip: BlockSkip::Estimated,
            root_iterations: 8,
            simplify: true,
        }
    }
}

/// How the grid polygonizer skips blocks of 4³ cubes without sampling them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BlockSkip {
    /// Only when a Taylor bound from the kernel's derivatives and the weights proves f has one
    /// sign in the block. Never misses surface, but the bound is loose for models with large,
    /// cancelling weights (normal constraints), where it rarely skips.
    Proven,
    /// Also when f at the block's eight corners has one sign and |f| there exceeds half the
    /// block's diagonal (the farthest any point is from a corner) times 1.5 × the largest |∇f|
    /// at the corners (the sampled-gradient heuristic of Turk & O'Brien 2002, §7.2); or, where
    /// that fails on one-signed corners, when f at the block's centre has that sign too and |f| at the nine
    /// points exceeds √5 cubes (the farthest any point of the block is from one of them) times
    /// 1.5 × the largest |∇f| at them. Can miss a component smaller than a block. The default.
    Estimated,
    /// Sample every lattice point.
    Never,
}

/// Figures of a polygonization.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PolygonizeStats {
    /// Position of lattice point (0, 0, 0), the box's lowest corner.
    pub origin: [f64; 3],
    /// Edge length of a lattice cube, in the model's units.
    pub cell_size: f64,
    /// Cubes along x, y, z.
    pub cells: [usize; 3],
    /// Lattice points where f was sampled (not counting root finding).
    pub samples: usize,
    /// Blocks of 4³ cubes skipped because the surface cannot cross them (grid method).
    pub skipped_blocks: usize,
}

impl PolygonizeStats {
    fn of(lattice: &Lattice, samples: usize, skipped_blocks: usize) -> Self {
        Self {
            origin: lattice.origin,
            cell_size: lattice.h,
            cells: lattice.cells.map(|c| c as usize),
            samples,
            skipped_blocks,
        }
    }
}

impl PolygonizeSettings {
    fn lattice(&self, f: &dyn ScalarField<3>) -> Result<Lattice, MeshError> {
        let (lo, hi) = match self.bounds {
            Some(b) => b,
            None => f.direct().surface_box(self.margin),
        };
        let side = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
        if !(side > 0.0 && side.is_finite()) || lo.iter().chain(&hi).any(|v| !v.is_finite()) {
            return Err(MeshError::Invalid(format!(
                "the box {lo:?} – {hi:?} is empty or not finite"
            )));
        }
        let h = match self.resolution {
            Resolution::CellSize(h) => h,
            Resolution::Cells(n) => side / n as f64,
        };
        if !(h > 0.0 && h.is_finite()) {
            return Err(MeshError::Invalid(format!(
                "cell size {h} must be positive"
            )));
        }
        let cells: [i64; 3] =
            core::array::from_fn(|d| (((hi[d] - lo[d]) / h).ceil() as i64).max(1));
        if cells.iter().any(|&c| c > MAX_CELLS) {
            return Err(MeshError::Invalid(format!(
                "{cells:?} cubes: at most {MAX_CELLS} along each side; use a larger cell size"
            )));
        }
        Ok(Lattice {
            origin: lo,
            h,
            cells,
        })
    }
}

/// Polygonizes every component of f's zero set inside the box, sampling f coarse-to-fine:
/// f and ∇f are sampled at every fourth lattice point, and blocks of 4³ cubes that the
/// surface cannot cross are skipped (see [`BlockSkip`]).
///
/// ```
/// use rbf_core::{InterpolantView, Kernel};
/// use rbf_mesh::{PolygonizeSettings, Resolution, polygonize_grid};
/// // f = 1 − |x|³: the unit sphere.
/// let f = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
/// let s = PolygonizeSettings { bounds: Some(([-1.5; 3], [1.5; 3])), resolution: Resolution::Cells(20), ..Default::default() };
/// let (mesh, _) = polygonize_grid(&f, &s).unwrap();
/// let r = mesh.check();
/// assert!(r.is_watertight() && r.genus == Some(0) && r.volume > 0.0);
/// ```
pub fn polygonize_grid(
    f: &dyn ScalarField<3>,
    settings: &PolygonizeSettings,
) -> Result<(TriMesh, PolygonizeStats), MeshError> {
    let lattice = settings.lattice(f)?;
    let total = lattice.cells.iter().map(|&c| c as f64).product::<f64>();
    if total > MAX_GRID_CUBES {
        return Err(MeshError::Invalid(format!(
            "{:?} cubes: the grid method samples the whole box, at most {MAX_GRID_CUBES:.0e} cubes; \
             use a larger cell size, smaller bounds, or continuation",
            lattice.cells
        )));
    }
    let (edges, tris, samples, skipped) = grid::cells(f, &lattice, settings.skip);
    let (edges, tris) = lattice::number_edges(edges, tris);
    let stats = PolygonizeStats::of(&lattice, samples, skipped);
    if tris.is_empty() {
        return Err(MeshError::Invalid("no surface inside the box".into()));
    }
    Ok((roots::assemble(f, &lattice, edges, tris, settings)?, stats))
}

/// Polygonizes the components of f's zero set reached from `seeds` (points on or near the
/// surface) by continuation, evaluating f only near the surface.
pub fn polygonize_continuation(
    f: &dyn ScalarField<3>,
    seeds: &[[f64; 3]],
    settings: &PolygonizeSettings,
) -> Result<(TriMesh, PolygonizeStats), MeshError> {
    let lattice = settings.lattice(f)?;
    let (edges, tris, samples) = continuation::cells(f, &lattice, seeds);
    let stats = PolygonizeStats::of(&lattice, samples, 0);
    if tris.is_empty() {
        return Err(MeshError::Invalid("no surface found near the seeds".into()));
    }
    Ok((roots::assemble(f, &lattice, edges, tris, settings)?, stats))
}

/// The box of the surface reached from `seeds` by continuation, as [`polygonize_continuation`]
/// reaches it: the box of where the surface crosses the lattice's edges, each crossing placed
/// by linear interpolation between the edge's ends (so within a fraction of a cube of the
/// surface's own box); and the lattice's stats. Costs the continuation's sampling only (no
/// root finding, no triangles), so it is a cheap way to find where a surface is before
/// meshing it finely.
///
/// ```
/// use rbf_core::{InterpolantView, Kernel};
/// use rbf_mesh::{PolygonizeSettings, Resolution, surface_extent};
/// // f = 1 − |x|³: the unit sphere.
/// let f = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
/// let s = PolygonizeSettings { bounds: Some(([-2.0; 3], [2.0; 3])), resolution: Resolution::Cells(16), ..Default::default() };
/// let ((lo, hi), stats) = surface_extent(&f, &[[1.0, 0.0, 0.0]], &s).unwrap();
/// assert_eq!(stats.cell_size, 0.25);
/// assert!((0..3).all(|d| (lo[d] + 1.0).abs() < 0.05 && (hi[d] - 1.0).abs() < 0.05));
/// ```
pub fn surface_extent(
    f: &dyn ScalarField<3>,
    seeds: &[[f64; 3]],
    settings: &PolygonizeSettings,
) -> Result<(SurfaceBox, PolygonizeStats), MeshError> {
    let lattice = settings.lattice(f)?;
    let (edges, _, samples) = continuation::cells(f, &lattice, seeds);
    if edges.is_empty() {
        return Err(MeshError::Empty);
    }
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for &(key, a, b) in &edges {
        let (p, o) = lattice::edge_of(key);
        let t = if a != b {
            (a / (a - b)).clamp(0.0, 1.0)
        } else {
            0.5
        };
        let at = lattice.point(p);
        for d in 0..3 {
            let x = at[d] + t * o[d] as f64 * lattice.h;
            lo[d] = lo[d].min(x);
            hi[d] = hi[d].max(x);
        }
    }
    let stats = PolygonizeStats::of(&lattice, samples, 0);
    Ok(((lo, hi), stats))
}

/// A box, as its lowest and highest corners.
pub type SurfaceBox = ([f64; 3], [f64; 3]);

/// The most cubes [`polygonize_grid`] lays over its box (1625³): its block corners alone then
/// take half a gigabyte.
const MAX_GRID_CUBES: f64 = 4.3e9;

/// Seeds for continuation from a model: its boundary constraints and the boundary points of its
/// normal constraints, which lie on the surface by construction.
pub fn surface_seeds(model: &Model<3>) -> Vec<[f64; 3]> {
    model
        .constraints
        .iter()
        .filter(|c| matches!(c.kind, ConstraintKind::Boundary | ConstraintKind::Normal))
        .map(|c| c.position)
        .collect()
}
