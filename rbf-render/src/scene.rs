//! A scene of solids over a ground plane, lit by directional lights, rendered by sphere
//! tracing with Phong shading, hard shadows and mirror reflections.

use std::time::Instant;

use rayon::prelude::*;
use rbf_core::ScalarField;

use crate::RenderError;
use crate::camera::{Camera, Ray};
use crate::csg::Csg;
use crate::image::{Image, check_size};
use crate::shade::{Light, RenderSettings, checker, default_lights, phong, sky};
use crate::tracer::{TraceCounts, Tracer};
use rbf_core::vec3::{Vec3, along, dot, normalize, scale, sub};

/// One solid in a scene: a CSG expression over the models, with its colour and reflectivity.
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    /// The solid: one model, or a union, intersection or difference of models by index.
    pub shape: Csg,
    /// Linear RGB in [0, 1].
    pub colour: [f64; 3],
    /// Fraction of light mirrored, in [0, 1].
    pub reflectivity: f64,
}

impl Object {
    /// A matte object of a colour from the palette, by index.
    ///
    /// ```
    /// use rbf_render::{Csg, Object};
    /// let o = Object::new(Csg::Model(0), 1);
    /// assert_eq!(o.reflectivity, 0.0);
    /// ```
    pub fn new(shape: Csg, index: usize) -> Self {
        const PALETTE: [[f64; 3]; 6] = [
            [0.80, 0.36, 0.18],
            [0.20, 0.45, 0.80],
            [0.30, 0.70, 0.30],
            [0.85, 0.70, 0.20],
            [0.60, 0.30, 0.70],
            [0.25, 0.70, 0.70],
        ];
        Self {
            shape,
            colour: PALETTE[index % PALETTE.len()],
            reflectivity: 0.0,
        }
    }
}

/// Work and time of a render, and whether its steps were proved safe.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderStats {
    /// Rays traced (camera, shadow and reflection rays, per solid).
    pub rays: u64,
    /// Points where models were evaluated.
    pub evaluations: u64,
    /// Seconds preparing the solids (bounds per cell).
    pub prepare_seconds: f64,
    /// Seconds tracing and shading.
    pub trace_seconds: f64,
    /// Whether every solid was stepped by proved bounds.
    pub guaranteed: bool,
}

/// Pixels whose colour differs from a neighbour's by more than this (linear RGB, any channel)
/// are traced again with `samples` × `samples` rays, unless both show the same smooth surface.
const EDGE: f64 = 0.02;

/// Neighbouring pixels on one object whose normals are this close (cosine of the angle) show
/// a smooth surface: their colours change smoothly between them, and extra rays would change
/// the pixel by little (measured on a 10⁵-centre model at 512 × 512: no channel by more than
/// 2 of 255, where the extra rays took a third of the render's time).
const SMOOTH: f64 = 0.995;

/// What a camera ray showed: an object (by index) with the outward normal there, or anything
/// else (sky, floor).
type Seen = Option<(usize, Vec3)>;

/// What a ray hit first: nothing, the floor or an object (by index), with the distance along
/// the ray.
#[derive(Clone, Copy)]
enum Hit {
    Nothing,
    Ground(f64),
    Object(usize, f64),
}

struct Renderer<'s, 'm> {
    tracers: Vec<Tracer<'s, 'm>>,
    objects: &'s [Object],
    settings: &'s RenderSettings,
    lights: Vec<Light>,
    ground: Option<(f64, f64)>,
    /// Offset of secondary rays off a surface.
    offset: f64,
}

/// Side of the square tiles of pixels traced together.
const TILE: usize = 32;

/// Renders the objects, made of the models, as the camera sees them.
///
/// ```
/// use rbf_core::{InterpolantView, Kernel};
/// use rbf_render::{Camera, Csg, Object, RenderSettings, render};
/// // f = 1 − r³: the unit sphere.
/// let sphere = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
/// let camera = Camera::orbit([-1.0; 3], [1.0; 3], 30.0, 20.0, 64, 48);
/// let settings = RenderSettings { samples: 1, ..Default::default() };
/// let (image, stats) = render(&[sphere], &[Object::new(Csg::Model(0), 0)], &camera, &settings).unwrap();
/// assert_eq!((image.width(), image.height()), (64, 48));
/// assert!(stats.evaluations > 0);
/// ```
pub fn render<F: ScalarField<3>>(
    models: &[F],
    objects: &[Object],
    camera: &Camera,
    settings: &RenderSettings,
) -> Result<(Image, RenderStats), RenderError> {
    check_size(camera.width, camera.height)?;
    check_scene(models.len(), objects, settings)?;
    let start = Instant::now();
    let fields = fields(models);
    let tracers = tracers(&fields, objects, settings, camera.width.max(camera.height));
    let prepare_seconds = start.elapsed().as_secs_f64();
    render_with(tracers, objects, camera, settings, prepare_seconds)
}

