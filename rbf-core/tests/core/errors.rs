//! Every fit error, from the library: a typed error naming the culprit, never a panic.

use rbf_core::{Constraint, FitError, FitSettings, NormalOffset, RowSource, fit};

fn cube() -> Vec<Constraint<3>> {
    let mut cs: Vec<Constraint<3>> = (0..8)
        .map(|i| {
            let c = |b: usize| if i >> b & 1 == 1 { 1.0 } else { -1.0 };
            Constraint::boundary([c(0), c(1), c(2)])
        })
        .collect();
    cs.push(Constraint::interior([0.0; 3], 1.0));
    cs
}

#[test]
fn too_few_constraints() {
    let cs = [
        Constraint::boundary([0.0, 0.0, 0.0]),
        Constraint::interior([1.0, 0.0, 0.0], 1.0),
    ];
    let e = fit(&cs, &FitSettings::default()).unwrap_err();
    assert_eq!(
        e,
        FitError::TooFewConstraints {
            rows: 2,
            needed: 4,
            dim: 3
        }
    );
    assert!(e.to_string().contains("at least 4"));
}

#[test]
fn nan_and_infinity_name_the_constraint_and_field() {
    let mut cs = cube();
    cs[3].position[1] = f64::NAN;
    let e = fit(&cs, &FitSettings::default()).unwrap_err();
    assert_eq!(
        e,
        FitError::NonFinite {
            constraint: 3,
            field: "position"
        }
    );
    let mut cs = cube();
    cs[8].value = f64::INFINITY;
    assert_eq!(
        fit(&cs, &FitSettings::default()).unwrap_err(),
        FitError::NonFinite {
            constraint: 8,
            field: "value"
        }
    );
    let mut cs = cube();
    cs.push(Constraint::normal([0.0, 0.0, 2.0], [0.0, f64::NAN, 1.0]));
    assert_eq!(
        fit(&cs, &FitSettings::default()).unwrap_err(),
        FitError::NonFinite {
            constraint: 9,
            field: "normal"
        }
    );
    let s = FitSettings {
        lambda: f64::NAN,
        ..Default::default()
    };
    assert!(matches!(
        fit(&cube(), &s).unwrap_err(),
        FitError::InvalidSetting { name: "lambda", .. }
    ));
}

#[test]
fn values_must_match_kinds() {
    let mut cs = cube();
    cs[8] = Constraint::interior([0.0; 3], -1.0);
    let e = fit(&cs, &FitSettings::default()).unwrap_err();
    assert!(
        matches!(
            e,
            FitError::InvalidValue {
                constraint: 8,
                field: "value",
                ..
            }
        ),
        "{e}"
    );
    let mut cs = cube();
    cs.push(Constraint::exterior([5.0; 3], 0.5));
    assert!(matches!(
        fit(&cs, &FitSettings::default()).unwrap_err(),
        FitError::InvalidValue { constraint: 9, .. }
    ));
    let mut cs = cube();
    cs[0].smoothing = -1.0;
    assert!(matches!(
        fit(&cs, &FitSettings::default()).unwrap_err(),
        FitError::InvalidValue {
            constraint: 0,
            field: "smoothing",
            ..
        }
    ));
}

#[test]
fn zero_normal() {
    let mut cs = cube();
    cs.push(Constraint::normal([0.0, 0.0, 2.0], [0.0, 0.0, 0.0]));
    assert_eq!(
        fit(&cs, &FitSettings::default()).unwrap_err(),
        FitError::ZeroNormal { constraint: 9 }
    );
}

