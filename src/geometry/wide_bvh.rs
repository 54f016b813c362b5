//! The BVH as it is traversed: eight children a node, each child's box in plain `f32`,
//! stored axis by axis so that one ray is tested against all eight boxes at once.
//!
//! obvhs builds the tree (PLOC, reinsertion, collapse to eight children: its
//! [`CwBvh`]); its own traversal decodes each child's box from bytes and walks the
//! children one at a time, which was half of a glass mesh's render time. This one takes
//! the tree's shape from it and the boxes from the primitives' own bounds (exact, tighter
//! than the quantized ones), and visits the children a ray hits nearest first.
//!
//! The box test is the slab test, t = (plane − o)·(1/d) per axis, and a box is entered
//! where the largest entry ≤ the smallest exit. The exits are computed with 1/d enlarged
//! by 1 + 2γ₃ (γ₃ = 3ε/(1 − 3ε), ε = 2⁻²⁴), and a box is visited while its entry is
//! below the nearest hit so far enlarged as much: the rounding of the subtraction, the
//! reciprocal and the product can then never make a ray miss a box it touches (Ize,
//! "Robust BVH ray traversal", 2013; pbrt does the same). So the search finds what
//! testing every primitive finds: the nearest hit (of hits at one distance, the lowest
//! slot's, whatever order the boxes come in), or a blocker
//! (tests/intersection.rs, and the tests below).

use crate::math::Vec3;
use crate::math::lanes::{Lanes, Real, max, min};
use obvhs::aabb::Aabb;
use obvhs::cwbvh::CwBvh;

/// Children a node.
const WIDE: usize = 8;

/// The enlargement of a box's exits, 1 + 2γ₃ (see the module's doc).
const EXIT_SCALE: f32 = {
    let eps = f32::EPSILON / 2.0;
    1.0 + 2.0 * (3.0 * eps) / (1.0 - 3.0 * eps)
};

/// Entries the traversal keeps on its own stack before it spills to the heap: a ray
/// postpones at most seven children a level, rarely more than two, and a tree over a
/// million triangles is about seven levels deep.
const STACK: usize = 32;

/// Eight children's boxes and what each is.
#[derive(Clone, Debug)]
#[repr(C, align(64))]
struct Node {
    // Planes by axis and side: [x min, x max, y min, y max, z min, z max], each for the
    // eight children. An empty child's box is inverted (min +∞, max −∞): never hit.
    planes: [[f32; WIDE]; 6],
    // An inner child's node, or a leaf's first primitive (its slot in the leaf order).
    first: [u32; WIDE],
    // A leaf's number of primitives; 0 for an inner child (and an empty one).
    count: [u8; WIDE],
}

/// A child a ray reached, at the distance it entered its box.
#[derive(Clone, Copy, Debug, Default)]
struct Reached {
    first: u32,
    count: u32,
    t: f32,
}

/// The wide BVH; primitives are named by their slot in the leaf order (obvhs's
/// `primitive_indices` give each slot's primitive).
#[derive(Clone, Debug)]
pub(super) struct WideBvh {
    // The root first.
    nodes: Vec<Node>,
}

/// A ray as the box test takes it.
#[derive(Clone, Copy)]
struct Slabs {
    origin: [f32; 3],
    inverse: [f32; 3],
    // The reciprocals enlarged by 1 + 2γ₃, for the exits (see the module's doc).
    padded: [f32; 3],
    // Per axis, the index into `Node::planes` of the plane the ray enters by (the min for
    // a positive direction, the max for a negative one) and of the one it leaves by.
    near: [usize; 3],
    far: [usize; 3],
}

impl Slabs {
    #[inline(always)]
    fn new(origin: Vec3, dir: Vec3) -> Slabs {
        let inverse = [1.0 / dir.x, 1.0 / dir.y, 1.0 / dir.z];
        // By the reciprocal's sign, so that −0.0 (whose reciprocal is −∞) enters by the
        // max as the reciprocal says.
        let near = [0, 1, 2].map(|a| 2 * a + inverse[a].is_sign_negative() as usize);
        Slabs {
            origin: origin.to_array(),
            inverse,
            padded: inverse.map(|i| i * EXIT_SCALE),
            near,
            far: near.map(|n| n ^ 1),
        }
    }

