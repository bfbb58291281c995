//! Scans to surfaces: clouds without normals (or with some flipped) become closed surfaces of
//! the right topology near the points; flat, tiny and hopelessly noisy clouds are refused.

use rbf_convert::{
    ConvertError, ReconstructSettings, mesh_resolution, reconstruct, scan_mesh, scan_surface,
};
use rbf_mesh::{
    PolygonizeSettings, Resolution, polygonize_continuation, read_mesh, sample_surface,
    surface_seeds,
};

/// Points spread over a torus around z (radii 1 and 0.4) by a golden-ratio lattice, and their
/// outward normals.
fn torus(n: usize) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let golden = 0.5 * (5f64.sqrt() - 1.0);
    (0..n)
        .map(|i| {
            let u = std::f64::consts::TAU * i as f64 / n as f64;
            let v = std::f64::consts::TAU * (i as f64 * golden).fract();
            let normal = [v.cos() * u.cos(), v.cos() * u.sin(), v.sin()];
            let r = 1.0 + 0.4 * v.cos();
            ([r * u.cos(), r * u.sin(), 0.4 * v.sin()], normal)
        })
        .unzip()
}

/// `normals` with every third one (from the first) reversed.
fn every_third_flipped(normals: &[[f64; 3]]) -> Vec<[f64; 3]> {
    normals
        .iter()
        .enumerate()
        .map(|(i, n)| if i % 3 == 0 { n.map(|c| -c) } else { *n })
        .collect()
}

