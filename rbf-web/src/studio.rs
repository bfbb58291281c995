//! The studio's engine in plain Rust (tested natively): a sculpting session, its surface as
//! triangle buffers ready for WebGL, its handles, and the files it reads and writes.

use std::path::Path;

use rbf_core::{AnyModel, Model};
use rbf_mesh::{
    MeshError, PolygonizeSettings, Resolution, TriMesh, polygonize_continuation, surface_extent,
    surface_seeds,
};
use rbf_sculpt::{Answer, Item, SculptError, Session};

/// Lattice cubes across the surface's box while a handle is dragged.
pub const COARSE_CELLS: usize = 16;
/// Lattice cubes across the surface's box when an edit is done (normals come from ∇f, so the
/// shading is smooth at this size).
pub const FINE_CELLS: usize = 28;
/// Lattice cubes across the constraints' box in the pass that finds the surface's own box.
pub const SCOUT_CELLS: usize = 12;
/// Rows a model may bring: the session factors them densely in one browser thread (about 3 s
/// and 50 MB at this size; each undo refactors).
pub const MAX_MODEL_ROWS: usize = 2500;
/// A dropped mesh gives at most this many vertices (two rows each) to its normal constraints:
/// a dense solve in one browser thread stays within a few seconds.
pub const MAX_MESH_VERTICES: usize = 700;

/// Why the studio could not do what was asked; the page shows the message as it is, and the
/// session is left as it was.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum StudioError {
    /// A model file that does not read.
    #[error("{file}: {source}")]
    Model {
        /// The file's name, as dropped or given.
        file: String,
        /// What is wrong in it.
        source: rbf_core::FileError,
    },
    /// A model too large to edit at interactive speed in a browser.
    #[error(
        "{file} has {rows} rows (normal constraints count twice): the studio edits up to {limit}; fit fewer points, or convert the mesh with `rbf convert --method normals --max-constraints 1200`"
    )]
    TooLarge {
        /// The file's name.
        file: String,
        /// Rows of its system.
        rows: usize,
        /// [`MAX_MODEL_ROWS`].
        limit: usize,
    },
    /// A 2D model: the studio sculpts surfaces.
    #[error(
        "{0} is a 2D model: the studio sculpts surfaces in 3D (curves are drawn with `rbf plot`)"
    )]
    TwoDimensional(String),
    /// A mesh file that does not read or cannot be written.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// A dropped mesh that could not be converted.
    #[error(transparent)]
    Convert(#[from] rbf_convert::ConvertError),
    /// An edit the session refused.
    #[error(transparent)]
    Sculpt(#[from] SculptError),
}

/// The surface as the page draws it: flat `f32` buffers, three entries a vertex.
#[derive(Clone, Debug, Default)]
pub struct Surface {
    /// Vertex positions, x y z per vertex.
    pub positions: Vec<f32>,
    /// Unit outward normals, one per vertex.
    pub normals: Vec<f32>,
    /// Three vertex indices per triangle, counter-clockwise seen from outside.
    pub indices: Vec<u32>,
    /// The mesh itself, for export.
    pub mesh: Option<TriMesh>,
}

/// A handle as the page draws it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Handle {
    /// The item's index in the session (stable across edits).
    pub index: usize,
    /// 0 boundary, 1 interior, 2 exterior, 3 normal handle.
    pub kind: u8,
    /// Where it is: the point, or a normal handle's tip.
    pub position: [f64; 3],
    /// For a normal handle, its boundary point (the other end of its stick); else `position`.
    pub base: [f64; 3],
}

/// A session with its surface.
///
/// ```
/// let mut studio = rbf_web::Studio::new().unwrap();
/// assert_eq!(studio.handles().len(), 12); // the paper's start
/// assert!(studio.surface().indices.len() > 300);
/// let answer = studio.run("add 0 0 1.3").line(0.5);
/// assert!(answer.starts_with("item 12 added"), "{answer}");
/// assert_eq!(studio.handles().len(), 13);
/// ```
pub struct Studio {
    session: Session,
    surface: Surface,
}

impl Studio {
    /// The paper's start (Turk & O'Brien 2002, §5): a blob through a tetrahedron's corners, in
    /// a cube of exterior constraints.
    pub fn new() -> Result<Self, StudioError> {
        Self::with_session(Session::new()?)
    }

