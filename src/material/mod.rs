//! Materials: each kind's data and every answer about it, in the spirit of pbrt's BxDFs.
//!
//! At a hit the tracer asks the material whether it is a light (`Material::light_emission`:
//! the ray ends there), and otherwise [`Material::scatter`] (and what it glows,
//! `Material::glow`, added to its shading), and gets a [`Scatter`]: which BRDF
//! the lights are seen through (shadow rays), and which child rays it spawns with which
//! weights, each [`Lobe`] saying how its direction was drawn ([`LobeKind`]) and with what
//! density; [`Scatter::parts`] is the same split as path tracing chooses between. The other
//! questions are the material's too: whether it emits (for light samples of emitting
//! surfaces, [`Material::emits`]), whether photons
//! pass it in one direction ([`Material::mirror_like`]), what a transmissive shadow ray
//! keeps crossing it ([`Material::shadow_transmittance`]), its Mueller matrices (the
//! polariser), and whether it disperses or absorbs. The tracer walks the tree, prunes,
//! counts and records; it knows no material kinds. A new kind is its data and its answers
//! in a file of its own, a variant here, and its scene key: every `match` here is
//! exhaustive, so the compiler lists each question the new kind must answer.

mod dielectric;
mod diffuse;
mod image;
mod metals;
mod rough;
mod scatter;
mod specular;
mod texture;

pub use dielectric::{Dielectric, Glazed};
pub(crate) use dielectric::{Split, split_lanes};
pub use diffuse::{Brdf, Diffuse};
pub use image::{ImageMap, Texels, Wrap};
pub use metals::{METALS, Metal, find_metal, metal, metal_names};
pub use rough::Microfacet;
pub use scatter::{Direct, Interface, Lobe, LobeKind, Part, Scatter, Side};
pub use specular::{Conductor, Glossy, Mirror, glossy_pdf};
pub use texture::Texture;

use crate::math::lanes::Lanes;
use crate::math::lanes::{Real, Vector, clamp};
use crate::math::{Color, Uniform, Vec3};
use crate::optics::polarization::Mueller;
use crate::optics::reflect_of;
use crate::params::Params;
use glam::Vec2;

/// How a surface scatters light.
#[derive(Clone, Debug, PartialEq)]
pub enum Material {
    /// Lambert plus an optional Phong highlight, lit by shadow rays: the basic shading (and
    /// a glow added, where it has an emission).
    Diffuse(Diffuse),
    /// An ideal mirror or polished metal: a constant reflectance at every angle.
    Mirror(Mirror),
    /// A glossy metal: the mirror direction jittered over a Phong lobe.
    Glossy(Glossy),
    /// A metal of complex index η + iκ: reflectance by the conductor Fresnel equations.
    Conductor(Conductor),
    /// A surface that emits light (and reflects none).
    Emissive(Emissive),
    /// A clear or coloured dielectric: reflected and refracted rays weighted by Fresnel.
    Dielectric(Dielectric),
    /// The lecture's glazed surface: a dielectric coat over a diffuse base.
    Glazed(Glazed),
}

/// A surface that emits light (and reflects none).
#[derive(Clone, Debug, PartialEq)]
pub struct Emissive {
    /// Emitted radiance, which may vary over the surface (an emitting checkerboard is one
    /// textured quad).
    pub radiance: Texture,
}

impl Emissive {
    /// A surface emitting `radiance` everywhere.
    pub fn solid(radiance: Color) -> Emissive {
        Emissive {
            radiance: Texture::Solid(radiance),
        }
    }
}

/// A hit as a material sees it.
#[derive(Clone, Copy, Debug)]
pub struct Interaction {
    /// The incoming ray's unit direction (towards the surface).
    pub dir: Vec3,
    /// Surface coordinates, for textures.
    pub uv: Vec2,
    /// The geometric normal, facing the side the ray arrived from.
    pub n_geom: Vec3,
    /// The shading normal, facing the side the ray arrived from.
    pub n_shade: Vec3,
    /// Whether the ray arrived from the surface's outside (against its own normal).
    pub entering: bool,
    /// The index of refraction on the surface's outer side: the medium an entering ray
    /// travels in, or the one a leaving ray goes out to (at `wavelength`).
    pub outside_ior: f32,
    /// The wavelength (nm) the ray carries since it met a dispersive surface, if it has.
    pub wavelength: Option<f32>,
}

