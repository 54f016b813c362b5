//! The ray tree: from each camera ray, shadow rays to the lights and reflected and refracted
//! child rays, pruned by depth and by attenuation (the path weight).
//!
//! Radiance is not scaled by (n2/n1)² when a ray refracts. Every path that reaches the
//! camera starts and ends in the scene's surrounding medium (lights and background live
//! there too), so the factors of entering and leaving a medium cancel; leaving them out
//! keeps R + (1 − R) = 1 at every split, which the white-furnace test checks.

mod crossing;
mod emitters;
mod media;
mod met;
mod path;
mod photons;
mod polarized;
mod record;
mod shade;
mod shadow;
mod spectral;
mod stats;
mod wave;

use media::{Arrival, Segment};
pub use media::{MAX_NESTING, Media};
pub use met::{MATERIAL_BITS, Met, Reach, reach};
pub use record::{End, NoRecorder, NodeHit, RayKind, RayTree, Recorder, STOKES_ROW, TreeNode};
pub use stats::Stats;
pub use wave::{MAX_WAVE_LIGHTS, Traced, Traversal, Waves};

use crate::camera::{Camera, CameraFrame, CameraSample};
use crate::light::PreparedLight;
use crate::material::{Interaction, Material};
use crate::math::lanes::{RayOf, Real};
use crate::math::{Color, Ray, SampleStream, Vec3};
use crate::optics::polarization::Analyzer;
use crate::params::{Params, Transport};
use crate::scene::{Hit, Scene};
use emitters::Emitters;
use glam::Vec2;
use polarized::{Polarization, Unpolarized};

/// The most reflected and refracted rays one camera sample may trace. Depth and weight
/// prune any tree a lecture draws long before this (a full binary tree of depth 8 has 510
/// child rays), but with no weight limit a deep tree grows without bound (a prism at depth
/// 64 would trace millions a sample): beyond the budget the rest of it is pruned, and
/// counted.
pub const MAX_TREE_RAYS: u32 = 1024;

/// What the pinhole ray through a point of the image meets first.
#[derive(Clone, Copy, Debug)]
pub struct Pick {
    /// The object hit.
    pub object: u32,
    /// Where.
    pub point: Vec3,
    /// Its distance from the eye along the view direction: the focus distance that makes
    /// it sharp.
    pub depth: f32,
}

/// The first surface on the pinhole ray through `film` (0..1 across and down the image)
/// of an image with aspect ratio `aspect`, seen through `camera`.
pub fn pick(scene: &Scene, camera: &Camera, aspect: f32, film: Vec2) -> Option<Pick> {
    let frame = camera.pinhole(aspect);
    let ray = frame.ray(film, Vec2::ZERO, 0.0);
    let hit = scene.intersect(&ray, f32::INFINITY)?;
    Some(Pick {
        object: hit.object,
        point: hit.surface.p,
        depth: (hit.surface.p - camera.position).dot(frame.forward()),
    })
}

/// What travels down the tree with every ray: the sample's random numbers, the counters,
/// the recorder, and the child rays the sample has traced so far.
struct Walk<'w, R: Recorder> {
    rng: &'w mut SampleStream,
    stats: &'w mut Stats,
    rec: &'w mut R,
    tree_rays: u32,
    // What the sample met that a parameter governs.
    met: Met,
}

/// Where a ray sits in the tree.
#[derive(Clone, Copy)]
struct Branch {
    depth: u32,
    weight: f32,
    kind: RayKind,
    // The parent's node in the recorded tree. 32 bits, not a usize: with the wavelength
    // the branch stays within the 32 bytes that are copied down every level.
    parent: Option<u32>,
    factor: f32,
    // The wavelength (nm) this branch carries since its first dispersive surface.
    wavelength: Option<f32>,
}

const _: () = assert!(std::mem::size_of::<Branch>() <= 32);

impl Branch {
    /// The root of a tree: a camera ray.
    const CAMERA: Branch = Branch {
        depth: 0,
        weight: 1.0,
        kind: RayKind::Camera,
        parent: None,
        factor: 1.0,
        wavelength: None,
    };

