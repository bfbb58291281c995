//! A pinhole camera: rays through pixels, and points back to pixels.

use rbf_core::vec3::{Vec3, add, cross, dot, norm, normalize, scale, sub};

/// A ray: origin and unit direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Start of the ray, in world coordinates (the camera's eye for a primary ray).
    pub origin: [f64; 3],
    /// Unit direction.
    pub direction: [f64; 3],
}

/// A perspective camera. `fov_degrees` is the vertical field of view; pixel (0, 0) is the top
/// left corner of the image.
///
/// ```
/// use rbf_render::Camera;
/// // Looking at the unit cube from the default orbit position.
/// let camera = Camera::orbit([-1.0; 3], [1.0; 3], 30.0, 20.0, 320, 240);
/// let ray = camera.ray(160.0, 120.0); // the centre of the image
/// let to_target: Vec<f64> = (0..3).map(|d| camera.target[d] - camera.eye[d]).collect();
/// let along: f64 = (0..3).map(|d| ray.direction[d] * to_target[d]).sum();
/// let length = to_target.iter().map(|x| x * x).sum::<f64>().sqrt();
/// assert!((along - length).abs() < 1e-9); // straight at the target
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Position of the camera's pinhole, in the models' coordinates.
    pub eye: [f64; 3],
    /// The point at the centre of the image.
    pub target: [f64; 3],
    /// Which way is up (need not be orthogonal to the view direction).
    pub up: [f64; 3],
    /// Vertical field of view in degrees.
    pub fov_degrees: f64,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

/// The camera's orthonormal frame and the screen's half-extent at unit distance.
struct Frame {
    forward: Vec3,
    right: Vec3,
    up: Vec3,
    half_height: f64,
    half_width: f64,
}

impl Camera {
    /// A camera on an orbit around the box [lo, hi]: looking at its centre from `azimuth`
    /// degrees around +y (0 looks along −z) and `elevation` degrees above the xz plane, far
    /// enough that the box's bounding sphere fills the view, with a 40° field of view.
    pub fn orbit(
        lo: [f64; 3],
        hi: [f64; 3],
        azimuth: f64,
        elevation: f64,
        width: u32,
        height: u32,
    ) -> Self {
        let fov_degrees: f64 = 40.0;
        let target = scale(add(lo, hi), 0.5);
        let radius = 0.5 * norm(sub(hi, lo)).max(1e-12);
        // The narrower of the two fields of view must hold the sphere.
        let half = (0.5 * fov_degrees.to_radians()).tan();
        let aspect = f64::from(width.max(1)) / f64::from(height.max(1));
        let narrow = half.min(half * aspect).atan();
        let distance = radius / narrow.sin() * 1.02;
        let (a, e) = (azimuth.to_radians(), elevation.to_radians());
        let direction = [e.cos() * a.sin(), e.sin(), e.cos() * a.cos()];
        Self {
            eye: add(target, scale(direction, distance)),
            target,
            up: [0.0, 1.0, 0.0],
            fov_degrees,
            width,
            height,
        }
    }

    fn frame(&self) -> Frame {
        let forward = normalize(sub(self.target, self.eye));
        let mut right = cross(forward, self.up);
        if norm(right) < 1e-12 {
            // Looking straight along `up`: any perpendicular will do.
            right = cross(forward, [1.0, 0.0, 0.0]);
            if norm(right) < 1e-12 {
                right = cross(forward, [0.0, 0.0, 1.0]);
            }
        }
        let right = normalize(right);
        let up = cross(right, forward);
        let half_height = (0.5 * self.fov_degrees.to_radians()).tan();
        let aspect = f64::from(self.width.max(1)) / f64::from(self.height.max(1));
        Frame {
            forward,
            right,
            up,
            half_height,
            half_width: half_height * aspect,
        }
    }

    /// The ray through the image point (x, y), in pixels from the top left corner (pixel
    /// centres are at half-integers).
    pub fn ray(&self, x: f64, y: f64) -> Ray {
        let f = self.frame();
        let sx = (2.0 * x / f64::from(self.width.max(1)) - 1.0) * f.half_width;
        let sy = (1.0 - 2.0 * y / f64::from(self.height.max(1))) * f.half_height;
        let direction = normalize(add(f.forward, add(scale(f.right, sx), scale(f.up, sy))));
        Ray {
            origin: self.eye,
            direction,
        }
    }

    /// Where p appears in the image: (x, y) in pixels and its depth along the view direction;
    /// `None` for points behind the camera.
    ///
    /// ```
    /// use rbf_render::Camera;
    /// let camera = Camera::orbit([-1.0; 3], [1.0; 3], 0.0, 0.0, 100, 100);
    /// let (x, y, _) = camera.project(camera.target).unwrap();
    /// assert!((x - 50.0).abs() < 1e-9 && (y - 50.0).abs() < 1e-9);
    /// ```
    pub fn project(&self, p: [f64; 3]) -> Option<(f64, f64, f64)> {
        let f = self.frame();
        let v = sub(p, self.eye);
        let depth = dot(v, f.forward);
        if !(depth > 0.0) {
            return None;
        }
        let sx = dot(v, f.right) / (depth * f.half_width);
        let sy = dot(v, f.up) / (depth * f.half_height);
        Some((
            (sx + 1.0) * 0.5 * f64::from(self.width),
            (1.0 - sy) * 0.5 * f64::from(self.height),
            depth,
        ))
    }
}
