//! The one render kernel: a pass of samples over the whole film, in bands of rows run in
//! parallel. The CLI, the tests and the progressive engine all call [`render_pass`].

use super::film::Taken;
use super::{Accum, Film, adaptive};
use crate::camera::Camera;
use crate::math::Color;
use crate::math::lanes::Width;
use crate::params::Params;
use crate::scene::Scene;
use crate::tracer::{Met, Stats, Traced, Tracer, Traversal, Waves};
use rayon::prelude::*;
use std::cell::Cell;
use std::sync::atomic::{AtomicU32, Ordering};

/// Rows per band: the unit of parallel work, progress and cancellation.
pub const BAND_ROWS: u32 = 4;

/// Watches a pass: asked before every pixel whether to go on, told after each band of rows
/// is done.
pub trait PassObserver: Sync {
    /// False stops the pass at the next pixel, in every band (none finishes its rows): the
    /// film then holds a partial pass, and the pass returns [`Cancelled`].
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

/// Adds `samples` samples to every pixel of `film`, seen through `camera`: sample numbers
/// `film.spp()` to `film.spp() + samples - 1`. Each pixel's samples are added to its sum
/// in sample order, so the film is bit-for-bit the same for any thread count and any split
/// into passes. The observer is asked before every pixel whether to go on.
pub fn render_pass(
    scene: &Scene,
    camera: &Camera,
    params: &Params,
    film: &mut Film,
    samples: u32,
    observer: &dyn PassObserver,
) -> Result<Stats, Cancelled> {
    render_pass_by(
        Traversal::best(),
        scene,
        camera,
        params,
        film,
        samples,
        observer,
    )
}

/// [`render_pass`] with the ray trees walked as `traversal` says: the same image, bit for
/// bit or within noise (see [`Traversal`]).
pub fn render_pass_by(
    traversal: Traversal,
    scene: &Scene,
    camera: &Camera,
    params: &Params,
    film: &mut Film,
    samples: u32,
    observer: &dyn PassObserver,
) -> Result<Stats, Cancelled> {
    let whole = Crop {
        size: (film.width(), film.height()),
        origin: (0, 0),
    };
    pass_of(
        traversal,
        (scene, camera, params),
        film,
        whole,
        samples,
        observer,
    )
}

/// Where a film lies in the image it is cut from: the image's size, and the pixel of the
/// image at the film's top left. A crop's pixels are the whole image's, bit for bit (its
/// samples are the same numbers of the same pixels), but where adaptive sampling decides:
/// it decides by the film it is given.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Crop {
    /// The whole image's size.
    pub size: (u32, u32),
    /// The whole image's pixel at the film's top left.
    pub origin: (u32, u32),
}

/// [`render_pass`] for a film cut from a larger image at `crop`.
pub fn render_crop_pass(
    scene: &Scene,
    camera: &Camera,
    params: &Params,
    film: &mut Film,
    crop: Crop,
    samples: u32,
    observer: &dyn PassObserver,
) -> Result<Stats, Cancelled> {
    let traversal = Traversal::best();
    pass_of(
        traversal,
        (scene, camera, params),
        film,
        crop,
        samples,
        observer,
    )
}

