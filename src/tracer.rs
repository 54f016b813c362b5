//! The ray tree: from each camera ray, shadow rays to the lights and reflected and refracted
//! child rays, pruned by depth and by attenuation (the path weight).
//!
//! Radiance is not scaled by (n2/n1)² when a ray refracts. Every path that reaches the
//! camera starts and ends in the scene's surrounding medium (lights and background live
//! there too), so the factors of entering and leaving a medium cancel; leaving them out
//! keeps R + (1 − R) = 1 at every split, which the white-furnace test checks.

use crate::camera::{Camera, CameraFrame};
use crate::light::Light;
use crate::material::{Dielectric, Material, Texture};
use crate::math::sampling::{phong_lobe, to_world};
use crate::math::{Color, Ray, SampleStream, Vec3, offset_ray_origin};
use crate::optics::{reflect, refract};
use crate::params::{Params, TreeMode};
use crate::scene::{Hit, Scene};
use glam::Vec2;
use std::f32::consts::PI;
use std::ops::AddAssign;

/// What the tracer did: rays by kind and branches pruned.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Stats {
    /// Camera samples taken.
    pub samples: u64,
    /// Eye rays.
    pub camera_rays: u64,
    /// Rays towards lights.
    pub shadow_rays: u64,
    /// Reflected rays.
    pub reflection_rays: u64,
    /// Refracted rays.
    pub refraction_rays: u64,
    /// Hits where the refracted ray does not exist: total internal reflection.
    pub tir_events: u64,
    /// Branches not traced because they would exceed `max_depth`.
    pub pruned_by_depth: u64,
    /// Branches not traced because their path weight fell below `min_weight`.
    pub pruned_by_weight: u64,
    /// Samples dropped because they were NaN or infinite.
    pub non_finite: u64,
}

impl Stats {
    /// All rays traced, of every kind.
    pub fn total_rays(&self) -> u64 {
        self.camera_rays + self.shadow_rays + self.reflection_rays + self.refraction_rays
    }
}

impl AddAssign for Stats {
    fn add_assign(&mut self, o: Stats) {
        self.samples += o.samples;
        self.camera_rays += o.camera_rays;
        self.shadow_rays += o.shadow_rays;
        self.reflection_rays += o.reflection_rays;
        self.refraction_rays += o.refraction_rays;
        self.tir_events += o.tir_events;
        self.pruned_by_depth += o.pruned_by_depth;
        self.pruned_by_weight += o.pruned_by_weight;
        self.non_finite += o.non_finite;
    }
}

/// What the pinhole ray through a point of the image meets first.
#[derive(Clone, Copy, Debug)]
pub struct Pick {
    /// The object hit.
    pub object: u32,
    /// Where.
    pub point: Vec3,
    /// Its distance from the eye along the view direction: the focus distance that makes
    /// it sharp.
    pub depth: f32,
}

/// The first surface on the pinhole ray through `film` (0..1 across and down the image)
/// of an image with aspect ratio `aspect`, seen through `camera`.
pub fn pick(scene: &Scene, camera: &Camera, aspect: f32, film: Vec2) -> Option<Pick> {
    let frame = camera.pinhole(aspect);
    let ray = frame.ray(film, Vec2::ZERO, 0.0);
    let hit = scene.intersect(&ray, f32::INFINITY)?;
    Some(Pick {
        object: hit.object,
        point: hit.surface.p,
        depth: (hit.surface.p - camera.position).dot(frame.forward()),
    })
}

/// How deeply dielectrics may nest (glass in water in glass ...); deeper entries are ignored.
pub const MAX_NESTING: usize = 8;

/// The dielectric objects a ray is inside, innermost last. Empty: the ray is in the
/// scene's surrounding medium.
#[derive(Clone, Copy, Debug, Default)]
pub struct Media {
    len: u8,
    // (object, material) of each medium entered.
    items: [(u32, u32); MAX_NESTING],
}

impl PartialEq for Media {
    fn eq(&self, other: &Media) -> bool {
        self.active() == other.active()
    }
}

impl Eq for Media {}

impl Media {
    fn active(&self) -> &[(u32, u32)] {
        &self.items[..self.len as usize]
    }

    /// The innermost medium's material.
    fn innermost(&self) -> Option<u32> {
        self.len.checked_sub(1).map(|i| self.items[i as usize].1)
    }

    /// After entering `object` made of `material`.
    fn entered(mut self, object: u32, material: u32) -> Media {
        if (self.len as usize) < MAX_NESTING {
            self.items[self.len as usize] = (object, material);
            self.len += 1;
        }
        self
    }

