//! The BVH over every bounded primitive of a scene, plus the unbounded planes beside it.
//!
//! The tree is obvhs's compressed wide BVH (8 children a node), built with PLOC and
//! reinsertion: a SAH-quality tree that builds a million triangles in well under a second.

use super::{Plane, Quad, Shape, Sphere};
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
    // The shapes tested one by one, copied out beside their object numbers: a tight loop
    // per kind, with no lookup in the scene's list and no match on the kind of shape.
    direct: Direct,
}

/// The spheres and quads tested directly (when there are at most DIRECT_MAX), and the planes.
#[derive(Clone, Debug, Default)]
struct Direct {
    spheres: Vec<(u32, Sphere)>,
    quads: Vec<(u32, Quad)>,
    planes: Vec<(u32, Plane)>,
}

impl Direct {
    /// The nearest hit in (0, t_max), and its distance.
    #[inline]
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<(PrimRef, f32)> {
        let mut best: Option<(u32, f32)> = None;
        let limit = |best: Option<(u32, f32)>| best.map_or(t_max, |(_, t)| t);
        for (o, p) in &self.planes {
            best = p.intersect_t(ray, limit(best)).map(|t| (*o, t)).or(best);
        }
        for (o, s) in &self.spheres {
            best = s.intersect_t(ray, limit(best)).map(|t| (*o, t)).or(best);
        }
        for (o, q) in &self.quads {
            best = q
                .intersect_t(ray, limit(best))
                .map(|(t, _)| (*o, t))
                .or(best);
        }
        best.map(|(object, t)| (PrimRef { object, index: 0 }, t))
    }

    /// Whether any of them blocks `ray` in (0, t_max).
    #[inline]
    fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.planes
            .iter()
            .any(|(_, p)| p.intersect_t(ray, t_max).is_some())
            || self
                .spheres
                .iter()
                .any(|(_, s)| s.intersect_t(ray, t_max).is_some())
            || self
                .quads
                .iter()
                .any(|(_, q)| q.intersect_t(ray, t_max).is_some())
    }
}

impl Accel {
    /// Builds the BVH over `shapes` (the scene's objects, in order). Every shape must be
    /// [`Shape::within_limits`]: the builder panics on bounds near 5e18.
    pub fn build(shapes: &[Shape]) -> Self {
        let mut prims = Vec::new();
        let mut bounds: Vec<Aabb> = Vec::new();
        let analytic = |s: &Shape| matches!(s, Shape::Sphere(_) | Shape::Quad(_));
        let direct_ok = shapes.iter().filter(|s| analytic(s)).count() <= DIRECT_MAX;
        let mut direct = Direct::default();
        for (object, shape) in shapes.iter().enumerate() {
            let object = object as u32;
            match shape {
                Shape::Plane(p) => direct.planes.push((object, p.clone())),
                Shape::Sphere(s) if direct_ok => direct.spheres.push((object, s.clone())),
                Shape::Quad(q) if direct_ok => direct.quads.push((object, q.clone())),
                _ => {
                    for index in 0..shape.primitive_count() as u32 {
                        prims.push(PrimRef { object, index });
                        bounds.push(shape.primitive_bounds(index));
                    }
                }
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
        Accel { bvh, prims, direct }
    }

    /// Number of bounded primitives (in the BVH or tested directly).
    pub fn primitive_count(&self) -> usize {
        self.prims.len() + self.direct.spheres.len() + self.direct.quads.len()
    }

    /// The nearest primitive hit by `ray` in (0, t_max), and its distance.
    #[inline]
    pub fn intersect(&self, shapes: &[Shape], ray: &Ray, t_max: f32) -> Option<(PrimRef, f32)> {
        let mut best = self.direct.intersect(ray, t_max);
        let t_best = best.map_or(t_max, |(_, t)| t);
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
        if self.direct.occluded(ray, t_max) {
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
        // The directly tested shapes first, then every BVH primitive one by one.
        let mut best = self.direct.intersect(ray, t_max);
        let mut t_best = best.map_or(t_max, |(_, t)| t);
        let all = self.prims.iter().copied();
        for p in all {
            if let Some(t) = shapes[p.object as usize].intersect_t(p.index, ray, t_best) {
                t_best = t;
                best = Some((p, t));
            }
        }
        best
    }
}
