//! The ray tree: from each camera ray, shadow rays to the lights and reflected child rays,
//! pruned by depth and by attenuation (the path weight).

use crate::camera::CameraFrame;
use crate::material::Material;
use crate::math::{Color, Ray, SampleStream, Vec3, offset_ray_origin};
use crate::optics::reflect;
use crate::params::Params;
use crate::scene::{Hit, Scene};
use glam::Vec2;
use std::f32::consts::PI;
use std::ops::AddAssign;

/// What the tracer did: rays by kind and branches pruned.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
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
        self.pruned_by_depth += o.pruned_by_depth;
        self.pruned_by_weight += o.pruned_by_weight;
        self.non_finite += o.non_finite;
    }
}

/// Traces the samples of one image of one scene under one set of parameters.
pub struct Tracer<'a> {
    scene: &'a Scene,
    params: &'a Params,
    frame: CameraFrame,
    width: u32,
    height: u32,
}

impl<'a> Tracer<'a> {
    /// A tracer for a `width` × `height` image.
    pub fn new(scene: &'a Scene, params: &'a Params, width: u32, height: u32) -> Self {
        Tracer {
            scene,
            params,
            frame: scene.camera.frame(width as f32 / height as f32),
            width,
            height,
        }
    }

    /// Radiance of sample number `sample` of pixel (x, y). Its random numbers depend only
    /// on (seed, pixel, sample), so the result does too.
    pub fn sample(&self, x: u32, y: u32, sample: u32, stats: &mut Stats) -> Color {
        let mut rng = SampleStream::new(self.params.seed, y * self.width + x, sample);
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
        self.trace(&ray, 0, 1.0, stats)
    }

    /// Radiance arriving along `ray`, at tree level `depth`, reached with path weight
    /// `weight` (the largest channel of the product of reflectances above it).
    pub fn trace(&self, ray: &Ray, depth: u32, weight: f32, stats: &mut Stats) -> Color {
        let Some(hit) = self.scene.intersect(ray, f32::INFINITY) else {
            return self.scene.background.radiance(ray.dir);
        };
        let s = &hit.surface;
        // Shade the side the ray arrived on.
        let (n_geom, n_shade) = if ray.dir.dot(s.n_geom) > 0.0 {
            (-s.n_geom, -s.n_shade)
        } else {
            (s.n_geom, s.n_shade)
        };
        match &self.scene.materials[hit.material as usize] {
            Material::Emissive { radiance } => *radiance,
            Material::Diffuse {
                albedo,
                specular,
                exponent,
            } => {
                let albedo = albedo.eval(s.uv);
                let lit = self.direct_light(
                    &hit, ray, n_geom, n_shade, albedo, *specular, *exponent, stats,
                );
                self.scene.ambient * albedo + lit
            }
            Material::Mirror { reflectance } => {
                let mut dir = reflect(ray.dir, n_shade);
                // A shading normal can tilt the mirror direction below the surface.
                if dir.dot(n_geom) <= 0.0 {
                    dir = reflect(ray.dir, n_geom);
                }
                let child = Ray {
                    origin: offset_ray_origin(s.p, n_geom),
                    dir,
                    time: ray.time,
                };
                match self.branch(depth, weight * reflectance.max_element(), stats) {
                    Some(w) => {
                        stats.reflection_rays += 1;
                        *reflectance * self.trace(&child, depth + 1, w, stats)
                    }
                    None => Color::ZERO,
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

    /// Light from the point lights reflected towards the viewer, one shadow ray each:
    /// L = Σ f(l, v) I cos θ / r², with f the Lambert plus normalized Phong BRDF.
    #[allow(clippy::too_many_arguments)]
    fn direct_light(
        &self,
        hit: &Hit,
        ray: &Ray,
        n_geom: Vec3,
        n: Vec3,
        albedo: Color,
        specular: Color,
        exponent: f32,
        stats: &mut Stats,
    ) -> Color {
        let p = hit.surface.p;
        let origin = offset_ray_origin(p, n_geom);
        let view = -ray.dir;
        let mut sum = Color::ZERO;
        for light in &self.scene.lights {
            let to_light = light.position - p;
            let dist2 = to_light.length_squared();
            let dist = dist2.sqrt();
            let l = to_light / dist;
            let cos = n.dot(l);
            if cos <= 0.0 || n_geom.dot(l) <= 0.0 {
                continue;
            }
            stats.shadow_rays += 1;
            let shadow = Ray {
                origin,
                dir: l,
                time: ray.time,
            };
            if self
                .scene
                .occluded(&shadow, (light.position - origin).length())
            {
                continue;
            }
            let mut f = albedo / PI;
            if specular != Color::ZERO {
                let cos_alpha = reflect(-l, n).dot(view).max(0.0);
                f += specular * (exponent + 2.0) / (2.0 * PI) * cos_alpha.powf(exponent);
            }
            sum += f * light.intensity * (cos / dist2);
        }
        sum
    }
}