    /// A studio on a model file (the JSON of `rbf fit`, `rbf convert` or a saved session);
    /// `name` names it in errors.
    pub fn from_model_json(name: &str, text: &str) -> Result<Self, StudioError> {
        let model = match AnyModel::from_json(text) {
            Ok(AnyModel::Three(model)) => model,
            Ok(AnyModel::Two(_)) => return Err(StudioError::TwoDimensional(name.into())),
            Err(source) => {
                return Err(StudioError::Model {
                    file: name.into(),
                    source,
                });
            }
        };
        let rows: usize = model.constraints.iter().map(|c| c.rows()).sum();
        if rows > MAX_MODEL_ROWS {
            return Err(StudioError::TooLarge {
                file: name.into(),
                rows,
                limit: MAX_MODEL_ROWS,
            });
        }
        Self::with_session(Session::from_model(&model)?)
    }

    /// A studio on a mesh file (OBJ, PLY or STL, by `name`'s extension), converted by normal
    /// constraints at an evenly spread subset of at most [`MAX_MESH_VERTICES`] vertices
    /// (Turk & O'Brien 2002, §4.3), as `rbf convert --method normals` thins large meshes.
    pub fn from_mesh(name: &str, bytes: &[u8]) -> Result<Self, StudioError> {
        let mesh = rbf_mesh::read_mesh_bytes(Path::new(name), bytes)?;
        let settings = rbf_convert::NormalSettings {
            max_vertices: MAX_MESH_VERTICES,
            ..Default::default()
        };
        let (model, _) = rbf_convert::convert_normals(&mesh, &settings, |_| {})?;
        Self::with_session(Session::from_model(&model)?)
    }

    fn with_session(session: Session) -> Result<Self, StudioError> {
        let mut studio = Self {
            session,
            surface: Surface::default(),
        };
        studio.remesh(FINE_CELLS)?;
        Ok(studio)
    }

    /// The current surface.
    pub fn surface(&self) -> &Surface {
        &self.surface
    }

    /// The session's model, as `rbf sculpt` writes it.
    pub fn model(&self) -> Model<3> {
        self.session.model()
    }

    /// Re-polygonizes the surface at `cells` lattice cubes across the surface's own box, by
    /// continuation from the boundary items: a first pass at [`SCOUT_CELLS`] across the
    /// centres' box (which exterior constraints far out make large) finds the surface's
    /// box (`surface_extent`: sampling only, no mesh); the second meshes that box, grown by
    /// a tenth of its size (at least a scouting cube); should the surface reach its faces, the
    /// centres' box (checked by `surface_box`) is meshed instead. A surface that cannot be
    /// meshed (f does not change sign near the items) leaves an empty surface, not an error:
    /// the next edit may bring it back.
    pub fn remesh(&mut self, cells: usize) -> Result<(), StudioError> {
        let model = self.session.model();
        let view = model.interpolant.view();
        // Values and gradients in f32 (four SIMD lanes, not two): see `single.rs`.
        let field = crate::single::SinglePrecision::new(&model.interpolant);
        let seeds = surface_seeds(&model);
        let polygonize = |resolution: usize, bounds: Option<([f64; 3], [f64; 3])>| {
            let settings = PolygonizeSettings {
                resolution: Resolution::Cells(resolution),
                bounds,
                ..Default::default()
            };
            polygonize_continuation(&field, &seeds, &settings)
        };
        // Scouting first in the centres' box grown by the usual margin, without the faces'
        // check of `surface_box` (a sixth of the evaluations of an edit). A surface that the
        // box cuts has crossings on its faces; one that comes within half a scouting cube of
        // them is scouted again in the checked box.
        let scout_in = |bounds: Option<([f64; 3], [f64; 3])>| {
            let settings = PolygonizeSettings {
                resolution: Resolution::Cells(SCOUT_CELLS),
                bounds,
                ..Default::default()
            };
            match surface_extent(&field, &seeds, &settings) {
                Ok((extent, stats)) => Ok(Some((extent, stats.cell_size))),
                Err(MeshError::Empty) => Ok(None),
                Err(e) => Err(e),
            }
        };
        let centres = grown_centre_box(view.centres(), PolygonizeSettings::default().margin);
        let mut scout = scout_in(centres)?;
        if let (Some(((lo, hi), step)), Some((clo, chi))) = (scout, centres)
            && (0..3).any(|d| lo[d] - clo[d] < 0.5 * step || chi[d] - hi[d] < 0.5 * step)
        {
            scout = scout_in(None)?;
        }
        let Some(((lo, hi), step)) = scout else {
            self.surface = Surface::default();
            return Ok(());
        };
        // Room around the surface: a tenth of its size (so the lattice depends on the
        // surface, not on how far out the centres reach), and at least a scouting cube.
        let side = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
        let room = (side / 10.0).max(step);
        let grown = (lo.map(|v| v - room), hi.map(|v| v + room));
        let cells = cells.clamp(4, 256);
        let (mut mesh, stats) = polygonize(cells, Some(grown))?;
        // A surface cut by the box comes within half a cube of a face: mesh the large box.
        let (mlo, mhi) = mesh.bounding_box();
        let near = 0.5 * stats.cell_size;
        if (0..3).any(|d| mlo[d] - grown.0[d] < near || grown.1[d] - mhi[d] < near) {
            mesh = polygonize(cells, None)?.0;
        }
        let positions = mesh.positions();
        // The polygonizer's normals, from ∇f at each vertex (outward).
        let normals: Vec<f32> = mesh
            .vertex_normals()
            .iter()
            .flat_map(|n| rbf_core::vec3::normalize(*n).map(|c| c as f32))
            .collect();
        self.surface = Surface {
            positions: positions.iter().flat_map(|p| p.map(|c| c as f32)).collect(),
            normals,
            indices: mesh.triangles().iter().flatten().copied().collect(),
            mesh: Some(mesh),
        };
        Ok(())
    }

