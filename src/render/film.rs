//! The film: per-pixel sums of radiance samples, resolved to PNG (8-bit sRGB) or EXR (linear).

use crate::math::Color;
use crate::math::srgb::{srgb_encode_table, srgb8, srgb8_exact};
use crate::render::output::{image_format, write_file, write_pair};
use crate::tracer::{Met, Reach};
use std::path::Path;

/// The noise (as [`Film::noise`] estimates it) under which an image reads as clean: the
/// status bar says so, and it is each lecture slide's target.
pub const CLEAN_NOISE: f32 = 0.02;

/// What a pixel has accumulated: the sum and count of its samples, and the same for the
/// samples of one half (`in_second_half`): the two halves give the noise estimate.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Accum {
    /// Sum of every sample, added in sample order.
    pub sum: [f64; 3],
    /// Sum of the samples in the second half.
    pub half_sum: [f64; 3],
    /// Samples summed (non-finite ones are dropped).
    pub count: u32,
    /// Samples of the second half summed.
    pub half_count: u32,
    /// Rays traced for this pixel's samples, of every kind: its cost.
    pub rays: u32,
    /// Sum of the squares of the samples' luminance, for the spread adaptive sampling
    /// reads (f32 is enough: the spread it must resolve grows with the count).
    pub luma_sq: f32,
}

// The size scene::MAX_PIXELS budgets for.
const _: () = assert!(std::mem::size_of::<Accum>() == 64);

/// Which half of a pixel's samples sample number `index` is in, for the noise estimate:
/// the octaves of sample numbers [2^(k−1), 2^k) go to the two halves in turn (k odd: the
/// second). An octave of Owen-scrambled Sobol samples is a stratified set of its own (a
/// shifted net, in every dimension), and so is each power-of-two run of it, so each half
/// is a union of stratified sets and their difference measures the error of stratified
/// sampling. Even and odd sample numbers, the obvious halves, are not: half a net taken
/// that way is no better spread than random points, and the estimate read 3–6 times the
/// true error of a Sobol image. For independent samples any split is as good.
#[inline]
pub(crate) fn in_second_half(index: u32) -> bool {
    // k = the bit length of the index: 0 for sample 0, 1 for 1, 2 for 2–3, 3 for 4–7.
    (u32::BITS - index.leading_zeros()) % 2 == 1
}

/// The luma of the mean of `count` samples summing to `sum`, scaled by `scale`, each
/// channel clipped to [0, 1] and sRGB encoded (Rec. 709 weights on the encoded values:
/// brightness as shown).
fn shown_luma(sum: [f64; 3], count: u32, scale: f64) -> f64 {
    let shown = |v: f64| srgb_encode_table((v * scale / count as f64) as f32) as f64;
    0.2126 * shown(sum[0]) + 0.7152 * shown(sum[1]) + 0.0722 * shown(sum[2])
}

impl Accum {
    /// Adds sample number `index` with radiance `c`.
    #[inline]
    pub fn add(&mut self, index: u32, c: Color) {
        self.luma_sq += luminance(c).powi(2);
        let c = c.to_array().map(f64::from);
        for (sum, v) in self.sum.iter_mut().zip(c) {
            *sum += v;
        }
        self.count += 1;
        if in_second_half(index) {
            for (sum, v) in self.half_sum.iter_mut().zip(c) {
                *sum += v;
            }
            self.half_count += 1;
        }
    }

    /// The pixel as shown: its mean scaled by `scale`, clipped to [0, 1], sRGB encoded, its
    /// Rec. 709 luma. `None` until each half has a sample, as for [`Accum::shown_error`],
    /// so that both count the same pixels.
    pub(crate) fn shown(&self, scale: f64) -> Option<f64> {
        let halves = self.half_count > 0 && self.count > self.half_count;
        halves.then(|| shown_luma(self.sum, self.count, scale))
    }

