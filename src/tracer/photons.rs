//! The caustics of point lights (`transport = "photons"`), by progressive photon mapping.
//!
//! A path from the camera can never hit a point light, and a light sample cannot pass
//! through glass, so light from a point light focused by glass or a mirror (L S+ D) is
//! what path tracing misses. For each sample number, photons are shot from every point
//! light towards the mirror-like objects (each object's bounding sphere, so that none is
//! wasted on the floor), followed through their mirrors and interfaces as a path follows
//! them, and stored where they land on a diffuse surface after at least one such bounce. A
//! path that meets a diffuse surface adds the photons within radius r around it:
//! L = Σ f(ωp, ωo) Φp / (π r²). Each sample number n has its own photons and a smaller
//! radius, r² = r₀² · n^(−1/3) (Knaus and Zwicker's probabilistic progressive photon
//! mapping, α = 2/3), so the average over samples converges: blurred at first, sharp in
//! the end.

use super::crossing::cross;
use super::media::transmittance;
use super::{Media, Tracer};
use crate::geometry::{KeyHasher, Shape};
use crate::material::{Brdf, Interaction, Part};
use crate::math::rng::mix64;
use crate::math::sampling::{to_world, uniform_cone};
use crate::math::{Color, Ray, SampleStream, Vec3, offset_ray_origin};
use rayon::prelude::*;
use std::collections::HashMap;
use std::f32::consts::PI;
use std::hash::BuildHasherDefault;

/// Photons shot per sample of a pass.
const PHOTONS_PER_SAMPLE: u32 = 20_000;

/// The gather radius of the first pass, as a fraction of the mean radius of the objects
/// photons are aimed at.
const FIRST_RADIUS: f32 = 0.03;

/// A photon stored on a diffuse surface.
#[derive(Clone, Copy, Debug)]
struct Photon {
    p: Vec3,
    // The surface's geometric normal, on the side the photon arrived from.
    n: Vec3,
    // Towards where it came from.
    wi: Vec3,
    power: Color,
}

/// The photons of one pass, in a grid of cells twice the gather radius wide.
#[derive(Debug)]
pub(super) struct PhotonMap {
    photons: Vec<Photon>,
    // Cell key → the range of `photons` in it (photons are sorted by key).
    cells: HashMap<u64, (u32, u32), BuildHasherDefault<KeyHasher>>,
    radius: f32,
    // Where the photons are, grown by the radius: most gathers are outside.
    lo: Vec3,
    hi: Vec3,
}

/// A cone of directions from a light towards an object's bounding sphere, and the share of
/// the photons it gets.
#[derive(Debug)]
pub(super) struct Target {
    light: usize,
    axis: Vec3,
    cos_max: f32,
    share: f32,
}

impl Target {
    fn solid_angle(&self) -> f32 {
        2.0 * PI * (1.0 - self.cos_max)
    }
}

/// The key of grid cell (x, y, z): the coordinates packed 21 bits each and mixed. Cells
/// far apart may share a key; they then share a range, which the distance test sorts out.
fn key(x: i32, y: i32, z: i32) -> u64 {
    let m = |v: i32| (v as u32 & 0x1f_ffff) as u64;
    mix64(m(x) | m(y) << 21 | m(z) << 42)
}

/// The cell of `p` in cells of width `w`, as coordinates.
fn cell_of(p: Vec3, w: f32) -> glam::IVec3 {
    (p / w).floor().as_ivec3()
}

