//! The `rbf` binary end to end: results, exit codes and messages.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn rbf(args: &[&str], stdin: Option<&str>) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_rbf"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    if let Some(text) = stdin {
        // The program may exit (on bad input) before it reads its stdin: a closed pipe is fine.
        let written = child.stdin.take().unwrap().write_all(text.as_bytes());
        if let Err(e) = written {
            assert_eq!(e.kind(), std::io::ErrorKind::BrokenPipe, "{e}");
        }
    } else {
        drop(child.stdin.take());
    }
    child.wait_with_output().unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

const TETRAHEDRON: &str = "\
# x y z value: the tetrahedron of Turk & O'Brien 2002, Figure 2, around an interior point
0.57735 0.57735 0.57735 0
0.57735 -0.57735 -0.57735 0
-0.57735 0.57735 -0.57735 0
-0.57735 -0.57735 0.57735 0
0 0 0 1
";

/// Writes `text` to `name` in `dir` and fits it to `dir/m.json` with `extra` options.
fn fit_file(dir: &Path, name: &str, text: &str, extra: &[&str]) -> (PathBuf, Output) {
    let input = write(dir, name, text);
    let model = dir.join("m.json");
    let mut args = vec![
        "fit",
        input.to_str().unwrap(),
        "-o",
        model.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let o = rbf(&args, None);
    (model, o)
}

#[test]
fn fit_then_eval_text() {
    let dir = tempfile::tempdir().unwrap();
    let (model, o) = fit_file(dir.path(), "tet.txt", TETRAHEDRON, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("residual"));
    let o = rbf(
        &["eval", model.to_str().unwrap(), "-", "--gradient"],
        Some("0 0 0\n0.57735 0.57735 0.57735\n3 0 0\n"),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let lines: Vec<Vec<f64>> = String::from_utf8(o.stdout)
        .unwrap()
        .lines()
        .map(|l| l.split_whitespace().map(|t| t.parse().unwrap()).collect())
        .collect();
    assert_eq!(lines.len(), 3);
    assert!(lines.iter().all(|l| l.len() == 4));
    assert!((lines[0][0] - 1.0).abs() < 1e-9, "interior value");
    assert!(lines[1][0].abs() < 1e-9, "on the surface");
    assert!(lines[2][0] < 0.0, "outside");
    assert!(lines[2][1] < 0.0, "f decreases outward");
}

#[test]
fn fit_json_2d_with_every_kind() {
    let dir = tempfile::tempdir().unwrap();
    let input = write(
        dir.path(),
        "c.json",
        r#"{"dim": 2, "lambda": 0, "normal_offset": {"relative": 0.02}, "constraints": [
            {"kind": "boundary", "position": [1, 0]},
            {"kind": "boundary", "position": [-1, 0]},
            {"kind": "normal", "position": [0, 1], "normal": [0, 1]},
            {"kind": "normal", "position": [0, -1], "normal": [0, -1], "offset": 0.05, "value": 2},
            {"kind": "interior", "position": [0, 0], "value": 1},
            {"kind": "exterior", "position": [3, 3], "value": -1, "smoothing": 0.001}
        ]}"#,
    );
    let model = dir.path().join("m.json");
    let o = rbf(
        &[
            "fit",
            input.to_str().unwrap(),
            "-o",
            model.to_str().unwrap(),
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("8 rows, 2D, thin-plate"),
        "{}",
        stderr(&o)
    );
    let o = rbf(&["eval", model.to_str().unwrap(), "-"], Some("1 0\n0 0\n"));
    let values: Vec<f64> = String::from_utf8(o.stdout)
        .unwrap()
        .lines()
        .map(|l| l.parse().unwrap())
        .collect();
    assert!(
        values[0].abs() < 1e-9 && (values[1] - 1.0).abs() < 1e-9,
        "{values:?}"
    );
}

#[test]
fn a_bad_line_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let input = write(dir.path(), "bad.txt", "0 0 0 1\n1 0 0 0\n0 1 zero 0\n");
    let o = rbf(&["fit", input.to_str().unwrap(), "-o", "/dev/null"], None);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(e.contains("bad.txt: line 3") && e.contains("`zero`"), "{e}");
    let input = write(dir.path(), "short.txt", "0 0 0 1\n1 0 0\n");
    let o = rbf(&["fit", input.to_str().unwrap(), "-o", "/dev/null"], None);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("line 2: expected 4 numbers"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn degenerate_inputs_exit_2_and_name_the_culprit() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "coplanar.txt",
            "0 0 0 0\n1 0 0 0\n0 1 0 0\n1 1 0 1\n2 2 0 0\n",
            "plane",
        ),
        (
            "dup.txt",
            "0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 1\n1 0 0 0\n",
            "constraint 1 and constraint 4",
        ),
        ("few.txt", "0 0 0 1\n1 0 0 0\n", "at least 4"),
        (
            "zero.txt",
            "0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n",
            "value 0",
        ),
        ("nan.txt", "0 0 0 1\nNaN 0 0 0\n", "line 2"),
        ("normal.txt", "0 0 0 1\n1 0 0 0 0 0\n", "zero length"),
        ("empty.txt", "# nothing\n", "at least 4"),
    ];
    for (name, text, expected) in cases {
        let input = write(dir.path(), name, text);
        let out = dir.path().join("never.json");
        let o = rbf(
            &["fit", input.to_str().unwrap(), "-o", out.to_str().unwrap()],
            None,
        );
        assert_eq!(o.status.code(), Some(2), "{name}: {}", stderr(&o));
        assert!(stderr(&o).contains(expected), "{name}: {}", stderr(&o));
        assert!(!stderr(&o).contains("panicked"));
        assert!(!out.exists(), "{name}: no model is written");
    }
}

#[test]
fn malformed_json_and_models_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let input = write(
        dir.path(),
        "c.json",
        "{\"constraints\": [\n {\"kind\": \"boundary\", \"position\": [1, 2]},\n {\"kind\": \"blob\"}]}",
    );
    let o = rbf(&["fit", input.to_str().unwrap(), "-o", "/dev/null"], None);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("line 3"), "{}", stderr(&o));
    let model = write(
        dir.path(),
        "m.json",
        "{\"format\": \"rbf-model\", \"version\": 7}",
    );
    let o = rbf(&["eval", model.to_str().unwrap(), "-"], Some("0 0 0\n"));
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("version"), "{}", stderr(&o));
    let o = rbf(&["eval", "/nonexistent/model.json", "-"], Some(""));
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("/nonexistent/model.json"));
}

#[test]
fn eval_refuses_an_accuracy_that_is_not_positive_and_finite() {
    let dir = tempfile::tempdir().unwrap();
    let (model, o) = fit_file(dir.path(), "tet.txt", TETRAHEDRON, &["-q"]);
    assert!(o.status.success());
    let m = model.to_str().unwrap();
    for bad in ["0", "-1e-6", "NaN", "inf"] {
        let option = format!("--accuracy={bad}");
        let o = rbf(&["eval", m, "-", &option], Some("0 0 0\n"));
        assert_eq!(o.status.code(), Some(1), "--accuracy {bad}");
        assert!(stderr(&o).contains("--accuracy"), "{}", stderr(&o));
        assert!(o.stdout.is_empty(), "nothing written for --accuracy {bad}");
    }
    // --exact and a positive accuracy give the direct sums' values on a small model.
    let exact = rbf(&["eval", m, "-", "--exact"], Some("0 0 0\n"));
    let loose = rbf(&["eval", m, "-", "--accuracy", "1e-3"], Some("0 0 0\n"));
    assert!(exact.status.success() && loose.status.success());
    assert_eq!(exact.stdout, loose.stdout);
    let both = rbf(
        &["eval", m, "-", "--exact", "--accuracy", "1e-3"],
        Some("0 0 0\n"),
    );
    assert_eq!(
        both.status.code(),
        Some(1),
        "--exact conflicts with --accuracy"
    );
}

