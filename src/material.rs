//! Materials: a closed set, each with the lecture's shading model.

use crate::math::Color;
use crate::optics::FresnelMode;
use crate::params::Params;
use glam::Vec2;

/// A colour that may vary over a surface.
#[derive(Clone, Debug, PartialEq)]
pub enum Texture {
    /// One colour everywhere.
    Solid(Color),
    /// Squares of two colours, `scale` squares per unit of the surface coordinates
    /// (world units on planes; the whole surface is 0..1 on spheres, quads and meshes).
    Checker {
        /// Colour of the squares where floor(u s) + floor(v s) is even.
        even: Color,
        /// Colour of the others.
        odd: Color,
        /// Squares per unit.
        scale: f32,
    },
}

impl Texture {
    /// The colour at surface coordinates `uv`.
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Color {
        match self {
            Texture::Solid(c) => *c,
            Texture::Checker { even, odd, scale } => {
                let k = (uv.x * scale).floor() as i64 + (uv.y * scale).floor() as i64;
                if k.rem_euclid(2) == 0 { *even } else { *odd }
            }
        }
    }
}

/// How a surface scatters light.
#[derive(Clone, Debug, PartialEq)]
pub enum Material {
    /// Lambertian diffuse reflection, with an optional Phong highlight: the basic shading
    /// of a ray tracer. BRDF f = albedo/π + specular (n+2)/(2π) cos^n α, where α is the
    /// angle between the mirror direction of the light and the view direction (the
    /// normalized Phong lobe, so `specular` is the fraction of light it reflects).
    Diffuse {
        /// Diffuse reflectance, 0..1 per channel.
        albedo: Texture,
        /// Reflectance of the Phong highlight (0 for none).
        specular: Color,
        /// Phong exponent n: higher is a smaller, sharper highlight.
        exponent: f32,
    },
    /// An ideal mirror or polished metal: the reflected ray, scaled by a constant
    /// reflectance (metals reflect strongly at every angle, with a colour).
    Mirror {
        /// Reflectance, 0..1 per channel.
        reflectance: Color,
    },
    /// A glossy metal: the mirror direction jittered over the Phong lobe cos^n α around it
    /// (the lecture's glossy reflection), times the reflectance. Higher n is sharper; the
    /// lobe is importance-sampled, so each jittered ray carries the reflectance exactly.
    Glossy {
        /// Reflectance, 0..1 per channel.
        reflectance: Color,
        /// Phong exponent n.
        exponent: f32,
    },
    /// A surface that emits light (and reflects none).
    Emissive {
        /// Emitted radiance.
        radiance: Color,
    },
    /// A clear or coloured dielectric (glass, water, an air bubble): every hit splits into
    /// a reflected ray of weight R and a refracted ray of weight 1 − R, R from the
    /// Fresnel mode. Light travelling inside is attenuated by Beer–Lambert, exp(−σ d).
    Dielectric(Dielectric),
    /// The lecture's glazed surface: a clear coat over a base colour. The coat reflects R
    /// (Fresnel or constant); the transmitted ray is not traced: the base's diffuse shading
    /// takes the remaining 1 − R.
    Glazed {
        /// The coat's interface.
        coat: Dielectric,
        /// Diffuse colour of the base (black for the black glazed sphere).
        base: Texture,
    },
}

/// The optical properties of a dielectric interface.
#[derive(Clone, Debug, PartialEq)]
pub struct Dielectric {
    /// Index of refraction of the material.
    pub ior: f32,
    /// True keeps `ior` when the `ior` parameter is set (for air bubbles and the like).
    pub ior_fixed: bool,
    /// How the reflectance is computed.
    pub fresnel: FresnelMode,
    /// The reflectance k in [`FresnelMode::Constant`].
    pub constant_reflectance: f32,
    /// Absorption coefficient σ per unit length, per channel (0: clear).
    pub absorption: Color,
}

impl Material {
    /// A short name of the material's kind, for listings and the inspector.
    pub fn kind(&self) -> &'static str {
        match self {
            Material::Diffuse { .. } => "diffuse",
            Material::Mirror { .. } => "mirror",
            Material::Glossy { .. } => "glossy",
            Material::Emissive { .. } => "emissive",
            Material::Dielectric(_) => "dielectric",
            Material::Glazed { .. } => "glazed",
        }
    }

    /// This material with the parameters' overrides applied: `ior` (unless the material
    /// fixes its own), `fresnel`, `constant_reflectance`, `absorption_scale` and
    /// `phong_exponent`.
    pub fn with_params(&self, params: &Params) -> Material {
        let apply = |d: &Dielectric| Dielectric {
            ior: match params.ior {
                Some(ior) if !d.ior_fixed => ior,
                _ => d.ior,
            },
            fresnel: params.fresnel.unwrap_or(d.fresnel),
            constant_reflectance: params
                .constant_reflectance
                .unwrap_or(d.constant_reflectance),
            ..d.clone()
        };
        match self {
            Material::Dielectric(d) => Material::Dielectric(apply(d)),
            Material::Glazed { coat, base } => Material::Glazed {
                coat: apply(coat),
                base: base.clone(),
            },
            Material::Glossy {
                reflectance,
                exponent,
            } => Material::Glossy {
                reflectance: *reflectance,
                exponent: params.phong_exponent.unwrap_or(*exponent),
            },
            other => other.clone(),
        }
    }

    /// The dielectric interface of this material, if it has one.
    pub fn dielectric(&self) -> Option<&Dielectric> {
        match self {
            Material::Dielectric(d) | Material::Glazed { coat: d, .. } => Some(d),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checker_alternates_in_both_directions() {
        let t = Texture::Checker {
            even: Color::ONE,
            odd: Color::ZERO,
            scale: 2.0,
        };
        assert_eq!(t.eval(Vec2::new(0.1, 0.1)), Color::ONE);
        assert_eq!(t.eval(Vec2::new(0.6, 0.1)), Color::ZERO);
        assert_eq!(t.eval(Vec2::new(0.6, 0.6)), Color::ONE);
        // Across zero the pattern continues instead of mirroring.
        assert_eq!(t.eval(Vec2::new(-0.1, 0.1)), Color::ZERO);
    }
}
