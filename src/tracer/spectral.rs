//! Dispersion in the ray tree: at a branch's first dispersive surface the tree splits into
//! three wavelengths, one per colour channel (see optics::dispersion).

use super::{Branch, End, Tracer, Walk};
use crate::math::Color;
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
        let u = w.rng.with_image_position();
        let shade_at = |lambda: f32, w: &mut Walk<R>| {
            let b = Branch {
                wavelength: Some(lambda),
                ..b
            };
            shade(b, w)
        };
        if self.params.tree == TreeMode::Stochastic {
            let lambda = dispersion::wavelength(u);
            let (l, end) = shade_at(lambda, w);
            return (dispersion::channel_weight(lambda) * l, end);
        }
        let mut sum = Color::ZERO;
        let mut end = End::Split;
        for c in 0..3 {
            let (l, e) = shade_at(dispersion::wavelength_in(c, u), w);
            sum[c] = l[c];
            end = e;
        }
        (sum, end)
    }
}
