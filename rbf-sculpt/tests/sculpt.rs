//! Sculpting: the incremental solver against fresh fits, knot insertion, undo, the torus of
//! Figure 7, floaters.

use proptest::prelude::*;
use rbf_core::{Constraint, FitSettings, InterpolantView, Kernel, fit};
use rbf_sculpt::{
    FloaterSettings, Floaters, IncrementalFit, Row, SculptError, Session, parse_script,
};

/// Points on a jittered 5³ grid in [−1, 1]³ (never closer than 0.2), picked by `picks`.
fn grid_point(k: usize, jitter: [f64; 3]) -> [f64; 3] {
    let c = [k % 5, (k / 5) % 5, k / 25 % 5];
    core::array::from_fn(|d| -1.0 + 0.5 * c[d] as f64 + 0.15 * jitter[d])
}

fn fresh(rows: &[Row<3>]) -> rbf_core::Interpolant<f64, 3> {
    let constraints: Vec<Constraint<3>> = rows
        .iter()
        .map(|r| match r.value {
            v if v > 0.0 => Constraint::interior(r.position, v),
            v if v < 0.0 => Constraint::exterior(r.position, v),
            _ => Constraint::boundary(r.position),
        })
        .collect();
    let settings = FitSettings {
        kernel: Some(Kernel::Cubic),
        ..Default::default()
    };
    fit(&constraints, &settings).unwrap().interpolant
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    /// After any sequence of insertions, deletions and moves, the updated factorization gives
    /// the same interpolant as a fresh fit of the rows that remain.
    #[test]
    fn updates_match_a_fresh_fit(
        cells in proptest::sample::subsequence((0..125).collect::<Vec<usize>>(), 40),
        jitter in proptest::collection::vec(proptest::array::uniform3(-1.0..1.0_f64), 40),
        values in proptest::collection::vec(-1.0..1.0_f64, 40),
        ops in proptest::collection::vec((0..3_u8, 0..1000_usize), 1..30),
    ) {
        let point = |i: usize| grid_point(cells[i], jitter[i]);
        let value = |i: usize| if i.is_multiple_of(3) { 0.0 } else { values[i] };
        let start: Vec<Row<3>> = (0..10).map(|i| Row { position: point(i), value: value(i) }).collect();
        let mut inc = IncrementalFit::new(Kernel::Cubic, &start).unwrap();
        let mut live: Vec<usize> = (0..10).collect(); // row ids
        let mut next = 10;
        for (op, pick) in ops {
            match op {
                0 if next < 40 => {
                    live.push(inc.push(Row { position: point(next), value: value(next) }).unwrap());
                    next += 1;
                }
                1 if live.len() > 6 => {
                    let id = live.remove(pick % live.len());
                    inc.remove(id).unwrap();
                }
                _ if next < 40 => {
                    // Move a row to an unused grid point.
                    let id = live[pick % live.len()];
                    inc.replace(id, Row { position: point(next), value: value(next) }).unwrap();
                    next += 1;
                }
                _ => {}
            }
        }
        let rows: Vec<Row<3>> = live.iter().map(|&id| inc.row(id).unwrap()).collect();
        let expected = fresh(&rows);
        let got = inc.interpolant().unwrap();
        for k in 0..20 {
            let x = grid_point((k * 37) % 125, [0.3, -0.2, 0.1]);
            let (a, b) = (got.value(&x), expected.value(&x));
            prop_assert!((a - b).abs() < 1e-8 * (1.0 + b.abs()), "{a} vs {b} at {x:?}");
        }
        // Interpolation: every remaining row is met.
        for r in &rows {
            prop_assert!((got.value(&r.position) - r.value).abs() < 1e-9);
        }
    }

    /// Knot insertion: a boundary constraint where a ray meets the surface leaves f unchanged.
    #[test]
    fn picking_a_boundary_constraint_leaves_the_surface_unchanged(
        direction in proptest::array::uniform3(-1.0..1.0_f64),
    ) {
        let n = direction.iter().map(|v| v * v).sum::<f64>().sqrt();
        prop_assume!(n > 0.1);
        let mut s = Session::new().unwrap();
        let eye = direction.map(|v| 4.0 * v / n);
        let probes: Vec<[f64; 3]> = (0..10).map(|k| grid_point(k * 12, [0.0; 3])).collect();
        let before: Vec<f64> = probes.iter().map(|p| s.interpolant().value(p)).collect();
        s.pick_boundary(eye, eye.map(|v| -v)).unwrap();
        for (p, b) in probes.iter().zip(&before) {
            let a = s.interpolant().value(p);
            prop_assert!((a - b).abs() < 1e-8 * (1.0 + b.abs()), "{a} vs {b}");
        }
    }
}

#[test]
fn a_dragged_pivot_refactors_once_and_stays_exact() {
    // 60 points on a sphere and its centre: the first row and the extremes are the pivots.
    let mut rows: Vec<Row<3>> = (0..60)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / 60.0;
            let (r, a) = ((1.0 - z * z).sqrt(), i as f64 * 2.399963229728653);
            Row {
                position: [r * a.cos(), r * a.sin(), z],
                value: 0.0,
            }
        })
        .collect();
    rows.push(Row {
        position: [0.0; 3],
        value: 1.0,
    });
    let mut inc = IncrementalFit::new(Kernel::Cubic, &rows).unwrap();
    let dragged = inc.pivots()[1];
    let mut now = rows.clone();
    for step in 1..=10 {
        // Outward, as a drag that keeps it the farthest point.
        let p = rows[dragged]
            .position
            .map(|v| v * (1.0 + 0.05 * step as f64));
        now[dragged] = Row {
            position: p,
            value: 0.0,
        };
        inc.replace(dragged, now[dragged]).unwrap();
        assert!(
            !inc.pivots().contains(&dragged),
            "step {step}: still a pivot"
        );
    }
    let (got, expected) = (inc.interpolant().unwrap(), fresh(&now));
    for k in 0..20 {
        let x = grid_point((k * 37) % 125, [0.3, -0.2, 0.1]);
        let (a, b) = (got.value(&x), expected.value(&x));
        assert!(
            (a - b).abs() < 1e-8 * (1.0 + b.abs()),
            "{a} vs {b} at {x:?}"
        );
    }
}

