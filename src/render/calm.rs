//! Calm frames: what the window shows of an image still on its way to its target, its
//! noise smoothed away where the scene's geometry says the light is one surface's.
//!
//! A drag on the distribution slides (soft shadows, depth of field, dispersion) restarts
//! the image at every step, so the window would show one sample per pixel (or per preview
//! block): speckle. The film is left as it is (snapshots, tev and the inspector read it,
//! and stay bit for bit what a render gives); the frame carries a second picture for the
//! screen, filtered by an edge-avoiding à-trous wavelet (Dammertz et al. 2010, with the
//! variance-guided luminance stop of Schied et al. 2017, "SVGF"):
//!
//! - five passes of the 3 × 3 kernel h = (1, 2, 1)/4, its taps 2^i apart in pass i (a
//!   reach of 31 pixels from 9 taps a pass: 5 × 5 taps cost three times as much and
//!   looked no calmer);
//! - a tap q counts for pixel p only on the same object, by the normals' agreement
//!   max(0, n_p·n_q)^32, and by depth, exp(−|z_p − z_q| / (2·|∇z_p|·2^i + 0.001·z_p)):
//!   what one eye ray through each pixel's centre meets ([`Guides`]);
//! - and by luminance, exp(−|l_p − l_q| / (4·σ_p)), σ_p the standard error of p's mean
//!   (blurred 3 × 3), so a noiseless edge (a hard shadow, a texture seen in focus) stays
//!   sharp and noise goes. A pixel's samples tell its spread from 4 on; before, it is the
//!   last image's (kept across a drag), raised where the frame's own values vary more
//!   than it says (a penumbra grown since), read so that an edge does not count;
//! - each pass carries the variance through: σ'² = Σ w²σ_q² / (Σ w)².
//!
//! Pixels whose neighbourhood has no spread are left exactly as they are: an image without
//! noise (a point light, a pinhole, mirrors and glass) is shown as rendered.

use super::{Film, PassObserver};
use crate::camera::Camera;
use crate::math::Color;
use crate::math::Vec3;
use crate::scene::Scene;
use glam::{Vec2, Vec4};
use rayon::prelude::*;

/// What one eye ray through each pixel's centre (a pinhole's, at the shutter's start)
/// meets: the edges the filter keeps.
#[derive(Clone, Debug)]
pub struct Guides {
    width: u32,
    height: u32,
    /// The object met, [`MISS`] where none.
    object: Vec<u32>,
    /// Its shading normal there, facing the eye (x, y, z), and the distance along the ray
    /// (w): one load for a tap.
    surface: Vec<Vec4>,
    /// The larger of the depth's changes to the next pixel across and down.
    slope: Vec<f32>,
}

/// No object met.
const MISS: u32 = u32::MAX;

/// Passes of the filter on a full-resolution frame.
const PASSES: u32 = 5;

/// The kernel's taps: the B-spline of degree 1 (1, 2, 1)/4.
const KERNEL: [f32; 3] = [0.25, 0.5, 0.25];

/// How many standard errors apart two luminances may be and still be averaged.
const SIGMA_LUMINANCE: f32 = 4.0;

/// The samples per pixel from which a film's spread is kept for the next generation.
const SPREAD_FROM: u32 = 4;

impl Guides {
    /// The guides of a `width` × `height` image of `scene` through `camera`.
    pub fn of(scene: &Scene, camera: &Camera, width: u32, height: u32) -> Guides {
        let frame = camera.pinhole(width as f32 / height.max(1) as f32);
        let n = width as usize * height as usize;
        let mut object = vec![MISS; n];
        let mut surface = vec![Vec4::new(0.0, 0.0, 0.0, f32::INFINITY); n];
        object
            .par_chunks_mut(width.max(1) as usize)
            .zip(surface.par_chunks_mut(width.max(1) as usize))
            .enumerate()
            .for_each(|(y, (object, surface))| {
                for x in 0..object.len() {
                    let film = Vec2::new(
                        (x as f32 + 0.5) / width as f32,
                        (y as f32 + 0.5) / height as f32,
                    );
                    let ray = frame.ray(film, Vec2::splat(0.5), 0.0);
                    if let Some(hit) = scene.intersect(&ray, f32::INFINITY) {
                        object[x] = hit.object;
                        let n = hit.surface.n_shade;
                        let n: Vec3 = if n.dot(ray.dir) > 0.0 { -n } else { n };
                        surface[x] = n.extend(hit.surface.t);
                    }
                }
            });
        let at = |x: u32, y: u32| surface[(y * width + x) as usize].w;
        let slope = (0..n)
            .map(|i| {
                let (x, y) = (i as u32 % width, i as u32 / width);
                let z = surface[i].w;
                let across = if x + 1 < width { at(x + 1, y) } else { z };
                let down = if y + 1 < height { at(x, y + 1) } else { z };
                let d = (across - z).abs().max((down - z).abs());
                if d.is_finite() { d } else { 0.0 }
            })
            .collect();
        Guides {
            width,
            height,
            object,
            surface,
            slope,
        }
    }

