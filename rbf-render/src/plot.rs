//! Plots of 2D curves f = 0 with their constraints marked as in Turk & O'Brien (2002),
//! Figures 1, 4, 5: boundary constraints as circles, interior as +, exterior as −, normal
//! constraints as short spikes; optionally f as a colour map.

use rayon::prelude::*;
use rbf_core::{Constraint, ConstraintKind, InterpolantView};

use crate::RenderError;
use crate::draw::{Pixel, ring, segment};
use crate::image::{Image, check_size};

/// Image size, region, colour map and line width of a 2D plot.
#[derive(Clone, Debug, PartialEq)]
pub struct PlotSettings {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Shade the plane by f: warm inside, cool outside, stronger with |f|.
    pub colour_map: bool,
    /// The region shown; by default the curve's box (see
    /// [`rbf_core::InterpolantView::surface_box`]) and every constraint, with a margin,
    /// widened to the image's aspect ratio.
    pub bounds: Option<([f64; 2], [f64; 2])>,
    /// Width of the curve in pixels.
    pub line_width: f64,
}

impl Default for PlotSettings {
    fn default() -> Self {
        Self {
            width: 512,
            height: 512,
            colour_map: false,
            bounds: None,
            line_width: 2.5,
        }
    }
}

const CURVE: [f32; 3] = [0.02, 0.02, 0.02];
const BOUNDARY: [f32; 3] = [0.05, 0.20, 0.65];
const INTERIOR: [f32; 3] = [0.05, 0.45, 0.10];
const EXTERIOR: [f32; 3] = [0.70, 0.08, 0.05];

/// Plots the curve f = 0 and the constraints.
///
/// ```
/// use rbf_core::{Constraint, FitSettings, fit};
/// use rbf_render::{PlotSettings, plot_curve};
/// let constraints = [
///     Constraint::boundary([1.0, 0.0]),
///     Constraint::boundary([0.0, 1.0]),
///     Constraint::boundary([-1.0, 0.0]),
///     Constraint::boundary([0.0, -1.0]),
///     Constraint::interior([0.0, 0.0], 1.0),
/// ];
/// let f = fit(&constraints, &FitSettings::default()).unwrap().interpolant;
/// let settings = PlotSettings { width: 64, height: 64, ..Default::default() };
/// let image = plot_curve(&f.view(), &constraints, &settings).unwrap();
/// assert_eq!(image.width(), 64);
/// ```
pub fn plot_curve(
    f: &InterpolantView<'_, f64, 2>,
    constraints: &[Constraint<2>],
    settings: &PlotSettings,
) -> Result<Image, RenderError> {
    check_size(settings.width, settings.height)?;
    let (w, h) = (f64::from(settings.width), f64::from(settings.height));
    let (lo, hi) = settings
        .bounds
        .unwrap_or_else(|| default_bounds(f, constraints, w / h));
    if !(0..2).all(|d| hi[d] > lo[d] && lo[d].is_finite() && hi[d].is_finite()) {
        return Err(RenderError::PlotBounds { lo, hi });
    }
    let pixel = ((hi[0] - lo[0]) / w).max((hi[1] - lo[1]) / h);
    let to_world = |x: f64, y: f64| {
        [
            lo[0] + x / w * (hi[0] - lo[0]),
            hi[1] - y / h * (hi[1] - lo[1]),
        ]
    };
    let to_pixel = |p: [f64; 2]| -> Pixel {
        (
            (p[0] - lo[0]) / (hi[0] - lo[0]) * w,
            (hi[1] - p[1]) / (hi[1] - lo[1]) * h,
        )
    };
    // f and its distance to the curve (first order) at every pixel centre.
    let samples: Vec<(f64, f64)> = (0..settings.height)
        .into_par_iter()
        .flat_map_iter(|y| {
            (0..settings.width).map(move |x| {
                let p = to_world(f64::from(x) + 0.5, f64::from(y) + 0.5);
                let (v, g) = f.value_and_gradient(&p);
                let slope = (g[0] * g[0] + g[1] * g[1]).sqrt();
                let distance = if slope > 0.0 {
                    v.abs() / slope / pixel
                } else {
                    f64::INFINITY
                };
                (v, distance)
            })
        })
        .collect();
    let scale = samples
        .iter()
        .map(|s| s.0.abs())
        .fold(0.0, f64::max)
        .max(1e-300)
        / 3.0;
    let pixels = samples
        .iter()
        .map(|&(v, distance)| {
            let mut c = [1.0_f32; 3];
            if settings.colour_map {
                let strength = (1.0 - (-v.abs() / scale).exp()) as f32;
                let tint = if v > 0.0 {
                    [0.95, 0.45, 0.20]
                } else {
                    [0.25, 0.50, 0.95]
                };
                c = core::array::from_fn(|k| 1.0 + (tint[k] - 1.0) * strength * 0.8);
            }
            let coverage = (0.5 * settings.line_width + 0.5 - distance).clamp(0.0, 1.0) as f32;
            core::array::from_fn(|k| c[k] * (1.0 - coverage) + CURVE[k] * coverage)
        })
        .collect();
    let mut image = Image::from_pixels(settings.width, settings.height, pixels);
    let size = 5.0;
    for c in constraints {
        let at = to_pixel(c.position);
        match c.kind {
            ConstraintKind::Boundary => ring(&mut image, at, size, 1.6, BOUNDARY),
            // The paper's marks: + inside, − outside.
            ConstraintKind::Interior => {
                let bar = |(dx, dy): Pixel| ((at.0 - dx, at.1 - dy), (at.0 + dx, at.1 + dy));
                for (from, to) in [bar((size, 0.0)), bar((0.0, size))] {
                    segment(&mut image, from, to, 2.0, INTERIOR);
                }
            }
            ConstraintKind::Exterior => {
                segment(
                    &mut image,
                    (at.0 - size, at.1),
                    (at.0 + size, at.1),
                    2.0,
                    EXTERIOR,
                );
            }
            ConstraintKind::Normal => {
                ring(&mut image, at, size, 1.6, BOUNDARY);
                let n = c.normal;
                let length = (n[0] * n[0] + n[1] * n[1]).sqrt();
                if length > 0.0 {
                    // Outward, in pixels (y grows downward).
                    let tip = (at.0 + 20.0 * n[0] / length, at.1 - 20.0 * n[1] / length);
                    segment(&mut image, at, tip, 1.8, CURVE);
                }
            }
        }
    }
    Ok(image)
}

/// The curve's box and the constraints, with a margin, widened to `aspect` (width / height).
fn default_bounds(
    f: &InterpolantView<'_, f64, 2>,
    constraints: &[Constraint<2>],
    aspect: f64,
) -> ([f64; 2], [f64; 2]) {
    let (mut lo, mut hi) = f.surface_box(0.0);
    for c in constraints {
        for d in 0..2 {
            lo[d] = lo[d].min(c.position[d]);
            hi[d] = hi[d].max(c.position[d]);
        }
    }
    let centre = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])];
    let mut half = [0.55 * (hi[0] - lo[0]), 0.55 * (hi[1] - lo[1])];
    let side = half[0].max(half[1]).max(1e-12);
    half = half.map(|v| v.max(0.05 * side));
    if half[0] / half[1] < aspect {
        half[0] = half[1] * aspect;
    } else {
        half[1] = half[0] / aspect;
    }
    (
        [centre[0] - half[0], centre[1] - half[1]],
        [centre[0] + half[0], centre[1] + half[1]],
    )
}
