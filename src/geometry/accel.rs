//! The BVH over every bounded primitive of a scene, plus the unbounded planes beside it.
//!
//! obvhs builds the tree (PLOC and reinsertion, collapsed to 8 children a node: a
//! SAH-quality tree that builds a million triangles in well under a second); it is
//! traversed as [`WideBvh`], eight boxes against a ray in one vector instruction.

use super::direct::{Direct, DirectWave};
use super::wide_bvh::{Stack, WideBvh};
use super::{PrimRef, Shape};
use crate::math::Ray;
use crate::math::lanes::{LaneKernel, Lanes, Mask, RayColumns, RayOf, Width};
use crate::math::rng::mix64;
use obvhs::{BvhBuildParams, aabb::Aabb, cwbvh::builder::build_cwbvh};
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::time::Duration;

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

/// The BVH over the boxes `bounds` (made distinct first, see [`break_ties`]), and the
/// leaf order: slot k of the leaves holds the primitive whose box is `bounds[order[k]]`.
pub(super) fn build_tree(bounds: &mut [Aabb]) -> (WideBvh, Vec<u32>) {
    break_ties(bounds);
    let cw = build_cwbvh(
        bounds,
        BvhBuildParams::medium_build(),
        &mut Duration::default(),
    );
    (WideBvh::new(&cw, bounds), cw.primitive_indices)
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
    bvh: Option<WideBvh>,
    // In the BVH's leaf order, so a leaf's slot indexes this directly.
    prims: Vec<PrimRef>,
    // The shapes tested one by one, copied out beside their object numbers: a tight loop
    // per kind, with no lookup in the scene's list and no match on the kind of shape.
    direct: Direct,
}

impl Accel {
    /// Builds the BVH over `shapes` (the scene's objects, in order). Every shape must be
    /// [`Shape::within_limits`]: the builder panics on bounds near 5e18.
    pub fn build(shapes: &[Shape]) -> Self {
        let (direct, mut prims) = Direct::new(shapes);
        let mut bounds: Vec<Aabb> = prims
            .iter()
            .map(|p| shapes[p.object as usize].leaf_bounds(p.index))
            .collect();
        let mut bvh = None;
        if !prims.is_empty() {
            let (tree, order) = build_tree(&mut bounds);
            prims = order.iter().map(|&i| prims[i as usize]).collect();
            bvh = Some(tree);
        }
        Accel { bvh, prims, direct }
    }

    /// Number of bounded primitives (in the BVH or tested directly).
    pub fn primitive_count(&self) -> usize {
        self.prims.len() + self.direct.bounded()
    }

    /// The nearest primitive hit by `ray` in (0, t_max), and its distance.
    #[inline]
    pub fn intersect(&self, shapes: &[Shape], ray: &Ray, t_max: f32) -> Option<(PrimRef, f32)> {
        let best = self.direct.intersect(ray, t_max);
        self.beyond_direct(&mut Stack::new(), shapes, ray, t_max, best)
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
            width.dispatch(BvhWave {
                accel: self,
                shapes,
                rays,
                out,
            });
        }
    }

    /// The nearest hit of `ray` in (0, t_max) given `best`, the directly tested shapes'.
    #[inline(always)]
    fn beyond_direct(
        &self,
        stack: &mut Stack,
        shapes: &[Shape],
        ray: &Ray,
        t_max: f32,
        mut best: Option<(PrimRef, f32)>,
    ) -> Option<(PrimRef, f32)> {
        let t_best = best.map_or(t_max, |(_, t)| t);
        let Some(bvh) = &self.bvh else {
            return best;
        };
        // Every distance returned is below the search's current limit and so taken: the
        // last primitive returned is the nearest.
        let mut nearest = PrimRef {
            object: 0,
            index: 0,
        };
        let found = bvh.nearest(stack, ray.origin, ray.dir, t_best, |slot, t_best| {
            let p = self.prims[slot as usize];
            match shapes[p.object as usize].intersect_leaf(p.index, ray, t_best) {
                Some((index, t)) => {
                    nearest = PrimRef { index, ..p };
                    t
                }
                None => f32::INFINITY,
            }
        });
        if let Some((_, t)) = found {
            best = Some((nearest, t));
        }
        best
    }

    /// Whether anything blocks `ray` in (0, t_max): the shadow-ray query, which stops at
    /// the first blocker found.
    #[inline]
    pub fn occluded(&self, shapes: &[Shape], ray: &Ray, t_max: f32) -> bool {
        let (o, d) = (ray.origin, ray.dir);
        self.direct.occluded(o, d, ray.time, t_max, false)
            || self.bvh_occluded(&mut Stack::new(), shapes, ray, t_max)
    }

    /// [`Accel::occluded`] for `N` rays (each up to its `t_max`), where `done` does not
    /// hold already: the directly tested shapes in lanes, the BVH ray by ray. True where a
    /// ray is blocked or done.
    #[inline(always)]
    pub(crate) fn occluded_lanes<const N: usize>(
        &self,
        shapes: &[Shape],
        rays: RayOf<Lanes<N>>,
        t_max: Lanes<N>,
        done: Mask<N>,
    ) -> Mask<N> {
        let mut blocked = self
            .direct
            .occluded(rays.origin, rays.dir, rays.time, t_max, done);
        if self.bvh.is_some() {
            let mut stack = Stack::new();
            for (i, b) in blocked.0.iter_mut().enumerate() {
                if *b == 0 {
                    *b = if self.bvh_occluded(&mut stack, shapes, &rays.get(i), t_max.0[i]) {
                        u32::MAX
                    } else {
                        0
                    };
                }
            }
        }
        blocked
    }

    /// Whether a BVH primitive blocks `ray` in (0, t_max).
    #[inline(always)]
    fn bvh_occluded(&self, stack: &mut Stack, shapes: &[Shape], ray: &Ray, t_max: f32) -> bool {
        let Some(bvh) = &self.bvh else {
            return false;
        };
        bvh.any(stack, ray.origin, ray.dir, t_max, |slot, t_max| {
            let p = self.prims[slot as usize];
            shapes[p.object as usize].leaf_blocks(p.index, ray, t_max)
        })
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
        for &leaf in &self.prims {
            let shape = &shapes[leaf.object as usize];
            for index in shape.leaf_primitives(leaf.index) {
                if let Some(t) = shape.intersect_t(index, ray, t_best) {
                    t_best = t;
                    best = Some((PrimRef { index, ..leaf }, t));
                }
            }
        }
        best
    }
}