/// [`render`] with a camera aimed at what it will show: `frame` gets the box [`surface_bounds`]
/// gives and returns the camera, of `width` × `height` pixels. Where the render's
/// lattice is the one [`surface_bounds`] uses (at 512 pixels, for example), its cells are
/// estimated once instead of twice: on a 10⁵-centre model that is 1.5 of 11 seconds.
///
/// ```
/// use rbf_core::{InterpolantView, Kernel};
/// use rbf_render::{Camera, Csg, Object, RenderSettings, render_framed};
/// let sphere = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
/// let settings = RenderSettings { samples: 1, ..Default::default() };
/// let (image, _, camera) = render_framed(&[sphere], &[Object::new(Csg::Model(0), 0)], &settings,
///     (64, 48), |lo, hi| Camera::orbit(lo, hi, 30.0, 20.0, 64, 48)).unwrap();
/// assert_eq!((image.width(), image.height(), camera.width), (64, 48, 64));
/// ```
pub fn render_framed<F: ScalarField<3>>(
    models: &[F],
    objects: &[Object],
    settings: &RenderSettings,
    (width, height): (u32, u32),
    frame: impl FnOnce([f64; 3], [f64; 3]) -> Camera,
) -> Result<(Image, RenderStats, Camera), RenderError> {
    check_size(width, height)?;
    check_scene(models.len(), objects, settings)?;
    let start = Instant::now();
    let side = width.max(height);
    if settings.cells_for(side) != settings.cells_for(0) {
        let (lo, hi) = surface_bounds(models, objects, settings)?;
        let camera = frame(lo, hi);
        let (image, stats) = render(models, objects, &camera, settings)?;
        return Ok((image, stats, camera));
    }
    let fields = fields(models);
    let tracers = tracers(&fields, objects, settings, side);
    let (lo, hi) = occupied(&tracers)?;
    let camera = frame(lo, hi);
    if settings.cells_for(camera.width.max(camera.height)) != settings.cells_for(side) {
        // A camera of another size than announced: its own lattice.
        let (image, stats) = render(models, objects, &camera, settings)?;
        return Ok((image, stats, camera));
    }
    let prepare_seconds = start.elapsed().as_secs_f64();
    let (image, stats) = render_with(tracers, objects, &camera, settings, prepare_seconds)?;
    Ok((image, stats, camera))
}

/// The objects' shapes name existing models, and the samples per pixel are 1 to 16.
fn check_scene(
    models: usize,
    objects: &[Object],
    settings: &RenderSettings,
) -> Result<(), RenderError> {
    if objects.is_empty() {
        return Err(RenderError::NoObjects);
    }
    for o in objects {
        o.shape.validate(models)?;
    }
    if !(1..=16).contains(&settings.samples) {
        return Err(RenderError::Samples(settings.samples));
    }
    Ok(())
}

/// One tracer per object, with its sampled band, for an image of `side` pixels at most.
fn tracers<'s, 'm>(
    fields: &'s [&'m dyn ScalarField<3>],
    objects: &'s [Object],
    settings: &RenderSettings,
    side: u32,
) -> Vec<Tracer<'s, 'm>> {
    objects
        .iter()
        .map(|o| {
            Tracer::new(
                fields,
                &o.shape,
                settings.cells_for(side),
                settings.lipschitz,
                true,
            )
        })
        .collect()
}

/// The box of the cells, over all tracers, that can hold surface.
fn occupied(tracers: &[Tracer<'_, '_>]) -> Result<([f64; 3], [f64; 3]), RenderError> {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for t in tracers {
        if let Some((a, b)) = t.occupied_bounds() {
            for d in 0..3 {
                lo[d] = lo[d].min(a[d]);
                hi[d] = hi[d].max(b[d]);
            }
        }
    }
    if lo[0] > hi[0] {
        return Err(RenderError::NoSurface);
    }
    Ok((lo, hi))
}