    /// Its size.
    pub(crate) fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }
}

/// Each pixel's spread: the variance of one sample's luminance, from the film's samples;
/// `None` before it has `SPREAD_FROM` per pixel. The engine keeps the last generation's
/// for the first frames of the next, which have too few samples to tell their own.
pub fn spread(film: &Film) -> Option<Vec<f32>> {
    (film.spp() >= SPREAD_FROM).then(|| film.pixels.par_iter().map(own_spread).collect())
}

/// A pixel's spread from its own samples (0 under two).
fn own_spread(a: &super::Accum) -> f32 {
    if a.count < 2 {
        return 0.0;
    }
    let n = a.count as f32;
    let l = super::film::luminance(a.mean());
    ((a.luma_sq - n * l * l) / (n - 1.0)).max(0.0)
}

/// The side of the cells a film is calmed in: each value of its calmed picture is a
/// 2 × 2 block's, stretched over the image as a preview's are. The filter's time is a
/// quarter of full resolution's, and two pixels of softness go unseen in a picture that
/// lasts until the image is clean.
pub const CALM_BLOCK: u32 = 2;

/// The filter's passes over cells of side `block` (a pass's reach in pixels doubles with
/// each level): 5 at full resolution, 4 at 2, down to 1.
fn passes_at(block: u32) -> u32 {
    PASSES.saturating_sub(block.max(1).ilog2()).max(1)
}

/// The film's picture calmed for the screen (see the module's doc), in cells of
/// [`CALM_BLOCK`]: `guides` of their grid, `spread` the last generation's ([`spread`]) for
/// pixels of few samples. `None` where nothing tells their noise, or once `observer` says
/// to stop (a newer image is wanted).
pub fn calm_film(
    film: &Film,
    guides: &Guides,
    spread: Option<&[f32]>,
    observer: &dyn PassObserver,
) -> Option<Vec<Color>> {
    let (w, h) = (film.width(), film.height());
    let grid = (w.div_ceil(CALM_BLOCK), h.div_ceil(CALM_BLOCK));
    if guides.size() != grid || spread.is_some_and(|s| s.len() != film.pixels.len()) {
        return None;
    }
    if film.spp() < 2 && spread.is_none() {
        return None;
    }
    let (means, variance) = cells(grid, CALM_BLOCK, (w, h), |p| {
        let a = &film.pixels[p];
        // A few samples' own spread is itself noisy (two alike in a penumbra read as
        // none): the last image's is steadier until there are more.
        let one = match spread {
            Some(s) if a.count < SPREAD_FROM => s[p],
            _ => own_spread(a),
        };
        (a.mean(), one / a.count.max(1) as f32)
    });
    let variance = if film.spp() < SPREAD_FROM {
        at_least_spatial(&means, variance, guides)
    } else {
        variance
    };
    calm(means, variance, guides, passes_at(CALM_BLOCK), observer)
}

/// A spread of a `width`-wide image at `block` × `block` cells: the mean of each cell's
/// pixels' (one sample's variance in a cell of one sample).
pub(crate) fn coarse_spread(spread: &[f32], width: u32, block: u32) -> Vec<f32> {
    let block = block.max(1);
    let width = width.max(1);
    let height = spread.len() as u32 / width;
    let (gw, gh) = (width.div_ceil(block), height.div_ceil(block));
    (0..gw * gh)
        .into_par_iter()
        .map(|c| {
            let (x0, y0) = ((c % gw) * block, (c / gw) * block);
            let (x1, y1) = ((x0 + block).min(width), (y0 + block).min(height));
            let (mut sum, mut k) = (0.0, 0.0);
            for y in y0..y1 {
                for x in x0..x1 {
                    sum += spread[(y * width + x) as usize];
                    k += 1.0;
                }
            }
            if k > 0.0 { sum / k } else { 0.0 }
        })
        .collect()
}