    /// Where the ray enters each of `node`'s children, if before `limit`; +∞ for those
    /// it does not, and a mask of the others (bit i: child i).
    #[inline(always)]
    fn enter(&self, node: &Node, limit: f32) -> (u32, Lanes<WIDE>) {
        let mut t_in = Lanes::splat(0.0);
        let mut t_out = Lanes::splat(limit);
        for axis in 0..3 {
            let o = Lanes::splat(self.origin[axis]);
            let t0 = (Lanes(node.planes[self.near[axis]]) - o) * Lanes::splat(self.inverse[axis]);
            let t1 = (Lanes(node.planes[self.far[axis]]) - o) * Lanes::splat(self.padded[axis]);
            // A NaN (a plane through the origin of a ray parallel to it: 0 × ∞) is no
            // limit: max and min keep their first argument where the other is NaN.
            t_in = max(t_in, t0);
            t_out = min(t_out, t1);
        }
        let entered = Lanes::select(t_in.less_eq(t_out), t_in, Lanes::splat(f32::INFINITY));
        let bits = (0..WIDE).fold(0, |bits, i| {
            bits | ((entered.0[i] != f32::INFINITY) as u32) << i
        });
        (bits, entered)
    }
}

/// The traversal's postponed children: a fixed array, then the heap. Made once for many
/// rays where it can be (filling the array was 6 % of a glass mesh's render when each
/// ray made its own).
pub(super) struct Stack {
    near: [Reached; STACK],
    len: usize,
    spilled: Vec<Reached>,
}

impl Stack {
    #[inline(always)]
    pub(super) fn new() -> Stack {
        Stack {
            near: [Reached::default(); STACK],
            len: 0,
            spilled: Vec::new(),
        }
    }

    #[inline(always)]
    fn push(&mut self, r: Reached) {
        if self.len < STACK {
            self.near[self.len] = r;
            self.len += 1;
        } else {
            self.spilled.push(r);
        }
    }

    #[inline(always)]
    fn pop(&mut self) -> Option<Reached> {
        if let Some(r) = self.spilled.pop() {
            return Some(r);
        }
        self.len = self.len.checked_sub(1)?;
        Some(self.near[self.len])
    }
}

impl WideBvh {
    /// The wide tree with `cw`'s shape, over primitives whose boxes are `bounds` (indexed
    /// as `cw` was built over them).
    pub(super) fn new(cw: &CwBvh, bounds: &[Aabb]) -> WideBvh {
        let empty = Node {
            planes: [
                [f32::INFINITY; WIDE],
                [f32::NEG_INFINITY; WIDE],
                [f32::INFINITY; WIDE],
                [f32::NEG_INFINITY; WIDE],
                [f32::INFINITY; WIDE],
                [f32::NEG_INFINITY; WIDE],
            ],
            first: [0; WIDE],
            count: [0; WIDE],
        };
        let mut nodes = vec![empty; cw.nodes.len()];
        if !nodes.is_empty() {
            boxes(cw, bounds, &mut nodes, 0);
        }
        WideBvh { nodes }
    }

