//! Metals in the lecture's two guises, the ideal mirror and glossy reflection by jittering
//! the mirror ray over a Phong lobe; and the physical metal, a conductor whose reflectance
//! follows the Fresnel equations for its complex index of refraction.

use super::{Interaction, Lobe, LobeKind, Scatter, Side};
use crate::math::sampling::{phong_lobe, phong_lobe_pdf, to_world};
use crate::math::{Color, Uniform, Vec3};
use crate::optics::fresnel_conductor;
use crate::optics::polarization::{Mueller, fresnel_amplitudes};

/// An ideal mirror or polished metal: the reflected ray, scaled by a constant reflectance
/// (metals reflect strongly at every angle, with a colour).
#[derive(Clone, Debug, PartialEq)]
pub struct Mirror {
    /// Reflectance, 0..1 per channel.
    pub reflectance: Color,
}

/// A glossy metal: the mirror direction jittered over the Phong lobe cos^n α around it
/// (the lecture's glossy reflection), times the reflectance. Higher n is sharper; the lobe
/// is importance-sampled, so each jittered ray carries the reflectance exactly.
#[derive(Clone, Debug, PartialEq)]
pub struct Glossy {
    /// Reflectance, 0..1 per channel.
    pub reflectance: Color,
    /// Phong exponent n.
    pub exponent: f32,
}

/// A conductor: a metal of complex index of refraction η + iκ per channel. Its reflectance
/// follows the exact conductor Fresnel equations: high at every angle, coloured, rising to
/// 1 at grazing ("it does depend on angle, but not much"). Polished, or glossy with a Phong
/// exponent.
#[derive(Clone, Debug, PartialEq)]
pub struct Conductor {
    /// Real part of the index of refraction, per channel.
    pub eta: Color,
    /// Extinction coefficient (imaginary part), per channel.
    pub k: Color,
    /// A Phong exponent for a brushed or glossy metal; `None` is polished.
    pub exponent: Option<f32>,
}

impl Conductor {
    pub(super) fn scatter(&self, hit: &Interaction, u: &mut impl Uniform) -> Scatter {
        let cos_i = hit.cos_i();
        let r = |c: usize| fresnel_conductor(cos_i, hit.outside_ior, self.eta[c], self.k[c]).2;
        let (kind, dir) = match self.exponent {
            Some(exponent) => (LobeKind::Glossy { exponent }, jittered(hit, exponent, u)),
            None => (LobeKind::Delta, hit.mirror_dir()),
        };
        Scatter {
            lobes: [
                Some(Lobe {
                    side: Side::Reflect,
                    kind,
                    dir,
                    weight: Color::new(r(0), r(1), r(2)),
                }),
                None,
            ],
            ..Scatter::default()
        }
    }
}

impl Conductor {
    /// The Mueller matrix of its reflection at `hit`, per channel: a metal shifts the phase
    /// between s and p, turning linear polarisation elliptical.
    pub(super) fn mueller(&self, hit: &Interaction) -> Mueller {
        let cos_i = hit.cos_i();
        Mueller::reflection(std::array::from_fn(|c| {
            fresnel_amplitudes(cos_i, hit.outside_ior, self.eta[c], self.k[c])
        }))
    }
}

/// The mirror direction jittered over the Phong lobe cos^n α; directions below the surface
/// are folded back above it (mirrored in the tangent plane): no energy lost, no black
/// speckles at grazing angles.
fn jittered(hit: &Interaction, exponent: f32, u: &mut impl Uniform) -> Vec3 {
    let dir = to_world(phong_lobe(u.next_2d(), exponent), hit.mirror_dir());
    let below = dir.dot(hit.n_geom);
    if below <= 0.0 {
        (dir - 2.0 * below * hit.n_geom).normalize()
    } else {
        dir
    }
}

/// The density per unit solid angle of `jittered`'s direction `dir` (above the
/// surface): the Phong lobe's own density there plus that of its mirror image below the
/// surface, which folding sends to `dir`. A glossy lobe of weight W then has
/// f cos θ = W · pdf, which is how path tracing evaluates it towards a light.
pub fn glossy_pdf(hit: &Interaction, exponent: f32, dir: Vec3) -> f32 {
    let above = dir.dot(hit.n_geom);
    if above <= 0.0 {
        return 0.0;
    }
    let mirror = hit.mirror_dir();
    let folded = dir - 2.0 * above * hit.n_geom;
    phong_lobe_pdf(dir.dot(mirror), exponent) + phong_lobe_pdf(folded.dot(mirror), exponent)
}

