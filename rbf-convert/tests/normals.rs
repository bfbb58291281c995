//! Normal-constraint conversion (Turk & O'Brien 2002, §4.3) on real and synthetic meshes.

use rbf_convert::{NormalSettings, convert_normals};
use rbf_mesh::{PolygonizeSettings, Resolution, polygonize_continuation, read_mesh, surface_seeds};

fn data(name: &str) -> std::path::PathBuf {
    std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../data/meshes")
        .join(name)
}

#[test]
fn a_sphere_like_mesh_gives_the_sphere_to_one_percent() {
    let mesh = rbf_mesh::TriMesh::icosphere(3); // 642 vertices on the unit sphere
    let (model, report) = convert_normals(&mesh, &NormalSettings::default(), |_| {}).unwrap();
    assert_eq!((report.vertices_used, report.thinned), (642, false));
    let f = &model.interpolant;
    for d in rbf_core::shapes::fibonacci_sphere(300) {
        // Bisection for the radius where f changes sign along d.
        let (mut lo, mut hi) = (0.5, 1.5);
        assert!(f.value(&d.map(|c| c * lo)) > 0.0 && f.value(&d.map(|c| c * hi)) < 0.0);
        for _ in 0..50 {
            let mid = 0.5 * (lo + hi);
            if f.value(&d.map(|c| c * mid)) > 0.0 {
                lo = mid
            } else {
                hi = mid
            }
        }
        assert!((lo - 1.0).abs() < 0.01, "radius {lo} along {d:?}");
    }
}

#[test]
fn the_torus_converts_to_a_closed_genus_one_surface_near_the_mesh() {
    let mesh = read_mesh(&data("torus.obj")).unwrap();
    let (model, report) = convert_normals(&mesh, &NormalSettings::default(), |_| {}).unwrap();
    assert_eq!(report.vertices_used, 2304);
    let f = model.interpolant.view();
    // The surface passes through every vertex.
    for p in mesh.positions() {
        assert!(f.value(p).abs() < 1e-8);
    }
    let s = PolygonizeSettings {
        resolution: Resolution::Cells(48),
        ..Default::default()
    };
    let (surface, _) = polygonize_continuation(&f, &surface_seeds(&model), &s).unwrap();
    let r = surface.check();
    assert!(r.is_watertight() && r.genus == Some(1), "{r:?}");
    // Two-way distance, measured independently of the fit: polygonized vertices to the
    // analytic torus the mesh approximates (radii 1 and 0.25 around y), and mesh vertices to
    // the implicit surface.
    let worst = surface
        .positions()
        .iter()
        .map(|p| {
            let ring = (p[0] * p[0] + p[2] * p[2]).sqrt() - 1.0;
            ((ring * ring + p[1] * p[1]).sqrt() - 0.25).abs()
        })
        .fold(0.0, f64::max);
    assert!(worst < 0.01, "the surface strays {worst} from the torus");
}

#[test]
fn large_meshes_are_thinned_evenly_and_say_so() {
    let mesh = read_mesh(&data("spot.obj")).unwrap();
    let s = NormalSettings {
        max_vertices: 600,
        ..Default::default()
    };
    let (model, report) = convert_normals(&mesh, &s, |_| {}).unwrap();
    assert!(report.thinned);
    assert!(
        report.vertices_used <= 600 && report.vertices_used > 450,
        "{report:?}"
    );
    assert_eq!(report.vertices, 2930);
    // Evenly spread: the nearest-neighbour distances vary little.
    let pts: Vec<[f64; 3]> = model.constraints.iter().map(|c| c.position).collect();
    let nn: Vec<f64> = pts
        .iter()
        .enumerate()
        .map(|(i, p)| {
            pts.iter()
                .enumerate()
                .filter(|(j, _)| *j != i)
                .map(|(_, q)| ((0..3).map(|d| (p[d] - q[d]).powi(2)).sum::<f64>()).sqrt())
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    let mean = nn.iter().sum::<f64>() / nn.len() as f64;
    let sd = (nn.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / nn.len() as f64).sqrt();
    assert!(sd / mean < 0.35, "coefficient of variation {}", sd / mean);
    let f = model.interpolant.view();
    let s = PolygonizeSettings {
        resolution: Resolution::Cells(40),
        ..Default::default()
    };
    let (surface, _) = polygonize_continuation(&f, &surface_seeds(&model), &s).unwrap();
    assert!(surface.check().is_watertight());
}

#[test]
fn a_mesh_without_normals_is_an_error() {
    // One triangle folded onto itself: the area vectors cancel at every vertex.
    let mesh = rbf_mesh::TriMesh::new(
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        vec![[0, 1, 2], [0, 2, 1]],
    )
    .unwrap();
    let e = convert_normals(&mesh, &NormalSettings::default(), |_| {}).unwrap_err();
    assert!(e.to_string().contains("normal"), "{e}");
}

#[test]
fn greedy_vertices_meet_every_vertex_within_the_tolerance() {
    let mesh = read_mesh(&data("spot.obj")).unwrap();
    let tolerance = 1e-3;
    let s = NormalSettings {
        tolerance: Some(tolerance),
        ..Default::default()
    };
    let (model, report) = convert_normals(&mesh, &s, |_| {}).unwrap();
    let (worst, converged) = report.greedy.unwrap();
    assert!(converged && worst <= tolerance, "{report:?}");
    assert!(
        report.thinned && report.vertices_used < report.vertices * 2 / 3,
        "{report:?}"
    );
    // Independently: every vertex of the mesh, chosen or not, is that near the surface.
    let (lo, hi) = mesh.bounding_box();
    let longest = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
    let f = &model.interpolant;
    for p in mesh.positions() {
        let (v, g) = f.value_and_gradient(p);
        let miss = v.abs() / (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
        assert!(
            miss <= tolerance * longest,
            "a vertex is {} of the box away",
            miss / longest
        );
    }
}
