//! Spheres, parallelograms and planes.

use super::SurfaceHit;
use crate::math::lanes::{Real, Vector, Wide, clamp};
use crate::math::{Ray, Vec3, orthonormal_basis};
use glam::Vec2;
use obvhs::aabb::Aabb;
use std::f32::consts::PI;

/// A sphere, possibly moving: its centre is `center + velocity * t` at frame time t.
#[derive(Clone, Debug)]
pub struct Sphere {
    /// Centre at time 0.
    pub center: Vec3,
    /// Radius, > 0.
    pub radius: f32,
    /// Displacement over the frame (time 0 to 1).
    pub velocity: Vec3,
}

impl Sphere {
    /// A sphere that does not move.
    pub fn new(center: Vec3, radius: f32) -> Self {
        Sphere {
            center,
            radius,
            velocity: Vec3::ZERO,
        }
    }

    /// The centre at frame time `t`.
    #[inline]
    pub fn center_at(&self, t: f32) -> Vec3 {
        self.center_of(t)
    }

    /// [`Sphere::center_at`] for one time or one per lane: c + v t.
    #[inline(always)]
    fn center_of<R: Real>(&self, time: R) -> R::V3 {
        R::V3::splat(self.center) + R::V3::splat(self.velocity).scale(time)
    }

    /// Bounds of the sphere over the whole frame.
    pub fn bounds(&self) -> Aabb {
        let start = Aabb::new(self.center - self.radius, self.center + self.radius);
        let end = Aabb::new(start.min + self.velocity, start.max + self.velocity);
        start.union(&end)
    }

    /// Nearest root of |o + t d - c|² = r² in (0, t_max).
    #[inline]
    pub fn intersect_t(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let t = self.nearest(ray.origin, ray.dir, ray.time, t_max);
        found(t)
    }

    /// [`Sphere::intersect_t`] for one ray or one per lane (origin `o`, unit direction `d`,
    /// frame time `time`): the distance, or +∞ where there is none in (0, t_max).
    ///
    /// Computed as in "Precision Improvements for Ray/Sphere Intersection" (Haines et al.,
    /// Ray Tracing Gems ch. 7): the discriminant as r² - |f - (f·d)d|² with f = o - c, and
    /// the near root as c/q, which avoids cancellation for small spheres seen from far away.
    #[inline(always)]
    pub(crate) fn nearest<R: Real>(&self, o: R::V3, d: R::V3, time: R, t_max: R) -> R {
        sphere_nearest(&self.at(R::V3::splat), o, d, time, t_max)
    }

    /// What [`Sphere::nearest`] reads of the sphere, each vector made by `v` (broadcast,
    /// or kept [`Wide`]).
    #[inline(always)]
    pub(crate) fn at<V>(&self, v: impl Fn(Vec3) -> V) -> SphereAt<V> {
        SphereAt {
            center: v(self.center),
            velocity: v(self.velocity),
            radius: self.radius,
        }
    }

    /// The hit record at `t`, with the point reprojected onto the sphere.
    pub fn surface_hit(&self, ray: &Ray, t: f32, with_uv: bool) -> SurfaceHit {
        let (p, n) = self.surface_of(ray.origin, ray.dir, ray.time, t);
        // Longitude around +y and colatitude from +y, each in [0, 1]; only for textures
        // (atan2 and acos cost as much as the intersection).
        let uv = if with_uv {
            Vec2::new(
                0.5 + n.z.atan2(n.x) / (2.0 * PI),
                n.y.clamp(-1.0, 1.0).acos() / PI,
            )
        } else {
            Vec2::ZERO
        };
        SurfaceHit {
            t,
            p,
            n_geom: n,
            n_shade: n,
            uv,
        }
    }