/// The image of prepared tracers, one per object.
fn render_with(
    tracers: Vec<Tracer<'_, '_>>,
    objects: &[Object],
    camera: &Camera,
    settings: &RenderSettings,
    prepare_seconds: f64,
) -> Result<(Image, RenderStats), RenderError> {
    let guaranteed = tracers.iter().all(Tracer::guaranteed);
    let band_samples: u64 = tracers.iter().map(|t| t.band_samples() as u64).sum();
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for t in &tracers {
        // The floor goes under the surface itself, not under the traced box.
        let (a, b) = t.occupied_bounds().unwrap_or_else(|| t.bounds());
        for d in 0..3 {
            lo[d] = lo[d].min(a[d]);
            hi[d] = hi[d].max(b[d]);
        }
    }
    let size = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
    let renderer = Renderer {
        lights: settings
            .lights
            .clone()
            .unwrap_or_else(|| default_lights(camera)),
        ground: settings.ground.then_some((lo[1], size / 6.0)),
        // Secondary rays start well beyond the distance at which a tracer calls a hit.
        offset: tracers
            .iter()
            .map(|t| 20.0 * t.epsilon)
            .fold(1e-4 * size, f64::max),
        tracers,
        objects,
        settings,
    };
    let start = Instant::now();
    let (width, height) = (camera.width as usize, camera.height as usize);
    // One ray through each pixel's centre, a square tile at a time: the points that one batch
    // evaluates lie close together, so a far field finds few centres near them (a row of the
    // image spans the whole object; measured on a 10⁵-centre model at 512 × 512: tracing took
    // 10.7 s by rows).
    let tiles_x = width.div_ceil(TILE);
    #[allow(clippy::type_complexity)]
    let tiles: Vec<(usize, Vec<[f64; 3]>, Vec<Seen>, TraceCounts)> = (0..tiles_x
        * height.div_ceil(TILE))
        .into_par_iter()
        .map(|tile| {
            let mut counts = TraceCounts::default();
            let (x0, y0) = ((tile % tiles_x) * TILE, (tile / tiles_x) * TILE);
            let rays: Vec<Ray> = (y0..(y0 + TILE).min(height))
                .flat_map(|y| (x0..(x0 + TILE).min(width)).map(move |x| (x, y)))
                .map(|(x, y)| camera.ray(x as f64 + 0.5, y as f64 + 0.5))
                .collect();
            let (colours, seen) = renderer.radiance_seen(&rays, settings.reflections, &mut counts);
            (tile, colours, seen, counts)
        })
        .collect();
    let mut counts = TraceCounts::default();
    let mut colours: Vec<[f64; 3]> = vec![[0.0; 3]; width * height];
    let mut seen: Vec<Seen> = vec![None; width * height];
    for (tile, tile_colours, tile_seen, c) in tiles {
        let (x0, y0) = ((tile % tiles_x) * TILE, (tile / tiles_x) * TILE);
        let w = (x0 + TILE).min(width) - x0;
        for (k, (colour, what)) in tile_colours.into_iter().zip(tile_seen).enumerate() {
            colours[(y0 + k / w) * width + x0 + k % w] = colour;
            seen[(y0 + k / w) * width + x0 + k % w] = what;
        }
        counts.rays += c.rays;
        counts.evaluations += c.evaluations;
    }
    // Anti-aliasing: s × s rays in each pixel that differs from a neighbour, unless both show
    // the same smooth surface (with shadows or mirrors, colour can change sharply there too).
    let s = settings.samples;
    if s > 1 {
        let plain = !settings.shadows && settings.reflections == 0;
        let smooth = |i: usize, j: usize| match (seen[i], seen[j]) {
            (Some((a, m)), Some((b, n))) => plain && a == b && dot(m, n) >= SMOOTH,
            _ => false,
        };
        let differs = |i: usize, j: usize| {
            (0..3).any(|d| (colours[i][d] - colours[j][d]).abs() > EDGE) && !smooth(i, j)
        };
        let mut edges: Vec<usize> = (0..width * height)
            .filter(|&i| {
                let (x, y) = (i % width, i / width);
                (x > 0 && differs(i, i - 1))
                    || (x + 1 < width && differs(i, i + 1))
                    || (y > 0 && differs(i, i - width))
                    || (y + 1 < height && differs(i, i + width))
            })
            .collect();
        // A tile's edge pixels are traced together, as its pixels were: the points a batch
        // evaluates lie close together, and few batches are tiny.
        let tile_of = |i: usize| (i / width / TILE) * tiles_x + (i % width) / TILE;
        edges.sort_by_key(|&i| (tile_of(i), i));
        let groups: Vec<&[usize]> = edges.chunk_by(|&a, &b| tile_of(a) == tile_of(b)).collect();
        let refined: Vec<(Vec<[f64; 3]>, TraceCounts)> = groups
            .par_iter()
            .map(|chunk| {
                let mut counts = TraceCounts::default();
                let mut rays = Vec::with_capacity(chunk.len() * (s * s) as usize);
                for &i in chunk.iter() {
                    let (x, y) = ((i % width) as f64, (i / width) as f64);
                    for j in 0..s {
                        for k in 0..s {
                            rays.push(camera.ray(
                                x + (f64::from(k) + 0.5) / f64::from(s),
                                y + (f64::from(j) + 0.5) / f64::from(s),
                            ));
                        }
                    }
                }
                let samples = renderer.radiance(&rays, settings.reflections, &mut counts);
                let per = (s * s) as usize;
                let means = samples
                    .chunks(per)
                    .map(|c| {
                        let mut sum = [0.0; 3];
                        for v in c {
                            for d in 0..3 {
                                sum[d] += v[d] / per as f64;
                            }
                        }
                        sum
                    })
                    .collect();
                (means, counts)
            })
            .collect();
        for (chunk, (means, c)) in groups.iter().zip(refined) {
            for (&i, mean) in chunk.iter().zip(means) {
                colours[i] = mean;
            }
            counts.rays += c.rays;
            counts.evaluations += c.evaluations;
        }
    }
    let pixels: Vec<[f32; 3]> = colours.iter().map(|c| c.map(|v| v as f32)).collect();
    let stats = RenderStats {
        prepare_seconds,
        guaranteed,
        rays: counts.rays,
        evaluations: counts.evaluations + band_samples,
        trace_seconds: start.elapsed().as_secs_f64(),
    };
    Ok((
        Image::from_pixels(camera.width, camera.height, pixels),
        stats,
    ))
}

