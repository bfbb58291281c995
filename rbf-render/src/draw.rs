//! Anti-aliased strokes on an image, by each pixel's distance to the shape.

use crate::image::Image;

/// A point in pixels (x right, y down).
pub(crate) type Pixel = (f64, f64);

/// Blends a shape over every pixel near it: `distance` gives a pixel centre's distance to the
/// shape's centre line, and the stroke is `width` pixels wide.
fn stroke(
    image: &mut Image,
    (lo, hi): (Pixel, Pixel),
    width: f64,
    colour: [f32; 3],
    distance: impl Fn(Pixel) -> f64,
) {
    let pad = width + 1.0;
    let x0 = (lo.0 - pad).floor().max(0.0) as i64;
    let x1 = (hi.0 + pad).ceil().min(f64::from(image.width())) as i64;
    let y0 = (lo.1 - pad).floor().max(0.0) as i64;
    let y1 = (hi.1 + pad).ceil().min(f64::from(image.height())) as i64;
    for y in y0..y1 {
        for x in x0..x1 {
            let d = distance((x as f64 + 0.5, y as f64 + 0.5));
            let coverage = (0.5 * width + 0.5 - d).clamp(0.0, 1.0);
            if coverage > 0.0 {
                image.blend(x, y, colour, coverage as f32);
            }
        }
    }
}

/// A line segment from a to b.
pub(crate) fn segment(image: &mut Image, a: Pixel, b: Pixel, width: f64, colour: [f32; 3]) {
    let lo = (a.0.min(b.0), a.1.min(b.1));
    let hi = (a.0.max(b.0), a.1.max(b.1));
    stroke(image, (lo, hi), width, colour, |p| {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let length2 = dx * dx + dy * dy;
        let t = if length2 > 0.0 {
            (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / length2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        ((p.0 - a.0 - t * dx).powi(2) + (p.1 - a.1 - t * dy).powi(2)).sqrt()
    });
}

/// A circle of `radius` around c.
pub(crate) fn ring(image: &mut Image, c: Pixel, radius: f64, width: f64, colour: [f32; 3]) {
    let lo = (c.0 - radius, c.1 - radius);
    let hi = (c.0 + radius, c.1 + radius);
    stroke(image, (lo, hi), width, colour, |p| {
        (((p.0 - c.0).powi(2) + (p.1 - c.1).powi(2)).sqrt() - radius).abs()
    });
}