    /// The point and unit normal at distance `t` along a ray (origin `o`, direction `d`,
    /// frame time `time`), for one ray or one per lane: n = (o + t d − c(time)) / |…|, the
    /// point reprojected onto the sphere as c + r n.
    #[inline(always)]
    pub(crate) fn surface_of<R: Real>(&self, o: R::V3, d: R::V3, time: R, t: R) -> (R::V3, R::V3) {
        let center = self.center_of(time);
        let n = ((o + d.scale(t)) - center).normalize();
        (center + n.scale(R::splat(self.radius)), n)
    }
}

/// A parallelogram `corner + a edge_u + b edge_v` for a, b in [0, 1]; its normal is
/// `edge_u × edge_v`.
#[derive(Clone, Debug)]
pub struct Quad {
    /// One corner.
    pub corner: Vec3,
    /// First edge from the corner.
    pub edge_u: Vec3,
    /// Second edge from the corner.
    pub edge_v: Vec3,
    normal: Vec3,
    // w = n / (n·n) with the unnormalized n: gives the (a, b) coordinates of a point.
    w: Vec3,
}

impl Quad {
    /// The parallelogram on `corner` spanned by `edge_u` and `edge_v` (not parallel).
    pub fn new(corner: Vec3, edge_u: Vec3, edge_v: Vec3) -> Self {
        let n = edge_u.cross(edge_v);
        Quad {
            corner,
            edge_u,
            edge_v,
            normal: n.normalize(),
            w: n / n.length_squared(),
        }
    }

    /// The unit normal, `edge_u × edge_v` normalized.
    pub fn normal(&self) -> Vec3 {
        self.normal
    }

    /// Bounds of the four corners.
    pub fn bounds(&self) -> Aabb {
        let c = self.corner;
        let pts = [
            c,
            c + self.edge_u,
            c + self.edge_v,
            c + self.edge_u + self.edge_v,
        ];
        Aabb::from_points(&pts)
    }

    /// Hit distance, if hit in (0, t_max).
    #[inline]
    pub fn intersect_t(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        found(self.nearest(ray.origin, ray.dir, t_max))
    }

    /// [`Quad::intersect_t`] for one ray or one per lane: the distance t to the plane
    /// n·(p − corner) = 0, where the point's coordinates a = w·(rel × edge_v) and
    /// b = w·(edge_u × rel) (rel = p − corner) are both in [0, 1]; +∞ where it misses.
    #[inline(always)]
    pub(crate) fn nearest<R: Real>(&self, o: R::V3, d: R::V3, t_max: R) -> R {
        quad_nearest(&self.at(R::V3::splat), o, d, t_max)
    }

    /// What [`Quad::nearest`] reads of the quad, each vector made by `v`
    /// (broadcast, or kept [`Wide`]).
    #[inline(always)]
    pub(crate) fn at<V>(&self, v: impl Fn(Vec3) -> V) -> QuadAt<V> {
        QuadAt {
            corner: v(self.corner),
            edge_u: v(self.edge_u),
            edge_v: v(self.edge_v),
            normal: v(self.normal),
            w: v(self.w),
        }
    }

    /// The hit record at `t`, with the point rebuilt from its surface coordinates.
    pub fn surface_hit(&self, ray: &Ray, t: f32) -> SurfaceHit {
        let (p, a, b) = self.surface_of(ray.origin, ray.dir, t);
        SurfaceHit {
            t,
            p,
            n_geom: self.normal,
            n_shade: self.normal,
            uv: Vec2::new(a, b),
        }
    }

