//! Instances: one triangle mesh with its own BVH, built once and placed many times.
//!
//! This is the lower level of a two-level BVH. The scene's tree holds each placement as
//! one box; a ray that reaches it is carried into the mesh's own frame,
//! o' = M⁻¹(o − v t) and d' = M⁻¹d (not renormalised, so a distance t along the one ray
//! is the same point as along the other), and traced through the mesh's tree. Only the
//! transform is stored per placement, so a model placed ten times costs its triangles
//! and its tree once.

use super::accel::build_tree;
use super::wide_bvh::{Stack, WideBvh};
use super::{Mesh, MeshError, SurfaceHit};
use crate::math::{Ray, Vec3};
use glam::{Affine3A, Mat3A, Vec2};
use obvhs::aabb::Aabb;
use std::sync::Arc;

/// A mesh in its own frame and the BVH over its triangles, shared by its placements.
#[derive(Debug)]
pub struct SharedMesh {
    mesh: Mesh,
    bvh: WideBvh,
    // The BVH's leaf order: leaf k is triangle `triangles[k]`.
    triangles: Vec<u32>,
}

impl SharedMesh {
    /// Builds the BVH over `mesh`'s triangles (which must lie within
    /// ±[`MAX_COORDINATE`](super::MAX_COORDINATE): the builder panics on bounds near 5e18). The mesh's own
    /// velocity is ignored: a placement says how it moves.
    pub fn new(mut mesh: Mesh) -> Arc<SharedMesh> {
        mesh.velocity = Vec3::ZERO;
        let mut bounds: Vec<Aabb> = (0..mesh.triangle_count())
            .map(|i| mesh.triangle_bounds(i))
            .collect();
        let (bvh, triangles) = build_tree(&mut bounds);
        Arc::new(SharedMesh {
            mesh,
            bvh,
            triangles,
        })
    }

    /// The mesh, in its own frame.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// The nearest triangle `ray` (in the mesh's frame) hits in (0, t_max), and where.
    #[inline]
    fn nearest(&self, ray: &Ray, t_max: f32) -> Option<(u32, f32)> {
        let found = self
            .bvh
            .nearest(&mut Stack::new(), ray.origin, ray.dir, t_max, |slot, t| {
                let triangle = self.triangles[slot as usize] as usize;
                self.mesh
                    .intersect_t(triangle, ray, t)
                    .map_or(f32::INFINITY, |(t, _)| t)
            });
        found.map(|(slot, t)| (self.triangles[slot as usize], t))
    }

    /// Whether any triangle blocks `ray` (in the mesh's frame) in (0, t_max).
    #[inline]
    fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.bvh
            .any(&mut Stack::new(), ray.origin, ray.dir, t_max, |slot, t| {
                let triangle = self.triangles[slot as usize] as usize;
                self.mesh.intersect_t(triangle, ray, t).is_some()
            })
    }
}

/// One placement of a [`SharedMesh`]: the transform `M` from the mesh's frame to the
/// scene's, and a displacement `velocity` over the frame, as a [`Mesh`] moves.
#[derive(Clone, Debug)]
pub struct Instance {
    shared: Arc<SharedMesh>,
    to_scene: Affine3A,
    to_mesh: Affine3A,
    // (M⁻¹)ᵀ, which carries normals: a normal n' = (M⁻¹)ᵀ n stays perpendicular to the
    // transformed surface.
    normal_matrix: Mat3A,
    smooth: bool,
    velocity: Vec3,
    // Over the whole frame, from the transformed vertices (tighter than a turned box).
    bounds: Aabb,
}

impl Instance {
    /// `shared` placed by `transform`, moving by `velocity` over the frame; with `smooth`
    /// false its vertex normals are ignored, for flat shading. The transform must keep
    /// orientation (determinant > 0), as a scene's rotation and positive scale do.
    pub fn new(
        shared: Arc<SharedMesh>,
        transform: Affine3A,
        smooth: bool,
        velocity: Vec3,
    ) -> Result<Instance, MeshError> {
        let det = transform.matrix3.determinant();
        let to_mesh = transform.inverse();
        if !(det > 0.0 && det.is_finite() && to_mesh.is_finite()) {
            return Err(MeshError::Transform);
        }
        let mut bounds = Aabb::INVALID;
        for &p in shared.mesh.positions() {
            let q = transform.transform_point3a(p);
            if !q.is_finite() {
                return Err(MeshError::Transform);
            }
            bounds.extend(q);
        }
        let moved = Aabb::new(bounds.min + velocity, bounds.max + velocity);
        Ok(Instance {
            normal_matrix: to_mesh.matrix3.transpose(),
            to_scene: transform,
            to_mesh,
            shared,
            smooth,
            velocity,
            bounds: bounds.union(&moved),
        })
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.shared.mesh.triangle_count()
    }

