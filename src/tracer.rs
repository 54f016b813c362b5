//! The ray tree: from each camera ray, shadow rays to the lights and reflected and refracted
//! child rays, pruned by depth and by attenuation (the path weight).
//!
//! Radiance is not scaled by (n2/n1)² when a ray refracts. Every path that reaches the
//! camera starts and ends in the scene's surrounding medium (lights and background live
//! there too), so the factors of entering and leaving a medium cancel; leaving them out
//! keeps R + (1 − R) = 1 at every split, which the white-furnace test checks.

use crate::camera::{Camera, CameraFrame};
use crate::light::Light;
use crate::material::{Dielectric, Material, Texture};
use crate::math::sampling::{phong_lobe, to_world};
use crate::math::{Color, Ray, SampleStream, Vec3, offset_ray_origin};
use crate::optics::{reflect, refract};
use crate::params::{Params, TreeMode};
use crate::scene::{Hit, Scene};
use glam::Vec2;
use std::f32::consts::PI;
use std::ops::AddAssign;

/// What the tracer did: rays by kind and branches pruned.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Stats {
    /// Camera samples taken.
    pub samples: u64,
    /// Eye rays.
    pub camera_rays: u64,
    /// Rays towards lights.
    pub shadow_rays: u64,
    /// Reflected rays.
    pub reflection_rays: u64,
    /// Refracted rays.
    pub refraction_rays: u64,
    /// Hits where the refracted ray does not exist: total internal reflection.
    pub tir_events: u64,
    /// Branches not traced because they would exceed `max_depth`.
    pub pruned_by_depth: u64,
    /// Branches not traced because their path weight fell below `min_weight`.
    pub pruned_by_weight: u64,
    /// Samples dropped because they were NaN or infinite.
    pub non_finite: u64,
}

impl Stats {
    /// All rays traced, of every kind.
    pub fn total_rays(&self) -> u64 {
        self.camera_rays + self.shadow_rays + self.reflection_rays + self.refraction_rays
    }
}

impl AddAssign for Stats {
    fn add_assign(&mut self, o: Stats) {
        self.samples += o.samples;
        self.camera_rays += o.camera_rays;
        self.shadow_rays += o.shadow_rays;
        self.reflection_rays += o.reflection_rays;
        self.refraction_rays += o.refraction_rays;
        self.tir_events += o.tir_events;
        self.pruned_by_depth += o.pruned_by_depth;
        self.pruned_by_weight += o.pruned_by_weight;
        self.non_finite += o.non_finite;
    }
}

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

/// How deeply dielectrics may nest (glass in water in glass ...); deeper entries are ignored.
pub const MAX_NESTING: usize = 8;

/// The dielectric objects a ray is inside, innermost last. Empty: the ray is in the
/// scene's surrounding medium.
#[derive(Clone, Copy, Debug, Default)]
pub struct Media {
    len: u8,
    // (object, material) of each medium entered.
    items: [(u32, u32); MAX_NESTING],
}

impl PartialEq for Media {
    fn eq(&self, other: &Media) -> bool {
        self.active() == other.active()
    }
}

impl Eq for Media {}

impl Media {
    fn active(&self) -> &[(u32, u32)] {
        &self.items[..self.len as usize]
    }

    /// The innermost medium's material.
    fn innermost(&self) -> Option<u32> {
        self.len.checked_sub(1).map(|i| self.items[i as usize].1)
    }

    /// After entering `object` made of `material`.
    fn entered(mut self, object: u32, material: u32) -> Media {
        if (self.len as usize) < MAX_NESTING {
            self.items[self.len as usize] = (object, material);
            self.len += 1;
        }
        self
    }

    /// After leaving `object` (the innermost one, unless geometry overlaps).
    fn left(mut self, object: u32) -> Media {
        if let Some(i) = self.active().iter().rposition(|&(o, _)| o == object) {
            self.items.copy_within(i + 1..self.len as usize, i);
            self.len -= 1;
        }
        self
    }
}

