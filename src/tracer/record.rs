//! What the inspector records of a ray tree: every ray, what it met, the lecture's
//! quantities at each interface, and why it ended. The renderer records nothing
//! ([`NoRecorder`] compiles away); the inspector records a [`RayTree`].

use crate::material::{Interaction, Interface, Side};
use crate::math::{Color, Ray, Vec3};
use crate::scene::Hit;

/// The kind of a ray in the tree.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum RayKind {
    /// From the eye.
    Camera,
    /// Mirror, glossy or Fresnel reflection.
    Reflect,
    /// Refraction into or out of a dielectric.
    Refract,
    /// Towards a light.
    Shadow,
}

impl RayKind {
    /// The kind of a child ray on `side` of a surface.
    pub(super) fn of_side(side: Side) -> RayKind {
        match side {
            Side::Reflect => RayKind::Reflect,
            Side::Transmit => RayKind::Refract,
        }
    }
}

/// Why a branch of the ray tree ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum End {
    /// It left the scene: the background's radiance.
    Miss,
    /// It reached a light or an emitting surface.
    LightHit,
    /// It ended on a diffuse surface, whose shading (shadow rays) absorbs the rest.
    Absorbed,
    /// It split into child rays.
    Split,
    /// A path (path tracing) goes on from here in one direction, chosen at random.
    Continued,
    /// A path ended at random by Russian roulette (its survivors count for it).
    Roulette,
    /// Not traced: it would exceed the maximum depth.
    DepthLimit,
    /// Not traced: its path weight fell below the minimum.
    WeightLimit,
    /// Not traced: its camera sample has traced [`super::MAX_TREE_RAYS`] child rays.
    BudgetLimit,
    /// The refracted ray does not exist: total internal reflection.
    TotalInternalReflection,
    /// A shadow ray that reached its light.
    Lit,
    /// A shadow ray blocked on its way.
    Occluded,
}

impl End {
    /// Why the branch ended, in words.
    pub fn describe(self) -> &'static str {
        match self {
            End::Miss => "left the scene (background)",
            End::LightHit => "reached a light",
            End::Absorbed => "diffuse surface: shaded by shadow rays, absorbed",
            End::Split => "split into child rays",
            End::Continued => "the path goes on: one direction, chosen at random",
            End::Roulette => "ended by Russian roulette",
            End::DepthLimit => "pruned: depth limit",
            End::WeightLimit => "pruned: weight below the minimum",
            End::BudgetLimit => "pruned: the sample's ray budget is spent",
            End::TotalInternalReflection => "no refracted ray: total internal reflection",
            End::Lit => "reached its light",
            End::Occluded => "blocked: in shadow",
        }
    }
}

/// What a recorded ray met, with the lecture's quantities at a dielectric.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct NodeHit {
    /// The object hit.
    pub object: u32,
    /// Its material.
    pub material: u32,
    /// Where.
    pub point: Vec3,
    /// The unit shading normal there, facing the side the ray came from.
    pub normal: Vec3,
    /// Angle of incidence, degrees.
    pub theta_i: f32,
    /// At a dielectric: the angle of refraction (degrees), if it exists.
    pub theta_t: Option<f32>,
    /// At a dielectric or glaze: the indices n1 → n2.
    pub n1_n2: Option<(f32, f32)>,
    /// At a dielectric or glaze: the Fresnel amplitudes F_s, F_p.
    pub f_s_f_p: Option<(f32, f32)>,
    /// At a dielectric or glaze: the exact reflectance and Schlick's.
    pub r_exact_schlick: Option<(f32, f32)>,
    /// The reflectance R the tree used (by the current Fresnel model).
    pub r: Option<f32>,
}

