//! Three-vectors as plain arrays: the few operations that meshes, rays and shading share. Not
//! part of the API that rbf-core promises (hidden from its docs); sibling crates use it so that
//! the workspace has one of these, not one per crate.

use crate::math::sqrt;

/// A point or direction in 3D.
pub type Vec3 = [f64; 3];

/// a + b.
#[inline]
pub fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// a − b.
#[inline]
pub fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// s·a.
#[inline]
pub fn scale(a: Vec3, s: f64) -> Vec3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// p + t·d: the point at parameter t on the ray from p along d.
#[inline]
pub fn along(p: Vec3, d: Vec3, t: f64) -> Vec3 {
    [p[0] + t * d[0], p[1] + t * d[1], p[2] + t * d[2]]
}

/// a · b.
#[inline]
pub fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// a × b.
#[inline]
pub fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// |a|.
#[inline]
pub fn norm(a: Vec3) -> f64 {
    sqrt(dot(a, a))
}

/// a / |a|, or a itself when it has no length.
///
/// ```
/// use rbf_core::vec3::normalize;
/// assert_eq!(normalize([0.0, 0.0, 2.0]), [0.0, 0.0, 1.0]);
/// assert_eq!(normalize([0.0; 3]), [0.0; 3]);
/// ```
#[inline]
pub fn normalize(a: Vec3) -> Vec3 {
    let n = norm(a);
    if n > 0.0 { scale(a, 1.0 / n) } else { a }
}
