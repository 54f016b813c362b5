//! Lights and the background.
//!
//! A light has a shape and an `intensity`: its radiant intensity seen from far away along
//! its axis. A rectangle or disk of area A then has radiance L = intensity / A on its front
//! side; a sphere of radius r has L = intensity / (π r²) all round. Scaling a light (the
//! `light_size` parameter) keeps its intensity, so the scene stays as bright while shadows
//! soften; at size 0 every light is a point, with hard shadows (a rectangle or disk then
//! still emits only forwards, with intensity × cos θ).

use crate::geometry::{Quad, Sphere};
use crate::math::sampling::{concentric_disk, to_world, uniform_cone};
use crate::math::{Color, Ray, Vec3, orthonormal_basis};
use glam::Vec2;
use std::f32::consts::PI;

/// The shape of a light, at size 1.
#[derive(Clone, Debug, PartialEq)]
pub enum LightShape {
    /// A rectangle spanning `center ± edge_u/2 ± edge_v/2`, emitting on the side of
    /// edge_u × edge_v.
    Rect {
        /// Centre.
        center: Vec3,
        /// First edge.
        edge_u: Vec3,
        /// Second edge.
        edge_v: Vec3,
    },
    /// A disk emitting on the side of its unit `normal`.
    Disk {
        /// Centre.
        center: Vec3,
        /// Unit normal: the emitting side.
        normal: Vec3,
        /// Radius.
        radius: f32,
    },
    /// A sphere emitting all round; radius 0 is a point light.
    Sphere {
        /// Centre.
        center: Vec3,
        /// Radius.
        radius: f32,
    },
}

/// A light.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    /// Where it is and how big at size 1.
    pub shape: LightShape,
    /// Radiant intensity per channel, along the axis (rectangles, disks) or all round
    /// (spheres and points).
    pub intensity: Color,
    /// The size it is drawn at, about its centre (the `light_size` parameter).
    pub scale: f32,
}

/// Light arriving at a point from one sampled point of a light.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Unit direction from the shaded point towards the light.
    pub dir: Vec3,
    /// Distance to the sampled point.
    pub dist: f32,
    /// Incident radiance divided by the density of `dir` (per solid angle), so that the
    /// shaded point's estimate of reflected light is f · value · cos θ.
    pub value: Color,
    /// The density of `dir` per unit solid angle; infinite for a point light (a delta),
    /// which only light sampling can find. Path tracing weighs strategies by it.
    pub pdf: f32,
}

impl Light {
    /// A point light of radiant intensity `intensity` at `position`.
    pub fn point(position: Vec3, intensity: Color) -> Self {
        Light {
            shape: LightShape::Sphere {
                center: position,
                radius: 0.0,
            },
            intensity,
            scale: 1.0,
        }
    }

    /// The light's centre.
    pub fn center(&self) -> Vec3 {
        match self.shape {
            LightShape::Rect { center, .. }
            | LightShape::Disk { center, .. }
            | LightShape::Sphere { center, .. } => center,
        }
    }

    /// This light drawn at size `s`.
    pub fn scaled(&self, s: f32) -> Light {
        Light {
            scale: s,
            ..self.clone()
        }
    }

    /// The emitting side of a rectangle or disk.
    fn normal(&self) -> Option<Vec3> {
        match &self.shape {
            LightShape::Rect { edge_u, edge_v, .. } => {
                Some(edge_u.cross(*edge_v).normalize_or_zero())
            }
            LightShape::Disk { normal, .. } => Some(*normal),
            LightShape::Sphere { .. } => None,
        }
    }

    /// For a light drawn as a point (a point light, or any light at size 0): its radiant
    /// intensity towards the unit direction `dir`, all round for a sphere, intensity × cos θ
    /// in front of a rectangle or disk. `None` for a light with an area, which paths can
    /// find by themselves.
    pub fn point_intensity(&self, dir: Vec3) -> Option<Color> {
        if self.area() > 0.0 {
            return None;
        }
        Some(match self.normal() {
            Some(n) => self.intensity * dir.dot(n).max(0.0),
            None => self.intensity,
        })
    }