    /// The pixel as shown ([`Accum::shown`]) and the standard error of that, estimated
    /// from the difference of its two halves' means as shown: for halves of a and b
    /// samples of n, |A − B|·√(ab)/n (the error of the whole mean if each half's error
    /// falls as one over the square root of its count; |A − B|/2 for equal halves). `None`
    /// until each half has a sample.
    pub(crate) fn shown_error(&self, scale: f64) -> Option<(f64, f64)> {
        let (b, a) = (self.half_count, self.count - self.half_count);
        let shown = self.shown(scale)?;
        let first_sum = [0, 1, 2].map(|i| self.sum[i] - self.half_sum[i]);
        let (second, first) = (
            shown_luma(self.half_sum, b, scale),
            shown_luma(first_sum, a, scale),
        );
        let weight = (a as f64 * b as f64).sqrt() / self.count as f64;
        Some((shown, (second - first).abs() * weight))
    }

    /// The mean radiance; black before any sample.
    #[inline]
    pub fn mean(&self) -> Color {
        let n = self.count.max(1) as f64;
        Color::new(
            (self.sum[0] / n) as f32,
            (self.sum[1] / n) as f32,
            (self.sum[2] / n) as f32,
        )
    }
}

/// Rec. 709 luminance of linear RGB.
#[inline]
pub(crate) fn luminance(c: Color) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// What a pixel's samples were: how many it has taken (sample numbers 0 to `count` − 1,
/// non-finite ones included) and what they met that a parameter governs.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Taken {
    pub(crate) count: u32,
    pub(crate) met: Met,
}

/// Accumulated radiance per pixel, row-major from the top left.
///
/// Sums are f64, added in sample order, so a pixel's value does not depend on how its
/// samples were split into passes. Each pixel also keeps how many samples it has taken
/// and what they met (`Taken`): after a change of parameters only the pixels the change
/// reaches start again ([`Film::restart_reached`]), and a pass stopped half-way leaves
/// each pixel whole, with the samples it has.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    pub(crate) pixels: Vec<Accum>,
    pub(crate) taken: Vec<Taken>,
    // The samples every pixel has (some may have more).
    spp: u32,
    // Adaptive sampling: the pixels that receive no more samples (see `adaptive`).
    pub(crate) done: Vec<bool>,
}

/// An image that cannot be written.
#[derive(Debug, thiserror::Error)]
pub enum FilmError {
    /// The name ends in neither `.png` nor `.exr`.
    #[error("{0}: unsupported image format (use a name ending in .png or .exr)")]
    UnsupportedFormat(String),
    /// Encoding or writing failed.
    // `error`, not `source`: the message already says it, and a source would be said twice.
    #[error("{path}: cannot write the image: {error}")]
    Write {
        /// The file.
        path: String,
        /// Why.
        error: String,
    },
}

/// Linear radiance, row-major, to 8-bit sRGB RGBA after scaling by 2^exposure.
pub fn to_srgba8(pixels: &[Color], exposure: f32) -> Vec<u8> {
    let scale = exposure.exp2();
    let mut out = Vec::with_capacity(pixels.len() * 4);
    for c in pixels {
        let c = *c * scale;
        out.extend_from_slice(&[srgb8(c.x), srgb8(c.y), srgb8(c.z), 255]);
    }
    out
}

