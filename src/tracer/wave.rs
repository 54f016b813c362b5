//! The ray tree as waves: the samples of a tile traced together, level by level, so that
//! the nearest-hit search of a whole level runs in SIMD lanes.
//!
//! Level 0 holds every camera ray of the samples; shading a level's hits (in order) queues
//! their reflected and refracted children as the next level, until a level is empty. Each
//! node keeps what the recursion would add up at it: its own light (emission, the lights'
//! shading, or the light or background its ray meets), its children with the weights their
//! radiance is multiplied by, and the transmittance along its segment. The sums are then
//! made from the deepest level up in exactly the recursion's order, so a sample's radiance
//! is the recursive walk's bit for bit wherever its random numbers are drawn in the same
//! order: always in the stochastic tree (one child a hit) and wherever a split tree draws
//! no numbers below a hit's first child before its second child draws (the numbers of a
//! sample are drawn level by level here, depth first there).
//!
//! The waves take the lecture's common case: the ray tree (not paths or photons), without
//! a polariser and without dispersion. The recursion ([`Tracer::sample`]) stays the
//! reference, and what the inspector records.

use super::lights::{Asked, Lit, Seen, Shadow, Shadows};
use super::media::transmittance;
use super::path::cross;
use super::shade::pick_lobe;
use super::surfaces::{Splits, Surfaces};
use super::{Branch, Media, Meet, NoRecorder, RayKind, Stats, Tracer, Walk};
use crate::camera::CameraSample;
use crate::geometry::PrimRef;
use crate::material::{Lobe, Side, Split};
use crate::math::lanes::{LaneKernel, Lanes, RayColumns, Width, asked_lanes};
use crate::math::rng::SobolLanes;
use crate::math::{Color, Pattern, Ray, SampleStream, offset_ray_origin};
use crate::params::TreeMode;
use crate::scene::Hit;
use std::ops::Range;

/// How the kernel walks each sample's ray tree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Traversal {
    /// One ray after another, depth first: the reference.
    Recursive,
    /// In waves of rays, level by level, the hit search `Width` rays at a time, where the
    /// scene and parameters allow ([`Tracer::traces_waves`]); recursively elsewhere.
    Waves(Width),
}

impl std::fmt::Display for Traversal {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        match self {
            Traversal::Recursive => write!(f, "recursively"),
            Traversal::Waves(w) => write!(
                f,
                "in waves, {} lane{} ({})",
                w.lanes(),
                if w.lanes() == 1 { "" } else { "s" },
                w.extension()
            ),
        }
    }
}

impl Traversal {
    /// How `tracer`'s samples are walked: this, where it [`Tracer::traces_waves`], else
    /// recursively.
    pub fn for_tracer(self, tracer: &Tracer) -> Traversal {
        if tracer.traces_waves() {
            self
        } else {
            Traversal::Recursive
        }
    }

    /// Waves at the widest width this processor runs ([`Width::best`]); the recursion
    /// where `RAYLAB_LANES` is 0 ([`asked_lanes`]).
    pub fn best() -> Traversal {
        match asked_lanes() {
            Some(0) => Traversal::Recursive,
            _ => Traversal::Waves(Width::best()),
        }
    }
}

/// What one sample of a wave gave: its radiance (NaN for a camera ray that could not be
/// traced) and how many rays it traced.
#[derive(Clone, Copy, Debug)]
pub struct Traced {
    /// The sample's radiance.
    pub radiance: Color,
    /// Its rays, of every kind.
    pub rays: u32,
}

/// Where a ray of a wave sits: its sample, the media it travels through (in the wave's
/// list of them), and its place in the tree. Kept beside the rays, which the hit search
/// reads on their own.
#[derive(Clone, Copy)]
pub(super) struct Node {
    // The sample of the wave it belongs to.
    slot: u32,
    pub(super) media: u32,
    depth: u32,
    weight: f32,
}

/// How a node's radiance is made: (local + Σ weight · L(child), over its children in
/// order) × tr, the transmittance along its segment (1 where nothing absorbs: 1 · x is x
/// bit for bit). A node whose ray meets a light or nothing has no children and tr 1.
struct Value {
    local: Color,
    tr: Color,
    children: Range<u32>,
}

