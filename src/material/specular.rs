//! Metals in the lecture's two guises: the ideal mirror, and glossy reflection by jittering
//! the mirror ray over a Phong lobe.

use super::{Interaction, Lobe, Scatter, Side};
use crate::math::sampling::{phong_lobe, to_world};
use crate::math::{Color, Uniform};

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

impl Mirror {
    pub(super) fn scatter(&self, hit: &Interaction) -> Scatter {
        Scatter {
            lobes: [
                Some(Lobe {
                    side: Side::Reflect,
                    dir: hit.mirror_dir(),
                    weight: self.reflectance,
                }),
                None,
            ],
            ..Scatter::default()
        }
    }
}

impl Glossy {
    pub(super) fn scatter(&self, hit: &Interaction, u: &mut impl Uniform) -> Scatter {
        // Sampling the normalized lobe exactly, each jittered ray carries the reflectance.
        let mut dir = to_world(phong_lobe(u.next_2d(), self.exponent), hit.mirror_dir());
        // Lobe directions below the surface are folded back above it (mirrored in the
        // tangent plane): no energy lost, no black speckles at grazing angles.
        let below = dir.dot(hit.n_geom);
        if below <= 0.0 {
            dir = (dir - 2.0 * below * hit.n_geom).normalize();
        }
        Scatter {
            lobes: [
                Some(Lobe {
                    side: Side::Reflect,
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
}
