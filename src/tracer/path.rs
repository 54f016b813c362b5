//! Path tracing (`transport = "path"`): the reference the lecture's tracer is compared
//! with. Each sample follows one path from the camera. At every hit the material's
//! [`Scatter`] is split into its parts: the smooth BRDF (diffuse plus Phong highlight),
//! a glossy lobe, mirror-like lobes (mirror, reflected and refracted rays). One part is
//! chosen with probability in proportion to its weight, and the path goes on through it
//! (divided by that probability, as the stochastic ray tree does).
//!
//! Where the chosen part is smooth or glossy, light arrives by two strategies: a sample of
//! each light and of the emitting surfaces (next-event estimation, a shadow ray), and the
//! path's own next direction, drawn from the BRDF, meeting a light. A rough interface
//! (rough glass) is sampled so at every vertex, as a whole, whichever of its jittered
//! children the path follows: the light samples on either side of it (a refraction's
//! leave through it), weighed against the density with which the path draws their
//! direction, its lobe's density times the chance of following that lobe. Each counts with its
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

use super::crossing::cross;
use super::media::transmittance;
use super::polarized::Polarization;
use super::record::{record_hit, record_interface, shadow_node};
use super::shadow::SHADOW_REACH;
use super::{End, Media, RayKind, Recorder, Stats, Tracer, TreeNode, Walk};
use crate::material::{Interaction, Material, Part, Scatter, Side};
use crate::math::{Color, Ray, SampleStream, Vec3, offset_ray_origin};
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

/// One segment of the path, for the inspector: its node, the path's throughput when it
/// set out, and the light added at its end.
struct Segment {
    id: usize,
    throughput: Color,
    added: Color,
}

/// A path under way: what it carries from one vertex to the next.
struct PathState<P> {
    ray: Ray,
    media: Media,
    throughput: Color,
    wavelength: Option<f32>,
    // The density with which the last vertex drew this ray's direction (None: a
    // mirror-like lobe or the camera, which no light sample competes with).
    came: Option<f32>,
    kind: RayKind,
    parent: Option<usize>,
    // The camera polariser's analyzer, until the path meets a diffuse surface.
    pol: Option<P>,
}

impl<P: Polarization> PathState<P> {
    /// The record of the ray about to be traced, at level `depth`.
    fn node(&self, depth: u32) -> TreeNode {
        TreeNode {
            parent: self.parent,
            kind: self.kind,
            ray: self.ray,
            depth,
            branch_weight: 1.0,
            path_weight: self.throughput.max_element(),
            hit: None,
            end_point: self.ray.at(100.0),
            end: End::Miss,
            radiance: Color::ZERO,
            stokes_weights: self.pol.as_ref().and_then(P::weights),
            wavelength: self.wavelength,
        }
    }

    /// After [`ROULETTE_AFTER`] bounces, whether the path goes on: with the chance of its
    /// throughput's largest channel (at most 1), the survivor divided by that chance.
    fn survives_roulette(&mut self, depth: u32, rng: &mut SampleStream) -> bool {
        if depth < ROULETTE_AFTER {
            return true;
        }
        let q = self.throughput.max_element().min(1.0);
        if q <= 0.0 || rng.next_1d() >= q {
            return false;
        }
        self.throughput /= q;
        true
    }

    /// The path leaving `hit` (node `id`), seen as `at`, on `side` along `dir`: its next ray.
    fn set_out(
        &mut self,
        at: &Interaction,
        hit: &Hit,
        side: Side,
        dir: Vec3,
        id: usize,
        stats: &mut Stats,
    ) {
        let n_side = cross(&mut self.media, at, hit, side);
        self.kind = match side {
            Side::Reflect => {
                stats.reflection_rays += 1;
                RayKind::Reflect
            }
            Side::Transmit => {
                stats.refraction_rays += 1;
                RayKind::Refract
            }
        };
        self.parent = Some(id);
        self.ray = Ray {
            origin: offset_ray_origin(hit.surface.p, n_side),
            dir,
            time: self.ray.time,
        };
    }

    /// Unpolarised radiance `c` arriving along the path, as the camera sees it.
    fn seen(&self, c: Color) -> Color {
        self.pol.as_ref().map_or(c, |p| p.seen(c))
    }
}

/// A path's vertex as its light samples see it: the ray that arrived, the point and the
/// hit as its material sees it, the part the light is seen through, the absorption of the
/// medium the point lies in and of the one beyond the surface (where a rough refraction's
/// light samples go), whether the path ends here (`alone`: the light samples then stand
/// alone, not weighed against the path's own next direction), and the vertex's node.
struct Vertex<'v> {
    ray: &'v Ray,
    p: Vec3,
    at: &'v Interaction,
    part: &'v Part<'v>,
    sigma: Color,
    sigma_beyond: Color,
    alone: bool,
    id: usize,
}

