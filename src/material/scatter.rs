//! What a material answers at a hit: its [`Scatter`], the child rays ([`Lobe`]) with the
//! kind of each, and the same split into the [`Part`]s a path chooses between, each of
//! which can say how much light it passes towards a direction and with what density it
//! would have drawn it.

use super::{Brdf, Interaction, Microfacet, glossy_pdf};
use crate::math::{Color, Vec3};

/// Which side of the surface a child ray leaves on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// Back into the medium the ray came from: a reflected ray.
    Reflect,
    /// Through the surface into the medium beyond: a refracted ray.
    Transmit,
}

/// How a lobe's direction was drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LobeKind {
    /// One direction only (a mirror, a polished metal, a reflected or refracted ray at an
    /// interface): no other direction carries light, so no light sample can find it.
    Delta,
    /// One sample of the Phong lobe cos^n α about the mirror direction, folded above the
    /// surface, of this exponent n: its density is [`glossy_pdf`].
    Glossy {
        /// The Phong exponent n.
        exponent: f32,
    },
    /// One facet of a rough interface drawn among those the ray sees, the child reflected
    /// or refracted there ([`Microfacet::eval`] gives its density towards any direction).
    Microfacet(Microfacet),
}

/// One child ray of a hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lobe {
    /// Reflected or refracted.
    pub side: Side,
    /// How its direction was drawn.
    pub kind: LobeKind,
    /// Its unit direction.
    pub dir: Vec3,
    /// What its radiance is multiplied by (R, 1 − R, a reflectance). The largest channel
    /// is its branch weight in the tree, and, in stochastic mode, the probability of
    /// following it: the lobes of one hit partition the light, their branch weights
    /// summing to at most 1.
    pub weight: Color,
}

impl Lobe {
    /// A lobe of one direction (mirror-like).
    pub fn delta(side: Side, dir: Vec3, weight: Color) -> Lobe {
        Lobe {
            side,
            kind: LobeKind::Delta,
            dir,
            weight,
        }
    }

    /// The density per unit solid angle with which this lobe draws `dir` at `at`, or `None`
    /// for a single direction (no density: nothing else can find it).
    #[inline]
    pub fn pdf(&self, at: &Interaction, dir: Vec3) -> Option<f32> {
        match self.kind {
            LobeKind::Delta => None,
            LobeKind::Glossy { exponent } => Some(glossy_pdf(at, exponent, dir)),
            LobeKind::Microfacet(facets) => Some(facets.eval(at, self.side, dir).1),
        }
    }

    /// Whether it has one direction only.
    #[inline]
    pub fn is_delta(&self) -> bool {
        self.kind == LobeKind::Delta
    }
}

/// The quantities of the lecture at a dielectric interface, for the inspector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interface {
    /// cos θi.
    pub cos_i: f32,
    /// Index of refraction on the side the ray comes from.
    pub n1: f32,
    /// Index of refraction on the other side.
    pub n2: f32,
    /// The reflectance the material used.
    pub r: f32,
}

/// Lights seen through a BRDF, the sum scaled by `scale` (1 − R under a glaze).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Direct {
    /// The BRDF at the hit.
    pub brdf: Brdf,
    /// The factor on the sum of ambient and lights.
    pub scale: f32,
}

/// What a material does with a ray that hits it (what it emits is
/// [`super::Material::emission`], asked first: a light ends the ray).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Scatter {
    /// Shading by the lights (one shadow ray each) and the ambient term.
    pub direct: Option<Direct>,
    /// Child rays, at most two.
    pub lobes: [Option<Lobe>; 2],
    /// The interface's quantities, where the surface is a dielectric interface.
    pub interface: Option<Interface>,
    /// The refracted ray does not exist: total internal reflection.
    pub total_internal_reflection: bool,
    /// A rough interface's facets, where the lobes are jittered over them: what a path's
    /// light samples see of the interface as a whole ([`Part::Interface`]).
    pub facets: Option<Microfacet>,
}

impl Scatter {
    /// The child rays.
    pub fn lobes(&self) -> impl Iterator<Item = &Lobe> {
        self.lobes.iter().flatten()
    }

