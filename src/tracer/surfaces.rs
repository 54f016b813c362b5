//! The hits of one level of the waves, made in lanes: where `N` neighbouring rays all met
//! the same sphere, quad or plane (as a tile's rays mostly do), their hit records, and the
//! radiance their surface emits where it is a light, are computed `N` at a time; other rays
//! one by one. Either way each hit is [`crate::scene::Scene::hit_at`]'s bit for bit.

use super::Tracer;
use crate::geometry::PrimRef;
use crate::math::Color;
use crate::math::lanes::{LaneKernel, Lanes, RayColumns};
use crate::scene::Hit;

/// The hits of a level's rays (`None`: the ray met nothing) and what each hit's surface
/// emits (`None`: it is not a light), from the nearest primitive and distance of each ray.
pub(super) struct Surfaces<'a, 't> {
    pub(super) tracer: &'a Tracer<'t>,
    pub(super) rays: &'a RayColumns,
    pub(super) nearest: &'a [Option<(PrimRef, f32)>],
    pub(super) hits: &'a mut Vec<Option<Hit>>,
    pub(super) emitted: &'a mut Vec<Option<Color>>,
}

impl LaneKernel for Surfaces<'_, '_> {
    type Output = ();
    #[inline(always)]
    fn run<const N: usize>(self) {
        let Surfaces {
            tracer,
            rays,
            nearest,
            hits,
            emitted,
        } = self;
        hits.clear();
        emitted.clear();
        for (c, chunk) in nearest.chunks(N).enumerate() {
            let first = c * N;
            // The last chunk may be short: it is made ray by ray.
            let in_lanes = one_object(chunk)
                .filter(|_| chunk.len() == N)
                .and_then(|object| {
                    let t = Lanes(std::array::from_fn(|k| chunk[k].map_or(0.0, |(_, t)| t)));
                    tracer
                        .scene
                        .hits_in_lanes(object, rays.lanes::<N>(first), t)
                });
            match in_lanes {
                Some((lanes, material)) => {
                    let hit = |k: usize| Hit {
                        surface: lanes.get(k, chunk[k].map_or(0.0, |(_, t)| t)),
                        object: chunk[k].map_or(0, |(prim, _)| prim.object),
                        material,
                    };
                    hits.extend((0..N).map(|k| Some(hit(k))));
                    let (u, v) = lanes.uv;
                    match tracer.materials[material as usize].emission_lanes(u, v) {
                        Some(radiance) => emitted.extend(radiance.iter().map(|&l| Some(l))),
                        None => emitted.extend(std::iter::repeat_n(None, N)),
                    }
                }
                None => {
                    for (k, near) in chunk.iter().enumerate() {
                        let hit = near
                            .map(|(prim, t)| tracer.scene.hit_at(prim, &rays.get(first + k), t));
                        let material = |h: &Hit| &tracer.materials[h.material as usize];
                        emitted.push(hit.and_then(|h| material(&h).emission(h.surface.uv)));
                        hits.push(hit);
                    }
                }
            }
        }
    }
}

/// The object every ray of `chunk` met, if they all met one.
#[inline(always)]
fn one_object(chunk: &[Option<(PrimRef, f32)>]) -> Option<u32> {
    let object = chunk.first()?.as_ref()?.0.object;
    chunk
        .iter()
        .all(|near| near.is_some_and(|(prim, _)| prim.object == object))
        .then_some(object)
}
