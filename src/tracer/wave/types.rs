//! What the waves are made of: a ray's node (its sample, media, path weight, wavelength),
//! how a node's radiance is made from its own light and its children, a level's rays, a
//! sample's state, what is known of a node's surface before it is shaded, and where a
//! node's children and shadow rays are queued.

use super::lights::Asked;
use crate::material::Split;
use crate::math::lanes::RayColumns;
use crate::math::{Color, Ray, SampleStream};
use crate::scene::Hit;
use crate::tracer::{Media, Met};
use std::ops::Range;

/// Where a ray of a wave sits: its sample, the media it travels through (in the wave's
/// list of them), its path weight, and the wavelength it carries since its first
/// dispersive surface. Its depth in the tree is its level's. Kept beside the rays, which
/// the hit search reads on their own; 16 bytes (with the depth and an `Option` it would be
/// 24, and slower: docs/performance.md, "Shaped by measurement").
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
pub(super) struct Level {
    pub(super) values: Vec<Value>,
    pub(super) children: Vec<Child>,
}

/// A sample's camera rays among level 0's nodes, and how its radiance is made from
/// theirs. Each ray is its node and what it counts for (its camera weight); no node: black
/// where the lens blocked it (weight 0), NaN where it could not be traced.
#[derive(Clone, Copy, Debug)]
pub(super) enum Root {
    /// One camera ray: its radiance times the slot's weight.
    One(Option<u32>),
    /// Through a dispersive lens in the split tree: one ray per colour channel at a
    /// wavelength in its box, each bringing back its own channel.
    PerChannel([(Option<u32>, f32); 3]),
    /// Through a dispersive lens in the stochastic tree: one ray at one wavelength over the
    /// spectrum, times its channel weight.
    Spectrum((Option<u32>, f32), Color),
}

/// A sample's state while its tree is traced.
pub(super) struct Slot {
    pub(super) rng: SampleStream,
    // What its radiance counts for: its camera ray's weight (1 but through a real lens;
    // 0 where the lens blocked it).
    pub(super) weight: f32,
    pub(super) tree_rays: u32,
    pub(super) rays: u32,
    // What the sample met that a parameter governs.
    pub(super) met: Met,
}

/// The rays of one level and where each sits.
#[derive(Default)]
pub(super) struct Rays {
    pub(super) rays: RayColumns,
    pub(super) nodes: Vec<Node>,
}

impl Rays {
    pub(super) fn clear(&mut self) {
        self.rays.clear();
        self.nodes.clear();
    }

    pub(super) fn push(&mut self, ray: &Ray, node: Node) -> u32 {
        self.rays.push(ray);
        self.nodes.push(node);
        self.nodes.len() as u32 - 1
    }
}

/// A node of a level (its place in the level, and where it sits) and what is known of its
/// surface before it is shaded: the hit (`None`: its ray met nothing, or met a light whose
/// record the lanes did not make), its distance, the area light seen in front of it (its
/// distance and radiance), the radiance the surface emits where it is a light, and a
/// dielectric's split where the lanes made it.
pub(super) struct Surface<'s> {
    pub(super) index: usize,
    pub(super) node: &'s Node,
    pub(super) hit: Option<&'s Hit>,
    pub(super) t: f32,
    pub(super) seen: Option<(f32, Color)>,
    pub(super) emitted: Option<Color>,
    pub(super) split: Option<&'s Split>,
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