    /// The record of `ray` at this place in the tree, ending at `end_point` for `end`
    /// (amended once its hit and radiance are known).
    fn node(&self, ray: &Ray, end_point: Vec3, end: End) -> TreeNode {
        TreeNode {
            parent: self.parent.map(|p| p as usize),
            kind: self.kind,
            ray: *ray,
            depth: self.depth,
            branch_weight: self.factor,
            path_weight: self.weight,
            hit: None,
            end_point,
            end,
            radiance: Color::ZERO,
            stokes_weights: None,
            wavelength: self.wavelength,
        }
    }
}

/// Where a branch of the tree meets a surface: the ray, what it hit, the media it
/// travelled through, and its node in the record.
#[derive(Clone, Copy)]
struct Meet<'m> {
    ray: &'m Ray,
    hit: &'m Hit,
    media: &'m Media,
    id: usize,
}

/// Traces the samples of one image of one scene under one set of parameters.
pub struct Tracer<'a> {
    scene: &'a Scene,
    params: &'a Params,
    // The scene's materials with the parameters' overrides (ior, fresnel, ...) applied.
    materials: Vec<Material>,
    // Whether any of them disperses: without, no hit needs to ask.
    dispersive: bool,
    // Whether any of them absorbs: without, no ray needs Beer–Lambert.
    absorbs: bool,
    // The scene's lights at the parameters' light size, prepared once.
    lights: Vec<PreparedLight>,
    // Whether any of them has an area a ray can hit (points cannot be seen).
    lights_seen: bool,
    // Whether the waves trace the shadow rays in lanes, after each level: with opaque
    // shadows, and lights that all aim at points ([`PreparedLight::aims_at_points`]),
    // point lights alone too (faster even there: docs/performance.md, "Shadow rays in
    // lanes").
    shadows_in_lanes: bool,
    // The emitting surfaces, for path tracing's light samples (empty in other transports).
    emitters: Emitters,
    // The pass's photons, with transport = "photons" (see `prepare_photons`).
    photons: Option<photons::PhotonMap>,
    // The photons' target cones and the targets' mean radius, found at the first pass.
    photon_targets: Option<(Vec<photons::Target>, f32)>,
    frame: CameraFrame,
    // The parameters' seed as the sample streams use it, mixed once.
    seed_key: u64,
    width: u32,
    height: u32,
}

impl<'a> Tracer<'a> {
    /// A tracer for a `width` × `height` image through the scene's own camera.
    pub fn new(scene: &'a Scene, params: &'a Params, width: u32, height: u32) -> Self {
        Self::with_camera(scene, &scene.camera, params, width, height)
    }

    /// A tracer for a `width` × `height` image through `camera`.
    pub fn with_camera(
        scene: &'a Scene,
        camera: &Camera,
        params: &'a Params,
        width: u32,
        height: u32,
    ) -> Self {
        let materials: Vec<Material> = scene
            .materials
            .iter()
            .map(|m| m.with_params(params))
            .collect();
        let emitters = match params.transport {
            Transport::Path | Transport::Photons => Emitters::new(scene, &materials),
            Transport::Whitted | Transport::TransmissiveShadows => Emitters::default(),
        };
        let lights: Vec<PreparedLight> = scene
            .lights
            .iter()
            .map(|l| l.scaled(params.light_size).prepare())
            .collect();
        Tracer {
            scene,
            params,
            dispersive: materials.iter().any(|m| m.needs_wavelength()),
            absorbs: materials.iter().any(|m| m.absorbs()),
            materials,
            emitters,
            photons: None,
            photon_targets: None,
            lights_seen: lights.iter().any(PreparedLight::can_be_seen),
            shadows_in_lanes: params.transport != Transport::TransmissiveShadows
                && lights.iter().all(PreparedLight::aims_at_points),
            lights,
            frame: camera.frame(width as f32 / height as f32, camera.exposure(params)),
            seed_key: crate::math::rng::seed_key(params.seed),
            width,
            height,
        }
    }

    /// Radiance of sample number `sample` of pixel (x, y). Its random numbers depend only
    /// on (seed, pixel, sample), so the result does too.
    pub fn sample(&self, x: u32, y: u32, sample: u32, stats: &mut Stats) -> Color {
        self.sample_recorded(x, y, sample, stats, &mut NoRecorder).0
    }

    /// [`Tracer::sample`], and what the sample met that a parameter governs.
    pub fn sample_met(&self, x: u32, y: u32, sample: u32, stats: &mut Stats) -> (Color, Met) {
        self.sample_recorded(x, y, sample, stats, &mut NoRecorder)
    }