    /// After leaving `object` (the innermost one, unless geometry overlaps).
    fn left(mut self, object: u32) -> Media {
        if let Some(i) = self.active().iter().rposition(|&(o, _)| o == object) {
            self.items.copy_within(i + 1..self.len as usize, i);
            self.len -= 1;
        }
        self
    }
}

/// exp(−σ t) per channel; exactly 1 where σ = 0 (even for t = ∞).
#[inline]
fn transmittance(sigma: Color, t: f32) -> Color {
    Color::select(sigma.cmpeq(Color::ZERO), Color::ONE, (-sigma * t).exp())
}

/// Traces the samples of one image of one scene under one set of parameters.
pub struct Tracer<'a> {
    scene: &'a Scene,
    params: &'a Params,
    // The scene's materials with the parameters' overrides (ior, fresnel) applied.
    materials: Vec<Material>,
    // The scene's lights at the parameters' light size.
    lights: Vec<Light>,
    frame: CameraFrame,
    width: u32,
    height: u32,
}

impl<'a> Tracer<'a> {
    /// A tracer for a `width` × `height` image through the scene's own camera.
    pub fn new(scene: &'a Scene, params: &'a Params, width: u32, height: u32) -> Self {
        Self::with_camera(scene, &scene.camera, params, width, height)
    }

    /// A tracer for a `width` × `height` image through `camera`.
    pub fn with_camera(
        scene: &'a Scene,
        camera: &Camera,
        params: &'a Params,
        width: u32,
        height: u32,
    ) -> Self {
        Tracer {
            scene,
            params,
            materials: scene
                .materials
                .iter()
                .map(|m| m.with_params(params))
                .collect(),
            lights: scene
                .lights
                .iter()
                .map(|l| l.scaled(params.light_size))
                .collect(),
            frame: camera.frame(width as f32 / height as f32, camera.exposure(params)),
            width,
            height,
        }
    }

    /// Radiance of sample number `sample` of pixel (x, y). Its random numbers depend only
    /// on (seed, pixel, sample), so the result does too.
    pub fn sample(&self, x: u32, y: u32, sample: u32, stats: &mut Stats) -> Color {
        let p = self.params;
        let mut rng =
            SampleStream::with_pattern(p.pattern, p.spp, p.seed, y * self.width + x, sample);
        // Dimensions in a fixed order: image position, lens, time, then the tree's own.
        let jitter = rng.next_2d();
        let lens = rng.next_2d();
        let time = rng.next_1d();
        let film = Vec2::new(
            (x as f32 + jitter.x) / self.width as f32,
            (y as f32 + jitter.y) / self.height as f32,
        );
        let ray = self.frame.ray(film, lens, time);
        stats.samples += 1;
        stats.camera_rays += 1;
        self.trace(&ray, 0, 1.0, &Media::default(), &mut rng, stats)
    }

    /// The index of refraction of the medium a ray in `media` travels through.
    fn ior_of(&self, media: &Media) -> f32 {
        media
            .innermost()
            .and_then(|m| self.materials[m as usize].dielectric())
            .map_or(self.scene.medium_ior, |d| d.ior)
    }

    /// Radiance arriving along `ray` at tree level `depth`, reached with path weight
    /// `weight` (largest channel of the product of the reflectances and transmittances
    /// above it), travelling through `media`.
    pub fn trace(
        &self,
        ray: &Ray,
        depth: u32,
        weight: f32,
        media: &Media,
        rng: &mut SampleStream,
        stats: &mut Stats,
    ) -> Color {
        let sigma = media
            .innermost()
            .and_then(|m| self.materials[m as usize].dielectric())
            .map_or(Color::ZERO, |d| d.absorption);
        let hit = self.scene.intersect(ray, f32::INFINITY);
        // Area lights are seen where nothing is in front of them.
        let mut nearest = hit.map_or(f32::INFINITY, |h| h.surface.t);
        let mut emitted = None;
        for light in &self.lights {
            if let Some((t, radiance)) = light.hit(ray, nearest) {
                nearest = t;
                emitted = Some(radiance);
            }
        }
        if let Some(radiance) = emitted {
            return transmittance(sigma, nearest) * radiance;
        }
        let Some(hit) = hit else {
            return transmittance(sigma, f32::INFINITY) * self.scene.background.radiance(ray.dir);
        };
        // Beer–Lambert along the segment just travelled.
        let tr = transmittance(sigma, hit.surface.t);
        tr * self.shade(
            ray,
            &hit,
            depth,
            weight * tr.max_element(),
            media,
            rng,
            stats,
        )
    }

