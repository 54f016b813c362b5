//! Materials: a closed set, each with the lecture's shading model.

use crate::math::Color;
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
    /// A surface that emits light (and reflects none).
    Emissive {
        /// Emitted radiance.
        radiance: Color,
    },
}

impl Material {
    /// A short name of the material's kind, for listings and the inspector.
    pub fn kind(&self) -> &'static str {
        match self {
            Material::Diffuse { .. } => "diffuse",
            Material::Mirror { .. } => "mirror",
            Material::Emissive { .. } => "emissive",
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
