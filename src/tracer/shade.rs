//! A hit's share of the ray tree: the material's emission, its shading by the lights, and
//! its reflected and refracted child rays, all of them (the lecture's split tree) or one
//! chosen by its weight (the stochastic tree), each pruned by depth, weight and budget.

use super::polarized::Polarization;
use super::record::{record_hit, record_interface};
use super::{
    Branch, End, MAX_TREE_RAYS, Media, Meet, Met, RayKind, Recorder, Stats, Tracer, TreeNode, Walk,
};
use crate::material::{Lobe, Side};
use crate::math::{Color, Ray, SampleStream, Vec3, offset_ray_origin};
use crate::params::TreeMode;

impl Tracer<'_> {
    /// The radiance leaving `hit` back along `ray`: a light's emission (which ends the ray),
    /// else its shading by the lights, its glow, and its child rays, walked as the tree
    /// mode says.
    #[inline(always)]
    pub(super) fn shade<R: Recorder, P: Polarization>(
        &self,
        m: Meet,
        b: Branch,
        w: &mut Walk<R>,
        pol: &P,
    ) -> (Color, End) {
        let Meet {
            ray,
            hit,
            media,
            id,
        } = m;
        let s = &hit.surface;
        let at = self.interaction(ray, hit, media, b.wavelength);
        let (entering, n_geom) = (at.entering, at.n_geom);
        record_hit(w.rec, id, hit, &at);
        let material = &self.materials[hit.material as usize];
        if let Some(radiance) = material.light_emission(at.uv) {
            return (pol.seen(radiance), End::LightHit);
        }
        w.met.material(hit.material);
        let scatter = material.scatter(&at, w.rng);
        // The polariser's analyzer in this interface's s/p frame.
        let s_frame = pol.at_interface(ray.dir, at.n_shade);
        let child_ray = |lobe: &Lobe| child_ray(s.p, n_geom, lobe, ray.time);
        w.stats.count_tir(scatter.total_internal_reflection);
        if w.rec.on() {
            if let Some(i) = scatter.interface {
                record_interface(w.rec, id, i);
            }
            if scatter.total_internal_reflection {
                // The refracted branch that total internal reflection forbids.
                let reflected = scatter.lobes().next().map_or(*ray, child_ray);
                w.rec.ray(|| TreeNode {
                    parent: Some(id),
                    kind: RayKind::Refract,
                    ray: reflected,
                    depth: b.depth + 1,
                    branch_weight: 0.0,
                    path_weight: 0.0,
                    hit: None,
                    end_point: s.p,
                    end: End::TotalInternalReflection,
                    radiance: Color::ZERO,
                    stokes_weights: None,
                    wavelength: b.wavelength,
                });
            }
        }
        let mut l = match scatter.direct {
            Some(direct) => {
                let lit = direct.scale * self.direct(m, &at, &direct, w);
                s_frame.direct(material, &at, lit)
            }
            None => Color::ZERO,
        };
        // Added after the lights, as the waves add it once a level's lights are complete.
        if let Some(glow) = material.glow(at.uv) {
            l += pol.seen(glow);
        }
        if scatter.lobes().next().is_none() {
            return (l, End::Absorbed);
        }
        for f in self.children(&scatter.lobes, b.depth, b.weight, w.rng) {
            // Each child traced through the media on its side of the surface, the stack
            // copied (whole) only for a crossing ray.
            let beyond;
            let media = match f.lobe.side {
                Side::Reflect => media,
                Side::Transmit => {
                    beyond = media.crossed(entering, hit);
                    &beyond
                }
            };
            let child = Branch {
                depth: b.depth + 1,
                weight: f.weight,
                kind: RayKind::of_side(f.lobe.side),
                parent: Some(id as u32),
                factor: f.factor,
                wavelength: b.wavelength,
            };
            let child_pol = s_frame.child(material, &at, f.lobe);
            l += f.tint * self.child(child, &child_ray(f.lobe), media, w, &child_pol);
        }
        (l, End::Split)
    }

    /// The children a hit of path weight `weight` at `depth` traces along its `lobes`, in
    /// order, as the tree mode says. Both walks ask this (the recursion here, the waves
    /// when they queue a node's children), so that they cannot choose differently.
    ///
    /// In the split tree, and wherever there is one lobe: every lobe of weight above 0 (a
    /// lobe of weight 0 adds nothing), tinted by its weight. In the stochastic tree, of two
    /// lobes one, chosen with probability its branch weight ([`pick_lobe`], one number
    /// drawn) and tinted by its weight over that probability: a dielectric's R / P(reflect)
    /// = 1 leaves the path weight unchanged. A branch past the depth or weight limit draws
    /// nothing and follows the first lobe untinted, so that [`Tracer::pruned`] counts (and
    /// the recorder records) the cut once.
    #[inline(always)]
    pub(super) fn children<'s>(
        &self,
        lobes: &'s [Option<Lobe>; 2],
        depth: u32,
        weight: f32,
        rng: &mut SampleStream,
    ) -> impl Iterator<Item = Follow<'s>> + use<'s> {
        // The stochastic tree's one child, or every lobe (none for the split tree).
        let (one, every): (_, &[Option<Lobe>]) = match lobes {
            [Some(first), Some(second)] if self.params.tree == TreeMode::Stochastic => {
                let one = if depth >= self.params.max_depth || weight < self.params.min_weight {
                    Some(Follow {
                        lobe: first,
                        tint: Color::ONE,
                        factor: 1.0,
                        weight,
                    })
                } else {
                    pick_lobe(first, second, rng.next_1d()).map(|(lobe, tint)| {
                        let factor = tint.max_element();
                        Follow {
                            lobe,
                            tint,
                            factor,
                            weight: weight * factor,
                        }
                    })
                };
                (one, &[])
            }
            _ => (None, lobes),
        };
        let each = every.iter().flatten().filter_map(move |lobe| {
            let factor = lobe.weight.max_element();
            (factor > 0.0).then_some(Follow {
                lobe,
                tint: lobe.weight,
                factor,
                weight: weight * factor,
            })
        });
        one.into_iter().chain(each)
    }

    /// Traces a child ray if the pruning rules allow, recording why not.
    fn child<R: Recorder, P: Polarization>(
        &self,
        b: Branch,
        ray: &Ray,
        media: &Media,
        w: &mut Walk<R>,
        pol: &P,
    ) -> Color {
        let why = self.pruned(&b, w.stats, &mut w.tree_rays, &mut w.met);
        match why {
            Some(end) => {
                w.rec.ray(|| b.node(ray, ray.origin, end));
                Color::ZERO
            }
            None => self.trace_in(ray, b, media, w, pol),
        }
    }

    /// Why the child `b` is not traced, counted, or `None`: it is, counted as a ray of its
    /// kind and against its sample's budget (`tree_rays` so far). Its depth and weight,
    /// tested against the limits, go into `met`.
    pub(super) fn pruned(
        &self,
        b: &Branch,
        stats: &mut Stats,
        tree_rays: &mut u32,
        met: &mut Met,
    ) -> Option<End> {
        met.branch(b.depth, b.weight);
        if b.depth > self.params.max_depth {
            stats.pruned_by_depth += 1;
            Some(End::DepthLimit)
        } else if b.weight < self.params.min_weight {
            stats.pruned_by_weight += 1;
            Some(End::WeightLimit)
        } else if *tree_rays >= MAX_TREE_RAYS {
            stats.pruned_by_budget += 1;
            Some(End::BudgetLimit)
        } else {
            *tree_rays += 1;
            match b.kind {
                RayKind::Refract => stats.refraction_rays += 1,
                _ => stats.reflection_rays += 1,
            }
            None
        }
    }
}

