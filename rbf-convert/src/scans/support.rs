//! Pieces of a reconstructed surface that the scan shows, and pieces it does not.

use rbf_cloud::distances_to_cloud;
use rbf_core::Model;
use rbf_far::{Evaluator, default_accuracy};
use rbf_mesh::{
    MeshError, PolygonizeSettings, Resolution, TriMesh, polygonize_continuation, surface_seeds,
};

use crate::{ConvertError, ReconstructReport};

/// The share of a piece's vertices that must lie within the reach of the scan for the piece to
/// be kept.
const SUPPORTED_SHARE: f64 = 0.5;

/// A piece smaller than the area this many of the scan's points stand for (the mesh's area over
/// their number) is a crumb: fewer points than that cannot show a piece of its own (a clean
/// boat scan kept one of 8 triangles, 12 points' worth, beside the thin tip of its bow).
const CRUMB_POINTS: f64 = 20.0;

/// The pieces of `mesh` that the scan supports: those with at least half their vertices within
/// `reach` of a scan point, wider than twice the reach and larger than the area 20 of the
/// points stand for (finer than that, the scan cannot show a piece). An implicit surface
/// fitted to a scan may close small bubbles far from every
/// point (where nothing constrains f); no scanned surface lies there. Returns the kept mesh and
/// how many pieces were dropped; the largest piece is always kept.
///
/// ```
/// use rbf_convert::supported_pieces;
/// use rbf_mesh::TriMesh;
/// // A triangle where the points are, and one far away.
/// let mesh = TriMesh::new(
///     vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [9.0, 0.0, 0.0], [9.5, 0.0, 0.0], [9.0, 0.5, 0.0]],
///     vec![[0, 1, 2], [3, 4, 5]],
/// ).unwrap();
/// let points = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
/// let (kept, dropped) = supported_pieces(&mesh, &points, 0.1).unwrap();
/// assert_eq!((kept.triangles().len(), dropped), (1, 1));
/// ```
pub fn supported_pieces(
    mesh: &TriMesh,
    points: &[[f64; 3]],
    reach: f64,
) -> Result<(TriMesh, usize), MeshError> {
    if mesh.components().len() <= 1 {
        return Ok((mesh.clone(), 0));
    }
    let distances = distances_to_cloud(points, mesh.positions());
    let crumb = CRUMB_POINTS * area(mesh, 0..mesh.triangles().len()) / points.len().max(1) as f64;
    keep_pieces(mesh, reach, crumb, |v| distances[v as usize] <= reach)
}

/// The area of the triangles `which` of `mesh`.
fn area(mesh: &TriMesh, which: impl IntoIterator<Item = usize>) -> f64 {
    which
        .into_iter()
        .map(|t| 0.5 * rbf_core::vec3::norm(mesh.area_vector(t)))
        .sum()
}