/// A preview's grid of one sample per `block` × `block` pixels calmed for the screen,
/// `guides` and `spread` (the last generation's, [`coarse_spread`]) of the grid's size;
/// `None` once `observer` says to stop.
pub(crate) fn calm_preview(
    grid: Vec<Color>,
    guides: &Guides,
    block: u32,
    spread: &[f32],
    observer: &dyn PassObserver,
) -> Option<Vec<Color>> {
    let (gw, gh) = guides.size();
    if grid.len() != (gw * gh) as usize || spread.len() != grid.len() {
        return None;
    }
    // A pass fewer than a film's at these cells: a preview lasts a frame of a drag, and
    // the drag's next level must not wait for it.
    let passes = passes_at(block).saturating_sub(1).max(1);
    let variance = at_least_spatial(&grid, spread.to_vec(), guides);
    calm(grid, variance, guides, passes, observer)
}

/// `variance`, raised where the values themselves vary more: the last image's spread
/// misses what a drag has moved since (a penumbra grown into a region that was lit, its
/// new speckle left as it was). A cell's spatial variance is the least over the four 3 × 3
/// windows that hold it in a corner, of the cells on its object there: a texture's or a
/// shadow's edge leaves one window flat, so it reads as no noise; noise fills all four.
fn at_least_spatial(values: &[Color], variance: Vec<f32>, guides: &Guides) -> Vec<f32> {
    let (w, h) = (guides.width as i64, guides.height as i64);
    let luma: Vec<f32> = values.iter().map(|c| super::film::luminance(*c)).collect();
    variance
        .into_par_iter()
        .enumerate()
        .map(|(p, v)| {
            let (x, y) = (p as i64 % w, p as i64 / w);
            let object = guides.object[p];
            let mut least = f32::INFINITY;
            for (sx, sy) in [(-1, -1), (1, -1), (-1, 1), (1, 1)] {
                let (mut sum, mut sum_sq, mut k) = (0.0f32, 0.0f32, 0.0f32);
                for dy in 0..3 {
                    for dx in 0..3 {
                        let (qx, qy) = (x + sx * dx, y + sy * dy);
                        if qx < 0 || qy < 0 || qx >= w || qy >= h {
                            continue;
                        }
                        let q = (qy * w + qx) as usize;
                        if guides.object[q] == object && luma[q].is_finite() {
                            sum += luma[q];
                            sum_sq += luma[q] * luma[q];
                            k += 1.0;
                        }
                    }
                }
                if k >= 4.0 {
                    let mean = sum / k;
                    least = least.min((sum_sq / k - mean * mean).max(0.0) * k / (k - 1.0));
                }
            }
            if least.is_finite() { v.max(least) } else { v }
        })
        .collect()
}

/// Each `block` × `block` cell of an image of `size` (a `grid` of them): the mean of its
/// pixels' values, and the variance of that mean (Σ v / k² over its k pixels), from what
/// `pixel` says of each (its value, the variance of its value).
fn cells(
    grid: (u32, u32),
    block: u32,
    size: (u32, u32),
    pixel: impl Fn(usize) -> (Color, f32) + Sync,
) -> (Vec<Color>, Vec<f32>) {
    let block = block.max(1);
    (0..grid.0 * grid.1)
        .into_par_iter()
        .map(|c| {
            let (x0, y0) = ((c % grid.0) * block, (c / grid.0) * block);
            let (x1, y1) = ((x0 + block).min(size.0), (y0 + block).min(size.1));
            let (mut sum, mut variance, mut k) = (Color::ZERO, 0.0, 0.0);
            for y in y0..y1 {
                for x in x0..x1 {
                    let (value, v) = pixel((y * size.0 + x) as usize);
                    sum += value;
                    variance += v;
                    k += 1.0;
                }
            }
            let k: f32 = if k > 0.0 { k } else { 1.0 };
            (sum / k, variance / (k * k))
        })
        .unzip()
}

