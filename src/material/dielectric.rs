//! Dielectrics: glass, water, an air bubble, and the lecture's glazed surface (a clear coat
//! over a diffuse base). The formulas are in [`crate::optics`].

use super::{Brdf, Direct, Interaction, Interface, Lobe, Scatter, Side, Texture};
use crate::math::Color;
use crate::optics::dispersion::ior_at;
use crate::optics::polarization::{Mueller, fresnel_amplitudes};
use crate::optics::{FresnelMode, refract};
use crate::params::Params;

/// A clear or coloured dielectric (glass, water, an air bubble): every hit splits into a
/// reflected ray of weight R and a refracted ray of weight 1 − R, R from the Fresnel mode;
/// under total internal reflection only the reflected ray, of weight 1. Light travelling
/// inside is attenuated by Beer–Lambert, exp(−σ d).
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
    /// Abbe number V_d: how much the index varies with the wavelength, `ior` being n_d at
    /// 587.6 nm (lower is more dispersive; 0: none). Glazes ignore it.
    pub abbe: f32,
}

/// The lecture's glazed surface: a clear coat over a base colour. The coat reflects R
/// (Fresnel or constant); the transmitted ray is not traced: the base's diffuse shading
/// takes the remaining 1 − R.
#[derive(Clone, Debug, PartialEq)]
pub struct Glazed {
    /// The coat's interface.
    pub coat: Dielectric,
    /// Diffuse colour of the base (black for the black glazed sphere).
    pub base: Texture,
}

impl Dielectric {
    /// Clear glass (or water, ...) of index `ior`: the exact Fresnel equations (k = 0.04,
    /// glass's R at normal incidence, should the constant model be chosen), no absorption,
    /// no dispersion. Scene files start from it.
    pub fn clear(ior: f32) -> Dielectric {
        Dielectric {
            ior,
            ior_fixed: false,
            fresnel: FresnelMode::Exact,
            constant_reflectance: 0.04,
            absorption: Color::ZERO,
            abbe: 0.0,
        }
    }

    /// This interface with the parameters' overrides: `ior` (unless fixed), `fresnel`,
    /// `constant_reflectance`, and σ times `absorption_scale`.
    pub(super) fn with_params(&self, params: &Params) -> Dielectric {
        Dielectric {
            ior: match params.ior {
                Some(ior) if !self.ior_fixed => ior,
                _ => self.ior,
            },
            ior_fixed: self.ior_fixed,
            fresnel: params.fresnel.unwrap_or(self.fresnel),
            constant_reflectance: params
                .constant_reflectance
                .unwrap_or(self.constant_reflectance),
            absorption: self.absorption * params.absorption_scale,
            abbe: match params.abbe {
                Some(abbe) if !self.ior_fixed => abbe,
                _ => self.abbe,
            },
        }
    }

    /// Whether its index depends on the wavelength.
    pub fn disperses(&self) -> bool {
        self.abbe > 0.0
    }

    /// The index of refraction at `wavelength` (nm), or n_d for a sample without one.
    #[inline]
    pub fn ior_at(&self, wavelength: Option<f32>) -> f32 {
        wavelength.map_or(self.ior, |l| ior_at(self.ior, self.abbe, l))
    }

    /// The reflectance R from `n1` into `n2` at cos θi, by this interface's Fresnel mode.
    fn reflectance(&self, cos_i: f32, n1: f32, n2: f32) -> f32 {
        self.fresnel
            .reflectance(cos_i, n1, n2, self.constant_reflectance)
    }

    /// The indices (n1, n2) on the side the ray comes from and the other, at the ray's
    /// wavelength.
    fn sides(&self, hit: &Interaction) -> (f32, f32) {
        let ior = self.ior_at(hit.wavelength);
        if hit.entering {
            (hit.outside_ior, ior)
        } else {
            (ior, hit.outside_ior)
        }
    }

    /// The Mueller matrix of the reflected or refracted ray from `n1` into `n2`: the
    /// Fresnel amplitudes with the exact model; the others do not polarise.
    pub(super) fn mueller(&self, hit: &Interaction, n1: f32, n2: f32, side: Side) -> Mueller {
        let cos_i = hit.cos_i();
        if self.fresnel != FresnelMode::Exact {
            let r = Color::splat(self.reflectance(cos_i, n1, n2));
            return match side {
                Side::Reflect => Mueller::neutral_reflection(r),
                Side::Transmit => Mueller::neutral_transmission(Color::ONE - r),
            };
        }
        let (r_s, r_p) = fresnel_amplitudes(cos_i, n1, n2, 0.0);
        match side {
            Side::Reflect => Mueller::reflection([(r_s, r_p); 3]),
            Side::Transmit => Mueller::transmission(r_s.norm2() as f32, r_p.norm2() as f32),
        }
    }

