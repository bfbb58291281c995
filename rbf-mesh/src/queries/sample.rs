//! Points spread over a mesh's surface in proportion to area.

use crate::TriMesh;

/// `count` points on the surface of `mesh`, spread in proportion to area: the i-th point falls
/// in the triangle at cumulative area (i + u) / count of the total, u random (stratified), at
/// a uniformly random place inside it. The same `seed` gives the same points. A mesh of zero
/// area gives none.
///
/// ```
/// use rbf_mesh::{TriMesh, sample_surface};
/// let points = sample_surface(&TriMesh::icosphere(3), 1000, 7);
/// assert_eq!(points.len(), 1000);
/// for p in &points {
///     let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
///     assert!(r > 0.99 && r <= 1.0 + 1e-12);
/// }
/// ```
pub fn sample_surface(mesh: &TriMesh, count: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut cumulative = Vec::with_capacity(mesh.triangles().len());
    let mut total = 0.0;
    for t in 0..mesh.triangles().len() {
        let a = mesh.area_vector(t);
        total += 0.5 * (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        cumulative.push(total);
    }
    if !(total > 0.0 && total.is_finite()) {
        return Vec::new();
    }
    let mut state = seed;
    let mut random = move || {
        // SplitMix64, top 53 bits as a float in [0, 1).
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..count)
        .map(|i| {
            let target = (i as f64 + random()) / count as f64 * total;
            let t = cumulative
                .partition_point(|&c| c <= target)
                .min(cumulative.len() - 1);
            let [a, b, c] = mesh.corners(t);
            // Uniform in the triangle: fold the unit square's upper half back.
            let (mut u, mut v) = (random(), random());
            if u + v > 1.0 {
                (u, v) = (1.0 - u, 1.0 - v);
            }
            core::array::from_fn(|d| a[d] + u * (b[d] - a[d]) + v * (c[d] - a[d]))
        })
        .collect()
}