/// `points` each moved by Gaussian noise of deviation `sigma` along every axis (Box–Muller from
/// a fixed integer hash: the same noise at every run).
fn with_noise(points: &[[f64; 3]], sigma: f64) -> Vec<[f64; 3]> {
    let uniform = |k: u64| {
        let x = k.wrapping_mul(0x9E37_79B9_7F4A_7C15).rotate_left(29) ^ 0xD1B5_4A32_D192_ED03;
        ((x.wrapping_mul(0xBF58_476D_1CE4_E5B9) >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    let gaussian = |k: u64| {
        (-2.0 * uniform(2 * k).ln()).sqrt() * (std::f64::consts::TAU * uniform(2 * k + 1)).cos()
    };
    points
        .iter()
        .enumerate()
        .map(|(i, p)| core::array::from_fn(|d| p[d] + sigma * gaussian((3 * i + d) as u64)))
        .collect()
}

/// Distance from `p` to the torus of [`torus`].
fn off_torus(p: &[f64; 3]) -> f64 {
    (((p[0].hypot(p[1]) - 1.0).powi(2) + p[2] * p[2]).sqrt() - 0.4).abs()
}

fn topology(model: &rbf_core::Model<3>) -> (bool, Option<i64>, usize) {
    let settings = PolygonizeSettings {
        resolution: Resolution::Cells(64),
        ..Default::default()
    };
    let (mesh, _) =
        polygonize_continuation(&model.interpolant.view(), &surface_seeds(model), &settings)
            .unwrap();
    let r = mesh.check();
    (r.is_watertight(), r.genus, r.components)
}

#[test]
fn a_torus_without_normals_comes_out_closed_with_its_hole() {
    let (points, _) = torus(4000);
    let (model, report) = reconstruct(&points, None, &ReconstructSettings::default()).unwrap();
    assert!(report.normals_estimated && report.within_tolerance);
    assert_eq!(report.pieces, 1);
    // A clean scan's smoothing fit is solved to 1e-3 of its largest value, as a noisy one's
    // (the surface moves by at most 0.07 of the offset: 0.07 % of the box), not the dense
    // solver's stricter 1e-6, which a sparse scan's ill-conditioned fit could miss.
    assert_eq!(model.settings.max_residual, 1e-3);
    assert!(report.lambda > 0.0);
    let (watertight, genus, components) = topology(&model);
    assert!(watertight);
    assert_eq!((genus, components), (Some(1), 1));
    // The surface passes near every point: f changes sign across each within the tolerance.
    let f = model.interpolant.view();
    assert!(f.value(&[1.0, 0.0, 0.0]) > 0.0, "inside the tube");
    assert!(f.value(&[0.0, 0.0, 0.0]) < 0.0, "the hole is outside");
}

/// A clean scan's normals are checked by lines of sight only when asked (`sight`), which
/// `scan_surface` asks for in a second attempt when the first mesh comes out open; asked, they
/// turn nothing on a torus whose normals are right, and the surface is the same closed torus.
#[test]
fn lines_of_sight_on_a_clean_scan_only_when_asked() {
    let (points, _) = torus(4000);
    let plain = scan_surface(&points, None, &ReconstructSettings::default(), Some(48)).unwrap();
    assert!(!plain.report.sight && !plain.report.looked_again);
    assert_eq!(plain.report.reversed_by_sight, 0);
    let asked = ReconstructSettings {
        sight: true,
        ..Default::default()
    };
    let sighted = scan_surface(&points, None, &asked, Some(48)).unwrap();
    assert!(sighted.report.sight && !sighted.report.looked_again);
    assert_eq!(sighted.report.reversed_by_sight, 0);
    for scan in [&plain, &sighted] {
        let r = scan.mesh.check();
        assert!(
            r.is_watertight() && r.genus == Some(1) && r.components == 1,
            "{r:?}"
        );
    }
}

/// A clean scan of a detailed object keeps its crevices open: 30 000 points spread evenly over
/// the fish (genus 0, its fins and gills in creases a few points wide) come out genus 0 in one
/// piece with the default smoothing fit, meshed as `rbf reconstruct` meshes them. The control:
/// the greedy fit on the same points, asked for by a tolerance of 2.5e-3, takes the points at
/// the bottom of the creases as centres and closes creases over (genus 3 when this was
/// written); a clean scan had it by default before.
#[test]
fn a_clean_scan_keeps_its_crevices_open() {
    let fish = read_mesh(
        &std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../data/meshes/fish.obj"),
    )
    .unwrap();
    let points = sample_surface(&fish, 30_000, 5);
    let resolution = mesh_resolution(&points);
    let topology_of = |settings: &ReconstructSettings| {
        let (model, report) = reconstruct(&points, None, settings).unwrap();
        let (mesh, _) = scan_mesh(&model, &report, &points, resolution).unwrap();
        let r = mesh.check();
        assert!(r.is_watertight());
        (report.lambda, r.genus, r.components)
    };
    let (lambda, genus, pieces) = topology_of(&ReconstructSettings::default());
    assert!(lambda > 0.0);
    assert_eq!((genus, pieces), (Some(0), 1));
    let greedy = ReconstructSettings {
        tolerance: Some(2.5e-3),
        ..Default::default()
    };
    let (lambda, genus, pieces) = topology_of(&greedy);
    assert_eq!(lambda, 0.0);
    assert!(
        genus > Some(0) || pieces > 1,
        "the greedy fit kept the crevices open too"
    );
}

/// A scan denser than `working` is worked on as a random subset of that many points, and its
/// given normals stay paired with their points: a torus of 12 000 points worked on as 3000
/// still comes out closed with its hole, though a third of its normals are given flipped.
#[test]
fn a_dense_scan_is_worked_on_as_a_subset_with_its_normals() {
    let (points, normals) = torus(12_000);
    let given = every_third_flipped(&normals);
    let settings = ReconstructSettings {
        working: 3000,
        ..Default::default()
    };
    let (model, report) = reconstruct(&points, Some(&given), &settings).unwrap();
    assert_eq!((report.points, report.outliers), (12_000, 0));
    assert_eq!(report.working, 3000);
    // About a third of the 3000 worked on were flipped, and were found.
    assert!((800..1200).contains(&report.flipped), "{}", report.flipped);
    let (watertight, genus, components) = topology(&model);
    assert!(watertight);
    assert_eq!((genus, components), (Some(1), 1));
}

#[test]
fn flipped_given_normals_are_fixed_before_fitting() {
    let (points, truth) = torus(3000);
    let given = every_third_flipped(&truth);
    let (model, report) =
        reconstruct(&points, Some(&given), &ReconstructSettings::default()).unwrap();
    assert!(!report.normals_estimated);
    assert_eq!(report.flipped, 1000);
    assert_eq!(topology(&model).1, Some(1));
}

/// Scanners write a zero normal where they have none: those points get estimated normals (and
/// are counted), and a cloud whose normals are all zero is reconstructed as one without
/// normals. Before, the zero normals' points were left out of the fit, and a cloud of zero
/// normals failed with "0 constraint point(s) cannot determine a surface".
#[test]
fn given_normals_of_zero_length_are_estimated() {
    let (points, truth) = torus(3000);
    let settings = ReconstructSettings {
        outlier_ratio: None,
        ..Default::default()
    };
    let some_zero: Vec<[f64; 3]> = truth
        .iter()
        .enumerate()
        .map(|(i, n)| if i % 10 == 0 { [0.0; 3] } else { *n })
        .collect();
    let (model, report) = reconstruct(&points, Some(&some_zero), &settings).unwrap();
    assert!(!report.normals_estimated);
    assert_eq!(report.normals_filled, 300);
    assert_eq!(topology(&model).1, Some(1));
    let (model, report) = reconstruct(&points, Some(&vec![[0.0; 3]; 3000]), &settings).unwrap();
    assert!(report.normals_estimated);
    assert_eq!(report.normals_filled, 0);
    assert_eq!(topology(&model).1, Some(1));
}

#[test]
fn outliers_are_dropped_and_counted() {
    let (mut points, _) = torus(3000);
    for i in 0..20 {
        let t = i as f64;
        points.push([3.0 + t.sin(), 2.5 * t.cos(), 2.0 + 0.1 * t]);
    }
    let (_, report) = reconstruct(&points, None, &ReconstructSettings::default()).unwrap();
    assert!(report.outliers >= 20, "{} dropped", report.outliers);
    assert!(report.outliers <= 20 + 60, "{} dropped", report.outliers);
}

/// A scan given twice over (merged scans repeat points) is the scan given once: the repeats
/// are dropped first, so neighbourhoods, outliers, normals and the fit are the same.
#[test]
fn a_scan_given_twice_is_reconstructed_as_once() {
    let (points, _) = torus(3000);
    let twice = [points.clone(), points.clone()].concat();
    let settings = ReconstructSettings::default();
    let (once, report_once) = reconstruct(&points, None, &settings).unwrap();
    let (again, report) = reconstruct(&twice, None, &settings).unwrap();
    assert_eq!((report.points, report.duplicates), (6000, 3000));
    assert_eq!(report.outliers, report_once.outliers);
    assert_eq!(report.centres, report_once.centres);
    let at = [
        [1.0, 0.0, 0.0],
        [0.3, 1.1, 0.2],
        [0.0, 0.0, 0.0],
        [2.0, 0.5, -0.1],
    ];
    for p in at {
        let (a, b) = (once.interpolant.value(&p), again.interpolant.value(&p));
        assert!(
            (a - b).abs() <= 1e-9 * a.abs().max(1.0),
            "{a} against {b} at {p:?}"
        );
    }
}

#[test]
fn flat_and_tiny_clouds_are_refused_with_what_they_are() {
    let plane: Vec<[f64; 3]> = (0..400)
        .map(|i| [(i % 20) as f64, (i / 20) as f64, 0.5 * (i % 20) as f64])
        .collect();
    let settings = ReconstructSettings {
        outlier_ratio: None,
        ..Default::default()
    };
    assert!(matches!(
        reconstruct(&plane, None, &settings),
        Err(ConvertError::Flat { shape: "plane" })
    ));
    let line: Vec<[f64; 3]> = (0..50).map(|i| [i as f64, 2.0 * i as f64, 0.0]).collect();
    assert!(matches!(
        reconstruct(&line, None, &settings),
        Err(ConvertError::Flat { shape: "line" })
    ));
    // Along a diagonal, where the points' coordinates round: still a line, not a plane.
    let diagonal: Vec<[f64; 3]> = (0..100)
        .map(|i| [i as f64 / 7.0, 2.0 * i as f64 / 7.0, 3.0 * i as f64 / 7.0])
        .collect();
    let refused = reconstruct(&diagonal, None, &settings);
    assert!(
        matches!(refused, Err(ConvertError::Flat { shape: "line" })),
        "{refused:?}"
    );
    assert!(matches!(
        reconstruct(&[[0.0; 3]; 5], None, &settings),
        Err(ConvertError::TooFewPoints { points: 5, .. })
    ));
    assert!(matches!(
        reconstruct(&[[1.0, 2.0, 3.0]; 40], None, &settings),
        Err(ConvertError::Flat { shape: "point" })
    ));
    // Coordinates whose squares overflow: such a cloud was taken for one point. And NaN, for
    // callers of the library that do not check it first.
    let (torus_points, _) = torus(400);
    for bad in [f64::NAN, 1e300, -f64::INFINITY] {
        let mut points = torus_points.clone();
        points[7][1] = bad;
        let refused = reconstruct(&points, None, &settings);
        assert!(
            matches!(refused, Err(ConvertError::PointOutOfRange { index: 7, .. })),
            "{refused:?}"
        );
    }
    let huge: Vec<[f64; 3]> = torus_points.iter().map(|p| p.map(|c| c * 1e300)).collect();
    assert!(matches!(
        reconstruct(&huge, None, &settings),
        Err(ConvertError::PointOutOfRange { .. })
    ));
}

/// A scan as users have them: two holes, one side three times as dense as the other, a few
/// outliers. The surface comes out closed, one piece, with the torus's hole, close to the torus
/// everywhere (holes filled smoothly), once pieces that no point is near are dropped.
#[test]
fn a_scan_with_holes_uneven_density_and_outliers_comes_out_one_closed_torus() {
    let (all, _) = torus(9000);
    let holes = [[1.4, 0.0, 0.0], [-0.6, 0.0, 0.3]];
    let mut points: Vec<[f64; 3]> = all
        .iter()
        .enumerate()
        .filter(|(i, p)| p[0] > 0.0 || i % 3 == 0)
        .filter(|(_, p)| {
            holes.iter().all(|h| {
                let d2: f64 = (0..3).map(|k| (p[k] - h[k]).powi(2)).sum();
                d2 > 0.25 * 0.25
            })
        })
        .map(|(_, p)| *p)
        .collect();
    for i in 0..15 {
        let t = i as f64;
        points.push([1.7 * t.sin(), 1.7 * (1.3 * t).cos(), 0.6 * (0.7 * t).sin()]);
    }
    let (model, report) = reconstruct(&points, None, &ReconstructSettings::default()).unwrap();
    let (mesh, dropped) = rbf_convert::scan_mesh(&model, &report, &points, 64).unwrap();
    let r = mesh.check();
    assert!(r.is_watertight(), "{r:?}");
    assert_eq!(
        (r.genus, r.components),
        (Some(1), 1),
        "{report:?}, {dropped} dropped"
    );
    let worst = mesh.positions().iter().map(off_torus).fold(0.0, f64::max);
    assert!(worst < 0.05, "a vertex {worst} from the torus");
}

/// A noisy scan: Gaussian noise of 0.6 % of the diagonal along every axis (a sixth of the
/// tube's radius in one deviation). The noise is measured about right, and the surface
/// comes out smooth, closed, one piece with the torus's hole, near the torus: with the noisy
/// normals chosen first, as a plain greedy fit does, it came out with genus 2.
#[test]
fn a_noisy_scan_comes_out_one_smooth_closed_torus() {
    let (clean, _) = torus(12_000);
    let sigma = 0.006 * (2.8f64 * 2.8 * 2.0 + 0.8 * 0.8).sqrt();
    let points = with_noise(&clean, sigma);
    let (model, report) = reconstruct(&points, None, &ReconstructSettings::default()).unwrap();
    let measured = report.noise * 2.8;
    assert!(
        (0.5 * sigma..2.0 * sigma).contains(&measured),
        "noise measured {measured}, made {sigma}"
    );
    let (mesh, _) = rbf_convert::scan_mesh(&model, &report, &points, 64).unwrap();
    let r = mesh.check();
    assert!(r.is_watertight(), "{r:?}");
    assert_eq!((r.genus, r.components), (Some(1), 1), "{report:?}");
    let worst = mesh.positions().iter().map(off_torus).fold(0.0, f64::max);
    assert!(worst < 4.0 * sigma, "a vertex {worst} from the torus");
}

/// A noisy scan is approximated by a smoothing fit, which passes through the middle of the
/// noise: its surface lies within a third of the noise's deviation of the torus (RMS over the
/// mesh's vertices), and closer than the greedy fit that a tolerance asks for, which passes
/// through the points the noise put farthest out first (measured: RMS 0.0040 against 0.0050,
/// worst vertex 0.0145 against 0.0157).
#[test]
fn a_smoothing_fit_passes_through_the_middle_of_the_noise() {
    let (clean, _) = torus(20_000);
    let sigma = 0.004 * (2.8f64 * 2.8 * 2.0 + 0.8 * 0.8).sqrt();
    let points = with_noise(&clean, sigma);
    let rms_off = |settings: &ReconstructSettings| {
        let (model, report) = reconstruct(&points, None, settings).unwrap();
        let (mesh, _) = rbf_convert::scan_mesh(&model, &report, &points, 96).unwrap();
        let r = mesh.check();
        assert!(r.is_watertight(), "{r:?}");
        assert_eq!((r.genus, r.components), (Some(1), 1), "{report:?}");
        let v = mesh.positions();
        let rms = (v.iter().map(|p| off_torus(p).powi(2)).sum::<f64>() / v.len() as f64).sqrt();
        let worst = v.iter().map(off_torus).fold(0.0, f64::max);
        (rms, worst, report, model)
    };
    let (smooth, smooth_worst, report, model) = rms_off(&ReconstructSettings::default());
    assert!(report.lambda > 0.0, "{report:?}");
    assert!((9000..=10_000).contains(&report.centres), "{report:?}");
    // Its 2·10⁴ centres are summed through the far field (as `scan_mesh` builds it), whose
    // mesh is the direct sums' to within 10⁻⁴ of a cube (7.2 / 96; 1.2·10⁻⁶ measured).
    let view = model.interpolant.view();
    let seeds = surface_seeds(&model);
    let evaluator =
        rbf_far::Evaluator::new(view, &seeds, rbf_far::default_accuracy(view.centres()));
    assert!(matches!(
        evaluator.method(),
        rbf_far::Method::FarField { .. }
    ));
    let (far, _) = rbf_convert::scan_mesh(&model, &report, &points, 96).unwrap();
    let settings = PolygonizeSettings {
        resolution: Resolution::Cells(96),
        ..Default::default()
    };
    let (direct, _) = polygonize_continuation(&view, &seeds, &settings).unwrap();
    let apart = |a: &[[f64; 3]], b: &[[f64; 3]]| {
        rbf_cloud::distances_to_cloud(a, b)
            .into_iter()
            .fold(0.0, f64::max)
    };
    let (a, b) = (far.positions(), direct.positions());
    assert!(
        a.len().abs_diff(b.len()) * 1000 <= b.len(),
        "{} and {} vertices",
        a.len(),
        b.len()
    );
    let moved = apart(a, b).max(apart(b, a));
    assert!(
        moved < 1e-4 * 7.2 / 96.0,
        "a vertex {moved} from the other mesh's"
    );
    assert!(
        smooth < sigma / 3.0,
        "RMS {smooth} off the torus, noise {sigma}"
    );
    let greedy = ReconstructSettings {
        tolerance: Some(report.tolerance),
        ..Default::default()
    };
    let (fitted, fitted_worst, greedy_report, _) = rms_off(&greedy);
    assert_eq!(greedy_report.lambda, 0.0);
    assert!(
        smooth < 0.9 * fitted && smooth_worst < fitted_worst,
        "smoothing fit {smooth} (worst {smooth_worst}), greedy fit {fitted} (worst {fitted_worst}) off the torus"
    );
}

/// A scan whose one half is sparse and noisy: its smoothing fit has about 2·10⁴ centres and
/// goes through the far field, which must be as accurate between the centres, where the
/// polygonizer samples, as at them: within the accuracy the scan's tolerance asks for.
#[test]
fn a_sparse_noisy_scan_meshes_through_the_far_field_as_by_direct_sums() {
    let (all, _) = torus(60_000);
    let sparse: Vec<[f64; 3]> = all
        .iter()
        .enumerate()
        .filter(|(i, p)| p[0] < 0.0 || i % 12 == 0)
        .map(|(_, p)| *p)
        .collect();
    let sigma = 0.005 * (2.8f64 * 2.8 * 2.0 + 0.8 * 0.8).sqrt();
    let points = with_noise(&sparse, sigma);
    let (model, report) = reconstruct(&points, None, &ReconstructSettings::default()).unwrap();
    assert!(report.lambda > 0.0, "{report:?}");
    let (far, _) = rbf_convert::scan_mesh(&model, &report, &points, 96).unwrap();
    let view = model.interpolant.view();
    let settings = PolygonizeSettings {
        resolution: Resolution::Cells(96),
        ..Default::default()
    };
    let (direct, _) = polygonize_continuation(&view, &surface_seeds(&model), &settings).unwrap();
    let apart = |a: &[[f64; 3]], b: &[[f64; 3]]| {
        rbf_cloud::distances_to_cloud(a, b)
            .into_iter()
            .fold(0.0, f64::max)
    };
    let (a, b) = (far.positions(), direct.positions());
    let moved = apart(a, b).max(apart(b, a));
    // The scan's mesh is evaluated to what moves the surface by a hundredth of the tolerance
    // where f has its median slope: two hundredths anywhere (with the far field calibrated at
    // the surface points alone, a noisy bunny's mesh lay 0.5 % of the diagonal inside).
    let allowed = 0.02 * report.tolerance * 7.2;
    assert!(
        moved < allowed,
        "a vertex {moved} from the direct sums' mesh, {allowed} allowed"
    );
}

/// A strip whose faces are three point spacings apart, thinner than the normal constraints'
/// default offset (1 % of its longest side, 3.2): each inside point goes only as deep as it
/// stays nearest its own face, so it does not land outside the other one, and the strip comes
/// out solid between its two faces.
#[test]
fn a_strip_thinner_than_the_offset_stays_solid_between_its_faces() {
    let (length, width, half) = (160i32, 8i32, 1.5);
    let mut points = Vec::new();
    let mut normals = Vec::new();
    for i in -length..=length {
        for j in -width..=width {
            let (x, y) = (i as f64, j as f64);
            for side in [1.0, -1.0] {
                points.push([x, y, side * half]);
                normals.push([0.0, 0.0, side]);
            }
            let rim = [
                if i.abs() == length {
                    i.signum() as f64
                } else {
                    0.0
                },
                if j.abs() == width {
                    j.signum() as f64
                } else {
                    0.0
                },
                0.0,
            ];
            if rim != [0.0; 3] {
                for z in [-0.75, 0.0, 0.75] {
                    points.push([x, y, z]);
                    normals.push(rim);
                }
            }
        }
    }
    let (model, _) = reconstruct(&points, Some(&normals), &ReconstructSettings::default()).unwrap();
    let f = model.interpolant.view();
    for k in 0..=10 {
        let (x, y) = (-140.0 + 28.0 * k as f64, 5.0 - k as f64);
        assert!(
            f.value(&[x, y, 0.0]) > 0.0,
            "inside the strip at ({x}, {y})"
        );
        for z in [2.5, -2.5] {
            assert!(
                f.value(&[x, y, z]) < 0.0,
                "outside the strip at ({x}, {y}, {z})"
            );
        }
    }
}

/// The default smoothing follows the measured noise (`smoothing_for_noise`): a very noisy
/// scan (1 % of the diagonal along each axis) is smoothed more than with the λ that suits
/// 0.5 % (1e-4), and its surface comes out closer to the true one.
#[test]
fn a_very_noisy_scan_is_smoothed_more() {
    let (clean, _) = torus(20_000);
    let diagonal = (2.8f64 * 2.8 * 2.0 + 0.8 * 0.8).sqrt();
    let points = with_noise(&clean, 0.01 * diagonal);
    let run = |smoothing: Option<f64>| {
        let settings = ReconstructSettings {
            smoothing,
            ..Default::default()
        };
        let (model, report) = reconstruct(&points, None, &settings).unwrap();
        let (mesh, _) = rbf_convert::scan_mesh(&model, &report, &points, 96).unwrap();
        let v = mesh.positions();
        let rms = (v.iter().map(|p| off_torus(p).powi(2)).sum::<f64>() / v.len() as f64).sqrt();
        (rms, report)
    };
    let (chosen, report) = run(None);
    let (fixed, fixed_report) = run(Some(1e-4));
    // λ in the points' units is the box's (longest side 2) times the cube of half the side.
    let expected = rbf_convert::smoothing_for_noise(report.noise) * fixed_report.lambda / 1e-4;
    assert!(
        (report.lambda - expected).abs() < 1e-9 * expected
            && report.lambda > 2.0 * fixed_report.lambda,
        "{report:?}"
    );
    // Measured: RMS 0.0082 against 0.0088 off the torus (noise 0.011 of the box measured).
    assert!(
        chosen < 0.96 * fixed,
        "RMS {chosen} off the torus, {fixed} with λ 1e-4"
    );
}

/// `n` points spread over a sphere of radius 1 about `centre` by a golden-angle lattice.
fn sphere(n: usize, centre: [f64; 3]) -> Vec<[f64; 3]> {
    (0..n)
        .map(|i| {
            let z = 1.0 - (2 * i + 1) as f64 / n as f64;
            let t = 2.399_963_229_728_653 * i as f64;
            let s = (1.0 - z * z).sqrt();
            [
                centre[0] + s * t.cos(),
                centre[1] + s * t.sin(),
                centre[2] + z,
            ]
        })
        .collect()
}

/// Two spheres a gap of under two spread spacings apart: the clean scan's spread gains points
/// where they face each other (and only a few), and the surface comes out as two closed
/// pieces; with a cap on the centres (`with_max_centres`) it gains none.
#[test]
fn a_spread_is_made_finer_where_two_sheets_face_each_other() {
    let mut points = sphere(10_000, [0.0; 3]);
    points.extend(sphere(10_000, [2.15, 0.0, 0.0]));
    // A spread of 3000 over the two spheres' area (8π) is about 0.1 apart; the gap is 0.15.
    let settings = ReconstructSettings {
        clean_centres: 3000,
        ..Default::default()
    };
    let (model, report) = reconstruct(&points, None, &settings).unwrap();
    assert!(
        report.added_where_sheets_close > 40 && report.added_where_sheets_close < 400,
        "{} added",
        report.added_where_sheets_close
    );
    let (watertight, _, components) = topology(&model);
    assert!(watertight);
    assert_eq!(components, 2);
    let capped = settings.with_max_centres(3000);
    let (_, report) = reconstruct(&points, None, &capped).unwrap();
    assert_eq!(report.added_where_sheets_close, 0);
    assert!(report.centres <= 3000);
}

/// The torus of [`torus`] scanned in slices: circles in 13 planes z = const, 0.06 apart, each
/// sampled 0.005 apart (as a stack of contours, or a line scanner's profiles). Sixteen
/// neighbours stay on their own circle and cannot tell a plane; the neighbourhoods grow until
/// they span the slices, and the surface comes out the torus, every normal pointing out.
#[test]
fn a_torus_scanned_in_slices_comes_out_closed_with_its_hole() {
    let mut points = Vec::new();
    let mut normals = Vec::new();
    for slice in 0..13 {
        let z = -0.36 + 0.06 * slice as f64;
        let across = (0.16 - z * z).sqrt();
        for side in [-1.0, 1.0] {
            let r = 1.0 + side * across;
            let count = (std::f64::consts::TAU * r / 0.005) as usize;
            for i in 0..count {
                let u = std::f64::consts::TAU * (i as f64 + 0.5 * slice as f64) / count as f64;
                points.push([r * u.cos(), r * u.sin(), z]);
                // The tube's outward normal: from its centre circle to the point.
                let (dx, dz) = (side * across, z);
                let length = dx.hypot(dz);
                normals.push([dx / length * u.cos(), dx / length * u.sin(), dz / length]);
            }
        }
    }
    let (model, report) = reconstruct(&points, None, &ReconstructSettings::default()).unwrap();
    assert!(report.neighbours > 16, "{}", report.neighbours);
    let (watertight, genus, components) = topology(&model);
    assert!(watertight);
    assert_eq!((genus, components), (Some(1), 1));
    let f = model.interpolant.view();
    let outward = points
        .iter()
        .zip(&normals)
        .filter(|(p, n)| {
            let g = f.gradient(p);
            -(g[0] * n[0] + g[1] * n[1] + g[2] * n[2]) > 0.0
        })
        .count();
    assert!(
        outward * 1000 >= 999 * points.len(),
        "{outward} of {}",
        points.len()
    );
    assert!(
        points.iter().all(|p| f.value(p).abs() < 0.05),
        "the surface passes by the points"
    );
}