impl PhotonMap {
    fn new(mut photons: Vec<Photon>, radius: f32) -> PhotonMap {
        let w = 2.0 * radius;
        let key_of = |p: Vec3| {
            let c = cell_of(p, w);
            key(c.x, c.y, c.z)
        };
        photons.sort_unstable_by_key(|ph| key_of(ph.p));
        let mut cells = HashMap::default();
        let mut start = 0;
        for i in 1..=photons.len() {
            let k = key_of(photons[start].p);
            if i == photons.len() || key_of(photons[i].p) != k {
                cells.insert(k, (start as u32, i as u32));
                start = i;
            }
        }
        let (lo, hi) = photons.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), ph| (lo.min(ph.p), hi.max(ph.p)),
        );
        PhotonMap {
            photons,
            cells,
            radius,
            lo: lo - radius,
            hi: hi + radius,
        }
    }

    /// The radiance the photons around `p` send back through the smooth BRDF `brdf`
    /// (scaled by `scale`) towards the viewer at `at`: Σ f Φ / (π r²) over the photons
    /// within r on the same side of the same surface.
    pub(super) fn gather(&self, p: Vec3, at: &Interaction, brdf: &Brdf, scale: f32) -> Color {
        if p.cmplt(self.lo).any() || p.cmpgt(self.hi).any() {
            return Color::ZERO;
        }
        let r = self.radius;
        // Cells 2r wide: the disc of radius r lies within the 2 × 2 × 2 cells nearest p.
        let c = cell_of(p - r, 2.0 * r);
        let view = -at.dir;
        let mut sum = Color::ZERO;
        for dx in 0..2 {
            for dy in 0..2 {
                for dz in 0..2 {
                    let Some(&(a, b)) = self.cells.get(&key(c.x + dx, c.y + dy, c.z + dz)) else {
                        continue;
                    };
                    for ph in &self.photons[a as usize..b as usize] {
                        if (ph.p - p).length_squared() > r * r
                            || ph.n.dot(at.n_geom) < 0.9
                            || ph.wi.dot(at.n_shade) <= 0.0
                        {
                            continue;
                        }
                        sum += brdf.eval(at.n_shade, ph.wi, view) * ph.power;
                    }
                }
            }
        }
        sum * (scale / (PI * r * r))
    }
}