/// Writes linear radiance `pixels` (`width` × `height`, row-major): `.png` as 8-bit sRGB
/// after scaling by 2^exposure, `.exr` as linear radiance; with `sidecar` inside the image
/// (PNG iTXt, EXR header) and beside it as `NAME.json`, the two replaced as a pair.
pub fn write_image(
    path: &Path,
    width: u32,
    height: u32,
    pixels: &[Color],
    exposure: f32,
    sidecar: Option<&super::Sidecar>,
) -> Result<(), FilmError> {
    let name = path.display().to_string();
    let mismatch = || FilmError::UnsupportedFormat(format!("{name} (size mismatch)"));
    if pixels.len() != width as usize * height as usize {
        return Err(mismatch());
    }
    let bytes = match image_format(path).as_deref() {
        Some("png") => {
            let img = srgb_image(width, height, pixels, exposure).ok_or_else(mismatch)?;
            return write_png(path, &img, sidecar);
        }
        Some("exr") => {
            super::exr_file::exr_bytes(width, height, pixels, sidecar).map_err(|e| e.to_string())
        }
        _ => return Err(FilmError::UnsupportedFormat(name)),
    };
    let write = |error: String| FilmError::Write {
        path: name.clone(),
        error,
    };
    let bytes = bytes.map_err(write)?;
    write_with_sidecar(path, &bytes, sidecar).map_err(|e| write(e.to_string()))
}

/// Writes `img` as a PNG at `path`, with `sidecar` inside it and beside it (see
/// [`write_image`]).
pub fn write_png(
    path: &Path,
    img: &image::RgbImage,
    sidecar: Option<&super::Sidecar>,
) -> Result<(), FilmError> {
    let embedded = sidecar.map(super::Sidecar::embedded_json);
    let (w, h) = img.dimensions();
    super::png_file::png_bytes(w, h, false, img.as_raw(), embedded.as_deref())
        .map_err(|e| e.to_string())
        .and_then(|bytes| write_with_sidecar(path, &bytes, sidecar).map_err(|e| e.to_string()))
        .map_err(|error| FilmError::Write {
            path: path.display().to_string(),
            error,
        })
}

/// Writes an image's `bytes` at `path`, and `sidecar` beside it as a pair (see
/// [`write_pair`]).
fn write_with_sidecar(
    path: &Path,
    bytes: &[u8],
    sidecar: Option<&super::Sidecar>,
) -> std::io::Result<()> {
    match sidecar {
        Some(sidecar) => write_pair(
            path,
            bytes,
            &super::sidecar_path(path),
            sidecar.file_json()?.as_bytes(),
        ),
        None => write_file(path, bytes),
    }
}

