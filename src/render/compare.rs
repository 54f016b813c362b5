//! Two images compared, as pbrt's `imgtool diff` and tev's difference view compare them:
//! the mean squared error and the relative one over linear RGB, the RMS error of the
//! brightness as shown (the scale of the status bar's noise estimate), and a false-colour
//! image of where they differ.

use super::film::luminance;
use super::ramp::inferno;
use crate::math::Color;
use crate::math::srgb::{srgb_decode, srgb_encode};
use std::path::Path;

/// An image's pixels as linear RGB, row-major from the top left.
pub struct LinearImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The pixels.
    pub pixels: Vec<Color>,
}

/// Two images that cannot be compared.
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    /// The file is not an image raylab reads (PNG, EXR, or another the `image` crate
    /// decodes).
    #[error("{path}: cannot read the image: {error}")]
    Read {
        /// The file.
        path: String,
        /// Why.
        error: String,
    },
    /// The images are not the same size.
    #[error("{a} is {}x{} and {b} is {}x{}: images of one size only", .a_size.0, .a_size.1, .b_size.0, .b_size.1)]
    Size {
        /// The first image.
        a: String,
        /// Its size.
        a_size: (u32, u32),
        /// The second.
        b: String,
        /// Its size.
        b_size: (u32, u32),
    },
}

impl LinearImage {
    /// The image at `path` as linear RGB: an EXR's (or HDR's) values as they are, an 8- or
    /// 16-bit image's through the sRGB curve.
    pub fn read(path: &Path) -> Result<LinearImage, CompareError> {
        let error = |e: &dyn std::fmt::Display| CompareError::Read {
            path: path.display().to_string(),
            error: e.to_string(),
        };
        let image = image::ImageReader::open(path)
            .map_err(|e| error(&e))?
            .with_guessed_format()
            .map_err(|e| error(&e))?
            .decode()
            .map_err(|e| error(&e))?;
        let encoded = !matches!(
            image,
            image::DynamicImage::ImageRgb32F(_) | image::DynamicImage::ImageRgba32F(_)
        );
        let rgb = image.into_rgb32f();
        let decode = |v: f32| if encoded { srgb_decode(v) } else { v };
        Ok(LinearImage {
            width: rgb.width(),
            height: rgb.height(),
            pixels: rgb
                .pixels()
                .map(|p| Color::new(decode(p[0]), decode(p[1]), decode(p[2])))
                .collect(),
        })
    }
}

/// The relative MSE's guard against division by a black reference pixel, as pbrt-v4's
/// `imgtool` adds it: (a − b)² / (b² + 0.01).
const REL_MSE_EPSILON: f64 = 0.01;

/// How far an image is from a reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Metrics {
    /// Mean over pixels and channels of (a − b)², linear RGB.
    pub mse: f64,
    /// Mean over pixels and channels of (a − b)² / (b² + 0.01), linear RGB, b the
    /// reference.
    pub rel_mse: f64,
    /// √(mean (Ya − Yb)²) / mean Yb, Y the luminance as shown (each channel clamped to
    /// [0, 1] and sRGB-encoded, then Rec. 709 weights): the status bar's noise scale.
    pub rms_shown: f64,
    /// The largest |Ya − Yb| as shown, and its pixel (x, y).
    pub largest: (f64, u32, u32),
}

/// `a`'s difference from `reference` (the two must be the same size), shown at
/// `exposure` (stops: both scaled by 2^exposure before they are clamped and encoded).
pub fn compare(a: &LinearImage, reference: &LinearImage, exposure: f32) -> Metrics {
    let scale = exposure.exp2();
    let shown = |c: Color| shown(scale * c);
    let n = a.pixels.len().max(1) as f64;
    let (mut se, mut rel, mut shown_se, mut shown_sum) = (0.0, 0.0, 0.0, 0.0);
    let mut largest = (0.0, 0, 0);
    for (i, (p, r)) in a.pixels.iter().zip(&reference.pixels).enumerate() {
        for c in 0..3 {
            let d = (p[c] - r[c]) as f64;
            se += d * d;
            rel += d * d / ((r[c] as f64).powi(2) + REL_MSE_EPSILON);
        }
        let (ya, yb) = (shown(*p), shown(*r));
        shown_se += (ya - yb) * (ya - yb);
        shown_sum += yb;
        if (ya - yb).abs() > largest.0 {
            let w = a.width.max(1) as usize;
            largest = ((ya - yb).abs(), (i % w) as u32, (i / w) as u32);
        }
    }
    let mean = shown_sum / n;
    Metrics {
        mse: se / (3.0 * n),
        rel_mse: rel / (3.0 * n),
        rms_shown: if mean > 0.0 {
            (shown_se / n).sqrt() / mean
        } else {
            0.0
        },
        largest,
    }
}