impl Interaction {
    /// cos θi, the cosine between the reversed ray and the shading normal.
    #[inline]
    pub fn cos_i(&self) -> f32 {
        cos_i_of::<f32>(self.dir, self.n_shade)
    }

    /// The mirror direction about the shading normal, or about the geometric one where the
    /// shading normal would tilt it below the surface.
    #[inline]
    pub fn mirror_dir(&self) -> Vec3 {
        mirror_dir_of::<f32>(self.dir, self.n_geom, self.n_shade)
    }
}

/// [`Interaction::cos_i`] for one ray or one per lane: (−dir)·n_shade clamped to [0, 1].
#[inline(always)]
pub(crate) fn cos_i_of<R: Real>(dir: R::V3, n_shade: R::V3) -> R {
    clamp(dir.neg().dot(n_shade), R::splat(0.0), R::splat(1.0))
}

/// [`Interaction::mirror_dir`] for one ray or one per lane.
#[inline(always)]
pub(crate) fn mirror_dir_of<R: Real>(dir: R::V3, n_geom: R::V3, n_shade: R::V3) -> R::V3 {
    let about_shade = reflect_of::<R>(dir, n_shade);
    let above = R::splat(0.0).less(about_shade.dot(n_geom));
    if R::all(above) {
        return about_shade;
    }
    R::V3::select(above, about_shade, reflect_of::<R>(dir, n_geom))
}

