//! Round trips through every format, and clean errors on malformed files.

use std::path::Path;

use rbf_mesh::{Location, MeshError, read_mesh, read_mesh_bytes, write_mesh};

use crate::{data, octahedron};

#[test]
fn round_trips_keep_the_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let original = read_mesh(&data("torus.obj")).unwrap();
    for ext in ["obj", "ply", "stl"] {
        let path = dir.path().join(format!("t.{ext}"));
        write_mesh(&path, &original).unwrap();
        let back = read_mesh(&path).unwrap();
        assert_eq!(back.triangles().len(), original.triangles().len(), "{ext}");
        assert_eq!(back.check().genus, Some(1), "{ext}");
        assert!(back.check().is_watertight(), "{ext}");
        // STL stores f32 and welds by position, so compare geometry, not indices.
        let tol = if ext == "stl" { 1e-6 } else { 0.0 };
        for t in 0..original.triangles().len() {
            let (a, b) = (original.corners(t), back.corners(t));
            for c in 0..3 {
                for d in 0..3 {
                    assert!((a[c][d] - b[c][d]).abs() <= tol, "{ext} triangle {t}");
                }
            }
        }
    }
}

#[test]
fn normals_survive_obj_and_ply() {
    let dir = tempfile::tempdir().unwrap();
    let o = octahedron();
    let normals = o.positions().to_vec();
    let m = o.with_normals(normals.clone()).unwrap();
    let path = dir.path().join("n.obj");
    write_mesh(&path, &m).unwrap();
    let back = read_mesh(&path).unwrap();
    for t in 0..m.triangles().len() {
        assert_eq!(back.corners(t), m.corners(t));
    }
    let ply = dir.path().join("n.ply");
    write_mesh(&ply, &m).unwrap();
    assert_eq!(read_mesh(&ply).unwrap().triangles(), m.triangles());
}

fn parse_error(name: &str, bytes: &[u8]) -> (Location, String) {
    match read_mesh_bytes(Path::new(name), bytes) {
        Err(MeshError::Parse {
            location,
            message,
            file,
        }) => {
            assert_eq!(file, Path::new(name));
            (location, message)
        }
        other => panic!("{name}: expected a parse error, got {other:?}"),
    }
}

