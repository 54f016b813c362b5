//! Shapes, their ray intersections, and the BVH over them.
//!
//! Every intersection routine returns the hit point *refined* from the surface's own
//! description (reprojected onto the sphere, rebuilt from barycentrics, projected onto the
//! plane) rather than `origin + t * dir`: its error is then a few ulps of the point, which
//! [`crate::math::offset_ray_origin`] is sized for.

mod accel;
mod direct;
mod instance;
mod mesh;
mod shapes;
mod wide_bvh;

pub use accel::Accel;
pub(crate) use accel::KeyHasher;
pub(crate) use direct::SMALL_MESH;
pub use instance::{Instance, SharedMesh};
pub use mesh::{Mesh, MeshError};
pub use shapes::{Plane, Quad, Sphere};

use crate::math::lanes::{Lanes, RayOf, Real, V3, Vector};
use crate::math::{Ray, Vec3};
use glam::Vec2;

/// One primitive: primitive `index` (a triangle, or 0) of scene object `object`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PrimRef {
    /// Index of the object in the scene's list.
    pub object: u32,
    /// Index of the primitive within the object's shape.
    pub index: u32,
}

/// How far from the origin geometry may reach, in scene units, on any axis and at any time
/// of the frame. Beyond it an f32 hit point keeps too few digits to offset a ray off its
/// surface, and far beyond it (about 5e18) the BVH builder's arithmetic overflows. Scene
/// files are checked against it before anything is built.
pub const MAX_COORDINATE: f32 = 1e6;

/// Whether `v` lies within ±[`MAX_COORDINATE`] on every axis (false for NaN).
pub fn within_limits(v: Vec3) -> bool {
    // Compared per axis: `max_element` would pass over a NaN.
    v.abs().cmple(Vec3::splat(MAX_COORDINATE)).all()
}

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
    /// A placement of a mesh shared with other placements: one leaf of the scene's BVH,
    /// over the mesh's own BVH.
    Instance(Instance),
}

/// The hit records of `N` rays on one analytic shape, column by column: points, unit
/// normals (geometric and shading alike) and surface coordinates (u, v).
#[derive(Clone, Copy)]
pub(crate) struct SurfaceLanes<const N: usize> {
    pub(crate) p: V3<Lanes<N>>,
    pub(crate) n: V3<Lanes<N>>,
    pub(crate) uv: (Lanes<N>, Lanes<N>),
}

/// How a ray meets a surface, for one ray or one per lane: whether it arrives against the
/// geometric normal (from the outside), and both normals turned to face it. Both walks
/// ask this.
pub(crate) struct Facing<R: Real> {
    pub(crate) entering: R::Mask,
    pub(crate) n_geom: R::V3,
    pub(crate) n_shade: R::V3,
}

impl<R: Real> Facing<R> {
    /// A ray along `dir` at a surface of geometric normal `n_geom` and shading normal
    /// `n_shade`.
    #[inline(always)]
    pub(crate) fn of(dir: R::V3, n_geom: R::V3, n_shade: R::V3) -> Self {
        let entering = dir.dot(n_geom).less(R::splat(0.0));
        let facing = |n: R::V3| R::V3::select(entering, n, n.neg());
        Facing {
            entering,
            n_geom: facing(n_geom),
            n_shade: facing(n_shade),
        }
    }
}

impl<const N: usize> SurfaceLanes<N> {
    /// Lane `i`'s record, at distance `t`.
    #[inline(always)]
    pub(crate) fn get(&self, i: usize, t: f32) -> SurfaceHit {
        SurfaceHit {
            t,
            p: self.p.get(i),
            n_geom: self.n.get(i),
            n_shade: self.n.get(i),
            uv: Vec2::new(self.uv.0.0[i], self.uv.1.0[i]),
        }
    }
}

impl Shape {
    /// How many primitives this shape has: its triangles, or 1 for a sphere or quad (0 for
    /// an unbounded plane). Emitters are sampled primitive by primitive.
    pub fn primitive_count(&self) -> usize {
        match self {
            Shape::Sphere(_) | Shape::Quad(_) => 1,
            Shape::Plane(_) => 0,
            Shape::Mesh(m) => m.triangle_count(),
            Shape::Instance(i) => i.triangle_count(),
        }
    }

    /// The bounds of primitive `index` of this shape over the whole frame.
    pub fn primitive_bounds(&self, index: u32) -> obvhs::aabb::Aabb {
        match self {
            Shape::Sphere(s) => s.bounds(),
            Shape::Quad(q) => q.bounds(),
            Shape::Plane(_) => obvhs::aabb::Aabb::INFINITY,
            Shape::Mesh(m) => m.triangle_bounds(index as usize),
            Shape::Instance(i) => i.triangle_bounds(index as usize),
        }
    }

    /// How many leaves this shape puts in the scene's BVH: one per primitive, but one for
    /// a whole instance, which has a BVH of its own.
    fn leaf_count(&self) -> usize {
        match self {
            Shape::Instance(_) => 1,
            _ => self.primitive_count(),
        }
    }

    /// The bounds of leaf `leaf` of this shape over the whole frame.
    fn leaf_bounds(&self, leaf: u32) -> obvhs::aabb::Aabb {
        match self {
            Shape::Instance(i) => i.bounds(),
            _ => self.primitive_bounds(leaf),
        }
    }

    /// The primitives under leaf `leaf`.
    fn leaf_primitives(&self, leaf: u32) -> std::ops::Range<u32> {
        match self {
            Shape::Instance(i) => 0..i.triangle_count() as u32,
            _ => leaf..leaf + 1,
        }
    }