impl Film {
    /// An empty film of `width` × `height` pixels.
    pub fn new(width: u32, height: u32) -> Self {
        Film {
            width,
            height,
            pixels: vec![Accum::default(); width as usize * height as usize],
            taken: vec![Taken::default(); width as usize * height as usize],
            spp: 0,
            done: vec![false; width as usize * height as usize],
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

    /// Samples per pixel rendered so far (including any dropped as non-finite): the
    /// samples every pixel has; after [`Film::restart_reached`] or a pass stopped half-way,
    /// some have more.
    pub fn spp(&self) -> u32 {
        self.spp
    }

    pub(crate) fn set_spp(&mut self, spp: u32) {
        self.spp = spp;
    }

    /// Empties the film, keeping its memory: it reads black, and the next pass starts each
    /// pixel afresh as it reaches it, so emptying costs only the pixels' counts (a drag
    /// empties it at every change).
    pub fn clear(&mut self) {
        self.spp = 0;
        self.taken.fill(Taken::default());
    }

    /// Starts again the pixels whose samples met what a change of parameters reaches
    /// (`reach`, see [`crate::tracer::reach`]): the next passes bring them back to the
    /// others' samples (and on), which keep their sums exactly. The film reads as before
    /// until each such pixel's first new sample. How many pixels start again; `behind`
    /// gets every pixel then under `floor` samples.
    pub fn restart_reached(&mut self, reach: &Reach, floor: u32, behind: &mut Vec<u32>) -> usize {
        let mut n = 0;
        behind.clear();
        for (p, t) in self.taken.iter_mut().enumerate() {
            if t.met.meets(reach) {
                *t = Taken::default();
                n += 1;
            }
            if t.count < floor {
                behind.push(p as u32);
            }
        }
        if n > 0 {
            self.spp = 0;
        }
        n
    }

    /// Empties the film and gives it a new size.
    pub fn resize(&mut self, width: u32, height: u32) {
        self.width = width;
        self.height = height;
        self.pixels.clear();
        self.pixels
            .resize(width as usize * height as usize, Accum::default());
        self.done.clear();
        self.done.resize(self.pixels.len(), false);
        self.taken.clear();
        self.taken.resize(self.pixels.len(), Taken::default());
        self.spp = 0;
    }

    /// Whether adaptive sampling may have decided on this film: some pixel is past its
    /// first decision's count, or stopped. Its decisions read the whole film, so a film
    /// decided on cannot keep part of itself through a change of parameters.
    pub fn decided(&self) -> bool {
        let first = super::adaptive::FIRST_CHECK;
        self.taken.iter().any(|t| t.count > first) || self.done.iter().any(|&d| d)
    }

    /// Whether adaptive sampling has stopped every pixel: more passes would trace nothing.
    pub fn all_done(&self) -> bool {
        self.spp > 0 && self.done.iter().all(|&d| d)
    }

    /// How many pixels adaptive sampling has stopped (0 while the film is empty).
    pub fn done_pixels(&self) -> usize {
        if self.spp == 0 {
            return 0;
        }
        self.done.iter().filter(|&&d| d).count()
    }

    /// The accumulators; none while the film is empty (they may hold an earlier image).
    fn accums(&self) -> &[Accum] {
        if self.spp == 0 { &[] } else { &self.pixels }
    }

    /// One pane of the A/B view: columns `x0` to `x1` (not included) of `other`, a film
    /// of the same size, in place of this film's.
    pub fn paste_columns(&mut self, other: &Film, x0: u32, x1: u32) {
        if (other.width, other.height) != (self.width, self.height) {
            return;
        }
        let w = self.width as usize;
        let x1 = (x1 as usize).min(w);
        let x0 = (x0 as usize).min(x1);
        for (row, theirs) in self.pixels.chunks_mut(w).zip(other.pixels.chunks(w)) {
            row[x0..x1].copy_from_slice(&theirs[x0..x1]);
        }
        for (row, theirs) in self.taken.chunks_mut(w).zip(other.taken.chunks(w)) {
            row[x0..x1].copy_from_slice(&theirs[x0..x1]);
        }
    }

    /// The mean radiance of pixel (x, y); black before any sample.
    pub fn pixel(&self, x: u32, y: u32) -> Color {
        self.accums()
            .get((y * self.width + x) as usize)
            .map_or(Color::ZERO, Accum::mean)
    }

    /// Rays traced per sample in every pixel, row-major: the cost of each pixel's tree.
    pub fn cost(&self) -> Vec<f32> {
        match self.accums() {
            [] => vec![0.0; self.pixels.len()],
            a => a
                .iter()
                .zip(&self.taken)
                .map(|(p, t)| p.rays as f32 / t.count.max(1) as f32)
                .collect(),
        }
    }

    /// Mean radiance of every pixel, row-major (black while the film is empty).
    pub fn pixels(&self) -> impl Iterator<Item = Color> + '_ {
        let empty = self.spp == 0;
        self.pixels
            .iter()
            .map(move |a| if empty { Color::ZERO } else { a.mean() })
    }

    /// The estimated noise of the image as shown: the standard error of each pixel's
    /// displayed value (scaled by 2^exposure, clipped to [0, 1], sRGB encoded), estimated
    /// from the difference of the means of its two halves of samples
    /// (`Accum::shown_error`), as an RMS over the image divided by the mean displayed
    /// brightness. Displayed, not linear: a highlight far above white is clipped and its
    /// noise cannot be seen, while a dark region's noise is (the sRGB curve is steep
    /// there). `None` before two samples per pixel.
    pub fn noise(&self, exposure: f32) -> Option<f32> {
        if self.spp < 2 {
            return None;
        }
        let scale = exposure.exp2() as f64;
        let (mut err2, mut total, mut n) = (0.0f64, 0.0f64, 0usize);
        for p in self.accums() {
            if let Some((shown, err)) = p.shown_error(scale) {
                err2 += err * err;
                total += shown;
                n += 1;
            }
        }
        (n > 0 && total > 0.0).then(|| ((err2 / n as f64).sqrt() / (total / n as f64)) as f32)
    }

    /// The image for display: radiance scaled by 2^exposure, clamped, sRGB encoded.
    pub fn to_srgb8(&self, exposure: f32) -> image::RgbImage {
        let pixels: Vec<Color> = self.pixels().collect();
        let image = srgb_image(self.width, self.height, &pixels, exposure);
        image.unwrap_or_else(|| image::RgbImage::new(self.width, self.height))
    }

    /// Writes the film: `.png` as 8-bit sRGB with `exposure`, `.exr` as linear radiance
    /// with `sidecar`'s parameters in its header.
    pub fn save(
        &self,
        path: &Path,
        exposure: f32,
        sidecar: Option<&super::Sidecar>,
    ) -> Result<(), FilmError> {
        let pixels: Vec<Color> = self.pixels().collect();
        write_image(path, self.width, self.height, &pixels, exposure, sidecar)
    }
}

/// Linear radiance (`width` × `height`, row-major) scaled by 2^exposure, as 8-bit sRGB;
/// `None` if the sizes disagree.
fn srgb_image(width: u32, height: u32, pixels: &[Color], exposure: f32) -> Option<image::RgbImage> {
    let scale = exposure.exp2();
    let bytes = pixels
        .iter()
        .flat_map(|c| (*c * scale).to_array().map(srgb8_exact))
        .collect();
    image::RgbImage::from_vec(width, height, bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::rng::{Pattern, SampleStream};
    use crate::math::srgb::srgb_encode;
    use glam::Vec2;

    #[test]
    fn exposure_scales_before_clamping() {
        let mut f = Film::new(1, 1);
        f.pixels[0].add(0, Color::new(0.25, 0.5, 2.0));
        f.set_spp(1);
        let px = f.to_srgb8(1.0).get_pixel(0, 0).0;
        assert_eq!(px, [188, 255, 255]);
    }

    #[test]
    fn noise_estimate_matches_the_standard_error_of_what_is_shown() {
        // Samples v + d in one half and v − d in the other: the half-means differ by 2d.
        // Where the display is nearly linear (sRGB's slope at 0.5 of full scale, over a
        // small d), the standard error of the shown value is 2d·s'(v)·√(ab)/n for halves of
        // a and b of n samples, relative to s(v).
        let (v, d) = (0.5f32, 0.001f32);
        let mut f = Film::new(4, 4);
        for p in &mut f.pixels {
            for i in 0..8 {
                p.add(
                    i,
                    Color::splat(if in_second_half(i) { v - d } else { v + d }),
                );
            }
        }
        f.set_spp(8);
        // Samples 1 and 4–7 are the second half: b = 5, a = 3.
        assert_eq!((0..8).filter(|&i| in_second_half(i)).count(), 5);
        let slope = (srgb_encode(v + d) - srgb_encode(v - d)) / (2.0 * d);
        let expected = 2.0 * d * slope * (15f32).sqrt() / 8.0 / srgb_encode(v);
        assert!((f.noise(0.0).unwrap() / expected - 1.0).abs() < 1e-3);
        // Two stops darker, the same samples are noisier as shown (sRGB is steeper there).
        assert!(f.noise(-2.0).unwrap() > f.noise(0.0).unwrap());
        f.set_spp(1);
        assert_eq!(f.noise(0.0), None);
    }

    /// The RMS over `pixels` pixels of the noise estimate and of the true error, for
    /// `spp` samples each of the pixel's coverage by an edge (a half-plane through it at an
    /// angle of its own), drawn by `pattern`.
    fn estimate_and_truth(pattern: Pattern, pixels: u32, spp: u32) -> (f64, f64) {
        let (mut est2, mut true2) = (0.0, 0.0);
        for pixel in 0..pixels {
            let angle = pixel as f32 * 2.399;
            let (n, c) = (
                Vec2::new(angle.cos(), angle.sin()),
                0.1 * (pixel % 7) as f32,
            );
            let inside = |p: Vec2| (p - Vec2::splat(0.5)).dot(n) < c;
            let mut a = Accum::default();
            for s in 0..spp {
                let p = SampleStream::with_pattern(pattern, spp, 5, pixel, s).next_2d();
                a.add(s, Color::splat(if inside(p) { 0.5 } else { 0.0 }));
            }
            // The covered fraction, on a fine grid.
            let k = 256;
            let grid = (0..k * k)
                .filter(|i| inside((Vec2::new((i % k) as f32, (i / k) as f32) + 0.5) / k as f32))
                .count();
            let exact = srgb_encode(0.5 * grid as f32 / (k * k) as f32) as f64;
            let (shown, err) = a.shown_error(1.0).unwrap();
            est2 += err * err;
            true2 += (shown - exact).powi(2);
        }
        (
            (est2 / pixels as f64).sqrt(),
            (true2 / pixels as f64).sqrt(),
        )
    }

    #[test]
    fn noise_estimate_reads_the_true_error_of_random_and_sobol_samples() {
        // 2000 pixels: the estimate's squared error has one degree of freedom a pixel, so
        // its RMS is within a few percent of its mean; 25 % is a wide margin for the
        // assumption the estimate makes (error falling as 1/√n within a half).
        let (est, truth) = estimate_and_truth(Pattern::Random, 2000, 16);
        assert!(
            (est / truth - 1.0).abs() < 0.25,
            "random: {est} against {truth}"
        );
        // Sobol samples' error falls faster than 1/√n, which the estimate assumes, so it
        // reads high; with halves that are stratified sets of their own, 1.6–1.9 times the
        // true error here (even against odd sample numbers read 3.3, 4.2 and 6.4 times it
        // at 16, 64 and 256 samples).
        for spp in [16, 64, 256] {
            let (est, truth) = estimate_and_truth(Pattern::Sobol, 2000, spp);
            let ratio = est / truth;
            assert!((1.0..2.2).contains(&ratio), "sobol {spp}: {ratio}");
        }
    }

    #[test]
    fn noise_in_a_highlight_clipped_to_white_does_not_count() {
        // A pixel whose samples swing between 5 and 50 shows white all the same.
        let mut f = Film::new(2, 1);
        for i in 0..8 {
            f.pixels[0].add(i, Color::splat(if i % 2 == 0 { 5.0 } else { 50.0 }));
            f.pixels[1].add(i, Color::splat(0.5));
        }
        f.set_spp(8);
        assert_eq!(f.noise(0.0), Some(0.0));
    }

    #[test]
    fn a_cleared_film_reads_black_and_its_next_pass_starts_afresh() {
        let scene = crate::scene::Scene::load("default").unwrap();
        let params = crate::params::Params {
            spp: 2,
            ..scene.params.clone()
        };
        let mut f = crate::render::render(&scene, &params, 16, 9, &())
            .unwrap()
            .0;
        f.clear();
        assert!(f.pixels().all(|c| c == Color::ZERO));
        assert!(f.cost().iter().all(|&c| c == 0.0));
        // Another seed: any trace of the first image would show.
        let params = crate::params::Params { seed: 1, ..params };
        let fresh = crate::render::render(&scene, &params, 16, 9, &())
            .unwrap()
            .0;
        crate::render::render_pass(&scene, &scene.camera, &params, &mut f, 2, &()).unwrap();
        assert!(
            f.pixels().eq(fresh.pixels()),
            "no trace of the earlier image"
        );
    }
}
