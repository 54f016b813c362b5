//! Rendering: the film, the render kernel, the progressive engine, snapshots with their
//! sidecars, and images compared.

pub mod adaptive;
mod calm;
pub mod compare;
mod controller;
mod drag;
mod engine;
mod exr_file;
mod film;
mod frame;
mod generation;
mod incidence;
mod kept;
mod kernel;
pub mod output;
mod pace;
mod png_file;
mod prerender;
mod priority;
pub mod ramp;
mod sheet;
mod snapshot;
pub mod tev;
pub(crate) mod text;

pub use calm::{CALM_BLOCK, Guides, calm_film, spread};
pub use drag::{DragReport, simulate_drag};
pub use engine::{Engine, EngineConfig, EngineError};
pub use film::{Accum, CLEAN_NOISE, Film, FilmError, to_srgba8, write_image, write_png};
pub use frame::{Calm, Frame, Progress};
pub use generation::{MAX_PASS_SPP, PREVIEW_LEVELS};
pub use incidence::{INCIDENCE_BAND, incidence_band, incidence_map};
pub use kernel::{
    BAND_ROWS, Cancelled, Crop, PassObserver, render_crop_pass, render_pass, render_pass_by,
    render_preview,
};
pub use png_file::{SIDECAR_KEY, embedded_sidecar};
pub use prerender::{FilmCache, PRERENDER_MEMORY, Prerender};
pub use sheet::{Animation, ContactSheet, SheetError, Sweep, frame_size, parse_sweep, sweep_each};
pub use snapshot::{PassError, ReferenceErrors, Rendered, Sidecar, SidecarError, sidecar_path};
pub use text::with_caption;

use crate::params::Params;
use crate::scene::Scene;
use crate::tracer::Stats;

/// Renders `params.spp` samples per pixel of a `width` × `height` image in one pass,
/// through the scene's camera.
pub fn render(
    scene: &Scene,
    params: &Params,
    width: u32,
    height: u32,
    observer: &dyn PassObserver,
) -> Result<(Film, Stats), Cancelled> {
    let mut film = Film::new(width, height);
    let stats = render_pass(
        scene,
        &scene.camera,
        params,
        &mut film,
        params.spp,
        observer,
    )?;
    Ok((film, stats))
}
