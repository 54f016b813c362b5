//! The shapes tested one by one, outside the BVH: the unbounded planes, and a handful of
//! spheres, quads and small meshes, for which a loop beats descending a tree and runs in
//! lanes, `N` rays against one shape at a time.

use super::mesh::triangle_nearest;
use super::shapes::{QuadAt, SphereAt, plane_nearest, quad_nearest, sphere_nearest};
use super::{Mesh, PrimRef, Shape};
use crate::math::lanes::{LaneKernel, Lanes, RayColumns, Real, Vector, Wide, max, min};
use crate::math::{Ray, Vec3};
use obvhs::aabb::Aabb;

/// Up to this many spheres, quads and small meshes are tested one by one, outside the BVH:
/// for a handful of them a loop beats descending a tree built for millions of triangles,
/// and it runs in lanes, `N` rays against one shape.
const DIRECT_MAX: usize = 16;

/// A mesh of at most this many triangles (a box has 12) counts as one shape of the
/// [`DIRECT_MAX`]: its triangles are tested one by one behind its bounding box.
pub(crate) const SMALL_MESH: usize = 16;

/// The spheres, quads and small meshes tested directly (when there are at most
/// DIRECT_MAX), and the planes: what their tests read, each vector kept [`Wide`] for the
/// lanes to load.
#[derive(Clone, Debug, Default)]
pub(super) struct Direct {
    // Each plane's unit normal and a point on it.
    planes: Vec<[Wide; 2]>,
    spheres: Vec<SphereAt<Wide>>,
    quads: Vec<QuadAt<Wide>>,
    meshes: Vec<SmallMesh>,
    // The primitive of each, planes first, then spheres, quads and the meshes' triangles.
    prims: Vec<PrimRef>,
}

/// A small mesh's triangles, behind the box that holds them over the whole frame.
#[derive(Clone, Debug)]
struct SmallMesh {
    // The box, a hair larger than the triangles' (see `SmallMesh::new`).
    lo: Wide,
    hi: Wide,
    velocity: Wide,
    // Each triangle's [v0, e1, e2] (see `triangle_nearest`).
    edges: Vec<[Wide; 3]>,
}

impl SmallMesh {
    fn new(mesh: &Mesh) -> Self {
        let b = (0..mesh.triangle_count())
            .map(|i| mesh.triangle_bounds(i))
            .fold(Aabb::INVALID, |a, b| a.union(&b));
        // Larger by more than the rounding of a hit's distance and of the box test, so
        // that no ray that meets a triangle misses the box.
        let size = (b.max - b.min).max_element() + b.min.abs().max(b.max.abs()).max_element();
        let pad = Vec3::splat(1e-5 * size + 1e-6);
        SmallMesh {
            lo: Wide::splat(b.min - pad),
            hi: Wide::splat(b.max + pad),
            velocity: Wide::splat(mesh.velocity),
            edges: mesh.edges().iter().map(|e| e.map(Wide::splat)).collect(),
        }
    }

    /// Where each ray (origin `o`, direction `d`) may meet the box in (0, t_max]: the slab
    /// test, with every NaN (a ray along a face's plane) counting as a meeting.
    #[inline(always)]
    fn may_meet<R: Real>(&self, o: R::V3, d: R::V3, t_max: R) -> R::Mask {
        let (o, d) = (o.coords(), d.coords());
        let (lo, hi) = (
            R::V3::wide(&self.lo).coords(),
            R::V3::wide(&self.hi).coords(),
        );
        // A slack on the far end for the rounding of t_max against the box's distances.
        let (mut near, mut far) = (R::splat(0.0), t_max * R::splat(1.0 + 1e-4));
        for k in 0..3 {
            let inv = R::splat(1.0) / d[k];
            let (t0, t1) = ((lo[k] - o[k]) * inv, (hi[k] - o[k]) * inv);
            // min and max keep their first argument where the second is NaN.
            near = max(near, min(t0, t1));
            far = min(far, max(t0, t1));
        }
        !far.less(near)
    }

