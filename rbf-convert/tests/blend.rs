//! Turk & O'Brien 2002, Figure 9: three overlapping tori blended into one closed surface.

use rbf_convert::blend;
use rbf_core::{Constraint, FitSettings, Model};
use rbf_mesh::{PolygonizeSettings, Resolution, polygonize_grid};

const R: f64 = 1.0;
const TUBE: f64 = 0.35;

/// Centres of the three tori, in the xz plane, overlapping pairwise.
const CENTRES: [[f64; 3]; 3] = [[-1.4, 0.0, 0.0], [0.0, 0.0, 0.0], [1.4, 0.0, 0.0]];

/// The exact signed distance to torus i (positive outside).
fn torus_distance(i: usize, p: [f64; 3]) -> f64 {
    let c = CENTRES[i];
    let (x, y, z) = (p[0] - c[0], p[1] - c[1], p[2] - c[2]);
    ((x * x + z * z).sqrt() - R).hypot(y) - TUBE
}

/// Torus i from `n` oriented points spread over it.
fn torus(i: usize, n: usize) -> Model<3> {
    // The library's torus (about z, major radius R = 1) turned to stand about y.
    let c = CENTRES[i];
    let constraints: Vec<Constraint<3>> = rbf_core::shapes::torus_points(n, TUBE)
        .into_iter()
        .map(|([x, y, z], [nx, ny, nz])| {
            Constraint::normal([c[0] + x, c[1] + z, c[2] + y], [nx, nz, ny])
        })
        .collect();
    let settings = FitSettings::default();
    let fit = rbf_solve::fit(&constraints, &settings).unwrap();
    Model {
        constraints,
        settings,
        interpolant: fit.interpolant,
        report: None,
    }
}

#[test]
fn three_tori_blend_into_one_closed_surface_without_bulges() {
    let tori: Vec<Model<3>> = (0..3).map(|i| torus(i, 400)).collect();
    let refs: Vec<&Model<3>> = tori.iter().collect();
    let (blended, report) = blend(&refs).unwrap();
    // Each torus loses the constraints inside its neighbours, the middle one on both sides.
    assert!(
        report
            .kept
            .iter()
            .zip(&report.total)
            .all(|(k, t)| k < t && *k > t / 2),
        "{report:?}"
    );
    assert!(report.kept[1] < report.kept[0] && report.kept[1] < report.kept[2]);
    let settings = PolygonizeSettings {
        resolution: Resolution::Cells(112),
        ..Default::default()
    };
    let (mesh, _) = polygonize_grid(&blended.interpolant.view(), &settings).unwrap();
    let check = mesh.check();
    assert!(check.is_watertight(), "{check:?}");
    assert_eq!(check.components, 1, "{check:?}");
    let mut far = 0;
    let (mut deepest, mut bulge, mut drift) = (0.0_f64, 0.0_f64, 0.0_f64);
    for &v in mesh.positions() {
        // Signed distance (positive outside) to each original model's surface, to first order.
        let d: Vec<f64> = tori
            .iter()
            .map(|t| {
                let (f, g) = t.interpolant.value_and_gradient(&v);
                -f / (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt()
            })
            .collect();
        let nearest = d.iter().copied().fold(f64::INFINITY, f64::min);
        deepest = deepest.min(nearest);
        bulge = bulge.max(nearest);
        // Away from the other tori (by the exact shapes) the blend keeps the original surface.
        let exact: Vec<f64> = (0..3).map(|i| torus_distance(i, v)).collect();
        if (0..3).filter(|&i| exact[i] > 0.5).count() == 2 {
            far += 1;
            drift = drift.max(nearest.abs());
        }
    }
    // Measured: the blend fills each crease by at most 0.11 of the tube's radius beyond the
    // union (no bulge) and dips at most 0.06 into it where constraints were dropped.
    assert!(
        deepest > -0.1 * TUBE,
        "a vertex lies {deepest} inside the union"
    );
    assert!(
        bulge < 0.25 * TUBE,
        "a vertex bulges {bulge} beyond the union"
    );
    assert!(
        drift < 0.01 * TUBE,
        "away from the blends the surface moved by {drift}"
    );
    assert!(far > mesh.positions().len() / 3, "{far}");
}

#[test]
fn models_of_different_kernels_do_not_blend() {
    let a = torus(0, 60);
    let mut b = torus(2, 60);
    let settings = FitSettings {
        kernel: Some(rbf_core::Kernel::Linear),
        ..Default::default()
    };
    b.interpolant = rbf_solve::fit(&b.constraints, &settings)
        .unwrap()
        .interpolant;
    let e = blend(&[&a, &b]).unwrap_err();
    assert!(e.to_string().contains("kernel"), "{e}");
    assert!(blend::<3>(&[]).is_err());
}
