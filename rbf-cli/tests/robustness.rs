//! The bad-input catalogue of docs/robustness.md: every case through the CLI (exit code and
//! the phrase of its message), and the file cases through the library too.

use std::path::Path;
use std::process::{Command, Stdio};

use std::io::Write;

const S: f64 = 0.57735;

fn tetrahedron_text() -> String {
    format!("{S} {S} {S} 0\n{S} -{S} -{S} 0\n-{S} {S} -{S} 0\n-{S} -{S} {S} 0\n0 0 0 1\n")
}

const TET_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

/// Runs `rbf` in `dir`; returns the exit code and stderr (stdout when stderr is empty).
fn rbf(dir: &Path, args: &[&str], stdin: &str) -> (i32, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_rbf"))
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let _ = child.stdin.take().unwrap().write_all(stdin.as_bytes());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    let text = if err.trim().is_empty() {
        String::from_utf8_lossy(&out.stdout).into_owned()
    } else {
        err
    };
    (out.status.code().unwrap_or(-1), text)
}

/// A case: its name, files to write, the command, its stdin, the exit code and a phrase the
/// message must contain.
struct Case {
    name: &'static str,
    files: Vec<(&'static str, Vec<u8>)>,
    args: Vec<&'static str>,
    stdin: &'static str,
    code: i32,
    phrase: &'static str,
}

fn case(
    name: &'static str,
    files: Vec<(&'static str, Vec<u8>)>,
    args: &[&'static str],
    code: i32,
    phrase: &'static str,
) -> Case {
    Case {
        name,
        files,
        args: args.to_vec(),
        stdin: "",
        code,
        phrase,
    }
}

fn text(name: &'static str, body: String) -> Vec<(&'static str, Vec<u8>)> {
    vec![(name, body.into_bytes())]
}

fn stl_header(count: u32, body: usize) -> Vec<u8> {
    let mut b = vec![0u8; 80];
    b.extend(count.to_le_bytes());
    b.extend(vec![0u8; body]);
    b
}

fn cases(model: &str) -> Vec<Case> {
    let tet = tetrahedron_text();
    let m: serde_json::Value = serde_json::from_str(model).unwrap();
    let edited = |f: &dyn Fn(&mut serde_json::Value)| {
        let mut v = m.clone();
        f(&mut v);
        serde_json::to_vec(&v).unwrap()
    };
    let eval = |name: &'static str,
                file: &'static str,
                body: Vec<u8>,
                stdin: &'static str,
                phrase: &'static str| Case {
        name,
        files: vec![(file, body), ("good.json", model.as_bytes().to_vec())],
        args: vec!["eval", file, "-"],
        stdin,
        code: 2,
        phrase,
    };
    let scaled: String = [
        [S, S, S, 0.0],
        [S, -S, -S, 0.0],
        [-S, S, -S, 0.0],
        [-S, -S, S, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]
    .iter()
    .map(|c| format!("{} {} {} {}\n", c[0] * 1e6, c[1] * 1e6, c[2] * 1e6, c[3]))
    .collect();
    let many: String = (0..200_000)
        .map(|i| format!("{} {} {} 0\n", i % 100, (i / 100) % 100, i / 10000))
        .collect::<String>()
        + "50 50 50 1\n";
    let inverted = TET_OBJ
        .replace("f 1 3 2", "f 1 2 3")
        .replace("f 1 2 4", "f 1 4 2")
        .replace("f 1 4 3", "f 1 3 4")
        .replace("f 2 3 4", "f 2 4 3");
    vec![
        case("empty constraint file", text("c.txt", String::new()), &["fit", "c.txt", "-o", "o.json"], 2, "at least 4 are needed"),
        case("comments only", text("c.txt", "# nothing\n\n".into()), &["fit", "c.txt", "-o", "o.json"], 2, "at least 4 are needed"),
        case("one point", text("c.txt", "0 0 0 0\n".into()), &["fit", "c.txt", "-o", "o.json"], 2, "1 constraint point(s) cannot"),
        case("only boundary constraints (f = 0 everywhere)", text("c.txt", "0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n".into()), &["fit", "c.txt", "-o", "o.json"], 2, "f would be 0 everywhere"),
        case("too few numbers on a line", text("c.txt", tet.clone() + "1 2\n"), &["fit", "c.txt", "-o", "o.json"], 2, "line 6: expected 4 numbers"),
        case("a word instead of a number", text("c.txt", tet.clone() + "1 two 3 0\n"), &["fit", "c.txt", "-o", "o.json"], 2, "line 6: `two` is not a number"),
        case("NaN value", text("c.txt", tet.clone() + "2 2 2 nan\n"), &["fit", "c.txt", "-o", "o.json"], 2, "line 6: `nan` is not a finite number"),
        case("infinite coordinate", text("c.txt", tet.clone() + "inf 2 2 -1\n"), &["fit", "c.txt", "-o", "o.json"], 2, "line 6: `inf` is not a finite number"),
        case("huge coordinate (1e300) beside small ones", text("c.txt", tet.clone() + "1e300 0 0 -1\n"), &["fit", "c.txt", "-o", "o.json"], 2, "closer than the minimum separation"),
        case("coordinates at scale 1e6", text("c.txt", scaled), &["fit", "c.txt", "-o", "o.json"], 0, "fitted 5 constraints"),
        case("two points 1e-16 apart", text("c.txt", tet.clone() + "0.5 0.5 0.5 0\n0.5 0.5 0.5000000000000001 0\n"), &["fit", "c.txt", "-o", "o.json"], 2, "constraint 5 and constraint 6 are"),
        case("a duplicated point", text("c.txt", tet.clone() + &format!("{S} {S} {S} 0\n")), &["fit", "c.txt", "-o", "o.json"], 2, "constraint 0 and constraint 5 are 0e0 apart"),
        case("ten thousand copies of one point", text("c.txt", tet.clone() + &"0.1 0.2 0.3 1\n".repeat(10_000)), &["fit", "c.txt", "-o", "o.json"], 2, "constraint 5 and constraint 6"),
        case("all points on a plane", text("c.txt", "0 0 0 0\n1 0 0 0\n0 1 0 0\n1 1 0 0\n0.5 0.5 0 1\n".into()), &["fit", "c.txt", "-o", "o.json"], 2, "(a plane)"),
        case("all points on a line", text("c.txt", "0 0 0 0\n1 0 0 0\n2 0 0 0\n3 0 0 1\n".into()), &["fit", "c.txt", "-o", "o.json"], 2, "(a line)"),
        case("a normal of zero length", text("c.txt", "1 0 0 0 0 0\n0 1 0 0 1 0\n0 0 1 0 0 1\n-1 0 0 -1 0 0\n".into()), &["fit", "c.txt", "-o", "o.json"], 2, "line 1: the normal has zero length"),
        case("CRLF line ends and commas", text("c.txt", tet.replace(' ', ", ").replace('\n', "\r\n")), &["fit", "c.txt", "-o", "o.json"], 0, "fitted 5 constraints"),
        case("negative λ", text("c.txt", tet.clone()), &["fit", "c.txt", "--lambda", "-1", "-o", "o.json"], 2, "λ must be finite and ≥ 0"),
        case("truncated JSON", text("c.json", r#"{"constraints": [{"kind": "boundary", "position": [0, 0"#.into()), &["fit", "c.json", "-o", "o.json"], 2, "line 1, column 55"),
        case("an unknown JSON field", text("c.json", r#"{"constraints": [], "colour": 1}"#.into()), &["fit", "c.json", "-o", "o.json"], 2, "unknown field `colour`"),
        case("a position of the wrong length", text("c.json", r#"{"constraints": [{"kind": "boundary", "position": [0, 0, 0]}, {"kind": "interior", "position": [0, 0], "value": 1}]}"#.into()), &["fit", "c.json", "-o", "o.json"], 2, "constraint 1 has 2 coordinates where 3"),
        case("dimension 4", text("c.json", r#"{"dim": 4, "constraints": [{"kind": "boundary", "position": [0, 0, 0, 0]}]}"#.into()), &["fit", "c.json", "-o", "o.json"], 2, "dimension 4 is not supported"),
        case("an unknown kernel", text("c.json", r#"{"kernel": "gaussian", "constraints": []}"#.into()), &["fit", "c.json", "-o", "o.json"], 2, "unknown variant `gaussian`"),
        case("a dense system larger than memory (200 001 rows)", text("c.txt", many), &["fit", "c.txt", "-o", "o.json", "--method", "dense"], 3, "MiB can be spared"),
        case("a constraint file of 10⁷ lines", text("c.txt", (0..10_000_000).map(|i| format!("{} {} {} 0\n", i % 1000, (i / 1000) % 1000, i / 1_000_000)).collect::<String>() + "5.5 5.5 5.5 1\n"), &["fit", "c.txt", "-o", "o.json"], 3, "a system of 10000001 rows needs"),
        eval("a model of another version", "v.json", edited(&|v| v["version"] = 2.into()), "0 0 0\n", "cannot be read; this library reads version 1"),
        eval("not a model file", "v.json", edited(&|v| v["format"] = "something".into()), "0 0 0\n", "is not `rbf-model`"),
        eval("weights and centres of different lengths", "v.json", edited(&|v| { v["weights"].as_array_mut().unwrap().pop(); }), "0 0 0\n", "weights has 4 entries where 5"),
        eval("a centre moved away from its constraint", "v.json", edited(&|v| v["centres"][0] = serde_json::json!([9, 9, 9])), "0 0 0\n", "centre 0 is not where constraint 0 puts it"),
        eval("a NaN in a model (not JSON)", "v.json", String::from_utf8(edited(&|_| {})).unwrap().replacen("\"weights\":[", "\"weights\":[NaN,", 1).into_bytes(), "0 0 0\n", "line 1, column"),
        eval("a point of the wrong dimension", "good2.json", model.as_bytes().to_vec(), "0 0\n", "expected 3 coordinates, found 2"),
        eval("a NaN point", "good2.json", model.as_bytes().to_vec(), "nan 0 0\n", "`nan` is not a finite number"),
        case("an empty OBJ", text("m.obj", String::new()), &["check", "m.obj"], 2, "no triangles"),
        case("an OBJ face index out of range", text("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n".into()), &["check", "m.obj"], 2, "line 4: vertex index 9 is out of range"),
        case("an OBJ vertex with NaN", text("m.obj", "v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".into()), &["check", "m.obj"], 2, "line 1: `nan` is not a finite number"),
        case("a truncated binary STL", vec![("m.stl", stl_header(2, 60))], &["check", "m.stl"], 2, "declares 2 triangles (184 bytes) but the file has 144"),
        case("an STL header claiming 10⁹ triangles (a 50 GB size field)", vec![("m.stl", stl_header(1_000_000_000, 50))], &["check", "m.stl"], 2, "declares 1000000000 triangles"),
        case("a PLY header claiming 10¹⁰ vertices", text("m.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 10000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n".into()), &["check", "m.ply"], 2, "declares 10000000000 `vertex` elements"),
        case("a truncated PLY", text("m.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n".into()), &["check", "m.ply"], 2, "ends in the middle of the data"),
        case("a mesh of zero-area triangles", text("m.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 3 2\n".into()), &["convert", "m.obj", "-o", "o.json", "--resolution", "16"], 2, "no voxel is inside the mesh"),
        case("one flat triangle", text("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".into()), &["convert", "m.obj", "-o", "o.json", "--resolution", "16"], 2, "no voxel is inside the mesh"),
        case("an inside-out mesh (inverted orientation)", text("m.obj", inverted), &["convert", "m.obj", "-o", "o.json", "--resolution", "24"], 0, "max error"),
        case("an open mesh (a face missing)", text("m.obj", TET_OBJ.replace("f 2 3 4\n", "")), &["convert", "m.obj", "-o", "o.json", "--resolution", "24"], 0, "not watertight: winding numbers"),
        case("a non-manifold edge", text("m.obj", format!("{TET_OBJ}v 1 1 -1\nf 1 2 5\n")), &["check", "m.obj"], 0, "non-manifold edges 1"),
        case("a resolution too coarse for any interior voxel", text("m.obj", TET_OBJ.into()), &["convert", "m.obj", "-o", "o.json", "--resolution", "1"], 2, "too coarse to hold its interior"),
        case("an image 0 pixels wide", text("good.json", model.into()), &["render", "good.json", "-o", "o.png", "--width", "0"], 2, "each side must be 1 to 16384"),
        case("an image 20000 × 20000", text("good.json", model.into()), &["render", "good.json", "-o", "o.png", "--width", "20000", "--height", "20000"], 2, "each side must be 1 to 16384"),
        case("a volume of 5000³ voxels", text("m.obj", TET_OBJ.into()), &["voxelize", "m.obj", "-o", "o.npy", "--resolution", "5000"], 2, "is too large"),
        case("a malformed sculpting script", text("s.json", r#"[{"move": {"item": 1}}"#.into()), &["sculpt", "s.json", "-o", "o.json"], 2, "missing field `to`"),
        case("a missing input file", vec![], &["fit", "none.txt", "-o", "o.json"], 2, "none.txt: No such file"),
        case("an output in a missing directory", text("c.txt", tet.clone()), &["fit", "c.txt", "-o", "no/such/dir/o.json"], 2, "no/such/dir/o.json"),
        case("an unknown option", vec![], &["fit", "--colour", "red"], 1, "unexpected argument"),
        case("10⁵ oriented points, greedily (a 320 GB system whole)", text("c.txt", torus_points(100_000)), &["fit", "c.txt", "-o", "o.json", "--greedy"], 0, "of 100000 constraints greedily"),
        case("a negative greedy tolerance", text("c.txt", tet.clone()), &["fit", "c.txt", "-o", "o.json", "--greedy", "--tolerance", "-1"], 1, "--tolerance must be a finite number ≥ 0"),
        case("comparing with a mesh of no area", [text("good.json", model.into()), text("m.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n".into())].concat(), &["compare", "good.json", "m.obj"], 2, "no area"),
    ]
}

/// `n` oriented points spread over a torus, one `x y z nx ny nz` line each.
fn torus_points(n: usize) -> String {
    rbf_core::shapes::torus_points(n, 0.35)
        .into_iter()
        .map(|(p, d)| format!("{} {} {} {} {} {}\n", p[0], p[1], p[2], d[0], d[1], d[2]))
        .collect()
}

#[test]
fn every_catalogued_bad_input_gets_its_documented_answer() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("t.txt"), tetrahedron_text()).unwrap();
    let (code, msg) = rbf(dir.path(), &["fit", "t.txt", "-o", "good.json"], "");
    assert_eq!(code, 0, "{msg}");
    let model = std::fs::read_to_string(dir.path().join("good.json")).unwrap();
    let cases = cases(&model);
    assert!(cases.len() >= 55, "{} cases", cases.len());
    let mut failures = Vec::new();
    for c in &cases {
        let here = tempfile::tempdir().unwrap();
        for (name, bytes) in &c.files {
            std::fs::write(here.path().join(name), bytes).unwrap();
        }
        let (code, msg) = rbf(here.path(), &c.args, c.stdin);
        if code != c.code || !msg.contains(c.phrase) {
            failures.push(format!(
                "{}: exit {code} (want {}), message: {}",
                c.name,
                c.code,
                msg.trim()
            ));
        }
        // Nothing half-written is left behind on failure.
        if c.code != 0 {
            for out in ["o.json", "o.png", "o.npy"] {
                assert!(!here.path().join(out).exists(), "{}: {out} written", c.name);
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The file cases through the library: the readers' typed errors name the place.
#[test]
fn the_library_names_the_culprit_in_bad_files() {
    use rbf_core::{AnyModel, ConstraintFile, parse_constraints};
    use rbf_mesh::read_mesh_bytes;
    let e = parse_constraints::<3>(&(tetrahedron_text() + "1 two 3 0\n")).unwrap_err();
    assert!(e.to_string().contains("line 6"), "{e}");
    let e = parse_constraints::<3>("0 0 0 nan\n").unwrap_err();
    assert!(e.to_string().contains("not a finite number"), "{e}");
    assert!(ConstraintFile::from_json(r#"{"constraints": [], "colour": 1}"#).is_err());
    assert!(AnyModel::from_json(r#"{"format": "rbf-model", "version": 2}"#).is_err());
    let e =
        read_mesh_bytes(Path::new("m.obj"), b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n").unwrap_err();
    assert!(e.to_string().contains("line 4"), "{e}");
    let e = read_mesh_bytes(Path::new("m.stl"), &stl_header(1_000_000_000, 50)).unwrap_err();
    assert!(e.to_string().contains("byte 80"), "{e}");
    let e = read_mesh_bytes(Path::new("m.ply"), b"ply\nformat binary_little_endian 1.0\nelement vertex 10000000000\nproperty float x\nend_header\n").unwrap_err();
    assert!(e.to_string().contains("10000000000"), "{e}");
    assert!(read_mesh_bytes(Path::new("m.obj"), b"").is_err());
}
