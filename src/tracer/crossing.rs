//! What a path and a photon each do at a hit, the same way: meet it (the first dispersive
//! surface on the way picking their wavelength) and cross it into the media beyond.

use super::{Media, Tracer};
use crate::material::{Interaction, Side};
use crate::math::{Color, Ray, SampleStream, Vec3};
use crate::optics::dispersion;
use crate::scene::Hit;

/// A path (or photon) leaving a surface on `side`: the media it is in from there, and the
/// normal its next ray sets out along.
pub(super) fn cross(media: &mut Media, at: &Interaction, hit: &Hit, side: Side) -> Vec3 {
    match side {
        Side::Reflect => at.n_geom,
        Side::Transmit => {
            *media = media.crossed(at.entering, hit);
            -at.n_geom
        }
    }
}

impl Tracer<'_> {
    /// The hit as its material sees it, for a path (or photon) through `media` carrying
    /// `wavelength`: the first dispersive surface on the way picks one, and `weight` takes
    /// its channel's weight.
    pub(super) fn meet(
        &self,
        ray: &Ray,
        hit: &Hit,
        media: &Media,
        wavelength: &mut Option<f32>,
        weight: &mut Color,
        rng: &mut SampleStream,
    ) -> Interaction {
        if self.splits_into_wavelengths(hit.material, *wavelength) {
            let lambda = dispersion::wavelength(rng.with_image_position());
            *wavelength = Some(lambda);
            *weight *= dispersion::channel_weight(lambda);
        }
        self.interaction(ray, hit, media, *wavelength)
    }
}
