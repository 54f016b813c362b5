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
pub(super) const FEW_BEHIND: f32 = 1.0 / 16.0;

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
        let fits = self.unlimited || self.ceiling <= params.spp;
        (!cached && self.floor() > 0 && fits).then_some(reach)
    }

    /// The samples every pixel has but those behind: while they catch up, the count the
    /// others were kept at; else the film's.
    fn floor(&self) -> u32 {
        match self.reached < 1.0 && self.film.spp() < self.kept_at {
            true => self.kept_at,
            false => self.film.spp(),
        }
    }

    /// Starts again, in the film, the pixels a change that reaches `reach` can alter.
    /// Whether the film keeps the rest; false: more than half of it would be behind the
    /// others, and the whole image starts again, its preview pyramid showing it sooner.
    pub(super) fn keep_unreached(&mut self, reach: &Reach) -> bool {
        // The last picture shows the pixels that were behind as they were when it was
        // sent: a stopped pass may have brought them up since. (While frames come, few.)
        self.outdated.extend_from_slice(&self.behind);
        if self.outdated.len() > self.film.pixels.len() {
            self.picture = None;
        }
        let floor = self.floor();
        // Behind: those started again, and those still catching up after the last change
        // (a pass stopped half-way may leave others ahead: they keep what they have).
        self.film.restart_reached(reach, floor, &mut self.behind);
        self.kept_at = floor;
        let pixels = self.film.taken.len().max(1);
        self.reached = self.behind.len() as f32 / pixels as f32;
        self.behind.len() * 2 <= pixels
    }

    /// The picture to send while the pixels behind catch up: the last one sent, those
    /// pixels as the film has them now; `None` once they have caught up, or where the last
    /// picture may not show the others as they are.
    pub(super) fn picture_behind(&self) -> Option<Arc<Vec<Color>>> {
        let picture = self.picture.as_ref()?;
        let catching_up = self.reached < 1.0 && self.film.spp() < self.kept_at;
        if !catching_up || picture.len() != self.film.pixels.len() {
            return None;
        }
        let mut pixels = Vec::clone(picture);
        for &p in self.behind.iter().chain(&self.outdated) {
            pixels[p as usize] = self.film.pixels[p as usize].mean();
        }
        Some(Arc::new(pixels))
    }

    /// The next level of the pyramid over the pixels behind: one sample per `block` ×
    /// `block` block that holds any, shown among the others at full resolution.
    pub(super) fn preview_reached(&mut self, pool: &rayon::ThreadPool, block: u32) {
        let (w, h) = (self.film.width(), self.film.height());
        let gw = w.div_ceil(block);
        let mut wanted = vec![false; (gw * h.div_ceil(block)) as usize];
        for &p in &self.behind {
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
        let film = &self.film;
        let mut pixels = match &self.picture {
            Some(p) if p.len() == film.pixels.len() => {
                let mut pixels = Vec::clone(p);
                for &q in &self.outdated {
                    pixels[q as usize] = film.pixels[q as usize].mean();
                }
                pixels
            }
            _ => pool.install(|| film.pixels.par_iter().map(Accum::mean).collect()),
        };
        self.outdated.clear();
        fill_behind(&mut pixels, &self.behind, w, (&grid, &wanted), block);
        if self.superseded() {
            return;
        }
        let pixels = Arc::new(pixels);
        self.picture = Some(Arc::clone(&pixels));
        self.emit(pixels, Arc::new(Vec::new()), (1, block), None);
    }
}