impl Material {
    /// A short name of the material's kind, for listings and the inspector.
    pub fn kind(&self) -> &'static str {
        match self {
            Material::Diffuse(_) => "diffuse",
            Material::Mirror(_) => "mirror",
            Material::Glossy(_) => "glossy",
            Material::Conductor(_) => "conductor",
            Material::Emissive(_) => "emissive",
            Material::Dielectric(_) => "dielectric",
            Material::Glazed(_) => "glazed",
        }
    }

    /// What this material does at `hit`, drawing the uniform numbers it needs from `u`.
    // Always in line: as a call its 240-byte result goes through memory at every hit
    // (docs/performance.md, "Shaped by measurement").
    #[inline(always)]
    pub fn scatter(&self, hit: &Interaction, u: &mut impl Uniform) -> Scatter {
        match self {
            Material::Diffuse(m) => m.scatter(hit),
            Material::Mirror(m) => m.scatter(hit),
            Material::Glossy(m) => m.scatter(hit, u),
            Material::Conductor(m) => m.scatter(hit, u),
            // It emits (`emission`) and reflects nothing.
            Material::Emissive(_) => Scatter::default(),
            Material::Dielectric(m) if m.is_rough() => m.rough_scatter(hit, u),
            Material::Dielectric(m) => m.scatter(hit),
            Material::Glazed(m) => m.scatter(hit),
        }
    }

    /// The radiance it emits at surface coordinates `uv`, if it emits: as a light (which
    /// reflects nothing) or as a glowing surface (which reflects as well). What a path
    /// adds where it meets the surface, and what light samples of emitting surfaces see.
    #[inline]
    pub fn emission(&self, uv: Vec2) -> Option<Color> {
        self.light_emission(uv).or_else(|| self.glow(uv))
    }

    /// The radiance it emits at `uv` if it is a light: it emits and reflects nothing, so a
    /// ray that meets it ends there with this radiance.
    #[inline]
    pub(crate) fn light_emission(&self, uv: Vec2) -> Option<Color> {
        self.light().map(|e| e.radiance.eval(uv))
    }

    /// The radiance it emits at `uv` if it glows: a surface that emits and also reflects (a
    /// diffuse surface with an `emission`), whose emission is added to its shading by the
    /// lights (L = Le + ambient + Σ lights), as glTF adds emission to the base colour's.
    #[inline(always)]
    pub(crate) fn glow(&self, uv: Vec2) -> Option<Color> {
        match self {
            Material::Diffuse(d) => d.emission.as_ref().map(|e| e.eval(uv)),
            Material::Mirror(_)
            | Material::Glossy(_)
            | Material::Conductor(_)
            | Material::Emissive(_)
            | Material::Dielectric(_)
            | Material::Glazed(_) => None,
        }
    }

    /// [`Material::light_emission`] at `N` points (surface coordinates u and v per lane):
    /// each lane's radiance, or `None` if it is not a light.
    #[inline(always)]
    pub(crate) fn emission_lanes<const N: usize>(
        &self,
        u: Lanes<N>,
        v: Lanes<N>,
    ) -> Option<[Color; N]> {
        self.light().map(|e| e.radiance.eval_lanes(u, v))
    }

    /// The interface every hit on it splits into a reflected and a refracted ray of
    /// weights R and 1 − R and nothing else (clear or coloured glass, not a glaze, whose
    /// base is shaded too): what the waves split in lanes ([`split_lanes`]).
    #[inline]
    pub(crate) fn splitting(&self) -> Option<&Dielectric> {
        match self {
            Material::Dielectric(d) if !d.is_rough() => Some(d),
            Material::Dielectric(_)
            | Material::Diffuse(_)
            | Material::Mirror(_)
            | Material::Glossy(_)
            | Material::Conductor(_)
            | Material::Emissive(_)
            | Material::Glazed(_) => None,
        }
    }

    /// Its shading by the lights at surface coordinates `uv`, where that is all it does
    /// (no child rays, no emission: a diffuse surface): what the waves shade from the hit
    /// without building an [`Interaction`] or a [`Scatter`].
    #[inline(always)]
    pub(crate) fn direct_only(&self, uv: Vec2) -> Option<Direct> {
        match self {
            Material::Diffuse(d) => Some(d.direct(uv)),
            Material::Mirror(_)
            | Material::Glossy(_)
            | Material::Conductor(_)
            | Material::Emissive(_)
            | Material::Dielectric(_)
            | Material::Glazed(_) => None,
        }
    }

    /// Its emission, if it is a light.
    #[inline(always)]
    fn light(&self) -> Option<&Emissive> {
        match self {
            Material::Emissive(e) => Some(e),
            Material::Diffuse(_)
            | Material::Mirror(_)
            | Material::Glossy(_)
            | Material::Conductor(_)
            | Material::Dielectric(_)
            | Material::Glazed(_) => None,
        }
    }

    /// Whether it emits light (a light or a glowing surface): path tracing then samples
    /// points on it as it samples the lights.
    pub fn emits(&self) -> bool {
        self.emission(Vec2::ZERO).is_some()
    }

    /// Whether it is a light: it emits and reflects nothing, and a ray ends at it.
    pub(crate) fn is_light(&self) -> bool {
        self.light().is_some()
    }

    /// Whether light can leave it in one direction only, as from a mirror, glass, a
    /// polished metal or a glaze's coat: photons from point lights are aimed at such
    /// objects and followed through them (a glossy or diffuse surface ends them).
    pub fn mirror_like(&self) -> bool {
        match self {
            Material::Mirror(_) | Material::Glazed(_) => true,
            Material::Dielectric(d) => !d.is_rough(),
            Material::Conductor(c) => c.exponent.is_none(),
            Material::Diffuse(_) | Material::Glossy(_) | Material::Emissive(_) => false,
        }
    }

    /// What a shadow ray keeps crossing this surface straight, unbent, at `hit` (the
    /// transmissive shadows' approximation), or `None` where the surface blocks it: a
    /// clear or coloured dielectric passes 1 − R at the ray's wavelength; every other
    /// surface, a glaze's opaque base included, blocks. Absorption inside is the tracer's
    /// (it knows how far the ray travels).
    #[inline]
    pub fn shadow_transmittance(&self, hit: &Interaction) -> Option<Color> {
        match self {
            Material::Dielectric(d) => Some(Color::splat(d.shadow_transmittance(hit))),
            Material::Diffuse(_)
            | Material::Mirror(_)
            | Material::Glossy(_)
            | Material::Conductor(_)
            | Material::Emissive(_)
            | Material::Glazed(_) => None,
        }
    }

    /// Where child `lobe` of `hit` is polarised in a plane of incidence that is not the
    /// surface's (a rough interface's facet): that facet's normal and the child's Mueller
    /// matrix in its s/p frame.
    pub fn facet_mueller(&self, hit: &Interaction, lobe: &Lobe) -> Option<(Vec3, Mueller)> {
        match self {
            Material::Dielectric(d) if d.is_rough() => d.facet_mueller(hit, lobe),
            _ => None,
        }
    }

    /// The Mueller matrix (in the s/p frame of `hit`, or of [`Material::facet_mueller`]'s
    /// facet) of the child ray on `side`, or for a
    /// glaze's `Transmit` the way its base's light comes out through the coat. Mirrors and
    /// glossy metals reflect without polarising; materials without that lobe, `None`.
    pub fn mueller(&self, hit: &Interaction, lobe: Option<&Lobe>, side: Side) -> Option<Mueller> {
        match (self, side) {
            // A rough interface's child polarises in its facet's plane of incidence
            // ([`Material::facet_mueller`] gives the frame this matrix is in).
            (Material::Dielectric(d), _) if d.is_rough() => {
                lobe.and_then(|l| d.facet_mueller(hit, l)).map(|(_, m)| m)
            }
            (Material::Dielectric(d), _) => Some(d.child_mueller(hit, side)),
            (Material::Glazed(g), _) => Some(g.mueller(hit, side)),
            (Material::Conductor(c), Side::Reflect) => Some(c.mueller(hit)),
            (Material::Mirror(_) | Material::Glossy(_), Side::Reflect) => {
                lobe.map(|l| Mueller::neutral_reflection(l.weight))
            }
            (
                Material::Conductor(_) | Material::Mirror(_) | Material::Glossy(_),
                Side::Transmit,
            )
            | (Material::Diffuse(_) | Material::Emissive(_), _) => None,
        }
    }

    /// This material with the parameters' overrides applied: `ior` (unless the material
    /// fixes its own), `fresnel`, `constant_reflectance`, `absorption_scale` and
    /// `phong_exponent`.
    pub fn with_params(&self, params: &Params) -> Material {
        match self {
            Material::Dielectric(d) => Material::Dielectric(d.with_params(params)),
            // (A glaze's coat is smooth whatever the `roughness`: unchanged by it.)
            Material::Glazed(g) => Material::Glazed(Glazed {
                coat: Dielectric {
                    roughness: g.coat.roughness,
                    ..g.coat.with_params(params)
                },
                base: g.base.clone(),
            }),
            Material::Glossy(g) => Material::Glossy(Glossy {
                reflectance: g.reflectance,
                exponent: params.phong_exponent.unwrap_or(g.exponent),
            }),
            Material::Conductor(c) => Material::Conductor(Conductor {
                exponent: c.exponent.map(|n| params.phong_exponent.unwrap_or(n)),
                ..c.clone()
            }),
            // No parameter reaches these (a diffuse highlight's exponent is its own).
            Material::Diffuse(_) | Material::Mirror(_) | Material::Emissive(_) => self.clone(),
        }
    }

    /// The dielectric interface of this material, if it has one: its index of refraction
    /// and, for a body light enters, its absorption.
    pub fn dielectric(&self) -> Option<&Dielectric> {
        match self {
            Material::Dielectric(d) | Material::Glazed(Glazed { coat: d, .. }) => Some(d),
            Material::Diffuse(_)
            | Material::Mirror(_)
            | Material::Glossy(_)
            | Material::Conductor(_)
            | Material::Emissive(_) => None,
        }
    }

    /// Whether a ray that meets it must carry a wavelength: its index of refraction
    /// depends on the wavelength. (A glaze's coat ignores its Abbe number.)
    pub fn needs_wavelength(&self) -> bool {
        match self {
            Material::Dielectric(d) => d.disperses(),
            Material::Diffuse(_)
            | Material::Mirror(_)
            | Material::Glossy(_)
            | Material::Conductor(_)
            | Material::Emissive(_)
            | Material::Glazed(_) => false,
        }
    }

    /// Whether light travelling inside it is absorbed (Beer–Lambert): without such a
    /// material in a scene, no ray needs the exponential.
    pub fn absorbs(&self) -> bool {
        match self {
            Material::Dielectric(d) => d.absorption != Color::ZERO,
            // A glaze's coat is a surface: nothing enters it.
            Material::Diffuse(_)
            | Material::Mirror(_)
            | Material::Glossy(_)
            | Material::Conductor(_)
            | Material::Emissive(_)
            | Material::Glazed(_) => false,
        }
    }

    /// Whether its scattering reads surface coordinates (a checker or an image).
    pub fn uses_uv(&self) -> bool {
        let textured = |t: &Texture| !matches!(t, Texture::Solid(_));
        match self {
            Material::Diffuse(d) => {
                textured(&d.albedo) || d.emission.as_ref().is_some_and(textured)
            }
            Material::Glazed(g) => textured(&g.base),
            Material::Emissive(e) => textured(&e.radiance),
            Material::Mirror(_)
            | Material::Glossy(_)
            | Material::Conductor(_)
            | Material::Dielectric(_) => false,
        }
    }

    /// The Phong exponent the `phong_exponent` parameter replaces, if this is glossy: then
    /// its reflected ray is one sample of the Phong lobe about the mirror direction (a
    /// [`LobeKind::Glossy`] lobe), not the one direction of a mirror.
    pub fn phong_exponent(&self) -> Option<f32> {
        match self {
            Material::Glossy(g) => Some(g.exponent),
            Material::Conductor(c) => c.exponent,
            Material::Diffuse(_)
            | Material::Mirror(_)
            | Material::Emissive(_)
            | Material::Dielectric(_)
            | Material::Glazed(_) => None,
        }
    }

    /// The roughness α the `roughness` parameter replaces, if this is a dielectric whose
    /// interface the parameter reaches (not one with `ior_fixed`): above 0 its children
    /// are jittered over facets (a [`LobeKind::Microfacet`] lobe each).
    pub fn roughness(&self) -> Option<f32> {
        match self {
            Material::Dielectric(d) if !d.ior_fixed => Some(d.roughness),
            Material::Dielectric(_)
            | Material::Diffuse(_)
            | Material::Mirror(_)
            | Material::Glossy(_)
            | Material::Conductor(_)
            | Material::Emissive(_)
            | Material::Glazed(_) => None,
        }
    }
}

#[cfg(test)]
pub(crate) mod test_util {
    use super::*;

    /// Fixed uniform numbers, handed out in order.
    pub struct Fixed(pub Vec<f32>);

    impl Uniform for Fixed {
        fn next_1d(&mut self) -> f32 {
            self.0.remove(0)
        }
        fn next_2d(&mut self) -> Vec2 {
            Vec2::new(self.0.remove(0), self.0.remove(0))
        }
        fn skip(&mut self, _n: u32) {}
    }

    /// A ray arriving from the outside at `theta` degrees from the normal +Y, in air.
    pub fn hit_at(theta_deg: f32) -> Interaction {
        let t = theta_deg.to_radians();
        Interaction {
            dir: Vec3::new(t.sin(), -t.cos(), 0.0),
            uv: Vec2::ZERO,
            n_geom: Vec3::Y,
            n_shade: Vec3::Y,
            entering: true,
            outside_ior: 1.0,
            wavelength: None,
        }
    }
}
