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
//! The waves take the lecture's ray tree (not paths or photons), without a polariser; a
//! dispersive surface splits a node into its wavelengths as the recursion splits its tree
//! (`tracer/spectral.rs`). The recursion ([`Tracer::sample`]) stays the reference, and
//! what the inspector records.

use super::lights::{Asked, Lit, Seen, Shadows};
use super::surfaces::{Hits, Splits, Surfaces};
use super::{Media, Stats, Tracer};
use crate::camera::CameraSample;
use crate::geometry::PrimRef;
use crate::material::Split;
use crate::math::lanes::{LaneKernel, Lanes, RayColumns, Real, V3, Width, asked_lanes, is_finite};
use crate::math::rng::SobolLanes;
use crate::math::{Color, Pattern, Ray, SampleStream};
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
/// list of them), its path weight, and the wavelength it carries since its first
/// dispersive surface. Its depth in the tree is its level's. Kept beside the rays, which
/// the hit search reads on their own; 16 bytes (with the depth and an `Option` it was 24,
/// and glass slides were 3 % slower).
#[derive(Clone, Copy)]
pub(super) struct Node {
    // The sample of the wave it belongs to.
    pub(super) slot: u32,
    pub(super) media: u32,
    pub(super) weight: f32,
    // The wavelength in nm; 0: none.
    wavelength: f32,
}

impl Node {
    /// A node of `slot`'s tree in `media` with path weight `weight`, carrying
    /// `wavelength`.
    #[inline(always)]
    pub(super) fn new(slot: u32, media: u32, weight: f32, wavelength: Option<f32>) -> Node {
        Node {
            slot,
            media,
            weight,
            wavelength: wavelength.unwrap_or(0.0),
        }
    }

    /// The wavelength (nm) it carries, if it has met a dispersive surface.
    #[inline(always)]
    pub(super) fn wavelength(&self) -> Option<f32> {
        (self.wavelength > 0.0).then_some(self.wavelength)
    }
}

/// How a node's radiance is made: (local + Σ weight · L(child), over its children in
/// order) × tr, the transmittance along its segment (1 where nothing absorbs: 1 · x is x
/// bit for bit). A node whose ray meets a light or nothing has no children and tr 1.
pub(super) struct Value {
    pub(super) local: Color,
    pub(super) tr: Color,
    pub(super) children: Range<u32>,
}

/// A child of a node: what its radiance is multiplied by, and its node in the next level
/// (`None`: pruned, radiance 0).
pub(super) struct Child {
    pub(super) weight: Color,
    pub(super) node: Option<u32>,
}

/// One level of the waves: how each node's radiance is made, and the children they list.
#[derive(Default)]
struct Level {
    values: Vec<Value>,
    children: Vec<Child>,
}

/// A sample's state while its tree is traced.
pub(super) struct Slot {
    pub(super) rng: SampleStream,
    pub(super) tree_rays: u32,
    pub(super) rays: u32,
}

/// The rays of one level and where each sits.
#[derive(Default)]
pub(super) struct Rays {
    pub(super) rays: RayColumns,
    pub(super) nodes: Vec<Node>,
}

impl Rays {
    fn clear(&mut self) {
        self.rays.clear();
        self.nodes.clear();
    }

    pub(super) fn push(&mut self, ray: &Ray, node: Node) -> u32 {
        self.rays.push(ray);
        self.nodes.push(node);
        self.nodes.len() as u32 - 1
    }
}

/// What is known of a node's surface before it is shaded: the hit (`None`: its ray met
/// nothing, or met a light whose record the lanes did not make), its distance, the area
/// light seen in front of it (its distance and radiance), the radiance the surface emits
/// where it is a light, and a dielectric's split where the lanes made it.
pub(super) struct Surface<'s> {
    pub(super) hit: Option<&'s Hit>,
    pub(super) t: f32,
    pub(super) seen: Option<(f32, Color)>,
    pub(super) emitted: Option<Color>,
    pub(super) split: Option<&'s Split>,
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
    hits: Hits,
    seen: Vec<Option<(f32, Color)>>,
    emitted: Vec<Option<Color>>,
    on_dielectrics: Vec<u32>,
    // The splits the hit records' lanes made (of `N` rays on one dielectric), and those
    // made of the other hits on dielectrics, each with its place in the level.
    lane_splits: Vec<(u32, Split)>,
    splits: Vec<(u32, Split)>,
    // Per light, the level's shadow rays towards it; what they gave; the nodes whose
    // sum of lights is then scaled, with the scale; and the glowing nodes, with their glow.
    shadows: Vec<Asked>,
    lit: Vec<Lit>,
    scaled: Vec<(u32, f32)>,
    glowing: Vec<(u32, Color)>,
    levels: Vec<Level>,
    radiance: Vec<Color>,
    below: Vec<Color>,
    traced: Vec<Traced>,
}