/// One ray of a recorded tree.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct TreeNode {
    /// The node it branched from.
    pub parent: Option<usize>,
    /// What kind of ray.
    pub kind: RayKind,
    /// The ray (for a pruned branch, none was traced: its would-be direction).
    pub ray: Ray,
    /// Its level in the tree (camera rays 0).
    pub depth: u32,
    /// The factor its parent gave it (R, 1 − R, a reflectance).
    pub branch_weight: f32,
    /// The product of the factors from the camera down to it.
    pub path_weight: f32,
    /// What it met, if anything.
    pub hit: Option<NodeHit>,
    /// Where it ended (the hit point, or a point far along a miss).
    pub end_point: Vec3,
    /// Why it ended.
    pub end: End,
    /// The radiance it brought back.
    pub radiance: Color,
    /// With a polariser: how this ray's light is seen through it and every interface
    /// above, per Stokes component (I, Q, U, V) in the ray's s/p frame, green channel,
    /// relative to the unpolarised weights. Unpolarised light counts w₀; light polarised
    /// along s counts w₀ + w₁, along p w₀ − w₁.
    pub stokes_weights: Option<[f32; 4]>,
    /// The wavelength (nm) it carries since the first dispersive surface above it.
    pub wavelength: Option<f32>,
}

impl TreeNode {
    /// One line naming the ray: its kind (and wavelength), level, what it met (by the
    /// scene's `object_names` and `material_names`) and why it ended.
    pub fn title(&self, object_names: &[String], material_names: &[String]) -> String {
        let target = self.hit.map_or("nothing".to_string(), |h| {
            let name = |names: &[String], i: u32| {
                names.get(i as usize).map_or("?".to_string(), String::clone)
            };
            format!(
                "{} ({})",
                name(object_names, h.object),
                name(material_names, h.material)
            )
        });
        let colour = self
            .wavelength
            .map_or(String::new(), |l| format!(" at {l:.0} nm"));
        format!(
            "{:?} ray{colour}, level {}: {target} — {}",
            self.kind,
            self.depth,
            self.end.describe()
        )
    }

    /// The lecture's quantities of the ray, as (label, value) rows: at a hit the angles,
    /// indices, Fresnel amplitudes and reflectances; with a polariser its Stokes weights;
    /// always its weights and radiance.
    pub fn rows(&self) -> Vec<(&'static str, String)> {
        let mut rows = Vec::new();
        if let Some(h) = self.hit {
            rows.push(("θi", format!("{:.2}°", h.theta_i)));
            if let Some((n1, n2)) = h.n1_n2 {
                rows.push(("n1 -> n2", format!("{n1:.3} -> {n2:.3}")));
                rows.push((
                    "θt",
                    h.theta_t
                        .map_or("none (total internal reflection)".into(), |t| {
                            format!("{t:.2}°")
                        }),
                ));
            }
            if let Some((f_s, f_p)) = h.f_s_f_p {
                rows.push(("Fs, Fp", format!("{f_s:.4}, {f_p:.4}")));
            }
            if let Some((exact, schlick)) = h.r_exact_schlick {
                rows.push(("R exact, Schlick", format!("{exact:.4}, {schlick:.4}")));
            }
            if let Some(r) = h.r {
                rows.push(("R used", format!("{r:.4}")));
            }
        }
        if let Some([w0, w1, w2, w3]) = self.stokes_weights {
            rows.push((
                STOKES_ROW,
                format!("I {w0:.3}, Q {w1:+.3}, U {w2:+.3}, V {w3:+.3}"),
            ));
        }
        rows.push(("branch weight", format!("{:.4}", self.branch_weight)));
        rows.push(("path weight", format!("{:.4}", self.path_weight)));
        let c = self.radiance;
        rows.push(("radiance", format!("({:.3}, {:.3}, {:.3})", c.x, c.y, c.z)));
        rows
    }
}

/// The label of the row of a ray's Stokes weights (the window explains it on hover).
pub const STOKES_ROW: &str = "through the polariser";

/// Watches the ray tree being traced. The renderer uses [`NoRecorder`], for which all of
/// this compiles away; the inspector uses [`RayTree`].
pub trait Recorder {
    /// A ray about to be traced, its record built only when recording; returns its id.
    fn ray(&mut self, _node: impl FnOnce() -> TreeNode) -> usize {
        0
    }
    /// Amends a ray's record once its hit, end and radiance are known.
    fn finish(&mut self, _id: usize, _f: &dyn Fn(&mut TreeNode)) {}
    /// Whether anything is recorded (skips work done only for the record).
    fn on(&self) -> bool {
        false
    }
}

