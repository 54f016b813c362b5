//! Lights and the background.

use crate::math::{Color, Vec3};

/// A point light: radiant intensity `intensity` (radiance units times area, per steradian)
/// in every direction. A surface at distance r facing it receives irradiance
/// E = intensity cos θ / r²; a white diffuse surface then has radiance E/π.
#[derive(Clone, Debug, PartialEq)]
pub struct PointLight {
    /// Where the light is.
    pub position: Vec3,
    /// Radiant intensity per channel.
    pub intensity: Color,
}

/// What a ray that leaves the scene sees.
#[derive(Clone, Debug, PartialEq)]
pub enum Background {
    /// The same radiance in every direction: a uniform environment.
    Constant(Color),
    /// A sky: `horizon` at and below the horizon (y ≤ 0), blending to `zenith` straight up.
    Gradient {
        /// Radiance at the horizon and below.
        horizon: Color,
        /// Radiance straight up.
        zenith: Color,
    },
}

impl Background {
    /// Radiance seen along the unit direction `dir`.
    #[inline]
    pub fn radiance(&self, dir: Vec3) -> Color {
        match self {
            Background::Constant(c) => *c,
            Background::Gradient { horizon, zenith } => horizon.lerp(*zenith, dir.y.max(0.0)),
        }
    }
}
