//! What a sample met that a parameter governs, and what a change of parameters reaches:
//! the record by which the engine re-renders, after a change, only the pixels whose samples
//! the change can alter (a pixel whose samples met nothing it governs keeps its sums: the
//! same sample numbers trace the same rays, bit for bit).
//!
//! A sample's outcome depends on the parameters only through
//! - the materials its rays hit (each resolved from the parameters: ior, Abbe number,
//!   roughness, Fresnel mode, constant reflectance, absorption, Phong exponent);
//! - the depth and weight tests of its branches (`max_depth`, `min_weight`);
//! - the photons it gathers (their map depends on every material and both limits);
//! - and on what every sample depends on (the pattern, seed, transport, tree, camera,
//!   lights, polariser), which re-renders everything.
//!
//! Adaptive sampling decides on the whole film at once: a film it has decided on starts
//! again whole (`Film::decided`); before its first decision, a pixel's samples are its own.
//!
//! So the record is: the materials hit (a bit each, modulo [`MATERIAL_BITS`]), whether
//! photons were gathered, the deepest branch tested against `max_depth` and the lightest
//! tested against `min_weight`.

use crate::light::{Light, LightShape};
use crate::params::{Params, Pattern, Transport};
use crate::scene::Scene;

/// Materials share the record's bits modulo this: material m sets bit m % 32 (a scene of
/// more materials re-renders a little more than it must, never less).
pub const MATERIAL_BITS: u32 = 32;

/// What one sample met (or all of a pixel's samples, [`Met::merge`]d) that the parameters
/// govern. 8 bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Met {
    // Bit m % MATERIAL_BITS: material m was hit.
    bits: u32,
    // The lightest path weight tested against `min_weight`, as the upper half of its f32
    // (rounded towards zero: never above the weight); +inf while none was tested.
    lightest: u16,
    // The deepest level tested against `max_depth` (saturating); 0 while none was.
    deepest: u8,
    // Whether photons were gathered.
    photons: bool,
}

/// +∞'s upper half.
const NO_WEIGHT: u16 = (f32::INFINITY.to_bits() >> 16) as u16;

impl Default for Met {
    fn default() -> Self {
        Met {
            bits: 0,
            lightest: NO_WEIGHT,
            deepest: 0,
            photons: false,
        }
    }
}

impl Met {
    /// A hit on material `m`.
    #[inline(always)]
    pub(crate) fn material(&mut self, m: u32) {
        // (MATERIAL_BITS is the width of `bits`: the shift takes m modulo it.)
        self.bits |= 1u32.wrapping_shl(m);
    }

    /// Photons gathered.
    #[inline(always)]
    pub(crate) fn photons(&mut self) {
        self.photons = true;
    }

    /// A branch at level `depth` with path weight `weight` tested against the limits.
    #[inline(always)]
    pub(crate) fn branch(&mut self, depth: u32, weight: f32) {
        self.deepest = self.deepest.max(depth.min(u8::MAX as u32) as u8);
        // Non-negative weights order as their bits do; NaN (which no limit prunes) sorts
        // above +inf and is never the lightest.
        let upper = (weight.to_bits() >> 16) as u16;
        self.lightest = self.lightest.min(upper);
    }

    /// Everything `other` met too.
    #[inline(always)]
    pub fn merge(&mut self, other: Met) {
        self.bits |= other.bits;
        self.photons |= other.photons;
        self.lightest = self.lightest.min(other.lightest);
        self.deepest = self.deepest.max(other.deepest);
    }

    /// Whether a change that reaches `reach` can alter what these samples gave.
    #[inline]
    pub fn meets(&self, reach: &Reach) -> bool {
        let lightest = f32::from_bits((self.lightest as u32) << 16);
        self.bits & reach.bits != 0
            || (self.photons && reach.photons)
            || reach.depth.is_some_and(|d| self.deepest as u32 > d)
            || reach.weight.is_some_and(|w| lightest < w)
    }
}

