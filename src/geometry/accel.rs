//! The BVH over every bounded primitive of a scene, plus the unbounded planes beside it.
//!
//! The tree is obvhs's compressed wide BVH (8 children a node), built with PLOC and
//! reinsertion: a SAH-quality tree that builds a million triangles in well under a second.

use super::{Plane, Quad, Shape, Sphere};
use crate::math::Ray;
use crate::math::rng::mix64;
use obvhs::{BvhBuildParams, aabb::Aabb, cwbvh::CwBvh, cwbvh::builder::build_cwbvh};
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::time::Duration;

/// The direction with every −0.0 turned into +0.0 (x + 0.0 does that in IEEE arithmetic).
///
/// Works around a bug in obvhs 0.4.0, written up here to be filed upstream
/// (tests/intersection.rs `obvhs_0_4_misses_rays_with_negative_zero_components` runs it):
///
/// > **A ray direction with a −0.0 component misses everything in `CwBvh::ray_traverse`.**
/// > Build a `CwBvh` over two boxes, [−1, 1]² × [−3, −2] and [4, 5]² × [−3, −2], with
/// > `build_cwbvh(&boxes, BvhBuildParams::medium_build(), ..)`. A ray from the origin along
/// > `vec3a(0.0, 0.0, -1.0)` hits the first box; along `-Vec3A::Z`, which is
/// > (−0.0, −0.0, −1.0), it hits nothing. Cause: `ray_get_octant_inv4` (cwbvh/mod.rs)
/// > classifies a component as negative by `dir.x < 0.0`, false for −0.0, while
/// > `Ray::new`'s `safe_inverse` turns ±0.0 into `x.signum() / f32::EPSILON`, and
/// > `(-0.0f32).signum()` is −1.0: the node test takes the near and far planes of one
/// > octant with the inverse direction of another. Fix: `dir.x.is_sign_negative()` (for
/// > each axis) in `ray_get_octant_inv4`, or `if x < 0.0 { -1.0 } else { 1.0 }` in
/// > `safe_inverse`, so that both agree.
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

/// Makes many identical boxes slightly different. PLOC merges mutual nearest neighbours;
/// among many identical boxes every distance ties, few pairs are mutual and the build turns
/// quadratic (20,000 copies of one sphere took 6 s). Beyond its first few copies, each
/// duplicate grows by its own tiny amount (a box a hair larger still bounds its
/// primitive). A few copies (the two triangles of a box's face share a box) are left as
/// they are, and with them the tree and the images of every ordinary scene.
fn break_ties(bounds: &mut [Aabb]) {
    const COPIES_KEPT: u32 = 4;
    // Checked first on a sample of boxes, so that ordinary scenes pay almost nothing: the
    // copies that make the build slow are tens of thousands, and show in any sample.
    const SAMPLE: u64 = 4096;
    let key = |b: &Aabb| {
        let (lo, hi) = (b.min.to_array(), b.max.to_array());
        [lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]]
            .iter()
            .fold(0u64, |h, x| mix64(h ^ x.to_bits() as u64))
    };
    type Copies = HashMap<u64, u32, BuildHasherDefault<KeyHasher>>;
    let n = bounds.len() as u64;
    let mut sampled = Copies::default();
    let many = (0..SAMPLE.min(n)).any(|k| {
        let i = if n <= SAMPLE { k } else { mix64(k) % n };
        let count = sampled.entry(key(&bounds[i as usize])).or_default();
        *count += 1;
        *count > COPIES_KEPT
    });
    if !many {
        return;
    }
    let mut copies = Copies::with_capacity_and_hasher(bounds.len(), Default::default());
    for (i, b) in bounds.iter_mut().enumerate() {
        let count = copies.entry(key(b)).or_default();
        *count += 1;
        if *count > COPIES_KEPT {
            // Up to 0.2 % of the box's extent, below and above by different amounts.
            let extent = (b.max - b.min).max_element().max(1e-6);
            let h = mix64(i as u64);
            let unit = |bits: u64| (bits & 0xff_ffff) as f32 / (1u32 << 24) as f32;
            b.min -= extent * 1e-3 * (1.0 + unit(h));
            b.max += extent * 1e-3 * (1.0 + unit(h >> 32));
        }
    }
}

/// Hashes keys that are hashes already: passes them through.
#[derive(Default)]
pub(crate) struct KeyHasher(u64);

impl Hasher for KeyHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = mix64(self.0 ^ b as u64);
        }
    }
    fn write_u64(&mut self, key: u64) {
        self.0 = key;
    }
}

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
    /// The nearest hit in (0, t_max), and its distance. Always inlined into
    /// [`Accel::intersect`]: as a call it cost the specular benchmark 2 % (measured).
    #[inline(always)]
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<(PrimRef, f32)> {
        // The nearest distance so far as a plain number, the limit of every next test,
        // rather than unwrapped from an Option at each: the loops run for every ray.
        let (mut t_best, mut best) = (t_max, None);
        for (o, p) in &self.planes {
            if let Some(t) = p.intersect_t(ray, t_best) {
                (t_best, best) = (t, Some(*o));
            }
        }
        for (o, s) in &self.spheres {
            if let Some(t) = s.intersect_t(ray, t_best) {
                (t_best, best) = (t, Some(*o));
            }
        }
        for (o, q) in &self.quads {
            if let Some((t, _)) = q.intersect_t(ray, t_best) {
                (t_best, best) = (t, Some(*o));
            }
        }
        best.map(|object| (PrimRef { object, index: 0 }, t_best))
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
        break_ties(&mut bounds);
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

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3A;

    #[test]
    fn many_identical_boxes_are_made_distinct_and_still_bound_their_primitive() {
        let unit = Aabb::new(Vec3A::ZERO, Vec3A::ONE);
        let mut bounds = vec![unit; 20_000];
        break_ties(&mut bounds);
        assert!(
            bounds
                .iter()
                .all(|b| b.min.cmple(unit.min).all() && b.max.cmpge(unit.max).all())
        );
        let exact = bounds.iter().filter(|b| **b == unit).count();
        assert_eq!(exact, 4, "the first copies are kept as they are");
        let mut sizes: Vec<(u32, u32)> = bounds
            .iter()
            .map(|b| (b.min.x.to_bits(), b.max.x.to_bits()))
            .collect();
        sizes.sort_unstable();
        sizes.dedup();
        assert!(sizes.len() > 19_000, "{} distinct boxes", sizes.len());
        // A few copies (a box's faces: two triangles each) change nothing.
        let mut pairs = vec![unit, unit, Aabb::new(Vec3A::ONE, Vec3A::splat(2.0))];
        let before = pairs.clone();
        break_ties(&mut pairs);
        assert_eq!(pairs, before);
    }
}