    /// The Mueller matrix of a child ray on `side` of this interface at `hit`.
    pub(super) fn child_mueller(&self, hit: &Interaction, side: Side) -> Mueller {
        let (n1, n2) = self.sides(hit);
        self.mueller(hit, n1, n2, side)
    }

    /// What a shadow ray keeps crossing this interface straight, unbent (transmissive
    /// shadows): 1 − R at the ray's wavelength. The ray does not bend, so its angle inside
    /// would be the outside angle, and leaving it would meet total internal reflection
    /// where the bent ray meets none: R is taken as seen from the outside, going in and out
    /// alike (as it is for a real ray, whose R is the same both ways across a slab).
    pub(super) fn shadow_transmittance(&self, hit: &Interaction) -> f32 {
        let n = self.ior_at(hit.wavelength);
        1.0 - self.reflectance(hit.cos_i(), hit.outside_ior, n)
    }

    pub(super) fn scatter(&self, hit: &Interaction) -> Scatter {
        let (n1, n2) = self.sides(hit);
        let cos_i = hit.cos_i();
        // Snell's law; the refracted ray must cross the geometric surface.
        let refracted = refract(hit.dir, hit.n_shade, n1, n2)
            .filter(|t| t.dot(hit.n_geom) < 0.0)
            .or_else(|| refract(hit.dir, hit.n_geom, n1, n2));
        let r = match refracted {
            Some(_) => self.reflectance(cos_i, n1, n2),
            None => 1.0,
        };
        Scatter {
            lobes: [
                Some(Lobe::delta(
                    Side::Reflect,
                    hit.mirror_dir(),
                    Color::splat(r),
                )),
                refracted.map(|dir| Lobe::delta(Side::Transmit, dir, Color::splat(1.0 - r))),
            ],
            interface: Some(Interface { cos_i, n1, n2, r }),
            total_internal_reflection: refracted.is_none(),
            ..Scatter::default()
        }
    }
}

impl Glazed {
    /// The coat's Mueller matrix: its reflection, or for `Transmit` the way the base's
    /// light comes out through it.
    pub(super) fn mueller(&self, hit: &Interaction, side: Side) -> Mueller {
        self.coat.mueller(hit, hit.outside_ior, self.coat.ior, side)
    }

