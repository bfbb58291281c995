//! The looks shared by traced scenes and rasterized meshes: Phong shading, the sky, the floor.

use crate::scene::Light;
use crate::vector::{Vec3, dot, normalize, scale, sub};

/// Phong shading of a surface of `colour` with outward normal `n`, seen along `direction`:
/// ambient, then diffuse and specular from every light that `lit` says reaches the point.
pub(crate) fn phong(
    colour: [f64; 3],
    n: Vec3,
    direction: Vec3,
    lights: &[Light],
    lit: impl Fn(usize) -> bool,
) -> [f64; 3] {
    let view = scale(direction, -1.0);
    let mut c = colour.map(|v| 0.15 * v);
    for (l, light) in lights.iter().enumerate() {
        if !lit(l) {
            continue;
        }
        let dir = normalize(light.direction);
        let diffuse = dot(n, dir).max(0.0);
        let mirror = sub(scale(n, 2.0 * dot(n, dir)), dir);
        let specular = dot(mirror, view).max(0.0).powi(40) * 0.35;
        for d in 0..3 {
            c[d] += light.intensity * (0.85 * diffuse * colour[d] + specular);
        }
    }
    c
}

/// The sky along a ray: `background[1]` at the horizon to `background[0]` overhead.
pub(crate) fn sky(direction: Vec3, background: [[f64; 3]; 2]) -> [f64; 3] {
    let [top, horizon] = background;
    let t = direction[1].clamp(0.0, 1.0);
    core::array::from_fn(|d| horizon[d] + (top[d] - horizon[d]) * t)
}

/// The floor's checker colour at p, squares of side `square`.
pub(crate) fn checker(p: Vec3, square: f64) -> [f64; 3] {
    let parity = ((p[0] / square).floor() + (p[2] / square).floor()) as i64 & 1;
    if parity == 0 { [0.85; 3] } else { [0.65; 3] }
}
