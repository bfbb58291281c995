//! Mesh checks against the properties recorded in the meshes' MANIFEST and on constructed
//! defects.

use rbf_mesh::{MeshError, TriMesh, read_mesh};

use crate::{data, octahedron};

#[test]
fn shipped_meshes_match_their_manifest() {
    // (file, vertices, faces, genus) from ../shared/data/meshes/MANIFEST.md.
    for (name, v, f, genus) in [
        ("torus.obj", 2304, 4608, 1),
        ("knot.obj", 1440, 2880, 1),
        ("spot.obj", 2930, 5856, 0),
    ] {
        let m = read_mesh(&data(name)).unwrap();
        let r = m.check();
        assert_eq!((r.vertices, r.triangles), (v, f), "{name}");
        assert!(r.is_watertight(), "{name}: {r:?}");
        assert_eq!(r.genus, Some(genus), "{name}");
        assert_eq!(r.components, 1);
        assert_eq!(r.degenerate_triangles, 0);
        assert!(
            r.volume > 0.0,
            "{name}: outward faces give a positive volume"
        );
    }
}

#[test]
fn a_closed_octahedron_is_watertight_with_genus_0() {
    let r = octahedron().check();
    assert!(r.is_watertight());
    assert_eq!(
        (r.euler_characteristic, r.genus, r.components),
        (2, Some(0), 1)
    );
    assert!((octahedron().volume() - 4.0 / 3.0).abs() < 1e-12);
}

#[test]
fn a_missing_triangle_leaves_three_boundary_edges() {
    let o = octahedron();
    let m = TriMesh::new(o.positions().to_vec(), o.triangles()[1..].to_vec()).unwrap();
    let r = m.check();
    assert_eq!(r.boundary_edges, 3);
    assert!(!r.is_watertight());
    assert_eq!(r.genus, None);
}

#[test]
fn a_flipped_triangle_gives_three_inconsistent_edges() {
    let o = octahedron();
    let mut t = o.triangles().to_vec();
    t[0].swap(1, 2);
    let r = TriMesh::new(o.positions().to_vec(), t).unwrap().check();
    assert_eq!(r.inconsistent_edges, 3);
    assert!(!r.is_watertight());
}

#[test]
fn flipping_everything_keeps_consistency_and_negates_volume() {
    let mut o = octahedron();
    o.flip();
    let r = o.check();
    assert!(r.is_watertight());
    assert!(r.volume < 0.0);
}

#[test]
fn non_manifold_edges_vertices_duplicates_and_degenerates_are_counted() {
    // Three triangles on one edge.
    let p = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let r = TriMesh::new(p, vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]])
        .unwrap()
        .check();
    assert_eq!(r.non_manifold_edges, 1);
    // Two octahedra touching at one vertex: one non-manifold vertex, one component.
    let o = octahedron();
    let mut p = o.positions().to_vec();
    p.extend(o.positions().iter().map(|v| [v[0] + 2.0, v[1], v[2]]));
    let mut t = o.triangles().to_vec();
    // Vertex 0 of the first is at (1,0,0); vertex 1 of the second is at (1,0,0) too: share it.
    t.extend(
        o.triangles()
            .iter()
            .map(|tri| tri.map(|i| if i == 1 { 0 } else { i + 6 })),
    );
    let r = TriMesh::new(p, t).unwrap().check();
    assert_eq!(
        (r.non_manifold_vertices, r.components, r.unused_vertices),
        (1, 1, 1)
    );
    // A repeated triangle and a zero-area one.
    let o = octahedron();
    let mut t = o.triangles().to_vec();
    t.push(t[3]);
    t.push([0, 0, 1]);
    let r = TriMesh::new(o.positions().to_vec(), t).unwrap().check();
    assert_eq!((r.duplicate_triangles, r.degenerate_triangles), (1, 1));
}

#[test]
fn two_separate_shapes_are_two_components() {
    let o = octahedron();
    let mut p = o.positions().to_vec();
    p.extend(o.positions().iter().map(|v| [v[0] + 5.0, v[1], v[2]]));
    let mut t = o.triangles().to_vec();
    t.extend(o.triangles().iter().map(|tri| tri.map(|i| i + 6)));
    let r = TriMesh::new(p, t).unwrap().check();
    assert_eq!(
        (r.components, r.genus, r.euler_characteristic),
        (2, Some(0), 4)
    );
}

#[test]
fn invalid_meshes_are_errors() {
    assert!(matches!(
        TriMesh::new(vec![[0.0; 3]], vec![]),
        Err(MeshError::Empty)
    ));
    assert!(matches!(
        TriMesh::new(
            vec![[0.0; 3], [f64::NAN, 0.0, 0.0], [1.0; 3]],
            vec![[0, 1, 2]]
        ),
        Err(MeshError::NonFinite { vertex: 1 })
    ));
    assert!(matches!(
        TriMesh::new(vec![[0.0; 3]; 3], vec![[0, 1, 2], [0, 1, 3]]),
        Err(MeshError::IndexOutOfRange {
            triangle: 1,
            index: 3,
            vertices: 3
        })
    ));
}