    /// The point at distance `t` along a ray (origin `o`, direction `d`) and its
    /// coordinates (a, b), for one ray or one per lane: a = w·(rel × edge_v) and
    /// b = w·(edge_u × rel) clamped to [0, 1] (rel = o + t d − corner), the point rebuilt
    /// as corner + a edge_u + b edge_v.
    #[inline(always)]
    pub(crate) fn surface_of<R: Real>(&self, o: R::V3, d: R::V3, t: R) -> (R::V3, R, R) {
        let at = R::V3::splat;
        let rel = (o + d.scale(t)) - at(self.corner);
        let w = at(self.w);
        let (zero, one) = (R::splat(0.0), R::splat(1.0));
        let a = clamp(w.dot(rel.cross(at(self.edge_v))), zero, one);
        let b = clamp(w.dot(at(self.edge_u).cross(rel)), zero, one);
        let p = at(self.corner) + at(self.edge_u).scale(a) + at(self.edge_v).scale(b);
        (p, a, b)
    }
}

/// An infinite plane through `point` with unit `normal`.
#[derive(Clone, Debug)]
pub struct Plane {
    /// A point on the plane.
    pub point: Vec3,
    /// Unit normal.
    pub normal: Vec3,
    tangent: Vec3,
    bitangent: Vec3,
}

impl Plane {
    /// The plane through `point` with normal `normal` (normalized here).
    pub fn new(point: Vec3, normal: Vec3) -> Self {
        let normal = normal.normalize();
        let (tangent, bitangent) = orthonormal_basis(normal);
        Plane {
            point,
            normal,
            tangent,
            bitangent,
        }
    }

    /// Hit distance in (0, t_max), if any.
    #[inline]
    pub fn intersect_t(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        found(self.nearest(ray.origin, ray.dir, t_max))
    }

    /// [`Plane::intersect_t`] for one ray or one per lane; +∞ where it misses.
    #[inline(always)]
    pub(crate) fn nearest<R: Real>(&self, o: R::V3, d: R::V3, t_max: R) -> R {
        plane_nearest(
            R::V3::splat(self.normal),
            R::V3::splat(self.point),
            o,
            d,
            t_max,
        )
    }

    /// The hit record at `t`, with the point projected onto the plane. The surface
    /// coordinates are world-space distances along two tangents (for checkers in world units).
    pub fn surface_hit(&self, ray: &Ray, t: f32) -> SurfaceHit {
        let (p, u, v) = self.surface_of(ray.origin, ray.dir, t);
        SurfaceHit {
            t,
            p,
            n_geom: self.normal,
            n_shade: self.normal,
            uv: Vec2::new(u, v),
        }
    }

    /// The point at distance `t` along a ray (origin `o`, direction `d`), projected onto
    /// the plane (q − n n·(q − point), q = o + t d), and its distances along the two
    /// tangents from `point`, for one ray or one per lane.
    #[inline(always)]
    pub(crate) fn surface_of<R: Real>(&self, o: R::V3, d: R::V3, t: R) -> (R::V3, R, R) {
        let at = R::V3::splat;
        let (n, point) = (at(self.normal), at(self.point));
        let q = o + d.scale(t);
        let p = q - n.scale(n.dot(q - point));
        let rel = p - point;
        (p, rel.dot(at(self.tangent)), rel.dot(at(self.bitangent)))
    }
}

/// The distance t = n·(q − o) / n·d along each ray to the plane through `q` with normal
/// `n`, +∞ where it is not in (0, t_max) or the ray runs parallel (|n·d| < 10⁻¹²); `None`
/// where that holds for every lane, as the scalar test returns early.
#[inline(always)]
fn plane_distance<R: Real>(n: R::V3, q: R::V3, o: R::V3, d: R::V3, t_max: R) -> Option<R> {
    let denom = n.dot(d);
    let t = n.dot(q - o) / denom;
    let zero = R::splat(0.0);
    let ok = !denom.abs().less(R::splat(1e-12)) & zero.less(t) & t.less(t_max);
    R::any(ok).then(|| R::select(ok, t, R::splat(f32::INFINITY)))
}

/// A sphere as [`sphere_nearest`] reads it: its centre at time 0 and velocity, each as
/// one ray's vector, or broadcast or loaded for the lanes, and its radius.
#[derive(Clone, Debug)]
pub(crate) struct SphereAt<V> {
    pub(crate) center: V,
    pub(crate) velocity: V,
    pub(crate) radius: f32,
}