    #[allow(clippy::too_many_arguments)]
    fn shade(
        &self,
        ray: &Ray,
        hit: &Hit,
        depth: u32,
        weight: f32,
        media: &Media,
        rng: &mut SampleStream,
        stats: &mut Stats,
    ) -> Color {
        let s = &hit.surface;
        let entering = ray.dir.dot(s.n_geom) < 0.0;
        // Normals facing the side the ray arrived from.
        let (n_geom, n_shade) = if entering {
            (s.n_geom, s.n_shade)
        } else {
            (-s.n_geom, -s.n_shade)
        };
        let reflected = || {
            let dir = reflect(ray.dir, n_shade);
            // A shading normal can tilt the mirror direction below the surface.
            let dir = if dir.dot(n_geom) > 0.0 {
                dir
            } else {
                reflect(ray.dir, n_geom)
            };
            Ray {
                origin: offset_ray_origin(s.p, n_geom),
                dir,
                time: ray.time,
            }
        };
        match &self.materials[hit.material as usize] {
            Material::Emissive { radiance } => *radiance,
            Material::Diffuse {
                albedo,
                specular,
                exponent,
            } => self.diffuse(
                ray, hit, n_geom, n_shade, albedo, *specular, *exponent, rng, stats,
            ),
            Material::Mirror { reflectance } => {
                match self.branch(depth, weight * reflectance.max_element(), stats) {
                    Some(w) => {
                        stats.reflection_rays += 1;
                        *reflectance * self.trace(&reflected(), depth + 1, w, media, rng, stats)
                    }
                    None => Color::ZERO,
                }
            }
            Material::Glossy {
                reflectance,
                exponent,
            } => {
                // Jitter the mirror direction over the Phong lobe around it. Sampling the
                // normalized lobe exactly, each jittered ray carries the reflectance.
                let u = rng.next_2d();
                let Some(w) = self.branch(depth, weight * reflectance.max_element(), stats) else {
                    return Color::ZERO;
                };
                let mut child = reflected();
                let mut dir = to_world(phong_lobe(u, *exponent), child.dir);
                // Lobe directions below the surface are folded back above it (mirrored in
                // the tangent plane): no energy lost, no black speckles at grazing angles.
                let below = dir.dot(n_geom);
                if below <= 0.0 {
                    dir = (dir - 2.0 * below * n_geom).normalize();
                }
                child.dir = dir;
                stats.reflection_rays += 1;
                *reflectance * self.trace(&child, depth + 1, w, media, rng, stats)
            }
            Material::Glazed { coat, base } => {
                // The coat is seen from the medium the ray travels in; nothing enters it.
                let (n1, n2) = (self.ior_of(media), coat.ior);
                let cos_i = (-ray.dir).dot(n_shade).clamp(0.0, 1.0);
                let r = coat
                    .fresnel
                    .reflectance(cos_i, n1, n2, coat.constant_reflectance);
                let mut l = (1.0 - r)
                    * self.diffuse(
                        ray,
                        hit,
                        n_geom,
                        n_shade,
                        base,
                        Color::ZERO,
                        1.0,
                        rng,
                        stats,
                    );
                if r > 0.0
                    && let Some(w) = self.branch(depth, weight * r, stats)
                {
                    stats.reflection_rays += 1;
                    l += r * self.trace(&reflected(), depth + 1, w, media, rng, stats);
                }
                l
            }
            Material::Dielectric(d) => self.dielectric(
                ray,
                hit,
                d,
                entering,
                n_geom,
                n_shade,
                reflected(),
                depth,
                weight,
                media,
                rng,
                stats,
            ),
        }
    }

