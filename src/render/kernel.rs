//! The one render kernel: a pass of samples over the whole film, in bands of rows run in
//! parallel. The CLI, the tests and the progressive engine all call [`render_pass`].

use super::Film;
use crate::params::Params;
use crate::scene::Scene;
use crate::tracer::{Stats, Tracer};
use rayon::prelude::*;

/// Rows per band: the unit of parallel work, progress and cancellation.
pub const BAND_ROWS: u32 = 4;

/// Watches a pass: asked before each band whether to go on, told after each band is done.
pub trait PassObserver: Sync {
    /// False stops the pass (bands already started finish).
    fn keep_going(&self) -> bool {
        true
    }
    /// A band of `rows` rows is done.
    fn band_done(&self, _rows: u32) {}
}

/// Watches nothing.
impl PassObserver for () {}

/// The pass was stopped by its observer; the film holds a partial pass and must be cleared.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the render pass was cancelled")]
pub struct Cancelled;

/// Adds `samples` samples to every pixel of `film`: sample numbers `film.spp()` to
/// `film.spp() + samples - 1`. Each pixel's samples are added to its sum in sample order,
/// so the film is bit-for-bit the same for any thread count and any split into passes.
pub fn render_pass(
    scene: &Scene,
    params: &Params,
    film: &mut Film,
    samples: u32,
    observer: &dyn PassObserver,
) -> Result<Stats, Cancelled> {
    let (width, height) = (film.width(), film.height());
    let tracer = Tracer::new(scene, params, width, height);
    let first = film.spp();
    let band_len = (width * BAND_ROWS) as usize;
    let results: Vec<Option<Stats>> = film
        .sum
        .par_chunks_mut(band_len)
        .zip(film.count.par_chunks_mut(band_len))
        .enumerate()
        .map(|(band, (sums, counts))| {
            if !observer.keep_going() {
                return None;
            }
            let mut stats = Stats::default();
            let y0 = band as u32 * BAND_ROWS;
            for (i, (sum, count)) in sums.iter_mut().zip(counts.iter_mut()).enumerate() {
                let (x, y) = (i as u32 % width, y0 + i as u32 / width);
                for s in first..first + samples {
                    let c = tracer.sample(x, y, s, &mut stats);
                    if c.is_finite() {
                        for k in 0..3 {
                            sum[k] += c[k] as f64;
                        }
                        *count += 1;
                    } else {
                        stats.non_finite += 1;
                    }
                }
            }
            observer.band_done(BAND_ROWS.min(height - y0));
            Some(stats)
        })
        .collect();
    let mut total = Stats::default();
    for r in results {
        total += r.ok_or(Cancelled)?;
    }
    film.set_spp(first + samples);
    Ok(total)
}
