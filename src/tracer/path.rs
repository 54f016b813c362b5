//! Path tracing (`transport = "path"`): the reference the lecture's tracer is compared
//! with. Each sample follows one path from the camera. At every hit the material's
//! [`Scatter`] is split into its parts: the smooth BRDF (diffuse plus Phong highlight),
//! a glossy lobe, mirror-like lobes (mirror, reflected and refracted rays). One part is
//! chosen with probability in proportion to its weight, and the path goes on through it
//! (divided by that probability, as the stochastic ray tree does).
//!
//! Where the chosen part is smooth or glossy, light arrives by two strategies: a sample of
//! each light and of the emitting surfaces (next-event estimation, a shadow ray), and the
//! path's own next direction, drawn from the BRDF, meeting a light. Each counts with its
//! multiple-importance weight (Veach's power heuristic, p_a² / (p_a² + p_b²) of the two
//! densities per solid angle), so that neither small bright lights (found by light
//! samples) nor sharp highlights of large ones (found by the BRDF) are noisy. Behind a
//! mirror-like part only the path can find a light: through glass it does (caustics from
//! area lights and emitters; a point light it never can).
//!
//! Shadow rays stop at every surface, glass included: light through glass comes by the
//! path. There is no ambient term (the light it stands in for is traced). After
//! [`ROULETTE_AFTER`] bounces a path of small weight ends at random, its survivors
//! divided by the chance to survive (Russian roulette); `max_depth` bounds every path.

use super::media::transmittance;
use super::polarized::Polarization;
use super::record::{record_hit, record_interface, shadow_node};
use super::{End, Media, RayKind, Recorder, Tracer, TreeNode, Walk};
use crate::material::{Brdf, Interaction, Lobe, Material, Scatter, Side, glossy_pdf};
use crate::math::{Color, Ray, SampleStream, Vec3, offset_ray_origin};
use crate::optics::dispersion;
use crate::scene::Hit;

/// Bounces before Russian roulette may end a path.
const ROULETTE_AFTER: u32 = 3;

/// Veach's power heuristic: the weight of a sample drawn with density `a` per solid angle
/// when `b` is the other strategy's density for the same direction. A point light's light
/// sample (a = ∞) takes it all.
fn power_heuristic(a: f32, b: f32) -> f32 {
    if a.is_infinite() {
        return 1.0;
    }
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 > 0.0 { a2 / (a2 + b2) } else { 0.0 }
}

/// The weight of a light sample of density `light_pdf` whose direction the BRDF draws with
/// density `bsdf_pdf`: the power heuristic, or all of it where the path goes no further
/// (`alone`) and so cannot find the light itself.
fn light_weight(alone: bool, light_pdf: f32, bsdf_pdf: f32) -> f32 {
    if alone {
        1.0
    } else {
        power_heuristic(light_pdf, bsdf_pdf)
    }
}

/// The part of a material a path goes on through.
pub(super) enum Part<'s> {
    /// The smooth BRDF, times the scale a glaze's coat leaves it.
    Smooth(Brdf, f32),
    /// A glossy lobe of this Phong exponent (its direction already drawn).
    Glossy(&'s Lobe, f32),
    /// A mirror-like lobe: one direction.
    Delta(&'s Lobe),
}

impl Part<'_> {
    /// Its weight: the largest channel of the light it passes on (at most 1 in all).
    pub(super) fn weight(&self) -> f32 {
        match self {
            Part::Smooth(brdf, scale) => scale * (brdf.albedo + brdf.specular).max_element(),
            Part::Glossy(lobe, _) | Part::Delta(lobe) => lobe.weight.max_element(),
        }
    }

    /// f cos θ towards `dir`, and the density with which this part would draw `dir`.
    fn eval(&self, at: &Interaction, dir: Vec3) -> (Color, f32) {
        match self {
            Part::Smooth(brdf, scale) => {
                let cos = at.n_shade.dot(dir);
                if cos <= 0.0 || at.n_geom.dot(dir) <= 0.0 {
                    return (Color::ZERO, 0.0);
                }
                let view = -at.dir;
                (
                    *scale * cos * brdf.eval(at.n_shade, dir, view),
                    brdf.pdf(at.n_shade, dir, view),
                )
            }
            Part::Glossy(lobe, exponent) => {
                let pdf = glossy_pdf(at, *exponent, dir);
                (lobe.weight * pdf, pdf)
            }
            Part::Delta(_) => (Color::ZERO, 0.0),
        }
    }
}