    /// The area that emits at the current scale (0 for a point).
    pub fn area(&self) -> f32 {
        let s2 = self.scale * self.scale;
        s2 * match &self.shape {
            LightShape::Rect { edge_u, edge_v, .. } => edge_u.cross(*edge_v).length(),
            LightShape::Disk { radius, .. } => PI * radius * radius,
            LightShape::Sphere { radius, .. } => 4.0 * PI * radius * radius,
        }
    }

    /// Emitted radiance (on the front side of rectangles and disks); 0 for a point.
    pub fn radiance(&self) -> Color {
        let projected = match &self.shape {
            LightShape::Sphere { radius, .. } => PI * (radius * self.scale).powi(2),
            _ => self.area(),
        };
        if projected > 0.0 {
            self.intensity / projected
        } else {
            Color::ZERO
        }
    }

    /// This light ready to be sampled and hit many times.
    pub fn prepare(&self) -> PreparedLight {
        let quad = match &self.shape {
            LightShape::Rect {
                center,
                edge_u,
                edge_v,
            } => {
                let (u, v) = (*edge_u * self.scale, *edge_v * self.scale);
                Some(Quad::new(*center - 0.5 * (u + v), u, v))
            }
            _ => None,
        };
        PreparedLight {
            area: self.area(),
            normal: self.normal(),
            radiance: self.radiance(),
            quad,
            light: self.clone(),
        }
    }
}

/// A light with what every sample and hit needs computed once for its scale: its area,
/// emitting side, radiance and (for a rectangle) its quad. The tracer keeps its lights so.
#[derive(Clone, Debug)]
pub struct PreparedLight {
    light: Light,
    area: f32,
    normal: Option<Vec3>,
    radiance: Color,
    quad: Option<Quad>,
}

impl PreparedLight {
    /// The uniform pair a sample of this light takes from the sample's stream: a light with
    /// no extent (a point, or any shape scaled to nothing) uses none, and its dimension is
    /// skipped rather than computed (the image is the same: the pair would go unused).
    pub(crate) fn draw(&self, u: &mut impl crate::math::Uniform) -> Vec2 {
        let extent = match &self.light.shape {
            LightShape::Sphere { radius, .. } => radius * self.light.scale > 0.0,
            _ => self.light.scale > 0.0,
        };
        if extent {
            u.next_2d()
        } else {
            u.skip(1);
            Vec2::ZERO
        }
    }

    /// A direction towards the light from `p`, from the uniform pair `u`: a uniform point
    /// on a rectangle or disk (density 1/A per area, so d²/(A cos θ_l) per solid angle), a
    /// uniform direction in the cone a sphere subtends, or the point itself. `None` when
    /// `p` sees only the back of the light, or is inside it.
    pub fn sample(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        let s = self.light.scale;
        let (q, normal) = match &self.light.shape {
            LightShape::Sphere { center, radius } if radius * s > 0.0 => {
                return self.sample_sphere(p, *center, radius * s, u);
            }
            LightShape::Sphere { center, .. } => (*center, None),
            LightShape::Rect {
                center,
                edge_u,
                edge_v,
            } => (
                *center + s * ((u.x - 0.5) * *edge_u + (u.y - 0.5) * *edge_v),
                self.normal,
            ),
            LightShape::Disk {
                center,
                normal,
                radius,
            } => {
                let (t, b) = orthonormal_basis(*normal);
                let d = concentric_disk(u) * (radius * s);
                (*center + d.x * t + d.y * b, Some(*normal))
            }
        };
        let to = q - p;
        let dist = to.length();
        if dist <= 0.0 {
            return None;
        }
        let dir = to / dist;
        let cos_l = normal.map_or(1.0, |n| -dir.dot(n));
        if cos_l <= 0.0 {
            return None;
        }
        let area = self.area;
        // Per solid angle the area density 1/A becomes d² / (A cos θ_l); L A = intensity.
        let (value, pdf) = if area > 0.0 {
            let g = area * cos_l / (dist * dist);
            (self.radiance * g, 1.0 / g)
        } else {
            (
                self.light.intensity * (cos_l / (dist * dist)),
                f32::INFINITY,
            )
        };
        Some(LightSample {
            dir,
            dist,
            value,
            pdf,
        })
    }

