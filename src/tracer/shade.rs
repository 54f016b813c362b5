//! A hit's share of the ray tree: the material's emission, its shading by the lights, and
//! its reflected and refracted child rays, all of them (the lecture's split tree) or one
//! chosen by its weight (the stochastic tree), each pruned by depth, weight and budget.

use super::polarized::Polarization;
use super::record::{record_hit, record_interface};
use super::{
    Branch, End, MAX_TREE_RAYS, Media, Meet, RayKind, Recorder, Stats, Tracer, TreeNode, Walk,
};
use crate::material::{Lobe, Scatter, Side};
use crate::math::{Color, Ray, offset_ray_origin};
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
        let scatter = material.scatter(&at, w.rng);
        // The polariser's analyzer in this interface's s/p frame.
        let s_frame = pol.at_interface(ray.dir, at.n_shade);
        let child_ray = |lobe: &Lobe| Ray {
            origin: offset_ray_origin(
                s.p,
                match lobe.side {
                    Side::Reflect => n_geom,
                    Side::Transmit => -n_geom,
                },
            ),
            dir: lobe.dir,
            time: ray.time,
        };
        if scatter.total_internal_reflection {
            w.stats.tir_events += 1;
        }
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
        let lobes = scatter.lobes().count();
        if lobes == 0 {
            return (l, End::Absorbed);
        }
        // Each child traced through the media on its side of the surface.
        let mut trace_child = |lobe: &Lobe, factor: f32, weight: f32, w: &mut Walk<R>| {
            // Built only for a crossing ray: the stack is copied whole.
            let beyond;
            let (kind, media) = match lobe.side {
                Side::Reflect => (RayKind::Reflect, media),
                Side::Transmit => {
                    beyond = if entering {
                        media.entered(hit.object, hit.material)
                    } else {
                        media.left(hit.object)
                    };
                    (RayKind::Refract, &beyond)
                }
            };
            let child = Branch {
                depth: b.depth + 1,
                weight,
                kind,
                parent: Some(id as u32),
                factor,
                wavelength: b.wavelength,
            };
            let child_pol = s_frame.child(material, &at, lobe);
            self.child(child, &child_ray(lobe), media, w, &child_pol)
        };
        if self.params.tree == TreeMode::Stochastic && lobes > 1 {
            l += self.follow_one(&scatter, b, w, &mut trace_child);
        } else {
            for lobe in scatter.lobes() {
                let factor = lobe.weight.max_element();
                // A lobe of weight 0 adds nothing: it is not traced.
                if factor > 0.0 {
                    l += lobe.weight * trace_child(lobe, factor, b.weight * factor, w);
                }
            }
        }
        (l, End::Split)
    }

    /// Stochastic mode: follows one lobe, chosen with probability equal to its branch
    /// weight (the last takes any rounding remainder). Dividing by that probability, a
    /// dielectric's R / P(reflect) = 1 leaves the path weight unchanged.
    fn follow_one<R: Recorder>(
        &self,
        scatter: &Scatter,
        b: Branch,
        w: &mut Walk<R>,
        trace_child: &mut impl FnMut(&Lobe, f32, f32, &mut Walk<R>) -> Color,
    ) -> Color {
        let mut lobes = scatter.lobes();
        let Some(first) = lobes.next() else {
            return Color::ZERO;
        };
        if b.depth >= self.params.max_depth || b.weight < self.params.min_weight {
            // Let `child` count and record the cut, once.
            return trace_child(first, 1.0, b.weight, w);
        }
        let Some((chosen, tint)) = pick_lobe(first, lobes, w.rng.next_1d()) else {
            return Color::ZERO;
        };
        tint * trace_child(chosen, tint.max_element(), b.weight * tint.max_element(), w)
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
        let why = self.pruned(&b, w.stats, &mut w.tree_rays);
        match why {
            Some(end) => {
                w.rec.ray(|| b.node(ray, ray.origin, end));
                Color::ZERO
            }
            None => self.trace_in(ray, b, media, w, pol),
        }
    }

    /// Why the child `b` is not traced, counted, or `None`: it is, counted as a ray of its
    /// kind and against its sample's budget (`tree_rays` so far).
    pub(super) fn pruned(&self, b: &Branch, stats: &mut Stats, tree_rays: &mut u32) -> Option<End> {
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

/// The stochastic tree's choice among the lobes `first` and `rest` by the uniform number
/// `u`: each with probability its branch weight (the last takes any rounding remainder),
/// and the tint its radiance is multiplied by (its weight over that probability); `None`
/// for a lobe of weight 0.
pub(super) fn pick_lobe<'s>(
    first: &'s Lobe,
    rest: impl Iterator<Item = &'s Lobe>,
    u: f32,
) -> Option<(&'s Lobe, Color)> {
    let mut chosen = first;
    let mut cumulative = first.weight.max_element();
    for lobe in rest {
        if u < cumulative {
            break;
        }
        chosen = lobe;
        cumulative += lobe.weight.max_element();
    }
    let p = chosen.weight.max_element();
    (p > 0.0).then(|| (chosen, chosen.weight / p))
}