/// The stochastic tree's choice between the lobes `first` and `second` by the uniform
/// number `u`: `first` with probability its branch weight, `second` otherwise (it takes
/// any rounding remainder), and the tint its radiance is multiplied by (its weight over
/// that probability); `None` for a lobe of weight 0.
fn pick_lobe<'s>(first: &'s Lobe, second: &'s Lobe, u: f32) -> Option<(&'s Lobe, Color)> {
    let chosen = if u < first.weight.max_element() {
        first
    } else {
        second
    };
    let p = chosen.weight.max_element();
    (p > 0.0).then(|| (chosen, chosen.weight / p))
}

/// A child a hit traces ([`Tracer::children`]): the lobe it follows, the tint its radiance
/// is multiplied by, its branch factor (the largest channel of the tint, in the record)
/// and its path weight.
pub(super) struct Follow<'s> {
    pub(super) lobe: &'s Lobe,
    pub(super) tint: Color,
    pub(super) factor: f32,
    pub(super) weight: f32,
}

/// The ray of a child along `lobe` from the hit point `p` at `time`, `n_geom` the
/// geometric normal facing the parent's ray: it leaves just off the surface on the lobe's
/// side (above for a reflected ray, below for a refracted one), so that it does not meet
/// the surface it leaves.
#[inline(always)]
pub(super) fn child_ray(p: Vec3, n_geom: Vec3, lobe: &Lobe, time: f32) -> Ray {
    let n_side = match lobe.side {
        Side::Reflect => n_geom,
        Side::Transmit => -n_geom,
    };
    Ray {
        origin: offset_ray_origin(p, n_side),
        dir: lobe.dir,
        time,
    }
}
