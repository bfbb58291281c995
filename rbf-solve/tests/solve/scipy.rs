//! Cross-check against an independent implementation: scipy's `RBFInterpolator` (fixture made
//! by `tests/fixtures/make_scipy_fixture.py`, committed).

use rbf_core::{Constraint, FitSettings, Kernel};

#[derive(serde::Deserialize)]
struct Fixture {
    cases: Vec<Case>,
}

#[derive(serde::Deserialize)]
struct Case {
    name: String,
    dim: usize,
    kernel: String,
    lambda: f64,
    points: Vec<Vec<f64>>,
    values: Vec<f64>,
    queries: Vec<Vec<f64>>,
    expected: Vec<f64>,
    expected_at_points: Vec<f64>,
}

fn check<const D: usize>(case: &Case) {
    let kernel = match case.kernel.as_str() {
        "cubic" => Kernel::Cubic,
        "thin-plate" => Kernel::ThinPlate,
        other => panic!("unknown kernel {other}"),
    };
    // Value constraints; scipy knows no kinds, only values.
    let cs: Vec<Constraint<D>> = case
        .points
        .iter()
        .zip(&case.values)
        .map(|(p, &v)| {
            let p: [f64; D] = p.as_slice().try_into().unwrap();
            match v {
                v if v > 0.0 => Constraint::interior(p, v),
                v if v < 0.0 => Constraint::exterior(p, v),
                _ => Constraint::boundary(p),
            }
        })
        .collect();
    let settings = FitSettings {
        kernel: Some(kernel),
        lambda: case.lambda,
        ..Default::default()
    };
    let fits = [
        (
            "rbf-solve",
            rbf_solve::fit(&cs, &settings).unwrap().interpolant,
        ),
        (
            "rbf-core dense",
            rbf_core::fit(&cs, &settings).unwrap().interpolant,
        ),
    ];
    let scale = case.expected.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for (solver, f) in &fits {
        let pairs = case
            .queries
            .iter()
            .zip(&case.expected)
            .chain(case.points.iter().zip(&case.expected_at_points));
        for (q, &want) in pairs {
            let q: [f64; D] = q.as_slice().try_into().unwrap();
            let got = f.value(&q);
            assert!(
                (got - want).abs() <= 1e-8 * scale,
                "{} ({solver}) at {q:?}: {got} vs scipy {want}",
                case.name
            );
        }
    }
}

#[test]
fn values_agree_with_scipy_rbf_interpolator() {
    let text = include_str!("../fixtures/scipy_rbf.json");
    let fixture: Fixture = serde_json::from_str(text).unwrap();
    assert_eq!(fixture.cases.len(), 4);
    for case in &fixture.cases {
        match case.dim {
            2 => check::<2>(case),
            3 => check::<3>(case),
            d => panic!("dimension {d}"),
        }
    }
}