/// Where a node's children go: the level below `depth`, its rays, the media they enter, the
/// list of the level's children; and the shadow rays it asks for, traced after the level.
pub(super) struct Queue<'q> {
    // The depth of the level whose children these are.
    pub(super) depth: u32,
    pub(super) next: &'q mut Rays,
    pub(super) media: &'q mut Vec<Media>,
    pub(super) children: &'q mut Vec<Child>,
    pub(super) lights: Lights<'q>,
}

/// The shadow rays a level's nodes ask for, per light, the nodes whose sum of lights is
/// then scaled, with the scale, and the nodes on glowing surfaces, with the glow added
/// after that (as the recursion adds it after the lights).
pub(super) struct Lights<'q> {
    pub(super) shadows: &'q mut [Asked],
    pub(super) scaled: &'q mut Vec<(u32, f32)>,
    pub(super) glowing: &'q mut Vec<(u32, Color)>,
}

/// The camera rays of a wave, with each sample's random numbers after the camera's, into
/// its slots, roots and level 0: with the Sobol pattern, `N` at a time in lanes, the draws
/// and the rays; with the others (the sampling lecture's patterns), ray by ray.
struct CameraRays<'a, 't> {
    tracer: &'a Tracer<'t>,
    samples: &'a [(u32, u32, u32)],
    stats: &'a mut Stats,
    slots: &'a mut Vec<Slot>,
    roots: &'a mut Vec<Option<u32>>,
    level: &'a mut Rays,
}

impl CameraRays<'_, '_> {
    /// A sample's slot (its stream `rng`), and its root: its camera ray's node, if the ray
    /// can be traced (`ray` finite; `None`: not).
    #[inline(always)]
    fn push(&mut self, rng: SampleStream, ray: Option<&Ray>) {
        let node = ray.map(|ray| {
            let node = Node::new(self.slots.len() as u32, 0, 1.0, None);
            self.level.push(ray, node)
        });
        self.push_slot(rng, node);
    }

    #[inline(always)]
    fn push_slot(&mut self, rng: SampleStream, root: Option<u32>) {
        self.stats.samples += 1;
        self.stats.camera_rays += root.is_some() as u64;
        self.roots.push(root);
        self.slots.push(Slot {
            rng,
            tree_rays: 0,
            rays: root.is_some() as u32,
        });
    }
}

impl LaneKernel for CameraRays<'_, '_> {
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
            let finite = |v: V3<Lanes<N>>| is_finite(v.x) & is_finite(v.y) & is_finite(v.z);
            // Each stream is made where it is stored: an array of them built first and
            // copied out stalls on store-to-load forwarding.
            if Lanes::all(finite(o) & finite(d)) {
                // The usual case: the rays go to the level as they are, `N` at a time.
                let first = self.level.nodes.len() as u32;
                let slot = self.slots.len() as u32;
                self.level.rays.push_lanes((o, d, time));
                let node = |i| Node::new(slot + i, 0, 1.0, None);
                self.level.nodes.extend((0..N as u32).map(node));
                // (Counted once for the `N`: an add to memory per sample waited on the last.)
                self.stats.samples += N as u64;
                self.stats.camera_rays += N as u64;
                self.roots.extend((first..first + N as u32).map(Some));
                self.slots.extend((0..N).map(|i| Slot {
                    rng: lanes.stream(i),
                    tree_rays: 0,
                    rays: 1,
                }));
            } else {
                for i in 0..N {
                    let ray = Ray {
                        origin: o.get(i),
                        dir: d.get(i),
                        time: time.0[i],
                    };
                    let traced = ray.origin.is_finite() && ray.dir.is_finite();
                    self.push(lanes.stream(i), traced.then_some(&ray));
                }
            }
        }
        for &(x, y, s) in rest {
            let (rng, cs) = t.camera_draw(x, y, s);
            let ray = t.camera_ray(x, y, &cs);
            let traced = ray.origin.is_finite() && ray.dir.is_finite();
            self.push(rng, traced.then_some(&ray));
        }
    }
}

/// The most lights a scene traced in waves has. A wave's level keeps a shadow ray for
/// every node and light until its shading is done (about 100 bytes each): a level of 4096
/// nodes keeps 26 MB at this count, where 250,000 lights kept gigabytes per thread. A
/// scene of more lights is traced by the recursion, which gives the same image and keeps
/// one node's shadow rays at a time.
pub const MAX_WAVE_LIGHTS: usize = 64;