    /// Whether the whole shape, over the whole frame, lies within ±[`MAX_COORDINATE`] (a
    /// plane: its anchor point).
    pub fn within_limits(&self) -> bool {
        let inside = |b: obvhs::aabb::Aabb| within_limits(b.min) && within_limits(b.max);
        match self {
            Shape::Sphere(s) => inside(s.bounds()),
            Shape::Quad(q) => inside(q.bounds()),
            Shape::Plane(p) => within_limits(p.point),
            Shape::Mesh(m) => (0..m.triangle_count()).all(|i| inside(m.triangle_bounds(i))),
            Shape::Instance(i) => i.within_limits(),
        }
    }

    /// The distance to primitive `index` along `ray`, if it is hit in (0, t_max).
    #[inline]
    pub fn intersect_t(&self, index: u32, ray: &Ray, t_max: f32) -> Option<f32> {
        match self {
            Shape::Sphere(s) => s.intersect_t(ray, t_max),
            Shape::Quad(q) => q.intersect_t(ray, t_max),
            Shape::Plane(p) => p.intersect_t(ray, t_max),
            Shape::Mesh(m) => m.intersect_t(index as usize, ray, t_max).map(|(t, _)| t),
            Shape::Instance(i) => i.intersect_triangle(index as usize, ray, t_max),
        }
    }

    /// The nearest primitive under leaf `leaf` that `ray` hits in (0, t_max), and the
    /// distance.
    #[inline(always)]
    fn intersect_leaf(&self, leaf: u32, ray: &Ray, t_max: f32) -> Option<(u32, f32)> {
        match self {
            Shape::Instance(i) => i.intersect(ray, t_max),
            _ => self.intersect_t(leaf, ray, t_max).map(|t| (leaf, t)),
        }
    }

    /// Whether a primitive under leaf `leaf` blocks `ray` in (0, t_max).
    #[inline(always)]
    fn leaf_blocks(&self, leaf: u32, ray: &Ray, t_max: f32) -> bool {
        match self {
            Shape::Instance(i) => i.occluded(ray, t_max),
            _ => self.intersect_t(leaf, ray, t_max).is_some(),
        }
    }

    /// The surface area of primitive `index` (infinite for a plane).
    pub fn primitive_area(&self, index: u32) -> f32 {
        match self {
            Shape::Sphere(s) => 4.0 * std::f32::consts::PI * s.radius * s.radius,
            Shape::Quad(q) => q.edge_u.cross(q.edge_v).length(),
            Shape::Plane(_) => f32::INFINITY,
            Shape::Mesh(m) => m.triangle_area(index as usize),
            Shape::Instance(i) => i.triangle_area(index as usize),
        }
    }

    /// A point uniform over the area of primitive `index` at frame time `time`, from the
    /// uniform pair `u`; `None` for a plane, which has no finite area.
    pub fn sample_point(&self, index: u32, u: Vec2, time: f32) -> Option<Vec3> {
        match self {
            Shape::Sphere(s) => {
                // z uniform in [−1, 1] is uniform in area (Archimedes).
                let z = 1.0 - 2.0 * u.x;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let phi = 2.0 * std::f32::consts::PI * u.y;
                Some(s.center_at(time) + s.radius * Vec3::new(r * phi.cos(), r * phi.sin(), z))
            }
            Shape::Quad(q) => Some(q.corner + u.x * q.edge_u + u.y * q.edge_v),
            Shape::Plane(_) => None,
            Shape::Mesh(m) => Some(m.sample_point(index as usize, u, time)),
            Shape::Instance(i) => Some(i.sample_point(index as usize, u, time)),
        }
    }

    /// The hit records of `N` rays that all met this shape, at distances `t`, computed in
    /// lanes (the rays given coordinate by coordinate: origins `o`, directions `d`, times):
    /// lane i of each column is [`Shape::surface_hit`]'s of ray i bit for bit. `None` where
    /// the record is made ray by ray: a mesh (each lane its own triangle), a sphere
    /// `with_uv`.
    #[inline(always)]
    pub(crate) fn surface_lanes<const N: usize>(
        &self,
        rays: RayOf<Lanes<N>>,
        t: Lanes<N>,
        with_uv: bool,
    ) -> Option<SurfaceLanes<N>> {
        let (o, d) = (rays.origin, rays.dir);
        let zero = Lanes::splat(0.0);
        Some(match self {
            Shape::Sphere(s) if !with_uv => {
                let (p, n) = s.surface_of(o, d, rays.time, t);
                SurfaceLanes {
                    p,
                    n,
                    uv: (zero, zero),
                }
            }
            Shape::Quad(q) => {
                let (p, a, b) = q.surface_of(o, d, t);
                SurfaceLanes {
                    p,
                    n: V3::splat(q.normal()),
                    uv: (a, b),
                }
            }
            Shape::Plane(plane) => {
                let (p, u, v) = plane.surface_of(o, d, t);
                SurfaceLanes {
                    p,
                    n: V3::splat(plane.normal),
                    uv: (u, v),
                }
            }
            Shape::Sphere(_) | Shape::Mesh(_) | Shape::Instance(_) => return None,
        })
    }

    /// The full hit record of primitive `index` at distance `t` along `ray`; surface
    /// coordinates only `with_uv` where they cost extra (spheres), else zero.
    pub fn surface_hit(&self, index: u32, ray: &Ray, t: f32, with_uv: bool) -> SurfaceHit {
        match self {
            Shape::Sphere(s) => s.surface_hit(ray, t, with_uv),
            Shape::Quad(q) => q.surface_hit(ray, t),
            Shape::Plane(p) => p.surface_hit(ray, t),
            Shape::Mesh(m) => m.surface_hit(index as usize, ray, t),
            Shape::Instance(i) => i.surface_hit(index as usize, ray, t),
        }
    }
}
