//! A scan's closed surface, start to end: the model ([`reconstruct`]) and its mesh
//! ([`scan_mesh`]), with a second attempt when the first mesh comes out open (the model
//! itself may already have made one: [`ReconstructReport::looked_again`]).

use rbf_core::Model;
use rbf_mesh::TriMesh;

use super::{ReconstructReport, ReconstructSettings, reconstruct, scan_mesh};
use crate::ConvertError;

/// What [`scan_surface`] made of a scan.
#[derive(Clone, Debug)]
pub struct ScanSurface {
    /// The fitted model.
    pub model: Model<3>,
    /// What the reconstruction found and did.
    pub report: ReconstructReport,
    /// The model's surface, without the pieces no point of the scan is near.
    pub mesh: TriMesh,
    /// Pieces dropped from the mesh ([`crate::supported_pieces`]).
    pub dropped: usize,
}

/// Reconstructs a scan ([`reconstruct`]) and polygonizes it at `resolution` cubes across
/// (`None`: [`crate::mesh_resolution`] of the points) without the pieces the scan does not
/// show ([`scan_mesh`]). A clean scan's normals are not checked by lines of sight; if its mesh
/// then comes out open (f positive out to the box: the normals of a part the winding numbers
/// cannot judge, such as a plate a few point spacings thick whose two sides came out facing
/// the same way), the scan is reconstructed again with them ([`ReconstructSettings::sight`]),
/// and the second attempt is kept if its mesh is closed ([`ReconstructReport::looked_again`]);
/// if it is not, or it fails, the first is returned as it was.
///
/// ```
/// use rbf_convert::{ReconstructSettings, scan_surface};
/// let points: Vec<[f64; 3]> = (0..800)
///     .map(|i| {
///         let z = 1.0 - (2 * i + 1) as f64 / 800.0;
///         let (t, s) = (2.399963 * i as f64, (1.0 - z * z).sqrt());
///         [s * t.cos(), s * t.sin(), z]
///     })
///     .collect();
/// let scan = scan_surface(&points, None, &ReconstructSettings::default(), Some(32)).unwrap();
/// assert!(scan.mesh.check().is_watertight() && !scan.report.looked_again);
/// ```
pub fn scan_surface(
    points: &[[f64; 3]],
    normals: Option<&[[f64; 3]]>,
    settings: &ReconstructSettings,
    resolution: Option<usize>,
) -> Result<ScanSurface, ConvertError> {
    let resolution = resolution.unwrap_or_else(|| crate::mesh_resolution(points));
    let attempt = |settings: &ReconstructSettings| -> Result<ScanSurface, ConvertError> {
        let (model, report) = reconstruct(points, normals, settings)?;
        let (mesh, dropped) = scan_mesh(&model, &report, points, resolution)?;
        Ok(ScanSurface {
            model,
            report,
            mesh,
            dropped,
        })
    };
    let scan = attempt(settings)?;
    if scan.report.sight || scan.mesh.check().is_watertight() {
        return Ok(scan);
    }
    let sighted = ReconstructSettings {
        sight: true,
        ..*settings
    };
    match attempt(&sighted) {
        Ok(mut again) if again.mesh.check().is_watertight() => {
            again.report.looked_again = true;
            Ok(again)
        }
        _ => Ok(scan),
    }
}
