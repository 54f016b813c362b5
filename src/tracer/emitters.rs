//! The scene's emitting surfaces as lights a path can aim at: path tracing samples a point
//! on them as it samples the lights, and weighs a path that finds one by itself against
//! that sample.
//!
//! One point per shading point, on a primitive chosen in proportion to its area and placed
//! uniformly on it: a density of 1 / A_total per unit area over all emitting surfaces,
//! d² / (A_total |cos θ_e|) per unit solid angle. Planes have no finite area and are not
//! sampled: only a path that meets one sees it.

use crate::material::Material;
use crate::math::Vec3;
use crate::scene::Scene;
use glam::Vec2;

/// The emitting primitives of a scene, sampled by area.
#[derive(Debug, Default)]
pub(super) struct Emitters {
    // (object, primitive) of each emitting primitive.
    prims: Vec<(u32, u32)>,
    // The running sum of their areas; the last is the total.
    cumulative: Vec<f32>,
    // Per object: whether its primitives are among `prims`.
    sampled: Vec<bool>,
}

impl Emitters {
    /// The primitives of every object whose material (as the tracer has it) emits.
    pub(super) fn new(scene: &Scene, materials: &[Material]) -> Emitters {
        let mut e = Emitters {
            sampled: vec![false; scene.shapes.len()],
            ..Emitters::default()
        };
        let mut total = 0.0;
        for (object, shape) in scene.shapes.iter().enumerate() {
            let material = &materials[scene.object_materials[object] as usize];
            if !material.emits() {
                continue;
            }
            for index in 0..shape.primitive_count() as u32 {
                let area = shape.primitive_area(index);
                if area > 0.0 && area.is_finite() {
                    total += area;
                    e.prims.push((object as u32, index));
                    e.cumulative.push(total);
                    e.sampled[object] = true;
                }
            }
        }
        e
    }

    /// Whether there is nothing to sample.
    pub(super) fn is_empty(&self) -> bool {
        self.prims.is_empty()
    }

    fn total_area(&self) -> f32 {
        self.cumulative.last().copied().unwrap_or(0.0)
    }

    /// A point on the emitting surfaces at frame time `time`, uniform in area: `pick`
    /// chooses the primitive, `u` places the point. Returns the object and the point.
    pub(super) fn sample(
        &self,
        scene: &Scene,
        pick: f32,
        u: Vec2,
        time: f32,
    ) -> Option<(u32, Vec3)> {
        let target = pick * self.total_area();
        let i = self
            .cumulative
            .partition_point(|&c| c <= target)
            .min(self.prims.len().checked_sub(1)?);
        let (object, index) = self.prims[i];
        let point = scene.shapes[object as usize].sample_point(index, u, time)?;
        Some((object, point))
    }

    /// The density per unit solid angle with which [`Emitters::sample`] picks a point of
    /// `object` seen at distance `dist`, at cos θ_e `cos_e` to its normal: 0 for an
    /// emitter that is not sampled.
    pub(super) fn pdf(&self, object: u32, dist: f32, cos_e: f32) -> f32 {
        if !self.sampled.get(object as usize).copied().unwrap_or(false) || cos_e <= 0.0 {
            return 0.0;
        }
        dist * dist / (self.total_area() * cos_e)
    }
}