/// A child of a node: what its radiance is multiplied by, and its node in the next level
/// (`None`: pruned, radiance 0).
struct Child {
    weight: Color,
    node: Option<u32>,
}

/// One level of the waves: how each node's radiance is made, and the children they list.
#[derive(Default)]
struct Level {
    values: Vec<Value>,
    children: Vec<Child>,
}

/// A sample's state while its tree is traced.
struct Slot {
    rng: SampleStream,
    tree_rays: u32,
    rays: u32,
}

/// The rays of one level and where each sits.
#[derive(Default)]
struct Rays {
    rays: RayColumns,
    nodes: Vec<Node>,
}

impl Rays {
    fn clear(&mut self) {
        self.rays.clear();
        self.nodes.clear();
    }

    fn push(&mut self, ray: &Ray, node: Node) -> u32 {
        self.rays.push(ray);
        self.nodes.push(node);
        self.nodes.len() as u32 - 1
    }
}

/// What is known of a node's surface before it is shaded: the hit (`None`: its ray met
/// nothing, or met a light whose record the lanes did not make), its distance, the area
/// light seen in front of it (its distance and radiance), the radiance the surface emits
/// where it is a light, and a dielectric's split where the lanes made it.
struct Surface<'s> {
    hit: Option<&'s Hit>,
    t: f32,
    seen: Option<(f32, Color)>,
    emitted: Option<Color>,
    split: Option<&'s Split>,
}

/// What waves work in, kept from one wave to the next so that a wave allocates nothing.
#[derive(Default)]
pub struct Waves {
    slots: Vec<Slot>,
    roots: Vec<Option<u32>>,
    level: Rays,
    next: Rays,
    // Every medium the wave's rays travel through: a reflected ray shares its parent's.
    media: Vec<Media>,
    nearest: Vec<Option<(PrimRef, f32)>>,
    hits: Vec<Option<Hit>>,
    seen: Vec<Option<(f32, Color)>>,
    emitted: Vec<Option<Color>>,
    on_dielectrics: Vec<u32>,
    splits: Vec<(u32, Split)>,
    // Per light, the level's shadow rays towards it; what they gave; and the nodes whose
    // sum of lights is then scaled, with the scale.
    shadows: Vec<Asked>,
    lit: Vec<Lit>,
    scaled: Vec<(u32, f32)>,
    levels: Vec<Level>,
    radiance: Vec<Color>,
    below: Vec<Color>,
    traced: Vec<Traced>,
}

/// Where a node's children go: the next level's rays, the media they enter, the list of the
/// level's children; and the shadow rays it asks for, traced after the level.
struct Queue<'q> {
    next: &'q mut Rays,
    media: &'q mut Vec<Media>,
    children: &'q mut Vec<Child>,
    shadows: &'q mut [Asked],
    scaled: &'q mut Vec<(u32, f32)>,
}

/// The camera rays of a wave, with each sample's random numbers after the camera's: with
/// the Sobol pattern, `N` at a time in lanes, the draws and the rays; with the others (the
/// sampling lecture's patterns), ray by ray.
struct CameraRays<'a, 't, F> {
    tracer: &'a Tracer<'t>,
    samples: &'a [(u32, u32, u32)],
    // Takes each sample's stream and ray, in order: where they are kept, so that they are
    // not built in one list and copied to another.
    out: F,
}

