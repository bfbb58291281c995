//! The nearest point of a mesh, against a brute-force search with an independent
//! point–triangle distance (plane projection with barycentric test, else the nearest edge).

use proptest::prelude::*;
use rbf_mesh::{TriMesh, WindingTree, read_mesh};

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn segment_distance(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let ab = sub(b, a);
    let t = (dot(sub(p, a), ab) / dot(ab, ab).max(1e-300)).clamp(0.0, 1.0);
    let q = [a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]];
    dot(sub(p, q), sub(p, q)).sqrt()
}

fn triangle_distance(p: [f64; 3], [a, b, c]: [[f64; 3]; 3]) -> f64 {
    let n = cross(sub(b, a), sub(c, a));
    let nn = dot(n, n);
    if nn > 0.0 {
        let h = dot(sub(p, a), n) / nn;
        let q = [p[0] - h * n[0], p[1] - h * n[1], p[2] - h * n[2]];
        // q inside when it is on the inner side of every edge.
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|&(u, v)| dot(cross(sub(v, u), sub(q, u)), n) >= 0.0);
        if inside {
            return h.abs() * nn.sqrt();
        }
    }
    segment_distance(p, a, b)
        .min(segment_distance(p, b, c))
        .min(segment_distance(p, c, a))
}

fn brute(mesh: &TriMesh, p: [f64; 3]) -> f64 {
    (0..mesh.triangles().len())
        .map(|t| triangle_distance(p, mesh.corners(t)))
        .fold(f64::INFINITY, f64::min)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    #[test]
    fn nearest_point_matches_brute_force(
        x in -1.6..1.6f64, y in -0.6..0.6f64, z in -1.6..1.6f64,
    ) {
        let mesh = read_mesh(&crate::data("torus.obj")).unwrap();
        let tree = WindingTree::new(&mesh);
        let p = [x, y, z];
        let (q, d) = tree.closest_point(p, f64::INFINITY).unwrap();
        let expected = brute(&mesh, p);
        prop_assert!((d - expected).abs() <= 1e-12 * (1.0 + expected), "{d} vs {expected}");
        // The point returned is that far away and lies on the mesh.
        prop_assert!((dot(sub(q, p), sub(q, p)).sqrt() - d).abs() < 1e-12);
        prop_assert!(brute(&mesh, q) < 1e-12);
        // A search radius below the distance finds nothing; above it, the same answer.
        prop_assert!(tree.closest_point(p, 0.99 * expected).is_none());
        prop_assert_eq!(tree.closest_point(p, 1.01 * expected + 1e-12).map(|r| r.1), Some(d));
    }
}