/// [`render_pass_by`] for a film at `crop` of its image.
fn pass_of(
    traversal: Traversal,
    (scene, camera, params): (&Scene, &Camera, &Params),
    film: &mut Film,
    crop: Crop,
    samples: u32,
    observer: &dyn PassObserver,
) -> Result<Stats, Cancelled> {
    let first = film.spp();
    let mut tracer = Tracer::with_camera(scene, camera, params, crop.size.0, crop.size.1);
    let waves = traversal.for_tracer(&tracer);
    if first == 0 {
        // A new image: no pixel is done (the flags may be an earlier image's).
        film.done.fill(false);
    }
    // Adaptive sampling decides at fixed counts: the pass is cut there. Each sample number
    // of photon mapping has photons of its own, so that the image does not depend on how
    // the samples are split into passes: one pass per sample.
    let pieces = match (tracer.gathers_photons(), params.noise_target) {
        (true, _) => (first..first + samples).map(|s| (s, 1)).collect(),
        (false, Some(_)) => adaptive::segments(first, samples),
        (false, None) => vec![(first, samples)],
    };
    let each = Share {
        observer,
        samples: pieces.len() as u32,
        rows: AtomicU32::new(0),
    };
    let observer: &dyn PassObserver = if pieces.len() == 1 { observer } else { &each };
    let mut total = Stats::default();
    for (start, count) in pieces {
        if let Some(target) = params.noise_target
            && start > 0
            && adaptive::is_checkpoint(start)
            && adaptive::decide(film, target)
        {
            // Every pixel is done: the rest of the pass would trace nothing.
            film.set_spp(first + samples);
            break;
        }
        let skip = params.noise_target.is_some() && start >= adaptive::FIRST_CHECK;
        if tracer.gathers_photons() {
            tracer.prepare_photons(start);
        }
        let at = crop.origin;
        total += match waves {
            Traversal::Waves(lanes) => {
                pass_in_waves((&tracer, at), lanes, film, start, count, skip, observer)?
            }
            _ => pass((&tracer, at), film, start, count, skip, observer)?,
        };
    }
    Ok(total)
}

/// Tells `observer` of the rows of `samples` passes as of one: a row is done when it is
/// done in all of them.
struct Share<'o> {
    observer: &'o dyn PassObserver,
    samples: u32,
    rows: AtomicU32,
}

impl PassObserver for Share<'_> {
    fn keep_going(&self) -> bool {
        self.observer.keep_going()
    }
    fn band_done(&self, rows: u32) {
        let before = self.rows.fetch_add(rows, Ordering::Relaxed);
        let n = self.samples.max(1);
        let done = (before + rows) / n - before / n;
        if done > 0 {
            self.observer.band_done(done);
        }
    }
}

/// Samples `first..first + samples` of every pixel (but those adaptive sampling has
/// stopped, where `skip`), by `tracer`, the film's pixel (0, 0) being the image's `at`.
fn pass(
    (tracer, (ox, oy)): (&Tracer, (u32, u32)),
    film: &mut Film,
    first: u32,
    samples: u32,
    skip: bool,
    observer: &dyn PassObserver,
) -> Result<Stats, Cancelled> {
    let width = film.width() as usize;
    let end = first + samples;
    over_bands(film, first, samples, observer, |y0, band| {
        let Band {
            pixels,
            taken,
            done,
            stats,
        } = band;
        // Row by row: the pixel's coordinates without a division per pixel.
        let rows = pixels
            .chunks_mut(width)
            .zip(taken.chunks_mut(width))
            .zip(done.chunks(width));
        for (row, ((pixels, taken), done)) in rows.enumerate() {
            let y = y0 + row as u32;
            for (x, ((pixel, taken), &done)) in pixels.iter_mut().zip(taken).zip(done).enumerate() {
                if !observer.keep_going() {
                    return None;
                }
                if skip && done {
                    continue;
                }
                // (A pixel a change left as it was may be ahead of the pass.)
                for s in taken.count.max(first)..end {
                    let before = stats.total_rays();
                    let (c, met) = tracer.sample_met(ox + x as u32, oy + y, s, stats);
                    let rays = (stats.total_rays() - before) as u32;
                    let traced = Traced {
                        radiance: c,
                        rays,
                        met,
                    };
                    add((pixel, taken), s, &traced, stats);
                }
            }
        }
        Some(())
    })
}

/// The samples one wave traces together: enough that its deeper levels still fill the
/// lanes, few enough that its nodes stay in cache and a cancelled pass stops soon.
const WAVE_SAMPLES: usize = 256;