/// A vertex as met: the ray that arrived, its hit and the hit as the material sees it, the
/// absorption of the medium the ray crossed, whether the path ends here (`last`: at
/// `max_depth`), and the vertex's node.
struct Meeting<'m> {
    ray: &'m Ray,
    hit: &'m Hit,
    at: &'m Interaction,
    sigma: Color,
    last: bool,
    id: usize,
}

impl Vertex<'_> {
    /// A shadow ray towards `dir` from the vertex: where it sets out, just off the surface
    /// on the side the ray came from (`here`) or beyond it (for a rough interface's
    /// refraction), and the absorption of the medium it crosses.
    fn leaving(&self, dir: Vec3, here: Vec3) -> (Vec3, Color) {
        let through = matches!(self.part, Part::Interface(_)) && dir.dot(self.at.n_geom) < 0.0;
        if through {
            (
                offset_ray_origin(self.p, -self.at.n_geom),
                self.sigma_beyond,
            )
        } else {
            (here, self.sigma)
        }
    }
}

/// What a vertex leaves the path: going on along the new ray, or ended, and why.
enum Next {
    On,
    End(End),
}

impl Tracer<'_> {
    /// The radiance one path from the camera ray `ray` brings back. `pol`: the camera
    /// polariser's analyzer, until the path meets a diffuse or glossy surface (which
    /// depolarises what it sends on). `wavelength`: the one it carries from the camera
    /// (through a dispersive lens); `None`: none until its first dispersive surface.
    pub(super) fn path<R: Recorder, P: Polarization>(
        &self,
        ray: &Ray,
        w: &mut Walk<R>,
        pol: Option<P>,
        wavelength: Option<f32>,
    ) -> Color {
        let mut st = PathState {
            ray: *ray,
            media: Media::default(),
            throughput: Color::ONE,
            wavelength,
            came: None,
            kind: RayKind::Camera,
            parent: None,
            pol,
        };
        let mut total = Color::ZERO;
        // Kept for the inspector only: no allocation per path when nothing records.
        let mut segments = Vec::new();
        for depth in 0.. {
            let id = w.rec.ray(|| st.node(depth));
            let mut segment = Segment {
                id,
                throughput: st.throughput,
                added: Color::ZERO,
            };
            // A vertex adds light once at most, so this sum is the same as adding as it goes.
            let next = self.vertex(&mut st, depth, id, &mut segment.added, w);
            total += segment.added;
            if w.rec.on() {
                segments.push(segment);
            }
            let end = match next {
                Next::On => End::Continued,
                Next::End(end) => end,
            };
            w.rec.finish(id, &|n| n.end = end);
            if end != End::Continued {
                break;
            }
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

    /// Traces the path's ray `st.ray` (node `id`, level `depth`) to what it meets, adds the
    /// light found there to `added`, and sets the path on its next ray, or ends it.
    fn vertex<R: Recorder, P: Polarization>(
        &self,
        st: &mut PathState<P>,
        depth: u32,
        id: usize,
        added: &mut Color,
        w: &mut Walk<R>,
    ) -> Next {
        let ray = st.ray;
        let sigma = self.absorption_in(&st.media);
        let hit = self.scene.intersect(&ray, f32::INFINITY);
        let mut nearest = hit.map_or(f32::INFINITY, |h| h.surface.t);
        let light_hit = self.light_seen(&ray, &mut nearest);
        let end_point = if nearest.is_finite() {
            ray.at(nearest)
        } else {
            ray.at(100.0)
        };
        w.rec.finish(id, &|n| n.end_point = end_point);
        if let Some((light, radiance)) = light_hit {
            let mis = st
                .came
                .map_or(1.0, |pdf| power_heuristic(pdf, light.pdf(&ray, nearest)));
            *added = st.seen(st.throughput * transmittance(sigma, nearest) * radiance * mis);
            return Next::End(End::LightHit);
        }
        let Some(hit) = hit else {
            let l = self.scene.background.radiance(ray.dir);
            *added = st.seen(st.throughput * transmittance(sigma, f32::INFINITY) * l);
            return Next::End(End::Miss);
        };
        st.throughput *= transmittance(sigma, hit.surface.t);
        let material = &self.materials[hit.material as usize];
        w.met.material(hit.material);
        let at = self.meet(
            &ray,
            &hit,
            &st.media,
            &mut st.wavelength,
            &mut st.throughput,
            w.rng,
        );
        record_hit(w.rec, id, &hit, &at);
        if let Some(radiance) = material.emission(at.uv) {
            let cos_e = (-ray.dir).dot(at.n_geom);
            let mis = st.came.map_or(1.0, |pdf| {
                power_heuristic(pdf, self.emitters.pdf(hit.object, hit.surface.t, cos_e))
            });
            *added = st.seen(st.throughput * radiance * mis);
            // A glowing surface reflects too: the path goes on from it.
            if material.is_light() {
                return Next::End(End::LightHit);
            }
        }
        let scatter = material.scatter(&at, w.rng);
        if let Some(i) = scatter.interface {
            record_interface(w.rec, id, i);
        }
        w.stats.count_tir(scatter.total_internal_reflection);
        let s_frame = st.pol.as_ref().map(|p| p.at_interface(ray.dir, at.n_shade));
        // Light arriving through a part, as the camera's polariser sees it.
        let seen = |lit: Color| match &s_frame {
            Some(s) => s.direct(material, &at, lit),
            None => lit,
        };
        let met = Meeting {
            ray: &ray,
            hit: &hit,
            at: &at,
            sigma,
            // At `max_depth` the path gathers light here and goes no further, so light
            // samples stand alone; before it, they are weighed against the BRDF's own
            // choice of their direction.
            last: depth >= self.params.max_depth,
            id,
        };
        // A rough interface is lit as a whole at every vertex (see the module's doc).
        if let Some(facets) = &scatter.facets {
            let beyond = self.absorption_in(&st.media.crossed(at.entering, &hit));
            let lit = self.lit_through(&met, &Part::Interface(facets), beyond, w);
            *added += st.throughput * seen(lit);
        }
        // One part, in proportion to its weight.
        let parts = scatter.parts();
        let sum: f32 = parts.iter().flatten().map(Part::weight).sum();
        if sum <= 0.0 {
            return Next::End(End::Absorbed);
        }
        let Some(part) = pick_part(&parts, w.rng.next_1d() * sum) else {
            return Next::End(End::Absorbed);
        };
        let p_choice = part.weight() / sum;
        w.met.branch(depth + 1, f32::INFINITY);
        if part.lit_by_samples() {
            let lit = self.lit_through(&met, part, sigma, w);
            *added += st.throughput / p_choice * seen(lit);
        }
        if met.last {
            w.stats.pruned_by_depth += 1;
            return Next::End(End::DepthLimit);
        }
        let next = next_direction(
            st,
            (part, &scatter, material),
            &met,
            s_frame.as_ref(),
            w.rng,
        );
        let Some((dir, side, weight)) = next else {
            return Next::End(End::Absorbed);
        };
        st.throughput *= weight / p_choice;
        if !st.survives_roulette(depth, w.rng) {
            return Next::End(End::Roulette);
        }
        st.set_out(&at, &hit, side, dir, id, w.stats);
        Next::On
    }

    /// The light arriving at the vertex `met` through `part`: its light samples (those
    /// leaving through the surface crossing a medium of absorption `beyond`), and for a
    /// smooth part the point lights' caustics from this pass's photons.
    fn lit_through<R: Recorder>(
        &self,
        met: &Meeting,
        part: &Part,
        beyond: Color,
        w: &mut Walk<R>,
    ) -> Color {
        let v = Vertex {
            ray: met.ray,
            p: met.hit.surface.p,
            at: met.at,
            part,
            sigma: met.sigma,
            sigma_beyond: beyond,
            alone: met.last,
            id: met.id,
        };
        let mut lit = self.light_samples(&v, w);
        // Recorded where a map would be gathered from even when there is none (no
        // mirror-like object to aim at): a change may make one (a rough glass made smooth).
        if let Part::Smooth(d) = part
            && self.gathers_photons()
        {
            w.met.photons();
            if let Some(map) = &self.photons {
                lit += map.gather(v.p, met.at, &d.brdf, d.scale);
            }
        }
        lit
    }

    /// Light arriving at the vertex `v` through its part: one sample of each light and one
    /// of the emitting surfaces, each weighed against the part drawing its direction
    /// (unless the vertex stands alone).
    fn light_samples<R: Recorder>(&self, v: &Vertex, w: &mut Walk<R>) -> Color {
        let here = offset_ray_origin(v.p, v.at.n_geom);
        let mut sum = Color::ZERO;
        for light in &self.lights {
            let u = light.draw(w.rng);
            let Some(ls) = light.sample(v.p, u) else {
                continue;
            };
            let (f_cos, pdf) = v.part.eval(v.at, ls.dir);
            if f_cos == Color::ZERO {
                continue;
            }
            w.stats.shadow_rays += 1;
            let (origin, sigma) = v.leaving(ls.dir, here);
            let s = Ray {
                origin,
                dir: ls.dir,
                time: v.ray.time,
            };
            let blocked = self.scene.occluded(&s, ls.dist * SHADOW_REACH);
            let c = if blocked {
                Color::ZERO
            } else {
                f_cos
                    * ls.value
                    * transmittance(sigma, ls.dist)
                    * light_weight(v.alone, ls.pdf, pdf)
            };
            sum += c;
            w.rec.ray(|| shadow_node(v.id, &s, ls.dist, blocked, c));
        }
        if !self.emitters.is_empty() {
            let (pick, u) = (w.rng.next_1d(), w.rng.next_2d());
            if let Some((object, q)) = self.emitters.sample(self.scene, pick, u, v.ray.time) {
                sum += self.emitter_sample(v, here, q, object, w);
            }
        }
        sum
    }

    /// The light from point `q` of emitting `object`, seen from the vertex `v` (`here` just
    /// off it on the side the ray came from), weighed as [`light_weight`] says.
    fn emitter_sample<R: Recorder>(
        &self,
        v: &Vertex,
        here: Vec3,
        q: Vec3,
        object: u32,
        w: &mut Walk<R>,
    ) -> Color {
        let to = q - v.p;
        let dist = to.length();
        if dist <= 0.0 {
            return Color::ZERO;
        }
        let dir = to / dist;
        let (f_cos, pdf) = v.part.eval(v.at, dir);
        if f_cos == Color::ZERO {
            return Color::ZERO;
        }
        w.stats.shadow_rays += 1;
        let (origin, sigma) = v.leaving(dir, here);
        let s = Ray {
            origin,
            dir,
            time: v.ray.time,
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
                match self.materials[h.material as usize].emission(h.surface.uv) {
                    Some(l) if light_pdf > 0.0 => {
                        f_cos * l / light_pdf
                            * transmittance(sigma, dist)
                            * light_weight(v.alone, light_pdf, pdf)
                    }
                    _ => Color::ZERO,
                }
            }
            None => Color::ZERO,
        };
        w.rec.ray(|| shadow_node(v.id, &s, dist, seen.is_none(), c));
        c
    }
}