impl SphereAt<Wide> {
    /// The sphere loaded for `R` (see [`Wide`]).
    #[inline(always)]
    pub(crate) fn load<R: Real>(&self) -> SphereAt<R::V3> {
        SphereAt {
            center: R::V3::wide(&self.center),
            velocity: R::V3::wide(&self.velocity),
            radius: self.radius,
        }
    }
}

/// [`Sphere::nearest`] for the sphere `s`, its vectors as the caller holds them.
#[inline(always)]
pub(crate) fn sphere_nearest<R: Real>(
    s: &SphereAt<R::V3>,
    o: R::V3,
    d: R::V3,
    time: R,
    t_max: R,
) -> R {
    // c + v t, as `Sphere::center_of`.
    let f = o - (s.center + s.velocity.scale(time));
    let b = -f.dot(d);
    let l = f + d.scale(b);
    let r2 = R::splat(s.radius * s.radius);
    let disc = r2 - l.length_squared();
    let (zero, miss) = (R::splat(0.0), R::splat(f32::INFINITY));
    let real = !disc.less(zero);
    if !R::any(real) {
        return miss;
    }
    let c = f.length_squared() - r2;
    let q = b + disc.sqrt().copysign(b);
    let real = real & !q.equal(zero);
    // The roots c/q and q, in order.
    let a = c / q;
    let ordered = a.less(q);
    let (t0, t1) = (R::select(ordered, a, q), R::select(ordered, q, a));
    let near = real & zero.less(t0) & t0.less(t_max);
    let far = real & zero.less(t1) & t1.less(t_max);
    R::select(near, t0, R::select(far, t1, miss))
}

/// A quad as [`quad_nearest`] reads it: its corner, edges, unit normal and w = n / (n·n),
/// each as one ray's vector, or broadcast or loaded for the lanes.
#[derive(Clone, Debug)]
pub(crate) struct QuadAt<V> {
    pub(crate) corner: V,
    pub(crate) edge_u: V,
    pub(crate) edge_v: V,
    pub(crate) normal: V,
    pub(crate) w: V,
}

impl QuadAt<Wide> {
    /// The quad loaded for `R` (see [`Wide`]).
    #[inline(always)]
    pub(crate) fn load<R: Real>(&self) -> QuadAt<R::V3> {
        QuadAt {
            corner: R::V3::wide(&self.corner),
            edge_u: R::V3::wide(&self.edge_u),
            edge_v: R::V3::wide(&self.edge_v),
            normal: R::V3::wide(&self.normal),
            w: R::V3::wide(&self.w),
        }
    }
}

/// [`Quad::intersect_t`] for one ray or one per lane: the distance t to the plane
/// n·(p − corner) = 0, where the point's coordinates a = w·(rel × edge_v) and
/// b = w·(edge_u × rel) (rel = p − corner) are both in [0, 1]; +∞ where it misses.
#[inline(always)]
pub(crate) fn quad_nearest<R: Real>(q: &QuadAt<R::V3>, o: R::V3, d: R::V3, t_max: R) -> R {
    let Some(t) = plane_distance(q.normal, q.corner, o, d, t_max) else {
        return R::splat(f32::INFINITY);
    };
    let rel = (o + d.scale(t)) - q.corner;
    let a = q.w.dot(rel.cross(q.edge_v));
    let b = q.w.dot(q.edge_u.cross(rel));
    let (zero, one) = (R::splat(0.0), R::splat(1.0));
    let inside = zero.less_eq(a) & a.less_eq(one) & zero.less_eq(b) & b.less_eq(one);
    R::select(inside, t, R::splat(f32::INFINITY))
}

