//! Model files: round trip, and clear errors on malformed or inconsistent files.

use rbf_core::{AnyModel, Constraint, FileError, FitSettings, Model, fit};

fn model() -> Model<3> {
    let mut cs: Vec<Constraint<3>> = (0..6)
        .map(|i| {
            let mut p = [0.0; 3];
            p[i / 2] = if i % 2 == 0 { 1.0 } else { -1.0 };
            Constraint::normal(p, p)
        })
        .collect();
    cs.push(Constraint::exterior([4.0, 4.0, 4.0], -2.0).with_smoothing(0.01));
    let settings = FitSettings {
        lambda: 1e-6,
        ..Default::default()
    };
    let f = fit(&cs, &settings).unwrap();
    Model {
        constraints: cs,
        settings,
        interpolant: f.interpolant,
        report: Some(f.report),
    }
}

fn read(text: &str) -> Result<AnyModel, FileError> {
    AnyModel::from_json(text)
}

#[test]
fn a_report_without_a_condition_estimate_round_trips() {
    // The iterative solver estimates no condition number: NaN, written as null.
    let mut m = model();
    let report = m.report.as_mut().unwrap();
    report.condition = f64::NAN;
    report.method = rbf_core::SolveMethod::Iterative;
    report.iterations = 7;
    let json = m.to_json();
    assert!(json.contains("\"condition\": null"), "{json}");
    let AnyModel::Three(back) = read(&json).unwrap() else {
        panic!("not 3D")
    };
    let r = back.report.unwrap();
    assert!(r.condition.is_nan());
    assert_eq!(
        (r.method, r.iterations),
        (rbf_core::SolveMethod::Iterative, 7)
    );
}

#[test]
fn round_trip_is_exact() {
    let m = model();
    let AnyModel::Three(back) = read(&m.to_json()).unwrap() else {
        panic!("not 3D")
    };
    assert_eq!(back.interpolant, m.interpolant);
    assert_eq!(back.constraints, m.constraints);
    assert_eq!(back.settings.lambda, m.settings.lambda);
    assert_eq!(back.report, m.report);
}

#[test]
fn malformed_json_names_line_and_column() {
    let e = read("{\n  \"format\": \"rbf-model\",\n  oops\n}").unwrap_err();
    let FileError::Json { line, .. } = e else {
        panic!("{e}")
    };
    assert_eq!(line, 3);
}

#[test]
fn wrong_format_or_version_is_rejected() {
    let json = model().to_json();
    assert!(matches!(
        read(&json.replace("rbf-model", "other")),
        Err(FileError::Format(_))
    ));
    let e = read(&json.replace("\"version\": 1", "\"version\": 99")).unwrap_err();
    assert!(e.to_string().contains("version"), "{e}");
    assert!(matches!(read("{}"), Err(FileError::Format(_))));
    // A format or version of the wrong type, and a file that is not an object.
    let e = read(&json.replace("\"rbf-model\"", "7")).unwrap_err();
    assert!(matches!(e, FileError::Format(_)), "{e}");
    let e = read(&json.replace("\"version\": 1", "\"version\": \"1\"")).unwrap_err();
    assert!(e.to_string().contains("whole number"), "{e}");
    assert!(matches!(read("[1, 2]"), Err(FileError::Format(_))));
    assert!(matches!(read("\"rbf-model\""), Err(FileError::Json { .. })));
}

#[test]
fn inconsistent_files_are_rejected() {
    let json = model().to_json();
    // A weight too few.
    let mut v: serde_json::Value = serde_json::from_str(&json).unwrap();
    v["weights"].as_array_mut().unwrap().pop();
    let e = read(&v.to_string()).unwrap_err();
    assert!(e.to_string().contains("weights"), "{e}");
    // A centre that is not where its constraint puts it.
    let mut v: serde_json::Value = serde_json::from_str(&json).unwrap();
    v["centres"][2][0] = serde_json::json!(0.123);
    let e = read(&v.to_string()).unwrap_err();
    assert!(e.to_string().contains("centre 2"), "{e}");
    // A non-finite weight (JSON null).
    let mut v: serde_json::Value = serde_json::from_str(&json).unwrap();
    v["weights"][0] = serde_json::Value::Null;
    assert!(read(&v.to_string()).is_err());
    // A 4D model.
    let mut v: serde_json::Value = serde_json::from_str(&json).unwrap();
    v["dim"] = serde_json::json!(4);
    assert!(matches!(read(&v.to_string()), Err(FileError::Dimension(4))));
    // A centre with two coordinates in a 3D model.
    let mut v: serde_json::Value = serde_json::from_str(&json).unwrap();
    v["centres"][0] = serde_json::json!([0.0, 1.0]);
    let e = read(&v.to_string()).unwrap_err();
    assert!(e.to_string().contains("centre 0"), "{e}");
    // Unknown fields are typos, not extensions.
    let mut v: serde_json::Value = serde_json::from_str(&json).unwrap();
    v["weigths"] = serde_json::json!([]);
    assert!(read(&v.to_string()).is_err());
}
