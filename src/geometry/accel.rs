//! The BVH over every bounded primitive of a scene, plus the unbounded planes beside it.
//!
//! The tree is obvhs's compressed wide BVH (8 children a node), built with PLOC and
//! reinsertion: a SAH-quality tree that builds a million triangles in well under a second.

use super::Shape;
use crate::math::Ray;
use obvhs::{BvhBuildParams, aabb::Aabb, cwbvh::CwBvh, cwbvh::builder::build_cwbvh};
use std::time::Duration;

/// The direction with every −0.0 turned into +0.0 (x + 0.0 does that in IEEE arithmetic).
///
/// obvhs 0.4 picks a node's traversal octant from `dir < 0` but inverts the direction with
/// `signum`, which disagree on −0.0: a ray along −z built as `-Vec3::Z` then misses
/// everything.
#[inline]
fn positive_zeros(dir: crate::math::Vec3) -> crate::math::Vec3 {
    dir + crate::math::Vec3::ZERO
}

/// One primitive: primitive `index` (a triangle, or 0) of scene object `object`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PrimRef {
    /// Index of the object in the scene's list.
    pub object: u32,
    /// Index of the primitive within the object's shape.
    pub index: u32,
}

/// Up to this many spheres and quads are tested one by one, outside the BVH: for a handful
/// of them a loop beats descending a tree built for millions of triangles.
const DIRECT_MAX: usize = 16;

/// Acceleration structure over a list of shapes: the BVH over triangles (and over spheres
/// and quads when there are many), the few spheres and quads tested directly, and the
/// unbounded planes.
#[derive(Clone, Debug)]
pub struct Accel {
    bvh: Option<CwBvh>,
    // In the BVH's leaf order, so a leaf's primitive id indexes this directly.
    prims: Vec<PrimRef>,
    // Spheres and quads tested directly (when there are at most DIRECT_MAX).
    direct: Vec<PrimRef>,
    unbounded: Vec<u32>,
}

impl Accel {
    /// Builds the BVH over `shapes` (the scene's objects, in order).
    pub fn build(shapes: &[Shape]) -> Self {
        let mut prims = Vec::new();
        let mut bounds: Vec<Aabb> = Vec::new();
        let mut unbounded = Vec::new();
        let analytic = |s: &Shape| matches!(s, Shape::Sphere(_) | Shape::Quad(_));
        let direct_ok = shapes.iter().filter(|s| analytic(s)).count() <= DIRECT_MAX;
        let mut direct = Vec::new();
        for (object, shape) in shapes.iter().enumerate() {
            if matches!(shape, Shape::Plane(_)) {
                unbounded.push(object as u32);
                continue;
            }
            if direct_ok && analytic(shape) {
                direct.push(PrimRef {
                    object: object as u32,
                    index: 0,
                });
                continue;
            }
            for index in 0..shape.primitive_count() as u32 {
                prims.push(PrimRef {
                    object: object as u32,
                    index,
                });
                bounds.push(shape.primitive_bounds(index));
            }
        }
        let bvh = (!prims.is_empty()).then(|| {
            build_cwbvh(
                &bounds,
                BvhBuildParams::medium_build(),
                &mut Duration::default(),
            )
        });
        if let Some(bvh) = &bvh {
            prims = bvh
                .primitive_indices
                .iter()
                .map(|&i| prims[i as usize])
                .collect();
        }
        Accel {
            bvh,
            prims,
            direct,
            unbounded,
        }
    }

    /// Number of bounded primitives (in the BVH or tested directly).
    pub fn primitive_count(&self) -> usize {
        self.prims.len() + self.direct.len()
    }

    /// The nearest primitive hit by `ray` in (0, t_max), and its distance.
    #[inline]
    pub fn intersect(&self, shapes: &[Shape], ray: &Ray, t_max: f32) -> Option<(PrimRef, f32)> {
        let mut best: Option<(PrimRef, f32)> = None;
        let mut t_best = t_max;
        for &object in &self.unbounded {
            if let Some(t) = shapes[object as usize].intersect_t(0, ray, t_best) {
                t_best = t;
                best = Some((PrimRef { object, index: 0 }, t));
            }
        }
        for &p in &self.direct {
            if let Some(t) = shapes[p.object as usize].intersect_t(p.index, ray, t_best) {
                t_best = t;
                best = Some((p, t));
            }
        }
        let Some(bvh) = &self.bvh else {
            return best;
        };
        let obv_ray = obvhs::ray::Ray::new(ray.origin, positive_zeros(ray.dir), 0.0, t_best);
        let mut hit = obvhs::ray::RayHit::none();
        let found = bvh.ray_traverse(obv_ray, &mut hit, |r, id| {
            let p = self.prims[id];
            shapes[p.object as usize]
                .intersect_t(p.index, ray, r.tmax)
                .unwrap_or(f32::INFINITY)
        });
        if found {
            best = Some((self.prims[hit.primitive_id as usize], hit.t));
        }
        best
    }

    /// Whether anything blocks `ray` in (0, t_max): the shadow-ray query, which stops at
    /// the first blocker found.
    #[inline]
    pub fn occluded(&self, shapes: &[Shape], ray: &Ray, t_max: f32) -> bool {
        if self
            .unbounded
            .iter()
            .any(|&o| shapes[o as usize].intersect_t(0, ray, t_max).is_some())
            || self.direct.iter().any(|p| {
                shapes[p.object as usize]
                    .intersect_t(p.index, ray, t_max)
                    .is_some()
            })
        {
            return true;
        }
        match &self.bvh {
            Some(bvh) => {
                let obv_ray = obvhs::ray::Ray::new(ray.origin, positive_zeros(ray.dir), 0.0, t_max);
                !bvh.ray_traverse_miss(obv_ray, |r, id| {
                    let p = self.prims[id];
                    shapes[p.object as usize]
                        .intersect_t(p.index, ray, r.tmax)
                        .unwrap_or(f32::INFINITY)
                })
            }
            None => false,
        }
    }

    /// The nearest hit by testing every primitive: the reference the BVH is tested against.
    pub fn intersect_brute_force(
        &self,
        shapes: &[Shape],
        ray: &Ray,
        t_max: f32,
    ) -> Option<(PrimRef, f32)> {
        let mut best: Option<(PrimRef, f32)> = None;
        let mut t_best = t_max;
        let all = self.prims.iter().chain(&self.direct).copied().chain(
            self.unbounded
                .iter()
                .map(|&object| PrimRef { object, index: 0 }),
        );
        for p in all {
            if let Some(t) = shapes[p.object as usize].intersect_t(p.index, ray, t_best) {
                t_best = t;
                best = Some((p, t));
            }
        }
        best
    }
}
