//! One node of the waves shaded: what the recursion's `trace_in` and `shade` do once the
//! node's surface is known. Its light (emission, the light or background its ray meets, the
//! lights' shading, with the shadow rays queued where they go to the lanes) and its
//! reflected and refracted children, queued as the next level's rays.

use super::lights::Shadow;
use super::types::{Child, Lights, Node, Queue, Slot, Surface, Value};
use crate::material::{Direct, Interaction, Lobe, Side, Split};
use crate::math::lanes::RayColumns;
use crate::math::{Color, Ray, SampleStream, Vec3, offset_ray_origin};
use crate::optics::dispersion;
use crate::scene::Hit;
use crate::tracer::media::Arrival;
use crate::tracer::shade::{Follow, child_ray};
use crate::tracer::spectral::Wavelengths;
use crate::tracer::{Branch, Meet, NoRecorder, RayKind, Stats, Tracer, Walk};

/// A node's hit being shaded: the node and its place in the level, its ray and the hit,
/// the wavelength it carries, and its path weight there (after the segment's
/// transmittance).
#[derive(Clone, Copy)]
struct AtNode<'a> {
    index: usize,
    node: &'a Node,
    ray: &'a Ray,
    hit: &'a Hit,
    wavelength: Option<f32>,
    weight: f32,
}

/// Where a node's children set out from: the node's hit, whether its ray arrived from the
/// surface's outside, and the geometric normal facing the ray.
#[derive(Clone, Copy)]
struct From<'a> {
    at: AtNode<'a>,
    entering: bool,
    n_geom: Vec3,
}