    pub(super) fn scatter(&self, hit: &Interaction) -> Scatter {
        // The coat is seen from the medium the ray travels in; nothing enters it.
        let (n1, n2) = (hit.outside_ior, self.coat.ior);
        let cos_i = hit.cos_i();
        let r = self.coat.reflectance(cos_i, n1, n2);
        Scatter {
            direct: Some(Direct {
                brdf: Brdf {
                    albedo: self.base.eval(hit.uv),
                    specular: Color::ZERO,
                    exponent: 1.0,
                },
                scale: 1.0 - r,
            }),
            lobes: [
                Some(Lobe::delta(
                    Side::Reflect,
                    hit.mirror_dir(),
                    Color::splat(r),
                )),
                None,
            ],
            interface: Some(Interface { cos_i, n1, n2, r }),
            ..Scatter::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Material;
    use crate::material::test_util::hit_at;
    use crate::math::Vec3;

    fn glass(fresnel: FresnelMode) -> Dielectric {
        Dielectric {
            fresnel,
            constant_reflectance: 0.1,
            absorption: Color::new(0.0, 0.5, 1.0),
            ..Dielectric::clear(1.5)
        }
    }

    #[test]
    fn head_on_glass_reflects_four_percent_and_transmits_the_rest() {
        let s = glass(FresnelMode::Exact).scatter(&hit_at(0.0));
        let lobes: Vec<_> = s.lobes().collect();
        assert_eq!(lobes.len(), 2);
        // R0 = ((n − 1)/(n + 1))² = 0.04.
        assert!((lobes[0].weight.x - 0.04).abs() < 1e-6);
        assert_eq!(lobes[0].weight.x + lobes[1].weight.x, 1.0);
        assert_eq!(lobes[1].side, Side::Transmit);
        assert!((lobes[1].dir - -Vec3::Y).length() < 1e-6);
        assert!(!s.total_internal_reflection);
    }

    #[test]
    fn refraction_obeys_snell_and_leaving_beyond_the_critical_angle_is_total() {
        let d = glass(FresnelMode::Exact);
        let s = d.scatter(&hit_at(40.0));
        let t = s.lobes().nth(1).unwrap().dir;
        // n1 sin θi = n2 sin θt.
        let sin_t = (1.0 - t.y * t.y).sqrt();
        assert!((40f32.to_radians().sin() - 1.5 * sin_t).abs() < 1e-5);
        // From inside, beyond asin(1/1.5) = 41.8°: one reflected ray of weight 1.
        let inside = Interaction {
            entering: false,
            ..hit_at(45.0)
        };
        let s = d.scatter(&inside);
        assert!(s.total_internal_reflection);
        let lobes: Vec<_> = s.lobes().collect();
        assert_eq!(lobes.len(), 1);
        assert_eq!(lobes[0].weight, Color::ONE);
        assert_eq!(s.interface.unwrap().n1, 1.5);
    }

    #[test]
    fn a_shadow_ray_keeps_one_minus_r_at_its_own_wavelength() {
        let flint = Dielectric {
            abbe: 30.0,
            ..Dielectric::clear(1.6)
        };
        // Head-on, R = ((n − 1)/(n + 1))² with n = n(λ), entering or leaving alike.
        let r0 = |n: f32| ((n - 1.0) / (n + 1.0)).powi(2);
        let mut seen = Vec::new();
        for wavelength in [None, Some(450.0), Some(650.0)] {
            let n = flint.ior_at(wavelength);
            for entering in [true, false] {
                let hit = Interaction {
                    entering,
                    wavelength,
                    ..hit_at(0.0)
                };
                let t = Material::Dielectric(flint.clone())
                    .shadow_transmittance(&hit)
                    .unwrap();
                assert!((t.x - (1.0 - r0(n))).abs() < 1e-6, "{wavelength:?}");
                assert_eq!((t.x, t.y), (t.z, t.x), "the same in every channel");
                seen.push(t.x);
            }
        }
        assert_eq!(seen[0], 1.0 - r0(1.6), "without a wavelength: n_d");
        assert!(
            seen[2] < seen[4],
            "blue (higher n) reflects more, keeps less"
        );
        // A glaze's base is opaque: it blocks.
        let glaze = Material::Glazed(Glazed {
            coat: flint,
            base: Texture::Solid(Color::ONE),
        });
        assert_eq!(glaze.shadow_transmittance(&hit_at(0.0)), None);
    }

    #[test]
    fn the_glaze_splits_between_its_coat_and_its_base() {
        let g = Glazed {
            coat: glass(FresnelMode::Constant),
            base: Texture::Solid(Color::splat(0.2)),
        };
        let s = g.scatter(&hit_at(60.0));
        let direct = s.direct.unwrap();
        assert_eq!(direct.scale, 0.9);
        assert_eq!(direct.brdf.albedo, Color::splat(0.2));
        assert_eq!(s.lobes().next().unwrap().weight, Color::splat(0.1));
        assert_eq!(s.lobes().count(), 1, "the transmitted ray is not traced");
    }

    #[test]
    fn parameters_override_the_interface_and_scale_absorption() {
        let params = Params {
            ior: Some(2.0),
            fresnel: Some(FresnelMode::Schlick),
            absorption_scale: 2.0,
            ..Params::default()
        };
        let d = glass(FresnelMode::Exact).with_params(&params);
        assert_eq!(d.ior, 2.0);
        assert_eq!(d.fresnel, FresnelMode::Schlick);
        assert_eq!(d.absorption, Color::new(0.0, 1.0, 2.0));
        let fixed = Dielectric {
            ior_fixed: true,
            ..glass(FresnelMode::Exact)
        };
        assert_eq!(fixed.with_params(&params).ior, 1.5);
    }

    #[test]
    fn a_dispersive_glass_refracts_each_wavelength_by_its_own_index() {
        let flint = Dielectric {
            abbe: 30.0,
            ..glass(FresnelMode::Exact)
        };
        for lambda in [450.0f32, 587.56, 650.0] {
            let n = crate::optics::dispersion::ior_at(1.5, 30.0, lambda);
            let hit = Interaction {
                wavelength: Some(lambda),
                ..hit_at(50.0)
            };
            let t = flint.scatter(&hit).lobes().nth(1).unwrap().dir;
            // Snell's law with n(λ): sin θi = n(λ) sin θt.
            let sin_t = (1.0 - t.y * t.y).sqrt();
            assert!(
                (50f32.to_radians().sin() - n * sin_t).abs() < 1e-5,
                "{lambda} nm"
            );
        }
        // Without a wavelength, n_d; with dispersion off, every wavelength sees n_d.
        assert_eq!(flint.ior_at(None), 1.5);
        assert_eq!(glass(FresnelMode::Exact).ior_at(Some(450.0)), 1.5);
        let params = Params {
            abbe: Some(0.0),
            ..Params::default()
        };
        assert!(!flint.with_params(&params).disperses());
    }
}