/// [`pass`] with each band's samples traced in waves of [`WAVE_SAMPLES`], `lanes` rays at
/// a time.
fn pass_in_waves(
    (tracer, (ox, oy)): (&Tracer, (u32, u32)),
    lanes: Width,
    film: &mut Film,
    first: u32,
    samples: u32,
    skip: bool,
    observer: &dyn PassObserver,
) -> Result<Stats, Cancelled> {
    let width = film.width();
    let end = first + samples;
    over_bands(film, first, samples, observer, |y0, band| {
        let Band {
            pixels,
            taken,
            done,
            stats,
        } = band;
        // Pixel by pixel (but those stopped, where `skip`), each pixel's samples in order,
        // from those it has. (The image's coordinates: the film's, moved to where it lies
        // in the image.) A pixel's count is read as its first sample is queued and written
        // as its samples are summed: cells, for the queue and the sums to share.
        let taken = Cell::from_mut(taken).as_slice_of_cells();
        let all = (0..pixels.len() as u32)
            .filter(|&i| !(skip && done[i as usize]))
            .flat_map(|i| {
                let (x, y) = (ox + i % width, oy + y0 + i / width);
                (taken[i as usize].get().count.max(first)..end).map(move |s| (x, y, s))
            });
        in_waves(
            tracer,
            lanes,
            all,
            observer,
            stats,
            |wave, traced, stats| {
                // A pixel's samples of the wave summed in a copy of its sums, which stays
                // in registers: summed in place, each f64 add waits on the last one's
                // store (docs/performance.md, "Shaped by measurement").
                let mut samples = wave.iter().zip(traced).peekable();
                while let Some((&(x, y, s), t)) = samples.next() {
                    let i = ((y - oy - y0) * width + x - ox) as usize;
                    let (mut sums, mut count) = (pixels[i], taken[i].get());
                    add((&mut sums, &mut count), s, t, stats);
                    while let Some((&(_, _, s), t)) =
                        samples.next_if(|((px, py, _), _)| (*px, *py) == (x, y))
                    {
                        add((&mut sums, &mut count), s, t, stats);
                    }
                    pixels[i] = sums;
                    taken[i].set(count);
                }
            },
        )
    })
}

/// Traces `samples` ((x, y, sample number) each) in waves of [`WAVE_SAMPLES`], `lanes`
/// rays at a time, handing each wave's samples and what each gave to `each`, in order;
/// `None` where `observer` stops it (asked before every wave).
fn in_waves(
    tracer: &Tracer,
    lanes: Width,
    samples: impl Iterator<Item = (u32, u32, u32)>,
    observer: &dyn PassObserver,
    stats: &mut Stats,
    mut each: impl FnMut(&[(u32, u32, u32)], &[Traced], &mut Stats),
) -> Option<()> {
    let mut samples = samples.peekable();
    let mut wave = Vec::with_capacity(WAVE_SAMPLES);
    let mut waves = Waves::default();
    while samples.peek().is_some() {
        if !observer.keep_going() {
            return None;
        }
        wave.clear();
        wave.extend(samples.by_ref().take(WAVE_SAMPLES));
        let traced = tracer.trace_wave(&wave, lanes, stats, &mut waves);
        each(&wave, traced, stats);
    }
    Some(())
}

/// Adds sample `s`, as it was `traced`, to a pixel (its sums and what its samples were);
/// a sample that is not finite is counted and dropped. Each pixel's samples must come in
/// sample order.
#[inline]
fn add((pixel, taken): (&mut Accum, &mut Taken), s: u32, traced: &Traced, stats: &mut Stats) {
    if s == 0 {
        // An empty film keeps its old sums until each pixel starts afresh here.
        *pixel = Accum::default();
        taken.met = Met::default();
    }
    taken.count = s + 1;
    taken.met.merge(traced.met);
    pixel.rays = pixel.rays.saturating_add(traced.rays);
    if traced.radiance.is_finite() {
        pixel.add(s, traced.radiance);
    } else {
        stats.non_finite += 1;
    }
}

/// A band of rows of a film: its pixels' sums, what their samples were, which are done,
/// and the band's counters.
struct Band<'b> {
    pixels: &'b mut [Accum],
    taken: &'b mut [Taken],
    done: &'b [bool],
    stats: &'b mut Stats,
}