/// The box of the cells, over all objects, that can hold surface (by the bounds of
/// `settings.lipschitz`): a tight box around what [`render`] will show, for aiming a camera.
///
/// ```
/// use rbf_core::{InterpolantView, Kernel};
/// use rbf_render::{Csg, Object, RenderSettings, surface_bounds};
/// let sphere = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
/// let (lo, hi) = surface_bounds(&[sphere], &[Object::new(Csg::Model(0), 0)],
///     &RenderSettings::default()).unwrap();
/// assert!(lo.iter().all(|&v| v < -1.0 && v > -1.3) && hi.iter().all(|&v| v > 1.0 && v < 1.3));
/// ```
pub fn surface_bounds<F: ScalarField<3>>(
    models: &[F],
    objects: &[Object],
    settings: &RenderSettings,
) -> Result<([f64; 3], [f64; 3]), RenderError> {
    if objects.is_empty() {
        return Err(RenderError::NoObjects);
    }
    for o in objects {
        o.shape.validate(models.len())?;
    }
    let fields = fields(models);
    let tracers: Vec<Tracer<'_, '_>> = objects
        .iter()
        .map(|o| {
            Tracer::new(
                &fields,
                &o.shape,
                settings.cells_for(0),
                settings.lipschitz,
                false,
            )
        })
        .collect();
    occupied(&tracers)
}

/// Where each ray first meets the solid `shape` (distance along the ray), by the same sphere
/// tracer as [`render`]: for picking points on a surface.
///
/// ```
/// use rbf_core::{InterpolantView, Kernel};
/// use rbf_render::{Csg, Ray, RenderSettings, first_hits};
/// let sphere = InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
/// let ray = Ray { origin: [0.0, 0.0, 5.0], direction: [0.0, 0.0, -1.0] };
/// let hits = first_hits(&[sphere], &Csg::Model(0), &[ray], &RenderSettings::default()).unwrap();
/// assert!((hits[0].unwrap() - 4.0).abs() < 1e-9);
/// ```
pub fn first_hits<F: ScalarField<3>>(
    models: &[F],
    shape: &Csg,
    rays: &[Ray],
    settings: &RenderSettings,
) -> Result<Vec<Option<f64>>, RenderError> {
    shape.validate(models.len())?;
    let fields = fields(models);
    let tracer = Tracer::new(
        &fields,
        shape,
        settings.cells_for(0),
        settings.lipschitz,
        true,
    );
    let limits = vec![f64::INFINITY; rays.len()];
    Ok(tracer.trace(rays, &limits, &mut TraceCounts::default()))
}

