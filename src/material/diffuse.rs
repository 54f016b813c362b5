//! Diffuse surfaces: Lambert plus an optional normalized Phong highlight, lit by shadow rays,
//! and optionally glowing.

use super::{Direct, Interaction, Scatter, Texture};
use crate::math::sampling::{cosine_hemisphere, phong_lobe, phong_lobe_pdf, to_world};
use crate::math::{Color, Vec3};
use crate::optics::reflect;
use glam::Vec2;
use std::f32::consts::PI;

/// Lambertian diffuse reflection, with an optional Phong highlight: the basic shading of a
/// ray tracer. Its light comes from the lights (shadow rays) and the ambient term; it
/// spawns no child rays.
#[derive(Clone, Debug, PartialEq)]
pub struct Diffuse {
    /// Diffuse reflectance, 0..1 per channel.
    pub albedo: Texture,
    /// Reflectance of the Phong highlight (0 for none).
    pub specular: Color,
    /// Phong exponent n: higher is a smaller, sharper highlight.
    pub exponent: f32,
    /// The radiance it emits besides what it reflects, if it glows (a glTF material's
    /// emission over its base colour, a `.mtl`'s `Ke` over its `Kd`): where it is dark, the
    /// surface is still its albedo, lit.
    pub emission: Option<Texture>,
}

/// A BRDF at one point: f = albedo/π + specular (n+2)/(2π) cos^n α, where α is the angle
/// between the mirror direction of the light and the view direction (the normalized Phong
/// lobe, so `specular` is the fraction of light it reflects).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Brdf {
    /// Diffuse reflectance here; also what the ambient term is multiplied by.
    pub albedo: Color,
    /// Reflectance of the Phong highlight.
    pub specular: Color,
    /// Phong exponent n.
    pub exponent: f32,
}

impl Brdf {
    /// f(l, v) for light arriving from `to_light` (unit), seen from `view` (unit, away
    /// from the surface), about the shading normal `n`.
    #[inline]
    pub fn eval(&self, n: Vec3, to_light: Vec3, view: Vec3) -> Color {
        let mut f = self.albedo / PI;
        if self.specular != Color::ZERO {
            let cos_alpha = reflect(-to_light, n).dot(view).max(0.0);
            f += self.specular * (self.exponent + 2.0) / (2.0 * PI) * cos_alpha.powf(self.exponent);
        }
        f
    }
}

impl Brdf {
    /// The probability that [`Brdf::sample`] draws from the Phong lobe rather than the
    /// cosine: in proportion to the reflectances.
    fn highlight_share(&self) -> f32 {
        let (d, s) = (self.albedo.max_element(), self.specular.max_element());
        if s > 0.0 { s / (d + s) } else { 0.0 }
    }

    /// A direction to gather light from, seen from `view` about the normal `n`: with
    /// probability ∝ the diffuse reflectance from the cosine lobe about n, else from the
    /// Phong lobe about the mirror direction of `view` (`pick` chooses, `u` places it).
    /// Its density is [`Brdf::pdf`]; it may fall below the surface, where f cos θ is 0.
    pub fn sample(&self, n: Vec3, view: Vec3, pick: f32, u: Vec2) -> Vec3 {
        if pick < self.highlight_share() {
            to_world(phong_lobe(u, self.exponent), reflect(-view, n))
        } else {
            to_world(cosine_hemisphere(u), n)
        }
    }

    /// The density of `dir` under [`Brdf::sample`]: the mixture
    /// (1 − s) cos θ / π + s (n+1)/(2π) cos^n α.
    pub fn pdf(&self, n: Vec3, dir: Vec3, view: Vec3) -> f32 {
        let s = self.highlight_share();
        let cosine = (1.0 - s) * n.dot(dir).max(0.0) / PI;
        if s > 0.0 {
            cosine + s * phong_lobe_pdf(reflect(-view, n).dot(dir), self.exponent)
        } else {
            cosine
        }
    }
}

impl Diffuse {
    /// A plain Lambertian surface of one colour.
    pub fn solid(albedo: Color) -> Diffuse {
        Diffuse {
            albedo: Texture::Solid(albedo),
            specular: Color::ZERO,
            exponent: 1.0,
            emission: None,
        }
    }

    pub(super) fn scatter(&self, hit: &Interaction) -> Scatter {
        Scatter {
            direct: Some(self.direct(hit.uv)),
            ..Scatter::default()
        }
    }

    /// Its shading by the lights at surface coordinates `uv`: all its scatter is.
    #[inline(always)]
    pub(crate) fn direct(&self, uv: Vec2) -> Direct {
        Direct {
            brdf: Brdf {
                albedo: self.albedo.eval(uv),
                specular: self.specular,
                exponent: self.exponent,
            },
            scale: 1.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::test_util::hit_at;

    #[test]
    fn lambert_is_albedo_over_pi_and_spawns_no_rays() {
        let d = Diffuse::solid(Color::splat(0.5));
        let s = d.scatter(&hit_at(30.0));
        assert_eq!(s.lobes().count(), 0);
        let direct = s.direct.unwrap();
        let f = direct.brdf.eval(Vec3::Y, Vec3::new(0.6, 0.8, 0.0), Vec3::Y);
        assert!((f - Color::splat(0.5 / PI)).abs().max_element() < 1e-7);
    }

    #[test]
    fn the_phong_lobe_peaks_in_the_mirror_direction() {
        let d = Diffuse {
            albedo: Texture::Solid(Color::ZERO),
            specular: Color::ONE,
            exponent: 50.0,
            emission: None,
        };
        let brdf = d.scatter(&hit_at(0.0)).direct.unwrap().brdf;
        let l = Vec3::new(0.6, 0.8, 0.0);
        let mirror = Vec3::new(-0.6, 0.8, 0.0);
        // At the mirror direction cos α = 1: f = (n + 2) / 2π.
        let peak = brdf.eval(Vec3::Y, l, mirror).x;
        assert!((peak - 52.0 / (2.0 * PI)).abs() < 1e-4);
        assert!(brdf.eval(Vec3::Y, l, Vec3::Y).x < peak * 0.01);
    }
}