/// exp(−σ t) per channel; exactly 1 where σ = 0 (even for t = ∞).
#[inline]
fn transmittance(sigma: Color, t: f32) -> Color {
    Color::select(sigma.cmpeq(Color::ZERO), Color::ONE, (-sigma * t).exp())
}

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
    /// Not traced: it would exceed the maximum depth.
    DepthLimit,
    /// Not traced: its path weight fell below the minimum.
    WeightLimit,
    /// The refracted ray does not exist: total internal reflection.
    TotalInternalReflection,
    /// A shadow ray that reached its light.
    Lit,
    /// A shadow ray blocked on its way.
    Occluded,
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
}

/// Watches the ray tree being traced. The renderer uses [`NoRecorder`], for which all of
/// this compiles away; the inspector uses [`RayTree`].
pub trait Recorder {
    /// A ray about to be traced; returns its id.
    fn ray(&mut self, _node: TreeNode) -> usize {
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
    /// The children of node `id`, in order.
    pub fn children(&self, id: usize) -> impl Iterator<Item = (usize, &TreeNode)> {
        self.nodes
            .iter()
            .enumerate()
            .filter(move |(_, n)| n.parent == Some(id))
    }
}

impl Recorder for RayTree {
    fn ray(&mut self, node: TreeNode) -> usize {
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

/// What travels down the tree with every ray: the sample's random numbers, the counters,
/// and the recorder.
struct Walk<'w, R: Recorder> {
    rng: &'w mut SampleStream,
    stats: &'w mut Stats,
    rec: &'w mut R,
}

/// Where a ray sits in the tree.
#[derive(Clone, Copy)]
struct Branch {
    depth: u32,
    weight: f32,
    kind: RayKind,
    parent: Option<usize>,
    factor: f32,
}

/// Traces the samples of one image of one scene under one set of parameters.
pub struct Tracer<'a> {
    scene: &'a Scene,
    params: &'a Params,
    // The scene's materials with the parameters' overrides (ior, fresnel) applied.
    materials: Vec<Material>,
    // The scene's lights at the parameters' light size.
    lights: Vec<Light>,
    frame: CameraFrame,
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
        Tracer {
            scene,
            params,
            materials: scene
                .materials
                .iter()
                .map(|m| m.with_params(params))
                .collect(),
            lights: scene
                .lights
                .iter()
                .map(|l| l.scaled(params.light_size))
                .collect(),
            frame: camera.frame(width as f32 / height as f32, camera.exposure(params)),
            width,
            height,
        }
    }

    /// Radiance of sample number `sample` of pixel (x, y). Its random numbers depend only
    /// on (seed, pixel, sample), so the result does too.
    pub fn sample(&self, x: u32, y: u32, sample: u32, stats: &mut Stats) -> Color {
        self.sample_recorded(x, y, sample, stats, &mut NoRecorder)
    }

    /// The whole ray tree of sample `sample` of pixel (x, y), with the radiance it gives:
    /// exactly what [`Tracer::sample`] computes, recorded.
    pub fn inspect(&self, x: u32, y: u32, sample: u32) -> (RayTree, Color) {
        let mut tree = RayTree::default();
        let c = self.sample_recorded(x, y, sample, &mut Stats::default(), &mut tree);
        (tree, c)
    }

    fn sample_recorded<R: Recorder>(
        &self,
        x: u32,
        y: u32,
        sample: u32,
        stats: &mut Stats,
        rec: &mut R,
    ) -> Color {
        let p = self.params;
        let mut rng =
            SampleStream::with_pattern(p.pattern, p.spp, p.seed, y * self.width + x, sample);
        // Dimensions in a fixed order: image position, lens, time, then the tree's own.
        let jitter = rng.next_2d();
        let lens = rng.next_2d();
        let time = rng.next_1d();
        let film = Vec2::new(
            (x as f32 + jitter.x) / self.width as f32,
            (y as f32 + jitter.y) / self.height as f32,
        );
        let ray = self.frame.ray(film, lens, time);
        stats.samples += 1;
        stats.camera_rays += 1;
        let mut walk = Walk {
            rng: &mut rng,
            stats,
            rec,
        };
        let root = Branch {
            depth: 0,
            weight: 1.0,
            kind: RayKind::Camera,
            parent: None,
            factor: 1.0,
        };
        self.trace_in(&ray, root, &Media::default(), &mut walk)
    }

