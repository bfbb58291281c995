//! The two-way surface distance against distances known in closed form.

use rbf_convert::{CompareSettings, surface_distance};
use rbf_core::{Constraint, FitSettings, Interpolant};
use rbf_mesh::TriMesh;

/// A unit sphere: boundary constraints at the 642 vertices of a level-3 icosphere, f = 1 at
/// the centre.
fn unit_sphere() -> Interpolant<f64, 3> {
    let mut constraints: Vec<Constraint<3>> = TriMesh::icosphere(3)
        .positions()
        .iter()
        .map(|&p| Constraint::boundary(p))
        .collect();
    constraints.push(Constraint::interior([0.0; 3], 1.0));
    rbf_solve::fit(&constraints, &FitSettings::default())
        .unwrap()
        .interpolant
}

const SETTINGS: CompareSettings = CompareSettings {
    samples: 5000,
    resolution: 96,
    seed: 1,
};

fn moved(mesh: &TriMesh, map: impl Fn([f64; 3]) -> [f64; 3]) -> TriMesh {
    TriMesh::new(
        mesh.positions().iter().map(|&p| map(p)).collect(),
        mesh.triangles().to_vec(),
    )
    .unwrap()
}

#[test]
fn a_sphere_shifted_by_t_is_t_away_at_most_and_t_over_two_on_average() {
    // The distance from a point q of the shifted sphere to the unit sphere is | |q| − 1 |:
    // t at the two poles along the shift and t·|cos θ| + O(t²) elsewhere, t / 2 on average.
    let f = unit_sphere();
    let t = 0.05;
    let mesh = moved(&TriMesh::icosphere(4), |p| [p[0] + t, p[1], p[2]]);
    let d = surface_distance(&f.view(), &mesh, &SETTINGS).unwrap();
    for s in [d.mesh_to_surface, d.surface_to_mesh] {
        assert!((s.max - t).abs() < 0.03 * t, "{d:?}");
        assert!((s.mean - t / 2.0).abs() < 0.05 * t, "{d:?}");
        // E[cos²θ] = 1/3 over the sphere.
        assert!((s.rms - t / 3f64.sqrt()).abs() < 0.05 * t, "{d:?}");
    }
    assert!((d.hausdorff() - t).abs() < 0.03 * t);
}

#[test]
fn a_sphere_against_itself_scaled_is_the_difference_of_radii_everywhere() {
    let f = unit_sphere();
    let mesh = moved(&TriMesh::icosphere(4), |p| p.map(|x| 1.1 * x));
    let d = surface_distance(&f.view(), &mesh, &SETTINGS).unwrap();
    for s in [d.mesh_to_surface, d.surface_to_mesh] {
        assert!((s.mean - 0.1).abs() < 0.002, "{d:?}");
        assert!((s.max - 0.1).abs() < 0.002, "{d:?}");
    }
}

#[test]
fn a_mesh_without_area_is_an_error() {
    let f = unit_sphere();
    let flat = TriMesh::new(
        vec![[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]],
        vec![[0, 1, 2]],
    )
    .unwrap();
    let e = surface_distance(&f.view(), &flat, &SETTINGS).unwrap_err();
    assert!(e.to_string().contains("no area"), "{e}");
}
