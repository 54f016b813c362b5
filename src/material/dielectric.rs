//! Dielectrics: glass, water, an air bubble, and the lecture's glazed surface (a clear coat
//! over a diffuse base). The formulas are in [`crate::optics`].

use super::{Brdf, Direct, Interaction, Interface, Lobe, Scatter, Side, Texture};
use super::{cos_i_of, mirror_dir_of};
use crate::geometry::Facing;
use crate::math::lanes::{Lanes, Real, V3, Vector};
use crate::math::{Color, Vec3};
use crate::optics::dispersion::ior_at;
use crate::optics::polarization::{Mueller, fresnel_amplitudes};
use crate::optics::{FresnelMode, fresnel_exact_of, refract_of};
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
    /// The GGX roughness α of the interface (`material/rough.rs`): 0 is smooth, the
    /// lecture's one reflected and one refracted ray; above 0 both are jittered, frosted
    /// glass. Glazes ignore it.
    pub roughness: f32,
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
            roughness: 0.0,
        }
    }

    /// This interface with the parameters' overrides: `ior`, `abbe` and `roughness` (unless
    /// fixed), `fresnel`, `constant_reflectance`, and σ times `absorption_scale`.
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
            roughness: match params.roughness {
                Some(alpha) if !self.ior_fixed => alpha,
                _ => self.roughness,
            },
        }
    }

    /// Whether its interface is rough: each hit jitters its children
    /// ([`Dielectric::roughness`]).
    #[inline]
    pub fn is_rough(&self) -> bool {
        self.roughness > 0.0
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

    /// [`Dielectric::reflectance`] for `N` hits on `dielectrics` at once, lane i on
    /// `dielectrics[i]`, bit for bit what it gives each: where every one computes R by the
    /// exact equations, those are made in lanes ([`fresnel_exact_of`], whose `f32`
    /// instance the exact mode is); else each hit asks its own interface.
    #[inline(always)]
    fn reflectance_lanes<const N: usize>(
        dielectrics: &[&Dielectric; N],
        cos_i: Lanes<N>,
        n1: Lanes<N>,
        n2: Lanes<N>,
    ) -> Lanes<N> {
        if dielectrics.iter().all(|d| d.fresnel == FresnelMode::Exact) {
            fresnel_exact_of(cos_i, n1, n2).2
        } else {
            Lanes::from_fn(|i| dielectrics[i].reflectance(cos_i.0[i], n1.0[i], n2.0[i]))
        }
    }

    /// The indices (n1, n2) on the side the ray comes from and the other, at the ray's
    /// wavelength.
    pub(super) fn sides(&self, hit: &Interaction) -> (f32, f32) {
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
        self.mueller_at(hit.cos_i(), n1, n2, side)
    }

    /// [`Dielectric::mueller`] of a ray meeting the interface (or a facet of it) at
    /// `cos_i`.
    pub(super) fn mueller_at(&self, cos_i: f32, n1: f32, n2: f32, side: Side) -> Mueller {
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
        let split = split_of::<f32>(hit.dir, hit.n_geom, hit.n_shade, n1, n2);
        let refracted = split.refracts.then_some(split.refracted);
        let r = match refracted {
            Some(_) => self.reflectance(split.cos_i, n1, n2),
            None => 1.0,
        };
        Split {
            mirror: split.mirror,
            refracted,
            interface: Interface {
                cos_i: split.cos_i,
                n1,
                n2,
                r,
            },
        }
        .scatter()
    }
}

/// [`Dielectric::scatter`] for `N` hits at once, made in lanes: hit i on `dielectrics[i]`,
/// the rays' directions `dir`, how each meets its surface (`facing`), and the indices
/// inside the dielectric and on its outer side at each ray's wavelength (`ior`,
/// `outside_ior`). Lane i's split is what `scatter` gives for hit
/// i, bit for bit.
#[inline(always)]
pub(crate) fn split_lanes<'d, const N: usize>(
    dielectrics: [&'d Dielectric; N],
    dir: V3<Lanes<N>>,
    facing: Facing<Lanes<N>>,
    ior: Lanes<N>,
    outside_ior: Lanes<N>,
) -> impl Iterator<Item = Split> + 'd {
    let n1 = Lanes::select(facing.entering, outside_ior, ior);
    let n2 = Lanes::select(facing.entering, ior, outside_ior);
    let split = split_of::<Lanes<N>>(dir, facing.n_geom, facing.n_shade, n1, n2);
    let r = Dielectric::reflectance_lanes(&dielectrics, split.cos_i, n1, n2);
    let r = Lanes::select(split.refracts, r, Lanes::splat(1.0));
    (0..N).map(move |i| Split {
        mirror: split.mirror.get(i),
        refracted: (split.refracts.0[i] != 0).then(|| split.refracted.get(i)),
        interface: Interface {
            cos_i: split.cos_i.0[i],
            n1: n1.0[i],
            n2: n2.0[i],
            r: r.0[i],
        },
    })
}

/// The two directions of a dielectric's split, for one ray or one per lane: the mirror
/// direction, the refracted one where it `refracts` (it must cross the geometric surface:
/// refracted about the shading normal, else about the geometric one), and cos θi.
struct SplitOf<R: Real> {
    mirror: R::V3,
    refracted: R::V3,
    refracts: R::Mask,
    cos_i: R,
}

