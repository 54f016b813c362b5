//! A scene opened (a slide's, the picker's, a file dropped) replaces the one shown in one
//! frame: the frame that has its first picture. Until then its engines work on it while
//! the window shows the last scene whole: title, caption, controls, instruments, A/B view
//! and picture all of one slide. (Changed piece by piece, a slide's dock, rays or A/B
//! labels sat for a frame or two on the last slide's picture.)

use super::RaylabApp;
use super::compare::{Compare, CompareKind};
use super::side::Told;
use crate::params::Params;
use crate::scene::Scene;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// A scene loaded and being rendered, not yet shown.
pub(crate) struct Arriving {
    scene: Arc<Scene>,
    // The Open it answers: a later Open overtakes it.
    opens: u64,
    // The parameters it opens with (the slide's, side A's of its comparison).
    params: Params,
    // The main engine's generation once told the scene and parameters: its frames from
    // there on are the new scene's.
    generation: u64,
    // Its A/B view's other sides (B, and C), started with it.
    compare: Option<Compare>,
    since: Instant,
}

/// How long the window waits for an arriving scene's first pictures at most. The engine
/// sends a preview within milliseconds even while paused; this bounds a failing one.
const WAIT: Duration = Duration::from_secs(2);

impl RaylabApp {
    /// A scene opened has loaded (answering Open number `opens`): the main engine, and the
    /// engines of its A/B view's other sides, start on it while the window shows the last
    /// scene.
    pub(super) fn stage(&mut self, ctx: &egui::Context, scene: Arc<Scene>, opens: u64) {
        let slide = self.lecture.pending_for(&scene);
        let mut params = scene.params.clone();
        if let Some(slide) = slide {
            match slide.params_on(&scene.params) {
                Ok(p) => params = p,
                Err(e) => self.toasts.error(format!("Slide `{}`: {e}", slide.title)),
            }
        }
        // The comparison it opens with, and where its dividers start: the slide's, or (a
        // scene opened outside the lecture) the one on, as it is.
        let kind = match slide {
            Some(s) => s.compare.map(|c| (CompareKind::Lecture(c), s.dividers())),
            None if self.lecture.shown().is_none() => self
                .compare
                .as_ref()
                .map(|c| (c.kind.clone(), c.dividers.clone())),
            None => None,
        };
        // Side A keeps its side of it.
        if let Some((kind, _)) = &kind {
            params = kind.side_a(&params);
        }
        let told = Told {
            scene: Arc::clone(&scene),
            camera: scene.camera.clone(),
            size: super::render_size(&scene, self.settings.resolution),
            unlimited: self.settings.unlimited,
            calm: self.settings.calm,
        };
        self.main.sync(&told, &params);
        // Its other sides start on it too, in engines of their own.
        let compare =
            kind.and_then(|(kind, dividers)| self.new_compare(ctx, &told, kind, dividers, &params));
        self.arriving = Some(Arriving {
            scene,
            opens,
            params,
            generation: self.main.engine().generation(),
            compare,
            since: Instant::now(),
        });
        ctx.request_repaint_after(WAIT);
    }

    /// Takes the main view's newest frame; whether there was one. While a scene is
    /// arriving, only frames of it are taken, and once it has a picture on every side (or
    /// waited `WAIT`) the window turns to it whole, in this frame.
    pub(super) fn receive_main(&mut self, ctx: &egui::Context) -> bool {
        let Some(a) = &mut self.arriving else {
            return self.main.receive();
        };
        if self.loader.overtaken(a.opens) {
            // A later Open is loading: the last scene stays until that one arrives.
            self.arriving = None;
            self.main.sync(&self.told(), &self.settings.params);
            return false;
        }
        let main_ready = self.main.hold_from(a.generation);
        let sides = a.compare.iter_mut().flat_map(|c| &mut c.sides);
        let sides_ready = sides.fold(true, |ready, side| {
            side.receive();
            ready && side.frame().is_some()
        });
        if (main_ready && sides_ready) || a.since.elapsed() >= WAIT {
            if let Some(a) = self.arriving.take() {
                self.arrive(ctx, a);
            }
            return self.main.receive();
        }
        false
    }

    /// Whether a scene is loading or arriving (loaded, its first picture on its way).
    pub fn is_loading(&self) -> bool {
        self.loader.is_loading() || self.arriving.is_some()
    }

    /// The arriving scene replaces the one shown: its parameters and camera, its slide's
    /// caption, controls, instruments and A/B view, all at once.
    fn arrive(&mut self, ctx: &egui::Context, a: Arriving) {
        self.history.clear();
        self.settings.params = a.params;
        self.settings.camera = a.scene.camera.clone();
        let was_slide = self.lecture.shown().is_some();
        let slide = self.lecture.arrived(&a.scene);
        match slide {
            Some(slide) => self.arrive_at_slide(slide),
            // Out of the lecture: nothing of the last slide stays.
            None if was_slide => self.leave_slide(),
            None => {}
        }
        // A slide in presentation mode says what it is in its own title.
        let quiet = self.hall.presenting && slide.is_some();
        self.replace_scene(a.scene, (!quiet).then_some("Opened"));
        // Its A/B view, if it has one (a slide's, or the one on, kept): none otherwise.
        if a.compare.is_some() || slide.is_some() {
            self.compare = a.compare;
        }
        if let Some(slide) = slide {
            self.show_slide(slide, ctx);
        } else {
            // A slide zooms its section as it needs; any other scene starts whole.
            self.instruments.section.zoom_to(1.0);
        }
    }

    /// `scene` is shown from now on, said in a message (`verb` and its name) unless
    /// `verb` is none; the last scene's inspected tree and error go.
    pub(super) fn replace_scene(&mut self, scene: Arc<Scene>, verb: Option<&str>) {
        if let Some(verb) = verb {
            self.toasts.info(format!("{verb} {}", scene.name));
        }
        for warning in &scene.warnings {
            self.toasts.warn(warning);
        }
        self.instruments.forget_inspection();
        self.error = None;
        self.view.fit();
        self.loader.watch(&scene);
        self.scene = scene;
    }
}