    /// The parts a path chooses between: the smooth BRDF, then the child rays.
    #[inline]
    pub fn parts(&self) -> [Option<Part<'_>>; 3] {
        [
            self.direct.as_ref().map(Part::Smooth),
            self.lobes[0].as_ref().map(Part::Lobe),
            self.lobes[1].as_ref().map(Part::Lobe),
        ]
    }
}

/// One part of a hit's scattering, as path tracing and photons choose between them.
#[derive(Clone, Copy, Debug)]
pub enum Part<'s> {
    /// The smooth BRDF (diffuse plus Phong highlight), times the scale a glaze's coat leaves
    /// it: lit by light samples, and the path goes on in a direction the BRDF draws.
    Smooth(&'s Direct),
    /// A child ray, its direction already drawn.
    Lobe(&'s Lobe),
    /// A rough interface as a whole, both its lobes ([`Microfacet::eval_path`]): what a
    /// path's light samples see of it. Never chosen: a path follows one of its lobes.
    Interface(&'s Microfacet),
}

impl Part<'_> {
    /// Its weight: the largest channel of the light it passes on (at most 1 in all).
    #[inline]
    pub fn weight(&self) -> f32 {
        match self {
            Part::Smooth(d) => d.scale * (d.brdf.albedo + d.brdf.specular).max_element(),
            Part::Lobe(lobe) => lobe.weight.max_element(),
            Part::Interface(_) => 0.0,
        }
    }

    /// Whether it passes light in one direction only: no light sample can find it.
    #[inline]
    pub fn is_delta(&self) -> bool {
        matches!(self, Part::Lobe(lobe) if lobe.is_delta())
    }

    /// Whether a path that follows it samples the lights through it: not for one
    /// direction, and not for a lobe of a rough interface, whose light samples see the
    /// interface whole ([`Part::Interface`]) whichever lobe the path follows (which lobes
    /// a hit has depends on the facet it draws).
    #[inline]
    pub fn lit_by_samples(&self) -> bool {
        match self {
            Part::Lobe(lobe) => matches!(lobe.kind, LobeKind::Glossy { .. }),
            Part::Smooth(_) | Part::Interface(_) => true,
        }
    }

    /// f cos θ towards `dir` (what light arriving from `dir` is multiplied by), and the
    /// density with which this part would draw `dir`: for the smooth BRDF
    /// scale · f(dir, view) cos θ and [`Brdf::pdf`] (0 below the surface); for a glossy
    /// lobe W · pdf and pdf, since its weight W is f cos θ / pdf; for a rough lobe
    /// [`Microfacet::eval`], for a rough interface [`Microfacet::eval_path`]; for one
    /// direction, 0.
    #[inline]
    pub fn eval(&self, at: &Interaction, dir: Vec3) -> (Color, f32) {
        match self {
            Part::Smooth(d) => {
                let cos = at.n_shade.dot(dir);
                if cos <= 0.0 || at.n_geom.dot(dir) <= 0.0 {
                    return (Color::ZERO, 0.0);
                }
                let view = -at.dir;
                (
                    d.scale * cos * d.brdf.eval(at.n_shade, dir, view),
                    d.brdf.pdf(at.n_shade, dir, view),
                )
            }
            Part::Lobe(lobe) => match lobe.kind {
                LobeKind::Microfacet(facets) => {
                    let (f_cos, pdf) = facets.eval(at, lobe.side, dir);
                    (Color::splat(f_cos), pdf)
                }
                _ => match lobe.pdf(at, dir) {
                    Some(pdf) => (lobe.weight * pdf, pdf),
                    None => (Color::ZERO, 0.0),
                },
            },
            Part::Interface(facets) => {
                let (f_cos, pdf) = facets.eval_path(at, dir);
                (Color::splat(f_cos), pdf)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::test_util::{Fixed, hit_at};
    use crate::material::{
        Conductor, Dielectric, Diffuse, Emissive, Glazed, Glossy, Material, Mirror, Texture,
    };

    /// One material of every kind (a conductor both polished and brushed).
    fn every_kind() -> Vec<Material> {
        let metal = crate::material::metal("gold").unwrap();
        let gold = Conductor {
            eta: metal.eta(),
            k: metal.k(),
            exponent: None,
        };
        vec![
            Material::Diffuse(Diffuse::solid(Color::splat(0.5))),
            Material::Mirror(Mirror {
                reflectance: Color::splat(0.9),
            }),
            Material::Glossy(Glossy {
                reflectance: Color::splat(0.8),
                exponent: 40.0,
            }),
            Material::Conductor(gold.clone()),
            Material::Conductor(Conductor {
                exponent: Some(25.0),
                ..gold
            }),
            Material::Emissive(Emissive::solid(Color::splat(3.0))),
            Material::Diffuse(Diffuse {
                emission: Some(Texture::Solid(Color::splat(2.0))),
                ..Diffuse::solid(Color::splat(0.5))
            }),
            Material::Dielectric(Dielectric::clear(1.5)),
            Material::Dielectric(Dielectric {
                roughness: 0.3,
                ..Dielectric::clear(1.5)
            }),
            Material::Glazed(Glazed {
                coat: Dielectric::clear(1.5),
                base: Texture::Solid(Color::ZERO),
            }),
        ]
    }

    #[test]
    fn every_kind_answers_each_question_as_its_scatter_shows() {
        let hit = hit_at(35.0);
        for m in every_kind() {
            let s = m.scatter(&hit, &mut Fixed(vec![0.3, 0.6]));
            let kind = m.kind();
            // The lobes say how they were drawn: glossy exactly where the exponent is, over
            // facets exactly where the interface is rough.
            for lobe in s.lobes() {
                match (m.phong_exponent(), m.roughness()) {
                    (Some(exponent), _) => {
                        assert_eq!(lobe.kind, LobeKind::Glossy { exponent }, "{kind}")
                    }
                    (None, Some(alpha)) if alpha > 0.0 => assert!(
                        matches!(lobe.kind, LobeKind::Microfacet(f) if f.alpha == alpha),
                        "{kind}"
                    ),
                    (None, _) => assert_eq!(lobe.kind, LobeKind::Delta, "{kind}"),
                }
            }
            // Photons pass it one way exactly where every lobe has one direction.
            let one_way = s.lobes().count() > 0 && s.lobes().all(Lobe::is_delta);
            assert_eq!(m.mirror_like(), one_way, "{kind}");
            // A light scatters nothing: its rays end there; a glowing surface scatters as
            // it would without its glow.
            if m.is_light() {
                assert_eq!(s, Scatter::default(), "{kind}");
                assert_eq!(m.glow(hit.uv), None, "{kind}");
            }
            assert_eq!(m.emission(hit.uv).is_some(), m.emits(), "{kind}");
            assert_eq!(m.light_emission(hit.uv).is_some(), m.is_light(), "{kind}");
            if let Material::Diffuse(d) = &m
                && d.emission.is_some()
            {
                let plain = Material::Diffuse(Diffuse {
                    emission: None,
                    ..d.clone()
                });
                assert_eq!(plain.scatter(&hit, &mut Fixed(vec![0.3, 0.6])), s, "{kind}");
            }
            // A shadow ray passes only where light can enter (a glaze's base is opaque).
            let enters = s.lobes().any(|l| l.side == Side::Transmit);
            assert_eq!(m.shadow_transmittance(&hit).is_some(), enters, "{kind}");
        }
    }

    #[test]
    fn a_glossy_part_passes_its_weight_times_its_density() {
        let at = hit_at(50.0);
        let lobe = Lobe {
            side: Side::Reflect,
            kind: LobeKind::Glossy { exponent: 30.0 },
            dir: at.mirror_dir(),
            weight: Color::new(0.9, 0.5, 0.2),
        };
        let dir = (at.mirror_dir() + Vec3::new(0.05, 0.0, 0.02)).normalize();
        let (f_cos, pdf) = Part::Lobe(&lobe).eval(&at, dir);
        assert_eq!(pdf, glossy_pdf(&at, 30.0, dir));
        assert!(pdf > 0.0);
        assert_eq!(f_cos, lobe.weight * pdf);
        // One direction: nothing for any other, and no density.
        let mirror = Lobe::delta(Side::Reflect, at.mirror_dir(), Color::ONE);
        assert_eq!(Part::Lobe(&mirror).eval(&at, dir), (Color::ZERO, 0.0));
        assert_eq!(mirror.pdf(&at, mirror.dir), None);
        assert!(Part::Lobe(&mirror).is_delta() && !Part::Lobe(&lobe).is_delta());
    }
}