impl<F: FnMut(SampleStream, &Ray)> LaneKernel for CameraRays<'_, '_, F> {
    type Output = ();
    #[inline(always)]
    fn run<const N: usize>(mut self) {
        let t = self.tracer;
        let sobol = t.params.pattern == Pattern::Sobol;
        let in_lanes = if sobol { self.samples.len() / N * N } else { 0 };
        let (chunks, rest) = self.samples.split_at(in_lanes);
        for chunk in chunks.chunks_exact(N) {
            let pixels = std::array::from_fn(|i| chunk[i].1 * t.width + chunk[i].0);
            let numbers = std::array::from_fn(|i| chunk[i].2);
            let mut lanes = SobolLanes::<N>::new(t.params.spp, t.seed_key, pixels, numbers);
            let cs = t.frame.draw_samples(&mut lanes);
            let lane = |f: fn(&CameraSample) -> f32| Lanes::<N>::from_fn(|i| f(&cs[i]));
            let xy = (
                Lanes::from_fn(|i| chunk[i].0 as f32),
                Lanes::from_fn(|i| chunk[i].1 as f32),
            );
            let pixel = (lane(|c| c.pixel.x), lane(|c| c.pixel.y));
            let lens = (lane(|c| c.lens.x), lane(|c| c.lens.y));
            let (o, d, time) = t.camera_ray_of(xy, pixel, lens, lane(|c| c.time));
            // Each stream is made where it is stored: an array of them built first and
            // copied out stalls on store-to-load forwarding.
            for i in 0..N {
                let ray = Ray {
                    origin: o.get(i),
                    dir: d.get(i),
                    time: time.0[i],
                };
                (self.out)(lanes.stream(i), &ray);
            }
        }
        for &(x, y, s) in rest {
            let (rng, cs) = t.camera_draw(x, y, s);
            (self.out)(rng, &t.camera_ray(x, y, &cs));
        }
    }
}

