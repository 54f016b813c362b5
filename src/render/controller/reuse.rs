//! After a change of parameters, the pixels it cannot alter are kept: the film starts
//! again only those whose samples met what the change reaches ([`crate::tracer::reach`]),
//! and the passes bring them back to the others' samples. The image is then bit for bit
//! what a fresh render with the new parameters gives.

use super::{Controller, Watch};
use crate::math::Color;
use crate::params::Params;
use crate::render::Accum;
use crate::render::kept::fill_behind;
use crate::render::kernel::render_preview_of;
use crate::render::prerender::Key;
use crate::tracer::Reach;
use rayon::prelude::*;
use std::sync::Arc;

/// The share of the image behind, at most, for which a change shows no preview: the
/// first pass over those pixels costs what a preview of the whole image at 4 × 4 would.
const FEW_BEHIND: f32 = 1.0 / 16.0;

/// What the controller knows of an image a change kept in part.
pub(super) struct Kept {
    // The share of the pixels this generation started behind the others (1: the whole
    // image), which they are, and the others' count of samples.
    reached: f32,
    behind: Vec<u32>,
    at: u32,
    // The last full-resolution picture sent, while every pixel at `at` still reads as it
    // shows (frames then change the pixels behind alone).
    picture: Option<Arc<Vec<Color>>>,
    // Pixels behind in earlier generations, which the picture may show as they were.
    outdated: Vec<u32>,
    // The most samples any pixel of the film may have (a pass stopped half-way may have
    // brought some to its end).
    pub(super) ceiling: u32,
}

impl Default for Kept {
    fn default() -> Self {
        Kept {
            reached: 1.0,
            behind: Vec::new(),
            at: 0,
            picture: None,
            outdated: Vec::new(),
            ceiling: 0,
        }
    }
}

impl Kept {
    /// The share of the image's pixels that started behind the others (1: all of it).
    pub(super) fn reached(&self) -> f32 {
        self.reached
    }

    /// Whether a film of `spp` samples per pixel is catching up: its pixels behind not yet
    /// at the count the others were kept at.
    fn catching_up(&self, spp: u32) -> bool {
        self.reached < 1.0 && spp < self.at
    }
}

impl Controller {
    /// What changing to `params` reaches, if the film can keep the pixels it cannot
    /// alter; `None` where the whole image is to start again (a change that reaches every
    /// sample, a film adaptive sampling has decided on, an image rendered ahead to adopt,
    /// a film of more samples than the new target, a film with nothing to keep).
    pub(super) fn reach(&self, params: &Params) -> Option<Reach> {
        if self.failure.is_some() {
            return None;
        }
        let reach = crate::tracer::reach(&self.scene, &self.params, params)?;
        let adaptive = self.params.noise_target.is_some() || params.noise_target.is_some();
        if adaptive && self.film.decided() {
            return None;
        }
        let size = (self.film.width(), self.film.height());
        let cached = Key::of(&self.scene, &self.camera, params, size)
            .is_some_and(|key| self.cache.as_ref().is_some_and(|c| c.holds(&key)));
        // A fresh image has the target's samples: a pixel with more cannot be kept.
        let fits = self.unlimited || self.kept.ceiling <= params.spp;
        (!cached && self.floor() > 0 && fits).then_some(reach)
    }

    /// The samples every pixel has but those behind: while they catch up, the count the
    /// others were kept at; else the film's.
    fn floor(&self) -> u32 {
        if self.kept.catching_up(self.film.spp()) {
            self.kept.at
        } else {
            self.film.spp()
        }
    }

    /// Starts again, in the film, the pixels a change that reaches `reach` can alter.
    /// Whether the film keeps the rest; false: more than half of it would be behind the
    /// others, and the whole image starts again, its preview pyramid showing it sooner.
    pub(super) fn keep_unreached(&mut self, reach: &Reach) -> bool {
        let floor = self.floor();
        let kept = &mut self.kept;
        // The last picture shows the pixels that were behind as they were when it was
        // sent: a stopped pass may have brought them up since. (While frames come, few.)
        kept.outdated.extend_from_slice(&kept.behind);
        if kept.outdated.len() > self.film.pixels.len() {
            kept.picture = None;
        }
        // Behind: those started again, and those still catching up after the last change
        // (a pass stopped half-way may leave others ahead: they keep what they have).
        self.film.restart_reached(reach, floor, &mut kept.behind);
        kept.at = floor;
        let pixels = self.film.taken.len().max(1);
        kept.reached = kept.behind.len() as f32 / pixels as f32;
        kept.behind.len() * 2 <= pixels
    }

