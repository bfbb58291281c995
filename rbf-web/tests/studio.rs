//! The studio's engine, natively: what the page relies on.

use rbf_sculpt::Answer;
use rbf_web::{COARSE_CELLS, FINE_CELLS, Studio, StudioError};

fn bounds(studio: &Studio) -> ([f32; 3], [f32; 3]) {
    let p = &studio.surface().positions;
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for (i, &v) in p.iter().enumerate() {
        lo[i % 3] = lo[i % 3].min(v);
        hi[i % 3] = hi[i % 3].max(v);
    }
    (lo, hi)
}

#[test]
fn the_surface_buffers_are_consistent_and_closed() {
    let studio = Studio::new().unwrap();
    let s = studio.surface();
    assert_eq!(s.positions.len(), s.normals.len());
    assert_eq!(s.positions.len() % 3, 0);
    assert_eq!(s.indices.len() % 3, 0);
    let vertices = (s.positions.len() / 3) as u32;
    assert!(s.indices.iter().all(|&i| i < vertices));
    // Unit normals pointing away from the blob's centre (it is star-shaped around it).
    for (p, n) in s.positions.chunks(3).zip(s.normals.chunks(3)) {
        let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!((length - 1.0).abs() < 1e-4);
        assert!(p[0] * n[0] + p[1] * n[1] + p[2] * n[2] > 0.0);
    }
    let check = s.mesh.as_ref().unwrap().check();
    assert!(check.is_watertight(), "{check:?}");
    assert_eq!(check.genus, Some(0));
    // Every vertex on the surface (|f| / |∇f|, the distance to first order) within a
    // thousandth of a lattice cube.
    let (lo, hi) = bounds(&studio);
    let cube = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f32::max) as f64 / FINE_CELLS as f64;
    let f = studio.model().interpolant;
    for p in s.positions.chunks(3) {
        let (v, g) = f.value_and_gradient(&[p[0] as f64, p[1] as f64, p[2] as f64]);
        let distance = v.abs() / g.iter().map(|c| c * c).sum::<f64>().sqrt();
        assert!(
            distance < 1e-3 * cube,
            "{distance:e} from the surface, cube {cube:e}"
        );
    }
}

#[test]
fn a_pick_adds_a_handle_on_the_surface_without_moving_it() {
    let mut studio = Studio::new().unwrap();
    let before = studio.model().interpolant;
    let hit = studio.hit([0.2, 0.1, 5.0], [0.0, 0.0, -1.0]).unwrap();
    let answer = studio.run("pick 0.2 0.1 5 0 0 -1");
    assert!(
        matches!(
            answer,
            Answer::Applied {
                added: Some(12),
                ..
            }
        ),
        "{answer:?}"
    );
    let after = studio.model().interpolant;
    for p in [[0.3, 0.2, 0.1], [0.0, 0.9, 0.2], [1.5, 0.0, 0.0]] {
        assert!((after.value(&p) - before.value(&p)).abs() < 1e-9);
    }
    let handle = studio.handles()[12];
    assert_eq!((handle.index, handle.kind), (12, 0));
    assert!((0..3).all(|d| (handle.position[d] - hit[d]).abs() < 1e-9));
    assert!(after.value(&handle.position).abs() < 1e-9);
}

#[test]
fn moving_a_handle_moves_the_surface_and_undo_restores_it() {
    let mut studio = Studio::new().unwrap();
    let (_, hi) = bounds(&studio);
    let top = match studio.run("add 0 1.2 0") {
        Answer::Applied { added: Some(i), .. } => i,
        other => panic!("{other:?}"),
    };
    studio.remesh(FINE_CELLS).unwrap();
    let (_, raised) = bounds(&studio);
    assert!(raised[1] > hi[1] + 0.1);
    assert!(matches!(
        studio.run(&format!("move {top} 0 1.8 0")),
        Answer::Applied { .. }
    ));
    studio.remesh(COARSE_CELLS).unwrap();
    let (_, pulled) = bounds(&studio);
    assert!(pulled[1] > 1.7, "{pulled:?}");
    assert!(matches!(studio.run("undo"), Answer::Applied { .. }));
    studio.remesh(FINE_CELLS).unwrap();
    let (_, back) = bounds(&studio);
    assert!((back[1] - raised[1]).abs() < 1e-6);
}

#[test]
fn normal_handles_show_their_boundary_point() {
    let mut studio = Studio::new().unwrap();
    let Answer::Applied {
        added: Some(handle),
        ..
    } = studio.run("normal 0")
    else {
        panic!("no handle");
    };
    let h = studio
        .handles()
        .into_iter()
        .find(|h| h.index == handle)
        .unwrap();
    assert_eq!(h.kind, 3);
    let corner = studio.handles()[0].position;
    assert_eq!(h.base, corner);
    let length = (0..3)
        .map(|d| (h.position[d] - h.base[d]).powi(2))
        .sum::<f64>()
        .sqrt();
    assert!((length - 0.2).abs() < 1e-9, "{length}");
}

#[test]
fn refused_edits_leave_everything_as_it_was() {
    let mut studio = Studio::new().unwrap();
    let before = studio.model().to_json();
    let corner = studio.handles()[1].position;
    for line in [
        "add 1 2".to_string(),
        "delete 40".to_string(),
        "normal 5".to_string(),
        format!("add {} {} {}", corner[0], corner[1], corner[2]),
    ] {
        assert!(
            matches!(studio.run(&line), Answer::Refused(_)),
            "{line} was applied"
        );
    }
    assert_eq!(studio.model().to_json(), before);
}