/// The luminance of `c` as shown: each channel clamped to [0, 1] and sRGB-encoded.
fn shown(c: Color) -> f64 {
    let s = |v: f32| srgb_encode(v.clamp(0.0, 1.0));
    luminance(Color::new(s(c.x), s(c.y), s(c.z))) as f64
}

/// Where `a` and `reference` differ, in false colour ([`inferno`]): |Ya − Yb| as shown,
/// black at 0 through purple, red and orange to pale yellow at `scale` and above.
pub fn difference_image(a: &LinearImage, reference: &LinearImage, scale: f64) -> image::RgbImage {
    let pixels = a.pixels.iter().zip(&reference.pixels);
    let bytes = pixels
        .flat_map(|(p, r)| inferno(((shown(*p) - shown(*r)).abs() / scale.max(1e-12)) as f32))
        .collect();
    image::RgbImage::from_raw(a.width, a.height, bytes).unwrap_or_default()
}

/// The 99th percentile of |Ya − Yb| as shown: a false-colour scale that a few outliers do
/// not set.
pub fn percentile_99(a: &LinearImage, reference: &LinearImage) -> f64 {
    let mut d: Vec<f64> = a
        .pixels
        .iter()
        .zip(&reference.pixels)
        .map(|(p, r)| (shown(*p) - shown(*r)).abs())
        .collect();
    if d.is_empty() {
        return 0.0;
    }
    let k = (d.len() - 1) * 99 / 100;
    let (_, v, _) = d.select_nth_unstable_by(k, f64::total_cmp);
    *v
}

impl LinearImage {
    /// Checks that it (named `name`) is `size` (that of what `other` names): one line
    /// naming both where not.
    pub fn check_size(
        &self,
        name: &str,
        (other, size): (&str, (u32, u32)),
    ) -> Result<(), CompareError> {
        if (self.width, self.height) == size {
            return Ok(());
        }
        Err(CompareError::Size {
            a: name.to_string(),
            a_size: (self.width, self.height),
            b: other.to_string(),
            b_size: size,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat(value: f32, n: usize) -> LinearImage {
        LinearImage {
            width: n as u32,
            height: 1,
            pixels: vec![Color::splat(value); n],
        }
    }

    #[test]
    fn the_metrics_of_two_flat_images_are_their_closed_forms() {
        let (a, b) = (flat(0.5, 4), flat(0.25, 4));
        let m = compare(&a, &b, 0.0);
        // (0.5 − 0.25)² = 0.0625; over 0.25² + 0.01 = 0.0725.
        assert_eq!(m.mse, 0.0625);
        assert!((m.rel_mse - 0.0625 / 0.0725).abs() < 1e-12);
        let (ya, yb) = (srgb_encode(0.5) as f64, srgb_encode(0.25) as f64);
        assert!((m.rms_shown - (ya - yb) / yb).abs() < 1e-6, "{m:?}");
        assert_eq!(compare(&a, &a, 0.0).mse, 0.0);
        assert_eq!(compare(&a, &a, 1.0).rms_shown, 0.0);
        // Shown a stop brighter, 0.5 clips to white.
        let brighter = compare(&a, &b, 1.0);
        let (ya, yb) = (1.0, srgb_encode(0.5) as f64);
        assert!((brighter.rms_shown - (ya - yb) / yb).abs() < 1e-6);
        assert_eq!(brighter.mse, m.mse);
    }

    #[test]
    fn the_largest_difference_is_found_where_it_is() {
        let mut a = flat(0.2, 6);
        a.width = 3;
        a.height = 2;
        let mut b = LinearImage {
            pixels: a.pixels.clone(),
            ..a
        };
        b.pixels[4] = Color::splat(0.9);
        let m = compare(&b, &a, 0.0);
        assert_eq!((m.largest.1, m.largest.2), (1, 1));
        assert!(m.largest.0 > 0.3);
    }
}