impl Tracer<'_> {
    /// Whether the kernel traces this tracer's samples in waves: the ray tree, without a
    /// polariser, in a scene of at most [`MAX_WAVE_LIGHTS`] lights.
    pub fn traces_waves(&self) -> bool {
        !self.params.transport.traces_paths()
            && self.params.polarizer.is_none()
            && self.lights.len() <= MAX_WAVE_LIGHTS
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
        if self.dispersive {
            self.waves::<true>(samples, width, stats, waves)
        } else {
            self.waves::<false>(samples, width, stats, waves)
        }
    }

    /// [`Tracer::trace_wave`], with nodes that may split into wavelengths where `SPECTRAL`
    /// (a scene with a dispersive surface; see `shade_node`).
    fn waves<'w, const SPECTRAL: bool>(
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
            lane_splits,
            splits,
            shadows,
            lit,
            scaled,
            glowing,
            levels,
            radiance,
            below,
            traced,
        } = waves;
        shadows.resize_with(self.lights.len(), Asked::default);
        media.clear();
        media.push(Media::default());
        self.camera_level(samples, width, stats, (slots, roots, level));
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
                nodes: &level.nodes,
                media,
                hits,
                emitted,
                on_dielectrics,
                splits: lane_splits,
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
            glowing.clear();
            let mut queue = Queue {
                depth: depth as u32,
                next,
                media,
                children,
                lights: Lights {
                    shadows,
                    scaled,
                    glowing,
                },
            };
            // The splits, each list in the order of the level.
            let mut splits = splits.iter().peekable();
            let mut lane_splits = lane_splits.iter().peekable();
            let surfaces = level
                .nodes
                .iter()
                .zip(hits.iter().zip(nearest.iter()))
                .zip(seen.iter().zip(emitted.iter()));
            for (i, ((node, (hit, near)), (&seen, &emitted))) in surfaces.enumerate() {
                // (Only a node with a hit record may have a split.)
                let at_i = |(j, _): &&(u32, Split)| *j as usize == i;
                let split = hit
                    .and_then(|_| lane_splits.next_if(at_i).or_else(|| splits.next_if(at_i)))
                    .map(|(_, s)| s);
                let slot = &mut slots[node.slot as usize];
                let surface = Surface {
                    hit,
                    t: near.map_or(f32::INFINITY, |(_, t)| t),
                    seen,
                    emitted,
                    split,
                };
                values.push(self.shade_node::<SPECTRAL>(
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
                add_lights((lit, scaled), values, &level.nodes, slots, stats);
            }
            for &(node, glow) in glowing.iter() {
                values[node as usize].local += glow;
            }
            std::mem::swap(level, next);
            depth += 1;
        }
        sum_levels(&levels[..depth], radiance, below);
        traced.clear();
        traced.extend(roots.iter().zip(slots.iter()).map(|(root, slot)| Traced {
            radiance: root.map_or(Color::NAN, |r| below[r as usize]),
            rays: slot.rays,
        }));
        traced
    }

    /// Level 0 of a wave: the camera ray of each of `samples` (made `width` at a time),
    /// each sample's slot, and its root node (`None`: its camera ray could not be traced).
    fn camera_level(
        &self,
        samples: &[(u32, u32, u32)],
        width: Width,
        stats: &mut Stats,
        (slots, roots, level): (&mut Vec<Slot>, &mut Vec<Option<u32>>, &mut Rays),
    ) {
        slots.clear();
        roots.clear();
        level.clear();
        width.dispatch(CameraRays {
            tracer: self,
            samples,
            stats,
            slots,
            roots,
            level,
        });
    }
}

/// Completes a level's lights once its shadow rays are traced: each node's lights added in
/// order (`lit`, each shadow ray counted to its sample), then each lit node's sum scaled
/// (`scaled`), as `Tracer::direct` does.
fn add_lights(
    (lit, scaled): (&[Lit], &[(u32, f32)]),
    values: &mut [Value],
    nodes: &[Node],
    slots: &mut [Slot],
    stats: &mut Stats,
) {
    for &Lit { node, light } in lit {
        if let Some(light) = light {
            values[node as usize].local += light;
            stats.shadow_rays += 1;
            slots[nodes[node as usize].slot as usize].rays += 1;
        }
    }
    for &(node, scale) in scaled {
        let value = &mut values[node as usize];
        value.local = scale * value.local;
    }
}

/// The radiance of the nodes of the first of `levels` into `below`, summed from the
/// deepest level up: each node's (local + Σ weight · L(child)) × tr, its children in
/// order, as the recursion adds them.
fn sum_levels(levels: &[Level], radiance: &mut Vec<Color>, below: &mut Vec<Color>) {
    below.clear();
    for level in levels.iter().rev() {
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
}