impl Renderer<'_, '_> {
    /// The nearest hit of each ray (the solids and the ground), with the solid's outward normal
    /// where tracing found it.
    fn nearest(&self, rays: &[Ray], counts: &mut TraceCounts) -> (Vec<Hit>, Vec<Option<Vec3>>) {
        let mut hits = vec![Hit::Nothing; rays.len()];
        let mut found = vec![None; rays.len()];
        let mut best = vec![f64::INFINITY; rays.len()];
        if let Some((height, _)) = self.ground {
            for (i, r) in rays.iter().enumerate() {
                if r.direction[1] < 0.0 && r.origin[1] > height {
                    let t = (height - r.origin[1]) / r.direction[1];
                    hits[i] = Hit::Ground(t);
                    best[i] = t;
                }
            }
        }
        for (k, tracer) in self.tracers.iter().enumerate() {
            let (traced, normals) = tracer.trace_with_normals(rays, &best, counts);
            for (i, (hit, normal)) in traced.into_iter().zip(normals).enumerate() {
                if let Some(t) = hit
                    && t < best[i]
                {
                    best[i] = t;
                    hits[i] = Hit::Object(k, t);
                    found[i] = normal;
                }
            }
        }
        (hits, found)
    }

    /// Whether each ray meets a solid before `limit`.
    fn blocked(&self, rays: &[Ray], counts: &mut TraceCounts) -> Vec<bool> {
        let mut blocked = vec![false; rays.len()];
        let limits = vec![f64::INFINITY; rays.len()];
        for tracer in &self.tracers {
            for (b, hit) in blocked.iter_mut().zip(tracer.trace(rays, &limits, counts)) {
                *b |= hit.is_some();
            }
        }
        blocked
    }

    /// The light arriving along each ray.
    fn radiance(&self, rays: &[Ray], depth: u32, counts: &mut TraceCounts) -> Vec<[f64; 3]> {
        self.radiance_seen(rays, depth, counts).0
    }

    /// [`Renderer::radiance`], with what each ray showed.
    fn radiance_seen(
        &self,
        rays: &[Ray],
        depth: u32,
        counts: &mut TraceCounts,
    ) -> (Vec<[f64; 3]>, Vec<Seen>) {
        let (hits, found) = self.nearest(rays, counts);
        let mut seen: Vec<Seen> = vec![None; rays.len()];
        // Surface points: position, outward normal, colour, reflectivity.
        let mut surfaces: Vec<(usize, Vec3, Vec3, [f64; 3], f64)> = Vec::new();
        let mut out: Vec<[f64; 3]> = rays.iter().map(|r| self.sky(r)).collect();
        // Each solid's normals at its hits that tracing did not give, evaluated together.
        let mut normals: Vec<std::vec::IntoIter<Vec3>> = (0..self.tracers.len())
            .map(|k| {
                let points: Vec<Vec3> = hits
                    .iter()
                    .zip(rays)
                    .zip(&found)
                    .filter_map(|((hit, ray), normal)| match *hit {
                        Hit::Object(o, t) if o == k && normal.is_none() => {
                            Some(along(ray.origin, ray.direction, t))
                        }
                        _ => None,
                    })
                    .collect();
                if points.is_empty() {
                    Vec::new().into_iter()
                } else {
                    counts.evaluations += points.len() as u64;
                    self.tracers[k].normals(&points).into_iter()
                }
            })
            .collect();
        for (i, ((hit, ray), normal)) in hits.iter().zip(rays).zip(&found).enumerate() {
            match *hit {
                Hit::Nothing => {}
                Hit::Ground(t) => {
                    let p = along(ray.origin, ray.direction, t);
                    surfaces.push((i, p, [0.0, 1.0, 0.0], self.checker(p), 0.0));
                }
                Hit::Object(k, t) => {
                    let p = along(ray.origin, ray.direction, t);
                    let mut n = match normal {
                        Some(n) => *n,
                        None => normals[k].next().unwrap_or([0.0, 1.0, 0.0]),
                    };
                    if dot(n, ray.direction) > 0.0 {
                        // Seen from inside (a cut-open solid): light the side we see.
                        n = scale(n, -1.0);
                    }
                    let o = &self.objects[k];
                    seen[i] = Some((k, n));
                    surfaces.push((i, p, n, o.colour, o.reflectivity));
                }
            }
        }
        // Shadows, light by light.
        let mut lit = vec![vec![true; surfaces.len()]; self.lights.len()];
        if self.settings.shadows {
            for (l, light) in self.lights.iter().enumerate() {
                let dir = normalize(light.direction);
                let shadow_rays: Vec<Ray> = surfaces
                    .iter()
                    .map(|s| Ray {
                        origin: along(s.1, s.2, self.offset),
                        direction: dir,
                    })
                    .collect();
                for (flag, b) in lit[l].iter_mut().zip(self.blocked(&shadow_rays, counts)) {
                    *flag = !b;
                }
            }
        }
        for (k, s) in surfaces.iter().enumerate() {
            let (i, _, n, colour, _) = *s;
            out[i] = phong(colour, n, rays[i].direction, &self.lights, |l| lit[l][k]);
        }
        // Mirror reflections.
        let mirrors: Vec<usize> = (0..surfaces.len())
            .filter(|&k| surfaces[k].4 > 0.0)
            .collect();
        if depth > 0 && !mirrors.is_empty() {
            let reflected: Vec<Ray> = mirrors
                .iter()
                .map(|&k| {
                    let (i, p, n, _, _) = surfaces[k];
                    let d = rays[i].direction;
                    Ray {
                        origin: along(p, n, self.offset),
                        direction: normalize(sub(d, scale(n, 2.0 * dot(n, d)))),
                    }
                })
                .collect();
            let colours = self.radiance(&reflected, depth - 1, counts);
            for (&k, c) in mirrors.iter().zip(colours) {
                let (i, _, _, _, r) = surfaces[k];
                for d in 0..3 {
                    out[i][d] = (1.0 - r) * out[i][d] + r * c[d];
                }
            }
        }
        (out, seen)
    }