    /// The nearest primitive along the ray from `origin` along `dir` in (0, `t_max`):
    /// `primitive(slot, t)` tests the primitive at `slot` against the ray below `t` and
    /// returns its distance (+∞ for none). Of hits at the same distance, the one of the
    /// lowest slot: what testing every primitive in slot order finds, whatever order the
    /// boxes are visited in. The slot and distance of the nearest.
    #[inline(always)]
    pub(super) fn nearest(
        &self,
        stack: &mut Stack,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        mut primitive: impl FnMut(u32, f32) -> f32,
    ) -> Option<(u32, f32)> {
        let mut best: Option<u32> = None;
        let mut t_best = t_max;
        self.walk(stack, origin, dir, &mut t_best, |first, count, t_best| {
            for slot in first..first + count {
                // A slot below the nearest's may tie with it: it is tested up to and
                // including the nearest's distance.
                let before = best.is_some_and(|b| slot < b);
                let t = primitive(slot, if before { t_best.next_up() } else { *t_best });
                if t < *t_best || (before && t == *t_best) {
                    *t_best = t;
                    best = Some(slot);
                }
            }
            false
        });
        best.map(|slot| (slot, t_best))
    }

    /// Whether `blocks(slot, t_max)` holds for a primitive along the ray from `origin`
    /// along `dir` before `t_max`: the search ends at the first.
    #[inline(always)]
    pub(super) fn any(
        &self,
        stack: &mut Stack,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        mut blocks: impl FnMut(u32, f32) -> bool,
    ) -> bool {
        let mut t = t_max;
        self.walk(stack, origin, dir, &mut t, |first, count, t| {
            (first..first + count).any(|slot| blocks(slot, *t))
        })
    }

    /// Visits the leaves whose boxes the ray enters before `t_max`, nearest box first
    /// (as far as the boxes tell), each by `leaf(first, count, t_max)`, which may lower
    /// `t_max` and ends the walk by returning true. Whether a leaf ended it.
    #[inline(always)]
    fn walk(
        &self,
        stack: &mut Stack,
        origin: Vec3,
        dir: Vec3,
        t_max: &mut f32,
        mut leaf: impl FnMut(u32, u32, &mut f32) -> bool,
    ) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let ray = Slabs::new(origin, dir);
        // (A walk the leaf ended leaves entries behind.)
        stack.len = 0;
        stack.spilled.clear();
        let mut at = Reached::default();
        loop {
            // The limit enlarged as the exits are: the entry is rounded too.
            let limit = *t_max * EXIT_SCALE;
            if at.t <= limit {
                if at.count > 0 {
                    if leaf(at.first, at.count, t_max) {
                        return true;
                    }
                } else {
                    let node = &self.nodes[at.first as usize];
                    let (mut hit, t_in) = ray.enter(node, limit);
                    if hit != 0 {
                        // Go on into the nearest child; postpone the others.
                        let child = |i: usize| Reached {
                            first: node.first[i],
                            count: node.count[i] as u32,
                            t: t_in.0[i],
                        };
                        let mut nearest = child(hit.trailing_zeros() as usize);
                        hit &= hit - 1;
                        while hit != 0 {
                            let other = child(hit.trailing_zeros() as usize);
                            hit &= hit - 1;
                            if other.t < nearest.t {
                                stack.push(nearest);
                                nearest = other;
                            } else {
                                stack.push(other);
                            }
                        }
                        at = nearest;
                        continue;
                    }
                }
            }
            match stack.pop() {
                Some(next) => at = next,
                None => return false,
            }
        }
    }
}

/// Fills `nodes[index]` from `cw`'s node `index` (and its subtree); returns its box.
fn boxes(cw: &CwBvh, bounds: &[Aabb], nodes: &mut [Node], index: usize) -> Aabb {
    let source = &cw.nodes[index];
    let mut whole = Aabb::INVALID;
    for child in 0..WIDE {
        if source.is_child_empty(child) {
            continue;
        }
        let (aabb, what) = if source.is_leaf(child) {
            let (first, count) = source.child_primitives(child);
            let aabb = (first..first + count).fold(Aabb::INVALID, |b, slot| {
                b.union(&bounds[cw.primitive_indices[slot as usize] as usize])
            });
            (aabb, (first, count))
        } else {
            let at = source.child_node_index(child);
            (boxes(cw, bounds, nodes, at as usize), (at, 0))
        };
        set_child(&mut nodes[index], child, &aabb, what);
        whole = whole.union(&aabb);
    }
    whole
}