#[test]
fn malformed_obj_names_the_line() {
    let (l, m) = parse_error("a.obj", b"v 0 0 0\nv 1 0 0\nv 0 x 0\nf 1 2 3\n");
    assert_eq!(l, Location::Line(3));
    assert!(m.contains("`x`"), "{m}");
    let (l, m) = parse_error("a.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    assert_eq!(l, Location::Line(4));
    assert!(m.contains("out of range"), "{m}");
    // A normal or texture index beyond those defined (a huge one overflowed inside tobj:
    // found by the obj fuzz target).
    let (l, m) = parse_error(
        "a.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//6148914691236517206\n",
    );
    assert_eq!(l, Location::Line(5));
    assert!(m.contains("1 normals are defined"), "{m}");
    let (l, m) = parse_error("a.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/2 2/1 3/1\n");
    assert_eq!(l, Location::Line(4));
    assert!(m.contains("0 texture coordinates"), "{m}");
    let (l, _) = parse_error("a.obj", b"v 0 0 nan\n");
    assert_eq!(l, Location::Line(1));
    let (l, _) = parse_error("a.obj", b"v 0 0 0\nv 1 0 0\nf 1 2\n");
    assert_eq!(l, Location::Line(3));
    // No faces at all.
    let e = read_mesh_bytes(Path::new("a.obj"), b"v 0 0 0\n").unwrap_err();
    assert!(e.to_string().contains("no triangles"), "{e}");
}

#[test]
fn malformed_ply_names_the_line_or_byte() {
    let (l, _) = parse_error("a.ply", b"plx\n");
    assert_eq!(l, Location::Line(1));
    let (l, m) = parse_error("a.ply", b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty fluff y\nend_header\n");
    assert_eq!(l, Location::Line(5));
    assert!(m.contains("fluff"), "{m}");
    // A size field far beyond the file: refused before any allocation.
    let (_, m) = parse_error(
        "a.ply",
        b"ply\nformat binary_little_endian 1.0\nelement vertex 10000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n\0\0\0\0",
    );
    assert!(m.contains("10000000000"), "{m}");
    // Fewer bytes than the declared vertices need: refused where the data starts.
    let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n".to_vec();
    let header = bytes.len() as u64;
    bytes.extend_from_slice(&[0u8; 20]);
    let (l, m) = parse_error("a.ply", &bytes);
    assert_eq!(l, Location::Byte(header));
    assert!(m.contains("2 `vertex` elements"), "{m}");
    // Data that ends inside a face list: the byte where it ran out.
    let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n".to_vec();
    let header = bytes.len() as u64;
    bytes.extend_from_slice(&[0u8; 36]);
    bytes.extend_from_slice(&[3, 0, 0, 0, 0, 1]);
    let (l, m) = parse_error("a.ply", &bytes);
    assert_eq!(l, Location::Byte(header + 41));
    assert!(m.contains("ends"), "{m}");
    // ASCII with a bad number.
    let (l, _) = parse_error(
        "a.ply",
        b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 oops\n",
    );
    assert_eq!(l, Location::Line(8));
}

#[test]
fn ply_ascii_with_quads_is_triangulated() {
    let text = b"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
    let m = read_mesh_bytes(Path::new("q.ply"), text).unwrap();
    assert_eq!(m.triangles(), &[[0, 1, 2], [0, 2, 3]]);
    assert_eq!(m.check().boundary_edges, 4);
}

#[test]
fn malformed_stl_names_the_line_or_byte() {
    let (l, _) = parse_error(
        "a.stl",
        b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0\n",
    );
    assert_eq!(l, Location::Line(5));
    let (l, m) = parse_error("a.stl", &[0u8; 90]);
    assert_eq!(l, Location::Byte(80));
    assert!(m.contains("0 triangles"), "{m}");
    let (l, _) = parse_error("a.stl", b"abc");
    assert_eq!(l, Location::Byte(0));
}

#[test]
fn ascii_stl_is_welded() {
    let text = b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
    let m = read_mesh_bytes(Path::new("a.stl"), text).unwrap();
    assert_eq!(m.positions().len(), 4);
    assert_eq!(m.check().boundary_edges, 4);
}

#[test]
fn unknown_extensions_and_missing_files_are_errors() {
    assert!(matches!(
        read_mesh_bytes(Path::new("a.xyz"), b""),
        Err(MeshError::UnknownFormat { .. })
    ));
    let e = read_mesh(Path::new("/nonexistent/a.obj")).unwrap_err();
    assert!(e.to_string().contains("/nonexistent/a.obj"));
}

/// Every prefix of a `.npy` file, and every single-byte change of its header, reads without a
/// panic: an error, or (for changes that keep it valid) a matrix of the declared shape.
#[test]
fn npy_files_cut_or_corrupted_are_errors_not_panics() {
    let header = "{'descr': '<f8', 'fortran_order': True, 'shape': (3, 2), }";
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    let padded = format!("{header:<117}\n");
    bytes.extend_from_slice(&(padded.len() as u16).to_le_bytes());
    bytes.extend_from_slice(padded.as_bytes());
    for v in [1.0f64, 2.0, 3.0, 4.0, 5.0, 6.0] {
        bytes.extend_from_slice(&v.to_le_bytes());
    }
    let path = std::path::Path::new("m.npy");
    let m = rbf_mesh::read_npy_matrix(path, &bytes).unwrap();
    // Fortran order on disk: columns (1 2 3) and (4 5 6); rows come out (1 4) (2 5) (3 6).
    assert_eq!((m.rows, m.cols), (3, 2));
    assert_eq!(m.data, vec![1.0, 4.0, 2.0, 5.0, 3.0, 6.0]);
    for cut in 0..bytes.len() {
        assert!(
            rbf_mesh::read_npy_matrix(path, &bytes[..cut]).is_err(),
            "cut at {cut}"
        );
    }
    for at in 0..128 {
        for byte in [0u8, b'9', b')', b'\'', 0xff] {
            let mut changed = bytes.clone();
            changed[at] = byte;
            if let Ok(m) = rbf_mesh::read_npy_matrix(path, &changed) {
                assert_eq!(m.data.len(), m.rows * m.cols);
            }
            let _ = rbf_mesh::read_point_cloud_bytes(path, &changed);
        }
    }
}
