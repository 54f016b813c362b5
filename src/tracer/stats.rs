//! What the tracer counts: rays by kind, branches pruned, samples dropped.

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
    /// Branches not traced because their sample had traced
    /// [`MAX_TREE_RAYS`](crate::tracer::MAX_TREE_RAYS) child rays.
    pub pruned_by_budget: u64,
    /// Samples dropped because they were NaN or infinite.
    pub non_finite: u64,
}

impl Stats {
    /// Counts a hit where the refracted ray does not exist (`total_internal_reflection`).
    #[inline(always)]
    pub(super) fn count_tir(&mut self, total_internal_reflection: bool) {
        self.tir_events += u64::from(total_internal_reflection);
    }

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
        self.pruned_by_budget += o.pruned_by_budget;
        self.non_finite += o.non_finite;
    }
}