/// Snell's law at a hit of direction `dir` with normals `n_geom` and `n_shade` (facing the
/// ray) from index `n1` into `n2`.
#[inline(always)]
fn split_of<R: Real>(dir: R::V3, n_geom: R::V3, n_shade: R::V3, n1: R, n2: R) -> SplitOf<R> {
    let (t, ok) = refract_of::<R>(dir, n_shade, n1, n2);
    let crosses = ok & t.dot(n_geom).less(R::splat(0.0));
    let (refracted, refracts) = if R::all(crosses) {
        (t, crosses)
    } else {
        let (about_geom, ok) = refract_of::<R>(dir, n_geom, n1, n2);
        (R::V3::select(crosses, t, about_geom), crosses | ok)
    };
    SplitOf {
        mirror: mirror_dir_of::<R>(dir, n_geom, n_shade),
        refracted,
        refracts,
        cos_i: cos_i_of::<R>(dir, n_shade),
    }
}

/// A dielectric's answer at one hit, before it is a [`Scatter`]: the mirror direction, the
/// refracted one (`None`: total internal reflection) and the interface's quantities.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Split {
    mirror: Vec3,
    refracted: Option<Vec3>,
    interface: Interface,
}

impl Split {
    /// The reflected ray of weight R and the refracted ray of weight 1 − R (under total
    /// internal reflection, R = 1 and no refracted ray).
    #[inline(always)]
    pub(crate) fn lobes(&self) -> [Option<Lobe>; 2] {
        let r = self.interface.r;
        [
            Some(Lobe::delta(Side::Reflect, self.mirror, Color::splat(r))),
            self.refracted
                .map(|dir| Lobe::delta(Side::Transmit, dir, Color::splat(1.0 - r))),
        ]
    }

    /// Whether the refracted ray does not exist.
    #[inline(always)]
    pub(crate) fn total_internal_reflection(&self) -> bool {
        self.refracted.is_none()
    }

    /// Its lobes ([`Split::lobes`]) and interface, as a scatter.
    #[inline]
    pub(crate) fn scatter(&self) -> Scatter {
        Scatter {
            lobes: self.lobes(),
            interface: Some(self.interface),
            total_internal_reflection: self.total_internal_reflection(),
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
    fn splits_made_in_lanes_are_each_hits_scatter_bit_for_bit() {
        use crate::math::lanes::{Lanes, Mask, V3};
        let exact = glass(FresnelMode::Exact);
        let schlick = Dielectric {
            ior: 1.33,
            ..glass(FresnelMode::Schlick)
        };
        // A dispersive flint, the rays of its lanes carrying wavelengths of their own.
        let flint = Dielectric {
            abbe: 25.8,
            ..glass(FresnelMode::Exact)
        };
        // Entering and leaving, head-on to grazing, beyond the critical angle (45° and 80°
        // from inside), with a shading normal tilted off the geometric one (at 60° and 89.9°
        // entering, 45° leaving), so that both refractions (about the shading normal, and
        // about the geometric one where the first would not cross the surface) are taken;
        // an outside index other than air.
        let tilted = Vec3::new(0.3, 1.0, 0.1).normalize();
        let hits: [Interaction; 8] = std::array::from_fn(|i| {
            let theta = [0.0, 30.0, 60.0, 89.9, 20.0, 45.0, 80.0, 87.0][i];
            Interaction {
                entering: i < 4,
                n_shade: if matches!(i, 2 | 3 | 5) {
                    tilted
                } else {
                    Vec3::Y
                },
                outside_ior: if i == 1 { 1.2 } else { 1.0 },
                wavelength: (i % 3 != 0).then_some(400.0 + 37.5 * i as f32),
                ..hit_at(theta)
            }
        });
        let tir = |h: &Interaction| exact.scatter(h).total_internal_reflection;
        assert!(
            hits.iter().any(tir) && !hits.iter().all(tir),
            "both cases are tried"
        );
        let (n1, n2) = (1.0, exact.ior);
        let about_geom = |h: &Interaction| {
            h.entering
                && crate::optics::refract(h.dir, h.n_shade, n1, n2)
                    .is_some_and(|t| t.dot(h.n_geom) >= 0.0)
        };
        assert!(
            hits.iter().any(about_geom),
            "the geometric refraction is tried"
        );
        for kinds in [
            [&exact; 8],
            std::array::from_fn(|i| [&exact, &schlick][i % 2]),
            std::array::from_fn(|i| [&flint, &schlick][i % 2]),
        ] {
            let v3 = |f: &dyn Fn(&Interaction) -> Vec3| V3::from_fn(|i| f(&hits[i]));
            let entering = Mask(
                hits.each_ref()
                    .map(|h| if h.entering { u32::MAX } else { 0 }),
            );
            let outside = Lanes::from_fn(|i| hits[i].outside_ior);
            let ior = Lanes::from_fn(|i| kinds[i].ior_at(hits[i].wavelength));
            let facing = Facing {
                entering,
                n_geom: v3(&|h| h.n_geom),
                n_shade: v3(&|h| h.n_shade),
            };
            let lanes = split_lanes(kinds, v3(&|h| h.dir), facing, ior, outside);
            for (i, split) in lanes.enumerate() {
                let (a, b) = (split.scatter(), kinds[i].scatter(&hits[i]));
                let bits = |s: &Scatter| {
                    let i = s.interface.unwrap();
                    let mut v = vec![i.cos_i, i.n1, i.n2, i.r];
                    for l in s.lobes() {
                        v.extend(l.dir.to_array().into_iter().chain(l.weight.to_array()));
                    }
                    v.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
                };
                assert_eq!(bits(&a), bits(&b), "hit {i}");
                assert_eq!(a.total_internal_reflection, b.total_internal_reflection);
            }
        }
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