    /// The index of refraction of the medium a ray in `media` travels through.
    fn ior_of(&self, media: &Media) -> f32 {
        media
            .innermost()
            .and_then(|m| self.materials[m as usize].dielectric())
            .map_or(self.scene.medium_ior, |d| d.ior)
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
        };
        self.trace_in(
            ray,
            branch,
            media,
            &mut Walk {
                rng,
                stats,
                rec: &mut NoRecorder,
            },
        )
    }

    fn trace_in<R: Recorder>(&self, ray: &Ray, b: Branch, media: &Media, w: &mut Walk<R>) -> Color {
        let id = w.rec.ray(TreeNode {
            parent: b.parent,
            kind: b.kind,
            ray: *ray,
            depth: b.depth,
            branch_weight: b.factor,
            path_weight: b.weight,
            hit: None,
            end_point: ray.at(100.0),
            end: End::Miss,
            radiance: Color::ZERO,
        });
        let sigma = media
            .innermost()
            .and_then(|m| self.materials[m as usize].dielectric())
            .map_or(Color::ZERO, |d| d.absorption);
        let hit = self.scene.intersect(ray, f32::INFINITY);
        // Area lights are seen where nothing is in front of them.
        let mut nearest = hit.map_or(f32::INFINITY, |h| h.surface.t);
        let mut emitted = None;
        for light in &self.lights {
            if let Some((t, radiance)) = light.hit(ray, nearest) {
                nearest = t;
                emitted = Some(radiance);
            }
        }
        let (radiance, end) = if let Some(radiance) = emitted {
            (transmittance(sigma, nearest) * radiance, End::LightHit)
        } else if let Some(hit) = hit {
            // Beer–Lambert along the segment just travelled.
            let tr = transmittance(sigma, hit.surface.t);
            let b = Branch {
                weight: b.weight * tr.max_element(),
                ..b
            };
            let (l, end) = self.shade(ray, &hit, b, id, media, w);
            (tr * l, end)
        } else {
            let l = transmittance(sigma, f32::INFINITY) * self.scene.background.radiance(ray.dir);
            (l, End::Miss)
        };
        if w.rec.on() {
            let end_point = if nearest.is_finite() {
                ray.at(nearest)
            } else {
                ray.at(100.0)
            };
            w.rec.finish(id, &|n| {
                n.end = end;
                n.radiance = radiance;
                n.end_point = end_point;
            });
        }
        radiance
    }

    /// Traces a child of node `parent` if the pruning rules allow, recording why not.
    #[allow(clippy::too_many_arguments)]
    fn child<R: Recorder>(
        &self,
        parent: usize,
        b: Branch,
        kind: RayKind,
        factor: f32,
        weight: f32,
        ray: &Ray,
        media: &Media,
        w: &mut Walk<R>,
    ) -> Color {
        let why = if b.depth >= self.params.max_depth {
            w.stats.pruned_by_depth += 1;
            Some(End::DepthLimit)
        } else if weight < self.params.min_weight {
            w.stats.pruned_by_weight += 1;
            Some(End::WeightLimit)
        } else {
            None
        };
        let child = Branch {
            depth: b.depth + 1,
            weight,
            kind,
            parent: Some(parent),
            factor,
        };
        match why {
            Some(end) => {
                w.rec.ray(TreeNode {
                    parent: Some(parent),
                    kind,
                    ray: *ray,
                    depth: child.depth,
                    branch_weight: factor,
                    path_weight: weight,
                    hit: None,
                    end_point: ray.origin,
                    end,
                    radiance: Color::ZERO,
                });
                Color::ZERO
            }
            None => {
                match kind {
                    RayKind::Refract => w.stats.refraction_rays += 1,
                    _ => w.stats.reflection_rays += 1,
                }
                self.trace_in(ray, child, media, w)
            }
        }
    }

    fn shade<R: Recorder>(
        &self,
        ray: &Ray,
        hit: &Hit,
        b: Branch,
        id: usize,
        media: &Media,
        w: &mut Walk<R>,
    ) -> (Color, End) {
        let s = &hit.surface;
        let entering = ray.dir.dot(s.n_geom) < 0.0;
        // Normals facing the side the ray arrived from.
        let (n_geom, n_shade) = if entering {
            (s.n_geom, s.n_shade)
        } else {
            (-s.n_geom, -s.n_shade)
        };
        if w.rec.on() {
            let cos_i = (-ray.dir).dot(n_shade).clamp(0.0, 1.0);
            let node_hit = NodeHit {
                object: hit.object,
                material: hit.material,
                point: s.p,
                theta_i: cos_i.acos().to_degrees(),
                theta_t: None,
                n1_n2: None,
                f_s_f_p: None,
                r_exact_schlick: None,
                r: None,
            };
            w.rec.finish(id, &|n| n.hit = Some(node_hit));
        }
        let reflected = || {
            let dir = reflect(ray.dir, n_shade);
            // A shading normal can tilt the mirror direction below the surface.
            let dir = if dir.dot(n_geom) > 0.0 {
                dir
            } else {
                reflect(ray.dir, n_geom)
            };
            Ray {
                origin: offset_ray_origin(s.p, n_geom),
                dir,
                time: ray.time,
            }
        };
        let material = &self.materials[hit.material as usize];
        match material {
            Material::Emissive { radiance } => (*radiance, End::LightHit),
            Material::Diffuse {
                albedo,
                specular,
                exponent,
            } => (
                self.diffuse(
                    ray, hit, n_geom, n_shade, albedo, *specular, *exponent, id, w,
                ),
                End::Absorbed,
            ),
            Material::Mirror { reflectance } | Material::Glossy { reflectance, .. } => {
                let mut child = reflected();
                if let Material::Glossy { exponent, .. } = material {
                    // Jitter the mirror direction over the Phong lobe around it. Sampling
                    // the normalized lobe exactly, each jittered ray carries the reflectance.
                    let u = w.rng.next_2d();
                    let mut dir = to_world(phong_lobe(u, *exponent), child.dir);
                    // Lobe directions below the surface are folded back above it (mirrored
                    // in the tangent plane): no energy lost, no black speckles at grazing.
                    let below = dir.dot(n_geom);
                    if below <= 0.0 {
                        dir = (dir - 2.0 * below * n_geom).normalize();
                    }
                    child.dir = dir;
                }
                let k = reflectance.max_element();
                let l = self.child(id, b, RayKind::Reflect, k, b.weight * k, &child, media, w);
                (*reflectance * l, End::Split)
            }
            Material::Glazed { coat, base } => {
                // The coat is seen from the medium the ray travels in; nothing enters it.
                let (n1, n2) = (self.ior_of(media), coat.ior);
                let cos_i = (-ray.dir).dot(n_shade).clamp(0.0, 1.0);
                let r = coat
                    .fresnel
                    .reflectance(cos_i, n1, n2, coat.constant_reflectance);
                if w.rec.on() {
                    record_interface(w.rec, id, cos_i, n1, n2, r);
                }
                let mut l = (1.0 - r)
                    * self.diffuse(ray, hit, n_geom, n_shade, base, Color::ZERO, 1.0, id, w);
                if r > 0.0 {
                    l += r * self.child(
                        id,
                        b,
                        RayKind::Reflect,
                        r,
                        b.weight * r,
                        &reflected(),
                        media,
                        w,
                    );
                }
                (l, End::Split)
            }
            Material::Dielectric(d) => (
                self.dielectric(
                    ray,
                    hit,
                    d,
                    entering,
                    n_geom,
                    n_shade,
                    reflected(),
                    b,
                    id,
                    media,
                    w,
                ),
                End::Split,
            ),
        }
    }

    /// The lecture's ray tree at a dielectric: a reflected child of weight R and a
    /// refracted child of weight 1 − R (or, in stochastic mode, one of them with
    /// probability R and 1 − R).
    #[allow(clippy::too_many_arguments)]
    fn dielectric<R: Recorder>(
        &self,
        ray: &Ray,
        hit: &Hit,
        d: &Dielectric,
        entering: bool,
        n_geom: Vec3,
        n_shade: Vec3,
        reflected: Ray,
        b: Branch,
        id: usize,
        media: &Media,
        w: &mut Walk<R>,
    ) -> Color {
        let p = hit.surface.p;
        let (n1, n2, media_t) = if entering {
            (
                self.ior_of(media),
                d.ior,
                media.entered(hit.object, hit.material),
            )
        } else {
            let outside = media.left(hit.object);
            (d.ior, self.ior_of(&outside), outside)
        };
        let cos_i = (-ray.dir).dot(n_shade).clamp(0.0, 1.0);
        // Snell's law; the refracted ray must cross the geometric surface.
        let refracted = refract(ray.dir, n_shade, n1, n2)
            .filter(|t| t.dot(n_geom) < 0.0)
            .or_else(|| refract(ray.dir, n_geom, n1, n2))
            .map(|dir| Ray {
                origin: offset_ray_origin(p, -n_geom),
                dir,
                time: ray.time,
            });
        let r = match refracted {
            Some(_) => d.fresnel.reflectance(cos_i, n1, n2, d.constant_reflectance),
            None => {
                w.stats.tir_events += 1;
                1.0
            }
        };
        if w.rec.on() {
            record_interface(w.rec, id, cos_i, n1, n2, r);
            if refracted.is_none() {
                // The refracted branch that total internal reflection forbids.
                w.rec.ray(TreeNode {
                    parent: Some(id),
                    kind: RayKind::Refract,
                    ray: reflected,
                    depth: b.depth + 1,
                    branch_weight: 0.0,
                    path_weight: 0.0,
                    hit: None,
                    end_point: p,
                    end: End::TotalInternalReflection,
                    radiance: Color::ZERO,
                });
            }
        }
        match self.params.tree {
            TreeMode::Split => {
                let mut l = Color::ZERO;
                if r > 0.0 {
                    l += r * self.child(
                        id,
                        b,
                        RayKind::Reflect,
                        r,
                        b.weight * r,
                        &reflected,
                        media,
                        w,
                    );
                }
                if let Some(t) = refracted
                    && r < 1.0
                {
                    l += (1.0 - r)
                        * self.child(
                            id,
                            b,
                            RayKind::Refract,
                            1.0 - r,
                            b.weight * (1.0 - r),
                            &t,
                            &media_t,
                            w,
                        );
                }
                l
            }
            TreeMode::Stochastic => {
                // Choosing a child with probability equal to its weight leaves the path
                // weight unchanged: R / P(reflect) = 1.
                if b.depth >= self.params.max_depth || b.weight < self.params.min_weight {
                    // Let `child` count and record the cut.
                    return self.child(
                        id,
                        b,
                        RayKind::Reflect,
                        1.0,
                        b.weight,
                        &reflected,
                        media,
                        w,
                    );
                }
                match refracted {
                    Some(t) if w.rng.next_1d() >= r => {
                        self.child(id, b, RayKind::Refract, 1.0, b.weight, &t, &media_t, w)
                    }
                    _ => self.child(id, b, RayKind::Reflect, 1.0, b.weight, &reflected, media, w),
                }
            }
        }
    }

    /// Diffuse shading: ambient plus every light, one shadow ray to one sampled point of
    /// each: L = a·L_ambient + Σ f(l, v) (L_light / p(l)) cos θ, with f the Lambert plus
    /// normalized Phong BRDF.
    #[allow(clippy::too_many_arguments)]
    fn diffuse<R: Recorder>(
        &self,
        ray: &Ray,
        hit: &Hit,
        n_geom: Vec3,
        n: Vec3,
        albedo: &Texture,
        specular: Color,
        exponent: f32,
        id: usize,
        w: &mut Walk<R>,
    ) -> Color {
        let albedo = albedo.eval(hit.surface.uv);
        let p = hit.surface.p;
        let origin = offset_ray_origin(p, n_geom);
        let view = -ray.dir;
        let mut sum = self.scene.ambient * albedo;
        for light in &self.lights {
            let u = w.rng.next_2d();
            let Some(ls) = light.sample(p, u) else {
                continue;
            };
            let cos = n.dot(ls.dir);
            if cos <= 0.0 || n_geom.dot(ls.dir) <= 0.0 {
                continue;
            }
            w.stats.shadow_rays += 1;
            let shadow = Ray {
                origin,
                dir: ls.dir,
                time: ray.time,
            };
            // Stop just short of the light's surface (it is not in the BVH anyway).
            let blocked = self.scene.occluded(&shadow, ls.dist * (1.0 - 1e-4));
            let mut contribution = Color::ZERO;
            if !blocked {
                let mut f = albedo / PI;
                if specular != Color::ZERO {
                    let cos_alpha = reflect(-ls.dir, n).dot(view).max(0.0);
                    f += specular * (exponent + 2.0) / (2.0 * PI) * cos_alpha.powf(exponent);
                }
                contribution = f * ls.value * cos;
                sum += contribution;
            }
            if w.rec.on() {
                w.rec.ray(TreeNode {
                    parent: Some(id),
                    kind: RayKind::Shadow,
                    ray: shadow,
                    depth: 0,
                    branch_weight: 1.0,
                    path_weight: 0.0,
                    hit: None,
                    end_point: shadow.at(ls.dist),
                    end: if blocked { End::Occluded } else { End::Lit },
                    radiance: contribution,
                });
            }
        }
        sum
    }
}

