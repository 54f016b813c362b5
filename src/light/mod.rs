//! Lights and the background.
//!
//! A light has a shape and an `intensity`: its radiant intensity seen from far away along
//! its axis. A rectangle or disk of area A then has radiance L = intensity / A on its front
//! side; a sphere of radius r has L = intensity / (π r²) all round. Scaling a light (the
//! `light_size` parameter) keeps its intensity, so the scene stays as bright while shadows
//! soften; at size 0 every light is a point, with hard shadows (a rectangle or disk then
//! still emits only forwards, with intensity × cos θ). A spot is a point at every size,
//! its intensity shaped by a cone.

use crate::geometry::{Quad, Sphere};
use crate::math::lanes::{RayOf, Real, Vector};
use crate::math::rng::Pair;
use crate::math::sampling::{concentric_disk, to_world, uniform_cone};
use crate::math::{Color, Ray, SampleStream, Uniform, Vec3, orthonormal_basis};
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
    /// A point shining into a cone about `cone.axis` (glTF's spot light): a point at
    /// every `light_size`.
    Spot {
        /// Position.
        center: Vec3,
        /// Where it shines, and how the light falls off towards the cone's edge.
        cone: Cone,
    },
}

/// A spot light's cone: full intensity within `cos_inner` of the axis, none beyond
/// `cos_outer`, and between them glTF's (KHR_lights_punctual) falloff
/// t², t = clamp((cos θ − cos θ_outer) / max(cos θ_inner − cos θ_outer, 0.001), 0, 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cone {
    /// Unit direction the spot shines along.
    pub axis: Vec3,
    /// Cosine of the angle within which it shines at full intensity.
    pub cos_inner: f32,
    /// Cosine of the angle beyond which it is dark (at most `cos_inner`).
    pub cos_outer: f32,
}

impl Cone {
    /// The share of the spot's intensity that leaves along the unit direction `dir`,
    /// given as its cosine with the axis, for one direction or one per lane.
    #[inline(always)]
    pub(crate) fn falloff<R: Real>(&self, cos: R) -> R {
        let scale = 1.0 / (self.cos_inner - self.cos_outer).max(0.001);
        let t = (cos - R::splat(self.cos_outer)) * R::splat(scale);
        let (zero, one) = (R::splat(0.0), R::splat(1.0));
        // A NaN cosine (a direction of zero length) is dark, as beyond the cone.
        let t = R::select(t.less(one), t, one);
        let t = R::select(zero.less(t), t, zero);
        t * t
    }
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