impl Tracer<'_> {
    /// Whether samples gather photons (`transport = "photons"`): each sample number then
    /// needs its own, shot by [`Tracer::prepare_photons`] before it is traced.
    pub fn gathers_photons(&self) -> bool {
        self.params.transport == crate::params::Transport::Photons
    }

    /// Shoots the photons of sample number `sample` (of every pixel), if samples gather
    /// photons and there are point lights and mirror-like objects.
    pub fn prepare_photons(&mut self, sample: u32) {
        self.photons = None;
        if !self.gathers_photons() {
            return;
        }
        // The cones depend on the scene only: found once per tracer, not per sample (a
        // glass mesh's bounds take a pass over its triangles).
        if self.photon_targets.is_none() {
            self.photon_targets = Some(self.targets());
        }
        let Some((targets, mean_radius)) = &self.photon_targets else {
            return;
        };
        if targets.is_empty() {
            return;
        }
        let radius = FIRST_RADIUS * mean_radius * ((sample + 1) as f32).powf(-1.0 / 6.0);
        // Collected in photon order whatever the threads: the same map every time.
        let photons: Vec<Photon> = (0..PHOTONS_PER_SAMPLE)
            .into_par_iter()
            .flat_map_iter(|k| self.shoot(k, sample, targets))
            .collect();
        self.photons = Some(PhotonMap::new(photons, radius));
    }

    /// The cones from each point light to each mirror-like object, their shares in
    /// proportion to solid angle times intensity, and the objects' mean radius.
    fn targets(&self) -> (Vec<Target>, f32) {
        let spheres: Vec<(Vec3, f32)> = self
            .scene
            .shapes
            .iter()
            .zip(&self.scene.object_materials)
            .filter(|&(shape, &m)| {
                !matches!(shape, Shape::Plane(_)) && self.materials[m as usize].mirror_like()
            })
            .filter_map(|(shape, _)| {
                let b = (0..shape.primitive_count() as u32)
                    .map(|i| shape.primitive_bounds(i))
                    .reduce(|a, b| a.union(&b))?;
                let (lo, hi) = (Vec3::from(b.min), Vec3::from(b.max));
                Some((0.5 * (lo + hi), 0.5 * (hi - lo).length()))
            })
            .collect();
        let mut targets = Vec::new();
        for (l, light) in self.scene.lights.iter().enumerate() {
            let light = light.scaled(self.params.light_size);
            if light.point_intensity(Vec3::Y).is_none() {
                continue;
            }
            for &(center, radius) in &spheres {
                let to = center - light.center();
                let d2 = to.length_squared();
                let (axis, cos_max) = if d2 <= radius * radius {
                    (Vec3::Y, -1.0)
                } else {
                    (to / d2.sqrt(), (1.0 - radius * radius / d2).sqrt())
                };
                let t = Target {
                    light: l,
                    axis,
                    cos_max,
                    share: 0.0,
                };
                let weight = t.solid_angle() * light.intensity.max_element();
                targets.push(Target { share: weight, ..t });
            }
        }
        let total: f32 = targets.iter().map(|t| t.share).sum();
        if total <= 0.0 {
            return (Vec::new(), 1.0);
        }
        for t in &mut targets {
            t.share /= total;
        }
        let mean = spheres.iter().map(|s| s.1).sum::<f32>() / spheres.len().max(1) as f32;
        (targets, mean)
    }

    /// Photon `k` of sample number `sample`: from a light, along its target's cone, through
    /// mirror-like bounces, stored wherever it meets a diffuse surface after one at least.
    fn shoot(&self, k: u32, sample: u32, targets: &[Target]) -> Vec<Photon> {
        let mut out = Vec::new();
        self.shoot_into(k, sample, targets, &mut out);
        out
    }

    fn shoot_into(
        &self,
        k: u32,
        sample: u32,
        targets: &[Target],
        out: &mut Vec<Photon>,
    ) -> Option<()> {
        let mut rng = SampleStream::new(self.params.seed ^ 0x5eed_f0f0, k, sample);
        let pick = rng.next_1d();
        let mut acc = 0.0;
        let target = targets
            .iter()
            .find(|t| {
                acc += t.share;
                pick < acc
            })
            .unwrap_or(&targets[targets.len() - 1]);
        let dir = to_world(uniform_cone(rng.next_2d(), target.cos_max), target.axis);
        let light = self.scene.lights[target.light].scaled(self.params.light_size);
        let intensity = light.point_intensity(dir)?;
        // The density of `dir` over every cone of this light that contains it.
        let pdf: f32 = targets
            .iter()
            .filter(|t| t.light == target.light && dir.dot(t.axis) >= t.cos_max)
            .map(|t| t.share / t.solid_angle())
            .sum();
        if pdf <= 0.0 {
            return None;
        }
        let mut power = intensity / (PHOTONS_PER_SAMPLE as f32 * pdf);
        let (shutter_open, shutter) = (self.params.shutter_open, self.params.shutter);
        let mut ray = Ray {
            origin: light.center(),
            dir,
            time: shutter_open + shutter * rng.next_1d(),
        };
        let mut media = Media::default();
        let mut wavelength = None;
        for bounce in 0..=self.params.max_depth {
            let hit = self.scene.intersect(&ray, f32::INFINITY)?;
            power *= transmittance(self.absorption_in(&media), hit.surface.t);
            let material = &self.materials[hit.material as usize];
            let at = self.meet(&ray, &hit, &media, &mut wavelength, &mut power, &mut rng);
            let scatter = material.scatter(&at, &mut rng);
            let parts = scatter.parts();
            if bounce > 0 && scatter.direct.is_some() {
                out.push(Photon {
                    p: hit.surface.p,
                    n: at.n_geom,
                    wi: -ray.dir,
                    power,
                });
            }
            // On through a mirror-like part, chosen in proportion to its weight; the
            // other parts' share ends the photon (its light there is gathered or found by
            // paths).
            let sum: f32 = parts.iter().flatten().map(Part::weight).sum();
            let u = rng.next_1d() * sum;
            let mut acc = 0.0;
            let Some(Part::Lobe(lobe)) = parts.iter().flatten().find(|p| {
                acc += p.weight();
                u < acc
            }) else {
                return None;
            };
            if !lobe.is_delta() {
                return None;
            }
            power *= lobe.weight * (sum / lobe.weight.max_element());
            let side_n = cross(&mut media, &at, &hit, lobe.side);
            ray = Ray {
                origin: offset_ray_origin(hit.surface.p, side_n),
                dir: lobe.dir,
                time: ray.time,
            };
        }
        None
    }
}
