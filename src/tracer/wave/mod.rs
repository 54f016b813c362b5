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
//! (`tracer/spectral.rs`), and a lens whose glass disperses gives a sample a camera ray per
//! wavelength, each a root of its own (`camera.rs`). The recursion ([`Tracer::sample`]) stays the reference, and
//! what the inspector records. Both walks ask the same functions for each rule of the
//! tree (which children a hit has, the media a child crosses into, the shadow rays' tests,
//! the transmittance along a segment, the wavelength split), so that they cannot part.
//!
//! Here the walk, level by level; `camera.rs` makes level 0, `hits.rs` a level's hit
//! records and dielectric splits in lanes, `shade.rs` shades one node and queues its
//! children, `lights.rs` finds the area lights seen and traces the shadow rays in lanes,
//! and `types.rs` holds what they share.

mod camera;
mod hits;
mod lights;
mod shade;
mod types;

use crate::geometry::PrimRef;
use crate::material::Split;
use crate::math::Color;
use crate::math::lanes::{Width, asked_lanes};
use crate::tracer::{Media, Met, Stats, Tracer};
use camera::CameraRays;
use hits::{Hits, Splits, Surfaces};
use lights::{Asked, Lit, Seen, Shadows};
use types::{Level, Lights, Node, Queue, Rays, Root, Slot, Surface, Value};

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
    /// What it met that a parameter governs.
    pub met: Met,
}

/// What waves work in, kept from one wave to the next so that a wave allocates nothing.
#[derive(Default)]
pub struct Waves {
    slots: Vec<Slot>,
    roots: Vec<Root>,
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
        width.dispatch(CameraRays {
            tracer: self,
            samples,
            stats,
            slots,
            roots,
            level,
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
                    index: i,
                    node,
                    hit,
                    t: near.map_or(f32::INFINITY, |(_, t)| t),
                    seen,
                    emitted,
                    split,
                };
                values.push(self.shade_node::<SPECTRAL>(
                    &level.rays,
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
                add_lights(lit, scaled, values, &level.nodes, slots, stats);
            }
            for &(node, glow) in glowing.iter() {
                values[node as usize].local += glow;
            }
            std::mem::swap(level, next);
            depth += 1;
        }
        sum_levels(&levels[..depth], radiance, below);
        sample_results(roots, slots, below, traced);
        traced
    }
}

/// Each sample's result from its roots' sums (`below`): the camera's weight applied as the
/// recursion applies it (× 1 through the thin lens); black where a real lens blocked the
/// ray, NaN for one that could not be traced; through a dispersive lens, each channel from
/// its wavelength's ray, or the one wavelength's times its channel weight, as
/// `Tracer::sample_through_dispersive_lens` makes them.
fn sample_results(roots: &[Root], slots: &[Slot], below: &[Color], traced: &mut Vec<Traced>) {
    let of = |(root, weight): (Option<u32>, f32)| match root {
        Some(r) => below[r as usize] * weight,
        None if weight == 0.0 => Color::ZERO,
        None => Color::NAN,
    };
    traced.clear();
    traced.extend(roots.iter().zip(slots).map(|(root, slot)| Traced {
        radiance: match *root {
            Root::One(r) => of((r, slot.weight)),
            Root::PerChannel(rays) => {
                let mut sum = Color::ZERO;
                for (c, ray) in rays.into_iter().enumerate() {
                    sum[c] = of(ray)[c];
                }
                sum
            }
            Root::Spectrum(ray, channel_weight) => channel_weight * of(ray),
        },
        rays: slot.rays,
        met: slot.met,
    }));
}

/// Completes a level's lights once its shadow rays are traced: each node's lights added in
/// order (`lit`, each shadow ray counted to its sample), then each lit node's sum scaled
/// (`scaled`), as `Tracer::direct` does.
fn add_lights(
    lit: &[Lit],
    scaled: &[(u32, f32)],
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