    /// The bounds of every triangle over the whole frame.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Whether the placement, over the whole frame, lies within ±[`MAX_COORDINATE`](super::MAX_COORDINATE).
    pub fn within_limits(&self) -> bool {
        super::within_limits(self.bounds.min) && super::within_limits(self.bounds.max)
    }

    /// Triangle `i`'s corners in the scene at time 0.
    fn corners(&self, i: usize) -> [Vec3; 3] {
        let [v0, e1, e2] = self.shared.mesh.edges()[i];
        let p0 = self.to_scene.transform_point3a(v0);
        let m = self.to_scene.matrix3;
        [p0, p0 + m * e1, p0 + m * e2]
    }

    /// Bounds of triangle `i` over the whole frame.
    pub fn triangle_bounds(&self, i: usize) -> Aabb {
        let [a, b, c] = self.corners(i);
        let v = self.velocity;
        Aabb::from_points(&[a, b, c, a + v, b + v, c + v])
    }

    /// The area of triangle `i` in the scene.
    pub fn triangle_area(&self, i: usize) -> f32 {
        let [a, b, c] = self.corners(i);
        0.5 * (b - a).cross(c - a).length()
    }

    /// A point uniform over triangle `i` in the scene at frame time `time`: an affine map
    /// scales every area of one triangle alike, so a point uniform over the mesh's
    /// triangle maps to one uniform over the placed triangle.
    pub fn sample_point(&self, i: usize, u: Vec2, time: f32) -> Vec3 {
        let local = self.shared.mesh.sample_point(i, u, 0.0);
        self.to_scene.transform_point3a(local) + self.velocity * time
    }

    /// `ray` in the mesh's frame: o' = M⁻¹(o − v t), d' = M⁻¹d.
    #[inline]
    fn local(&self, ray: &Ray) -> Ray {
        Ray {
            origin: self
                .to_mesh
                .transform_point3a(ray.origin - self.velocity * ray.time),
            dir: self.to_mesh.transform_vector3a(ray.dir),
            time: ray.time,
        }
    }

    /// The nearest triangle `ray` hits in (0, t_max), and the distance.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<(u32, f32)> {
        self.shared.nearest(&self.local(ray), t_max)
    }

    /// The distance to triangle `i` along `ray`, if it is hit in (0, t_max).
    pub fn intersect_triangle(&self, i: usize, ray: &Ray, t_max: f32) -> Option<f32> {
        let local = self.local(ray);
        self.shared
            .mesh
            .intersect_t(i, &local, t_max)
            .map(|(t, _)| t)
    }

    /// Whether any triangle blocks `ray` in (0, t_max).
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.shared.occluded(&self.local(ray), t_max)
    }

    /// The hit record of triangle `i` at `t`: made in the mesh's frame, then carried into
    /// the scene's (the point by M, the normals by (M⁻¹)ᵀ).
    pub fn surface_hit(&self, i: usize, ray: &Ray, t: f32) -> SurfaceHit {
        let local = self
            .shared
            .mesh
            .surface_hit_shaded(i, &self.local(ray), t, self.smooth);
        let normal = |n: Vec3| (self.normal_matrix * n).normalize_or_zero();
        let n_shade = normal(local.n_shade);
        let mut n_geom = normal(local.n_geom);
        if n_geom.dot(n_shade) < 0.0 {
            n_geom = -n_geom;
        }
        SurfaceHit {
            t,
            p: self.to_scene.transform_point3a(local.p) + self.velocity * ray.time,
            n_geom,
            n_shade,
            uv: local.uv,
        }
    }

    /// Triangle `i`'s corners in the scene at frame time `time`.
    pub fn corners_at(&self, i: usize, time: f32) -> [Vec3; 3] {
        self.corners(i).map(|p| p + self.velocity * time)
    }
}