    /// The origins `o` at times `time` in the mesh's own frame (it only translates).
    #[inline(always)]
    fn local<R: Real>(&self, o: R::V3, time: R) -> R::V3 {
        o - R::V3::wide(&self.velocity).scale(time)
    }
}

impl Direct {
    /// The planes of `shapes`, with their spheres, quads and small meshes when there are
    /// at most [`DIRECT_MAX`] of them; and the primitives left for the BVH.
    pub(super) fn new(shapes: &[Shape]) -> (Direct, Vec<PrimRef>) {
        let small = |s: &Shape| match s {
            Shape::Sphere(_) | Shape::Quad(_) => true,
            Shape::Mesh(m) => m.triangle_count() <= SMALL_MESH,
            Shape::Plane(_) | Shape::Instance(_) => false,
        };
        let direct_ok = shapes.iter().filter(|s| small(s)).count() <= DIRECT_MAX;
        let mut direct = Direct::default();
        let mut rest = Vec::new();
        // The primitives of the planes, spheres, quads and meshes tested directly, kind by
        // kind.
        let mut tested: [Vec<PrimRef>; 4] = Default::default();
        for (object, shape) in shapes.iter().enumerate() {
            let object = object as u32;
            let prim = PrimRef { object, index: 0 };
            match shape {
                Shape::Plane(p) => {
                    direct.planes.push([p.normal, p.point].map(Wide::splat));
                    tested[0].push(prim);
                }
                Shape::Sphere(s) if direct_ok => {
                    direct.spheres.push(s.at(Wide::splat));
                    tested[1].push(prim);
                }
                Shape::Quad(q) if direct_ok => {
                    direct.quads.push(q.at(Wide::splat));
                    tested[2].push(prim);
                }
                Shape::Mesh(m) if direct_ok && small(shape) => {
                    direct.meshes.push(SmallMesh::new(m));
                    let count = m.triangle_count() as u32;
                    tested[3].extend((0..count).map(|index| PrimRef { object, index }));
                }
                _ => {
                    let count = shape.leaf_count() as u32;
                    rest.extend((0..count).map(|index| PrimRef { object, index }));
                }
            }
        }
        // In the order `Direct::nearest` tests them.
        direct.prims = tested.concat();
        (direct, rest)
    }

    /// How many bounded primitives (all but the planes) are tested here.
    pub(super) fn bounded(&self) -> usize {
        self.prims.len() - self.planes.len()
    }

    /// The nearest hit in (0, t_max), and its distance. Always inlined into
    /// [`Accel::intersect`], which calls it for every ray (docs/performance.md, "Shaped by
    /// measurement").
    #[inline(always)]
    pub(super) fn intersect(&self, ray: &Ray, t_max: f32) -> Option<(PrimRef, f32)> {
        let (t, place) = self.nearest(ray.origin, ray.dir, ray.time, t_max);
        self.found(t, place as i32)
    }

    /// The nearest of them along each lane's ray in (0, t_max): its distance and its place
    /// in `objects` (as a number, exact below 2²⁴), or (t_max, −1) where none is hit. The
    /// nearest distance so far is the limit of every next test.
    #[inline(always)]
    fn nearest<R: Real>(&self, o: R::V3, d: R::V3, time: R, t_max: R) -> (R, R) {
        let (mut t_best, mut best) = (t_max, R::splat(-1.0));
        let mut keep = |t: R, place: usize| {
            let hit = t.less(R::splat(f32::INFINITY));
            t_best = R::select(hit, t, t_best);
            best = R::select(hit, R::splat(place as f32), best);
            t_best
        };
        let mut limit = t_max;
        let mut place = 0;
        for [n, p] in &self.planes {
            limit = keep(
                plane_nearest(R::V3::wide(n), R::V3::wide(p), o, d, limit),
                place,
            );
            place += 1;
        }
        for s in &self.spheres {
            limit = keep(sphere_nearest(&s.load::<R>(), o, d, time, limit), place);
            place += 1;
        }
        for q in &self.quads {
            limit = keep(quad_nearest(&q.load::<R>(), o, d, limit), place);
            place += 1;
        }
        for m in &self.meshes {
            if R::any(m.may_meet(o, d, limit)) {
                let o = m.local(o, time);
                for (k, e) in m.edges.iter().enumerate() {
                    limit = keep(
                        triangle_nearest(e.each_ref().map(R::V3::wide), o, d, limit).0,
                        place + k,
                    );
                }
            }
            place += m.edges.len();
        }
        (t_best, best)
    }

