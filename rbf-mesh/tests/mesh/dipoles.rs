//! Winding numbers of oriented points through the cluster hierarchy, against direct sums.

use rbf_mesh::{DipoleTree, read_mesh, winding_numbers_exact};

use crate::data;

/// Spot's triangles taken as dipoles at their centroids (area vector as moment: an uneven
/// spread, dense at the eyes and sparse on the flanks): at probes along the normals one to
/// twenty mean spacings off the surface, and all over the box, the hierarchy's winding number is
/// within 0.03 of the direct sum over every dipole, and within 0.1 of the mesh's own (exact)
/// winding number where it is five spacings or more from every dipole.
#[test]
fn the_dipole_tree_agrees_with_direct_sums() {
    let mesh = read_mesh(&data("spot.obj")).unwrap();
    let (points, moments): (Vec<[f64; 3]>, Vec<[f64; 3]>) = (0..mesh.triangles().len())
        .map(|t| {
            let [a, b, c] = mesh.corners(t);
            let (u, v) = (sub(b, a), sub(c, a));
            let area = [
                0.5 * (u[1] * v[2] - u[2] * v[1]),
                0.5 * (u[2] * v[0] - u[0] * v[2]),
                0.5 * (u[0] * v[1] - u[1] * v[0]),
            ];
            (core::array::from_fn(|d| (a[d] + b[d] + c[d]) / 3.0), area)
        })
        .unzip();
    let total: f64 = moments.iter().map(|&m| crate::norm(m)).sum();
    let spacing = (total / points.len() as f64).sqrt();
    let mut probes = Vec::new();
    for (i, (p, m)) in points.iter().zip(&moments).enumerate().step_by(7) {
        let n = m.map(|c| c / crate::norm(*m).max(f64::MIN_POSITIVE));
        let t = spacing * (1.0 + (i % 20) as f64);
        let side = if i % 2 == 0 { 1.0 } else { -1.0 };
        probes.push(core::array::from_fn(|d| p[d] + side * t * n[d]));
    }
    for i in 0..500 {
        let f = |k: usize| ((i * k) as f64 * 0.618_034).fract() * 2.4 - 1.2;
        probes.push([f(1), f(7), f(13)]);
    }
    let tree = DipoleTree::new(&points, &moments);
    let direct = |q: [f64; 3]| {
        let mut sum = 0.0;
        for (p, m) in points.iter().zip(&moments) {
            let r = sub(*p, q);
            let r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
            if r2 > 0.0 {
                sum += (m[0] * r[0] + m[1] * r[1] + m[2] * r[2]) / (r2 * r2.sqrt());
            }
        }
        sum / (4.0 * std::f64::consts::PI)
    };
    let exact = winding_numbers_exact(&mesh, &probes);
    let mut worst: f64 = 0.0;
    for (q, w) in probes.iter().zip(exact) {
        let (fast, slow) = (tree.winding_number(*q), direct(*q));
        worst = worst.max((fast - slow).abs());
        assert!(
            (fast - slow).abs() < 0.03,
            "{q:?}: tree {fast}, direct {slow}"
        );
        let clear = points
            .iter()
            .map(|p| crate::norm(sub(*p, *q)))
            .fold(f64::INFINITY, f64::min);
        if clear > 5.0 * spacing {
            assert!((fast - w).abs() < 0.1, "{q:?}: tree {fast}, mesh {w}");
        }
    }
    assert!(worst > 0.0, "the tree summed everything directly");
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