#[test]
fn fit_refuses_an_accuracy_it_cannot_certify() {
    let dir = tempfile::tempdir().unwrap();
    for bad in ["0", "-1e-6", "NaN", "inf", "1e-20"] {
        let option = format!("--max-residual={bad}");
        let (model, o) = fit_file(dir.path(), "tet.txt", TETRAHEDRON, &[&option]);
        assert_eq!(o.status.code(), Some(1), "--max-residual {bad}");
        assert!(
            stderr(&o).contains("--max-residual must be a finite fraction"),
            "{}",
            stderr(&o)
        );
        assert!(!model.exists(), "nothing written for --max-residual {bad}");
    }
}

#[test]
fn eval_checks_the_points_dimension() {
    let dir = tempfile::tempdir().unwrap();
    let (model, o) = fit_file(dir.path(), "tet.txt", TETRAHEDRON, &["-q"]);
    assert!(o.status.success());
    assert!(o.stderr.is_empty(), "--quiet prints nothing");
    let o = rbf(&["eval", model.to_str().unwrap(), "-"], Some("0 0\n"));
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("line 1: expected 3 coordinates"),
        "{}",
        stderr(&o)
    );
}

/// A version-1 `.npy` file: `descr` numbers of `shape` (`fortran` order or C), raw `body`.
fn npy_file(descr: &str, fortran: bool, shape: &str, body: &[u8]) -> Vec<u8> {
    let order = if fortran { "True" } else { "False" };
    let header = format!("{{'descr': '{descr}', 'fortran_order': {order}, 'shape': {shape}, }}");
    let padded = format!("{header:<117}\n");
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend_from_slice(&(padded.len() as u16).to_le_bytes());
    bytes.extend_from_slice(padded.as_bytes());
    bytes.extend_from_slice(body);
    bytes
}

/// The header's shape and the float64 numbers of an `.npy` file that rbf wrote.
fn read_npy_f64(bytes: &[u8]) -> (String, Vec<f64>) {
    let len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let header = std::str::from_utf8(&bytes[10..10 + len]).unwrap();
    assert!(header.contains("'descr': '<f8'"), "{header}");
    assert!(header.contains("'fortran_order': False"), "{header}");
    let shape = header.split("'shape': ").nth(1).unwrap();
    let shape = shape[..=shape.find(')').unwrap()].to_string();
    let data = bytes[10 + len..]
        .chunks_exact(8)
        .map(|b| f64::from_le_bytes(b.try_into().unwrap()))
        .collect();
    (shape, data)
}

#[test]
fn eval_reads_and_writes_npy() {
    let dir = tempfile::tempdir().unwrap();
    let (model, o) = fit_file(dir.path(), "tet.txt", TETRAHEDRON, &["-q"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let points = [
        [0.0, 0.0, 0.0],
        [0.57735, 0.57735, 0.57735],
        [3.0, 0.5, -0.25],
    ];
    // float32, Fortran order: the column of x first.
    let mut body = Vec::new();
    for d in 0..3 {
        for p in &points {
            body.extend_from_slice(&(p[d] as f32).to_le_bytes());
        }
    }
    let input = dir.path().join("p.npy");
    std::fs::write(&input, npy_file("<f4", true, "(3, 3)", &body)).unwrap();
    let text: String = points
        .iter()
        .map(|p| {
            let x = p.map(|v| f64::from(v as f32));
            format!("{:?} {:?} {:?}\n", x[0], x[1], x[2])
        })
        .collect();
    let expected = rbf(
        &["eval", model.to_str().unwrap(), "-", "--gradient"],
        Some(&text),
    );
    assert!(expected.status.success(), "{}", stderr(&expected));
    let expected: Vec<f64> = String::from_utf8(expected.stdout)
        .unwrap()
        .split_whitespace()
        .map(|t| t.parse().unwrap())
        .collect();

    let out = dir.path().join("v.npy");
    let (m, i, o) = (
        model.to_str().unwrap(),
        input.to_str().unwrap(),
        out.to_str().unwrap(),
    );
    let run = rbf(&["eval", m, i, "-o", o], None);
    assert!(run.status.success(), "{}", stderr(&run));
    let (shape, values) = read_npy_f64(&std::fs::read(&out).unwrap());
    assert_eq!(shape, "(3,)");
    for (k, v) in values.iter().enumerate() {
        assert_eq!(*v, expected[4 * k], "value {k}");
    }
    assert!((values[0] - 1.0).abs() < 1e-6 && values[2] < 0.0);

    let run = rbf(&["eval", m, i, "-o", o, "--gradient"], None);
    assert!(run.status.success(), "{}", stderr(&run));
    let (shape, rows) = read_npy_f64(&std::fs::read(&out).unwrap());
    assert_eq!(shape, "(3, 4)");
    assert_eq!(rows, expected);

    // Text out when the name does not end in .npy.
    let txt = dir.path().join("v.txt");
    let run = rbf(&["eval", m, i, "-o", txt.to_str().unwrap()], None);
    assert!(run.status.success(), "{}", stderr(&run));
    let written: Vec<f64> = std::fs::read_to_string(&txt)
        .unwrap()
        .split_whitespace()
        .map(|t| t.parse().unwrap())
        .collect();
    assert_eq!(written, values);

    // The wrong number of columns, NaN and a cut file are refused, naming the file.
    let bad = dir.path().join("bad.npy");
    let b = bad.to_str().unwrap();
    let two: Vec<u8> = [1.0f64, 2.0].iter().flat_map(|v| v.to_le_bytes()).collect();
    std::fs::write(&bad, npy_file("<f8", false, "(1, 2)", &two)).unwrap();
    let run = rbf(&["eval", m, b], None);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        stderr(&run).contains("bad.npy: an array of shape (1, 2); the model is 3D"),
        "{}",
        stderr(&run)
    );
    let nan: Vec<u8> = [0.0f64, 0.0, 0.0, 1.0, f64::NAN, 0.0]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    std::fs::write(&bad, npy_file("<f8", false, "(2, 3)", &nan)).unwrap();
    let run = rbf(&["eval", m, b], None);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        stderr(&run).contains("point 1 has a coordinate that is not a finite number"),
        "{}",
        stderr(&run)
    );
    std::fs::write(&bad, npy_file("<f8", false, "(2, 3)", &nan[..20])).unwrap();
    let run = rbf(&["eval", m, b], None);
    assert_eq!(run.status.code(), Some(2));
    assert!(stderr(&run).contains("bad.npy"), "{}", stderr(&run));
}

#[test]
fn usage_errors_exit_1_and_help_teaches() {
    let o = rbf(&["fit"], None);
    assert_eq!(o.status.code(), Some(1));
    let o = rbf(
        &["fit", "x.txt", "-o", "m.json", "--kernel", "gaussian"],
        None,
    );
    assert_eq!(o.status.code(), Some(1));
    let o = rbf(&["fit", "--help"], None);
    assert_eq!(o.status.code(), Some(0));
    let help = String::from_utf8(o.stdout).unwrap();
    assert!(
        help.contains("Examples:") && help.contains("x y z nx ny nz"),
        "{help}"
    );
}