/// `passes` passes of the filter over `means` (see the module's doc); `None` once
/// `observer` says to stop (asked for each row).
fn calm(
    means: Vec<Color>,
    variance: Vec<f32>,
    guides: &Guides,
    passes: u32,
    observer: &dyn PassObserver,
) -> Option<Vec<Color>> {
    let w = guides.width as usize;
    // Colour and luminance in one value a tap loads at once; what is not finite as black
    // (neither a film's means nor a preview's are).
    let with_luma = |c: &Color| {
        let c = if c.is_finite() { *c } else { Color::ZERO };
        Vec4::new(c.x, c.y, c.z, super::film::luminance(c))
    };
    let mut colour: Vec<Vec4> = means.par_iter().map(with_luma).collect();
    let mut variance = variance;
    let mut next_colour = colour.clone();
    let mut next_variance = variance.clone();
    for pass in 0..passes {
        let step = 1usize << pass;
        let blurred = blur3(&variance, guides.width as i64, guides.height as i64);
        let taps = Taps {
            colour: &colour,
            variance: &variance,
            blurred: &blurred,
            guides,
            step,
        };
        next_colour
            .par_chunks_mut(w)
            .zip(next_variance.par_chunks_mut(w))
            .enumerate()
            .for_each(|(y, (colour_row, variance_row))| {
                if !observer.keep_going() {
                    return;
                }
                for (x, (c, v)) in colour_row.iter_mut().zip(variance_row).enumerate() {
                    (*c, *v) = taps.filter(x, y);
                }
            });
        if !observer.keep_going() {
            return None;
        }
        std::mem::swap(&mut colour, &mut next_colour);
        std::mem::swap(&mut variance, &mut next_variance);
    }
    Some(colour.iter().map(|c| Color::new(c.x, c.y, c.z)).collect())
}

/// What one pass of the filter reads.
struct Taps<'a> {
    /// Each pixel's colour (x, y, z) and luminance (w).
    colour: &'a [Vec4],
    variance: &'a [f32],
    blurred: &'a [f32],
    guides: &'a Guides,
    step: usize,
}

impl Taps<'_> {
    /// Pixel (x, y) filtered, and its variance.
    #[inline]
    fn filter(&self, x: usize, y: usize) -> (Vec4, f32) {
        let g = self.guides;
        let (w, h) = (g.width as usize, g.height as usize);
        let p = y * w + x;
        let sigma = self.blurred[p].sqrt();
        if sigma.is_nan() || sigma <= 0.0 {
            return (self.colour[p], self.variance[p]);
        }
        let to_luma = 1.0 / (SIGMA_LUMINANCE * sigma);
        let (lp, object, surface) = (self.colour[p].w, g.object[p], g.surface[p]);
        let step = self.step;
        // The depth stop's scale at this pass's tap distance (the centre's own depth is 0
        // apart, whatever its scale).
        let zp = surface.w;
        let to_depth = 1.0 / (2.0 * g.slope[p] * step as f32 + 1e-3 * zp);
        let normal = surface.truncate();
        let (mut sum, mut weights, mut spread) = (Vec4::ZERO, 0.0f32, 0.0f32);
        for (j, ky) in KERNEL.iter().enumerate() {
            let Some(qy) = (y + j * step).checked_sub(step).filter(|&q| q < h) else {
                continue;
            };
            for (i, kx) in KERNEL.iter().enumerate() {
                let Some(qx) = (x + i * step).checked_sub(step).filter(|&q| q < w) else {
                    continue;
                };
                let q = qy * w + qx;
                if g.object[q] != object {
                    continue;
                }
                let cq = self.colour[q];
                // One exponential for the luminance and depth stops together.
                let mut stop = (lp - cq.w).abs() * to_luma;
                let mut agree = kx * ky;
                if object != MISS {
                    let sq = g.surface[q];
                    stop += (zp - sq.w).abs() * to_depth;
                    // max(0, n_p·n_q)^32, by five squarings.
                    let mut n = normal.dot(sq.truncate()).max(0.0);
                    for _ in 0..5 {
                        n *= n;
                    }
                    agree *= n;
                }
                let wq = agree * fast_exp_neg(stop);
                sum += cq * wq;
                weights += wq;
                spread += wq * wq * self.variance[q];
            }
        }
        // (The centre tap always counts: weights > 0.)
        (sum / weights, spread / (weights * weights))
    }
}

/// e^−x for x ≥ 0, to within 0.03 % (0 beyond x = 30): a weight needs no more, and libm's
/// exp was a fifth of the filter's time (perf).
#[inline]
fn fast_exp_neg(x: f32) -> f32 {
    if x.is_nan() || x >= 30.0 {
        return 0.0;
    }
    // e^−x = 2^(−x·log2 e) = 2^−k · 2^−f, 2^−f on [0, 1) by a least-squares cubic
    // through 1 at 0 (its largest relative error 2.4e−4).
    let t = x * std::f32::consts::LOG2_E;
    // (t ≥ 0: truncation is the floor, without libm's call.)
    let k = t as i32;
    let f = t - k as f32;
    let frac = 1.0 + f * (-0.691_836_4 + f * (0.232_112_9 + f * -0.040_395_55));
    frac * f32::from_bits(((127 - k) as u32) << 23)
}