impl Tracer<'_> {
    /// What the recursion's `trace_in` does at a node once its `surface` is known
    /// (the hit, the radiance it emits, a dielectric's split where the lanes made it): the
    /// light it meets, or the hit's own light, with its children queued. `SPECTRAL`: the
    /// scene has a dispersive surface, where the node may split into its wavelengths
    /// (a constant, so that the waves of other scenes carry no wavelengths and make no
    /// checks for them: docs/performance.md, "Shaped by measurement").
    #[inline(always)]
    pub(super) fn shade_node<const SPECTRAL: bool>(
        &self,
        rays: &RayColumns,
        surface: Surface,
        slot: &mut Slot,
        stats: &mut Stats,
        queue: &mut Queue,
    ) -> Value {
        let Surface {
            index,
            node,
            hit,
            t,
            seen,
            emitted,
            split,
        } = surface;
        let segment = self.segment(&queue.media[node.media as usize]);
        let first = queue.children.len() as u32;
        let value = |local: Color, tr: Color, queue: &Queue| Value {
            local,
            tr,
            children: first..queue.children.len() as u32,
        };
        if let Some((t, radiance)) = seen {
            return value(segment.along(t, radiance), Color::ONE, queue);
        }
        if let Some(radiance) = emitted {
            // A light's node has no hit record (its distance is the nearest hit's).
            return value(radiance, segment.along(t, Color::ONE), queue);
        }
        // (Its ray is gathered from the columns only where it is needed.)
        let Some(hit) = hit else {
            let dir = rays.get(index).dir;
            let l = segment.along(f32::INFINITY, self.scene.background.radiance(dir));
            return value(l, Color::ONE, queue);
        };
        slot.met.material(hit.material);
        let ray = &rays.get(index);
        let wavelength = if SPECTRAL { node.wavelength() } else { None };
        let at = AtNode {
            index,
            node,
            ray,
            hit,
            wavelength,
            weight: node.weight,
        };
        if let Some(split) = split
            && !segment.absorbs()
        {
            let mut w = Walk {
                rng: &mut slot.rng,
                stats,
                rec: &mut NoRecorder,
                tree_rays: slot.tree_rays,
                met: slot.met,
            };
            let traced = self.split_children(at, split, &mut w, queue);
            slot.tree_rays = w.tree_rays;
            slot.met = w.met;
            slot.rays += traced;
            return value(Color::ZERO, Color::ONE, queue);
        }
        let material = &self.materials[hit.material as usize];
        if let Some(glow) = material.glow(hit.surface.uv) {
            queue.lights.glowing.push((index as u32, glow));
        }
        if !segment.absorbs()
            && self.shadows_in_lanes
            && let Some(direct) = material.direct_only(hit.surface.uv)
        {
            // A surface whose light is all it has (diffuse): its shadow rays queued, no
            // children, without an Interaction or a Scatter built for it.
            let f = Arrival::facing(ray.dir, &hit.surface);
            let lights = &mut queue.lights;
            let local =
                self.queue_shadows(&at, f.n_geom, f.n_shade, &direct, &mut slot.rng, lights);
            return value(local, Color::ONE, queue);
        }
        let (tr, weight) = segment.to_hit(hit.surface.t, node.weight);
        let tr = tr.unwrap_or(Color::ONE);
        let at = AtNode { weight, ..at };
        // The rays this node traces (none above, where its ray ends).
        let before = stats.total_rays();
        let mut rec = NoRecorder;
        let mut w = Walk {
            rng: &mut slot.rng,
            stats,
            rec: &mut rec,
            tree_rays: slot.tree_rays,
            met: slot.met,
        };
        let (local, tr) = if SPECTRAL && self.splits_into_wavelengths(hit.material, wavelength) {
            // The node splits into its wavelengths; their lights (if any) are traced
            // here, each summed into its own channel.
            let scatter = |lambda: f32, w: &mut Walk<NoRecorder>, queue: &mut Queue| {
                let at = AtNode {
                    wavelength: Some(lambda),
                    ..at
                };
                self.scatter_node(at, None, false, w, queue)
            };
            self.spectral_node(tr, &mut w, queue, scatter)
        } else {
            (self.scatter_node(at, split, true, &mut w, queue), tr)
        };
        slot.tree_rays = w.tree_rays;
        slot.met = w.met;
        slot.rays += (w.stats.total_rays() - before) as u32;
        value(local, tr, queue)
    }

    /// A node's hit `at` scattered by its material (or by the lanes' `split` of it): its
    /// children queued, its light returned, the shadow rays queued where `in_lanes` (else
    /// traced here).
    #[inline(always)]
    fn scatter_node(
        &self,
        at: AtNode,
        split: Option<&Split>,
        in_lanes: bool,
        w: &mut Walk<NoRecorder>,
        queue: &mut Queue,
    ) -> Color {
        let AtNode {
            ray,
            hit,
            node,
            wavelength,
            ..
        } = at;
        // (Read from the queue, whose list of media grows once the children are queued.)
        let media = &queue.media[node.media as usize];
        let m = Meet {
            ray,
            hit,
            media,
            id: 0,
        };
        let seen = self.interaction(ray, hit, media, wavelength);
        let scatter = match split {
            Some(split) => split.scatter(),
            None => self.materials[hit.material as usize].scatter(&seen, w.rng),
        };
        w.stats.count_tir(scatter.total_internal_reflection);
        let local = match scatter.direct {
            Some(direct) if in_lanes => {
                self.node_light(m, &at, &seen, &direct, w, &mut queue.lights)
            }
            Some(direct) => direct.scale * self.direct(m, &seen, &direct, w),
            None => Color::ZERO,
        };
        let from = From {
            at,
            entering: seen.entering,
            n_geom: seen.n_geom,
        };
        self.queue_children(&from, &scatter.lobes, w, queue);
        local
    }

    /// The lights' shading of the node's hit `at` (met as `m`, seen by its material as
    /// `seen`; a `direct` term): where shadow rays go to the lanes, the node's ambient
    /// term, its shadow rays queued in `lights` per light (their random numbers drawn here,
    /// in the recursion's order) to be completed and scaled after the level; else the
    /// whole sum, traced here.
    #[inline(always)]
    fn node_light(
        &self,
        m: Meet,
        at: &AtNode,
        seen: &Interaction,
        direct: &Direct,
        w: &mut Walk<NoRecorder>,
        lights: &mut Lights,
    ) -> Color {
        if !self.shadows_in_lanes {
            return direct.scale * self.direct(m, seen, direct, w);
        }
        self.queue_shadows(at, seen.n_geom, seen.n_shade, direct, w.rng, lights)
    }

    /// The shadow rays of a node's hit `at` with the normals `n_geom` and `n_shade` facing
    /// its ray, shaded by `direct`: queued in `lights` per light (their random numbers
    /// drawn here, in the recursion's order), the node listed to be scaled after the level;
    /// its ambient term returned.
    #[inline(always)]
    fn queue_shadows(
        &self,
        at: &AtNode,
        n_geom: Vec3,
        n_shade: Vec3,
        direct: &Direct,
        rng: &mut SampleStream,
        lights: &mut Lights,
    ) -> Color {
        let AtNode {
            index, ray, hit, ..
        } = *at;
        let p = hit.surface.p;
        let origin = offset_ray_origin(p, n_geom);
        for (light, asked) in self.lights.iter().zip(lights.shadows.iter_mut()) {
            asked.push(&Shadow {
                node: index as u32,
                p,
                origin,
                n_geom,
                n: n_shade,
                view: -ray.dir,
                time: ray.time,
                u: light.draw_or_later(rng),
                brdf: direct.brdf,
            });
        }
        lights.scaled.push((index as u32, direct.scale));
        self.ambient(direct)
    }

    /// The children of the node `from` along `lobes` (a scatter's child rays), as the
    /// recursion's `shade` traces them ([`Tracer::children`]): each listed in
    /// `queue.children`, and queued as a ray where the pruning rules let it be traced.
    #[inline(always)]
    fn queue_children(
        &self,
        from: &From,
        lobes: &[Option<Lobe>; 2],
        w: &mut Walk<NoRecorder>,
        queue: &mut Queue,
    ) {
        for f in self.children(lobes, queue.depth, from.at.weight, w.rng) {
            let node = self.queue_child(from, &f, w, queue);
            queue.children.push(Child {
                weight: f.tint,
                node,
            });
        }
    }

    /// The children of a node's hit `at` on a dielectric whose split the lanes made, where
    /// nothing absorbs: its reflected and refracted lobes (R and 1 − R) queued as
    /// `queue_children` queues any scatter's, without the scatter built. Returns the rays
    /// it queued.
    #[inline(always)]
    fn split_children(
        &self,
        at: AtNode,
        split: &Split,
        w: &mut Walk<NoRecorder>,
        queue: &mut Queue,
    ) -> u32 {
        let f = Arrival::facing(at.ray.dir, &at.hit.surface);
        let from = From {
            at,
            entering: f.entering,
            n_geom: f.n_geom,
        };
        w.stats.count_tir(split.total_internal_reflection());
        let before = w.stats.total_rays();
        self.queue_children(&from, &split.lobes(), w, queue);
        (w.stats.total_rays() - before) as u32
    }

    /// The child `f` of `from`, if the pruning rules let it be traced: its node in the
    /// next level, its ray queued, and the media it enters where it crosses the surface.
    #[inline(always)]
    fn queue_child(
        &self,
        from: &From,
        f: &Follow,
        w: &mut Walk<NoRecorder>,
        q: &mut Queue,
    ) -> Option<u32> {
        let From {
            at:
                AtNode {
                    node,
                    ray,
                    hit,
                    wavelength,
                    ..
                },
            entering,
            n_geom,
        } = *from;
        let branch = Branch {
            depth: q.depth + 1,
            weight: f.weight,
            kind: RayKind::of_side(f.lobe.side),
            parent: None,
            factor: f.factor,
            wavelength,
        };
        if self
            .pruned(&branch, w.stats, &mut w.tree_rays, &mut w.met)
            .is_some()
        {
            return None;
        }
        let media = match f.lobe.side {
            Side::Reflect => node.media,
            Side::Transmit => {
                let beyond = q.media[node.media as usize].crossed(entering, hit);
                q.media.push(beyond);
                q.media.len() as u32 - 1
            }
        };
        let ray = child_ray(hit.surface.p, n_geom, f.lobe, ray.time);
        let child = Node::new(node.slot, media, f.weight, wavelength);
        Some(q.next.push(&ray, child))
    }

    /// `shade_spectral` for a node of the waves, whose segment's transmittance is `tr`:
    /// `scatter` shades its hit at one wavelength, queueing that wavelength's children.
    /// Returns the node's light and the factor its sum is multiplied by, so that the
    /// level-by-level sums give the recursion's radiance bit for bit: in the split tree,
    /// each wavelength's light in its own channel and its children's weights kept to that
    /// channel only (the other channels add exact zeros); in the stochastic tree, the
    /// channel weight folded into `tr` (exactly the recursion's where nothing absorbs,
    /// tr = 1; within a rounding where something does).
    // (Out of line: a node of its own kind, once per sample.)
    #[inline(never)]
    pub(super) fn spectral_node(
        &self,
        tr: Color,
        w: &mut Walk<NoRecorder>,
        queue: &mut Queue,
        scatter: impl Fn(f32, &mut Walk<NoRecorder>, &mut Queue) -> Color,
    ) -> (Color, Color) {
        match self.wavelengths(w.rng) {
            Wavelengths::One(lambda) => {
                let local = scatter(lambda, w, queue);
                (local, tr * dispersion::channel_weight(lambda))
            }
            Wavelengths::PerChannel(lambdas) => {
                let mut sum = Color::ZERO;
                for (c, lambda) in lambdas.into_iter().enumerate() {
                    let first = queue.children.len();
                    let l = scatter(lambda, w, queue);
                    sum[c] = l[c];
                    for child in &mut queue.children[first..] {
                        let mut only = Color::ZERO;
                        only[c] = child.weight[c];
                        child.weight = only;
                    }
                }
                (sum, tr)
            }
        }
    }
}