    /// Applies one line of the command language of `rbf sculpt -` (the page's clicks and
    /// drags are sent as such lines too); [`Answer::line`] words the answer as the CLI does. The
    /// surface is not re-meshed: call [`Studio::remesh`].
    pub fn run(&mut self, line: &str) -> Answer {
        self.session.run_command(line)
    }

    /// Starts a gesture (a drag): its edits will undo as one.
    pub fn begin_gesture(&mut self) -> usize {
        self.session.history_len()
    }

    /// Ends a gesture begun at `mark`: its edits become one step of the history.
    pub fn end_gesture(&mut self, mark: usize) {
        self.session.squash_history(mark);
    }

    /// Where the ray from `origin` along `direction` first meets the surface.
    pub fn hit(&self, origin: [f64; 3], direction: [f64; 3]) -> Result<[f64; 3], StudioError> {
        Ok(self.session.pick(origin, direction)?)
    }

    /// Starts or stops the floaters (Witkin & Heckbert particles that spread evenly over the
    /// surface and follow every edit, as in Turk & O'Brien 2002, §5), spaced 1/20 of the
    /// surface's diagonal.
    pub fn set_floaters(&mut self, on: bool) {
        if !on {
            self.session.stop_floaters();
            return;
        }
        if self.session.floaters().is_some() {
            return;
        }
        let diagonal = self.surface.mesh.as_ref().map_or(2.0, |m| {
            let (lo, hi) = m.bounding_box();
            rbf_core::vec3::norm(rbf_core::vec3::sub(hi, lo))
        });
        self.session
            .start_floaters(rbf_sculpt::FloaterSettings::for_size(diagonal));
    }

    /// The floaters as discs: centre, outward unit normal and radius (half their spacing), or
    /// none when they are off.
    pub fn floaters(&self) -> Vec<([f64; 3], [f64; 3], f64)> {
        let Some(floaters) = self.session.floaters() else {
            return Vec::new();
        };
        let f = self.session.interpolant().view();
        let radius = 0.5 * floaters.settings().spacing;
        floaters
            .points()
            .iter()
            .zip(floaters.normals(&f))
            .map(|(&p, n)| (p, n, radius))
            .collect()
    }

    /// Live items as handles.
    pub fn handles(&self) -> Vec<Handle> {
        let items = self.session.items();
        items
            .iter()
            .enumerate()
            .filter_map(|(index, item)| {
                let (kind, position, base) = match (*item)? {
                    Item::Boundary(p) => (0, p, p),
                    Item::Interior(p, _) => (1, p, p),
                    Item::Exterior(p, _) => (2, p, p),
                    Item::Normal { boundary, tip, .. } => {
                        let base = match items.get(boundary).copied().flatten() {
                            Some(Item::Boundary(b)) => b,
                            _ => tip,
                        };
                        (3, tip, base)
                    }
                };
                Some(Handle {
                    index,
                    kind,
                    position,
                    base,
                })
            })
            .collect()
    }

    /// The current surface as the bytes of a mesh file, the format by `name`'s extension (OBJ,
    /// PLY, STL).
    pub fn export(&self, name: &str) -> Result<Vec<u8>, StudioError> {
        let mesh = self.surface.mesh.as_ref().ok_or(MeshError::Empty)?;
        Ok(rbf_mesh::mesh_bytes(Path::new(name), mesh)?)
    }
}

/// The box of the centres grown by `margin` times its longest side; `None` without centres or
/// with all of them at one point.
fn grown_centre_box(centres: &[[f64; 3]], margin: f64) -> Option<([f64; 3], [f64; 3])> {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for c in centres {
        for d in 0..3 {
            lo[d] = lo[d].min(c[d]);
            hi[d] = hi[d].max(c[d]);
        }
    }
    let side = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
    (side > 0.0 && side.is_finite())
        .then(|| (lo.map(|v| v - margin * side), hi.map(|v| v + margin * side)))
}