impl Mirror {
    pub(super) fn scatter(&self, hit: &Interaction) -> Scatter {
        Scatter {
            lobes: [
                Some(Lobe::delta(
                    Side::Reflect,
                    hit.mirror_dir(),
                    self.reflectance,
                )),
                None,
            ],
            ..Scatter::default()
        }
    }
}

impl Glossy {
    pub(super) fn scatter(&self, hit: &Interaction, u: &mut impl Uniform) -> Scatter {
        // Sampling the normalized lobe exactly, each jittered ray carries the reflectance.
        let dir = jittered(hit, self.exponent, u);
        Scatter {
            lobes: [
                Some(Lobe {
                    side: Side::Reflect,
                    kind: LobeKind::Glossy {
                        exponent: self.exponent,
                    },
                    dir,
                    weight: self.reflectance,
                }),
                None,
            ],
            ..Scatter::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Interaction;
    use crate::material::test_util::{Fixed, hit_at};
    use crate::math::Vec3;

    #[test]
    fn a_mirror_reflects_about_the_normal_with_its_reflectance() {
        let m = Mirror {
            reflectance: Color::new(0.9, 0.8, 0.7),
        };
        let s = m.scatter(&hit_at(30.0));
        let lobes: Vec<_> = s.lobes().collect();
        assert_eq!(lobes.len(), 1);
        assert_eq!(lobes[0].side, Side::Reflect);
        assert_eq!(lobes[0].weight, m.reflectance);
        let expected = Vec3::new(0.5, 30f32.to_radians().cos(), 0.0);
        assert!((lobes[0].dir - expected).length() < 1e-6);
    }

    #[test]
    fn a_glossy_ray_stays_above_the_surface_and_near_the_mirror() {
        let g = Glossy {
            reflectance: Color::ONE,
            exponent: 1000.0,
        };
        // The lobe's directions for an 8 × 8 grid of uniform numbers.
        let dirs = |g: &Glossy, hit: &Interaction| -> Vec<Vec3> {
            (0..64)
                .map(|k| {
                    let u = vec![(k % 8) as f32 / 8.0 + 0.01, (k / 8) as f32 / 8.0 + 0.01];
                    g.scatter(hit, &mut Fixed(u)).lobes().next().unwrap().dir
                })
                .collect()
        };
        let hit = hit_at(45.0);
        for d in dirs(&g, &hit) {
            assert!(d.dot(hit.n_geom) > 0.0);
            // n = 1000: cos α is above 0.99 for nearly all of the lobe's mass.
            assert!(d.dot(hit.mirror_dir()) > 0.98, "{d}");
        }
        // A wide lobe at grazing incidence folds what falls below back above.
        let wide = Glossy {
            reflectance: Color::ONE,
            exponent: 1.0,
        };
        let folded = dirs(&wide, &hit_at(89.0));
        assert!(folded.iter().all(|d| d.dot(Vec3::Y) >= 0.0));
    }

    #[test]
    fn a_conductor_reflects_by_the_fresnel_equations_of_its_complex_index() {
        let gold = Conductor {
            eta: Color::new(0.18, 0.42, 1.37),
            k: Color::new(3.42, 2.35, 1.77),
            exponent: None,
        };
        let head_on = gold.scatter(&hit_at(0.0), &mut Fixed(vec![]));
        let lobe = head_on.lobes().next().unwrap();
        for c in 0..3 {
            let (eta, k) = (gold.eta[c], gold.k[c]);
            let r0 = ((eta - 1.0).powi(2) + k * k) / ((eta + 1.0).powi(2) + k * k);
            assert!(
                (lobe.weight[c] - r0).abs() < 1e-6,
                "{c}: {} vs {r0}",
                lobe.weight[c]
            );
        }
        assert!((lobe.dir - Vec3::Y).length() < 1e-6);
        // At 70° under water: the equations with n1 = 1.33, and yellow stays yellow.
        let mut wet = hit_at(70.0);
        wet.outside_ior = 1.33;
        let w = gold
            .scatter(&wet, &mut Fixed(vec![]))
            .lobes()
            .next()
            .unwrap()
            .weight;
        let cos = 70f32.to_radians().cos();
        for c in 0..3 {
            let r = fresnel_conductor(cos, 1.33, gold.eta[c], gold.k[c]).2;
            assert_eq!(w[c], r);
        }
        assert!(w.x > w.y && w.y > w.z);
        // Glossy: a jittered direction, above the surface.
        let brushed = Conductor {
            exponent: Some(20.0),
            ..gold
        };
        let s = brushed.scatter(&hit_at(80.0), &mut Fixed(vec![0.3, 0.9]));
        let dir = s.lobes().next().unwrap().dir;
        assert!(dir.y > 0.0 && (dir - hit_at(80.0).mirror_dir()).length() > 1e-3);
    }
}