/// `mesh` without the pieces (but the largest) that have fewer than half their vertices `near`,
/// are no wider than twice `reach` or have less area than `crumb`, and how many were dropped.
fn keep_pieces(
    mesh: &TriMesh,
    reach: f64,
    crumb: f64,
    near: impl Fn(u32) -> bool,
) -> Result<(TriMesh, usize), MeshError> {
    let pieces = mesh.components();
    let triangles = mesh.triangles();
    let mut keep = Vec::new();
    let mut dropped = 0;
    for (i, piece) in pieces.iter().enumerate() {
        let mut vertices: Vec<u32> = piece.iter().flat_map(|&t| triangles[t]).collect();
        vertices.sort_unstable();
        vertices.dedup();
        let supported = vertices.iter().filter(|&&v| near(v)).count();
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for &v in &vertices {
            let p = mesh.positions()[v as usize];
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let width = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
        let shown = supported as f64 >= SUPPORTED_SHARE * vertices.len() as f64
            && width > 2.0 * reach
            && area(mesh, piece.iter().copied()) >= crumb;
        if i == 0 || shown {
            keep.extend_from_slice(piece);
        } else {
            dropped += 1;
        }
    }
    if dropped == 0 {
        return Ok((mesh.clone(), 0));
    }
    keep.sort_unstable();
    Ok((mesh.with_triangles(&keep)?, dropped))
}

/// The mesh of a reconstructed scan: `model` (from [`crate::reconstruct`], with its `report`)
/// polygonized by continuation from its constraints at `resolution` cubes across, without the
/// pieces no point of the scan is near ([`supported_pieces`]). Returns the mesh and how many
/// pieces were dropped.
///
/// ```
/// use rbf_convert::{ReconstructSettings, reconstruct, scan_mesh};
/// let points: Vec<[f64; 3]> = (0..800)
///     .map(|i| {
///         let z = 1.0 - (2 * i + 1) as f64 / 800.0;
///         let (t, s) = (2.399963 * i as f64, (1.0 - z * z).sqrt());
///         [s * t.cos(), s * t.sin(), z]
///     })
///     .collect();
/// let (model, report) = reconstruct(&points, None, &ReconstructSettings::default()).unwrap();
/// let (mesh, dropped) = scan_mesh(&model, &report, &points, 32).unwrap();
/// assert!(mesh.check().is_watertight());
/// assert_eq!(dropped, 0);
/// ```
pub fn scan_mesh(
    model: &Model<3>,
    report: &ReconstructReport,
    points: &[[f64; 3]],
    resolution: usize,
) -> Result<(TriMesh, usize), ConvertError> {
    let settings = PolygonizeSettings {
        resolution: Resolution::Cells(resolution),
        ..Default::default()
    };
    let view = model.interpolant.view();
    let seeds = surface_seeds(model);
    // A smoothing fit of 10⁴ normal constraints has 2·10⁴ centres: the far field pays there.
    // Its accuracy is measured at the centres, half of them off the surface (the normal
    // constraints' offset points): measured at the surface points alone, it was chosen too
    // low and missed between them (a noisy bunny scan's mesh lay 0.5 % of the diagonal inside
    // its surface, F-score 0.54 against 0.98 by direct sums).
    let f = Evaluator::new(view, view.centres(), default_accuracy(view.centres()));
    let (mesh, _) = polygonize_continuation(&f, &seeds, &settings)?;
    Ok(supported_pieces(&mesh, points, report.support_reach)?)
}

/// The triangles of `mesh` whose corners all lie within `distance` of a scan point: the
/// surface of an open scan (a face, a terrain) without what the implicit surface adds to close
/// it; then, as in [`supported_pieces`], crumbs that the cut leaves (narrower than twice the
/// distance, or smaller than 20 points' worth of area) are dropped. The result is open; an error if nothing is left.
///
/// ```
/// use rbf_convert::trimmed;
/// use rbf_mesh::TriMesh;
/// let mesh = TriMesh::new(
///     vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [9.0, 0.0, 0.0]],
///     vec![[0, 1, 2], [1, 3, 2]],
/// ).unwrap();
/// let points = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
/// assert_eq!(trimmed(&mesh, &points, 0.1).unwrap().triangles().len(), 1);
/// ```
pub fn trimmed(mesh: &TriMesh, points: &[[f64; 3]], distance: f64) -> Result<TriMesh, MeshError> {
    let near: Vec<bool> = distances_to_cloud(points, mesh.positions())
        .into_iter()
        .map(|d| d <= distance)
        .collect();
    let keep: Vec<usize> = (0..mesh.triangles().len())
        .filter(|&t| mesh.triangles()[t].iter().all(|&v| near[v as usize]))
        .collect();
    // Every corner left is within the distance of a point: only the crumbs' size decides.
    let cut = mesh.with_triangles(&keep)?;
    let crumb = CRUMB_POINTS * area(&cut, 0..cut.triangles().len()) / points.len().max(1) as f64;
    Ok(keep_pieces(&cut, distance, crumb, |_| true)?.0)
}

#[cfg(test)]
mod tests {
    use super::supported_pieces;
    use rbf_mesh::TriMesh;

    /// A crumb beside the surface, wider than twice the reach and every vertex of it on a scan
    /// point, but with the area of a point or two (as a clean boat scan kept one beside the
    /// thin tip of its bow): dropped. The same piece, scaled up to hold many points' worth, is
    /// kept.
    #[test]
    fn a_crumb_smaller_than_twenty_points_worth_is_dropped() {
        let sphere = TriMesh::icosphere(4);
        let small = TriMesh::icosphere(1);
        let with_piece = |radius: f64| {
            let mut positions = sphere.positions().to_vec();
            let at = positions.len() as u32;
            positions.extend(
                small
                    .positions()
                    .iter()
                    .map(|p| [1.2 + radius * p[0], radius * p[1], radius * p[2]]),
            );
            let mut triangles = sphere.triangles().to_vec();
            triangles.extend(small.triangles().iter().map(|t| t.map(|v| v + at)));
            TriMesh::new(positions, triangles).unwrap()
        };
        let crumb = with_piece(0.02);
        // The scan: every vertex of the mesh, the crumb's too.
        let points = crumb.positions().to_vec();
        let (kept, dropped) = supported_pieces(&crumb, &points, 0.001).unwrap();
        assert_eq!(dropped, 1);
        assert_eq!(kept.triangles().len(), sphere.triangles().len());
        let piece = with_piece(0.15);
        let points = piece.positions().to_vec();
        let (kept, dropped) = supported_pieces(&piece, &points, 0.001).unwrap();
        assert_eq!(
            (dropped, kept.triangles().len()),
            (0, piece.triangles().len())
        );
    }
}