impl Tracer<'_> {
    /// Whether the kernel traces this tracer's samples in waves: the ray tree, without a
    /// polariser or dispersion.
    pub fn traces_waves(&self) -> bool {
        !self.params.transport.traces_paths() && self.params.polarizer.is_none() && !self.dispersive
    }

    /// The samples `samples` ((x, y, sample number) each) traced together in waves, the hit
    /// search `width` rays at a time, in `waves`: what [`Tracer::sample`] gives for each.
    /// Only for a tracer that [`Tracer::traces_waves`].
    pub fn trace_wave<'w>(
        &self,
        samples: &[(u32, u32, u32)],
        width: Width,
        stats: &mut Stats,
        waves: &'w mut Waves,
    ) -> &'w [Traced] {
        let Waves {
            slots,
            roots,
            level,
            next,
            media,
            nearest,
            hits,
            seen,
            emitted,
            on_dielectrics,
            splits,
            shadows,
            lit,
            scaled,
            levels,
            radiance,
            below,
            traced,
        } = waves;
        slots.clear();
        roots.clear();
        shadows.resize_with(self.lights.len(), Asked::default);
        level.clear();
        media.clear();
        media.push(Media::default());
        let camera_ray = |rng: SampleStream, ray: &Ray| {
            stats.samples += 1;
            let camera = ray.origin.is_finite() && ray.dir.is_finite();
            let node = Node {
                slot: slots.len() as u32,
                media: 0,
                depth: 0,
                weight: 1.0,
            };
            roots.push(camera.then(|| level.push(ray, node)));
            stats.camera_rays += camera as u64;
            slots.push(Slot {
                rng,
                tree_rays: 0,
                rays: camera as u32,
            });
        };
        width.dispatch(CameraRays {
            tracer: self,
            samples,
            out: camera_ray,
        });
        let mut depth = 0;
        while !level.rays.is_empty() {
            self.scene.intersect_wave(&level.rays, width, nearest);
            width.dispatch(Seen {
                tracer: self,
                rays: &level.rays,
                nearest,
                out: seen,
            });
            width.dispatch(Surfaces {
                tracer: self,
                rays: &level.rays,
                nearest,
                hits,
                emitted,
                on_dielectrics,
            });
            width.dispatch(Splits {
                tracer: self,
                rays: &level.rays,
                nodes: &level.nodes,
                media,
                hits,
                on_dielectrics,
                splits,
            });
            if levels.len() == depth {
                levels.push(Level::default());
            }
            let Level { values, children } = &mut levels[depth];
            values.clear();
            children.clear();
            next.clear();
            shadows.iter_mut().for_each(Asked::clear);
            scaled.clear();
            let mut queue = Queue {
                next,
                media,
                children,
                shadows,
                scaled,
            };
            // The splits, in the order of the hits on dielectrics.
            let mut splits = splits.iter().peekable();
            let surfaces = level
                .nodes
                .iter()
                .zip(hits.iter().zip(nearest.iter()))
                .zip(seen.iter().zip(emitted.iter()));
            for (i, ((node, (hit, near)), (&seen, &emitted))) in surfaces.enumerate() {
                let split = splits.next_if(|(j, _)| *j as usize == i).map(|(_, s)| s);
                let slot = &mut slots[node.slot as usize];
                let surface = Surface {
                    hit: hit.as_ref(),
                    t: near.map_or(f32::INFINITY, |(_, t)| t),
                    seen,
                    emitted,
                    split,
                };
                values.push(self.shade_node(
                    &level.rays,
                    (i, node),
                    surface,
                    slot,
                    stats,
                    &mut queue,
                ));
            }
            if !scaled.is_empty() {
                width.dispatch(Shadows {
                    tracer: self,
                    asked: shadows,
                    out: lit,
                });
                for &Lit { node, light } in lit.iter() {
                    if let Some(light) = light {
                        values[node as usize].local += light;
                        stats.shadow_rays += 1;
                        slots[level.nodes[node as usize].slot as usize].rays += 1;
                    }
                }
                for &(node, scale) in scaled.iter() {
                    let value = &mut values[node as usize];
                    value.local = scale * value.local;
                }
            }
            std::mem::swap(level, next);
            depth += 1;
        }
        // The sums, from the deepest level up.
        below.clear();
        for level in levels[..depth].iter().rev() {
            radiance.clear();
            radiance.extend(level.values.iter().map(|v| {
                let mut l = v.local;
                for c in &level.children[v.children.start as usize..v.children.end as usize] {
                    l += c.weight * c.node.map_or(Color::ZERO, |n| below[n as usize]);
                }
                v.tr * l
            }));
            std::mem::swap(radiance, below);
        }
        traced.clear();
        traced.extend(roots.iter().zip(slots.iter()).map(|(root, slot)| Traced {
            radiance: root.map_or(Color::NAN, |r| below[r as usize]),
            rays: slot.rays,
        }));
        traced
    }

    /// What the recursion's `trace_in` does at `node` once its ray's `surface` is known
    /// (the hit, the radiance it emits, a dielectric's split where the lanes made it): the
    /// light it meets, or the hit's own light, with its children queued.
    #[inline(always)]
    fn shade_node(
        &self,
        rays: &RayColumns,
        (index, node): (usize, &Node),
        surface: Surface,
        slot: &mut Slot,
        stats: &mut Stats,
        queue: &mut Queue,
    ) -> Value {
        let Surface {
            hit,
            t,
            seen,
            emitted,
            split,
        } = surface;
        let media = &queue.media[node.media as usize];
        let sigma = self.absorption(media);
        let first = queue.children.len() as u32;
        let value = |local: Color, tr: Color, queue: &Queue| Value {
            local,
            tr,
            children: first..queue.children.len() as u32,
        };
        let along = |t: f32, l: Color| sigma.map_or(l, |s| transmittance(s, t) * l);
        if let Some((t, radiance)) = seen {
            return value(along(t, radiance), Color::ONE, queue);
        }
        if let Some(radiance) = emitted {
            // A light's node has no hit record (its distance is the nearest hit's).
            let tr = sigma.map_or(Color::ONE, |s| transmittance(s, t));
            return value(radiance, tr, queue);
        }
        // (Its ray is gathered from the columns only where it is needed.)
        let Some(hit) = hit else {
            let dir = rays.get(index).dir;
            let l = along(f32::INFINITY, self.scene.background.radiance(dir));
            return value(l, Color::ONE, queue);
        };
        let tr = sigma.map(|s| transmittance(s, hit.surface.t));
        let weight = tr.map_or(node.weight, |tr| node.weight * tr.max_element());
        let tr = tr.unwrap_or(Color::ONE);
        let ray = &rays.get(index);
        // The rays this node traces (none above, where its ray ends).
        let before = stats.total_rays();
        let at = self.interaction(ray, hit, media, None);
        let material = &self.materials[hit.material as usize];
        let mut rec = NoRecorder;
        let mut w = Walk {
            rng: &mut slot.rng,
            stats,
            rec: &mut rec,
            tree_rays: slot.tree_rays,
        };
        let scatter = match split {
            Some(split) => split.scatter(),
            None => material.scatter(&at, w.rng),
        };
        if scatter.total_internal_reflection {
            w.stats.tir_events += 1;
        }
        let local = match scatter.direct {
            // The lights' sum, kept to be completed and scaled once the level's shadow
            // rays are traced: their random numbers drawn here, in the recursion's order.
            Some(direct) if self.shadows_in_lanes => {
                let (p, n_geom) = (hit.surface.p, at.n_geom);
                let origin = offset_ray_origin(p, n_geom);
                for (light, asked) in self.lights.iter().zip(queue.shadows.iter_mut()) {
                    asked.push(&Shadow {
                        node: index as u32,
                        p,
                        origin,
                        n_geom,
                        n: at.n_shade,
                        view: -ray.dir,
                        time: ray.time,
                        u: light.draw(w.rng),
                        brdf: direct.brdf,
                    });
                }
                queue.scaled.push((index as u32, direct.scale));
                self.ambient(&direct)
            }
            Some(direct) => {
                let m = Meet {
                    ray,
                    hit,
                    media,
                    id: 0,
                };
                direct.scale * self.direct(m, &at, &direct, &mut w)
            }
            None => Color::ZERO,
        };
        // The child along `lobe`, if the pruning rules let it be traced: its node.
        let child =
            |lobe: &Lobe, factor: f32, weight: f32, w: &mut Walk<NoRecorder>, q: &mut Queue| {
                let branch = Branch {
                    depth: node.depth + 1,
                    weight,
                    kind: match lobe.side {
                        Side::Reflect => RayKind::Reflect,
                        Side::Transmit => RayKind::Refract,
                    },
                    parent: None,
                    factor,
                    wavelength: None,
                };
                if self.pruned(&branch, w.stats, &mut w.tree_rays).is_some() {
                    return None;
                }
                let (n_side, media) = match lobe.side {
                    Side::Reflect => (at.n_geom, node.media),
                    Side::Transmit => {
                        let mut beyond = q.media[node.media as usize];
                        let n_side = cross(&mut beyond, &at, hit, lobe.side);
                        q.media.push(beyond);
                        (n_side, q.media.len() as u32 - 1)
                    }
                };
                let ray = Ray {
                    origin: offset_ray_origin(hit.surface.p, n_side),
                    dir: lobe.dir,
                    time: ray.time,
                };
                let child = Node {
                    slot: node.slot,
                    media,
                    depth: branch.depth,
                    weight,
                };
                Some(q.next.push(&ray, child))
            };
        let lobes = scatter.lobes().count();
        if self.params.tree == TreeMode::Stochastic && lobes > 1 {
            // As `follow_one`: one lobe, with probability its branch weight.
            let mut all = scatter.lobes();
            if let Some(first) = all.next() {
                let (weight, node) =
                    if node.depth >= self.params.max_depth || weight < self.params.min_weight {
                        (Color::ONE, child(first, 1.0, weight, &mut w, queue))
                    } else {
                        match pick_lobe(first, all, w.rng.next_1d()) {
                            Some((chosen, tint)) => {
                                let f = tint.max_element();
                                (tint, child(chosen, f, weight * f, &mut w, queue))
                            }
                            None => (Color::ONE, None),
                        }
                    };
                queue.children.push(Child { weight, node });
            }
        } else {
            for lobe in scatter.lobes() {
                let factor = lobe.weight.max_element();
                if factor > 0.0 {
                    let node = child(lobe, factor, weight * factor, &mut w, queue);
                    queue.children.push(Child {
                        weight: lobe.weight,
                        node,
                    });
                }
            }
        }
        slot.tree_rays = w.tree_rays;
        slot.rays += (w.stats.total_rays() - before) as u32;
        value(local, tr, queue)
    }
}
