//! The lights of one level of the waves, in lanes: the area lights its rays see, and its
//! shadow rays, traced once its shading is done. The lights' sampled points, the cosines,
//! the occlusion test, the lights' surfaces and radiance are each made `N` at a time by
//! the formulas the recursion uses (their `f32` instances), so that a node's light is the
//! recursion's bit for bit. The BVH and each BRDF are asked ray by ray.

use crate::geometry::PrimRef;
use crate::material::Brdf;
use crate::math::lanes::{Columns, LaneKernel, Lanes, RayColumns, RayOf, Real};
use crate::math::rng::{Pair, SobolDraw, sobol_pairs};
use crate::math::{Color, Vec3};
use crate::tracer::Tracer;
use crate::tracer::shadow::{SHADOW_REACH, faces_light};
use glam::Vec2;

/// The area light each ray of a level sees in front of its nearest hit, if any: the
/// distance to it and its radiance there, as [`Tracer::light_seen`] finds it. Every
/// light with a lanes formula ([`crate::light::PreparedLight::nearest_of`]) is tested
/// `N` rays at a time; a scene with a disk light, and the last short chunk, ray by ray.
pub(super) struct Seen<'a, 't> {
    pub(super) tracer: &'a Tracer<'t>,
    pub(super) rays: &'a RayColumns,
    pub(super) nearest: &'a [Option<(PrimRef, f32)>],
    pub(super) out: &'a mut Vec<Option<(f32, Color)>>,
}

impl LaneKernel for Seen<'_, '_> {
    type Output = ();
    #[inline(always)]
    fn run<const N: usize>(self) {
        let Seen {
            tracer: t,
            rays,
            nearest,
            out,
        } = self;
        out.clear();
        let miss = f32::INFINITY;
        let limit = |k: usize| nearest[k].map_or(miss, |(_, t)| t);
        let one_by_one = |k: usize| {
            let mut near = limit(k);
            t.light_seen(&rays.get(k), &mut near)
                .map(|(_, radiance)| (near, radiance))
        };
        if !t.lights_seen {
            out.resize(nearest.len(), None);
            return;
        }
        let in_lanes = nearest.len() / N * N;
        for first in (0..in_lanes).step_by(N) {
            let ray = rays.lanes::<N>(first);
            let mut near = Lanes::<N>::from_fn(|k| limit(first + k));
            let mut which = Lanes::<N>::splat(-1.0);
            let mut every = true;
            for (j, light) in t.lights.iter().enumerate() {
                if !light.can_be_seen() {
                    continue;
                }
                let Some(t) = light.nearest_of(ray, near) else {
                    every = false;
                    break;
                };
                let hit = t.less(Lanes::splat(miss));
                near = Lanes::select(hit, t, near);
                which = Lanes::select(hit, Lanes::splat(j as f32), which);
            }
            if every {
                out.extend((0..N).map(|k| {
                    let light = &t.lights[(which.0[k] >= 0.0).then_some(which.0[k] as usize)?];
                    Some((near.0[k], light.seen_along(ray.dir.get(k))))
                }));
            } else {
                out.extend((first..first + N).map(one_by_one));
            }
        }
        out.extend((in_lanes..nearest.len()).map(one_by_one));
    }
}

/// A shadow ray a node of the level asks for: towards the point of one light drawn at
/// `u` (or to be drawn, in lanes, with the rest of the light's), from the hit `p`
/// (leaving at `origin`, just off the surface), lit through `brdf` about the shading
/// normal `n` and seen along `view`.
#[derive(Clone, Copy)]
pub(super) struct Shadow {
    pub(super) node: u32,
    pub(super) p: Vec3,
    pub(super) origin: Vec3,
    pub(super) n_geom: Vec3,
    pub(super) n: Vec3,
    pub(super) view: Vec3,
    pub(super) time: f32,
    pub(super) u: Pair,
    pub(super) brdf: Brdf,
}

/// The shadow rays asked of one light, as columns for the lanes to load (at these places:
/// p, origin, n_geom, n, view, time, u, the BRDF's Phong exponent), beside each one's node
/// and the BRDF's colours.
const P: usize = 0;
const ORIGIN: usize = 3;
const N_GEOM: usize = 6;
const N_SHADE: usize = 9;
const VIEW: usize = 12;
const TIME: usize = 15;
const U: usize = 16;
const EXPONENT: usize = 18;