/// [`Plane::nearest`] for the plane through `point` with unit normal `normal`, as the
/// caller holds them.
#[inline(always)]
pub(crate) fn plane_nearest<R: Real>(
    normal: R::V3,
    point: R::V3,
    o: R::V3,
    d: R::V3,
    t_max: R,
) -> R {
    plane_distance(normal, point, o, d, t_max).unwrap_or(R::splat(f32::INFINITY))
}

/// A distance from the formulas above as the scalar callers take it: +∞ is no hit (a hit
/// is below t_max, so finite).
#[inline(always)]
fn found(t: f32) -> Option<f32> {
    (t < f32::INFINITY).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hit_records_made_in_lanes_are_each_rays_own_bit_for_bit() {
        use crate::geometry::Shape;
        use crate::math::lanes::{Lanes, RayOf, V3};
        let moving = Sphere {
            velocity: Vec3::new(0.3, 0.0, -0.2),
            ..Sphere::new(Vec3::new(0.1, 0.2, -5.0), 1.3)
        };
        let shapes = [
            Shape::Sphere(moving),
            Shape::Quad(Quad::new(
                Vec3::new(-8.0, -6.0, -9.0),
                Vec3::new(16.0, 0.0, 0.0),
                Vec3::new(0.0, 12.0, 1.0),
            )),
            Shape::Plane(Plane::new(
                Vec3::new(0.0, -1.0, 0.0),
                Vec3::new(0.1, 1.0, 0.05),
            )),
        ];
        // Rays from near the origin towards -z, fanned out, at four times.
        let rays: [Ray; 4] = std::array::from_fn(|i| {
            let f = i as f32;
            let dir = Vec3::new(0.03 * f - 0.05, -0.04 * f - 0.05, -1.0);
            Ray::new(Vec3::new(0.01 * f, -0.02, 0.3), dir, 0.25 * f)
        });
        let row = |f: &dyn Fn(&Ray) -> f32| Lanes::<4>(rays.each_ref().map(f));
        let lanes_of = |time| RayOf {
            origin: V3::from_fn(|i| rays[i].origin),
            dir: V3::from_fn(|i| rays[i].dir),
            time,
        };
        for shape in &shapes {
            let t = row(&|r| shape.intersect_t(0, r, f32::INFINITY).unwrap());
            let lanes = shape
                .surface_lanes(lanes_of(row(&|r| r.time)), t, false)
                .unwrap();
            for (i, ray) in rays.iter().enumerate() {
                let (a, b) = (
                    lanes.get(i, t.0[i]),
                    shape.surface_hit(0, ray, t.0[i], false),
                );
                let bits = |v: Vec3| v.to_array().map(f32::to_bits);
                assert_eq!(bits(a.p), bits(b.p), "{shape:?} ray {i}");
                assert_eq!(bits(a.n_geom), bits(b.n_geom));
                assert_eq!(bits(a.n_shade), bits(b.n_shade));
                assert_eq!(
                    a.uv.to_array().map(f32::to_bits),
                    b.uv.to_array().map(f32::to_bits)
                );
            }
        }
        // A sphere's surface coordinates (atan2, acos) are made ray by ray.
        let t = row(&|r| shapes[0].intersect_t(0, r, f32::INFINITY).unwrap());
        assert!(
            shapes[0]
                .surface_lanes(lanes_of(row(&|r| r.time)), t, true)
                .is_none()
        );
    }

    #[test]
    fn sphere_hit_distances() {
        let s = Sphere::new(Vec3::new(0.0, 0.0, -5.0), 1.0);
        let ray = Ray::new(Vec3::ZERO, -Vec3::Z, 0.0);
        assert!((s.intersect_t(&ray, f32::INFINITY).unwrap() - 4.0).abs() < 1e-6);
        // From inside: the far side.
        let inside = Ray::new(Vec3::new(0.0, 0.0, -5.0), Vec3::X, 0.0);
        assert!((s.intersect_t(&inside, f32::INFINITY).unwrap() - 1.0).abs() < 1e-6);
        // Behind, beside, and beyond t_max.
        assert!(
            s.intersect_t(&Ray::new(Vec3::ZERO, Vec3::Z, 0.0), f32::INFINITY)
                .is_none()
        );
        assert!(
            s.intersect_t(
                &Ray::new(Vec3::new(1.01, 0.0, 0.0), -Vec3::Z, 0.0),
                f32::INFINITY
            )
            .is_none()
        );
        assert!(s.intersect_t(&ray, 3.9).is_none());
        let hit = s.surface_hit(&ray, 4.0, true);
        assert!((hit.p - Vec3::new(0.0, 0.0, -4.0)).length() < 1e-6);
        assert!((hit.n_geom - Vec3::Z).length() < 1e-6);
    }

    #[test]
    fn tiny_far_sphere_is_hit_exactly() {
        // The naive quadratic loses this to cancellation.
        let s = Sphere::new(Vec3::new(0.0, 0.0, -10000.0), 0.01);
        let ray = Ray::new(Vec3::new(0.005, 0.0, 0.0), -Vec3::Z, 0.0);
        let t = s.intersect_t(&ray, f32::INFINITY).unwrap();
        let expected = 10000.0 - (0.01f32 * 0.01 - 0.005 * 0.005).sqrt();
        assert!((t - expected).abs() < 2e-3, "t = {t}, expected {expected}");
    }

    #[test]
    fn a_moving_sphere_is_where_its_time_says() {
        let s = Sphere {
            velocity: Vec3::new(2.0, 0.0, 0.0),
            ..Sphere::new(Vec3::new(0.0, 0.0, -5.0), 0.5)
        };
        let at = |x: f32, time: f32| {
            s.intersect_t(
                &Ray::new(Vec3::new(x, 0.0, 0.0), -Vec3::Z, time),
                f32::INFINITY,
            )
        };
        assert!(at(0.0, 0.0).is_some() && at(2.0, 0.0).is_none());
        assert!(at(0.0, 1.0).is_none() && at(2.0, 1.0).is_some());
        assert!(at(1.0, 0.5).is_some());
        let b = s.bounds();
        assert!(b.min.x <= -0.5 && b.max.x >= 2.5);
    }

    #[test]
    fn quad_hits_inside_and_misses_outside() {
        let q = Quad::new(
            Vec3::new(-1.0, -1.0, -3.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
        );
        let hit = q.intersect_t(
            &Ray::new(Vec3::new(0.5, 0.5, 0.0), -Vec3::Z, 0.0),
            f32::INFINITY,
        );
        let t = hit.unwrap();
        assert!((t - 3.0).abs() < 1e-6);
        let uv = q
            .surface_hit(&Ray::new(Vec3::new(0.5, 0.5, 0.0), -Vec3::Z, 0.0), t)
            .uv;
        assert!((uv - Vec2::new(0.75, 0.75)).length() < 1e-6);
        assert!(
            q.intersect_t(
                &Ray::new(Vec3::new(1.5, 0.0, 0.0), -Vec3::Z, 0.0),
                f32::INFINITY
            )
            .is_none()
        );
        assert!((q.normal() - Vec3::Z).length() < 1e-6);
    }

    #[test]
    fn plane_hit_and_parallel_miss() {
        let p = Plane::new(Vec3::ZERO, Vec3::Y);
        let ray = Ray::new(Vec3::new(0.0, 2.0, 0.0), Vec3::new(0.0, -1.0, 1.0), 0.0);
        let t = p.intersect_t(&ray, f32::INFINITY).unwrap();
        let hit = p.surface_hit(&ray, t);
        assert_eq!(hit.p.y, 0.0);
        assert!((hit.p.z - 2.0).abs() < 1e-5);
        assert!(
            p.intersect_t(&Ray::new(Vec3::Y, Vec3::X, 0.0), f32::INFINITY)
                .is_none()
        );
    }
}
