//! The interface workbench's link to the image: each pixel's angle of incidence where its
//! camera ray first meets a dielectric, and the pixels within a band of one angle.

use crate::camera::Camera;
use crate::params::Params;
use crate::scene::Scene;
use crate::tracer::Tracer;
use rayon::prelude::*;

/// Half the width of the band the workbench outlines, in degrees: the pixels whose first
/// hit meets a dielectric at θi ± this.
pub const INCIDENCE_BAND: f32 = 0.5;

/// The angle of incidence (degrees) of every pixel of a `width` × `height` image, row by
/// row, where its first camera ray (sample 0, the one the inspector traces) first meets a
/// dielectric through `camera`; `None` elsewhere. Computed on rayon's threads.
pub fn incidence_map(
    scene: &Scene,
    camera: &Camera,
    params: &Params,
    width: u32,
    height: u32,
) -> Vec<Option<f32>> {
    let tracer = Tracer::with_camera(scene, camera, params, width, height);
    (0..height)
        .into_par_iter()
        .flat_map_iter(|y| {
            let tracer = &tracer;
            (0..width).map(move |x| tracer.first_incidence(x, y, 0))
        })
        .collect()
}

/// Which pixels of `map` meet a dielectric within [`INCIDENCE_BAND`] of `angle` degrees.
pub fn incidence_band(map: &[Option<f32>], angle: f32) -> Vec<bool> {
    map.iter()
        .map(|a| a.is_some_and(|a| (a - angle).abs() <= INCIDENCE_BAND))
        .collect()
}
