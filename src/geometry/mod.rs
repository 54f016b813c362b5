//! Shapes, their ray intersections, and the BVH over them.
//!
//! Every intersection routine returns the hit point *refined* from the surface's own
//! description (reprojected onto the sphere, rebuilt from barycentrics, projected onto the
//! plane) rather than `origin + t * dir`: its error is then a few ulps of the point, which
//! [`crate::math::offset_ray_origin`] is sized for.

mod accel;
mod mesh;
mod shapes;

pub use accel::{Accel, PrimRef};
pub use mesh::Mesh;
pub use shapes::{Plane, Quad, Sphere};

use crate::math::{Ray, Vec3};
use glam::Vec2;

/// Where a ray meets a surface.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceHit {
    /// Distance along the ray.
    pub t: f32,
    /// The refined hit point.
    pub p: Vec3,
    /// Unit geometric normal, facing the surface's outside (for a closed shape) or its
    /// winding side.
    pub n_geom: Vec3,
    /// Unit shading normal (interpolated vertex normals on meshes), in the same hemisphere
    /// as `n_geom`.
    pub n_shade: Vec3,
    /// Surface coordinates, for textures.
    pub uv: Vec2,
}

/// The geometry of one scene object.
#[derive(Clone, Debug)]
pub enum Shape {
    /// A sphere.
    Sphere(Sphere),
    /// A parallelogram.
    Quad(Quad),
    /// An infinite plane (kept outside the BVH: it has no bounds).
    Plane(Plane),
    /// A triangle mesh.
    Mesh(Mesh),
}

impl Shape {
    /// How many BVH primitives this shape contributes (0 for an unbounded plane).
    pub fn primitive_count(&self) -> usize {
        match self {
            Shape::Sphere(_) | Shape::Quad(_) => 1,
            Shape::Plane(_) => 0,
            Shape::Mesh(m) => m.triangle_count(),
        }
    }

    /// The bounds of primitive `index` of this shape.
    pub fn primitive_bounds(&self, index: u32) -> obvhs::aabb::Aabb {
        match self {
            Shape::Sphere(s) => s.bounds(),
            Shape::Quad(q) => q.bounds(),
            Shape::Plane(_) => obvhs::aabb::Aabb::INFINITY,
            Shape::Mesh(m) => m.triangle_bounds(index as usize),
        }
    }

    /// The distance to primitive `index` along `ray`, if it is hit in (0, t_max).
    #[inline]
    pub fn intersect_t(&self, index: u32, ray: &Ray, t_max: f32) -> Option<f32> {
        match self {
            Shape::Sphere(s) => s.intersect_t(ray, t_max),
            Shape::Quad(q) => q.intersect_t(ray, t_max).map(|(t, _)| t),
            Shape::Plane(p) => p.intersect_t(ray, t_max),
            Shape::Mesh(m) => m.intersect_t(index as usize, ray, t_max).map(|(t, _)| t),
        }
    }

    /// The full hit record of primitive `index` at distance `t` along `ray`; surface
    /// coordinates only `with_uv` where they cost extra (spheres), else zero.
    pub fn surface_hit(&self, index: u32, ray: &Ray, t: f32, with_uv: bool) -> SurfaceHit {
        match self {
            Shape::Sphere(s) => s.surface_hit(ray, t, with_uv),
            Shape::Quad(q) => q.surface_hit(ray, t),
            Shape::Plane(p) => p.surface_hit(ray, t),
            Shape::Mesh(m) => m.surface_hit(index as usize, ray, t),
        }
    }
}