    fn sample_sphere(&self, p: Vec3, center: Vec3, radius: f32, u: Vec2) -> Option<LightSample> {
        let to_center = center - p;
        let dc2 = to_center.length_squared();
        if dc2 <= radius * radius {
            return None;
        }
        let dc = dc2.sqrt();
        // The cone of directions that meet the sphere: sin θ_max = r / d.
        let cos_max = (1.0 - radius * radius / dc2).max(0.0).sqrt();
        let dir = to_world(uniform_cone(u, cos_max), to_center / dc);
        let ray = Ray {
            origin: p,
            dir,
            time: 0.0,
        };
        let dist = Sphere::new(center, radius)
            .intersect_t(&ray, f32::INFINITY)
            .unwrap_or(dc - radius);
        let solid_angle = 2.0 * PI * (1.0 - cos_max);
        Some(LightSample {
            dir,
            dist,
            value: self.radiance * solid_angle,
            pdf: 1.0 / solid_angle,
        })
    }

    /// The density per unit solid angle with which [`PreparedLight::sample`] from `p`
    /// picks the direction of `ray` (from `p`), which meets the light at distance `t`:
    /// what a path that found the light by itself weighs its light sample against.
    pub fn pdf(&self, ray: &Ray, t: f32) -> f32 {
        match (&self.light.shape, self.normal) {
            (LightShape::Sphere { center, radius }, _) => {
                let r = radius * self.light.scale;
                let dc2 = (*center - ray.origin).length_squared();
                let cos_max = (1.0 - r * r / dc2).max(0.0).sqrt();
                1.0 / (2.0 * PI * (1.0 - cos_max))
            }
            (_, Some(n)) => {
                let cos_l = ray.dir.dot(n).abs();
                t * t / (self.area * cos_l)
            }
            (_, None) => 0.0,
        }
    }

    /// Whether a ray can hit the light: it has an area (a point has none).
    pub(crate) fn can_be_seen(&self) -> bool {
        self.area > 0.0
    }

    /// Where `ray` meets the light's emitting surface before `t_max`, and the radiance it
    /// sees there (black from behind a rectangle or disk). Points are never hit.
    pub fn hit(&self, ray: &Ray, t_max: f32) -> Option<(f32, Color)> {
        if !self.can_be_seen() {
            return None;
        }
        let s = self.light.scale;
        let t = match &self.light.shape {
            LightShape::Rect { .. } => self.quad.as_ref()?.intersect_t(ray, t_max)?,
            LightShape::Disk {
                center,
                normal,
                radius,
            } => {
                let denom = normal.dot(ray.dir);
                if denom.abs() < 1e-12 {
                    return None;
                }
                let t = normal.dot(*center - ray.origin) / denom;
                let inside = (ray.at(t) - *center).length_squared() <= (radius * s).powi(2);
                (t > 0.0 && t < t_max && inside).then_some(t)?
            }
            LightShape::Sphere { center, radius } => {
                Sphere::new(*center, radius * s).intersect_t(ray, t_max)?
            }
        };
        let front = self.normal.is_none_or(|n| ray.dir.dot(n) < 0.0);
        Some((t, if front { self.radiance } else { Color::ZERO }))
    }
}

/// What a ray that leaves the scene sees.
#[derive(Clone, Debug, PartialEq)]
pub enum Background {
    /// The same radiance in every direction: a uniform environment.
    Constant(Color),
    /// A sky: `horizon` at and below the horizon (y ≤ 0), blending to `zenith` straight up.
    Gradient {
        /// Radiance at the horizon and below.
        horizon: Color,
        /// Radiance straight up.
        zenith: Color,
    },
}

