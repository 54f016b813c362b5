//! raylab: an interactive lab for the lecture "Dielectrics and distribution in ray tracing".
//!
//! A CPU ray tracer built for teaching: every concept of the lecture is a parameter of one
//! [`params::Params`] model, and every image is reproducible bit for bit from its
//! parameters and seed.
//!
//! The layers, from the bottom, each using only those below it (docs/internals.md draws
//! them; `tests/layers.rs` holds the code to that): [`math`] (vectors, rays, deterministic
//! random numbers, the sRGB curve) and [`guard`]; [`optics`] (the lecture's formulas) and
//! [`geometry`] (shapes and the BVH); [`params`] (the one parameter table); [`material`],
//! [`light`] and [`camera`]; [`scene`] (files, OBJ and glTF models, built-in scenes);
//! [`tracer`] (the ray tree, paths, the waves); [`render`] (the film, the one render
//! kernel, the progressive engine); [`section`] (the 2D diagrams); [`lecture`] (the
//! slides); and `app` (the egui previewer, the only module that knows egui; built with the
//! `gui` feature, on by default).
//!
//! ```
//! use raylab::{params::Params, render::render, scene::Scene};
//! let scene = Scene::load("default").unwrap();
//! let params = Params { spp: 1, ..scene.params.clone() };
//! let (film, stats) = render(&scene, &params, 32, 18, &()).unwrap();
//! assert_eq!(film.spp(), 1);
//! assert_eq!(stats.camera_rays, 32 * 18);
//! ```
// Lints (no unsafe code but the measured exceptions Cargo.toml lists; documented public
// items; no unwrap outside tests): Cargo.toml.

#[cfg(feature = "gui")]
pub mod app;
pub mod camera;
pub mod geometry;
pub mod guard;
pub mod lecture;
pub mod light;
pub mod material;
pub mod math;
pub mod optics;
pub mod params;
pub mod render;
pub mod scene;
pub mod section;
pub mod tracer;

/// The version of raylab, as written into snapshot sidecars.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The commit raylab was built from (12 hex digits), if it could be known: git's `HEAD`
/// when built in a clone, or the one a registry's package records (see `build.rs`).
pub const COMMIT: Option<&str> = match env!("RAYLAB_COMMIT").as_bytes() {
    [] => None,
    _ => Some(env!("RAYLAB_COMMIT")),
};

/// The version and, where known, the commit: "0.2.0 (commit 1a2b3c4d5e6f)". What
/// `raylab --version` says and what images name as their software.
pub const VERSION_LINE: &str = env!("RAYLAB_VERSION_LINE");