/// Records the lecture's quantities at a dielectric interface hit by node `id`.
fn record_interface<R: Recorder>(rec: &mut R, id: usize, cos_i: f32, n1: f32, n2: f32, r: f32) {
    let (f_s, f_p, r_exact) = crate::optics::fresnel_exact(cos_i, n1, n2);
    let theta_t = crate::optics::cos_transmitted(cos_i, n1, n2).map(|c| c.acos().to_degrees());
    let r_schlick = crate::optics::schlick(cos_i, n1, n2);
    rec.finish(id, &|n| {
        if let Some(h) = &mut n.hit {
            h.theta_t = theta_t;
            h.n1_n2 = Some((n1, n2));
            h.f_s_f_p = Some((f_s, f_p));
            h.r_exact_schlick = Some((r_exact, r_schlick));
            h.r = Some(r);
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn media_enter_and_leave_in_any_order() {
        let m = Media::default().entered(3, 10).entered(5, 11);
        assert_eq!(m.innermost(), Some(11));
        assert_eq!(m.left(5).innermost(), Some(10));
        // Leaving the outer one first (overlapping geometry) keeps the inner.
        assert_eq!(m.left(3).innermost(), Some(11));
        assert_eq!(m.left(3).left(5), Media::default());
        // Leaving what was never entered changes nothing.
        assert_eq!(m.left(9), m);
    }

    #[test]
    fn transmittance_is_beer_lambert_and_one_without_absorption() {
        let t = transmittance(Color::new(0.0, 1.0, 2.0), 0.5);
        assert_eq!(t.x, 1.0);
        assert!((t.y - (-0.5f32).exp()).abs() < 1e-7);
        assert!((t.z - (-1.0f32).exp()).abs() < 1e-7);
        assert_eq!(
            transmittance(Color::new(0.0, 1.0, 0.0), f32::INFINITY),
            Color::new(1.0, 0.0, 1.0)
        );
    }
}
