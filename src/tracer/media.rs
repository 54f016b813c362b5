//! The media a ray travels through: the stack of dielectric objects it has entered,
//! Beer–Lambert attenuation along a segment, and which side of a surface a ray arrives on.

use crate::geometry::{Facing, SurfaceHit};
use crate::math::{Color, Vec3};
use crate::scene::Hit;

/// How deeply dielectrics may nest (glass in water in glass ...); deeper entries are ignored.
pub const MAX_NESTING: usize = 8;

/// The dielectric objects a ray is inside, innermost last. Empty: the ray is in the
/// scene's surrounding medium.
#[derive(Clone, Copy, Debug, Default)]
pub struct Media {
    // A whole word, not a byte: the struct is copied at every hit, and a byte-wide
    // increment followed by a word-wide copy stalls store-to-load forwarding.
    len: u32,
    // (object, material) of each medium entered.
    items: [(u32, u32); MAX_NESTING],
}

impl PartialEq for Media {
    fn eq(&self, other: &Media) -> bool {
        self.active() == other.active()
    }
}

impl Eq for Media {}

impl Media {
    fn active(&self) -> &[(u32, u32)] {
        &self.items[..self.len as usize]
    }

    /// The innermost medium's material.
    pub(super) fn innermost(&self) -> Option<u32> {
        self.len.checked_sub(1).map(|i| self.items[i as usize].1)
    }

    /// After entering `object` made of `material`.
    pub(super) fn entered(mut self, object: u32, material: u32) -> Media {
        if (self.len as usize) < MAX_NESTING {
            self.items[self.len as usize] = (object, material);
            self.len += 1;
        }
        self
    }

    /// After crossing `hit`'s surface into it (`entering`) or out of it.
    #[inline]
    pub(super) fn crossed(self, entering: bool, hit: &Hit) -> Media {
        if entering {
            self.entered(hit.object, hit.material)
        } else {
            self.left(hit.object)
        }
    }

    /// The innermost medium's material once `object` is left, without building that stack.
    pub(super) fn innermost_after_leaving(&self, object: u32) -> Option<u32> {
        match self.active().iter().rposition(|&(o, _)| o == object) {
            Some(i) if i + 1 == self.len as usize => i.checked_sub(1).map(|j| self.items[j].1),
            _ => self.innermost(),
        }
    }

    /// The medium on `object`'s outer side for a ray meeting it, `entering` it or leaving
    /// it: the innermost one now, or the one that is innermost once it is left.
    #[inline]
    pub(super) fn outside(&self, entering: bool, object: u32) -> Option<u32> {
        if entering {
            self.innermost()
        } else {
            self.innermost_after_leaving(object)
        }
    }

    /// After leaving `object` (the innermost one, unless geometry overlaps).
    pub(super) fn left(mut self, object: u32) -> Media {
        if let Some(i) = self.active().iter().rposition(|&(o, _)| o == object) {
            // Leaving the innermost medium, as rays do unless geometry overlaps, moves
            // nothing (and calls no memmove for nothing).
            if i + 1 < self.len as usize {
                self.items.copy_within(i + 1..self.len as usize, i);
            }
            self.len -= 1;
        }
        self
    }
}

/// exp(−σ t) per channel; exactly 1 where σ = 0 (even for t = ∞).
#[inline]
pub(super) fn transmittance(sigma: Color, t: f32) -> Color {
    // Nothing absorbs along most rays: no exp for them.
    if sigma == Color::ZERO {
        return Color::ONE;
    }
    Color::select(sigma.cmpeq(Color::ZERO), Color::ONE, (-sigma * t).exp())
}

/// What a ray's segment through one medium does to the light along it: Beer–Lambert,
/// exp(−σ t), where some material of the scene absorbs; nothing at all elsewhere (no exp,
/// and no multiply by 1, so that the light is the same bits). Both walks ask this.
#[derive(Clone, Copy)]
pub(super) struct Segment {
    // σ of the medium; `None` in a scene where nothing absorbs.
    sigma: Option<Color>,
}

impl Segment {
    /// A segment through a medium of absorption `sigma` (`None`: a scene where nothing
    /// absorbs).
    #[inline(always)]
    pub(super) fn new(sigma: Option<Color>) -> Segment {
        Segment { sigma }
    }

    /// Whether the scene has absorbing media (even where this one absorbs nothing).
    #[inline(always)]
    pub(super) fn absorbs(self) -> bool {
        self.sigma.is_some()
    }

    /// `l` once it has come `t` along the segment.
    #[inline(always)]
    pub(super) fn along(self, t: f32, l: Color) -> Color {
        self.sigma.map_or(l, |s| transmittance(s, t) * l)
    }

    /// To a hit at distance `t`: the transmittance (`None`: 1, nothing absorbs) and the
    /// path weight `weight` becomes, times its largest channel.
    #[inline(always)]
    pub(super) fn to_hit(self, t: f32, weight: f32) -> (Option<Color>, f32) {
        let tr = self.sigma.map(|s| transmittance(s, t));
        (tr, tr.map_or(weight, |tr| weight * tr.max_element()))
    }
}

/// How a ray meets a surface.
pub(super) struct Arrival {
    /// It arrives from the surface's outside (against its normal).
    pub(super) entering: bool,
    /// The geometric normal, facing the side the ray arrives from.
    pub(super) n_geom: Vec3,
    /// The shading normal, facing the side the ray arrives from.
    pub(super) n_shade: Vec3,
    /// The medium on the surface's outer side (once left, when inside).
    pub(super) outside: Option<u32>,
}

impl Arrival {
    pub(super) fn at(dir: Vec3, hit: &Hit, media: &Media) -> Arrival {
        let f = Arrival::facing(dir, &hit.surface);
        Arrival {
            entering: f.entering,
            n_geom: f.n_geom,
            n_shade: f.n_shade,
            outside: media.outside(f.entering, hit.object),
        }
    }

    /// Whether a ray along `dir` arrives from `s`'s outside (against its normal), and the
    /// geometric and shading normals turned to face it.
    #[inline(always)]
    pub(super) fn facing(dir: Vec3, s: &SurfaceHit) -> Facing<f32> {
        Facing::of(dir, s.n_geom, s.n_shade)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn media_enter_and_leave_in_any_order() {
        let m = Media::default().entered(3, 10).entered(5, 11);
        assert_eq!(m.innermost(), Some(11));
        assert_eq!(m.left(5).innermost(), Some(10));
        // Leaving the outer one first (overlapping geometry) keeps the inner.
        assert_eq!(m.left(3).innermost(), Some(11));
        assert_eq!(m.left(3).left(5), Media::default());
        // Leaving what was never entered changes nothing.
        assert_eq!(m.left(9), m);
        for object in [3, 5, 9] {
            assert_eq!(
                m.innermost_after_leaving(object),
                m.left(object).innermost()
            );
        }
    }

    #[test]
    fn transmittance_is_beer_lambert_and_one_without_absorption() {
        let t = transmittance(Color::new(0.0, 1.0, 2.0), 0.5);
        assert_eq!(t.x, 1.0);
        assert!((t.y - (-0.5f32).exp()).abs() < 1e-7);
        assert!((t.z - (-1.0f32).exp()).abs() < 1e-7);
        assert_eq!(
            transmittance(Color::new(0.0, 1.0, 0.0), f32::INFINITY),
            Color::new(1.0, 0.0, 1.0)
        );
    }
}
