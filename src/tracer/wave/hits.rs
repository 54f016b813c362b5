//! The hits of one level of the waves, made in lanes: where `N` neighbouring rays met the
//! same sphere, quad or plane (as a tile's rays mostly do), or two or three of them, their
//! hit records and the radiance their surface emits where it is a light are computed `N` at
//! a time, and where all `N` met one dielectric, its reflected and refracted directions and
//! Fresnel reflectance from the same lanes; other rays one by one, and the other hits on
//! dielectrics split `N` at a time after. Either way each is what the scalar code gives,
//! bit for bit.

use super::types::Node;
use crate::geometry::{Facing, PrimRef};
use crate::material::{Dielectric, Split, split_lanes};
use crate::math::lanes::{LaneKernel, Lanes, RayColumns, Real, V3};
use crate::math::{Color, Ray};
use crate::scene::Hit;
use crate::tracer::{Media, Tracer};

/// The hit records of a level's rays: only the rays that have one, each ray's place in
/// that list beside. (A list of `Option<Hit>` writes 96 bytes for every ray without a
/// record, most of a level where its rays meet a light: docs/performance.md, "Shaped by
/// measurement".)
#[derive(Default)]
pub(super) struct Hits {
    records: Vec<Hit>,
    // Per ray, its record's place, or NONE.
    of: Vec<u32>,
}

const NONE: u32 = u32::MAX;

impl Hits {
    fn clear(&mut self) {
        self.records.clear();
        self.of.clear();
    }

    fn push(&mut self, hit: Option<Hit>) {
        match hit {
            Some(hit) => {
                self.of.push(self.records.len() as u32);
                self.records.push(hit);
            }
            None => self.of.push(NONE),
        }
    }

    /// The hit of ray `i` of the level, if it has a record.
    #[inline(always)]
    pub(super) fn get(&self, i: usize) -> Option<&Hit> {
        self.records.get(*self.of.get(i)? as usize)
    }

    /// Each ray's hit, in order.
    pub(super) fn iter(&self) -> impl Iterator<Item = Option<&Hit>> {
        self.of.iter().map(|&k| self.records.get(k as usize))
    }
}

/// The hits of a level's rays (none where the ray met nothing, or where `N` neighbours
/// met one light, which needs no records), what each hit's surface emits (`None`: it is
/// not a light), from the nearest primitive and distance of each ray (the rays' nodes and
/// media beside); and the hits on dielectrics: where `N` neighbours met one, their splits
/// (`splits`, each with its place in the level), made from the same lanes as their
/// records; the others' places, in order, for [`Splits`].
pub(super) struct Surfaces<'a, 't> {
    pub(super) tracer: &'a Tracer<'t>,
    pub(super) rays: &'a RayColumns,
    pub(super) nearest: &'a [Option<(PrimRef, f32)>],
    pub(super) nodes: &'a [Node],
    pub(super) media: &'a [Media],
    pub(super) hits: &'a mut Hits,
    pub(super) emitted: &'a mut Vec<Option<Color>>,
    pub(super) on_dielectrics: &'a mut Vec<u32>,
    pub(super) splits: &'a mut Vec<(u32, Split)>,
}