/// Runs `band` (its first row, and the band) on every band of rows of `film` in parallel,
/// telling `observer` of each; `None` from a band cancels the pass. The film then holds
/// samples `..first + samples`.
fn over_bands(
    film: &mut Film,
    first: u32,
    samples: u32,
    observer: &dyn PassObserver,
    band: impl Fn(u32, Band) -> Option<()> + Sync,
) -> Result<Stats, Cancelled> {
    let (width, height) = (film.width(), film.height());
    let band_len = (width * BAND_ROWS) as usize;
    let results: Vec<Option<Stats>> = film
        .pixels
        .par_chunks_mut(band_len)
        .zip(film.taken.par_chunks_mut(band_len))
        .zip(film.done.par_chunks(band_len))
        .enumerate()
        .map(|(i, ((pixels, taken), done))| {
            let mut stats = Stats::default();
            let y0 = i as u32 * BAND_ROWS;
            let b = Band {
                pixels,
                taken,
                done,
                stats: &mut stats,
            };
            band(y0, b)?;
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

/// A preview at one level of the resolution pyramid: one sample (number 0) at the centre
/// of every `block` × `block` block of a `width` × `height` image. Returns the grid of
/// blocks, `width.div_ceil(block)` × `height.div_ceil(block)`, row-major linear radiance:
/// the display stretches it over the image with bilinear filtering, so no blocks show.
/// `block` 8 costs 1/64 of a 1-spp pass, 4 costs 1/16, 2 costs 1/4.
pub fn render_preview(
    scene: &Scene,
    camera: &Camera,
    params: &Params,
    width: u32,
    height: u32,
    block: u32,
    observer: &dyn PassObserver,
) -> Result<(Vec<Color>, Stats), Cancelled> {
    let size = (width, height);
    preview_of((scene, camera, params), size, block, None, observer)
}

/// [`render_preview`] of the blocks `wanted` marks (one flag per block of the grid); the
/// others are left black.
pub(crate) fn render_preview_of(
    (scene, camera, params): (&Scene, &Camera, &Params),
    (width, height): (u32, u32),
    block: u32,
    wanted: &[bool],
    observer: &dyn PassObserver,
) -> Result<(Vec<Color>, Stats), Cancelled> {
    let size = (width, height);
    preview_of((scene, camera, params), size, block, Some(wanted), observer)
}

fn preview_of(
    (scene, camera, params): (&Scene, &Camera, &Params),
    (width, height): (u32, u32),
    block: u32,
    wanted: Option<&[bool]>,
    observer: &dyn PassObserver,
) -> Result<(Vec<Color>, Stats), Cancelled> {
    let mut tracer = Tracer::with_camera(scene, camera, params, width, height);
    tracer.prepare_photons(0);
    let block = block.max(1);
    let nx = width.div_ceil(block);
    // The pixel at the centre of block i (the last block may be cut short).
    let centre = |i: u32, size: u32| (i * block + block / 2).min(size - 1);
    let mut grid = vec![Color::ZERO; nx as usize * height.div_ceil(block) as usize];
    let lanes = match Traversal::best().for_tracer(&tracer) {
        Traversal::Waves(lanes) => Some(lanes),
        Traversal::Recursive => None,
    };
    let shown = |c: Color| if c.is_finite() { c } else { Color::ZERO };
    let results: Vec<Option<Stats>> = grid
        .par_chunks_mut(nx as usize)
        .enumerate()
        .map(|(j, row)| {
            let mut stats = Stats::default();
            let cy = centre(j as u32, height);
            // The row's blocks to trace.
            let first = j * nx as usize;
            let blocks = (0..row.len()).filter(|&i| wanted.is_none_or(|w| w[first + i]));
            if let Some(lanes) = lanes {
                let centres = blocks.clone().map(|i| (centre(i as u32, width), cy, 0));
                let mut cells = blocks;
                in_waves(
                    &tracer,
                    lanes,
                    centres,
                    observer,
                    &mut stats,
                    |_, traced, _| {
                        // (The wave's results first: zip takes from its first side first.)
                        for (t, i) in traced.iter().zip(cells.by_ref()) {
                            row[i] = shown(t.radiance);
                        }
                    },
                )?;
                return Some(stats);
            }
            for i in blocks {
                if !observer.keep_going() {
                    return None;
                }
                row[i] = shown(tracer.sample(centre(i as u32, width), cy, 0, &mut stats));
            }
            Some(stats)
        })
        .collect();
    let mut total = Stats::default();
    for r in results {
        total += r.ok_or(Cancelled)?;
    }
    Ok((grid, total))
}