/// The BVH's search for every ray of a wave, one ray after another, given the directly
/// tested shapes' nearest hits in `out`: run as a lane kernel only so that the box tests
/// are compiled for the processor's vector extension (eight boxes in one instruction).
struct BvhWave<'a> {
    accel: &'a Accel,
    shapes: &'a [Shape],
    rays: &'a RayColumns,
    out: &'a mut [Option<(PrimRef, f32)>],
}

impl LaneKernel for BvhWave<'_> {
    type Output = ();
    #[inline(always)]
    fn run<const N: usize>(self) {
        let mut stack = Stack::new();
        for (i, best) in self.out.iter_mut().enumerate() {
            let ray = self.rays.get(i);
            let accel = self.accel;
            *best = accel.beyond_direct(&mut stack, self.shapes, &ray, f32::INFINITY, *best);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Mesh, Plane, Quad, Sphere};
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
        shapes.extend(boxes());
        let accel = Accel::build(&shapes);
        assert!(
            accel.bvh.is_none(),
            "everything is tested directly, in lanes"
        );
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
        // The search tests copies of the shapes' vectors (`Wide`): it finds the nearest of
        // every shape's own test, on its own vectors, bit for bit.
        let own = |ray: &Ray| {
            let mut best: Option<(PrimRef, f32)> = None;
            for (object, shape) in shapes.iter().enumerate() {
                // (A plane, unbounded, counts no leaf; it is primitive 0.)
                for index in 0..shape.leaf_count().max(1) as u32 {
                    let t_best = best.map_or(f32::INFINITY, |(_, t)| t);
                    if let Some(t) = shape.intersect_t(index, ray, t_best) {
                        let object = object as u32;
                        best = Some((PrimRef { object, index }, t));
                    }
                }
            }
            best.map(|(p, t)| (p, t.to_bits()))
        };
        for (i, hit) in scalar.iter().enumerate() {
            assert_eq!(
                hit.map(|(p, t)| (p, t.to_bits())),
                own(&rays.get(i)),
                "ray {i}"
            );
        }
        // Shadow rays: beyond the nearest hit (blocked by it) or short of it, or of length 1.
        let reach = |i: usize| {
            let t = scalar[i].map_or(1.0, |(_, t)| t);
            if i.is_multiple_of(2) {
                t * 1.001
            } else {
                t * 0.5
            }
        };
        let blocked = |i: usize| accel.occluded(&shapes, &rays.get(i), reach(i));
        fn occluded_lanes<const N: usize>(
            accel: &Accel,
            shapes: &[Shape],
            rays: &RayColumns,
            reach: &dyn Fn(usize) -> f32,
        ) -> Vec<bool> {
            let mut out = Vec::new();
            for i in (0..rays.len()).step_by(N) {
                let t_max = Lanes::<N>::from_fn(|k| reach((i + k).min(rays.len() - 1)));
                let none = Mask([0; N]);
                let blocked = accel.occluded_lanes(shapes, rays.lanes::<N>(i), t_max, none);
                out.extend(blocked.0.iter().map(|&b| b != 0));
            }
            out.truncate(rays.len());
            out
        }
        let expected: Vec<bool> = (0..rays.len()).map(blocked).collect();
        assert!(expected.iter().any(|&b| b) && !expected.iter().all(|&b| b));
        assert_eq!(
            occluded_lanes::<4>(&accel, &shapes, &rays, &reach),
            expected
        );
        assert_eq!(
            occluded_lanes::<8>(&accel, &shapes, &rays, &reach),
            expected
        );
        assert_eq!(
            occluded_lanes::<16>(&accel, &shapes, &rays, &reach),
            expected
        );
        for width in Width::ALL {
            let mut out = Vec::new();
            accel.intersect_wave(&shapes, &rays, width, &mut out);
            let bits = |h: &Option<(PrimRef, f32)>| h.map(|(p, t)| (p, t.to_bits()));
            let a: Vec<_> = out.iter().map(bits).collect();
            let b: Vec<_> = scalar.iter().map(bits).collect();
            assert_eq!(a, b, "{width:?}");
        }
    }

    /// A rotated box and a moving one: small meshes, tested directly.
    fn boxes() -> [Shape; 2] {
        let turn = glam::Affine3A::from_rotation_y(0.5) * glam::Affine3A::from_rotation_x(0.3);
        let cuboid = |lo: Vec3, hi: Vec3| Mesh::cuboid(lo, hi).expect("a box");
        let turned = cuboid(Vec3::new(-1.0, -0.5, -2.5), Vec3::new(0.5, 0.8, -1.2))
            .transformed(&turn, false)
            .expect("a turned box");
        let mut moving = cuboid(Vec3::new(0.5, -1.0, -0.5), Vec3::new(1.5, 0.2, 0.4));
        moving.velocity = Vec3::new(-0.4, 0.3, 0.0);
        [Shape::Mesh(turned), Shape::Mesh(moving)]
    }

    #[test]
    fn small_meshes_tested_directly_find_the_nearest_triangle_and_every_blocker() {
        let shapes = boxes();
        let accel = Accel::build(&shapes);
        assert!(accel.bvh.is_none(), "two boxes need no BVH");
        let mut state = 11u64;
        let mut u = || {
            state = mix64(state);
            to_unit_f32(state)
        };
        let (mut hits, mut short) = (0, 0);
        for i in 0..20_000 {
            // From all around the boxes and from within them; some along an axis, some
            // starting on a face's plane, some with a reach that ends short.
            let o = Vec3::new(5.0 * u() - 2.5, 4.0 * u() - 2.0, 5.0 * u() - 3.5);
            let o = if i % 97 == 0 {
                Vec3::new(o.x, 0.2, o.z)
            } else {
                o
            };
            let d = match i % 40 {
                0 => Vec3::Y,
                1 => -Vec3::X,
                _ => Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5).normalize_or(Vec3::Z),
            };
            let ray = Ray {
                origin: o,
                dir: d,
                time: u(),
            };
            let t_max = if i % 5 == 0 { 3.0 * u() } else { f32::INFINITY };
            // Every triangle, one by one: what the BVH would find, to the bit.
            let mut every = None::<(PrimRef, f32)>;
            for (object, shape) in shapes.iter().enumerate() {
                let Shape::Mesh(m) = shape else {
                    unreachable!()
                };
                for index in 0..m.triangle_count() {
                    let limit = every.map_or(t_max, |(_, t)| t);
                    if let Some((t, _)) = m.intersect_t(index, &ray, limit) {
                        let object = object as u32;
                        let index = index as u32;
                        every = Some((PrimRef { object, index }, t));
                    }
                }
            }
            let found = accel.intersect(&shapes, &ray, t_max);
            let t = |h: Option<(PrimRef, f32)>| h.map(|(_, t)| t.to_bits());
            assert_eq!(t(found), t(every), "ray {i}: {ray:?} up to {t_max}");
            assert_eq!(found.map(|(p, _)| p.object), every.map(|(p, _)| p.object));
            assert_eq!(accel.occluded(&shapes, &ray, t_max), every.is_some());
            hits += every.is_some() as u32;
            short += (every.is_none() && t_max < f32::INFINITY) as u32;
        }
        assert!(
            hits > 2000 && short > 500,
            "{hits} hits, {short} short misses"
        );
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