impl Background {
    /// Radiance seen along the unit direction `dir`.
    #[inline]
    pub fn radiance(&self, dir: Vec3) -> Color {
        match self {
            Background::Constant(c) => *c,
            Background::Gradient { horizon, zenith } => horizon.lerp(*zenith, dir.y.max(0.0)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::SampleStream;

    /// The irradiance estimate at `p` (normal `n`) from `samples` samples of `light`.
    fn irradiance(light: &Light, p: Vec3, n: Vec3, samples: u32) -> f64 {
        let light = light.prepare();
        let mut sum = 0.0f64;
        for i in 0..samples {
            let u =
                SampleStream::with_pattern(crate::math::Pattern::Sobol, samples, 1, 0, i).next_2d();
            if let Some(s) = light.sample(p, u) {
                sum += (s.value.x * s.dir.dot(n).max(0.0)) as f64;
            }
        }
        sum / samples as f64
    }

    #[test]
    fn disk_light_sampling_converges_to_the_analytic_irradiance() {
        // On the axis of a disk of radius R and radiance L at height h: E = π L R² / (h² + R²).
        let (radius, h) = (1.5f32, 2.0f32);
        let light = Light {
            shape: LightShape::Disk {
                center: Vec3::new(0.0, h, 0.0),
                normal: -Vec3::Y,
                radius,
            },
            intensity: Color::splat(3.0),
            scale: 1.0,
        };
        let l = light.radiance().x as f64;
        let expected =
            std::f64::consts::PI * l * (radius * radius) as f64 / (h * h + radius * radius) as f64;
        let got = irradiance(&light, Vec3::ZERO, Vec3::Y, 1 << 14);
        assert!(
            (got - expected).abs() < 1e-3 * expected,
            "{got} vs {expected}"
        );
        // From behind, nothing.
        assert!(
            light
                .prepare()
                .sample(Vec3::new(0.0, 5.0, 0.0), Vec2::splat(0.5))
                .is_none()
        );
    }

    #[test]
    fn sphere_light_irradiance_is_that_of_a_point_of_equal_intensity() {
        // A sphere light's far field: E = I cos θ / d² (exact outside the sphere, for a
        // surface that sees the whole sphere).
        let light = Light {
            shape: LightShape::Sphere {
                center: Vec3::new(0.0, 3.0, 0.0),
                radius: 0.8,
            },
            intensity: Color::splat(5.0),
            scale: 1.0,
        };
        let got = irradiance(&light, Vec3::ZERO, Vec3::Y, 1 << 12);
        assert!((got - 5.0 / 9.0).abs() < 1e-4, "{got}");
    }

    #[test]
    fn rect_light_at_size_zero_is_a_forward_point_light() {
        let rect = Light {
            shape: LightShape::Rect {
                center: Vec3::new(0.0, 2.0, 0.0),
                edge_u: Vec3::X,
                edge_v: Vec3::Z,
            },
            intensity: Color::splat(4.0),
            scale: 0.0,
        };
        // edge_u × edge_v = x × z = −y: it shines down.
        let point = rect.prepare();
        let s = point.sample(Vec3::ZERO, Vec2::splat(0.3)).unwrap();
        assert!((s.value.x - 4.0 / 4.0).abs() < 1e-6 && (s.dir - Vec3::Y).length() < 1e-6);
        assert!(
            point
                .sample(Vec3::new(0.0, 4.0, 0.0), Vec2::splat(0.3))
                .is_none()
        );
        assert!(
            point
                .hit(&Ray::new(Vec3::ZERO, Vec3::Y, 0.0), f32::INFINITY)
                .is_none(),
            "a point is never hit"
        );
        // At size 1 it is seen from below, and is dark from above.
        let big = rect.scaled(1.0).prepare();
        let (t, l) = big
            .hit(&Ray::new(Vec3::ZERO, Vec3::Y, 0.0), f32::INFINITY)
            .unwrap();
        assert!((t - 2.0).abs() < 1e-6 && (l.x - 4.0).abs() < 1e-6);
        let (_, back) = big
            .hit(
                &Ray::new(Vec3::new(0.0, 4.0, 0.0), -Vec3::Y, 0.0),
                f32::INFINITY,
            )
            .unwrap();
        assert_eq!(back, Color::ZERO);
        // Scaling keeps the intensity: the on-axis irradiance far away is unchanged.
        let far = Vec3::new(0.0, -200.0, 0.0);
        for size in [0.0, 0.5, 2.0] {
            let e = irradiance(&rect.scaled(size), far, Vec3::Y, 256);
            assert!(
                (e - 4.0 / 202.0f64.powi(2)).abs() < 1e-3 * 4.0 / 202.0f64.powi(2),
                "size {size}: {e}"
            );
        }
    }
}
