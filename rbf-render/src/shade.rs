//! The look shared by traced scenes and rasterized meshes: lights, samples, shadows, the sky
//! and the floor ([`RenderSettings`]), and Phong shading.

use rbf_core::vec3::{Vec3, add, cross, dot, normalize, scale, sub};

use crate::camera::Camera;
use crate::tracer::Lipschitz;

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

/// A light infinitely far away.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// Toward the light (any length).
    pub direction: [f64; 3],
    /// Brightness (1 is full).
    pub intensity: f64,
}

/// Anti-aliasing, shadows, reflections, floor, lights and ray stepping of a render.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    /// Rays per pixel along each axis (anti-aliasing): 2 traces 4 rays a pixel, in the
    /// pixels whose colour differs from a neighbour's and that do not show one smooth surface
    /// with it (the same object, normals within about 6°). With shadows or mirrors, and on the
    /// floor, colour alone decides.
    pub samples: u32,
    /// Trace toward each light for hard shadows.
    pub shadows: bool,
    /// Depth of mirror reflections (0: none).
    pub reflections: u32,
    /// A checkered floor under the scene.
    pub ground: bool,
    /// Lights; `None` puts one above and to the left of the camera.
    pub lights: Option<Vec<Light>>,
    /// Background at the top and at the horizon (linear RGB).
    pub background: [[f64; 3]; 2],
    /// Which bound on |∇f| sizes the ray steps: proved, estimated, or sampled; `Auto` by
    /// default.
    pub lipschitz: Lipschitz,
    /// Cells along the longest side of each solid's box; 0 (the default) picks 32, or for
    /// [`Lipschitz::Auto`] one per 16 pixels of the image's longer side, 8 to 64 (at most 64
    /// with Auto, 256 otherwise).
    pub cells: usize,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            samples: 2,
            shadows: true,
            reflections: 0,
            ground: true,
            lights: None,
            background: [[0.45, 0.60, 0.85], [0.92, 0.94, 0.97]],
            lipschitz: Lipschitz::Auto,
            cells: 0,
        }
    }
}

impl RenderSettings {
    /// The cells of a solid's box for an image whose longer side is `side` pixels (0: none).
    pub(crate) fn cells_for(&self, side: u32) -> usize {
        match (self.cells, side) {
            (0, side) if side > 0 && self.lipschitz == Lipschitz::Auto => {
                (side as usize / 16).clamp(8, 64)
            }
            (0, _) => 32,
            // The sampled band holds (4 × cells)³ samples at most: 64 keeps it within memory.
            (cells, _) if self.lipschitz == Lipschitz::Auto => cells.min(64),
            (cells, _) => cells.min(256),
        }
    }
}

/// A key light above and to the left of the camera.
pub(crate) fn default_lights(camera: &Camera) -> Vec<Light> {
    let forward = normalize(sub(camera.target, camera.eye));
    let right = normalize(cross(forward, camera.up));
    let up = cross(right, forward);
    let direction = add(
        add(scale(up, 1.0), scale(right, -0.6)),
        scale(forward, -0.5),
    );
    vec![Light {
        direction: normalize(direction),
        intensity: 1.0,
    }]
}