/// The parts of `scatter` (of `material`) with their weights: the smooth BRDF, then the
/// lobes, the first glossy where the material is.
pub(super) fn parts<'s>(material: &Material, scatter: &'s Scatter) -> [Option<Part<'s>>; 3] {
    let glossy = material.phong_exponent();
    let lobe = |i: usize| {
        scatter.lobes[i].as_ref().map(|l| match glossy {
            Some(n) if i == 0 => Part::Glossy(l, n),
            _ => Part::Delta(l),
        })
    };
    [
        scatter.direct.map(|d| Part::Smooth(d.brdf, d.scale)),
        lobe(0),
        lobe(1),
    ]
}

/// A path (or photon) leaving a surface on `side`: the media it is in from there, and the
/// normal its next ray sets out along.
pub(super) fn cross(media: &mut Media, at: &Interaction, hit: &Hit, side: Side) -> Vec3 {
    match side {
        Side::Reflect => at.n_geom,
        Side::Transmit => {
            *media = if at.entering {
                media.entered(hit.object, hit.material)
            } else {
                media.left(hit.object)
            };
            -at.n_geom
        }
    }
}

/// One segment of the path, for the inspector: its node, the path's throughput when it
/// set out, and the light added at its end.
struct Segment {
    id: usize,
    throughput: Color,
    added: Color,
}