/// A 3 × 3 binomial blur of `v` (w × h): the variance a pass's luminance stop reads, its
/// own estimate steadied by its neighbours' (as SVGF does).
fn blur3(v: &[f32], w: i64, h: i64) -> Vec<f32> {
    const K: [f32; 3] = [0.25, 0.5, 0.25];
    (0..v.len())
        .into_par_iter()
        .map(|p| {
            let (x, y) = (p as i64 % w, p as i64 / w);
            let (mut sum, mut weights) = (0.0, 0.0);
            for (j, ky) in K.iter().enumerate() {
                for (i, kx) in K.iter().enumerate() {
                    let (qx, qy) = (x + i as i64 - 1, y + j as i64 - 1);
                    if qx >= 0 && qy >= 0 && qx < w && qy < h {
                        sum += kx * ky * v[(qy * w + qx) as usize];
                        weights += kx * ky;
                    }
                }
            }
            sum / weights
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Color;

    /// Guides of a `w` × `h` image: one object facing the eye at depth 1, except where
    /// `other` says a pixel is on a second object.
    fn flat(w: u32, h: u32, other: impl Fn(u32, u32) -> bool) -> Guides {
        let n = (w * h) as usize;
        Guides {
            width: w,
            height: h,
            object: (0..n as u32).map(|i| other(i % w, i / w) as u32).collect(),
            surface: vec![Vec4::new(0.0, 0.0, 1.0, 1.0); n],
            slope: vec![0.0; n],
        }
    }

    /// A deterministic stream of uniform numbers in [0, 1).
    fn uniforms(seed: u64) -> impl FnMut() -> f32 {
        let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
        move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 40) as f32 / (1u64 << 24) as f32
        }
    }

    #[test]
    fn a_picture_without_spread_is_shown_exactly_as_rendered() {
        // A hard edge of luminance on one object (a hard shadow), no noise: untouched.
        let (w, h) = (32, 16);
        let guides = flat(w, h, |_, _| false);
        let means: Vec<Color> = (0..w * h)
            .map(|i| Color::splat(if i % w < 13 { 0.1 } else { 0.8 }))
            .collect();
        let out = calm(means.clone(), vec![0.0; means.len()], &guides, PASSES, &()).unwrap();
        assert_eq!(out, means);
    }

    #[test]
    fn noise_on_one_surface_falls_and_its_mean_stays() {
        // One sample per pixel of a uniform 0.5 grey, noise of standard deviation 0.29
        // (uniform on [0, 1)): the calmed pixels' spread about 0.5 falls at least tenfold
        // in variance, and their mean stays within 1 %.
        let (w, h) = (64, 64);
        let guides = flat(w, h, |_, _| false);
        let mut u = uniforms(7);
        let means: Vec<Color> = (0..w * h).map(|_| Color::splat(u())).collect();
        let variance = vec![1.0 / 12.0; means.len()];
        let out = calm(means.clone(), variance, &guides, PASSES, &()).unwrap();
        let mse = |v: &[Color]| v.iter().map(|c| (c.x - 0.5).powi(2)).sum::<f32>() / v.len() as f32;
        let mean = out.iter().map(|c| c.x).sum::<f32>() / out.len() as f32;
        assert!(
            mse(&out) < mse(&means) / 10.0,
            "{} vs {}",
            mse(&out),
            mse(&means)
        );
        assert!((mean - 0.5).abs() < 0.005, "mean {mean}");
    }

    #[test]
    fn noise_is_not_carried_from_one_object_to_another() {
        // Noisy dark object on the left, a bright one on the right: no pixel of the dark
        // one takes any of the bright one's light.
        let (w, h) = (32, 16);
        let guides = flat(w, h, |x, _| x >= 16);
        let mut u = uniforms(3);
        let means: Vec<Color> = (0..w * h)
            .map(|i| Color::splat(if i % w < 16 { 0.1 * u() } else { 10.0 }))
            .collect();
        let out = calm(means, vec![0.01; (w * h) as usize], &guides, PASSES, &()).unwrap();
        for (i, c) in out.iter().enumerate() {
            if i as u32 % w < 16 {
                assert!(c.x <= 0.1, "pixel {i}: {c:?}");
            } else {
                assert_eq!(c.x, 10.0, "pixel {i}");
            }
        }
    }
}