    /// The angle of incidence (degrees) at which the camera ray of sample `sample` of pixel
    /// (x, y) first meets a dielectric (bare, or a glaze's coat), as [`Tracer::inspect`]
    /// records it; `None` where it first meets anything else, a light, or nothing. The
    /// interface workbench outlines the pixels at its angle by it.
    pub fn first_incidence(&self, x: u32, y: u32, sample: u32) -> Option<f32> {
        let (_, cs) = self.camera_draw(x, y, sample);
        let (ray, _) = self.camera_ray(x, y, &cs);
        let hit = self.scene.intersect(&ray, f32::INFINITY)?;
        let mut nearest = hit.surface.t;
        if self.light_seen(&ray, &mut nearest).is_some() {
            return None;
        }
        self.materials[hit.material as usize].dielectric()?;
        let at = self.interaction(&ray, &hit, &Media::default(), None);
        Some(at.cos_i().acos().to_degrees())
    }

    /// Where sample `sample` of pixel (x, y) leaves the camera: its image position (0 to 1
    /// across and down) and its point on the lens (unit square); the lens bench draws its
    /// ray from them.
    pub fn camera_point(&self, x: u32, y: u32, sample: u32) -> (Vec2, Vec2) {
        let (_, cs) = self.camera_draw(x, y, sample);
        (self.film_at(x, y, &cs), cs.lens)
    }

    /// The camera's frame the tracer shoots its camera rays through.
    pub fn frame(&self) -> &CameraFrame {
        &self.frame
    }

    /// The whole ray tree of sample `sample` of pixel (x, y), with the radiance it gives:
    /// exactly what [`Tracer::sample`] computes, recorded.
    pub fn inspect(&self, x: u32, y: u32, sample: u32) -> (RayTree, Color) {
        let mut tree = RayTree::default();
        let (c, _) = self.sample_recorded(x, y, sample, &mut Stats::default(), &mut tree);
        (tree, c)
    }

    fn sample_recorded<R: Recorder>(
        &self,
        x: u32,
        y: u32,
        sample: u32,
        stats: &mut Stats,
        rec: &mut R,
    ) -> (Color, Met) {
        let (mut rng, cs) = self.camera_draw(x, y, sample);
        stats.samples += 1;
        let mut walk = Walk {
            rng: &mut rng,
            stats,
            rec,
            tree_rays: 0,
            met: Met::default(),
        };
        let c = if self.frame.disperses() {
            self.sample_through_dispersive_lens(self.film_at(x, y, &cs), &cs, &mut walk)
        } else {
            let (ray, weight) = self.camera_ray(x, y, &cs);
            self.trace_camera_ray(&ray, weight, None, &mut walk)
        };
        (c, walk.met)
    }

    /// The radiance camera ray `ray` brings back, times `weight`, what it counts for, by
    /// the parameters' transport (and through the polariser, if any), carrying `wavelength`
    /// from the camera (through a dispersive lens). Black where the lens blocked it (weight
    /// 0); NaN, untraced, where the ray is not finite (the kernel counts and drops the
    /// sample, where the background would have turned a NaN direction into a colour).
    fn trace_camera_ray<R: Recorder>(
        &self,
        ray: &Ray,
        weight: f32,
        wavelength: Option<f32>,
        walk: &mut Walk<R>,
    ) -> Color {
        if weight == 0.0 {
            return Color::ZERO;
        }
        if !(ray.origin.is_finite() && ray.dir.is_finite()) {
            return Color::NAN;
        }
        walk.stats.camera_rays += 1;
        let root = Branch {
            wavelength,
            ..Branch::CAMERA
        };
        let media = Media::default();
        let c = match (self.params.transport.traces_paths(), self.params.polarizer) {
            (true, None) => self.path(ray, walk, None::<Unpolarized>, wavelength),
            (true, Some(angle)) => {
                let axis = self.frame.polarizer_axis(angle, ray.dir);
                let analyzer = Some(Analyzer::linear_polarizer(axis));
                self.path(ray, walk, analyzer, wavelength)
            }
            (false, None) => self.trace_in(ray, root, &media, walk, &Unpolarized),
            (false, Some(angle)) => {
                let axis = self.frame.polarizer_axis(angle, ray.dir);
                let analyzer = Analyzer::linear_polarizer(axis);
                self.trace_in(ray, root, &media, walk, &analyzer)
            }
        };
        // (× 1 through the thin lens: the same bits.)
        c * weight
    }

