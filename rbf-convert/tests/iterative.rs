//! The iterative conversion of Yngve & Turk (2002) on the shipped meshes at resolution 64.

use rbf_convert::{IterativeSettings, convert_iterative};
use rbf_mesh::{PolygonizeSettings, Resolution, polygonize_grid, read_mesh};

fn data(name: &str) -> std::path::PathBuf {
    std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../data/meshes")
        .join(name)
}

#[test]
fn shipped_meshes_convert_within_two_voxels_with_their_genus() {
    for (name, genus) in [("torus.obj", 1), ("knot.obj", 1), ("spot.obj", 0)] {
        let mesh = read_mesh(&data(name)).unwrap();
        let s = IterativeSettings {
            resolution: 64,
            ..Default::default()
        };
        let (model, report) = convert_iterative(&mesh, &s, |_, _| {}).unwrap();
        let t = report
            .topology
            .expect("closed meshes get the topology check");
        assert!(t.agrees() && t.goal_genus == genus, "{name}: {t:?}");
        let best = report.iterations[report.best - 1];
        assert!(best.max_error <= 2.0, "{name}: {best:?}");
        assert!(best.rms_error <= 0.4, "{name}: {best:?}");
        let f = model.interpolant.view();
        let p = PolygonizeSettings {
            resolution: Resolution::CellSize(report.voxel_size),
            ..Default::default()
        };
        let (surface, _) = polygonize_grid(&f, &p).unwrap();
        let r = surface.check();
        assert!(r.is_watertight(), "{name}: {r:?}");
        assert_eq!(r.genus, Some(genus), "{name}");
        assert_eq!(r.components, 1, "{name}");
        // Independently of the loop's own metric: sampled two-way distances between the
        // original mesh and the polygonized result, within two voxels.
        let h = report.voxel_size;
        let step = (surface.positions().len() / 300).max(1);
        for p in surface.positions().iter().step_by(step) {
            let d = (0..mesh.triangles().len())
                .map(|t| point_triangle(*p, mesh.corners(t)))
                .fold(f64::INFINITY, f64::min);
            assert!(
                d <= 2.0 * h,
                "{name}: a surface point is {} voxels from the mesh",
                d / h
            );
        }
        for p in mesh
            .positions()
            .iter()
            .step_by((mesh.positions().len() / 300).max(1))
        {
            let (v, g) = f.value_and_gradient(p);
            let d = v.abs() / (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
            assert!(
                d <= 2.0 * h,
                "{name}: a mesh vertex is {} voxels from the surface",
                d / h
            );
        }
    }
}

/// Distance from p to triangle (a, b, c) (Ericson, Real-Time Collision Detection, 5.1.5).
fn point_triangle(p: [f64; 3], [a, b, c]: [[f64; 3]; 3]) -> f64 {
    let sub = |x: [f64; 3], y: [f64; 3]| [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
    let dot = |x: [f64; 3], y: [f64; 3]| x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    let at = |u: f64, v: f64| -> [f64; 3] {
        core::array::from_fn(|d| a[d] + u * (b[d] - a[d]) + v * (c[d] - a[d]))
    };
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    let closest = if d1 <= 0.0 && d2 <= 0.0 {
        a
    } else {
        let bp = sub(p, b);
        let (d3, d4) = (dot(ab, bp), dot(ac, bp));
        let cp = sub(p, c);
        let (d5, d6) = (dot(ab, cp), dot(ac, cp));
        let vc = d1 * d4 - d3 * d2;
        let vb = d5 * d2 - d1 * d6;
        let va = d3 * d6 - d5 * d4;
        if d3 >= 0.0 && d4 <= d3 {
            b
        } else if d6 >= 0.0 && d5 <= d6 {
            c
        } else if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
            at(d1 / (d1 - d3), 0.0)
        } else if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
            at(0.0, d2 / (d2 - d6))
        } else if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
            let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
            core::array::from_fn(|d| b[d] + w * (c[d] - b[d]))
        } else {
            let denom = 1.0 / (va + vb + vc);
            at(vb * denom, vc * denom)
        }
    };
    let d = sub(p, closest);
    dot(d, d).sqrt()
}

#[test]
fn meshes_with_holes_convert_through_winding_numbers() {
    let torus = read_mesh(&data("torus.obj")).unwrap();
    let tris: Vec<[u32; 3]> = torus
        .triangles()
        .iter()
        .enumerate()
        .filter(|(t, _)| t % 61 != 7)
        .map(|(_, t)| *t)
        .collect();
    let holed = rbf_mesh::TriMesh::new(torus.positions().to_vec(), tris).unwrap();
    let s = IterativeSettings {
        resolution: 40,
        ..Default::default()
    };
    let (model, report) = convert_iterative(&holed, &s, |_, _| {}).unwrap();
    assert!(!report.watertight);
    let best = report.iterations[report.best - 1];
    assert!(best.max_error <= 2.0, "{best:?}");
    let p = PolygonizeSettings {
        resolution: Resolution::CellSize(report.voxel_size),
        ..Default::default()
    };
    let (surface, _) = polygonize_grid(&model.interpolant.view(), &p).unwrap();
    assert_eq!(surface.check().genus, Some(1));
}

#[test]
fn flat_meshes_and_hopeless_resolutions_are_clear_errors() {
    let flat = rbf_mesh::TriMesh::new(
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        vec![[0, 1, 2]],
    )
    .unwrap();
    let e = convert_iterative(
        &flat,
        &IterativeSettings {
            resolution: 16,
            ..Default::default()
        },
        |_, _| {},
    )
    .unwrap_err();
    assert!(e.to_string().contains("no voxel is inside"), "{e}");
    let torus = read_mesh(&data("torus.obj")).unwrap();
    let e = convert_iterative(
        &torus,
        &IterativeSettings {
            resolution: 1,
            ..Default::default()
        },
        |_, _| {},
    )
    .unwrap_err();
    assert!(e.to_string().contains("too coarse"), "{e}");
}