#[test]
fn duplicate_points_are_named() {
    let mut cs = cube();
    cs.push(Constraint::boundary([1.0, -1.0, -1.0]));
    let e = fit(&cs, &FitSettings::default()).unwrap_err();
    let FitError::Coincident {
        first,
        second,
        distance,
        ..
    } = e
    else {
        panic!("{e}")
    };
    assert_eq!((first.constraint, second.constraint, distance), (1, 9, 0.0));
    // Nearly coincident: within 1e-9 of the model's size.
    let mut cs = cube();
    cs.push(Constraint::boundary([1.0, -1.0, -1.0 + 1e-12]));
    assert!(matches!(
        fit(&cs, &FitSettings::default()).unwrap_err(),
        FitError::Coincident { .. }
    ));
}

#[test]
fn a_normal_offset_point_landing_on_another_constraint_is_named() {
    let mut cs = cube();
    // The inside point of this normal constraint is exactly at the interior constraint 8.
    cs.push(Constraint::normal([0.0, 0.0, 0.5], [0.0, 0.0, 1.0]).with_offset(0.5));
    let e = fit(&cs, &FitSettings::default()).unwrap_err();
    let FitError::Coincident { first, second, .. } = e else {
        panic!("{e}")
    };
    assert_eq!(
        first,
        RowSource {
            constraint: 8,
            offset_point: false
        }
    );
    assert_eq!(
        second,
        RowSource {
            constraint: 9,
            offset_point: true
        }
    );
    assert!(
        e.to_string()
            .contains("the offset point of normal constraint 9")
    );
}

#[test]
fn coplanar_points_in_3d() {
    let cs: Vec<Constraint<3>> = (0..20)
        .map(|i| {
            let p = [(i % 5) as f64, (i / 5) as f64, 2.0];
            if i == 7 {
                Constraint::interior(p, 1.0)
            } else {
                Constraint::boundary(p)
            }
        })
        .collect();
    let e = fit(&cs, &FitSettings::default()).unwrap_err();
    assert_eq!(e, FitError::AffinelyDependent { rows: 20, rank: 3 });
    assert!(e.to_string().contains("plane"), "{e}");
}

#[test]
fn collinear_points_in_2d() {
    let cs: Vec<Constraint<2>> = (0..6)
        .map(|i| {
            let t = i as f64;
            Constraint::interior([1.0 + t, 2.0 - 0.5 * t], 1.0 + t)
        })
        .collect();
    let e = fit(&cs, &FitSettings::default()).unwrap_err();
    assert_eq!(e, FitError::AffinelyDependent { rows: 6, rank: 2 });
    assert!(e.to_string().contains("line"), "{e}");
}

#[test]
fn all_zero_values_give_no_surface() {
    let cs: Vec<Constraint<3>> = cube().into_iter().take(8).collect();
    assert_eq!(
        fit(&cs, &FitSettings::default()).unwrap_err(),
        FitError::NoNonZeroValue { rows: 8 }
    );
}

#[test]
fn hopelessly_ill_conditioned_systems_are_reported_not_returned() {
    // Two constraints 1e-14 apart with different values, the coincidence check switched off:
    // no interpolant can honour both to working precision.
    let mut cs = cube();
    cs.push(Constraint::interior([0.0, 0.0, 1e-14], 2.0));
    let s = FitSettings {
        min_separation: 0.0,
        ..Default::default()
    };
    let e = fit(&cs, &s).unwrap_err();
    assert!(
        matches!(
            e,
            FitError::IllConditioned { .. } | FitError::Singular { .. }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("condition"), "{e}");
}

#[test]
fn invalid_offsets() {
    let s = FitSettings {
        normal_offset: NormalOffset::Relative(0.0),
        ..Default::default()
    };
    assert!(matches!(
        fit(&cube(), &s).unwrap_err(),
        FitError::InvalidSetting { .. }
    ));
    let mut cs = cube();
    cs.push(Constraint::normal([0.0, 0.0, 2.0], [0.0, 0.0, 1.0]).with_offset(-1.0));
    assert!(matches!(
        fit(&cs, &FitSettings::default()).unwrap_err(),
        FitError::InvalidValue {
            constraint: 9,
            field: "offset",
            ..
        }
    ));
}