/// Child `i` of `node`: box `aabb`, and (first, count) as [`Node`] keeps them.
fn set_child(node: &mut Node, i: usize, aabb: &Aabb, (first, count): (u32, u32)) {
    let (lo, hi) = (aabb.min.to_array(), aabb.max.to_array());
    for axis in 0..3 {
        node.planes[2 * axis][i] = lo[axis];
        node.planes[2 * axis + 1][i] = hi[axis];
    }
    node.first[i] = first;
    // obvhs's leaves hold at most three primitives (a unary count in three bits).
    node.count[i] = count as u8;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::rng::{mix64, to_unit_f32};
    use glam::Vec3A;
    use obvhs::{BvhBuildParams, cwbvh::builder::build_cwbvh};

    /// Where the ray enters `b` (from 0 on), if it does: the plain slab test.
    fn entry(b: &Aabb, o: Vec3, d: Vec3) -> Option<f32> {
        let (lo, hi) = (Vec3::from(b.min), Vec3::from(b.max));
        let (t0, t1) = ((lo - o) / d, (hi - o) / d);
        let near = t0.min(t1).max_element().max(0.0);
        let far = t0.max(t1).min_element();
        (near <= far).then_some(near)
    }

    #[test]
    fn the_nearest_is_the_lowest_slot_at_the_least_distance_whatever_the_order_visited() {
        let mut state = 3u64;
        let mut u = || {
            state = mix64(state);
            to_unit_f32(state)
        };
        // 2,000 small boxes in a 10-unit cube.
        let bounds: Vec<Aabb> = (0..2000)
            .map(|_| {
                let c = Vec3A::new(u(), u(), u()) * 10.0;
                let h = Vec3A::new(u(), u(), u()) * 0.3 + 0.05;
                Aabb::new(c - h, c + h)
            })
            .collect();
        // (As `accel::build_tree` builds it, but for its ties, which these boxes have none of.)
        let cw = build_cwbvh(
            &bounds,
            BvhBuildParams::medium_build(),
            &mut Default::default(),
        );
        let (bvh, order) = (WideBvh::new(&cw, &bounds), cw.primitive_indices);
        let mut stack = Stack::new();
        let mut found = 0;
        for _ in 0..3000 {
            let o = Vec3::new(u(), u(), u()) * 14.0 - 2.0;
            let d = (Vec3::new(u(), u(), u()) * 2.0 - 1.0).normalize();
            // A primitive "hit" at its box's entry rounded up to a whole number: many tie,
            // in leaves far apart.
            let t_of = |slot: u32| {
                let b = &bounds[order[slot as usize] as usize];
                entry(b, o, d).map_or(f32::INFINITY, |t| t.ceil().max(1.0))
            };
            let mut every = None;
            for slot in 0..order.len() as u32 {
                let t = t_of(slot);
                if t < every.map_or(f32::INFINITY, |(_, b)| b) {
                    every = Some((slot, t));
                }
            }
            let nearest = bvh.nearest(&mut stack, o, d, f32::INFINITY, |slot, limit| {
                let t = t_of(slot);
                if t < limit { t } else { f32::INFINITY }
            });
            assert_eq!(nearest, every, "from {o} along {d}");
            let blocked = bvh.any(&mut stack, o, d, f32::INFINITY, |slot, limit| {
                t_of(slot) < limit
            });
            assert_eq!(blocked, every.is_some());
            found += every.is_some() as u32;
        }
        assert!(found > 1000, "too few hits ({found}) to mean anything");
    }

    #[test]
    fn the_stack_spills_to_the_heap_and_gives_back_the_last_first() {
        let mut stack = Stack::new();
        for k in 0..3 * STACK as u32 {
            stack.push(Reached {
                first: k,
                count: 0,
                t: k as f32,
            });
        }
        for k in (0..3 * STACK as u32).rev() {
            assert_eq!(stack.pop().map(|r| r.first), Some(k));
        }
        assert!(stack.pop().is_none());
    }
}
