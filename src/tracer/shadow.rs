//! Shading by the lights: one shadow ray to a sampled point of each light. How a shadow
//! ray sees dielectrics depends on the light transport: the lecture's tracer stops at
//! them (black shadows behind glass and water); with transmissive shadows it passes
//! straight through, attenuated at each interface and along the way.

use super::media::transmittance;
use super::record::shadow_node;
use super::{Arrival, Media, Recorder, Tracer, Walk};
use crate::material::{Direct, Interaction, Material};
use crate::math::{Color, Ray, offset_ray_origin};
use crate::params::Transport;
use crate::scene::Hit;

/// The most dielectric surfaces one shadow ray passes through before it counts as blocked:
/// a scene of many glass objects in a row cannot make one shadow ray run on for ever.
const MAX_SHADOW_CROSSINGS: u32 = 64;

impl Tracer<'_> {
    /// Shading by the lights: ambient plus every light, one shadow ray to one sampled point
    /// of each: L = a·L_ambient + Σ f(l, v) (L_light / p(l)) cos θ · T, T the shadow ray's
    /// transmittance (0 or 1 in the lecture's tracer). `media` are those the shaded point
    /// lies in.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(super) fn direct<R: Recorder>(
        &self,
        ray: &Ray,
        hit: &Hit,
        at: &Interaction,
        direct: &Direct,
        id: usize,
        media: &Media,
        w: &mut Walk<R>,
    ) -> Color {
        let p = hit.surface.p;
        let (n_geom, n) = (at.n_geom, at.n_shade);
        let origin = offset_ray_origin(p, n_geom);
        let view = -ray.dir;
        let mut sum = self.scene.ambient * direct.brdf.albedo;
        for light in &self.lights {
            let u = light.draw(w.rng);
            let Some(ls) = light.sample(p, u) else {
                continue;
            };
            let cos = n.dot(ls.dir);
            if cos <= 0.0 || n_geom.dot(ls.dir) <= 0.0 {
                continue;
            }
            w.stats.shadow_rays += 1;
            let shadow = Ray {
                origin,
                dir: ls.dir,
                time: ray.time,
            };
            // Stop just short of the light's surface (it is not in the BVH anyway).
            let reach = ls.dist * (1.0 - 1e-4);
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
                    let t = self.shadow_transmittance(&shadow, reach, media);
                    let c = t * direct.brdf.eval(n, ls.dir, view) * ls.value * cos;
                    (t == Color::ZERO, c)
                }
            };
            sum += contribution;
            w.rec
                .ray(|| shadow_node(id, &shadow, ls.dist, blocked, contribution));
        }
        sum
    }

    /// The transmittance of `shadow` over `dist`, starting in `media`, passing straight
    /// through clear and coloured dielectrics: at each interface 1 − R (R by that
    /// material's Fresnel model, at the ray's angle seen from the outside), and exp(−σ d)
    /// inside. Any other surface blocks it. Straight, so wrong about where light lands:
    /// real glass bends it into caustics.
    fn shadow_transmittance(&self, shadow: &Ray, dist: f32, media: &Media) -> Color {
        let mut media = *media;
        let mut ray = *shadow;
        let mut left = dist;
        let mut t = Color::ONE;
        for _ in 0..MAX_SHADOW_CROSSINGS {
            let sigma = self.absorption_in(&media);
            let Some(hit) = self.scene.intersect(&ray, left) else {
                return t * transmittance(sigma, left);
            };
            let Material::Dielectric(d) = &self.materials[hit.material as usize] else {
                return Color::ZERO;
            };
            let s = &hit.surface;
            let Arrival {
                entering,
                n_geom,
                n_shade,
                outside,
            } = Arrival::at(ray.dir, &hit, &media);
            // The ray does not bend, so its angle inside the glass would be the outside
            // angle, and leaving it would meet total internal reflection where the bent
            // ray meets none: R is taken as seen from the outside, going in and out alike
            // (as it is for a real ray, whose R is the same both ways across a slab).
            let cos_i = (-ray.dir).dot(n_shade).clamp(0.0, 1.0);
            let n_out = self.ior_of(outside, None);
            let r = d
                .fresnel
                .reflectance(cos_i, n_out, d.ior, d.constant_reflectance);
            t *= transmittance(sigma, s.t) * (1.0 - r);
            if t.max_element() <= 0.0 {
                return Color::ZERO;
            }
            media = if entering {
                media.entered(hit.object, hit.material)
            } else {
                media.left(hit.object)
            };
            left -= s.t;
            ray = Ray {
                origin: offset_ray_origin(s.p, -n_geom),
                ..ray
            };
        }
        Color::ZERO
    }
}
