//! The BVH over every bounded primitive of a scene, plus the unbounded planes beside it.
//!
//! The tree is obvhs's compressed wide BVH (8 children a node), built with PLOC and
//! reinsertion: a SAH-quality tree that builds a million triangles in well under a second.

use super::{Plane, Quad, Shape, Sphere};
use crate::math::Ray;
use crate::math::lanes::{LaneKernel, Lanes, RayColumns, Real, Width};
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
    planes: Vec<Plane>,
    spheres: Vec<Sphere>,
    quads: Vec<Quad>,
    // The object of each, planes first, then spheres, then quads.
    objects: Vec<u32>,
}

impl Direct {
    /// The nearest hit in (0, t_max), and its distance. Always inlined into
    /// [`Accel::intersect`]: as a call it cost the specular benchmark 2 % (measured).
    #[inline(always)]
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<(PrimRef, f32)> {
        let (t, place) = self.nearest(ray.origin, ray.dir, ray.time, t_max);
        self.found(t, place)
    }

    /// The nearest of them along each lane's ray in (0, t_max): its distance and its place
    /// in `objects` (as a number, exact below 2²⁴), or (t_max, −1) where none is hit. The
    /// nearest distance so far is the limit of every next test.
    #[inline(always)]
    fn nearest<R: Real>(&self, o: R::V3, d: R::V3, time: R, t_max: R) -> (R, R) {
        let (mut t_best, mut best) = (t_max, R::splat(-1.0));
        let mut place = 0.0;
        let mut keep = |t: R| {
            let hit = t.less(R::splat(f32::INFINITY));
            t_best = R::select(hit, t, t_best);
            best = R::select(hit, R::splat(place), best);
            place += 1.0;
            t_best
        };
        let mut limit = t_max;
        for p in &self.planes {
            limit = keep(p.nearest(o, d, limit));
        }
        for s in &self.spheres {
            limit = keep(s.nearest(o, d, time, limit));
        }
        for q in &self.quads {
            limit = keep(q.nearest(o, d, limit));
        }
        (t_best, best)
    }

    /// The hit of [`Direct::nearest`]'s answer for one ray.
    #[inline(always)]
    fn found(&self, t: f32, place: f32) -> Option<(PrimRef, f32)> {
        (place >= 0.0).then(|| {
            let object = self.objects[place as usize];
            (PrimRef { object, index: 0 }, t)
        })
    }

    /// Whether any of them blocks `ray` in (0, t_max).
    #[inline]
    fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.planes
            .iter()
            .any(|p| p.intersect_t(ray, t_max).is_some())
            || self
                .spheres
                .iter()
                .any(|s| s.intersect_t(ray, t_max).is_some())
            || self
                .quads
                .iter()
                .any(|q| q.intersect_t(ray, t_max).is_some())
    }
}

/// The nearest hit of every ray of a wave against the directly tested shapes, `N` rays at a
/// time, into `out`.
struct DirectWave<'a> {
    direct: &'a Direct,
    rays: &'a RayColumns,
    out: &'a mut [Option<(PrimRef, f32)>],
}

