//! The controller's calmed frames (see [`crate::render::calm`]): when a frame is calmed,
//! and what calms it, kept per geometry.

use super::{Controller, Watch};
use crate::math::Color;
use crate::render::calm::{self, Guides};
use crate::render::{CLEAN_NOISE, Calm};
use std::sync::Arc;
use std::sync::atomic::Ordering;

impl Controller {
    /// Whether a newer image was asked for (while a frame was calmed: the calm stops, and
    /// the frame of the old image is not sent).
    pub(super) fn superseded(&self) -> bool {
        self.requested.load(Ordering::Relaxed) != self.generation
    }

    /// Forgets what calms frames of the last geometry.
    pub(super) fn forget_geometry(&mut self) {
        self.guides.clear();
        self.spread = None;
        self.coarse_spread.clear();
        self.one_sample_noise = 0.0;
    }

    /// Whether the image shown now is to be calmed: on, on its way, and noisy: its own
    /// estimate, or before it has one (one sample per pixel, or a preview's one per block)
    /// the last image's, over CLEAN_NOISE. An image without noise (a point light, a
    /// pinhole) is shown as rendered, at full resolution.
    ///
    /// An image a change re-rendered in part is not: its kept pixels are as clean as they
    /// were, and calming the whole to smooth a part would cost a pass's time a frame.
    fn calms(&self) -> bool {
        let one_sample = self.one_sample_noise / (self.film.spp().max(1) as f32).sqrt();
        self.calm
            && self.kept.reached() == 1.0
            && !self.target_reached()
            && self.film.noise(self.params.exposure).unwrap_or(one_sample) > CLEAN_NOISE
    }

    /// The guides of a `width` × `height` grid of the current geometry: made once per
    /// geometry for each grid (the calmed film's, and each preview level's).
    fn guides(&mut self, width: u32, height: u32) -> Arc<Guides> {
        if let Some(g) = self.guides.iter().find(|g| g.size() == (width, height)) {
            return Arc::clone(g);
        }
        let g = Arc::new(Guides::of(&self.scene, &self.camera, width, height));
        self.guides.push(Arc::clone(&g));
        g
    }

    /// The film's picture calmed, if it is to be and can be.
    pub(super) fn calm_film(&mut self) -> Option<Calm> {
        if !self.calms() {
            return None;
        }
        let (w, h) = (self.film.width(), self.film.height());
        let block = calm::CALM_BLOCK;
        let guides = self.on_pool(|c| c.guides(w.div_ceil(block), h.div_ceil(block)));
        let spread = self.spread.clone();
        let pixels = self.on_pool(|c| {
            let watch = Watch {
                requested: &c.requested,
                generation: c.generation,
            };
            calm::calm_film(
                &c.film,
                &guides,
                spread.as_deref().map(Vec::as_slice),
                &watch,
            )
        })?;
        Some(Calm {
            pixels: Arc::new(pixels),
            block,
        })
    }

    /// `f` run on the workers (its parallel loops theirs, not the process's global pool).
    fn on_pool<R: Send>(&mut self, f: impl FnOnce(&mut Self) -> R + Send) -> R {
        match self.pool.clone() {
            Some(pool) => pool.install(|| f(self)),
            None => f(self),
        }
    }

    /// A preview's grid calmed, if frames are calmed and the last image's spread is known.
    pub(super) fn calm_preview(&mut self, grid: &[Color], block: u32) -> Option<Calm> {
        let spread = self.spread.clone().filter(|_| self.calms())?;
        let (w, h) = (self.film.width(), self.film.height());
        let (gw, gh) = (w.div_ceil(block), h.div_ceil(block));
        self.on_pool(|c| {
            let guides = c.guides(gw, gh);
            let spread = match c.coarse_spread.iter().find(|(b, _)| *b == block) {
                Some((_, s)) => Arc::clone(s),
                None => {
                    let s = Arc::new(calm::coarse_spread(&spread, w, block));
                    c.coarse_spread.push((block, Arc::clone(&s)));
                    s
                }
            };
            let watch = Watch {
                requested: &c.requested,
                generation: c.generation,
            };
            let calm = calm::calm_preview(grid.to_vec(), &guides, block, &spread, &watch)?;
            Some(Calm {
                pixels: Arc::new(calm),
                block,
            })
        })
    }
}
