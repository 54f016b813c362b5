//! One side of the view: an engine, what it was last told, its newest frame and the
//! texture that shows it. The main view is one side; the A/B view's side B is another.

use super::instruments::{cost_range, heat_map_rgba};
use crate::camera::Camera;
use crate::params::Params;
use crate::render::{Engine, EngineConfig, EngineError, FilmCache, Frame, to_srgba8};
use crate::scene::Scene;
use std::sync::Arc;

/// What a side's engine renders: the scene, camera, image size, whether it refines
/// without end and calms its frames. The parameters are compared with the engine's own.
#[derive(Clone)]
pub(crate) struct Told {
    pub(crate) scene: Arc<Scene>,
    pub(crate) camera: Camera,
    pub(crate) size: (u32, u32),
    pub(crate) unlimited: bool,
    /// Frames on their way calmed for the screen ([`Engine::set_calm`]).
    pub(crate) calm: bool,
}

/// What a texture shows: the exposure, the cost heat map's scale (if shown), and whether
/// pixels are drawn as squares.
type Shown = (f32, Option<(f32, f32)>, bool);

/// One engine and its image.
pub(crate) struct Side {
    engine: Engine,
    // What the engine was last told, so that each frame sends only what changed.
    told: Told,
    frame: Option<Frame>,
    // A frame taken aside while a scene arrives, to be shown with it (`hold_from`).
    held: Option<Frame>,
    texture: Option<egui::TextureHandle>,
    // The texture's name, and what it shows: the exposure, or the cost map's scale, and
    // whether pixels are sharp squares; `None` after a new frame arrived.
    name: &'static str,
    shown: Option<Shown>,
    // The texture's pixels (sRGB RGBA, the frame's grid), as last uploaded.
    pixels: Vec<u8>,
    // The newest frame's fewest and most rays per sample, found once when it arrived.
    cost_range: Option<(f32, f32)>,
    paused: bool,
    cache: FilmCache,
    // What the engine's newest generations render, newest last: the scene and
    // parameters it was told at each (for `rendered`).
    generations: std::collections::VecDeque<(u64, Arc<Scene>, Params)>,
}

/// How many generations a side remembers what they render.
const GENERATIONS: usize = 16;

impl Side {
    /// Starts an engine on `told` with `params`; frames ask `ctx` to repaint.
    pub(crate) fn new(
        ctx: &egui::Context,
        name: &'static str,
        told: Told,
        params: Params,
        config: EngineConfig,
        cache: FilmCache,
    ) -> Result<Side, EngineError> {
        let repaint = ctx.clone();
        let (w, h) = told.size;
        let scene = Arc::clone(&told.scene);
        let wake = move || repaint.request_repaint();
        let cached = Some(cache.clone());
        let mut engine = Engine::sharing(scene, params, w, h, config, cached, wake)?;
        if told.camera != told.scene.camera {
            engine.set_camera(told.camera.clone());
        }
        if told.unlimited {
            engine.set_unlimited(true);
        }
        if !told.calm {
            engine.set_calm(false);
        }
        let mut side = Side {
            generations: Default::default(),
            engine,
            told,
            frame: None,
            held: None,
            texture: None,
            name,
            shown: None,
            pixels: Vec::new(),
            cost_range: None,
            paused: false,
            cache,
        };
        side.note_generation();
        Ok(side)
    }

    /// Notes what the engine's generation renders, if it is new.
    fn note_generation(&mut self) {
        let generation = self.engine.generation();
        if self.generations.back().is_some_and(|g| g.0 == generation) {
            return;
        }
        let params = self.engine.params().clone();
        let scene = Arc::clone(&self.told.scene);
        self.generations.push_back((generation, scene, params));
        if self.generations.len() > GENERATIONS {
            self.generations.pop_front();
        }
    }

    /// What the newest frame was rendered from: its scene and parameters (none before the
    /// first frame, or for a generation older than the side remembers).
    pub(crate) fn rendered(&self) -> Option<(&Scene, &Params)> {
        let generation = self.frame.as_ref()?.generation;
        let (_, scene, params) = self.generations.iter().find(|g| g.0 == generation)?;
        Some((scene, params))
    }

    /// The images rendered ahead, which every side of the window shares.
    pub(crate) fn cache(&self) -> &FilmCache {
        &self.cache
    }

    /// Tells the engine what changed since it was last told. A new scene resets the
    /// engine's camera to the scene's, so the camera is compared after it. Parameters out
    /// of range are not sent (the controls never make them; a sidecar could).
    pub(crate) fn sync(&mut self, to: &Told, params: &Params) {
        // Each step is a generation of its own, noted as it is told.
        if !Arc::ptr_eq(&self.told.scene, &to.scene) {
            self.engine.set_scene(Arc::clone(&to.scene));
            self.told.scene = Arc::clone(&to.scene);
            self.told.camera = to.scene.camera.clone();
            self.note_generation();
        }
        if params != self.engine.params() && params.validate().is_ok() {
            self.engine.set_params(params.clone());
            self.note_generation();
        }
        if to.camera != self.told.camera {
            self.engine.set_camera(to.camera.clone());
            self.told.camera = to.camera.clone();
            self.note_generation();
        }
        if to.size != self.told.size {
            self.engine.resize(to.size.0, to.size.1);
            self.told.size = to.size;
            self.note_generation();
        }
        if to.unlimited != self.told.unlimited {
            self.engine.set_unlimited(to.unlimited);
            self.told.unlimited = to.unlimited;
        }
        if to.calm != self.told.calm {
            self.engine.set_calm(to.calm);
            self.told.calm = to.calm;
        }
    }

