//! Adaptive sampling: samples where the noise is.
//!
//! At fixed sample counts (16, 24, then four times per doubling) each pixel's noise is
//! estimated from its own samples, and pixels that have had their share stop receiving
//! samples. The decisions are made on the whole film between passes, at counts that do not
//! depend on how the samples were split into passes, so an image is the same bit for bit
//! for any thread count and any split (the kernel cuts its passes at these counts).

use super::{Accum, Film};
use rayon::prelude::*;

/// The first decision is made once every pixel has this many samples: fewer give too
/// rough an estimate of a pixel's spread.
pub(crate) const FIRST_CHECK: u32 = 16;

/// Whether adaptive sampling acts on a render with `params`: it is on, and the target
/// goes past the first decision.
pub fn acts(params: &crate::params::Params) -> bool {
    params.noise_target.is_some() && params.spp > FIRST_CHECK
}

/// Whether the film is decided on when it holds `k` samples: 16 and 24, then four times
/// per doubling (32, 40, 48, 56, 64, 80, ..., 128, 160, ...). A pixel then takes at most a
/// quarter more samples than it needed, and a decision (a pass over the whole film) stays
/// rare beside the samples between two. (Powers of two alone keep each pixel's Sobol
/// prefix evenly spread, but a pixel that needed 70 samples took 128, which was slower
/// overall: docs/performance.md, "Shaped by measurement".)
pub(crate) fn is_checkpoint(k: u32) -> bool {
    if k < FIRST_CHECK {
        return false;
    }
    // A quarter of the power of two at or below k, at least 8.
    let step = (1u32 << (31 - k.leading_zeros())) / 4;
    k.is_multiple_of(step.max(8))
}

/// Samples `first..first + samples` cut at the decision points: (first sample, count) of
/// each piece, in order.
pub(crate) fn segments(first: u32, samples: u32) -> Vec<(u32, u32)> {
    let end = first.saturating_add(samples);
    let mut pieces = Vec::new();
    let mut start = first;
    while start < end {
        let mut stop = start + 1;
        while stop < end && !is_checkpoint(stop) {
            stop += 1;
        }
        pieces.push((start, stop - start));
        start = stop;
    }
    pieces
}

/// The slope of the sRGB curve at linear value `y` (in [0, 1]): how much a small error
/// in `y` moves the displayed value. 12.92 on the linear toe, else
/// d/dy (1.055 y^(1/2.4) − 0.055) = (1.055 / 2.4) y^(1/2.4 − 1).
fn srgb_slope(y: f64) -> f64 {
    if y <= 0.003_130_8 {
        12.92
    } else {
        1.055 / 2.4 * y.powf(1.0 / 2.4 - 1.0)
    }
}

/// The standard error of pixel `a`'s displayed luminance: the sample variance of its
/// samples' luminance Y, s² = (Σ Y² − n Ȳ²)/(n − 1), over n, carried through the sRGB
/// curve at Ȳ (clipped at white, as the display clips). Infinite before two samples.
fn displayed_error(a: &Accum) -> f64 {
    let n = a.count as f64;
    if a.count < 2 {
        return f64::INFINITY;
    }
    let mean = [0, 1, 2].map(|i| a.sum[i] / n);
    let y = 0.2126 * mean[0] + 0.7152 * mean[1] + 0.0722 * mean[2];
    let variance = ((a.luma_sq as f64 - n * y * y) / (n - 1.0)).max(0.0);
    (variance / n).sqrt() * srgb_slope(y.clamp(0.0, 1.0))
}