    fn sky(&self, ray: &Ray) -> [f64; 3] {
        sky(ray.direction, self.settings.background)
    }

    fn checker(&self, p: Vec3) -> [f64; 3] {
        checker(p, self.ground.map_or(1.0, |g| g.1))
    }
}

/// The models as the tracer takes them.
fn fields<F: ScalarField<3>>(models: &[F]) -> Vec<&dyn ScalarField<3>> {
    models.iter().map(|m| m as &dyn ScalarField<3>).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rbf_core::{InterpolantView, Kernel};

    #[test]
    fn normals_found_while_tracing_are_the_surface_s() {
        // f = 1 − |x|³: the unit sphere, whose outward normal at p is p itself.
        let sphere =
            InterpolantView::new(Kernel::Cubic, &[[0.0; 3]], &[-1.0], 1.0, [0.0; 3]).unwrap();
        let models = [sphere];
        let fields = fields(&models);
        let settings = RenderSettings::default();
        let shape = Csg::Model(0);
        let tracer = Tracer::new(
            &fields,
            &shape,
            settings.cells_for(0),
            settings.lipschitz,
            true,
        );
        // Rays from a ring of eyes toward points spread over the sphere's middle.
        let rays: Vec<Ray> = (0..200)
            .map(|i| {
                let a = i as f64 * 0.7;
                let origin = [4.0 * a.cos(), 1.5 * (0.3 * a).sin(), 4.0 * a.sin()];
                let aim = [0.3 * (1.3 * a).cos(), 0.3 * (0.9 * a).sin(), 0.0];
                Ray {
                    origin,
                    direction: normalize(sub(aim, origin)),
                }
            })
            .collect();
        let limits = vec![f64::INFINITY; rays.len()];
        let (hits, normals) =
            tracer.trace_with_normals(&rays, &limits, &mut TraceCounts::default());
        for ((ray, hit), normal) in rays.iter().zip(&hits).zip(&normals) {
            let p = along(
                ray.origin,
                ray.direction,
                hit.expect("every ray meets the sphere"),
            );
            let n = normal.expect("the band's Newton steps give the normal");
            let exact = normalize(p);
            // The gradient is taken up to 10⁻³ of a fine cell from the hit (fine cells are
            // about 1/50 here), so the normal may turn by that times the curvature (1).
            let gap = dot(sub(n, exact), sub(n, exact)).sqrt();
            assert!(
                gap < 1e-4,
                "normal {n:?} at {p:?}, {gap:e} from the sphere's"
            );
        }
    }
}