    /// A spot light at `position` of radiant intensity `intensity` along its axis, shaped
    /// by `cone`.
    pub fn spot(position: Vec3, cone: Cone, intensity: Color) -> Self {
        Light {
            shape: LightShape::Spot {
                center: position,
                cone,
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
            | LightShape::Sphere { center, .. }
            | LightShape::Spot { center, .. } => center,
        }
    }

    /// This light moved, turned and (its extent) scaled by `t`, a transform that scales
    /// uniformly (a placed model's). Its intensity is kept: scaling a model moves its
    /// lights apart without brightening them.
    pub(crate) fn transformed(&self, t: &glam::Affine3A) -> Light {
        let to = |p: Vec3| Vec3::from(t.transform_point3(p.into()));
        let turn = |v: Vec3| Vec3::from(t.transform_vector3(v.into()));
        let scale = turn(Vec3::X).length();
        let shape = match &self.shape {
            LightShape::Spot { center, cone } => LightShape::Spot {
                center: to(*center),
                cone: Cone {
                    axis: turn(cone.axis).normalize(),
                    ..*cone
                },
            },
            LightShape::Sphere { center, radius } => LightShape::Sphere {
                center: to(*center),
                radius: radius * scale,
            },
            LightShape::Rect {
                center,
                edge_u,
                edge_v,
            } => LightShape::Rect {
                center: to(*center),
                edge_u: turn(*edge_u),
                edge_v: turn(*edge_v),
            },
            LightShape::Disk {
                center,
                normal,
                radius,
            } => LightShape::Disk {
                center: to(*center),
                normal: turn(*normal).normalize(),
                radius: radius * scale,
            },
        };
        Light {
            shape,
            ..self.clone()
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
            LightShape::Sphere { .. } | LightShape::Spot { .. } => None,
        }
    }

    /// For a light drawn as a point (a point light, a spot, or any light at size 0): its
    /// radiant intensity towards the unit direction `dir`, all round for a sphere,
    /// intensity × cos θ in front of a rectangle or disk, intensity × the cone's falloff
    /// for a spot. `None` for a light with an area, which paths can find by themselves.
    pub fn point_intensity(&self, dir: Vec3) -> Option<Color> {
        if self.area() > 0.0 {
            return None;
        }
        Some(match (&self.shape, self.normal()) {
            (LightShape::Spot { cone, .. }, _) => self.intensity * cone.falloff(dir.dot(cone.axis)),
            (_, Some(n)) => self.intensity * dir.dot(n).max(0.0),
            (_, None) => self.intensity,
        })
    }

    /// The area that emits at the current scale (0 for a point).
    pub fn area(&self) -> f32 {
        let s2 = self.scale * self.scale;
        s2 * match &self.shape {
            LightShape::Rect { edge_u, edge_v, .. } => edge_u.cross(*edge_v).length(),
            LightShape::Disk { radius, .. } => PI * radius * radius,
            LightShape::Sphere { radius, .. } => 4.0 * PI * radius * radius,
            LightShape::Spot { .. } => 0.0,
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
        let cone = match &self.shape {
            LightShape::Spot { cone, .. } => Some(*cone),
            _ => None,
        };
        PreparedLight {
            area: self.area(),
            normal: self.normal(),
            radiance: self.radiance(),
            quad,
            cone,
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
    cone: Option<Cone>,
}

impl PreparedLight {
    /// The uniform pair a sample of this light takes from the sample's stream: a light with
    /// no extent (a point, or any shape scaled to nothing) uses none, and its dimension is
    /// skipped rather than computed (the image is the same: the pair would go unused).
    pub(crate) fn draw(&self, u: &mut impl crate::math::Uniform) -> Vec2 {
        if self.has_extent() {
            u.next_2d()
        } else {
            u.skip(1);
            Vec2::ZERO
        }
    }

    /// [`PreparedLight::draw`] from a sample's stream, the pair left to be drawn later in
    /// lanes where the stream's pattern allows ([`SampleStream::next_2d_or_later`]).
    #[inline(always)]
    pub(crate) fn draw_or_later(&self, rng: &mut SampleStream) -> Pair {
        if self.has_extent() {
            rng.next_2d_or_later()
        } else {
            rng.skip(1);
            Pair::Drawn(Vec2::ZERO)
        }
    }

    /// Whether it has an extent to sample: not a point, nor a shape scaled to nothing.
    #[inline(always)]
    fn has_extent(&self) -> bool {
        match &self.light.shape {
            LightShape::Sphere { radius, .. } => radius * self.light.scale > 0.0,
            LightShape::Spot { .. } => false,
            _ => self.light.scale > 0.0,
        }
    }

    /// A direction towards the light from `p`, from the uniform pair `u`: a uniform point
    /// on a rectangle or disk (density 1/A per area, so d²/(A cos θ_l) per solid angle), a
    /// uniform direction in the cone a sphere subtends, or the point itself. `None` when
    /// `p` sees only the back of the light, or is inside it.
    pub fn sample(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        let s = self.light.scale;
        if let LightShape::Disk {
            center,
            normal,
            radius,
        } = &self.light.shape
        {
            let (t, b) = orthonormal_basis(*normal);
            let d = concentric_disk(u) * (radius * s);
            let q = *center + d.x * t + d.y * b;
            let (dir, dist, factor, valid) = self.toward::<f32>(p, q);
            return valid.then(|| self.sample_of(dir, dist, factor));
        }
        if let Some(q) = self.point_of::<f32>((u.x, u.y)) {
            let (dir, dist, factor, valid) = self.toward::<f32>(p, q);
            return valid.then(|| self.sample_of(dir, dist, factor));
        }
        match &self.light.shape {
            LightShape::Sphere { center, radius } => self.sample_sphere(p, *center, radius * s, u),
            _ => None,
        }
    }

    /// The point [`PreparedLight::sample`] aims at, from the uniform pair `u`, for one
    /// sample or one per lane, where it is made so: a uniform point on a rectangle,
    /// centre + s ((u₁ − ½) edge_u + (u₂ − ½) edge_v), or a point light's position. `None`
    /// for a disk and a sphere with a radius.
    #[inline(always)]
    pub(crate) fn point_of<R: Real>(&self, u: (R, R)) -> Option<R::V3> {
        let s = self.light.scale;
        match &self.light.shape {
            LightShape::Rect {
                center,
                edge_u,
                edge_v,
            } => {
                let half = R::splat(0.5);
                let across = R::V3::splat(*edge_u).scale(u.0 - half)
                    + R::V3::splat(*edge_v).scale(u.1 - half);
                Some(R::V3::splat(*center) + across.scale(R::splat(s)))
            }
            // A sphere with a radius is sampled by its cone of directions instead.
            LightShape::Sphere { center, radius } => {
                if radius * s > 0.0 {
                    None
                } else {
                    Some(R::V3::splat(*center))
                }
            }
            LightShape::Spot { center, .. } => Some(R::V3::splat(*center)),
            LightShape::Disk { .. } => None,
        }
    }

    /// Whether [`PreparedLight::point_of`] makes this light's points: a rectangle or a
    /// point light.
    pub(crate) fn aims_at_points(&self) -> bool {
        self.point_of::<f32>((0.5, 0.5)).is_some()
    }

    /// From `p` towards the light's point `q`, for one sample or one per lane: the unit
    /// direction, the distance, the factor on the light's [`PreparedLight::base`]
    /// (A cos θ_l / d² for an area, cos θ_l / d² for a point: per solid angle the area
    /// density 1/A becomes d² / (A cos θ_l), and L A = intensity; a spot's falloff / d²),
    /// and whether the point is seen from its emitting side (inside a spot's cone) at a
    /// distance.
    #[inline(always)]
    pub(crate) fn toward<R: Real>(&self, p: R::V3, q: R::V3) -> (R::V3, R, R, R::Mask) {
        let to = q - p;
        let dist = to.length_squared().sqrt();
        let dir = to.div(dist);
        let cos_l = match self.normal {
            Some(n) => -dir.dot(R::V3::splat(n)),
            None => R::splat(1.0),
        };
        let zero = R::splat(0.0);
        // As `dist > 0` and `cos_l > 0` fail for NaN in the scalar code: not ≤ 0.
        let valid = !dist.less_eq(zero) & !cos_l.less_eq(zero);
        let dd = dist * dist;
        let factor = if self.area > 0.0 {
            R::splat(self.area) * cos_l / dd
        } else {
            cos_l / dd
        };
        match &self.cone {
            Some(cone) => {
                let falloff = cone.falloff(-dir.dot(R::V3::splat(cone.axis)));
                (dir, dist, factor * falloff, valid & !falloff.less_eq(zero))
            }
            None => (dir, dist, factor, valid),
        }
    }

    /// What a sample's radiance over its density is made of: the light's radiance (an
    /// area) or its intensity (a point), times a sample's factor.
    pub(crate) fn base(&self) -> Color {
        if self.area > 0.0 {
            self.radiance
        } else {
            self.light.intensity
        }
    }

    /// The sample along `dir` at `dist`, with [`PreparedLight::toward`]'s `factor`.
    fn sample_of(&self, dir: Vec3, dist: f32, factor: f32) -> LightSample {
        let pdf = if self.area > 0.0 {
            1.0 / factor
        } else {
            f32::INFINITY
        };
        LightSample {
            dir,
            dist,
            value: self.base() * factor,
            pdf,
        }
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
            _ => self.nearest_of::<f32>(ray.of(), t_max)?,
        };
        (t < f32::INFINITY).then(|| (t, self.seen_along(ray.dir)))
    }

    /// Where a ray (origin `o`, unit direction `d`, frame time `time`) meets a
    /// rectangle's or sphere's emitting surface in (0, t_max), for one ray or one per
    /// lane: its distance, +∞ where it misses; `None` for a disk, and for a light that
    /// [`PreparedLight::can_be_seen`] not.
    #[inline(always)]
    pub(crate) fn nearest_of<R: Real>(&self, ray: RayOf<R>, t_max: R) -> Option<R> {
        if !self.can_be_seen() {
            return None;
        }
        let (o, d) = (ray.origin, ray.dir);
        match &self.light.shape {
            LightShape::Rect { .. } => Some(self.quad.as_ref()?.nearest(o, d, t_max)),
            LightShape::Sphere { center, radius } => {
                let sphere = Sphere::new(*center, radius * self.light.scale);
                Some(sphere.nearest(o, d, ray.time, t_max))
            }
            LightShape::Disk { .. } | LightShape::Spot { .. } => None,
        }
    }

    /// The radiance a ray along `dir` sees where it meets the light: black from behind a
    /// rectangle or disk.
    pub(crate) fn seen_along(&self, dir: Vec3) -> Color {
        if self.normal.is_none_or(|n| dir.dot(n) < 0.0) {
            self.radiance
        } else {
            Color::ZERO
        }
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
mod tests;