#[test]
fn lambda_and_kernel_options_reach_the_model() {
    let dir = tempfile::tempdir().unwrap();
    let (model, o) = fit_file(
        dir.path(),
        "tet.txt",
        TETRAHEDRON,
        &["--lambda", "0.01", "--kernel", "linear"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&model).unwrap();
    assert!(
        text.contains("\"kernel\": \"linear\"") && text.contains("\"lambda\": 0.01"),
        "{text}"
    );
    // Smoothed: the interior value is no longer met exactly.
    let o = rbf(&["eval", model.to_str().unwrap(), "-"], Some("0 0 0\n"));
    let v: f64 = String::from_utf8(o.stdout).unwrap().trim().parse().unwrap();
    assert!(v > 0.0 && (v - 1.0).abs() > 1e-6, "{v}");
}

#[test]
fn a_model_is_solved_again_with_a_new_lambda() {
    let dir = tempfile::tempdir().unwrap();
    let (exact, o) = fit_file(dir.path(), "tet.txt", TETRAHEDRON, &["--kernel", "linear"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let smooth = dir.path().join("smooth.json");
    let o = rbf(
        &[
            "fit",
            exact.to_str().unwrap(),
            "--lambda",
            "0.05",
            "-o",
            smooth.to_str().unwrap(),
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&smooth).unwrap();
    // The model's own settings carry over (its kernel); λ is the new one.
    assert!(
        text.contains("\"kernel\": \"linear\"") && text.contains("\"lambda\": 0.05"),
        "{text}"
    );
    let value = |m: &Path| -> f64 {
        let o = rbf(&["eval", m.to_str().unwrap(), "-"], Some("0 0 0\n"));
        String::from_utf8(o.stdout).unwrap().trim().parse().unwrap()
    };
    assert!((value(&exact) - 1.0).abs() < 1e-9);
    assert!((value(&smooth) - 1.0).abs() > 1e-4);
    // A model re-solved with its own settings is the same model.
    let again = dir.path().join("again.json");
    let o = rbf(
        &[
            "fit",
            exact.to_str().unwrap(),
            "-o",
            again.to_str().unwrap(),
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!((value(&again) - value(&exact)).abs() < 1e-12);
}

#[test]
fn demo_runs_and_writes_models() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("demo");
    let o = rbf(&["demo", "-o", out.to_str().unwrap()], None);
    assert!(o.status.success(), "{}", stderr(&o));
    let stdout = String::from_utf8(o.stdout).unwrap();
    for name in ["figure2-blob", "sculpt-start", "torus-2000"] {
        assert!(out.join(format!("{name}.json")).exists(), "{name}");
        assert!(out.join(format!("{name}.obj")).exists(), "{name}");
    }
    assert!(stdout.contains("watertight, genus 1"), "{stdout}");
    // The main job: the built-in mesh converted, polygonized and rendered; every file it
    // names exists and is what it claims.
    for file in ["spot.json", "spot-implicit.obj", "spot.png"] {
        assert!(stdout.contains(file), "{stdout}");
    }
    let model = std::fs::read_to_string(out.join("spot.json")).unwrap();
    assert!(model.contains("\"format\": \"rbf-model\""));
    let png = std::fs::read(out.join("spot.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let o = rbf(
        &["check", out.join("spot-implicit.obj").to_str().unwrap()],
        None,
    );
    assert!(
        String::from_utf8(o.stdout)
            .unwrap()
            .contains("watertight: yes")
    );
    let errors = stdout.lines().find(|l| l.contains("max error")).unwrap();
    assert!(
        errors.contains("max error 1.00") || errors.contains("max error 1.41"),
        "{errors}"
    );
    // The surfaces themselves: within two voxels everywhere, a third of one on average.
    let distance = stdout.lines().find(|l| l.contains("Hausdorff")).unwrap();
    let number_after = |word: &str| -> f64 {
        let rest = &distance[distance.find(word).unwrap() + word.len()..];
        rest.split_whitespace().next().unwrap().parse().unwrap()
    };
    assert!(number_after("RMS ") < 0.34, "{distance}");
    assert!(number_after("Hausdorff ") < 2.0, "{distance}");
}

#[test]
fn numerical_failures_exit_3() {
    let dir = tempfile::tempdir().unwrap();
    // Two interior points 1e-14 apart with different values, the coincidence check disabled.
    let input = write(
        dir.path(),
        "near.txt",
        &format!("{TETRAHEDRON}0 0 1e-14 2\n"),
    );
    let o = rbf(
        &[
            "fit",
            input.to_str().unwrap(),
            "-o",
            "/dev/null",
            "--min-separation",
            "0",
        ],
        None,
    );
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(stderr(&o).contains("condition"), "{}", stderr(&o));
}

#[test]
fn a_system_too_large_for_memory_exits_3_with_its_size() {
    // 200 000 value constraints: a dense system of 320 GB, refused before any allocation.
    // (Without --method dense, the iterative solver would take them.)
    let dir = tempfile::tempdir().unwrap();
    let mut text = String::with_capacity(200_000 * 40);
    for i in 0..200_000_u64 {
        let (x, y, z) = (i % 100, (i / 100) % 100, i / 10_000);
        text.push_str(&format!("{x} {y} {z} {}\n", if i == 0 { 1 } else { 0 }));
    }
    let input = write(dir.path(), "huge.txt", &text);
    let o = rbf(
        &[
            "fit",
            input.to_str().unwrap(),
            "-o",
            "/dev/null",
            "--method",
            "dense",
        ],
        None,
    );
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains("200000 rows needs") && e.contains("MiB"), "{e}");
}

#[test]
fn check_reports_a_mesh() {
    let torus = concat!(env!("CARGO_MANIFEST_DIR"), "/../data/meshes/torus.obj");
    let o = rbf(&["check", torus], None);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(
        text.contains("genus 1") && text.contains("watertight: yes"),
        "{text}"
    );
    let o = rbf(&["check", torus, "--json"], None);
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(
        text.contains("\"genus\":1") && text.contains("\"watertight\":true"),
        "{text}"
    );
    let dir = tempfile::tempdir().unwrap();
    let bad = write(dir.path(), "bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
    let o = rbf(&["check", bad.to_str().unwrap()], None);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("bad.obj: line 3"), "{}", stderr(&o));
}

#[test]
fn mesh_writes_a_watertight_surface_in_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let (model, o) = fit_file(dir.path(), "tet.txt", TETRAHEDRON, &["-q"]);
    assert!(o.status.success());
    for (ext, method) in [
        ("obj", "continuation"),
        ("ply", "grid"),
        ("stl", "marching-cubes"),
    ] {
        let out = dir.path().join(format!("blob.{ext}"));
        let o = rbf(
            &[
                "mesh",
                model.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
                "--resolution",
                "24",
                "--method",
                method,
            ],
            None,
        );
        assert!(o.status.success(), "{ext}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("watertight, genus 0, 1 component"),
            "{ext}: {}",
            stderr(&o)
        );
        let o = rbf(&["check", out.to_str().unwrap()], None);
        let text = String::from_utf8(o.stdout).unwrap();
        assert!(
            text.contains("watertight: yes") && text.contains("outward"),
            "{ext}: {text}"
        );
    }
    let o = rbf(
        &[
            "mesh",
            model.to_str().unwrap(),
            "-o",
            "x.obj",
            "--cell-size=-1",
        ],
        None,
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn voxelize_writes_npy_and_its_metadata() {
    let dir = tempfile::tempdir().unwrap();
    let torus = concat!(env!("CARGO_MANIFEST_DIR"), "/../data/meshes/torus.obj");
    let out = dir.path().join("t.npy");
    let o = rbf(
        &[
            "voxelize",
            torus,
            "--resolution",
            "20",
            "-o",
            out.to_str().unwrap(),
            "--signed-distance",
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let bytes = std::fs::read(&out).unwrap();
    assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00");
    let header_len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let header = std::str::from_utf8(&bytes[10..10 + header_len]).unwrap();
    assert!(
        header.contains("'<f4'") && header.contains("'shape': ("),
        "{header}"
    );
    let meta = std::fs::read_to_string(dir.path().join("t.json")).unwrap();
    assert!(
        meta.contains("\"voxel_size\"") && meta.contains("\"origin\"") && meta.contains("signed"),
        "{meta}"
    );
    // Shape in the header matches the data.
    let shape: Vec<usize> = header
        .split("'shape': (")
        .nth(1)
        .unwrap()
        .split(')')
        .next()
        .unwrap()
        .split(',')
        .filter_map(|t| t.trim().parse().ok())
        .collect();
    assert_eq!(
        bytes.len() - 10 - header_len,
        4 * shape.iter().product::<usize>()
    );
}

#[test]
fn convert_then_mesh_keeps_the_genus() {
    let dir = tempfile::tempdir().unwrap();
    let torus = concat!(env!("CARGO_MANIFEST_DIR"), "/../data/meshes/torus.obj");
    let model = dir.path().join("torus.json");
    let o = rbf(
        &[
            "convert",
            torus,
            "-o",
            model.to_str().unwrap(),
            "--method",
            "normals",
            "--max-constraints",
            "800",
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("of 2304 vertices used (thinned evenly)"),
        "{}",
        stderr(&o)
    );
    let out = dir.path().join("smooth.ply");
    let o = rbf(
        &[
            "mesh",
            model.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--resolution",
            "48",
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("watertight, genus 1, 1 component"),
        "{}",
        stderr(&o)
    );
    // Vertices chosen greedily to a tolerance; the model reads back.
    let o = rbf(
        &[
            "convert",
            torus,
            "-o",
            model.to_str().unwrap(),
            "--method",
            "normals",
            "--tolerance",
            "1e-3",
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("chosen greedily"), "{}", stderr(&o));
    let o = rbf(&["info", model.to_str().unwrap()], None);
    assert!(o.status.success(), "{}", stderr(&o));
    let bad = write(
        dir.path(),
        "flat.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n",
    );
    let o = rbf(&["convert", bad.to_str().unwrap(), "-o", "/dev/null"], None);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn iterative_convert_reports_every_iteration() {
    let dir = tempfile::tempdir().unwrap();
    let knot = concat!(env!("CARGO_MANIFEST_DIR"), "/../data/meshes/knot.obj");
    let model = dir.path().join("knot.json");
    let report = dir.path().join("report.json");
    let o = rbf(
        &[
            "convert",
            knot,
            "-o",
            model.to_str().unwrap(),
            "--resolution",
            "48",
            "--report",
            report.to_str().unwrap(),
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("max error"), "{}", stderr(&o));
    // The knot is closed, of genus 1: the summary and the report say it was kept.
    assert!(
        stderr(&o).contains("topology kept: genus 1, 1 component(s)"),
        "{}",
        stderr(&o)
    );
    let text = std::fs::read_to_string(&report).unwrap();
    assert!(
        text.contains("\"iterations\"")
            && text.contains("\"max_error_voxels\"")
            && text.contains("\"fit_seconds\""),
        "{text}"
    );
    let parsed: serde_json::Value = serde_json::from_str(&text).unwrap();
    let t = &parsed["topology"];
    assert_eq!(
        (
            &t["mesh_genus"],
            &t["genus"],
            &t["components"],
            &t["agrees"]
        ),
        (&1.into(), &1.into(), &1.into(), &true.into()),
        "{t}"
    );
    let out = dir.path().join("knot.obj");
    let o = rbf(
        &[
            "mesh",
            model.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--method",
            "grid",
            "--resolution",
            "64",
        ],
        None,
    );
    assert!(
        stderr(&o).contains("genus 1, 1 component"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn render_and_plot_write_pngs() {
    let dir = tempfile::tempdir().unwrap();
    let (model, o) = fit_file(dir.path(), "tet.txt", TETRAHEDRON, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let png = dir.path().join("tet.png");
    let m = model.to_str().unwrap();
    let o = rbf(
        &[
            "render",
            m,
            "-o",
            png.to_str().unwrap(),
            "--width",
            "48",
            "--height",
            "32",
            "--shadows",
            "--reflections",
            "1",
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    // Two models as one solid, and a mesh.
    let o = rbf(
        &[
            "render",
            m,
            m,
            "--subtract",
            "-o",
            png.to_str().unwrap(),
            "--width",
            "16",
            "--height",
            "16",
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let mesh = dir.path().join("tet.obj");
    let o = rbf(
        &[
            "mesh",
            m,
            "-o",
            mesh.to_str().unwrap(),
            "--resolution",
            "16",
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let o = rbf(
        &[
            "render",
            mesh.to_str().unwrap(),
            "-o",
            png.to_str().unwrap(),
            "--smooth",
            "--width",
            "16",
            "--height",
            "16",
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    // A 3D model is not plotted, a mesh is not mixed with models, a bad point is a usage error.
    let o = rbf(&["plot", m, "-o", png.to_str().unwrap()], None);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("rbf render"), "{}", stderr(&o));
    let o = rbf(
        &[
            "render",
            m,
            mesh.to_str().unwrap(),
            "-o",
            png.to_str().unwrap(),
        ],
        None,
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let o = rbf(
        &["render", m, "-o", png.to_str().unwrap(), "--eye", "1,2"],
        None,
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    // A 2D model plots.
    let curve = write(dir.path(), "c.txt", "1 0 0\n0 1 0\n-1 0 0\n0 -1 0\n0 0 1\n");
    let c2 = dir.path().join("c.json");
    let o = rbf(
        &[
            "fit",
            curve.to_str().unwrap(),
            "--dim",
            "2",
            "-o",
            c2.to_str().unwrap(),
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let o = rbf(
        &[
            "plot",
            c2.to_str().unwrap(),
            "-o",
            png.to_str().unwrap(),
            "--colour-map",
            "--width",
            "64",
            "--height",
            "64",
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn blend_reports_what_each_model_kept() {
    let dir = tempfile::tempdir().unwrap();
    let sphere = |name: &str, cx: f64| {
        let text: String = [
            [1., 0., 0.],
            [-1., 0., 0.],
            [0., 1., 0.],
            [0., -1., 0.],
            [0., 0., 1.],
            [0., 0., -1.],
        ]
        .iter()
        .map(|d: &[f64; 3]| {
            format!(
                "{} {} {} {} {} {}\n",
                cx + d[0],
                d[1],
                d[2],
                d[0],
                d[1],
                d[2]
            )
        })
        .collect();
        let input = write(dir.path(), &format!("{name}.txt"), &text);
        let out = dir.path().join(format!("{name}.json"));
        let o = rbf(
            &["fit", input.to_str().unwrap(), "-o", out.to_str().unwrap()],
            None,
        );
        assert!(o.status.success(), "{}", stderr(&o));
        out
    };
    let (a, b) = (sphere("a", 0.0), sphere("b", 1.5));
    let out = dir.path().join("ab.json");
    let o = rbf(
        &[
            "blend",
            a.to_str().unwrap(),
            b.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("kept 5 of 6"), "{}", stderr(&o));
    let o = rbf(&["eval", out.to_str().unwrap(), "-"], Some("0.75 0 0\n"));
    let v: f64 = String::from_utf8(o.stdout).unwrap().trim().parse().unwrap();
    assert!(v > 0.0);
    // A 2D model with a 3D one is a usage error; one model alone is too.
    let curve = write(dir.path(), "c.txt", "1 0 0\n0 1 0\n-1 0 0\n0 -1 0\n0 0 1\n");
    let c2 = dir.path().join("c.json");
    let o = rbf(
        &[
            "fit",
            curve.to_str().unwrap(),
            "--dim",
            "2",
            "-o",
            c2.to_str().unwrap(),
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let o = rbf(
        &[
            "blend",
            a.to_str().unwrap(),
            c2.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ],
        None,
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let o = rbf(
        &["blend", a.to_str().unwrap(), "-o", out.to_str().unwrap()],
        None,
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
}

#[test]
fn sculpt_replays_the_torus_script_and_floaters_sample_it() {
    let dir = tempfile::tempdir().unwrap();
    let script = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../rbf-sculpt/scripts/torus.json"
    );
    // One edit per line between the brackets.
    let edits = std::fs::read_to_string(script).unwrap().lines().count() - 2;
    let model = dir.path().join("torus.json");
    let frames = dir.path().join("frames");
    let o = rbf(
        &[
            "sculpt",
            script,
            "-o",
            model.to_str().unwrap(),
            "--frames",
            frames.to_str().unwrap(),
            "--frame-size",
            "24",
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read_dir(&frames).unwrap().count(), edits);
    let mesh = dir.path().join("torus.obj");
    let o = rbf(
        &[
            "mesh",
            model.to_str().unwrap(),
            "-o",
            mesh.to_str().unwrap(),
            "--method",
            "grid",
            "--resolution",
            "64",
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("genus 1, 1 component"),
        "{}",
        stderr(&o)
    );
    let points = dir.path().join("torus.xyz");
    let o = rbf(
        &[
            "floaters",
            model.to_str().unwrap(),
            "-n",
            "200",
            "-o",
            points.to_str().unwrap(),
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&points).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert!((140..=260).contains(&lines.len()), "{}", lines.len());
    assert!(lines.iter().all(|l| l.split_whitespace().count() == 6));
    // A script that names a missing item fails on that edit, with exit code 2.
    let bad = write(
        dir.path(),
        "bad.json",
        r#"[{"add_boundary": {"position": [0, 1.5, 0]}}, {"delete": {"item": 99}}]"#,
    );
    let o = rbf(
        &[
            "sculpt",
            bad.to_str().unwrap(),
            "-o",
            model.to_str().unwrap(),
        ],
        None,
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("edit 2") && stderr(&o).contains("no item 99"),
        "{}",
        stderr(&o)
    );
    let bad = write(
        dir.path(),
        "bad2.json",
        r#"[{"add_boundary": {"where": [0, 1.5, 0]}}]"#,
    );
    let o = rbf(
        &[
            "sculpt",
            bad.to_str().unwrap(),
            "-o",
            model.to_str().unwrap(),
        ],
        None,
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn info_export_and_completions() {
    let dir = tempfile::tempdir().unwrap();
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/embedded");
    let model = format!("{root}/model.json");
    // The committed export is what `rbf export` writes today.
    let out = dir.path().join("model.rs");
    let o = rbf(
        &[
            "export",
            &model,
            "--format",
            "rust",
            "-o",
            out.to_str().unwrap(),
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let committed = std::fs::read_to_string(format!("{root}/src/model.rs")).unwrap();
    assert_eq!(
        std::fs::read_to_string(&out).unwrap(),
        committed,
        "re-run rbf export for examples/embedded"
    );
    let o = rbf(
        &[
            "export",
            &model,
            "--precision",
            "f32",
            "-o",
            out.to_str().unwrap(),
        ],
        None,
    );
    assert!(o.status.success());
    assert!(
        std::fs::read_to_string(&out)
            .unwrap()
            .contains("InterpolantView<'static, f32, 3>")
    );
    // Info, for people and as JSON.
    let o = rbf(&["info", &model], None);
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(
        text.contains("3D model, kernel cubic") && text.contains("4 boundary, 1 interior"),
        "{text}"
    );
    let o = rbf(&["info", &model, "--json"], None);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["constraints"]["boundary"], 4);
    assert_eq!(v["dimension"], 3);
    let o = rbf(&["info", "/nonexistent.json"], None);
    assert_eq!(o.status.code(), Some(2));
    // Completions name the subcommands.
    for shell in ["bash", "zsh", "fish"] {
        let o = rbf(&["completions", shell], None);
        assert!(o.status.success());
        let script = String::from_utf8(o.stdout).unwrap();
        assert!(
            script.contains("sculpt") && script.contains("render"),
            "{shell}"
        );
    }
}

#[test]
fn the_gallery_reproduces_the_papers_figures_at_reduced_size() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("gallery");
    let o = rbf(
        &["gallery", "-o", out.to_str().unwrap(), "--size", "40", "-q"],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("gallery.json")).unwrap()).unwrap();
    let figures = summary["figures"].as_array().unwrap();
    let fig = |name: &str| &figures.iter().find(|f| f["figure"] == name).unwrap()["facts"];
    for f in figures {
        let name = f["figure"].as_str().unwrap();
        assert!(out.join(format!("{name}.png")).exists(), "{name}");
    }
    assert_eq!(figures.len(), 10);
    let closed = |v: &serde_json::Value| v["watertight"] == true && v["components"] == 1;
    // The tetrahedron's surface is closed; the branching shape is one piece.
    assert!(closed(&fig("fig2")["left"]) && fig("fig2")["left"]["genus"] == 0);
    assert!(closed(&fig("fig2")["right"]));
    // 2D curves pass through their boundary constraints.
    for name in ["fig1", "fig4", "fig5"] {
        assert!(
            fig(name)["boundary_residual"].as_f64().unwrap() < 1e-9,
            "{name}"
        );
    }
    assert_eq!(fig("fig4")["inside_between_the_two"], true);
    // The sculpted torus has genus 1; the blended tori are one watertight surface.
    assert!(closed(&fig("fig7")["right"]) && fig("fig7")["right"]["genus"] == 1);
    assert!(closed(&fig("fig9")["blend"]));
    assert!(closed(&fig("fig3-fig6")["surface"]));
    // Yngve & Turk's 2D refinement: errors fall from the first step to the last.
    let steps = fig("yngve-fig3")["steps"].as_array().unwrap();
    let (first, last) = (&steps[0], &steps[steps.len() - 1]);
    assert!(last["max"].as_f64().unwrap() < first["max"].as_f64().unwrap());
    assert!(last["rms"].as_f64().unwrap() < 0.5 * first["rms"].as_f64().unwrap());
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert_eq!(html.matches("<figure>").count(), 10);
}

#[test]
fn verbose_shows_every_iteration_and_conflicts_with_quiet() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = concat!(env!("CARGO_MANIFEST_DIR"), "/../data/meshes/torus.obj");
    let out = dir.path().join("t.json");
    let o = rbf(
        &[
            "convert",
            mesh,
            "-o",
            out.to_str().unwrap(),
            "--resolution",
            "40",
            "-v",
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("iteration  1:") && stderr(&o).contains("evaluate"),
        "{}",
        stderr(&o)
    );
    let o = rbf(&["-q", "-v", "info", out.to_str().unwrap()], None);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
}

#[test]
fn compare_measures_a_sphere_against_a_cube_both_ways() {
    let dir = tempfile::tempdir().unwrap();
    // A unit sphere from 200 oriented points spread over it.
    let points: String = rbf_core::shapes::fibonacci_sphere(200)
        .into_iter()
        .map(|p| format!("{} {} {} {} {} {}\n", p[0], p[1], p[2], p[0], p[1], p[2]))
        .collect();
    let (model, o) = fit_file(dir.path(), "sphere.txt", &points, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let cube = write(
        dir.path(),
        "cube.obj",
        "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n\
         f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n",
    );
    let o = rbf(
        &[
            "compare",
            model.to_str().unwrap(),
            cube.to_str().unwrap(),
            "--json",
            "--resolution",
            "64",
            "--voxels",
            "2",
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let r: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    // The cube's corners are √3 − 1 from the sphere; the sphere's points on the cube's
    // diagonals are 1 − 1/√3 from the cube; the sphere touches the face centres.
    let m2s = r["mesh_to_surface"]["max"].as_f64().unwrap();
    let s2m = r["surface_to_mesh"]["max"].as_f64().unwrap();
    assert!((0.69..0.735).contains(&m2s), "{r}");
    assert!((0.40..0.425).contains(&s2m), "{r}");
    assert_eq!(r["hausdorff"].as_f64().unwrap(), m2s);
    // One voxel of a 2-voxel grid over a cube of side 2 is 1.
    assert_eq!(r["mesh_to_surface"]["voxels"]["max"].as_f64().unwrap(), m2s);
    let o = rbf(
        &["compare", model.to_str().unwrap(), model.to_str().unwrap()],
        None,
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let (curve, o) = fit_file(
        dir.path(),
        "square.txt",
        "1 0 0\n0 1 0\n-1 0 0\n0 -1 0\n0 0 1\n",
        &["--dim", "2"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let curve = curve.to_str().unwrap();
    for args in [
        ["compare", curve, cube.to_str().unwrap()],
        ["mesh", curve, "-o=/dev/null"],
    ] {
        let o = rbf(&args, None);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        assert!(stderr(&o).contains("is a 2D model"), "{}", stderr(&o));
    }
    let o = rbf(
        &[
            "compare",
            model.to_str().unwrap(),
            cube.to_str().unwrap(),
            "--samples",
            "0",
        ],
        None,
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
}

#[test]
fn large_fits_go_to_the_iterative_solver_which_says_when_it_stops_short() {
    let dir = tempfile::tempdir().unwrap();
    // 3000 oriented points: 6000 rows, above the dense limit of --method auto.
    let points: String = rbf_core::shapes::fibonacci_sphere(3000)
        .into_iter()
        .map(|p| format!("{} {} {} {} {} {}\n", p[0], p[1], p[2], p[0], p[1], p[2]))
        .collect();
    let (model, o) = fit_file(dir.path(), "cloud.txt", &points, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("Iterative") && stderr(&o).contains("iterations"),
        "{}",
        stderr(&o)
    );
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&model).unwrap()).unwrap();
    assert_eq!(m["report"]["method"], "iterative");
    // Within the iterative solver's default limit.
    assert!(m["report"]["residual"].as_f64().unwrap() <= 1e-5);
    // The dense method on the same rows: the same surface.
    let (_, o) = fit_file(dir.path(), "cloud.txt", &points, &["--method", "dense"]);
    assert!(stderr(&o).contains("ProjectedCholesky"), "{}", stderr(&o));
    // One iteration cannot reach 1e-13: an error (exit 3) that says so, or, when allowed, a
    // model and a warning.
    let short = [
        "--method",
        "fast",
        "--max-iterations",
        "1",
        "--max-residual",
        "1e-13",
    ];
    let (_, o) = fit_file(dir.path(), "cloud.txt", &points, &short);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(stderr(&o).contains("did not converge"), "{}", stderr(&o));
    let allowed = [&short[..], &["--allow-unconverged"]].concat();
    let (model, o) = fit_file(dir.path(), "cloud.txt", &points, &allowed);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("warning: the iterative solve stopped"),
        "{}",
        stderr(&o)
    );
    assert!(model.exists());
    // --exact (direct products whatever the size) is taken by the iterative method.
    let (exact, o) = fit_file(
        dir.path(),
        "cloud.txt",
        &points,
        &["--method", "fast", "--exact"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let e: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&exact).unwrap()).unwrap();
    assert_eq!(e["report"]["method"], "iterative");
    assert!(e["report"]["residual"].as_f64().unwrap() <= 1e-5);
    // Options of other methods are refused.
    for bad in [
        &["--tolerance", "1e-3"][..],
        &["--method", "fast", "--solver", "lu"],
    ] {
        let (_, o) = fit_file(dir.path(), "cloud.txt", &points, bad);
        assert_eq!(o.status.code(), Some(1), "{bad:?}: {}", stderr(&o));
    }
}

#[test]
fn greedy_fit_uses_few_of_many_points_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let n = 3000;
    let points: String = rbf_core::shapes::fibonacci_sphere(n)
        .into_iter()
        .map(|p| format!("{} {} {} {} {} {}\n", p[0], p[1], p[2], p[0], p[1], p[2]))
        .collect();
    let (model, o) = fit_file(dir.path(), "scan.txt", &points, &["--greedy", "-v"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("round  1: 100 constraints miss by up to"),
        "{}",
        stderr(&o)
    );
    assert!(
        stderr(&o).contains(&format!("of {n} constraints greedily")),
        "{}",
        stderr(&o)
    );
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&model).unwrap()).unwrap();
    let used = m["constraints"].as_array().unwrap().len();
    assert!((10..n / 5).contains(&used), "{used}");
    // The model reads back (its normal constraints keep the offsets they were fitted with).
    let o = rbf(&["info", model.to_str().unwrap()], None);
    assert!(o.status.success(), "{}", stderr(&o));
    // A budget too small for the tolerance: the best fit within it, and a warning.
    let (_, o) = fit_file(
        dir.path(),
        "scan.txt",
        &points,
        &["--greedy", "--tolerance", "1e-9", "--max-centres", "50"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("warning: 50 constraints still miss"),
        "{}",
        stderr(&o)
    );
    for bad in [
        &["--tolerance", "1e-3"][..],
        &["--greedy", "--tolerance", "-1"],
        &["--greedy", "--max-centres", "0"],
        &["--greedy", "--solver", "lu"],
    ] {
        let (_, o) = fit_file(dir.path(), "scan.txt", &points, bad);
        assert_eq!(o.status.code(), Some(1), "{bad:?}: {}", stderr(&o));
    }
}

#[test]
fn sculpt_takes_commands_at_a_prompt_and_from_text_files() {
    let dir = tempfile::tempdir().unwrap();
    let model = dir.path().join("blob.json");
    let preview = dir.path().join("blob.png");
    let o = rbf(
        &[
            "sculpt",
            "-",
            "-o",
            model.to_str().unwrap(),
            "--preview",
            preview.to_str().unwrap(),
            "--frame-size",
            "48",
        ],
        Some(
            "add 0 0 1.5\nadd 1 2\ndelete 99\nmove 12 0 0 1.8\nnormal 12\nundo\nquit\nadd 5 5 5\n",
        ),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8(o.stdout.clone()).unwrap();
    let answers: Vec<&str> = out.lines().collect();
    assert!(answers[0].starts_with("item 12 added; 13 items"), "{out}");
    assert_eq!(answers[1], "refused: usage: add X Y Z");
    assert!(
        answers[2].starts_with("refused: ") && answers[2].contains("99"),
        "{out}"
    );
    assert!(answers[3].starts_with("done; 13 items"), "{out}");
    assert!(answers[4].starts_with("item 13 added; 14 items"), "{out}");
    assert!(answers[5].starts_with("done; 13 items"), "{out}");
    assert_eq!(answers.len(), 6, "nothing after quit: {out}");
    assert!(
        stderr(&o).contains("4 edits applied, 2 refused; 13 constraints"),
        "{}",
        stderr(&o)
    );
    assert_eq!(&std::fs::read(&preview).unwrap()[1..4], b"PNG");
    // The model reads back and passes through the moved point.
    let o = rbf(&["eval", model.to_str().unwrap(), "-"], Some("0 0 1.8\n"));
    assert!(o.status.success(), "{}", stderr(&o));
    let v: f64 = String::from_utf8(o.stdout).unwrap().trim().parse().unwrap();
    assert!(v.abs() < 1e-9, "{v}");
    // The same commands in a text file; a bad line there is an error naming it.
    let script = write(
        dir.path(),
        "edits.txt",
        "# a bump\nadd 0 0 1.5\nmove 12 0 0 1.8\n",
    );
    let o = rbf(
        &[
            "sculpt",
            script.to_str().unwrap(),
            "-o",
            model.to_str().unwrap(),
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("applied 2 edits"), "{}", stderr(&o));
    let bad = write(dir.path(), "bad.txt", "add 0 0 1.5\nsmooth 3\n");
    let o = rbf(
        &[
            "sculpt",
            bad.to_str().unwrap(),
            "-o",
            model.to_str().unwrap(),
        ],
        None,
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("bad.txt: line 2, column 1: unknown command `smooth`"),
        "{}",
        stderr(&o)
    );
}

/// `rbf studio` without a built page says what to run; a bad model is refused before serving;
/// a built page (a stand-in here) is served on 127.0.0.1 with the model it was given.
#[test]
fn studio_explains_a_missing_build_refuses_bad_models_and_serves_files() {
    let dir = tempfile::tempdir().unwrap();
    let web = dir.path().join("web");
    std::fs::create_dir_all(web.join("pkg")).unwrap();
    let web_arg = web.to_str().unwrap();
    let o = rbf(&["studio", "--web", web_arg, "--port", "0"], None);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("run web/build.sh first"),
        "{}",
        stderr(&o)
    );
    write(&web.join("pkg"), "rbf_web.js", "export default 1;\n");
    write(&web, "index.html", "<!doctype html><title>studio</title>\n");
    let bad = write(dir.path(), "bad.json", "{\"format\": ");
    let o = rbf(
        &[
            "studio",
            bad.to_str().unwrap(),
            "--web",
            web_arg,
            "--port",
            "0",
        ],
        None,
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("bad.json"), "{}", stderr(&o));
    // Serve a model: read the URL, then fetch the page, the config and the model.
    let points: String = rbf_core::shapes::fibonacci_sphere(30)
        .into_iter()
        .map(|p| format!("{} {} {} {} {} {}\n", p[0], p[1], p[2], p[0], p[1], p[2]))
        .collect();
    let (model, o) = fit_file(dir.path(), "sphere.txt", &points, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    /// Stops the server however the test ends.
    struct Server(std::process::Child);
    impl Drop for Server {
        fn drop(&mut self) {
            let _ = self.0.kill();
            let _ = self.0.wait();
        }
    }
    let model_arg = model.to_str().unwrap();
    let mut child = Server(
        Command::new(env!("CARGO_BIN_EXE_rbf"))
            .args(["studio", model_arg, "--web", web_arg, "--port", "0"])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap(),
    );
    let mut line = String::new();
    std::io::BufRead::read_line(
        &mut std::io::BufReader::new(child.0.stdout.take().unwrap()),
        &mut line,
    )
    .unwrap();
    let address = line
        .split("http://")
        .nth(1)
        .and_then(|rest| rest.split('/').next())
        .unwrap()
        .to_string();
    assert!(address.starts_with("127.0.0.1:"), "{line}");
    let request = |path: &str, host: &str| -> String {
        use std::io::Read;
        let mut s = std::net::TcpStream::connect(&address).unwrap();
        write!(s, "GET {path} HTTP/1.1\r\nHost: {host}\r\n\r\n").unwrap();
        let mut reply = String::new();
        s.read_to_string(&mut reply).unwrap();
        reply
    };
    let get = |path: &str| request(path, &address);
    let page = get("/");
    assert!(
        page.starts_with("HTTP/1.1 200") && page.contains("<title>studio</title>"),
        "{page}"
    );
    assert!(get("/pkg/rbf_web.js").contains("Content-Type: text/javascript"));
    assert!(get("/studio.json").contains(r#"{"model": "model.json"}"#));
    let served = get("/model.json");
    let body = served.split("\r\n\r\n").nth(1).unwrap();
    assert_eq!(body, std::fs::read_to_string(&model).unwrap());
    // Nothing outside the page's folder, though these files exist: the model written beside
    // web/, and the system's own files.
    assert!(dir.path().join("m.json").is_file());
    for escape in ["/../m.json", "//etc/hostname", "/pkg/../../m.json", "/C:/x"] {
        assert!(get(escape).starts_with("HTTP/1.1 404"), "{escape}");
    }
    assert!(get("/nothing.js").starts_with("HTTP/1.1 404"));
    assert!(get("?x").starts_with("HTTP/1.1 200"));
    // A page elsewhere that points its own name at 127.0.0.1 is refused.
    assert!(request("/model.json", "evil.example:80").starts_with("HTTP/1.1 403"));
    drop(child);
}

/// Point clouds in: `.npy` files written by numpy itself (`tests/fixtures`, made by the script
/// beside them) and PLY with normals; a cloud without normals is refused, saying what is
/// missing.
#[test]
fn fit_reads_point_clouds_from_npy_and_ply() {
    let dir = tempfile::tempdir().unwrap();
    let fixtures = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures");
    let out = dir.path().join("m.json");
    let out_arg = out.to_str().unwrap();
    let on_sphere = |model: &str| {
        // f at the sphere's own points (fresh ones, not the fitted ones) and at the centre.
        let probe: String = rbf_core::shapes::fibonacci_sphere(7)
            .into_iter()
            .map(|p| format!("{} {} {}\n", p[0], p[1], p[2]))
            .collect::<String>()
            + "0 0 0\n";
        let o = rbf(&["eval", model, "-"], Some(&probe));
        assert!(o.status.success(), "{}", stderr(&o));
        let values: Vec<f64> = String::from_utf8_lossy(&o.stdout)
            .lines()
            .map(|l| l.trim().parse().unwrap())
            .collect();
        assert!(values[..7].iter().all(|v| v.abs() < 0.05), "{values:?}");
        assert!(values[7] > 0.0, "the centre is inside: {values:?}");
    };
    for file in ["sphere_oriented.npy", "sphere_values_f4_fortran_be.npy"] {
        let o = rbf(
            &["fit", &format!("{fixtures}/{file}"), "-o", out_arg, "-q"],
            None,
        );
        assert!(o.status.success(), "{file}: {}", stderr(&o));
        on_sphere(out_arg);
    }
    let info = rbf(&["info", out_arg], None);
    assert!(String::from_utf8_lossy(&info.stdout).contains("60 boundary, 8 interior"));
    // PLY, binary little-endian, with normals: the sphere again.
    let points = rbf_core::shapes::fibonacci_sphere(60);
    let mut ply = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\nend_header\n",
        points.len()
    )
    .into_bytes();
    for p in &points {
        for v in p.iter().chain(p) {
            ply.extend_from_slice(&(*v as f32).to_le_bytes());
        }
    }
    let scan = dir.path().join("scan.ply");
    std::fs::write(&scan, &ply).unwrap();
    let o = rbf(&["fit", scan.to_str().unwrap(), "-o", out_arg, "-q"], None);
    assert!(o.status.success(), "{}", stderr(&o));
    on_sphere(out_arg);
    // Without normals: refused, saying so.
    let bare = write(
        dir.path(),
        "bare.ply",
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n",
    );
    for file in [bare, PathBuf::from(format!("{fixtures}/sphere_points.npy"))] {
        let o = rbf(&["fit", file.to_str().unwrap(), "-o", out_arg], None);
        assert_eq!(o.status.code(), Some(2));
        assert!(
            stderr(&o).contains("has points but no normals"),
            "{}",
            stderr(&o)
        );
    }
    // A truncated array names the file and what is short.
    let cut = dir.path().join("cut.npy");
    let whole = std::fs::read(format!("{fixtures}/sphere_oriented.npy")).unwrap();
    std::fs::write(&cut, &whole[..whole.len() - 8]).unwrap();
    let o = rbf(&["fit", cut.to_str().unwrap(), "-o", out_arg], None);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("cut.npy") && stderr(&o).contains("bytes of data"),
        "{}",
        stderr(&o)
    );
}

/// A binary little-endian PLY of float32 oriented points, as scanners write them.
fn binary_ply(points: &[([f64; 3], [f64; 3])]) -> Vec<u8> {
    let mut bytes = format!(
        "ply\nformat binary_little_endian 1.0\ncomment scan-like test cloud\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\nend_header\n",
        points.len()
    )
    .into_bytes();
    for (p, n) in points {
        for v in p.iter().chain(n) {
            bytes.extend_from_slice(&(*v as f32).to_le_bytes());
        }
    }
    bytes
}

#[test]
fn a_scan_like_cloud_with_holes_closes_with_its_topology() {
    // Oriented points at uneven density on a bumpy sphere and on a torus, each with three
    // unscanned caps: 4000 points, 8000 rows (the iterative solver), float32 binary PLY.
    let dir = tempfile::tempdir().unwrap();
    let mut state = 12345_u64;
    let mut uniform = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let holes = [[0.0, 0.0, 1.0], [0.8, -0.6, 0.0], [-0.6, 0.0, -0.8]];
    let mut sphere = Vec::new();
    while sphere.len() < 4000 {
        let u = [uniform() - 0.5, uniform() - 0.5, uniform() * 0.8 - 0.5];
        let l = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
        if !(0.05..=0.5).contains(&l) {
            continue;
        }
        let u = [u[0] / l, u[1] / l, u[2] / l];
        if holes
            .iter()
            .any(|h| h[0] * u[0] + h[1] * u[1] + h[2] * u[2] > 0.95)
        {
            continue;
        }
        // r = 1 + 0.1 sin(3 θ): the normal of a star-shaped surface r(θ) from its gradient.
        let theta = u[2].acos();
        let r = 1.0 + 0.1 * (3.0 * theta).sin();
        let dr = 0.3 * (3.0 * theta).cos();
        let e_theta = {
            let s = (1.0 - u[2] * u[2]).sqrt().max(1e-12);
            [u[0] * u[2] / s, u[1] * u[2] / s, -s]
        };
        let n = [
            r * u[0] - dr * e_theta[0],
            r * u[1] - dr * e_theta[1],
            r * u[2] - dr * e_theta[2],
        ];
        sphere.push(([r * u[0], r * u[1], r * u[2]], n));
    }
    let mut torus = Vec::new();
    while torus.len() < 4000 {
        let (a, b) = (
            uniform() * std::f64::consts::TAU,
            uniform() * std::f64::consts::TAU,
        );
        if a.cos() > 0.93 || (a - 2.0).cos() > 0.95 || (b - 1.0).cos() > 0.97 {
            continue;
        }
        let n = [a.cos() * b.cos(), a.sin() * b.cos(), b.sin()];
        let p = [
            (1.0 + 0.35 * b.cos()) * a.cos(),
            (1.0 + 0.35 * b.cos()) * a.sin(),
            0.35 * b.sin(),
        ];
        torus.push((p, n));
    }
    for (name, cloud, genus) in [("sphere", sphere, 0), ("torus", torus, 1)] {
        let ply = dir.path().join(format!("{name}.ply"));
        std::fs::write(&ply, binary_ply(&cloud)).unwrap();
        let model = dir.path().join(format!("{name}.json"));
        let o = rbf(
            &["fit", ply.to_str().unwrap(), "-o", model.to_str().unwrap()],
            None,
        );
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("8000 rows") && stderr(&o).contains("Iterative"),
            "{}",
            stderr(&o)
        );
        let surface = dir.path().join(format!("{name}.obj"));
        let o = rbf(
            &[
                "mesh",
                model.to_str().unwrap(),
                "-o",
                surface.to_str().unwrap(),
                "--resolution",
                "48",
                "--method",
                "grid",
            ],
            None,
        );
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        let o = rbf(&["check", surface.to_str().unwrap()], None);
        let text = String::from_utf8(o.stdout).unwrap();
        assert!(
            text.contains("components 1,") && text.contains(&format!("genus {genus}\n")),
            "{name}: {text}"
        );
        assert!(text.contains("watertight: yes"), "{name}: {text}");
    }
}

#[test]
fn a_cloud_too_large_for_memory_is_refused_from_its_header() {
    // A binary PLY whose header promises 10⁹ oriented points, and a .npy of 10¹⁰ rows: refused
    // at once (exit 3) with what they need, without reading (there is nothing to read).
    let dir = tempfile::tempdir().unwrap();
    let ply = dir.path().join("huge.ply");
    let mut bytes = binary_ply(&[]);
    let header = String::from_utf8(bytes.clone()).unwrap();
    bytes = header
        .replace("element vertex 0", "element vertex 1000000000")
        .into_bytes();
    std::fs::write(&ply, bytes).unwrap();
    let npy = dir.path().join("huge.npy");
    let text = format!(
        "{:<117}\n",
        "{'descr': '<f8', 'fortran_order': False, 'shape': (10000000000, 6), }"
    );
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend_from_slice(&(text.len() as u16).to_le_bytes());
    bytes.extend_from_slice(text.as_bytes());
    std::fs::write(&npy, bytes).unwrap();
    for (file, extra) in [
        (&ply, &[][..]),
        (&npy, &[][..]),
        (&ply, &["--method", "greedy"][..]),
    ] {
        let mut args = vec!["fit", file.to_str().unwrap(), "-o", "/dev/null"];
        args.extend_from_slice(extra);
        let o = rbf(&args, None);
        assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
        assert!(stderr(&o).contains("MiB"), "{}", stderr(&o));
    }
}

#[test]
fn bad_scans_are_refused_naming_the_culprit() {
    let dir = tempfile::tempdir().unwrap();
    let mut cloud: Vec<([f64; 3], [f64; 3])> = rbf_core::shapes::fibonacci_sphere(50)
        .into_iter()
        .map(|p| (p, p))
        .collect();
    cloud[17].0[1] = f64::NAN;
    let ply = dir.path().join("nan.ply");
    std::fs::write(&ply, binary_ply(&cloud)).unwrap();
    let o = rbf(&["fit", ply.to_str().unwrap(), "-o", "/dev/null"], None);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("nan.ply") && stderr(&o).contains("vertex 17 has a coordinate"),
        "{}",
        stderr(&o)
    );
    // A binary PLY cut in the middle of a vertex.
    cloud[17].0[1] = 0.5;
    let bytes = binary_ply(&cloud);
    let cut = dir.path().join("cut.ply");
    std::fs::write(&cut, &bytes[..bytes.len() - 30]).unwrap();
    let o = rbf(&["fit", cut.to_str().unwrap(), "-o", "/dev/null"], None);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("cut.ply"), "{}", stderr(&o));
}

/// `rbf reconstruct`: a torus scanned without normals (an .xyz file) becomes a watertight mesh
/// of genus 1 with the model beside it; a flat cloud is refused and nothing is written.
#[test]
fn reconstruct_a_cloud_without_normals_and_refuse_a_flat_one() {
    let dir = tempfile::tempdir().unwrap();
    let golden = 0.5 * (5f64.sqrt() - 1.0);
    let text: String = (0..3000)
        .map(|i| {
            let u = std::f64::consts::TAU * i as f64 / 3000.0;
            let v = std::f64::consts::TAU * (i as f64 * golden).fract();
            let r = 1.0 + 0.4 * v.cos();
            format!("{} {} {}\n", r * u.cos(), r * u.sin(), 0.4 * v.sin())
        })
        .collect();
    let cloud = write(dir.path(), "torus.xyz", &text);
    let mesh = dir.path().join("torus.obj");
    let model = dir.path().join("torus.json");
    let o = rbf(
        &[
            "reconstruct",
            cloud.to_str().unwrap(),
            "-o",
            mesh.to_str().unwrap(),
            "--model",
            model.to_str().unwrap(),
            "--resolution",
            "64",
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let said = stderr(&o);
    assert!(
        said.contains("3000 points read") && said.contains("normals estimated"),
        "{said}"
    );
    assert!(
        said.contains("watertight, genus 1, 1 component(s)"),
        "{said}"
    );
    assert!(mesh.exists() && model.exists());
    let flat: String = (0..400)
        .map(|i| format!("{} {} 0\n", i % 20, i / 20))
        .collect();
    let cloud = write(dir.path(), "flat.xyz", &flat);
    let out = dir.path().join("flat.obj");
    let o = rbf(
        &[
            "reconstruct",
            cloud.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ],
        None,
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("lie on a plane"), "{}", stderr(&o));
    assert!(!out.exists());
    // --trim: the torus's surface lies within 0.1 of its points everywhere (they cover it), so
    // trimming there keeps it whole; a distance that is no distance is refused.
    let cloud = dir.path().join("torus.xyz");
    let trim = |out: &std::path::Path, distance: &str| {
        rbf(
            &[
                "reconstruct",
                cloud.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
                "--resolution",
                "64",
                &format!("--trim={distance}"),
            ],
            None,
        )
    };
    let trimmed = dir.path().join("trimmed.obj");
    let o = trim(&trimmed, "0.1");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("watertight, genus 1"), "{}", stderr(&o));
    // Closer than the points' spacing (about 0.07), the cut opens the surface and says so.
    let o = trim(&trimmed, "0.02");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains(", open,"), "{}", stderr(&o));
    for bad in ["0", "-1", "nan"] {
        let out = dir.path().join(format!("bad-{bad}.obj"));
        let o = trim(&out, bad);
        // A bad option is a usage error (exit 1), as for --tolerance.
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        assert!(stderr(&o).contains("--trim"), "{}", stderr(&o));
        assert!(!out.exists());
    } // A smoothing that is no λ is refused the same way.
    for bad in ["0", "-1e-4", "nan", "inf"] {
        let out = dir.path().join(format!("smoothing-{bad}.obj"));
        let o = rbf(
            &[
                "reconstruct",
                cloud.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
                &format!("--smoothing={bad}"),
            ],
            None,
        );
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        assert!(stderr(&o).contains("--smoothing"), "{}", stderr(&o));
        assert!(!out.exists());
    }
}