    /// The lecture's ray tree at a dielectric: a reflected child of weight R and a
    /// refracted child of weight 1 − R (or, in stochastic mode, one of them with
    /// probability R and 1 − R).
    #[allow(clippy::too_many_arguments)]
    fn dielectric(
        &self,
        ray: &Ray,
        hit: &Hit,
        d: &Dielectric,
        entering: bool,
        n_geom: Vec3,
        n_shade: Vec3,
        reflected: Ray,
        depth: u32,
        weight: f32,
        media: &Media,
        rng: &mut SampleStream,
        stats: &mut Stats,
    ) -> Color {
        let p = hit.surface.p;
        let (n1, n2, media_t) = if entering {
            (
                self.ior_of(media),
                d.ior,
                media.entered(hit.object, hit.material),
            )
        } else {
            let outside = media.left(hit.object);
            (d.ior, self.ior_of(&outside), outside)
        };
        let cos_i = (-ray.dir).dot(n_shade).clamp(0.0, 1.0);
        // Snell's law; the refracted ray must cross the geometric surface.
        let refracted = refract(ray.dir, n_shade, n1, n2)
            .filter(|t| t.dot(n_geom) < 0.0)
            .or_else(|| refract(ray.dir, n_geom, n1, n2))
            .map(|dir| Ray {
                origin: offset_ray_origin(p, -n_geom),
                dir,
                time: ray.time,
            });
        let r = match refracted {
            Some(_) => d.fresnel.reflectance(cos_i, n1, n2, d.constant_reflectance),
            None => {
                stats.tir_events += 1;
                1.0
            }
        };
        match self.params.tree {
            TreeMode::Split => {
                let mut l = Color::ZERO;
                if r > 0.0
                    && let Some(w) = self.branch(depth, weight * r, stats)
                {
                    stats.reflection_rays += 1;
                    l += r * self.trace(&reflected, depth + 1, w, media, rng, stats);
                }
                if let Some(t) = refracted
                    && r < 1.0
                    && let Some(w) = self.branch(depth, weight * (1.0 - r), stats)
                {
                    stats.refraction_rays += 1;
                    l += (1.0 - r) * self.trace(&t, depth + 1, w, &media_t, rng, stats);
                }
                l
            }
            TreeMode::Stochastic => {
                // Choosing a child with probability equal to its weight leaves the path
                // weight unchanged: R / P(reflect) = 1.
                let Some(w) = self.branch(depth, weight, stats) else {
                    return Color::ZERO;
                };
                match refracted {
                    Some(t) if rng.next_1d() >= r => {
                        stats.refraction_rays += 1;
                        self.trace(&t, depth + 1, w, &media_t, rng, stats)
                    }
                    _ => {
                        stats.reflection_rays += 1;
                        self.trace(&reflected, depth + 1, w, media, rng, stats)
                    }
                }
            }
        }
    }

    /// Whether a child at `depth + 1` with path weight `weight` is traced (the lecture's
    /// two pruning rules), counting the branches cut.
    fn branch(&self, depth: u32, weight: f32, stats: &mut Stats) -> Option<f32> {
        if depth >= self.params.max_depth {
            stats.pruned_by_depth += 1;
            None
        } else if weight < self.params.min_weight {
            stats.pruned_by_weight += 1;
            None
        } else {
            Some(weight)
        }
    }

    /// Diffuse shading: ambient plus every light, one shadow ray to one sampled point of
    /// each: L = a·L_ambient + Σ f(l, v) (L_light / p(l)) cos θ, with f the Lambert plus
    /// normalized Phong BRDF.
    #[allow(clippy::too_many_arguments)]
    fn diffuse(
        &self,
        ray: &Ray,
        hit: &Hit,
        n_geom: Vec3,
        n: Vec3,
        albedo: &Texture,
        specular: Color,
        exponent: f32,
        rng: &mut SampleStream,
        stats: &mut Stats,
    ) -> Color {
        let albedo = albedo.eval(hit.surface.uv);
        let p = hit.surface.p;
        let origin = offset_ray_origin(p, n_geom);
        let view = -ray.dir;
        let mut sum = self.scene.ambient * albedo;
        for light in &self.lights {
            let u = rng.next_2d();
            let Some(ls) = light.sample(p, u) else {
                continue;
            };
            let cos = n.dot(ls.dir);
            if cos <= 0.0 || n_geom.dot(ls.dir) <= 0.0 {
                continue;
            }
            stats.shadow_rays += 1;
            let shadow = Ray {
                origin,
                dir: ls.dir,
                time: ray.time,
            };
            // Stop just short of the light's surface (it is not in the BVH anyway).
            if self.scene.occluded(&shadow, ls.dist * (1.0 - 1e-4)) {
                continue;
            }
            let mut f = albedo / PI;
            if specular != Color::ZERO {
                let cos_alpha = reflect(-ls.dir, n).dot(view).max(0.0);
                f += specular * (exponent + 2.0) / (2.0 * PI) * cos_alpha.powf(exponent);
            }
            sum += f * ls.value * cos;
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn media_enter_and_leave_in_any_order() {
        let m = Media::default().entered(3, 10).entered(5, 11);
        assert_eq!(m.innermost(), Some(11));
        assert_eq!(m.left(5).innermost(), Some(10));
        // Leaving the outer one first (overlapping geometry) keeps the inner.
        assert_eq!(m.left(3).innermost(), Some(11));
        assert_eq!(m.left(3).left(5), Media::default());
        // Leaving what was never entered changes nothing.
        assert_eq!(m.left(9), m);
    }

    #[test]
    fn transmittance_is_beer_lambert_and_one_without_absorption() {
        let t = transmittance(Color::new(0.0, 1.0, 2.0), 0.5);
        assert_eq!(t.x, 1.0);
        assert!((t.y - (-0.5f32).exp()).abs() < 1e-7);
        assert!((t.z - (-1.0f32).exp()).abs() < 1e-7);
        assert_eq!(
            transmittance(Color::new(0.0, 1.0, 0.0), f32::INFINITY),
            Color::new(1.0, 0.0, 1.0)
        );
    }
}