impl Tracer<'_> {
    /// The radiance one path from the camera ray `ray` brings back. `pol`: the camera
    /// polariser's analyzer, until the path meets a diffuse or glossy surface (which
    /// depolarises what it sends on).
    pub(super) fn path<R: Recorder, P: Polarization>(
        &self,
        ray: &Ray,
        w: &mut Walk<R>,
        mut pol: Option<P>,
    ) -> Color {
        let mut ray = *ray;
        let mut media = Media::default();
        let mut throughput = Color::ONE;
        let mut total = Color::ZERO;
        let mut wavelength = None;
        // The density with which the last vertex drew this ray's direction (None: a
        // mirror-like lobe or the camera, which no light sample competes with).
        let mut came: Option<f32> = None;
        let mut kind = RayKind::Camera;
        let mut parent = None;
        // Kept for the inspector only: no allocation per path when nothing records.
        let recording = w.rec.on();
        let mut segments = Vec::new();
        let seen = |pol: &Option<P>, c: Color| pol.as_ref().map_or(c, |p| p.seen(c));
        for depth in 0.. {
            let id = w.rec.ray(|| TreeNode {
                parent,
                kind,
                ray,
                depth,
                branch_weight: 1.0,
                path_weight: throughput.max_element(),
                hit: None,
                end_point: ray.at(100.0),
                end: End::Miss,
                radiance: Color::ZERO,
                stokes_weights: pol.as_ref().and_then(P::weights),
                wavelength,
            });
            let mut segment = Segment {
                id,
                throughput,
                added: Color::ZERO,
            };
            let sigma = self.absorption_in(&media);
            let hit = self.scene.intersect(&ray, f32::INFINITY);
            let mut nearest = hit.map_or(f32::INFINITY, |h| h.surface.t);
            let mut light_hit = None;
            for light in &self.lights {
                if let Some((t, radiance)) = light.hit(&ray, nearest) {
                    nearest = t;
                    light_hit = Some((light, radiance));
                }
            }
            let end_point = if nearest.is_finite() {
                ray.at(nearest)
            } else {
                ray.at(100.0)
            };
            // Where the path ends, what it adds there.
            let end = |rec: &mut R, total: &mut Color, segment: &mut Segment, c: Color, e: End| {
                let c = seen(&pol, c);
                *total += c;
                segment.added = c;
                rec.finish(id, &|n| {
                    n.end = e;
                    n.end_point = end_point;
                });
            };
            if let Some((light, radiance)) = light_hit {
                let mis = came.map_or(1.0, |pdf| power_heuristic(pdf, light.pdf(&ray, nearest)));
                let l = throughput * transmittance(sigma, nearest) * radiance * mis;
                end(w.rec, &mut total, &mut segment, l, End::LightHit);
                if recording {
                    segments.push(segment);
                }
                break;
            }
            let Some(hit) = hit else {
                let l = self.scene.background.radiance(ray.dir);
                let l = throughput * transmittance(sigma, f32::INFINITY) * l;
                end(w.rec, &mut total, &mut segment, l, End::Miss);
                if recording {
                    segments.push(segment);
                }
                break;
            };
            w.rec.finish(id, &|n| n.end_point = end_point);
            throughput *= transmittance(sigma, hit.surface.t);
            let material = &self.materials[hit.material as usize];
            let at = self.meet(&ray, &hit, &media, &mut wavelength, &mut throughput, w.rng);
            record_hit(w.rec, id, &hit, &at);
            let scatter = material.scatter(&at, w.rng);
            if let Some(radiance) = scatter.emitted {
                let cos_e = (-ray.dir).dot(at.n_geom);
                let mis = came.map_or(1.0, |pdf| {
                    power_heuristic(pdf, self.emitters.pdf(hit.object, hit.surface.t, cos_e))
                });
                end(
                    w.rec,
                    &mut total,
                    &mut segment,
                    throughput * radiance * mis,
                    End::LightHit,
                );
                if recording {
                    segments.push(segment);
                }
                break;
            }
            if let Some(i) = scatter.interface {
                record_interface(w.rec, id, i);
            }
            if scatter.total_internal_reflection {
                w.stats.tir_events += 1;
            }
            // One part, in proportion to its weight.
            let parts = parts(material, &scatter);
            let sum: f32 = parts.iter().flatten().map(Part::weight).sum();
            if sum <= 0.0 {
                w.rec.finish(id, &|n| n.end = End::Absorbed);
                if recording {
                    segments.push(segment);
                }
                break;
            }
            let u = w.rng.next_1d() * sum;
            let mut cumulative = 0.0;
            let mut chosen = None;
            for part in parts.iter().flatten() {
                cumulative += part.weight();
                chosen = Some(part);
                if u < cumulative {
                    break;
                }
            }
            let Some(part) = chosen else { break };
            let p_choice = part.weight() / sum;
            let s_frame = pol.as_ref().map(|p| p.at_interface(ray.dir, at.n_shade));
            let p = hit.surface.p;
            // At `max_depth` the path gathers light here and goes no further, so light
            // samples stand alone; before it, they are weighed against the BRDF's own
            // choice of their direction.
            let last = depth >= self.params.max_depth;
            if !matches!(part, Part::Delta(_)) {
                let mut lit = self.light_samples(&ray, p, &at, part, sigma, last, id, w);
                // The point lights' caustics, from this pass's photons.
                if let (Some(map), Part::Smooth(brdf, scale)) = (&self.photons, part) {
                    lit += map.gather(p, &at, brdf, *scale);
                }
                let lit = match &s_frame {
                    Some(s) => s.direct(material, &at, lit),
                    None => lit,
                };
                let c = throughput / p_choice * lit;
                total += c;
                segment.added += c;
            }
            if last {
                w.stats.pruned_by_depth += 1;
                w.rec.finish(id, &|n| n.end = End::DepthLimit);
                if recording {
                    segments.push(segment);
                }
                break;
            }
            // The next direction and what the path carries along it.
            let (dir, side, weight, next_pol) = match part {
                Part::Smooth(brdf, _) => {
                    let pick = w.rng.next_1d();
                    let dir = brdf.sample(at.n_shade, -ray.dir, pick, w.rng.next_2d());
                    let (f_cos, pdf) = part.eval(&at, dir);
                    if pdf <= 0.0 || f_cos == Color::ZERO {
                        w.rec.finish(id, &|n| n.end = End::Absorbed);
                        if recording {
                            segments.push(segment);
                        }
                        break;
                    }
                    came = Some(pdf);
                    // A diffuse surface sends on unpolarised light: the analyzer ends
                    // here, as what it makes of the light from now on.
                    if let Some(s) = &s_frame {
                        throughput *= s.direct(material, &at, Color::ONE);
                    }
                    (dir, Side::Reflect, f_cos / pdf, None)
                }
                Part::Glossy(lobe, exponent) => {
                    came = Some(glossy_pdf(&at, *exponent, lobe.dir));
                    let next = s_frame.as_ref().map(|s| s.child(material, &at, lobe));
                    (lobe.dir, lobe.side, lobe.weight, next)
                }
                Part::Delta(lobe) => {
                    came = None;
                    let next = s_frame.as_ref().map(|s| s.child(material, &at, lobe));
                    (lobe.dir, lobe.side, lobe.weight, next)
                }
            };
            pol = next_pol;
            throughput *= weight / p_choice;
            if recording {
                segments.push(segment);
            }
            if depth >= ROULETTE_AFTER {
                let q = throughput.max_element().min(1.0);
                if q <= 0.0 || w.rng.next_1d() >= q {
                    w.rec.finish(id, &|n| n.end = End::Roulette);
                    break;
                }
                throughput /= q;
            }
            w.rec.finish(id, &|n| n.end = End::Continued);
            let n_side = cross(&mut media, &at, &hit, side);
            kind = match side {
                Side::Reflect => {
                    w.stats.reflection_rays += 1;
                    RayKind::Reflect
                }
                Side::Transmit => {
                    w.stats.refraction_rays += 1;
                    RayKind::Refract
                }
            };
            parent = Some(id);
            ray = Ray {
                origin: offset_ray_origin(p, n_side),
                dir,
                time: ray.time,
            };
        }
        if w.rec.on() {
            // The radiance arriving along each segment: what the path gathered from there
            // on, divided by the throughput it set out with.
            let mut after = Color::ZERO;
            for s in segments.iter().rev() {
                after += s.added;
                let arriving = after / s.throughput.max(Color::splat(1e-30));
                w.rec.finish(s.id, &|n| n.radiance = arriving);
            }
        }
        total
    }

    /// The hit as its material sees it, for a path (or photon) through `media` carrying
    /// `wavelength`: the first dispersive surface on the way picks one, and `weight` takes
    /// its channel's weight.
    pub(super) fn meet(
        &self,
        ray: &Ray,
        hit: &Hit,
        media: &Media,
        wavelength: &mut Option<f32>,
        weight: &mut Color,
        rng: &mut SampleStream,
    ) -> Interaction {
        if self.dispersive
            && wavelength.is_none()
            && self.materials[hit.material as usize].disperses()
        {
            let lambda = dispersion::wavelength(rng.next_1d());
            *wavelength = Some(lambda);
            *weight *= dispersion::channel_weight(lambda);
        }
        self.interaction(ray, hit, media, *wavelength)
    }

    /// Light arriving at `p` through `part`: one sample of each light and one of the
    /// emitting surfaces, each weighed against `part` drawing its direction (unless
    /// `alone`, where the path goes no further). `sigma`: the absorption of the medium `p`
    /// lies in.
    #[allow(clippy::too_many_arguments)]
    fn light_samples<R: Recorder>(
        &self,
        ray: &Ray,
        p: Vec3,
        at: &Interaction,
        part: &Part,
        sigma: Color,
        alone: bool,
        id: usize,
        w: &mut Walk<R>,
    ) -> Color {
        let mis = |light_pdf, bsdf_pdf| light_weight(alone, light_pdf, bsdf_pdf);
        let origin = offset_ray_origin(p, at.n_geom);
        let shadow = |dir| Ray {
            origin,
            dir,
            time: ray.time,
        };
        let mut sum = Color::ZERO;
        for light in &self.lights {
            let u = light.draw(w.rng);
            let Some(ls) = light.sample(p, u) else {
                continue;
            };
            let (f_cos, pdf) = part.eval(at, ls.dir);
            if f_cos == Color::ZERO {
                continue;
            }
            w.stats.shadow_rays += 1;
            let s = shadow(ls.dir);
            let blocked = self.scene.occluded(&s, ls.dist * (1.0 - 1e-4));
            let c = if blocked {
                Color::ZERO
            } else {
                f_cos * ls.value * transmittance(sigma, ls.dist) * mis(ls.pdf, pdf)
            };
            sum += c;
            w.rec.ray(|| shadow_node(id, &s, ls.dist, blocked, c));
        }
        if !self.emitters.is_empty() {
            let (pick, u) = (w.rng.next_1d(), w.rng.next_2d());
            if let Some((object, q)) = self.emitters.sample(self.scene, pick, u, ray.time) {
                sum +=
                    self.emitter_sample(ray, origin, p, q, object, at, part, sigma, alone, id, w);
            }
        }
        sum
    }

    /// The light from point `q` of emitting `object`, seen from `p` through `part`, weighed
    /// as [`light_weight`] says.
    #[allow(clippy::too_many_arguments)]
    fn emitter_sample<R: Recorder>(
        &self,
        ray: &Ray,
        origin: Vec3,
        p: Vec3,
        q: Vec3,
        object: u32,
        at: &Interaction,
        part: &Part,
        sigma: Color,
        alone: bool,
        id: usize,
        w: &mut Walk<R>,
    ) -> Color {
        let to = q - p;
        let dist = to.length();
        if dist <= 0.0 {
            return Color::ZERO;
        }
        let dir = to / dist;
        let (f_cos, pdf) = part.eval(at, dir);
        if f_cos == Color::ZERO {
            return Color::ZERO;
        }
        w.stats.shadow_rays += 1;
        let s = Ray {
            origin,
            dir,
            time: ray.time,
        };
        // Visible when the first surface on the way is the sampled point's.
        let seen = self
            .scene
            .intersect(&s, dist * 1.001 + 1e-4)
            .filter(|h| h.object == object && (h.surface.t - dist).abs() <= 1e-3 * dist + 1e-4);
        let c = match seen {
            Some(h) => {
                let cos_e = dir.dot(h.surface.n_geom).abs();
                let light_pdf = self.emitters.pdf(object, dist, cos_e);
                match &self.materials[h.material as usize] {
                    Material::Emissive(e) if light_pdf > 0.0 => {
                        let l = e.radiance.eval(h.surface.uv);
                        f_cos * l / light_pdf
                            * transmittance(sigma, dist)
                            * light_weight(alone, light_pdf, pdf)
                    }
                    _ => Color::ZERO,
                }
            }
            None => Color::ZERO,
        };
        w.rec.ray(|| shadow_node(id, &s, dist, seen.is_none(), c));
        c
    }
}