    /// Sample `sample` of pixel (x, y): its random numbers, with the camera's drawn.
    #[inline(always)]
    fn camera_draw(&self, x: u32, y: u32, sample: u32) -> (SampleStream, CameraSample) {
        let p = self.params;
        let mut rng = SampleStream::with_seed_key(
            p.pattern,
            p.spp,
            self.seed_key,
            y * self.width + x,
            sample,
        );
        let cs = self.frame.draw_sample(&mut rng);
        (rng, cs)
    }

    /// The camera ray of pixel (x, y) for the camera sample `cs`, and what its radiance
    /// counts for (0: the lens blocks it).
    #[inline(always)]
    fn camera_ray(&self, x: u32, y: u32, cs: &CameraSample) -> (Ray, f32) {
        if self.frame.real_lens().is_some() {
            return self
                .frame
                .weighed_ray(self.film_at(x, y, cs), cs.lens, cs.time);
        }
        let (pixel, lens) = ((cs.pixel.x, cs.pixel.y), (cs.lens.x, cs.lens.y));
        let ray = self.camera_ray_of((x as f32, y as f32), pixel, lens, cs.time);
        (ray.into(), 1.0)
    }

    /// The image position (0 to 1 across and down) of camera sample `cs` of pixel (x, y).
    #[inline(always)]
    pub(super) fn film_at(&self, x: u32, y: u32, cs: &CameraSample) -> Vec2 {
        (Vec2::new(x as f32, y as f32) + cs.pixel)
            / Vec2::new(self.width as f32, self.height as f32)
    }

    /// [`Tracer::camera_ray`] for one ray or one per lane: the pixel (x, y), and the camera
    /// sample's position in it, lens point and time, coordinate by coordinate. The thin
    /// lens only (see [`CameraFrame::ray_of`]).
    #[inline(always)]
    fn camera_ray_of<R: Real>(
        &self,
        (x, y): (R, R),
        pixel: (R, R),
        lens: (R, R),
        time_u: R,
    ) -> RayOf<R> {
        // The film position ((x + pixel.x) / width, (y + pixel.y) / height).
        let film_x = (x + pixel.0) / R::splat(self.width as f32);
        let film_y = (y + pixel.1) / R::splat(self.height as f32);
        self.frame.ray_of(film_x, film_y, lens.0, lens.1, time_u)
    }

    /// The index of refraction at `wavelength` of the medium whose innermost dielectric is
    /// `innermost` (a material), or of the scene's surrounding medium.
    fn ior_of(&self, innermost: Option<u32>, wavelength: Option<f32>) -> f32 {
        self.dielectric_of(innermost)
            .map_or(self.scene.medium_ior, |d| d.ior_at(wavelength))
    }

    /// The absorption coefficient σ of the innermost of `media` (0 in the surrounding
    /// medium); `None`, without a lookup, in a scene where no material absorbs.
    fn absorption(&self, media: &Media) -> Option<Color> {
        self.absorbs.then(|| {
            self.dielectric_of(media.innermost())
                .map_or(Color::ZERO, |d| d.absorption)
        })
    }

    /// A ray's segment through the innermost of `media`.
    #[inline(always)]
    fn segment(&self, media: &Media) -> Segment {
        Segment::new(self.absorption(media))
    }

    /// [`Tracer::absorption`], 0 where nothing absorbs.
    fn absorption_in(&self, media: &Media) -> Color {
        self.absorption(media).unwrap_or(Color::ZERO)
    }

    /// The hit as its material sees it: `ray` arriving at `hit` through `media`, carrying
    /// `wavelength`.
    #[inline(always)]
    fn interaction(
        &self,
        ray: &Ray,
        hit: &Hit,
        media: &Media,
        wavelength: Option<f32>,
    ) -> Interaction {
        let arrival = Arrival::at(ray.dir, hit, media);
        Interaction {
            dir: ray.dir,
            uv: hit.surface.uv,
            n_geom: arrival.n_geom,
            n_shade: arrival.n_shade,
            entering: arrival.entering,
            outside_ior: self.ior_of(arrival.outside, wavelength),
            wavelength,
        }
    }

