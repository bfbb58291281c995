//! Polygon meshes drawn with a z-buffer, lit like the traced scenes, so that a mesh and its
//! implicit conversion can be put side by side.

use rayon::prelude::*;
use rbf_mesh::TriMesh;

use crate::RenderError;
use crate::camera::Camera;
use crate::image::{Image, check_size};
use crate::shade::{RenderSettings, default_lights};
use crate::shade::{checker, phong, sky};
use rbf_core::vec3::{add, cross, dot, normalize, scale, sub};

/// How a mesh's faces are shaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshStyle {
    /// One normal per triangle: facets show.
    Flat,
    /// Area-weighted vertex normals interpolated across each triangle.
    Smooth,
}

/// Renders a triangle mesh (counter-clockwise faces seen from outside) in `colour`, with the
/// lights, background, ground and anti-aliasing of `settings` (no shadows).
///
/// ```
/// use rbf_mesh::TriMesh;
/// use rbf_render::{Camera, MeshStyle, RenderSettings, render_mesh};
/// let mesh = TriMesh::new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
/// )
/// .unwrap();
/// let camera = Camera::orbit([0.0; 3], [1.0; 3], 30.0, 20.0, 64, 64);
/// let image = render_mesh(&mesh, &camera, MeshStyle::Flat, [0.8, 0.4, 0.2],
///     &RenderSettings::default()).unwrap();
/// assert_eq!(image.width(), 64);
/// ```
pub fn render_mesh(
    mesh: &TriMesh,
    camera: &Camera,
    style: MeshStyle,
    colour: [f64; 3],
    settings: &RenderSettings,
) -> Result<Image, RenderError> {
    check_size(camera.width, camera.height)?;
    let (positions, triangles) = (mesh.positions(), mesh.triangles());
    let s = settings.samples.clamp(1, 16);
    let big = Camera {
        width: camera.width * s,
        height: camera.height * s,
        ..*camera
    };
    check_size(big.width.min(16384), big.height.min(16384))?;
    let (bw, bh) = (big.width as usize, big.height as usize);
    // Per sample: depth, triangle, perspective-correct barycentrics.
    let mut depth = vec![f64::INFINITY; bw * bh];
    let mut face = vec![u32::MAX; bw * bh];
    let mut weights = vec![[0.0_f32; 3]; bw * bh];
    for (t, tri) in triangles.iter().enumerate() {
        let corners = tri.map(|v| positions[v as usize]);
        let Some(p) = corners
            .iter()
            .map(|&c| big.project(c))
            .collect::<Option<Vec<_>>>()
        else {
            continue; // behind the camera, in part
        };
        let area = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1);
        if area == 0.0 || !area.is_finite() {
            continue;
        }
        let x0 = p
            .iter()
            .map(|q| q.0)
            .fold(f64::INFINITY, f64::min)
            .floor()
            .max(0.0) as usize;
        let x1 = (p
            .iter()
            .map(|q| q.0)
            .fold(f64::NEG_INFINITY, f64::max)
            .ceil()
            .max(0.0) as usize)
            .min(bw);
        let y0 = p
            .iter()
            .map(|q| q.1)
            .fold(f64::INFINITY, f64::min)
            .floor()
            .max(0.0) as usize;
        let y1 = (p
            .iter()
            .map(|q| q.1)
            .fold(f64::NEG_INFINITY, f64::max)
            .ceil()
            .max(0.0) as usize)
            .min(bh);
        for y in y0..y1 {
            for x in x0..x1 {
                let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
                let edge = |a: usize, b: usize| {
                    ((p[b].0 - p[a].0) * (py - p[a].1) - (px - p[a].0) * (p[b].1 - p[a].1)) / area
                };
                let b = [edge(1, 2), edge(2, 0), edge(0, 1)];
                if b.iter().any(|&v| v < 0.0) {
                    continue;
                }
                // Perspective-correct: interpolate 1/depth linearly on screen.
                let inverse: f64 = (0..3).map(|k| b[k] / p[k].2).sum();
                let z = 1.0 / inverse;
                let at = y * bw + x;
                if z < depth[at] {
                    depth[at] = z;
                    face[at] = t as u32;
                    weights[at] = core::array::from_fn(|k| (b[k] / p[k].2 * z) as f32);
                }
            }
        }
    }
    let normals = match style {
        MeshStyle::Flat => None,
        MeshStyle::Smooth => Some(
            mesh.vertex_normals()
                .into_iter()
                .map(normalize)
                .collect::<Vec<_>>(),
        ),
    };
    let lights = settings
        .lights
        .clone()
        .unwrap_or_else(|| default_lights(camera));
    let (lo_y, size) = mesh_floor(mesh);
    let samples: Vec<[f64; 3]> = (0..bw * bh)
        .into_par_iter()
        .map(|at| {
            let (x, y) = ((at % bw) as f64 + 0.5, (at / bw) as f64 + 0.5);
            let ray = big.ray(x, y);
            if face[at] == u32::MAX {
                return background(&ray, settings, lo_y, size);
            }
            let t = face[at] as usize;
            let c = triangles[t].map(|v| positions[v as usize]);
            let n = match &normals {
                None => normalize(cross(sub(c[1], c[0]), sub(c[2], c[0]))),
                Some(n) => {
                    let w = weights[at];
                    let mut sum = [0.0; 3];
                    for k in 0..3 {
                        sum = add(sum, scale(n[triangles[t][k] as usize], f64::from(w[k])));
                    }
                    normalize(sum)
                }
            };
            let n = if dot(n, ray.direction) > 0.0 {
                scale(n, -1.0)
            } else {
                n
            };
            phong(colour, n, ray.direction, &lights, |_| true)
        })
        .collect();
    // Average each pixel's s × s samples.
    let (w, h) = (camera.width as usize, camera.height as usize);
    let s = s as usize;
    let pixels = (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            let mut sum = [0.0; 3];
            for j in 0..s {
                for k in 0..s {
                    sum = add(sum, samples[(y * s + j) * bw + x * s + k]);
                }
            }
            sum.map(|v| (v / (s * s) as f64) as f32)
        })
        .collect();
    Ok(Image::from_pixels(camera.width, camera.height, pixels))
}

/// The height of the floor under a mesh and the size of its checker squares.
fn mesh_floor(mesh: &TriMesh) -> (f64, f64) {
    let (lo, hi) = mesh.bounding_box();
    let size = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
    (lo[1], size.max(1e-12) / 6.0)
}

/// The sky, or the checkered floor at height `floor` when `settings.ground` is on.
fn background(ray: &crate::Ray, settings: &RenderSettings, floor: f64, square: f64) -> [f64; 3] {
    if settings.ground && ray.direction[1] < 0.0 && ray.origin[1] > floor {
        let t = (floor - ray.origin[1]) / ray.direction[1];
        let p = rbf_core::vec3::along(ray.origin, ray.direction, t);
        // The floor lit from above, as in the traced scenes.
        return checker(p, square).map(|grey| grey * (0.15 + 0.85 * 0.8));
    }
    sky(ray.direction, settings.background)
}
