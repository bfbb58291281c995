//! RGB images in linear light, written as 8-bit sRGB PNG.

use crate::RenderError;

/// The largest side accepted, in pixels.
pub const MAX_SIDE: u32 = 16384;

/// An RGB image in linear light, row by row from the top.
///
/// ```
/// use rbf_render::Image;
/// let mut image = Image::new(4, 2, [0.0, 0.0, 0.0]).unwrap();
/// image.set(3, 1, [1.0, 0.5, 0.0]);
/// let png = image.to_png().unwrap();
/// assert_eq!(&png[1..4], b"PNG");
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    width: u32,
    height: u32,
    pixels: Vec<[f32; 3]>,
}

impl Image {
    /// An image of one colour; sides from 1 to [`MAX_SIDE`].
    pub fn new(width: u32, height: u32, colour: [f32; 3]) -> Result<Self, RenderError> {
        check_size(width, height)?;
        Ok(Self {
            width,
            height,
            pixels: vec![colour; width as usize * height as usize],
        })
    }

    /// An image from its pixels, row by row from the top.
    pub(crate) fn from_pixels(width: u32, height: u32, pixels: Vec<[f32; 3]>) -> Self {
        debug_assert_eq!(pixels.len(), width as usize * height as usize);
        Self {
            width,
            height,
            pixels,
        }
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The pixels, row by row from the top, in linear RGB.
    pub fn pixels(&self) -> &[[f32; 3]] {
        &self.pixels
    }

    /// The pixel at column x, row y.
    pub fn get(&self, x: u32, y: u32) -> [f32; 3] {
        self.pixels[y as usize * self.width as usize + x as usize]
    }

    /// Sets the pixel at column x, row y (ignored outside the image).
    pub fn set(&mut self, x: u32, y: u32, colour: [f32; 3]) {
        if x < self.width && y < self.height {
            self.pixels[y as usize * self.width as usize + x as usize] = colour;
        }
    }

    /// Blends `colour` over the pixel with coverage `alpha` in [0, 1].
    pub fn blend(&mut self, x: i64, y: i64, colour: [f32; 3], alpha: f32) {
        if x < 0 || y < 0 || x >= i64::from(self.width) || y >= i64::from(self.height) {
            return;
        }
        let a = alpha.clamp(0.0, 1.0);
        let p = &mut self.pixels[y as usize * self.width as usize + x as usize];
        for c in 0..3 {
            p[c] = p[c] * (1.0 - a) + colour[c] * a;
        }
    }

    /// Two images next to each other, `left` then `right`, on a white background where their
    /// heights differ.
    ///
    /// ```
    /// use rbf_render::Image;
    /// let a = Image::new(3, 2, [1.0; 3]).unwrap();
    /// let b = Image::new(4, 5, [0.0; 3]).unwrap();
    /// let both = Image::side_by_side(&a, &b).unwrap();
    /// assert_eq!((both.width(), both.height()), (7, 5));
    /// ```
    pub fn side_by_side(left: &Image, right: &Image) -> Result<Image, RenderError> {
        let mut out = Image::new(
            left.width + right.width,
            left.height.max(right.height),
            [1.0; 3],
        )?;
        for (image, dx) in [(left, 0), (right, left.width)] {
            for y in 0..image.height {
                for x in 0..image.width {
                    out.set(x + dx, y, image.get(x, y));
                }
            }
        }
        Ok(out)
    }

    /// Darkens by `factor` (0 black, 1 unchanged) every pixel whose centre, mapped onto the box
    /// `[lo, hi]` of a plane (x to the right, y up, as [`crate::plot_curve`] draws), satisfies
    /// `inside`: a region drawn under a plot.
    ///
    /// ```
    /// use rbf_render::Image;
    /// let mut image = Image::new(4, 2, [1.0; 3]).unwrap();
    /// image.darken_region(([0.0, 0.0], [4.0, 2.0]), 0.5, |p| p[0] < 2.0 && p[1] > 1.0);
    /// assert_eq!(image.get(0, 0), [0.5; 3]); // top left: x < 2, y > 1
    /// assert_eq!(image.get(0, 1), [1.0; 3]);
    /// assert_eq!(image.get(3, 0), [1.0; 3]);
    /// ```
    pub fn darken_region(
        &mut self,
        (lo, hi): ([f64; 2], [f64; 2]),
        factor: f32,
        inside: impl Fn([f64; 2]) -> bool,
    ) {
        let (w, h) = (f64::from(self.width), f64::from(self.height));
        for y in 0..self.height {
            for x in 0..self.width {
                let p = [
                    lo[0] + (f64::from(x) + 0.5) / w * (hi[0] - lo[0]),
                    hi[1] - (f64::from(y) + 0.5) / h * (hi[1] - lo[1]),
                ];
                if inside(p) {
                    let c = self.get(x, y);
                    self.set(x, y, c.map(|v| v * factor));
                }
            }
        }
    }

    /// 8-bit sRGB bytes, row by row.
    pub fn to_srgb8(&self) -> Vec<u8> {
        self.pixels
            .iter()
            .flat_map(|p| p.map(encode_srgb))
            .collect()
    }

    /// The image as a PNG file (8-bit sRGB).
    pub fn to_png(&self) -> Result<Vec<u8>, RenderError> {
        let mut bytes = Vec::new();
        let mut encoder = png::Encoder::new(&mut bytes, self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(&self.to_srgb8())?;
        writer.finish()?;
        Ok(bytes)
    }
}

/// Linear light in [0, 1] to an 8-bit sRGB value.
fn encode_srgb(v: f32) -> u8 {
    let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
    let s = if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0 + 0.5) as u8
}

/// Refuses sides of 0 or above [`MAX_SIDE`].
pub(crate) fn check_size(width: u32, height: u32) -> Result<(), RenderError> {
    if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
        return Err(RenderError::Size { width, height });
    }
    Ok(())
}