/// Records nothing.
pub struct NoRecorder;
impl Recorder for NoRecorder {}

/// The whole tree of one camera sample, in the order it was traced.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct RayTree {
    /// Every ray, parents before children.
    pub nodes: Vec<TreeNode>,
}

impl RayTree {
    /// Its camera rays: one, or one per wavelength through a lens whose glass disperses.
    pub fn roots(&self) -> impl Iterator<Item = usize> + '_ {
        self.nodes
            .iter()
            .enumerate()
            .filter(|(_, n)| n.parent.is_none())
            .map(|(id, _)| id)
    }

    /// The children of node `id`, in order.
    pub fn children(&self, id: usize) -> impl Iterator<Item = (usize, &TreeNode)> {
        self.nodes
            .iter()
            .enumerate()
            .filter(move |(_, n)| n.parent == Some(id))
    }
}

impl Recorder for RayTree {
    fn ray(&mut self, node: impl FnOnce() -> TreeNode) -> usize {
        let mut node = node();
        // A shadow ray leaves its parent's hit: one level below it.
        if node.kind == RayKind::Shadow
            && let Some(parent) = node.parent.and_then(|p| self.nodes.get(p))
        {
            node.depth = parent.depth + 1;
        }
        self.nodes.push(node);
        self.nodes.len() - 1
    }
    fn finish(&mut self, id: usize, f: &dyn Fn(&mut TreeNode)) {
        if let Some(n) = self.nodes.get_mut(id) {
            f(n);
        }
    }
    fn on(&self) -> bool {
        true
    }
}

/// Records the lecture's quantities at a dielectric interface hit by node `id`.
pub(super) fn record_interface<R: Recorder>(rec: &mut R, id: usize, i: Interface) {
    let Interface { cos_i, n1, n2, r } = i;
    let (f_s, f_p, r_exact) = crate::optics::fresnel_exact(cos_i, n1, n2);
    let theta_t = crate::optics::cos_transmitted(cos_i, n1, n2).map(|c| c.acos().to_degrees());
    let r_schlick = crate::optics::schlick(cos_i, n1, n2);
    rec.finish(id, &|n| {
        // The first wavelength's, where the tree splits into three at a dispersive surface
        // (the one its first children carry).
        if let Some(h) = n.hit.as_mut().filter(|h| h.n1_n2.is_none()) {
            h.theta_t = theta_t;
            h.n1_n2 = Some((n1, n2));
            h.f_s_f_p = Some((f_s, f_p));
            h.r_exact_schlick = Some((r_exact, r_schlick));
            h.r = Some(r);
        }
    });
}

/// Records where the ray of node `id` meets a surface, and at what angle. Inlined: with
/// no recorder it is nothing, not a call per hit.
#[inline(always)]
pub(super) fn record_hit<R: Recorder>(rec: &mut R, id: usize, hit: &Hit, at: &Interaction) {
    if rec.on() {
        let node_hit = NodeHit {
            object: hit.object,
            material: hit.material,
            point: hit.surface.p,
            normal: at.n_shade,
            theta_i: at.cos_i().acos().to_degrees(),
            theta_t: None,
            n1_n2: None,
            f_s_f_p: None,
            r_exact_schlick: None,
            r: None,
        };
        rec.finish(id, &|n| {
            n.hit.get_or_insert(node_hit);
        });
    }
}

/// The record of a shadow ray from node `parent`, reaching `dist` along `shadow` (its
/// light's point, or its blocker), with the light it brought.
pub(super) fn shadow_node(
    parent: usize,
    shadow: &Ray,
    dist: f32,
    blocked: bool,
    contribution: Color,
) -> TreeNode {
    TreeNode {
        parent: Some(parent),
        kind: RayKind::Shadow,
        ray: *shadow,
        // Set from the parent's when recorded.
        depth: 0,
        branch_weight: 1.0,
        path_weight: 0.0,
        hit: None,
        end_point: shadow.at(dist),
        end: if blocked { End::Occluded } else { End::Lit },
        radiance: contribution,
        stokes_weights: None,
        wavelength: None,
    }
}