impl LaneKernel for Surfaces<'_, '_> {
    type Output = ();
    #[inline(always)]
    fn run<const N: usize>(self) {
        let Surfaces {
            tracer,
            rays,
            nearest,
            nodes,
            media,
            hits,
            emitted,
            on_dielectrics,
            splits,
        } = self;
        hits.clear();
        emitted.clear();
        on_dielectrics.clear();
        splits.clear();
        let materials = &tracer.materials;
        // A dispersive glass splits a ray without a wavelength into its wavelengths (the
        // scalar code does that); a ray carrying one is split at its own indices. (Asked
        // only in a scene that disperses, so that the others do not pay for it.)
        let splits_into_wavelengths = |m: u32, k: usize| {
            // (The node read only in such a scene.)
            tracer.dispersive && tracer.splits_into_wavelengths(m, nodes[k].wavelength())
        };
        let dielectric = |m: u32, k: usize| {
            materials[m as usize].splitting().is_some() && !splits_into_wavelengths(m, k)
        };
        for (c, chunk) in nearest.chunks(N).enumerate() {
            let first = c * N;
            // (The last chunk may be short.)
            let full = chunk.len() == N;
            let t = Lanes::from_fn(|k| chunk.get(k).copied().flatten().map_or(0.0, |(_, t)| t));
            let ray_lanes = rays.lanes::<N>(first);
            if full
                && let Some(object) = one_object(chunk)
                && let Some((lanes, material)) = tracer.scene.hits_in_lanes(object, ray_lanes, t)
            {
                let (u, v) = lanes.uv;
                if let Some(radiance) = materials[material as usize].emission_lanes(u, v) {
                    // Every ray met one light (as most of a level's rays do where they see
                    // an emitting surface): its radiance is all their nodes need, no records.
                    emitted.extend(radiance.iter().map(|&l| Some(l)));
                    hits.of.extend([NONE; N]);
                    continue;
                }
                let hit = |k: usize| Hit {
                    surface: lanes.get(k, t.0[k]),
                    object,
                    material,
                };
                let at = hits.records.len() as u32;
                hits.records.extend((0..N).map(hit));
                hits.of.extend(at..at + N as u32);
                if let Some(d) = materials[material as usize].splitting()
                    && !(first..first + N).any(|k| splits_into_wavelengths(material, k))
                {
                    let made =
                        tracer.split_in_lanes([d; N], ray_lanes.dir, lanes.n, lanes.n, |k| {
                            let node = &nodes[first + k];
                            (&media[node.media as usize], object, node.wavelength())
                        });
                    splits.extend((first as u32..).zip(made));
                }
                emitted.extend(std::iter::repeat_n(None, N));
                continue;
            }
            // A short chunk, and rays on many objects, are made ray by ray.
            let Some(objects) = full.then(|| objects_of::<MAX_OBJECTS>(chunk)).flatten() else {
                let found = Found {
                    hits,
                    emitted,
                    on_dielectrics,
                };
                found.by_ray(tracer, &dielectric, rays, first, chunk);
                continue;
            };
            // Else object by object, each one's records in lanes where its shape has a
            // lanes formula, its rays' places in the level filled in.
            let base = hits.of.len();
            hits.of.extend([NONE; N]);
            emitted.extend(std::iter::repeat_n(None, N));
            for object in objects.into_iter().flatten() {
                let on = |k: &usize| chunk[*k].is_some_and(|(prim, _)| prim.object == object);
                let Some((lanes, material)) = tracer.scene.hits_in_lanes(object, ray_lanes, t)
                else {
                    for k in (0..N).filter(on) {
                        let near = chunk[k].map(|(prim, t)| (prim, rays.get(first + k), t));
                        let (hit, light) = tracer.surface_at(near);
                        emitted[base + k] = light;
                        if let Some(hit) = hit {
                            hits.of[base + k] = hits.records.len() as u32;
                            hits.records.push(hit);
                        }
                    }
                    continue;
                };
                let (u, v) = lanes.uv;
                if let Some(radiance) = materials[material as usize].emission_lanes(u, v) {
                    for k in (0..N).filter(on) {
                        emitted[base + k] = Some(radiance[k]);
                    }
                    continue;
                }
                for k in (0..N).filter(on) {
                    hits.of[base + k] = hits.records.len() as u32;
                    hits.records.push(Hit {
                        surface: lanes.get(k, t.0[k]),
                        object,
                        material,
                    });
                }
            }
            // The hits on dielectrics, in the order of the level.
            for k in base..base + N {
                if hits.get(k).is_some_and(|h| dielectric(h.material, k)) {
                    on_dielectrics.push(k as u32);
                }
            }
        }
    }
}

/// Where a level's hits go: the records, the lights' radiance, and the places of the hits
/// on dielectrics.
struct Found<'a> {
    hits: &'a mut Hits,
    emitted: &'a mut Vec<Option<Color>>,
    on_dielectrics: &'a mut Vec<u32>,
}

impl Found<'_> {
    /// The hits of `chunk`'s rays (from ray `first` of the level) made one by one
    /// (`dielectric` says where the material of ray k's hit splits it in lanes).
    #[inline(always)]
    fn by_ray(
        self,
        tracer: &Tracer,
        dielectric: &impl Fn(u32, usize) -> bool,
        rays: &RayColumns,
        first: usize,
        chunk: &[Option<(PrimRef, f32)>],
    ) {
        for (k, near) in chunk.iter().enumerate() {
            let near = near.map(|(prim, t)| (prim, rays.get(first + k), t));
            let (hit, light) = tracer.surface_at(near);
            self.emitted.push(light);
            if hit.is_some_and(|h| dielectric(h.material, first + k)) {
                self.on_dielectrics.push((first + k) as u32);
            }
            self.hits.push(hit);
        }
    }
}