impl LaneKernel for DirectWave<'_> {
    type Output = ();
    #[inline(always)]
    fn run<const N: usize>(self) {
        for (group, out) in self.out.chunks_mut(N).enumerate() {
            let (o, d, time) = self.rays.lanes::<N>(group * N);
            let (t, place) = self.direct.nearest(o, d, time, Lanes::splat(f32::INFINITY));
            for (i, out) in out.iter_mut().enumerate() {
                *out = self.direct.found(t.0[i], place.0[i]);
            }
        }
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
        // The objects of the planes, spheres and quads tested directly, kind by kind.
        let mut objects: [Vec<u32>; 3] = Default::default();
        for (object, shape) in shapes.iter().enumerate() {
            let object = object as u32;
            match shape {
                Shape::Plane(p) => {
                    direct.planes.push(p.clone());
                    objects[0].push(object);
                }
                Shape::Sphere(s) if direct_ok => {
                    direct.spheres.push(s.clone());
                    objects[1].push(object);
                }
                Shape::Quad(q) if direct_ok => {
                    direct.quads.push(q.clone());
                    objects[2].push(object);
                }
                _ => {
                    for index in 0..shape.primitive_count() as u32 {
                        prims.push(PrimRef { object, index });
                        bounds.push(shape.primitive_bounds(index));
                    }
                }
            }
        }
        // In the order `Direct::nearest` tests them.
        direct.objects = objects.concat();
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
        let best = self.direct.intersect(ray, t_max);
        self.beyond_direct(shapes, ray, t_max, best)
    }

    /// [`Accel::intersect`] for every ray of `rays` (each from 0 to ∞), into `out`: the
    /// directly tested shapes `width` rays at a time, the BVH one ray after another.
    pub fn intersect_wave(
        &self,
        shapes: &[Shape],
        rays: &RayColumns,
        width: Width,
        out: &mut Vec<Option<(PrimRef, f32)>>,
    ) {
        out.clear();
        out.resize(rays.len(), None);
        width.dispatch(DirectWave {
            direct: &self.direct,
            rays,
            out,
        });
        if self.bvh.is_some() {
            for (i, best) in out.iter_mut().enumerate() {
                *best = self.beyond_direct(shapes, &rays.get(i), f32::INFINITY, *best);
            }
        }
    }

    /// The nearest hit of `ray` in (0, t_max) given `best`, the directly tested shapes'.
    #[inline(always)]
    fn beyond_direct(
        &self,
        shapes: &[Shape],
        ray: &Ray,
        t_max: f32,
        mut best: Option<(PrimRef, f32)>,
    ) -> Option<(PrimRef, f32)> {
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
    use crate::math::Vec3;
    use crate::math::rng::{mix64, to_unit_f32};
    use glam::Vec3A;

    #[test]
    fn every_width_finds_each_rays_nearest_hit_as_the_scalar_search_does_bit_for_bit() {
        let mut shapes = vec![
            Shape::Plane(Plane::new(Vec3::new(0.0, -1.0, 0.0), Vec3::Y)),
            Shape::Quad(Quad::new(
                Vec3::new(-2.0, -1.0, -3.0),
                Vec3::new(4.0, 0.0, 0.0),
                Vec3::new(0.0, 3.0, 0.5),
            )),
            Shape::Sphere(Sphere {
                velocity: Vec3::new(0.5, 0.0, 0.0),
                ..Sphere::new(Vec3::new(0.3, 0.2, -1.0), 0.7)
            }),
        ];
        for k in 0..5 {
            let c = Vec3::new(k as f32 - 2.0, 0.5 * k as f32, -2.0 - k as f32);
            shapes.push(Shape::Sphere(Sphere::new(c, 0.4 + 0.1 * k as f32)));
        }
        let accel = Accel::build(&shapes);
        // Rays from all over, inside spheres too, some along the plane (parallel to it).
        let mut state = 7u64;
        let mut u = || {
            state = mix64(state);
            to_unit_f32(state)
        };
        let mut rays = RayColumns::default();
        let mut scalar = Vec::new();
        for i in 0..1003 {
            let o = Vec3::new(4.0 * u() - 2.0, 3.0 * u() - 1.0, 4.0 * u() - 3.0);
            let d = if i % 50 == 0 {
                Vec3::X
            } else {
                Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5).normalize_or(Vec3::Z)
            };
            let ray = Ray {
                origin: o,
                dir: d,
                time: u(),
            };
            rays.push(&ray);
            scalar.push(accel.intersect(&shapes, &ray, f32::INFINITY));
        }
        let found = scalar.iter().filter(|h| h.is_some()).count();
        assert!(found > 300 && found < 1000, "{found} hits");
        for width in Width::ALL {
            let mut out = Vec::new();
            accel.intersect_wave(&shapes, &rays, width, &mut out);
            let bits = |h: &Option<(PrimRef, f32)>| h.map(|(p, t)| (p, t.to_bits()));
            let a: Vec<_> = out.iter().map(bits).collect();
            let b: Vec<_> = scalar.iter().map(bits).collect();
            assert_eq!(a, b, "{width:?}");
        }
    }

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
