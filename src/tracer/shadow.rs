//! Shading by the lights: one shadow ray to a sampled point of each light. How a shadow
//! ray sees dielectrics depends on the light transport: the lecture's tracer stops at
//! them (black shadows behind glass and water); with transmissive shadows it passes
//! straight through, attenuated at each interface and along the way.

use super::media::transmittance;
use super::record::shadow_node;
use super::{Media, Meet, Met, Recorder, Tracer, Walk};
use crate::material::{Direct, Interaction};
use crate::math::lanes::{Real, Vector};
use crate::math::{Color, Ray, offset_ray_origin};
use crate::params::Transport;

/// The most dielectric surfaces one shadow ray passes through before it counts as blocked:
/// a scene of many glass objects in a row cannot make one shadow ray run on for ever.
const MAX_SHADOW_CROSSINGS: u32 = 64;

/// How far a shadow ray reaches, as a fraction of the distance to the light's point: just
/// short of the light's surface (which is not in the BVH anyway).
pub(super) const SHADOW_REACH: f32 = 1.0 - 1e-4;

/// cos θ = n · l between the shading normal and the direction `dir` to a light's point,
/// for one ray or one per lane, and whether a shadow ray is traced there: the light must
/// be in front of the shading normal (cos θ > 0, else it adds nothing) and of the
/// geometric one (else the shadow ray would start into the surface). `n_geom` and
/// `n_shade` face the arriving ray. Both walks ask this.
#[inline(always)]
pub(super) fn faces_light<R: Real>(n_geom: R::V3, n_shade: R::V3, dir: R::V3) -> (R, R::Mask) {
    let zero = R::splat(0.0);
    let cos = n_shade.dot(dir);
    (cos, !cos.less_eq(zero) & !n_geom.dot(dir).less_eq(zero))
}

impl Tracer<'_> {
    /// Shading by the lights: ambient plus every light, one shadow ray to one sampled point
    /// of each: L = a·L_ambient + Σ f(l, v) (L_light / p(l)) cos θ · T, T the shadow ray's
    /// transmittance (0 or 1 in the lecture's tracer), for the surface `m` meets, seen by
    /// its material as `at`.
    #[inline(always)]
    pub(super) fn direct<R: Recorder>(
        &self,
        m: Meet,
        at: &Interaction,
        direct: &Direct,
        w: &mut Walk<R>,
    ) -> Color {
        let Meet {
            ray,
            hit,
            media,
            id,
        } = m;
        let p = hit.surface.p;
        let (n_geom, n) = (at.n_geom, at.n_shade);
        let origin = offset_ray_origin(p, n_geom);
        let view = -ray.dir;
        let mut sum = self.ambient(direct);
        for light in &self.lights {
            let u = light.draw(w.rng);
            let Some(ls) = light.sample(p, u) else {
                continue;
            };
            let (cos, lit) = faces_light::<f32>(n_geom, n, ls.dir);
            if !lit {
                continue;
            }
            w.stats.shadow_rays += 1;
            let shadow = Ray {
                origin,
                dir: ls.dir,
                time: ray.time,
            };
            let reach = ls.dist * SHADOW_REACH;
            let (blocked, contribution) = match self.params.transport {
                Transport::Whitted | Transport::Path | Transport::Photons => {
                    let blocked = self.scene.occluded(&shadow, reach);
                    let c = if blocked {
                        Color::ZERO
                    } else {
                        direct.brdf.eval(n, ls.dir, view) * ls.value * cos
                    };
                    (blocked, c)
                }
                Transport::TransmissiveShadows => {
                    let t =
                        self.shadow_transmittance(&shadow, reach, media, at.wavelength, &mut w.met);
                    let c = t * direct.brdf.eval(n, ls.dir, view) * ls.value * cos;
                    (t == Color::ZERO, c)
                }
            };
            sum += contribution;
            w.rec.ray(|| {
                // A blocked ray's record stops at its blocker, where the diagrams draw it.
                let end = match blocked {
                    true => self.scene.intersect(&shadow, reach).map(|h| h.surface.t),
                    false => None,
                };
                shadow_node(id, &shadow, end.unwrap_or(ls.dist), blocked, contribution)
            });
        }
        sum
    }

    /// The ambient term of [`Tracer::direct`]'s sum: a·L_ambient.
    #[inline(always)]
    pub(super) fn ambient(&self, direct: &Direct) -> Color {
        self.scene.ambient * direct.brdf.albedo
    }

    /// The transmittance of `shadow` over `dist`, starting in `media` and carrying
    /// `wavelength`, passing straight through whatever lets it (each material says what it
    /// keeps: 1 − R for a dielectric) and exp(−σ d) inside; any other surface blocks it.
    /// Straight, so wrong about where light lands: real glass bends it into caustics. The
    /// materials it passes go into `met`.
    fn shadow_transmittance(
        &self,
        shadow: &Ray,
        dist: f32,
        media: &Media,
        wavelength: Option<f32>,
        met: &mut Met,
    ) -> Color {
        let mut media = *media;
        let mut ray = *shadow;
        let mut left = dist;
        let mut t = Color::ONE;
        for _ in 0..MAX_SHADOW_CROSSINGS {
            let sigma = self.absorption_in(&media);
            let Some(hit) = self.scene.intersect(&ray, left) else {
                return t * transmittance(sigma, left);
            };
            let at = self.interaction(&ray, &hit, &media, wavelength);
            let material = &self.materials[hit.material as usize];
            met.material(hit.material);
            let Some(through) = material.shadow_transmittance(&at) else {
                return Color::ZERO;
            };
            let s = &hit.surface;
            t *= transmittance(sigma, s.t) * through;
            if t.max_element() <= 0.0 {
                return Color::ZERO;
            }
            media = media.crossed(at.entering, &hit);
            left -= s.t;
            ray = Ray {
                origin: offset_ray_origin(s.p, -at.n_geom),
                ..ray
            };
        }
        Color::ZERO
    }
}