/// Marks the pixels that are done, so that the image's noise (the RMS of the pixels'
/// errors ε, as the status bar measures it) ends at `target_percent` % of its mean
/// displayed brightness M for the fewest samples. A pixel's error is ε = σ/√n for the
/// spread σ of its samples; the samples n_p that make Σ ε_p² smallest for a given Σ n_p
/// grow as σ_p (a Lagrange multiplier: d(σ²/n)/dn = −σ²/n² the same for every pixel). So a
/// pixel has had its share once ε² ≤ c σ, with c = (target · M)² / mean σ: then the RMS
/// of ε is at most target · M. A pixel is done when it and each neighbour in its 3 × 3
/// block have had their share (or were done), so that a pixel whose few samples happen
/// to agree does not stop beside noisy ones. Returns whether every pixel is done. Rows in
/// parallel; each result depends on the film alone.
pub(crate) fn decide(film: &mut Film, target_percent: f32) -> bool {
    let (w, h) = (film.width() as usize, film.height() as usize);
    let shown: Vec<f64> = film
        .pixels
        .par_iter()
        .map(|a| a.shown(1.0).unwrap_or(0.0))
        .collect();
    // (ε, σ) of each pixel.
    let spread: Vec<(f64, f64)> = film
        .pixels
        .par_iter()
        .map(|a| {
            let e = displayed_error(a);
            (e, e * (a.count as f64).sqrt())
        })
        .collect();
    // Summed in pixel order, so the limit is the same bits for any thread count.
    let n = film.pixels.len().max(1) as f64;
    let mean = shown.iter().sum::<f64>() / n;
    let limit = target_percent as f64 / 100.0 * mean;
    let mean_sigma = spread
        .iter()
        .map(|&(_, s)| s)
        .filter(|s| s.is_finite())
        .sum::<f64>()
        / n;
    let c = limit * limit / mean_sigma.max(f64::MIN_POSITIVE);
    let converged: Vec<bool> = spread
        .par_iter()
        .zip(film.done.par_iter())
        .map(|(&(e, sigma), &done)| done || e * e <= c * sigma)
        .collect();
    film.done
        .par_chunks_mut(w.max(1))
        .enumerate()
        .for_each(|(y, row)| {
            let rows = y.saturating_sub(1)..(y + 2).min(h);
            for (x, done) in row.iter_mut().enumerate() {
                let cols = x.saturating_sub(1)..(x + 2).min(w);
                *done = rows.clone().all(|r| {
                    converged[r * w + cols.start..r * w + cols.end]
                        .iter()
                        .all(|&c| c)
                });
            }
        });
    film.done.iter().all(|&d| d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_are_cut_at_every_decision_point_and_nowhere_else() {
        let points: Vec<u32> = (0..300).filter(|&k| is_checkpoint(k)).collect();
        assert_eq!(
            points,
            [
                16, 24, 32, 40, 48, 56, 64, 80, 96, 112, 128, 160, 192, 224, 256
            ]
        );
        assert_eq!(segments(0, 4), vec![(0, 4)]);
        assert_eq!(segments(0, 40), vec![(0, 16), (16, 8), (24, 8), (32, 8)]);
        assert_eq!(segments(13, 6), vec![(13, 3), (16, 3)]);
        assert_eq!(segments(20, 4), vec![(20, 4)]);
        assert_eq!(segments(70, 30), vec![(70, 10), (80, 16), (96, 4)]);
        assert_eq!(segments(20, 0), vec![]);
    }

    #[test]
    fn the_error_is_the_standard_error_of_the_shown_value() {
        // Samples of luminance 0.2 ± 0.1 (grey): s² = 0.01·n/(n − 1), error √(s²/n)·slope.
        let mut a = Accum::default();
        for i in 0..64 {
            let v = if i % 2 == 0 { 0.1 } else { 0.3 };
            a.add(i, crate::math::Color::splat(v));
        }
        let expected = (0.01f64 * 64.0 / 63.0 / 64.0).sqrt() * srgb_slope(0.2);
        assert!((displayed_error(&a) / expected - 1.0).abs() < 1e-4);
        // Samples that agree have no error; one sample has no estimate.
        let mut flat = Accum::default();
        for i in 0..16 {
            flat.add(i, crate::math::Color::splat(0.5));
        }
        assert!(displayed_error(&flat) < 1e-6);
        let mut one = Accum::default();
        one.add(0, crate::math::Color::splat(0.5));
        assert_eq!(displayed_error(&one), f64::INFINITY);
    }

    #[test]
    fn a_noisy_pixel_keeps_its_neighbours_going() {
        // A flat 5 × 5 film with one noisy pixel at (1, 1), its samples 0.5 and 0.9 in
        // turn: ε ≈ 0.031 as shown, an RMS over the film of ε/5 ≈ 0.006. Under a target of
        // 0.5 % of the mean shown (about 0.0037) it has not had its share: it and its
        // eight neighbours go on, the rest are done. Under 2 % (about 0.015) the film's
        // noise is already there, and every pixel is done.
        let film = || {
            let mut film = Film::new(5, 5);
            for (i, a) in film.pixels.iter_mut().enumerate() {
                for s in 0..16 {
                    let noisy = i == 6 && s % 2 == 1;
                    a.add(s, crate::math::Color::splat(if noisy { 0.9 } else { 0.5 }));
                }
            }
            film.set_spp(16);
            film
        };
        let mut tight = film();
        assert!(!decide(&mut tight, 0.5));
        let going: Vec<usize> = (0..25).filter(|&i| !tight.done[i]).collect();
        assert_eq!(going, vec![0, 1, 2, 5, 6, 7, 10, 11, 12]);
        let mut loose = film();
        assert!(decide(&mut loose, 2.0));
    }
}
