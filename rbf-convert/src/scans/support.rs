//! Pieces of a reconstructed surface that the scan shows, and pieces it does not.

use rbf_cloud::distances_to_cloud;
use rbf_core::{ConstraintKind, Model};
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
/// points stand for (finer than that, the scan cannot show a piece), and that face outward
/// (enclose a positive volume). An implicit surface fitted to a scan may close small bubbles
/// far from every point (where nothing constrains f); no scanned surface lies there. And a
/// piece that faces inward is a closed cavity inside the solid, which no scanner sees from
/// outside: the points on it were seen through an opening narrower than the surface could
/// follow, which closed over (a simulated cow scan's mouth, its lips closer than the points'
/// spacing, left its inside as a cavity, a second piece); the solid is kept whole. Returns the
/// kept mesh and how many pieces were dropped; the largest piece is always kept.
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
    keep_pieces(mesh, reach, crumb, true, |v| distances[v as usize] <= reach)
}

/// The area of the triangles `which` of `mesh`.
fn area(mesh: &TriMesh, which: impl IntoIterator<Item = usize>) -> f64 {
    which
        .into_iter()
        .map(|t| 0.5 * rbf_core::vec3::norm(mesh.area_vector(t)))
        .sum()
}

/// `mesh` without the pieces (but the largest) that have fewer than half their vertices `near`,
/// are no wider than twice `reach`, have less area than `crumb` or, where `closed`, face
/// inward; and how many were dropped.
fn keep_pieces(
    mesh: &TriMesh,
    reach: f64,
    crumb: f64,
    closed: bool,
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
        let shown = || -> Result<bool, MeshError> {
            Ok(supported as f64 >= SUPPORTED_SHARE * vertices.len() as f64
                && width > 2.0 * reach
                && area(mesh, piece.iter().copied()) >= crumb
                && !(closed && mesh.with_triangles(piece)?.volume() < 0.0))
        };
        if i == 0 || shown()? {
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
    // its surface, F-score 0.54 against 0.98 by direct sums). Its accuracy is what moves the
    // surface by a hundredth of the scan's tolerance, no finer.
    let f = Evaluator::new(view, view.centres(), mesh_accuracy(model, report));
    let (mesh, _) = polygonize_continuation(&f, &seeds, &settings)?;
    Ok(supported_pieces(&mesh, points, report.support_reach)?)
}

/// The share of the scan's tolerance that the mesh's evaluations may move its surface by.
const MESH_ACCURACY: f64 = 0.01;

/// The accuracy (in f's units) that [`scan_mesh`] evaluates `model` to: what moves its surface
/// by [`MESH_ACCURACY`] of the scan's tolerance, f changing at the median slope |∇f| of its
/// normal constraints' points; never finer than rbf-far's default (10⁻⁶ of the diagonal). The
/// default alone took the far field to order 12 on a scan whose tolerance was 7.6·10⁻³ of the
/// box, and its near field's direct sums most of the time.
fn mesh_accuracy(model: &Model<3>, report: &ReconstructReport) -> f64 {
    let view = model.interpolant.view();
    let finest = default_accuracy(view.centres());
    let on_surface: Vec<[f64; 3]> = (model.constraints.iter())
        .filter(|c| c.kind == ConstraintKind::Normal)
        .map(|c| c.position)
        .collect();
    let sample: Vec<[f64; 3]> = (on_surface.iter())
        .step_by(on_surface.len().div_ceil(SLOPE_SAMPLE).max(1))
        .copied()
        .collect();
    if sample.is_empty() {
        return finest;
    }
    let mut values = vec![0.0; sample.len()];
    let mut gradients = vec![[0.0; 3]; sample.len()];
    // Lengths match by construction.
    let _ = view.par_values_and_gradients(&sample, &mut values, &mut gradients);
    let slopes: Vec<f64> = gradients.iter().map(|&g| rbf_core::vec3::norm(g)).collect();
    let slope = super::dipoles::median(&slopes);
    let longest = super::reconstruct::longest_side(&on_surface);
    let accuracy = MESH_ACCURACY * report.tolerance * longest * slope;
    if accuracy.is_finite() {
        accuracy.max(finest)
    } else {
        finest
    }
}

/// Points of the scan's surface at which [`mesh_accuracy`] takes f's slope.
const SLOPE_SAMPLE: usize = 1000;

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
    Ok(keep_pieces(&cut, distance, crumb, false, |_| true)?.0)
}

#[cfg(test)]
mod tests {
    use super::{MESH_ACCURACY, mesh_accuracy, supported_pieces};
    use crate::{ReconstructSettings, reconstruct};
    use rbf_mesh::TriMesh;

    /// The mesh's accuracy moves the surface by a hundredth of the tolerance where f has its
    /// median slope, and by at most two hundredths at nine in ten of the scan's points.
    #[test]
    fn the_mesh_accuracy_moves_the_surface_by_a_hundredth_of_the_tolerance() {
        let points: Vec<[f64; 3]> = (0..3000)
            .map(|i| {
                let z = 1.0 - (2 * i + 1) as f64 / 3000.0;
                let (t, s) = (2.399963 * i as f64, (1.0 - z * z).sqrt());
                [2.0 * s * t.cos(), 1.5 * s * t.sin(), z]
            })
            .collect();
        let (model, report) = reconstruct(&points, None, &ReconstructSettings::default()).unwrap();
        let accuracy = mesh_accuracy(&model, &report);
        let allowed = MESH_ACCURACY * report.tolerance * 4.0; // the longest side is 4
        let f = model.interpolant.view();
        let mut moved: Vec<f64> = points
            .iter()
            .map(|p| accuracy / rbf_core::vec3::norm(f.gradient(p)))
            .collect();
        moved.sort_by(f64::total_cmp);
        let (median, ninth) = (moved[moved.len() / 2], moved[moved.len() * 9 / 10]);
        assert!(
            median <= 1.2 * allowed && median >= 0.8 * allowed,
            "{median} against {allowed}"
        );
        assert!(ninth <= 2.0 * allowed, "{ninth} against {allowed}");
    }

    /// A closed cavity inside the solid (a sphere within a sphere, facing inward), every vertex
    /// of it on a scan point: dropped, the solid kept whole. The same sphere facing outward (a
    /// separate piece, an object inside a hollow one) is kept.
    #[test]
    fn a_closed_cavity_is_dropped_and_an_outward_piece_kept() {
        let sphere = TriMesh::icosphere(4);
        let inner = |facing_in: bool| {
            let mut positions = sphere.positions().to_vec();
            let at = positions.len() as u32;
            positions.extend(sphere.positions().iter().map(|p| p.map(|c| 0.5 * c)));
            let mut triangles = sphere.triangles().to_vec();
            triangles.extend(sphere.triangles().iter().map(|&[a, b, c]| {
                let t = [a + at, b + at, c + at];
                if facing_in { [t[0], t[2], t[1]] } else { t }
            }));
            TriMesh::new(positions, triangles).unwrap()
        };
        let cavity = inner(true);
        assert!(cavity.volume() < sphere.volume());
        let points = cavity.positions().to_vec();
        let (kept, dropped) = supported_pieces(&cavity, &points, 0.001).unwrap();
        assert_eq!(dropped, 1);
        assert_eq!(kept.triangles().len(), sphere.triangles().len());
        assert!(kept.volume() > 0.0);
        let nested = inner(false);
        let (kept, dropped) = supported_pieces(&nested, &points, 0.001).unwrap();
        assert_eq!(
            (dropped, kept.triangles().len()),
            (0, nested.triangles().len())
        );
    }

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