#[test]
fn undo_returns_the_previous_interpolant_exactly() {
    let mut s = Session::new().unwrap();
    let i = s.add_boundary([0.0, 1.4, 0.0]).unwrap();
    let before = s.interpolant().clone();
    let items = s.items();
    s.move_item(i, [0.3, 1.7, 0.2]).unwrap();
    s.add_normal(i).unwrap();
    assert_ne!(s.interpolant(), &before);
    s.undo().unwrap();
    s.undo().unwrap();
    assert_eq!(s.interpolant(), &before);
    assert_eq!(s.items(), items);
    s.redo().unwrap();
    assert!(s.interpolant().value(&[0.3, 1.7, 0.2]).abs() < 1e-9);
    // Editing after undo clears the redo history.
    s.add_boundary([1.4, 0.0, 0.0]).unwrap();
    assert_eq!(s.redo(), Err(SculptError::History("redo")));
}

#[test]
fn the_torus_script_sculpts_a_genus_one_surface() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/torus.json");
    let edits = parse_script(&std::fs::read_to_string(path).unwrap()).unwrap();
    let mut s = Session::new().unwrap();
    for e in &edits {
        s.apply(e).unwrap();
    }
    let settings = rbf_mesh::PolygonizeSettings {
        resolution: rbf_mesh::Resolution::Cells(96),
        ..Default::default()
    };
    let (mesh, _) = rbf_mesh::polygonize_grid(&s.interpolant().view(), &settings).unwrap();
    let check = mesh.check();
    assert!(check.is_watertight() && check.components == 1, "{check:?}");
    assert_eq!(check.genus, Some(1), "{check:?}");
    // The model's constraints are the session's, and its interpolant passes through them.
    let model = s.model();
    assert_eq!(model.constraints.len(), s.items().iter().flatten().count());
    for c in &model.constraints {
        assert!((model.interpolant.value(&c.position) - c.value).abs() < 1e-9);
    }
}

#[test]
fn bad_edits_are_errors_and_change_nothing() {
    let mut s = Session::new().unwrap();
    let before = s.interpolant().clone();
    assert_eq!(s.delete(99), Err(SculptError::NoSuchItem(99)));
    assert!(matches!(
        s.move_normal(0, [0.0; 3]),
        Err(SculptError::WrongKind { .. })
    ));
    assert_eq!(
        s.add_boundary([f64::NAN, 0.0, 0.0]),
        Err(SculptError::NotFinite)
    );
    // A point on top of another one makes the system singular.
    assert!(matches!(
        s.add_boundary([3.0, 3.0, 3.0]),
        Err(SculptError::Singular(_))
    ));
    assert!(matches!(
        s.pick_boundary([0.0, 9.0, 0.0], [0.0, 1.0, 0.0]),
        Err(SculptError::Missed { .. })
    ));
    assert_eq!(s.interpolant(), &before);
    // Deleting pivots refactors; leaving only the cube's top face (z = 3) is refused: four
    // coplanar points cannot fix a linear polynomial.
    for i in 0..7 {
        s.delete(i).unwrap();
    }
    let kept = s.interpolant().clone();
    assert!(matches!(s.delete(7), Err(SculptError::Singular(_))));
    assert_eq!(s.items().iter().flatten().count(), 5);
    assert_eq!(s.interpolant(), &kept);
}

fn cv(points: &[[f64; 3]]) -> f64 {
    let nearest: Vec<f64> = points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            points
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .map(|(_, q)| (0..3).map(|d| (p[d] - q[d]).powi(2)).sum::<f64>().sqrt())
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    let mean = nearest.iter().sum::<f64>() / nearest.len() as f64;
    let var = nearest.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / nearest.len() as f64;
    var.sqrt() / mean
}

#[test]
fn floaters_spread_evenly_and_keep_their_density_as_the_surface_grows() {
    let centre = [[0.0; 3]];
    let sphere = |r: f64| {
        InterpolantView::new(Kernel::Cubic, &centre, &[-1.0], r * r * r, [0.0; 3]).unwrap()
    };
    let f = sphere(1.0);
    let settings = FloaterSettings {
        spacing: 0.25,
        step: 0.25,
        projections: 4,
    };
    let mut floaters = Floaters::new(&f, &[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], settings);
    floaters.settle(&f, 400);
    let diagonal = 2.0 * 3.0_f64.sqrt();
    for p in floaters.points() {
        let r = p.iter().map(|v| v * v).sum::<f64>().sqrt();
        assert!((r - 1.0).abs() < 1e-4 * diagonal);
    }
    let variation = cv(floaters.points());
    assert!(variation < 0.3, "coefficient of variation {variation}");
    let count = floaters.len();
    // Twice the area: radius √2.
    let g = sphere(2.0_f64.sqrt());
    floaters.settle(&g, 400);
    let ratio = floaters.len() as f64 / count as f64;
    assert!(
        (1.6..2.5).contains(&ratio),
        "{count} → {} floaters",
        floaters.len()
    );
    assert!(cv(floaters.points()) < 0.3);
}
