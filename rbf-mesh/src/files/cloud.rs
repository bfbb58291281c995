//! Point clouds in: what scanners and surface-reconstruction tools write — PLY vertices with
//! `nx ny nz` (ASCII or binary, faces ignored), and NumPy `.npy` arrays of N × 3 points or
//! N × 6 oriented points.

use std::path::Path;

use super::{extension, npy, ply};
use crate::MeshError;

/// Points, and their normals when the file has them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PointCloud {
    /// The points.
    pub positions: Vec<[f64; 3]>,
    /// One outward normal per point (any length), when the file carries them.
    pub normals: Option<Vec<[f64; 3]>>,
}

/// How many points a point cloud file declares and how many numbers each carries, read from
/// its header alone (its first 64 KiB), so that a cloud too large for memory can be refused
/// before it is read. `None` for a file that is not `.ply` or `.npy`; for a PLY the numbers are
/// 6 when the vertices have `nx ny nz`, else 3.
///
/// ```
/// let dir = std::env::temp_dir().join("rbf-declared-cloud-doc");
/// std::fs::create_dir_all(&dir).unwrap();
/// let path = dir.join("scan.ply");
/// // A header that promises 10⁹ oriented points, and no data.
/// std::fs::write(&path, "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\n\
///     property float x\nproperty float y\nproperty float z\nproperty float nx\n\
///     property float ny\nproperty float nz\nend_header\n").unwrap();
/// assert_eq!(rbf_mesh::declared_cloud_size(&path).unwrap(), Some((1_000_000_000, 6)));
/// ```
pub fn declared_cloud_size(path: &Path) -> Result<Option<(u64, usize)>, MeshError> {
    use std::io::Read;
    let kind = extension(path);
    if !matches!(kind.as_deref(), Some("ply" | "npy")) {
        return Ok(None);
    }
    let io = |source| MeshError::Io {
        file: path.into(),
        source,
    };
    let mut prefix = Vec::new();
    std::fs::File::open(path)
        .map_err(io)?
        .take(64 << 10)
        .read_to_end(&mut prefix)
        .map_err(io)?;
    if kind.as_deref() == Some("ply") {
        let points = ply::vertex_count(path, &prefix)?;
        let text = String::from_utf8_lossy(&prefix);
        let normals = ["nx", "ny", "nz"]
            .iter()
            .all(|n| text.lines().any(|l| l.split_whitespace().last() == Some(n)));
        Ok(Some((points, if normals { 6 } else { 3 })))
    } else {
        let h = npy::header(path, &prefix)?;
        Ok(Some((h.rows as u64, h.cols)))
    }
}

/// Reads a point cloud (`.ply` or `.npy`, by extension).
///
/// ```no_run
/// let cloud = rbf_mesh::read_point_cloud("scan.ply".as_ref())?;
/// println!("{} points, normals: {}", cloud.positions.len(), cloud.normals.is_some());
/// # Ok::<(), rbf_mesh::MeshError>(())
/// ```
pub fn read_point_cloud(path: &Path) -> Result<PointCloud, MeshError> {
    let bytes = std::fs::read(path).map_err(|source| MeshError::Io {
        file: path.into(),
        source,
    })?;
    read_point_cloud_bytes(path, &bytes)
}

/// Reads a point cloud from bytes; `path` gives the format (by extension) and names it in
/// errors. Every coordinate must be a finite number.
///
/// ```
/// let ply = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n\
///            property float z\nproperty float nx\nproperty float ny\nproperty float nz\n\
///            end_header\n0 0 1 0 0 1\n1 0 0 1 0 0\n";
/// let cloud = rbf_mesh::read_point_cloud_bytes("scan.ply".as_ref(), ply.as_bytes()).unwrap();
/// assert_eq!(cloud.normals.unwrap()[1], [1.0, 0.0, 0.0]);
/// ```
pub fn read_point_cloud_bytes(path: &Path, bytes: &[u8]) -> Result<PointCloud, MeshError> {
    let cloud = match extension(path).as_deref() {
        Some("ply") => {
            let (positions, _, normals) = ply::read(path, bytes)?;
            PointCloud { positions, normals }
        }
        Some("npy") => {
            let m = npy::read_npy_matrix(path, bytes)?;
            let row = |i: usize, from: usize| -> [f64; 3] {
                core::array::from_fn(|d| m.data[i * m.cols + from + d])
            };
            match m.cols {
                3 => PointCloud {
                    positions: (0..m.rows).map(|i| row(i, 0)).collect(),
                    normals: None,
                },
                6 => PointCloud {
                    positions: (0..m.rows).map(|i| row(i, 0)).collect(),
                    normals: Some((0..m.rows).map(|i| row(i, 3)).collect()),
                },
                cols => {
                    return Err(MeshError::Invalid(format!(
                        "{}: an array of {cols} columns: a point cloud has 3 (x y z) or 6 (x y z nx ny nz)",
                        path.display()
                    )));
                }
            }
        }
        _ => return Err(MeshError::UnknownFormat { file: path.into() }),
    };
    let all = cloud.positions.iter().chain(cloud.normals.iter().flatten());
    if let Some(i) = all.clone().position(|p| !p.iter().all(|v| v.is_finite())) {
        let point = i % cloud.positions.len().max(1);
        return Err(MeshError::Invalid(format!(
            "{}: point {point} has a coordinate or normal that is not a finite number",
            path.display()
        )));
    }
    Ok(cloud)
}