/// The 2D entry (Yngve & Turk 2002, Figure 3) on a ring: the curve comes within the target
/// error of the goal's boundary, the hole stays outside, the band inside, and the same pixels
/// are classed as the goal's except along the boundary.
#[test]
fn a_ring_converts_in_2d_with_its_hole() {
    let (inner, outer) = (0.45, 1.0);
    let ring = |p: [f64; 2]| {
        let r = (p[0] * p[0] + p[1] * p[1]).sqrt();
        r > inner && r < outer
    };
    let settings = rbf_convert::IterativeSettings {
        resolution: 64,
        ..Default::default()
    };
    let mut seen = 0;
    let (curve, report) =
        rbf_convert::convert_iterative_2d(ring, ([-1.1; 2], [1.1; 2]), &settings, |it, model| {
            seen += 1;
            assert_eq!(
                model.constraints.len(),
                it.boundary + it.interior + it.exterior
            );
        })
        .unwrap();
    assert_eq!(seen, report.iterations.len());
    assert_eq!(report.shape[2], 1);
    let best = report.iterations[report.best - 1];
    assert!(best.max_error <= settings.target_error, "{best:?}");
    let f = &curve.interpolant;
    assert!(f.value(&[0.0, 0.0]) < 0.0, "the hole is outside");
    let pixel = report.voxel_size;
    for k in 0..64 {
        let a = std::f64::consts::TAU * k as f64 / 64.0;
        let at = |r: f64| f.value(&[r * a.cos(), r * a.sin()]);
        assert!(
            at(0.5 * (inner + outer)) > 0.0,
            "the band is inside at angle {a}"
        );
        // Farther than two pixels from the goal's boundary, the classes agree.
        for r in [inner - 2.0 * pixel, outer + 2.0 * pixel] {
            assert!(at(r) < 0.0, "outside at radius {r}, angle {a}");
        }
        for r in [inner + 2.0 * pixel, outer - 2.0 * pixel] {
            assert!(at(r) > 0.0, "inside at radius {r}, angle {a}");
        }
    }
}

/// Bad boxes and sizes of the 2D entry are errors that say what to change, never a panic.
#[test]
fn bad_2d_boxes_and_sizes_are_clear_errors() {
    let disc = |p: [f64; 2]| p[0] * p[0] + p[1] * p[1] < 1.0;
    let run = |lo: [f64; 2], hi: [f64; 2], resolution: usize| {
        let settings = rbf_convert::IterativeSettings {
            resolution,
            ..Default::default()
        };
        rbf_convert::convert_iterative_2d(disc, (lo, hi), &settings, |_, _| {})
            .map(|_| ())
            .unwrap_err()
            .to_string()
    };
    for (lo, hi, resolution) in [
        ([1.0, -1.0], [-1.0, 1.0], 32),
        ([-1.0, -1.0], [1.0, 1.0], 0),
        ([f64::NAN, -1.0], [1.0, 1.0], 32),
        ([-1.0, -1.0], [f64::INFINITY, 1.0], 32),
    ] {
        let e = run(lo, hi, resolution);
        assert!(
            e.contains("has no pixels"),
            "{lo:?} {hi:?} {resolution}: {e}"
        );
    }
    let e = run([-1.0; 2], [1.0; 2], 1 << 20);
    assert!(e.contains("too large"), "{e}");
    // A region that misses the box: nothing inside.
    let e = rbf_convert::convert_iterative_2d(
        |_| false,
        ([-1.0; 2], [1.0; 2]),
        &rbf_convert::IterativeSettings::default(),
        |_, _| {},
    )
    .map(|_| ())
    .unwrap_err();
    assert!(e.to_string().contains("no voxel is inside"), "{e}");
}

/// The paper stops once the largest error is within a voxel; this loop goes on while the RMS
/// of the errors is above its target too (a surface a voxel off in many places), and stops at
/// the first iteration within both. The torus at 64 is within a voxel at once, RMS 0.35.
#[test]
fn the_loop_goes_on_while_its_rms_is_above_the_target() {
    let mesh = read_mesh(&data("torus.obj")).unwrap();
    let run = |target_rms: f64| {
        let s = IterativeSettings {
            resolution: 64,
            target_rms,
            ..Default::default()
        };
        convert_iterative(&mesh, &s, |_, _| {}).unwrap().1
    };
    let target = IterativeSettings::default();
    // By the paper's rule alone: one iteration, within a voxel but not within the RMS target.
    let paper = run(f64::INFINITY);
    let first = paper.iterations[0];
    assert_eq!(paper.iterations.len(), 1, "{:?}", paper.iterations);
    assert!(first.max_error <= target.target_error, "{first:?}");
    assert!(first.rms_error > target.target_rms, "{first:?}");
    // With it: on until both are met, and no further.
    let ours = run(target.target_rms);
    let (last, before) = ours.iterations.split_last().unwrap();
    assert!(!before.is_empty());
    for it in before {
        assert!(
            it.max_error > target.target_error || it.rms_error > target.target_rms,
            "{it:?}"
        );
    }
    assert!(last.max_error <= target.target_error, "{last:?}");
    assert!(last.rms_error <= target.target_rms, "{last:?}");
    assert_eq!(ours.best, ours.iterations.len());
}