    fn dielectric_of(&self, material: Option<u32>) -> Option<&crate::material::Dielectric> {
        material.and_then(|m| self.materials[m as usize].dielectric())
    }

    /// Radiance arriving along `ray` at tree level `depth`, reached with path weight
    /// `weight` (largest channel of the product of the reflectances and transmittances
    /// above it), travelling through `media`.
    pub fn trace(
        &self,
        ray: &Ray,
        depth: u32,
        weight: f32,
        media: &Media,
        rng: &mut SampleStream,
        stats: &mut Stats,
    ) -> Color {
        let branch = Branch {
            depth,
            weight,
            kind: RayKind::Camera,
            parent: None,
            factor: 1.0,
            wavelength: None,
        };
        self.trace_in(
            ray,
            branch,
            media,
            &mut Walk {
                rng,
                stats,
                rec: &mut NoRecorder,
                tree_rays: 0,
                met: Met::default(),
            },
            &Unpolarized,
        )
    }

    /// Radiance arriving along `ray` (starting in the surrounding medium) by the
    /// parameters' light transport: one path in path tracing, the ray tree otherwise. For
    /// measurements that are not through the camera, such as the irradiance on a wall.
    pub fn radiance(&self, ray: &Ray, rng: &mut SampleStream, stats: &mut Stats) -> Color {
        let mut walk = Walk {
            rng,
            stats,
            rec: &mut NoRecorder,
            tree_rays: 0,
            met: Met::default(),
        };
        match self.params.transport {
            Transport::Path | Transport::Photons => {
                self.path(ray, &mut walk, None::<Unpolarized>, None)
            }
            Transport::Whitted | Transport::TransmissiveShadows => self.trace_in(
                ray,
                Branch::CAMERA,
                &Media::default(),
                &mut walk,
                &Unpolarized,
            ),
        }
    }

    /// The nearest light `ray` meets before `nearest` (which becomes its distance), and the
    /// radiance it sends back along the ray. Only lights with an area can be met.
    #[inline(always)]
    fn light_seen(&self, ray: &Ray, nearest: &mut f32) -> Option<(&PreparedLight, Color)> {
        let mut seen = None;
        if self.lights_seen {
            for light in &self.lights {
                if let Some((t, radiance)) = light.hit(ray, *nearest) {
                    *nearest = t;
                    seen = Some((light, radiance));
                }
            }
        }
        seen
    }

    /// `pol`: the analyzer of a camera with a polariser, through every interface above.
    fn trace_in<R: Recorder, P: Polarization>(
        &self,
        ray: &Ray,
        b: Branch,
        media: &Media,
        w: &mut Walk<R>,
        pol: &P,
    ) -> Color {
        let id = w.rec.ray(|| b.node(ray, ray.at(100.0), End::Miss));
        let segment = self.segment(media);
        let hit = self.scene.intersect(ray, f32::INFINITY);
        // Area lights are seen where nothing is in front of them.
        let mut nearest = hit.map_or(f32::INFINITY, |h| h.surface.t);
        let (radiance, end) = if let Some((_, radiance)) = self.light_seen(ray, &mut nearest) {
            (pol.seen(segment.along(nearest, radiance)), End::LightHit)
        } else if let Some(hit) = &hit {
            let (tr, weight) = segment.to_hit(hit.surface.t, b.weight);
            let b = Branch { weight, ..b };
            let m = Meet {
                ray,
                hit,
                media,
                id,
            };
            let (l, end) = if self.splits_into_wavelengths(hit.material, b.wavelength) {
                self.shade_spectral(b, w, |b, w| self.shade(m, b, w, pol))
            } else {
                self.shade(m, b, w, pol)
            };
            (tr.map_or(l, |tr| tr * l), end)
        } else {
            let l = segment.along(f32::INFINITY, self.scene.background.radiance(ray.dir));
            (pol.seen(l), End::Miss)
        };
        if w.rec.on() {
            let end_point = if nearest.is_finite() {
                ray.at(nearest)
            } else {
                ray.at(100.0)
            };
            let stokes_weights = pol.weights();
            w.rec.finish(id, &|n| {
                n.end = end;
                n.radiance = radiance;
                n.end_point = end_point;
                n.stokes_weights = stokes_weights;
            });
        }
        radiance
    }
}
