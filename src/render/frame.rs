//! What the engine sends: frames of a generation, and how far the generation has got.

use crate::math::Color;
use crate::tracer::Stats;
use std::sync::Arc;
use std::time::Duration;

/// How far the current generation has got.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Progress {
    /// Samples per pixel in the film.
    pub spp: u32,
    /// Samples per pixel it stops at; `None` runs on without end.
    pub target: Option<u32>,
    /// Time since the generation started.
    pub elapsed: Duration,
    /// Rays traced per second by the full-resolution passes.
    pub rays_per_second: f64,
    /// Estimated time to reach the target, at the pace of the newest passes.
    pub eta: Option<Duration>,
    /// Estimated noise of the image as shown, relative to its brightness (see
    /// [`super::Film::noise`]).
    pub noise: Option<f32>,
    /// With adaptive sampling, the share of pixels it has stopped (0 to 1); `None` off.
    pub pixels_done: Option<f32>,
    /// What the tracer did in this generation.
    pub stats: Stats,
    /// Whether refinement is paused.
    pub paused: bool,
    /// The share of the image's pixels this image started behind the others (0 to 1): 1
    /// for an image rendered afresh; after a change of parameters that could not alter the
    /// rest (see [`crate::tracer::reach`]), those it started again and any still catching
    /// up from the change before.
    pub reached: f32,
    /// Why this generation stopped, if a pass failed inside raylab (a bug): the window
    /// shows it; a new generation tries again.
    pub failure: Option<String>,
}

impl Progress {
    /// Whether the target has been reached.
    pub fn done(&self) -> bool {
        self.target.is_some_and(|t| self.spp >= t) || self.pixels_done == Some(1.0)
    }

    /// The fraction of the target done, 0 to 1 (1 without a target: nothing to wait for,
    /// or once adaptive sampling has stopped every pixel).
    pub fn fraction(&self) -> f32 {
        if self.pixels_done == Some(1.0) {
            return 1.0;
        }
        self.target
            .map_or(1.0, |t| (self.spp as f32 / t.max(1) as f32).min(1.0))
    }

    /// Samples per pixel done, of the target: "37 / 256", or "37" without one.
    pub fn of_target(&self) -> String {
        match self.target {
            Some(t) => format!("{} / {t}", self.spp),
            None => self.spp.to_string(),
        }
    }
}

/// One image of a generation: a coarse preview, or the film after a pass.
#[derive(Clone, Debug)]
pub struct Frame {
    /// The generation it belongs to.
    pub generation: u64,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Linear mean radiance, row-major from the top left: every pixel after a pass; for a
    /// preview, one value per block ([`Frame::grid_size`]), to be stretched over the image
    /// with bilinear filtering (for a preview of the pixels a change started again, every
    /// pixel: the kept ones as they are, the others stretched from its blocks). Every pixel changes from one frame to the next (a pass adds
    /// samples to all of them), so frames are whole.
    pub pixels: Arc<Vec<Color>>,
    /// Rays traced per sample in every pixel (the cost heat map); empty for a preview.
    pub cost: Arc<Vec<f32>>,
    /// A preview's block side (one sample per block, upsampled): 8, 4 or 2; 1 for the
    /// film after a pass.
    pub block: u32,
    /// The side of the coarsest blocks the window shows of it: `block`, or a calmed
    /// picture's cells; where a change re-rendered part of the image, the blocks of the
    /// preview (or cells) shown among its kept pixels, `block` being 1.
    pub coarsest: u32,
    /// Progress at this frame.
    pub progress: Progress,
    /// `pixels` calmed for the screen while the image is on its way and noisy (see
    /// [`crate::render::Engine::set_calm`]): what the window shows. Snapshots, tev and the
    /// inspector read `pixels`.
    pub calm: Option<Calm>,
}

/// A frame's picture calmed for the screen: one value per `block` × `block` cell of the
/// image, row-major from the top left, to be stretched over it with bilinear filtering.
#[derive(Clone, Debug)]
pub struct Calm {
    /// Linear radiance, one value per cell.
    pub pixels: Arc<Vec<Color>>,
    /// The cells' side in pixels.
    pub block: u32,
}

impl Frame {
    /// Whether this is a preview (one sample per block), not the film after a pass.
    pub fn is_preview(&self) -> bool {
        self.block > 1
    }

    /// What the window shows: the calmed picture if there is one, else `pixels`; and its
    /// cells' side (1: every pixel).
    pub fn shown(&self) -> (&[Color], u32) {
        match &self.calm {
            Some(calm) => (&calm.pixels, calm.block),
            None => (&self.pixels, self.block),
        }
    }

    /// The size of `pixels`: the image's for a pass, its blocks' for a preview.
    pub fn grid_size(&self) -> (u32, u32) {
        (
            self.width.div_ceil(self.block),
            self.height.div_ceil(self.block),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn progress_says_how_far_of_its_target() {
        let at = |spp, target| Progress {
            spp,
            target,
            ..Progress::default()
        };
        assert_eq!(at(37, Some(256)).of_target(), "37 / 256");
        assert_eq!(at(37, None).of_target(), "37");
        assert_eq!(at(64, Some(256)).fraction(), 0.25);
        assert_eq!(at(300, Some(256)).fraction(), 1.0, "past the target: full");
        assert_eq!(at(0, Some(0)).fraction(), 0.0, "a target of 0 divides by 1");
        assert_eq!(
            at(5, None).fraction(),
            1.0,
            "no target: nothing to wait for"
        );
    }
}
