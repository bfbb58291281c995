//! Reading and writing meshes: OBJ, PLY (ASCII and binary) and STL (ASCII and binary) in;
//! OBJ, binary PLY and binary STL out. Format by file extension.

mod cloud;
mod npy;
mod obj;
mod ply;
mod stl;

pub use cloud::{PointCloud, declared_cloud_size, read_point_cloud, read_point_cloud_bytes};
pub(crate) use npy::npy_preamble;
pub use npy::{Matrix, npy_f64_bytes, read_npy_matrix};

use std::path::Path;

use crate::{Location, MeshError, TriMesh};

/// Reads a mesh, choosing the format by extension (`.obj`, `.ply`, `.stl`).
///
/// ```no_run
/// let mesh = rbf_mesh::read_mesh("bunny.obj".as_ref())?;
/// println!("{} triangles", mesh.triangles().len());
/// # Ok::<(), rbf_mesh::MeshError>(())
/// ```
pub fn read_mesh(path: &Path) -> Result<TriMesh, MeshError> {
    let bytes = std::fs::read(path).map_err(|source| MeshError::Io {
        file: path.into(),
        source,
    })?;
    read_mesh_bytes(path, &bytes)
}

/// Reads a mesh from bytes; `path` gives the format (by extension) and names it in errors.
pub fn read_mesh_bytes(path: &Path, bytes: &[u8]) -> Result<TriMesh, MeshError> {
    let (positions, triangles) = match extension(path).as_deref() {
        Some("obj") => obj::read(path, bytes)?,
        Some("ply") => {
            let (positions, triangles, _) = ply::read(path, bytes)?;
            (positions, triangles)
        }
        Some("stl") => stl::read(path, bytes)?,
        _ => return Err(MeshError::UnknownFormat { file: path.into() }),
    };
    TriMesh::new(positions, triangles).map_err(|e| MeshError::InFile {
        file: path.into(),
        source: Box::new(e),
    })
}

/// A mesh as the bytes of a file, the format by `path`'s extension as [`write_mesh`] chooses
/// it: for downloads and other writes that are not to a file.
///
/// ```
/// let mesh = rbf_mesh::TriMesh::icosphere(1);
/// let stl = rbf_mesh::mesh_bytes("sphere.stl".as_ref(), &mesh).unwrap();
/// assert_eq!(stl.len(), 84 + 50 * mesh.triangles().len()); // binary STL
/// assert!(rbf_mesh::mesh_bytes("sphere.xyz".as_ref(), &mesh).is_err());
/// ```
pub fn mesh_bytes(path: &Path, mesh: &TriMesh) -> Result<Vec<u8>, MeshError> {
    Ok(match extension(path).as_deref() {
        Some("obj") => obj::write(mesh),
        Some("ply") => ply::write(mesh),
        Some("stl") => stl::write(mesh),
        _ => return Err(MeshError::UnknownFormat { file: path.into() }),
    })
}

/// Writes a mesh, choosing the format by extension: OBJ (text, with normals if present), PLY
/// (binary little-endian, double precision) or STL (binary). The file is written to a temporary
/// name and renamed, so an interrupted write leaves nothing half-written.
pub fn write_mesh(path: &Path, mesh: &TriMesh) -> Result<(), MeshError> {
    let bytes = mesh_bytes(path, mesh)?;
    let io = |source| MeshError::Io {
        file: path.into(),
        source,
    };
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
    let tmp = dir.join(format!(
        ".{}.{}.tmp",
        name.unwrap_or_default(),
        std::process::id()
    ));
    std::fs::write(&tmp, bytes).map_err(io)?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        io(e)
    })
}

fn extension(path: &Path) -> Option<String> {
    path.extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
}

/// A parse error at a line of `path`.
pub(crate) fn at_line(path: &Path, line: usize, message: impl Into<String>) -> MeshError {
    MeshError::Parse {
        file: path.into(),
        location: Location::Line(line),
        message: message.into(),
    }
}

/// A parse error at a byte offset of `path`.
pub(crate) fn at_byte(path: &Path, byte: u64, message: impl Into<String>) -> MeshError {
    MeshError::Parse {
        file: path.into(),
        location: Location::Byte(byte),
        message: message.into(),
    }
}

/// Parses a finite float token.
pub(crate) fn number(token: &str) -> Option<f64> {
    token.parse::<f64>().ok().filter(|v| v.is_finite())
}