impl Tracer<'_> {
    /// The splits of `N` hits on `dielectrics` (the rays' directions `dir`, the surfaces'
    /// normals `n_geom` and `n_shade`), each ray's media, the object it met and the
    /// wavelength it carries given by `of_ray`: as `Arrival::at` and the scalar split make
    /// them, the normals turned to face the ray, the indices at each ray's wavelength, the
    /// one outside taken from the media.
    #[inline(always)]
    fn split_in_lanes<'d, 'm, const N: usize>(
        &self,
        dielectrics: [&'d Dielectric; N],
        dir: V3<Lanes<N>>,
        n_geom: V3<Lanes<N>>,
        n_shade: V3<Lanes<N>>,
        of_ray: impl Fn(usize) -> (&'m Media, u32, Option<f32>),
    ) -> impl Iterator<Item = Split> + 'd {
        let facing = Facing::<Lanes<N>>::of(dir, n_geom, n_shade);
        let entering = facing.entering;
        let mut ior = Lanes::<N>::splat(0.0);
        let outside_ior = Lanes::<N>::from_fn(|k| {
            let (media, object, wavelength) = of_ray(k);
            ior.0[k] = dielectrics[k].ior_at(wavelength);
            self.ior_of(media.outside(entering.0[k] != 0, object), wavelength)
        });
        split_lanes(dielectrics, dir, facing, ior, outside_ior)
    }

    /// The hit of a ray that met `near` (its primitive, the ray, the distance), and the
    /// radiance its surface emits where it is a light.
    #[inline(always)]
    fn surface_at(&self, near: Option<(PrimRef, Ray, f32)>) -> (Option<Hit>, Option<Color>) {
        let hit = near.map(|(prim, ray, t)| self.scene.hit_at(prim, &ray, t));
        let material = |h: &Hit| &self.materials[h.material as usize];
        let light = hit.and_then(|h| material(&h).light_emission(h.surface.uv));
        (hit, light)
    }
}

/// The split of each hit of a level on a dielectric that [`Surfaces`] did not split (the
/// places `on_dielectrics` lists) into its reflected and refracted rays, with its place in
/// the level, in that order: `N` at a time, gathered from wherever they are in the level.
pub(super) struct Splits<'a, 't> {
    pub(super) tracer: &'a Tracer<'t>,
    pub(super) rays: &'a RayColumns,
    pub(super) nodes: &'a [Node],
    pub(super) media: &'a [Media],
    pub(super) hits: &'a Hits,
    pub(super) on_dielectrics: &'a [u32],
    pub(super) splits: &'a mut Vec<(u32, Split)>,
}

impl LaneKernel for Splits<'_, '_> {
    type Output = ();
    #[inline(always)]
    fn run<const N: usize>(self) {
        let Splits {
            tracer,
            rays,
            nodes,
            media,
            hits,
            on_dielectrics,
            splits,
        } = self;
        splits.clear();
        for group in on_dielectrics.chunks(N) {
            // Each hit's dielectric; a short last group repeats its last hit in the lanes
            // past it, and only the group's own lanes are kept.
            let on = |i: u32| {
                let hit = hits.get(i as usize)?;
                let dielectric = tracer.materials[hit.material as usize].splitting()?;
                Some((i, hit, dielectric))
            };
            let Some(last) = group.last().and_then(|&i| on(i)) else {
                continue;
            };
            let lanes: [_; N] = std::array::from_fn(|k| group.get(k).and_then(|&i| on(i)));
            let lane = |k: usize| lanes[k].unwrap_or(last);
            let at = |k: usize| lane(k).0 as usize;
            let hit = |k: usize| lane(k).1;
            let dielectrics: [_; N] = std::array::from_fn(|k| lane(k).2);
            let surface = |k: usize| hit(k).surface;
            let dir = V3::from_fn(|k| rays.get(at(k)).dir);
            let n_geom = V3::from_fn(|k| surface(k).n_geom);
            let n_shade = V3::from_fn(|k| surface(k).n_shade);
            let made = tracer.split_in_lanes(dielectrics, dir, n_geom, n_shade, |k| {
                let node = &nodes[at(k)];
                (
                    &media[node.media as usize],
                    hit(k).object,
                    node.wavelength(),
                )
            });
            let kept = lanes
                .iter()
                .zip(made)
                .filter_map(|(l, s)| l.map(|(i, ..)| (i, s)));
            splits.extend(kept);
        }
    }
}

/// The most objects the rays of one chunk may meet for their records to be made in lanes,
/// once per object.
const MAX_OBJECTS: usize = 3;

/// The objects the rays of `chunk` met, each once, in the order they are first met (none
/// where no ray met anything); `None` where they met more than `K`.
#[inline(always)]
fn objects_of<const K: usize>(chunk: &[Option<(PrimRef, f32)>]) -> Option<[Option<u32>; K]> {
    let mut objects = [None; K];
    let mut count = 0;
    for (prim, _) in chunk.iter().flatten() {
        let object = Some(prim.object);
        if objects[..count].contains(&object) {
            continue;
        }
        *objects.get_mut(count)? = object;
        count += 1;
    }
    Some(objects)
}

/// The object every ray of `chunk` met, if they all met one.
#[inline(always)]
fn one_object(chunk: &[Option<(PrimRef, f32)>]) -> Option<u32> {
    let object = chunk.first()?.as_ref()?.0.object;
    // Without an early exit: the chunks that do not qualify are few, and a branch per ray
    // costs more than the compares.
    chunk
        .iter()
        .fold(true, |all, near| {
            all & near.is_some_and(|(prim, _)| prim.object == object)
        })
        .then_some(object)
}