#[test]
fn models_round_trip_and_bad_files_are_named() {
    let mut studio = Studio::new().unwrap();
    studio.run("add 0 0 1.4");
    let json = studio.model().to_json();
    let again = Studio::from_model_json("saved.json", &json).unwrap();
    assert_eq!(again.handles().len(), 13);
    let p = [0.1, 0.2, 0.3];
    let (a, b) = (studio.model().interpolant, again.model().interpolant);
    assert!((a.value(&p) - b.value(&p)).abs() < 1e-9);
    let e = Studio::from_model_json("broken.json", "{").err().unwrap();
    assert!(matches!(e, StudioError::Model { .. }));
    assert!(e.to_string().starts_with("broken.json: "), "{e}");
    // A real 2D model: refused for its dimension.
    let constraints = vec![
        rbf_core::Constraint::boundary([1.0, 0.0]),
        rbf_core::Constraint::boundary([0.0, 1.0]),
        rbf_core::Constraint::boundary([-1.0, 0.0]),
        rbf_core::Constraint::interior([0.0, 0.0], 1.0),
    ];
    let settings = rbf_core::FitSettings::default();
    let fit = rbf_core::fit(&constraints, &settings).unwrap();
    let curve = rbf_core::Model {
        constraints,
        settings,
        interpolant: fit.interpolant,
        report: None,
    };
    let e = Studio::from_model_json("curve.json", &curve.to_json())
        .err()
        .unwrap();
    assert!(matches!(e, StudioError::TwoDimensional(_)), "{e}");
    // A model too large to edit in a browser: refused before it is factored. (Its weights are
    // not a fit's; the file reader checks only that its centres are its constraints' points.)
    let big = rbf_core::shapes::sphere(1300);
    let system = rbf_core::System::new(&big, &settings).unwrap();
    let centres = system.points().to_vec();
    let weights = vec![0.0; centres.len()];
    let interpolant =
        rbf_core::Interpolant::new(rbf_core::Kernel::Cubic, centres, weights, 1.0, [0.0; 3])
            .unwrap();
    let model = rbf_core::Model {
        constraints: big,
        settings,
        interpolant,
        report: None,
    };
    let e = Studio::from_model_json("big.json", &model.to_json())
        .err()
        .unwrap();
    assert!(matches!(e, StudioError::TooLarge { rows: 2600, .. }), "{e}");
}

#[test]
fn meshes_open_as_normal_constraints_and_export_in_every_format() {
    let octahedron = "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n\
        f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";
    let studio = Studio::from_mesh("octahedron.obj", octahedron.as_bytes()).unwrap();
    assert_eq!(studio.handles().len(), 12);
    assert_eq!(studio.handles().iter().filter(|h| h.kind == 3).count(), 6);
    for name in ["s.obj", "s.ply", "s.stl"] {
        let bytes = studio.export(name).unwrap();
        let back = rbf_mesh::read_mesh_bytes(name.as_ref(), &bytes).unwrap();
        assert_eq!(
            back.triangles().len(),
            studio.surface().indices.len() / 3,
            "{name}"
        );
    }
    assert!(studio.export("s.xyz").is_err());
    let e = Studio::from_mesh("bad.obj", b"v 0 0 0\nf 1 2 3\n")
        .err()
        .unwrap();
    assert!(e.to_string().contains("bad.obj"), "{e}");
}

#[test]
fn floaters_lie_on_the_surface_and_follow_edits() {
    let mut studio = Studio::new().unwrap();
    assert!(studio.floaters().is_empty());
    studio.set_floaters(true);
    let discs = studio.floaters();
    assert!(discs.len() > 30, "{} floaters", discs.len());
    let f = studio.model().interpolant;
    for (p, n, r) in &discs {
        let g = f.gradient(p);
        let slope = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
        assert!(f.value(p).abs() / slope < 1e-4, "a floater off the surface");
        assert!((n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0).abs() < 1e-9);
        assert!(*r > 0.0);
    }
    assert!(matches!(studio.run("add 0 0 1.6"), Answer::Applied { .. }));
    let f = studio.model().interpolant;
    for (p, _, _) in studio.floaters() {
        let g = f.gradient(&p);
        let slope = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
        assert!(f.value(&p).abs() / slope < 1e-3, "a floater left behind");
    }
    studio.set_floaters(false);
    assert!(studio.floaters().is_empty());
}

#[test]
fn a_drag_undoes_as_one_edit() {
    let mut studio = Studio::new().unwrap();
    let start = studio.model().to_json();
    let mark = studio.begin_gesture();
    for z in [1.0, 1.2, 1.4, 1.6] {
        assert!(matches!(
            studio.run(&format!("move 0 0.6 0.6 {z}")),
            Answer::Applied { .. }
        ));
    }
    studio.end_gesture(mark);
    assert!(matches!(studio.run("undo"), Answer::Applied { .. }));
    assert_eq!(studio.model().to_json(), start);
    assert!(matches!(studio.run("undo"), Answer::Refused(_)));
    assert!(matches!(studio.run("redo"), Answer::Applied { .. }));
    assert_eq!(studio.handles()[0].position, [0.6, 0.6, 1.6]);
}
