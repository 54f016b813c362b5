//! After a change of parameters, the pixels it cannot alter are kept: the film starts
//! again only those whose samples met what the change reaches ([`crate::tracer::reach`]),
//! and the passes bring them back to the others' samples. The image is then bit for bit
//! what a fresh render with the new parameters gives.

use super::Controller;
use crate::params::Params;
use crate::render::prerender::Key;
use crate::tracer::Reach;

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
        let most = self.film.taken.iter().map(|t| t.count).max().unwrap_or(0);
        let fits = self.unlimited || most <= params.spp;
        (!cached && most > 0 && fits).then_some(reach)
    }

    /// Starts again, in the film, the pixels a change that reaches `reach` can alter.
    /// Whether the film keeps the rest; false: more than half of it would start again, and
    /// the whole image does, its preview pyramid showing it sooner.
    pub(super) fn keep_unreached(&mut self, reach: &Reach) -> bool {
        self.film.restart_reached(reach);
        let behind = self.film.taken.iter().filter(|t| t.count == 0).count();
        let pixels = self.film.taken.len().max(1);
        self.reached = behind as f32 / pixels as f32;
        behind * 2 <= pixels
    }
}