    /// After a change: the film emptied where it was not `kept` in part; whether the
    /// generation needs no preview (nothing to render again, or so little that its first
    /// pass costs what a preview of the whole image would).
    pub(super) fn restart_kept(&mut self, kept: bool) -> bool {
        if !kept {
            self.film.clear();
            self.kept = Kept::default();
        }
        if self.kept.picture.is_none() {
            self.kept.outdated.clear();
        }
        kept && (self.film.spp() > 0 || self.kept.reached <= FEW_BEHIND)
    }

    /// Before a pass to `end` samples per pixel: whether it only brings the pixels behind
    /// up to the others (which it leaves as the picture shows them, even stopped).
    pub(super) fn pass_to(&mut self, end: u32) -> bool {
        self.kept.ceiling = self.kept.ceiling.max(end);
        self.kept.reached < 1.0 && end <= self.kept.at
    }

    /// A pass stopped half-way that did not only bring pixels behind up: the picture may
    /// no longer show the others as they are.
    pub(super) fn stopped_ahead(&mut self) {
        self.kept.picture = None;
    }

    /// The film's pixels for a frame after a pass: while the pixels behind catch up, the
    /// last picture with them as the film has them now; else every pixel's mean. Kept as
    /// the picture.
    pub(super) fn frame_pixels(&mut self) -> Arc<Vec<Color>> {
        let refreshed = self
            .kept
            .catching_up(self.film.spp())
            .then(|| self.refreshed(&self.kept.behind))
            .flatten();
        let pixels = Arc::new(refreshed.unwrap_or_else(|| self.film.pixels().collect()));
        self.kept.picture = Some(Arc::clone(&pixels));
        self.kept.outdated.clear();
        pixels
    }

    /// A copy of the last picture with `pixels` and the outdated ones as the film has
    /// them now; `None` without a picture of this film's size.
    fn refreshed(&self, pixels: &[u32]) -> Option<Vec<Color>> {
        let picture = self.kept.picture.as_ref()?;
        if picture.len() != self.film.pixels.len() {
            return None;
        }
        let mut copy = Vec::clone(picture);
        for &p in pixels.iter().chain(&self.kept.outdated) {
            copy[p as usize] = self.film.pixels[p as usize].mean();
        }
        Some(copy)
    }

    /// The next level of the pyramid over the pixels behind: one sample per `block` ×
    /// `block` block that holds any, shown among the others at full resolution.
    pub(super) fn preview_reached(&mut self, pool: &rayon::ThreadPool, block: u32) {
        let (w, h) = (self.film.width(), self.film.height());
        let gw = w.div_ceil(block);
        let mut wanted = vec![false; (gw * h.div_ceil(block)) as usize];
        for &p in &self.kept.behind {
            let (x, y) = (p % w, p / w);
            wanted[((y / block) * gw + x / block) as usize] = true;
        }
        let watch = Watch {
            requested: &self.requested,
            generation: self.generation,
        };
        let what = (&*self.scene, &self.camera, &self.params);
        let result = crate::guard::caught(|| {
            pool.install(|| render_preview_of(what, (w, h), block, &wanted, &watch))
        });
        let (grid, stats) = match result {
            Ok(Ok(preview)) => preview,
            // A newer generation was asked for: its command waits.
            Ok(Err(_)) => return,
            Err(failure) => return self.fail(failure),
        };
        self.preview_level += 1;
        self.stats += stats;
        let mut pixels = self.refreshed(&[]).unwrap_or_else(|| {
            let film = &self.film;
            pool.install(|| film.pixels.par_iter().map(Accum::mean).collect())
        });
        self.kept.outdated.clear();
        fill_behind(&mut pixels, &self.kept.behind, w, (&grid, &wanted), block);
        if self.superseded() {
            return;
        }
        let pixels = Arc::new(pixels);
        self.kept.picture = Some(Arc::clone(&pixels));
        self.emit(pixels, Arc::new(Vec::new()), (1, block), None);
    }
}
