//! Dispersion in the ray tree: at a branch's first dispersive surface the tree splits into
//! three wavelengths, one per colour channel (see optics::dispersion).

use super::{Branch, End, Tracer, Walk};
use crate::camera::CameraSample;
use crate::math::{Color, SampleStream};
use crate::optics::dispersion;
use crate::params::TreeMode;
use crate::tracer::Recorder;

impl Tracer<'_> {
    /// `shade` at the first dispersive surface on a branch, where the branch takes the
    /// wavelength it carries from there on. The ray tree splits into three, one
    /// wavelength in each channel's box from one u, the third coordinate of the sample's
    /// image position ([`crate::math::SampleStream::with_image_position`]), so that a
    /// pixel's samples are stratified in position and wavelength together (the colour
    /// seen through a prism changes across a pixel). Every sample brings back
    /// all three colours, each from one wavelength of its box (weight 1). In stochastic
    /// mode, one path per sample, it takes one wavelength uniform over 400–700 nm and
    /// brings back its box's channel times 3. Either way each channel's mean is its box's
    /// mean: the same image.
    pub(super) fn shade_spectral<R: Recorder>(
        &self,
        b: Branch,
        w: &mut Walk<R>,
        shade: impl Fn(Branch, &mut Walk<R>) -> (Color, End),
    ) -> (Color, End) {
        let mut end = End::Split;
        let wavelengths = self.wavelengths(w.rng);
        let l = wavelengths.gather(|lambda| {
            let (l, e) = shade(
                Branch {
                    wavelength: Some(lambda),
                    ..b
                },
                w,
            );
            end = e;
            l
        });
        (l, end)
    }

    /// The radiance of camera sample `cs` at image position `film` through a real lens
    /// whose glass disperses: the sample's wavelengths are drawn at the camera, as
    /// [`Tracer::wavelengths`] draws them at a scene's first dispersive surface, and each
    /// is traced out through the lens on its own ray and then into the scene carrying its
    /// wavelength (so the scene's own glass does not split it again). In the split tree
    /// each colour channel comes from its own wavelength's ray (weight 1 each); in the
    /// stochastic tree and in path tracing (one path per sample) from one wavelength
    /// uniform over 400–700 nm, in its box's channel times 3.
    pub(super) fn sample_through_dispersive_lens<R: Recorder>(
        &self,
        film: glam::Vec2,
        cs: &CameraSample,
        w: &mut Walk<R>,
    ) -> Color {
        self.wavelengths(w.rng).gather(|lambda| {
            let (ray, weight) = self
                .frame
                .weighed_ray_at(film, cs.lens, cs.time, Some(lambda));
            self.trace_camera_ray(&ray, weight, Some(lambda), w)
        })
    }

    /// Whether a ray carrying `wavelength` (`None`: none yet) that meets `material` splits
    /// into wavelengths there: at its first surface whose index depends on the wavelength.
    /// Every walk asks this (the recursion, the waves, paths and photons).
    #[inline(always)]
    pub(super) fn splits_into_wavelengths(&self, material: u32, wavelength: Option<f32>) -> bool {
        self.dispersive
            && wavelength.is_none()
            && self.materials[material as usize].needs_wavelength()
    }

    /// The wavelengths a branch takes at its first dispersive surface (or a sample at a
    /// dispersive lens), from one number u (the third coordinate of the sample's image
    /// position, drawn from `rng`): in the split tree one in each colour channel's box,
    /// each brought back in its channel only (weight 1); in the stochastic tree and in
    /// path tracing (one path a sample) one uniform over 400–700 nm, brought back in its
    /// box's channel times 3 ([`dispersion::channel_weight`]).
    #[inline(always)]
    pub(super) fn wavelengths(&self, rng: &mut SampleStream) -> Wavelengths {
        let u = rng.with_image_position();
        if self.params.tree == TreeMode::Stochastic || self.params.transport.traces_paths() {
            Wavelengths::One(dispersion::wavelength(u))
        } else {
            Wavelengths::PerChannel([0, 1, 2].map(|c| dispersion::wavelength_in(c, u)))
        }
    }
}

/// The wavelengths (nm) a branch splits into ([`Tracer::wavelengths`]).
pub(super) enum Wavelengths {
    /// One, over the whole spectrum (the stochastic tree, paths).
    One(f32),
    /// One in each colour channel's box (the split tree).
    PerChannel([f32; 3]),
}

impl Wavelengths {
    /// The colour they bring back, from the radiance `at` each brings: the one wavelength's
    /// times its channel weight, or each channel from its own wavelength.
    #[inline(always)]
    pub(super) fn gather(self, mut at: impl FnMut(f32) -> Color) -> Color {
        match self {
            Wavelengths::One(lambda) => dispersion::channel_weight(lambda) * at(lambda),
            Wavelengths::PerChannel(lambdas) => {
                let mut sum = Color::ZERO;
                for (c, lambda) in lambdas.into_iter().enumerate() {
                    sum[c] = at(lambda)[c];
                }
                sum
            }
        }
    }
}