#[derive(Default)]
pub(super) struct Asked {
    columns: Columns<19>,
    // Apart: a (node, BRDF) pair built field by field and copied whole stalls on
    // store-to-load forwarding; so does a BRDF copied whole, its exponent stored alone and
    // loaded with the padding beside it, so the exponent is a column (docs/performance.md,
    // "Shaped by measurement").
    nodes: Vec<u32>,
    colours: Vec<[Color; 2]>,
    // The light's points still to be drawn, one a ray, where its Sobol pairs are drawn
    // in lanes (then the columns' u is unused): a light's rays of one wave are all drawn
    // one way, as the pattern and the light say.
    later: Vec<SobolDraw>,
}

impl Asked {
    pub(super) fn clear(&mut self) {
        self.columns.clear();
        self.nodes.clear();
        self.colours.clear();
        self.later.clear();
    }

    #[inline(always)]
    pub(super) fn push(&mut self, s: &Shadow) {
        let [p, o, g, n, v] = [s.p, s.origin, s.n_geom, s.n, s.view];
        let u = match s.u {
            Pair::Drawn(u) => u,
            Pair::Later(draw) => {
                self.later.push(draw);
                Vec2::ZERO
            }
        };
        let e = s.brdf.exponent;
        self.columns.push([
            p.x, p.y, p.z, o.x, o.y, o.z, g.x, g.y, g.z, n.x, n.y, n.z, v.x, v.y, v.z, s.time, u.x,
            u.y, e,
        ]);
        self.nodes.push(s.node);
        self.colours.push([s.brdf.albedo, s.brdf.specular]);
    }

    /// The light's uniform pairs for rays `i..i + N`: drawn in lanes where they were left
    /// to be, else as asked.
    #[inline(always)]
    fn u<const N: usize>(&self, i: usize) -> (Lanes<N>, Lanes<N>) {
        debug_assert!(self.later.is_empty() || self.later.len() == self.nodes.len());
        match self.later.get(i..) {
            Some(later) if !later.is_empty() => sobol_pairs(&later[..later.len().min(N)]),
            _ => (self.columns.lane(i, U), self.columns.lane(i, U + 1)),
        }
    }
}

/// What a shadow ray gave its node: the light it adds (zero where it is blocked); `None`
/// where the light is behind the surface or faces away, and no ray was traced.
pub(super) struct Lit {
    pub(super) node: u32,
    pub(super) light: Option<Color>,
}

/// The shadow rays of a level, light by light (so that each node adds its lights in the
/// recursion's order), into `out` in that order.
pub(super) struct Shadows<'a, 't> {
    pub(super) tracer: &'a Tracer<'t>,
    // Per light, the shadow rays asked of it, in the order of the nodes.
    pub(super) asked: &'a [Asked],
    pub(super) out: &'a mut Vec<Lit>,
}

impl LaneKernel for Shadows<'_, '_> {
    type Output = ();
    #[inline(always)]
    fn run<const N: usize>(self) {
        let t = self.tracer;
        self.out.clear();
        for (light, asked) in t.lights.iter().zip(self.asked) {
            let base = light.base();
            let c = &asked.columns;
            let chunks = asked.nodes.chunks(N).zip(asked.colours.chunks(N));
            for (k, (nodes, colours)) in chunks.enumerate() {
                let i = k * N;
                let u = asked.u::<N>(i);
                // The waves ask only lights that aim at points (`Tracer::shadows_in_lanes`).
                let Some(q) = light.point_of::<Lanes<N>>(u) else {
                    continue;
                };
                let (dir, dist, factor, valid) = light.toward::<Lanes<N>>(c.lanes3(i, P), q);
                let (n, view) = (c.lanes3::<N>(i, N_SHADE), c.lanes3::<N>(i, VIEW));
                let (cos, faces) = faces_light::<Lanes<N>>(c.lanes3(i, N_GEOM), n, dir);
                let lit = valid & faces;
                let reach = dist * Lanes::splat(SHADOW_REACH);
                let blocked = if Lanes::any(lit) {
                    let rays = RayOf {
                        origin: c.lanes3(i, ORIGIN),
                        dir,
                        time: c.lane(i, TIME),
                    };
                    t.scene.occluded_lanes(rays, reach, !lit)
                } else {
                    !lit
                };
                let exponent = c.lane::<N>(i, EXPONENT);
                let shadows = nodes.iter().zip(colours).enumerate();
                self.out
                    .extend(shadows.map(|(j, (&node, &[albedo, specular]))| {
                        let light = (lit.0[j] != 0).then(|| {
                            if blocked.0[j] != 0 {
                                Color::ZERO
                            } else {
                                let brdf = Brdf {
                                    albedo,
                                    specular,
                                    exponent: exponent.0[j],
                                };
                                let f = brdf.eval(n.get(j), dir.get(j), view.get(j));
                                f * (base * factor.0[j]) * cos.0[j]
                            }
                        });
                        Lit { node, light }
                    }));
            }
        }
    }
}