    /// Takes the newest frame the engine sent (or the one held aside), dropping older
    /// ones; whether there was one.
    pub(crate) fn receive(&mut self) -> bool {
        let newest = self.engine.frames().try_iter().last();
        let Some(frame) = newest.or_else(|| self.held.take()) else {
            return false;
        };
        self.held = None;
        self.paused = frame.progress.paused;
        self.cost_range = (!frame.cost.is_empty()).then(|| cost_range(&frame.cost));
        self.frame = Some(frame);
        self.shown = None;
        true
    }

    /// Holds the newest frame of generation `first` or later aside, not shown until the
    /// next `receive` (older ones are dropped); whether one is held.
    pub(crate) fn hold_from(&mut self, first: u64) -> bool {
        let newest = self.engine.frames().try_iter().last();
        if let Some(frame) = newest.filter(|f| f.generation >= first) {
            self.held = Some(frame);
        }
        self.held.is_some()
    }

    /// Brings the texture up to date with the newest frame, shown at `exposure`, or as the
    /// cost heat map on the scale `cost` (rays per sample from black to yellow); its pixels
    /// drawn as squares if `sharp`, else filtered smoothly.
    pub(crate) fn upload(
        &mut self,
        ctx: &egui::Context,
        exposure: f32,
        cost: Option<(f32, f32)>,
        sharp: bool,
    ) {
        let Some(frame) = &self.frame else { return };
        let cost = cost.filter(|_| !frame.cost.is_empty());
        if self.shown == Some((exposure, cost, sharp)) {
            return;
        }
        // The calmed picture where there is one (not under the cost map: the film's).
        let (pixels, block) = match cost {
            Some(_) => (&frame.pixels[..], frame.block),
            None => frame.shown(),
        };
        let rgba = match cost {
            Some((lo, hi)) => heat_map_rgba(&frame.cost, lo, hi),
            None => to_srgba8(pixels, exposure),
        };
        let (w, h) = (frame.width.div_ceil(block), frame.height.div_ceil(block));
        let image = egui::ColorImage::from_rgba_unmultiplied([w as usize, h as usize], &rgba);
        // Blocks (a preview's, a calmed picture's) are stretched smoothly (bilinear); a
        // pass's pixels too, unless the view shows them as squares (a whole zoom of 2 or
        // more, `ViewState::sharp`).
        let magnification = if sharp && block == 1 {
            egui::TextureFilter::Nearest
        } else {
            egui::TextureFilter::Linear
        };
        let options = egui::TextureOptions {
            magnification,
            minification: egui::TextureFilter::Linear,
            ..Default::default()
        };
        match &mut self.texture {
            Some(t) => t.set(image, options),
            None => self.texture = Some(ctx.load_texture(self.name, image, options)),
        }
        self.shown = Some((exposure, cost, sharp));
        self.pixels = rgba;
    }

    /// The texture's pixels as last uploaded: sRGB RGBA rows of the newest frame's grid.
    pub(crate) fn pixels(&self) -> &[u8] {
        &self.pixels
    }

    /// Pauses a running engine or resumes a paused one.
    pub(crate) fn toggle_pause(&mut self) {
        if self.paused {
            self.engine.resume();
        } else {
            self.engine.pause();
        }
        self.paused = !self.paused;
    }

    /// Starts refining again from the first sample.
    pub(crate) fn restart(&mut self) {
        self.engine.restart_now();
        self.note_generation();
    }

    /// Whether the engine is paused (as far as the window knows).
    pub(crate) fn paused(&self) -> bool {
        self.paused
    }

    /// The engine.
    pub(crate) fn engine(&self) -> &Engine {
        &self.engine
    }

    /// The camera the engine renders through.
    pub(crate) fn camera(&self) -> &Camera {
        &self.told.camera
    }

    /// The newest frame received.
    pub(crate) fn frame(&self) -> Option<&Frame> {
        self.frame.as_ref()
    }

    /// The newest frame's fewest and most rays per sample (none for a preview).
    pub(crate) fn cost_range(&self) -> Option<(f32, f32)> {
        self.cost_range
    }

    /// The texture showing it.
    pub(crate) fn texture(&self) -> Option<&egui::TextureHandle> {
        self.texture.as_ref()
    }

    /// Whether the newest frame is finished and of the engine's newest generation.
    pub(crate) fn settled(&self) -> bool {
        self.frame
            .as_ref()
            .is_some_and(|f| f.generation == self.engine.generation() && f.progress.done())
    }
}
