//! The film: per-pixel sums of radiance samples, resolved to PNG (8-bit sRGB) or EXR (linear).

use crate::math::Color;
use std::path::Path;

/// Accumulated radiance: a sum and a sample count per pixel, row-major from the top left.
///
/// Sums are f64, added in sample order, so a pixel's value does not depend on how its
/// samples were split into passes.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    pub(crate) sum: Vec<[f64; 3]>,
    pub(crate) count: Vec<u32>,
    spp: u32,
}

/// An image that cannot be written.
#[derive(Debug, thiserror::Error)]
pub enum FilmError {
    /// The name ends in neither `.png` nor `.exr`.
    #[error("{0}: unsupported image format (use a name ending in .png or .exr)")]
    UnsupportedFormat(String),
    /// Encoding or writing failed.
    #[error("{path}: cannot write the image: {source}")]
    Write {
        /// The file.
        path: String,
        /// Why.
        source: image::ImageError,
    },
}

/// Linear to sRGB transfer function (IEC 61966-2-1), for values in [0, 1].
#[inline]
pub fn srgb_encode(linear: f32) -> f32 {
    if linear <= 0.003_130_8 {
        12.92 * linear
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    }
}

impl Film {
    /// An empty film of `width` × `height` pixels.
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Film {
            width,
            height,
            sum: vec![[0.0; 3]; n],
            count: vec![0; n],
            spp: 0,
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

    /// Samples per pixel rendered so far (including any dropped as non-finite).
    pub fn spp(&self) -> u32 {
        self.spp
    }

    pub(crate) fn set_spp(&mut self, spp: u32) {
        self.spp = spp;
    }

    /// Empties the film.
    pub fn clear(&mut self) {
        self.sum.fill([0.0; 3]);
        self.count.fill(0);
        self.spp = 0;
    }

    /// The mean radiance of pixel (x, y); black before any sample.
    pub fn pixel(&self, x: u32, y: u32) -> Color {
        let i = (y * self.width + x) as usize;
        let n = self.count[i].max(1) as f64;
        let s = self.sum[i];
        Color::new((s[0] / n) as f32, (s[1] / n) as f32, (s[2] / n) as f32)
    }

    /// Mean radiance of every pixel, row-major.
    pub fn pixels(&self) -> impl Iterator<Item = Color> + '_ {
        (0..self.height).flat_map(move |y| (0..self.width).map(move |x| self.pixel(x, y)))
    }

    /// The image for display: radiance scaled by 2^exposure, clamped, sRGB encoded.
    pub fn to_srgb8(&self, exposure: f32) -> image::RgbImage {
        let scale = exposure.exp2();
        let mut img = image::RgbImage::new(self.width, self.height);
        for (px, c) in img.pixels_mut().zip(self.pixels()) {
            let c = c * scale;
            *px = image::Rgb(c.to_array().map(|v| {
                let v = if v.is_finite() {
                    v.clamp(0.0, 1.0)
                } else {
                    0.0
                };
                (srgb_encode(v) * 255.0 + 0.5) as u8
            }));
        }
        img
    }

    /// The linear radiance image (no exposure, no clamping), for EXR.
    pub fn to_linear(&self) -> image::Rgb32FImage {
        let mut img = image::Rgb32FImage::new(self.width, self.height);
        for (px, c) in img.pixels_mut().zip(self.pixels()) {
            *px = image::Rgb(c.to_array());
        }
        img
    }

    /// Writes the film: `.png` as 8-bit sRGB with `exposure`, `.exr` as linear radiance.
    pub fn save(&self, path: &Path, exposure: f32) -> Result<(), FilmError> {
        let name = path.display().to_string();
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        let written = match ext.as_deref() {
            Some("png") => self
                .to_srgb8(exposure)
                .save_with_format(path, image::ImageFormat::Png),
            Some("exr") => self
                .to_linear()
                .save_with_format(path, image::ImageFormat::OpenExr),
            _ => return Err(FilmError::UnsupportedFormat(name)),
        };
        written.map_err(|source| FilmError::Write { path: name, source })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_curve_endpoints_and_midtone() {
        assert_eq!(srgb_encode(0.0), 0.0);
        assert!((srgb_encode(1.0) - 1.0).abs() < 1e-6);
        // Linear 0.2140 is the sRGB mid-grey 0.5.
        assert!((srgb_encode(0.214_041) - 0.5).abs() < 1e-4);
    }

    #[test]
    fn exposure_scales_before_clamping() {
        let mut f = Film::new(1, 1);
        f.sum[0] = [0.25, 0.5, 2.0];
        f.count[0] = 1;
        let px = f.to_srgb8(1.0).get_pixel(0, 0).0;
        assert_eq!(px, [188, 255, 255]);
    }
}