/// The path's next direction through the `part` it chose of `scatter` at the vertex `met`
/// (of `material`; `s_frame`, the camera's analyzer there), and what it carries along it (f cos θ / pdf, before the choice's
/// chance): drawn from a smooth BRDF (the camera's analyzer ends there: a diffuse surface
/// sends on unpolarised light), or a lobe's own. Sets the density the path drew it with,
/// for the light it may meet. `None`: absorbed.
// Inlined into its one caller: callgrind counts 1 % fewer instructions on path.toml
// with path tracing (95.07 M against 95.99 M, one thread, 4 spp).
#[inline(always)]
fn next_direction<P: Polarization>(
    st: &mut PathState<P>,
    (part, scatter, material): (&Part, &Scatter, &Material),
    met: &Meeting,
    s_frame: Option<&P>,
    rng: &mut SampleStream,
) -> Option<(Vec3, Side, Color)> {
    let at = met.at;
    match part {
        Part::Smooth(d) => {
            let pick = rng.next_1d();
            let dir = d.brdf.sample(at.n_shade, -met.ray.dir, pick, rng.next_2d());
            let (f_cos, pdf) = part.eval(at, dir);
            if pdf <= 0.0 || f_cos == Color::ZERO {
                return None;
            }
            st.came = Some(pdf);
            if let Some(s) = s_frame {
                st.throughput *= s.direct(material, at, Color::ONE);
            }
            st.pol = None;
            Some((dir, Side::Reflect, f_cos / pdf))
        }
        // (Never chosen: not among the scatter's parts.)
        Part::Interface(_) => None,
        Part::Lobe(lobe) => {
            // Through a rough interface, the density of the path's own choice.
            st.came = match &scatter.facets {
                Some(facets) => Some(facets.eval_path(at, lobe.dir).1),
                None => lobe.pdf(at, lobe.dir),
            };
            st.pol = s_frame.map(|s| s.child(material, at, lobe));
            Some((lobe.dir, lobe.side, lobe.weight))
        }
    }
}

/// The part that the number `u` (uniform over 0 to the parts' summed weight) falls in.
fn pick_part<'p, 's>(parts: &'p [Option<Part<'s>>; 3], u: f32) -> Option<&'p Part<'s>> {
    let mut cumulative = 0.0;
    let mut chosen = None;
    for part in parts.iter().flatten() {
        cumulative += part.weight();
        chosen = Some(part);
        if u < cumulative {
            break;
        }
    }
    chosen
}