/// What a change of parameters can alter, sample by sample: see [`reach`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Reach {
    // The record's bits of the materials the change alters, and whether the photons.
    bits: u32,
    photons: bool,
    // A branch deeper than this is tested differently: the lower of the two `max_depth`s.
    depth: Option<u32>,
    // A branch lighter than this is tested differently: the higher of the two
    // `min_weight`s.
    weight: Option<f32>,
}

impl Reach {
    /// Whether the change alters no sample.
    pub fn is_nothing(&self) -> bool {
        *self == Reach::default()
    }
}

/// What changing the parameters from `old` to `new` can alter in an image of `scene` (the
/// camera and size the same): `None` for every sample, or what a sample must have met to
/// change ([`Met::meets`]). The exposure alters no sample, nor does the target samples per
/// pixel but of the regular and jittered patterns. Adaptive sampling's decisions are not
/// a sample's: a film it has decided on must start again whole whatever this says
/// ([`crate::render::Film::decided`]).
pub fn reach(scene: &Scene, old: &Params, new: &Params) -> Option<Reach> {
    // Every parameter but those a sample's record tells of (and those that alter none).
    // Regular and jittered samples are strata of the target count: a new target moves
    // every one.
    let by_count = matches!(new.pattern, Pattern::Regular | Pattern::Jittered);
    let global = |p: &Params| Params {
        spp: if by_count { p.spp } else { 0 },
        exposure: 0.0,
        ior: None,
        abbe: None,
        roughness: None,
        fresnel: None,
        constant_reflectance: None,
        absorption_scale: 0.0,
        phong_exponent: None,
        max_depth: 0,
        min_weight: 0.0,
        light_size: 0.0,
        // (Which pixels take more samples is decided on the film: see the module's doc.)
        noise_target: None,
        ..p.clone()
    };
    if global(old) != global(new) {
        return None;
    }
    // A point (or spot) light is the same at every size; an area light is not, and it
    // lights (or is seen by) nearly every pixel.
    let point = |l: &Light| match l.shape {
        LightShape::Spot { .. } => true,
        LightShape::Sphere { radius, .. } => radius == 0.0,
        LightShape::Rect { .. } | LightShape::Disk { .. } => false,
    };
    if old.light_size != new.light_size && !scene.lights.iter().all(point) {
        return None;
    }
    let mut reach = Reach::default();
    for (m, material) in scene.materials.iter().enumerate() {
        if material.with_params(old) != material.with_params(new) {
            reach.bits |= 1u32.wrapping_shl(m as u32);
        }
    }
    if old.max_depth != new.max_depth {
        reach.depth = Some(old.max_depth.min(new.max_depth));
    }
    if old.min_weight != new.min_weight {
        reach.weight = Some(old.min_weight.max(new.min_weight));
    }
    // The photon map is every material's and both limits'.
    if new.transport == Transport::Photons && !reach.is_nothing() {
        reach.photons = true;
    }
    Some(reach)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_change_reaches_what_it_governs_and_nothing_else() {
        let mut glass = Met::default();
        glass.material(2);
        let mut deep = Met::default();
        deep.branch(5, 0.5);
        let mut light = Met::default();
        light.branch(1, 0.011);
        let nothing = Met::default();
        let by_material = Reach {
            bits: 1 << 2,
            ..Reach::default()
        };
        assert!(glass.meets(&by_material) && !deep.meets(&by_material));
        let by_depth = Reach {
            depth: Some(4),
            ..Reach::default()
        };
        assert!(deep.meets(&by_depth) && !light.meets(&by_depth));
        let by_weight = Reach {
            weight: Some(0.02),
            ..Reach::default()
        };
        assert!(light.meets(&by_weight) && !deep.meets(&by_weight));
        for r in [by_material, by_depth, by_weight] {
            assert!(!nothing.meets(&r));
        }
        let mut all = nothing;
        for m in [glass, deep, light] {
            all.merge(m);
        }
        for r in [by_material, by_depth, by_weight] {
            assert!(all.meets(&r));
        }
    }
}