    /// The hit of [`Direct::nearest`]'s answer for one ray.
    #[inline(always)]
    /// (`place` as an integer: a miss's -1 indexes nothing.)
    fn found(&self, t: f32, place: i32) -> Option<(PrimRef, f32)> {
        self.prims.get(place as usize).map(|&prim| (prim, t))
    }

    /// Where any of them blocks each ray (origin `o`, direction `d`, at `time`) in
    /// (0, t_max), or `blocked` holds already: the shadow-ray query, which stops once every
    /// ray is blocked.
    #[inline(always)]
    pub(super) fn occluded<R: Real>(
        &self,
        o: R::V3,
        d: R::V3,
        time: R,
        t_max: R,
        mut blocked: R::Mask,
    ) -> R::Mask {
        let miss = R::splat(f32::INFINITY);
        let mut block = |t: R| {
            blocked = blocked | t.less(miss);
            R::all(blocked)
        };
        for [n, p] in &self.planes {
            if block(plane_nearest(R::V3::wide(n), R::V3::wide(p), o, d, t_max)) {
                return blocked;
            }
        }
        for s in &self.spheres {
            if block(sphere_nearest(&s.load::<R>(), o, d, time, t_max)) {
                return blocked;
            }
        }
        for q in &self.quads {
            if block(quad_nearest(&q.load::<R>(), o, d, t_max)) {
                return blocked;
            }
        }
        for m in &self.meshes {
            if R::any(m.may_meet(o, d, t_max)) {
                let o = m.local(o, time);
                for e in &m.edges {
                    if block(triangle_nearest(e.each_ref().map(R::V3::wide), o, d, t_max).0) {
                        return blocked;
                    }
                }
            }
        }
        blocked
    }
}

/// The nearest hit of every ray of a wave against the directly tested shapes, `N` rays at a
/// time, into `out`.
pub(super) struct DirectWave<'a> {
    pub(super) direct: &'a Direct,
    pub(super) rays: &'a RayColumns,
    pub(super) out: &'a mut [Option<(PrimRef, f32)>],
}

impl LaneKernel for DirectWave<'_> {
    type Output = ();
    #[inline(always)]
    fn run<const N: usize>(self) {
        for (group, out) in self.out.chunks_mut(N).enumerate() {
            let rays = self.rays.lanes::<N>(group * N);
            let far = Lanes::splat(f32::INFINITY);
            let (t, place) = self.direct.nearest(rays.origin, rays.dir, rays.time, far);
            // The places made integers in lanes: a whole number p with |p| < 2²² is the
            // low bits of p + 2²³ (exact, with 2²³'s exponent), and −1 (none) becomes −2,
            // which indexes nothing. (`as i32` saturates, which is done lane by lane: 7
            // instructions a ray with AVX2.)
            const TWO_23: f32 = 8_388_608.0;
            let bits = |p: f32| (p + TWO_23).to_bits().wrapping_sub(TWO_23.to_bits());
            let place: [i32; N] = std::array::from_fn(|i| bits(place.0[i]) as i32);
            for ((out, &place), &t) in out.iter_mut().zip(&place).zip(&t.0) {
                *out = self.direct.found(t, place);
            }
        }
    }
}
