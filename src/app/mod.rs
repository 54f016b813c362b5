//! The previewer: an egui/eframe window over the progressive engine. The only module that
//! knows egui.
//!
//! The window never waits. Each frame, [`eframe::App::logic`] takes what arrived (the
//! engines' frames, loaded scenes, a finished contact sheet, a snapshot written, a tree
//! traced aside), tells the engines what the controls changed and uploads textures;
//! [`eframe::App::ui`] draws and edits state, and at its end carries out the commands its
//! keys, buttons and menus asked for (`command`). Files are written, and trees that need
//! photons traced, on threads of their own. One file per concern: a `side::Side` is an
//! engine and its image (the main view, the A/B view's B); the loader, slides, contact
//! sheet, snapshots, toasts, toolbar, instruments; `state` what it shows, for the tests.

mod arrival;
mod command;
mod compare;
mod controls;
mod files;
mod fit;
mod history;
mod instruments;
mod lecture;
mod loader;
pub mod open_failure;
mod persist;
mod present;
mod sheet;
mod side;
mod snapshot;
mod state;
mod system_dialog;
mod tev;
mod toasts;
mod toolbar;
mod view;
mod widgets;

use crate::camera::Camera;
use crate::params::Params;
use crate::render::{EngineConfig, EngineError};
use crate::scene::{BUILTIN_SCENES, Scene};
use compare::Compare;
use controls::controls_ui;
use egui::{CentralPanel, Panel};
use history::History;
use instruments::Instruments;
use lecture::Lecture;
use loader::Loader;
use present::Hall;
use sheet::SheetForm;
use side::{Side, Told};
pub use state::Open;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};
use toasts::Toasts;
use view::ViewState;
use widgets::Controls;

/// How the window starts.
#[derive(Clone, Debug)]
pub struct AppOptions {
    /// The scene to open (a file or built-in name); `None` reopens the last one.
    pub scene: Option<std::ffi::OsString>,
    /// Where snapshots go (the pictures folder's `raylab` unless told; Save as… changes it,
    /// and the window remembers the folder where `persist` is on).
    pub snapshot_dir: PathBuf,
    /// Where the scene picker looks for scene files.
    pub scenes_dir: PathBuf,
    /// Worker threads; `None` renders on every core (below the window's priority).
    pub threads: Option<usize>,
    /// Close the window after this long (for scripted runs).
    pub close_after: Option<Duration>,
    /// Remember the scene, parameters and camera between runs.
    pub persist: bool,
    /// Stream the image into tev at this address (HOST:PORT) from the start.
    pub tev: Option<String>,
    /// Open… and Save as… use the system's file dialogs where it has them (the binary
    /// turns this on; tests and scripted windows keep raylab's own, which is the same
    /// everywhere).
    pub system_dialogs: bool,
}

impl Default for AppOptions {
    fn default() -> Self {
        AppOptions {
            scene: None,
            snapshot_dir: default_snapshot_dir(),
            scenes_dir: PathBuf::from("scenes"),
            threads: None,
            close_after: None,
            persist: true,
            tev: None,
            system_dialogs: false,
        }
    }
}

/// Where snapshots go at first: the user's pictures folder (as the platform names it:
/// ~/Pictures, XDG_PICTURES_DIR, the Pictures known folder), in a folder `raylab`; failing
/// that the home folder's `raylab`, or `raylab-snapshots` here. Save as… moves it.
fn default_snapshot_dir() -> PathBuf {
    dirs::picture_dir()
        .or_else(dirs::home_dir)
        .map_or_else(|| PathBuf::from("raylab-snapshots"), |d| d.join("raylab"))
}

/// What the controls hold.
#[derive(Clone, Debug, PartialEq)]
struct Settings {
    params: Params,
    camera: Camera,
    // Render resolution as a fraction of the scene's image size.
    resolution: f32,
    // Refine on past the target.
    unlimited: bool,
    // Show frames on their way calmed.
    calm: bool,
}

/// The previewer application.
pub struct RaylabApp {
    options: AppOptions,
    scene: Arc<Scene>,
    settings: Settings,
    // The main view's engine and image.
    main: Side,
    compare: Option<Compare>,
    view: ViewState,
    instruments: Instruments,
    loader: Loader,
    lecture: Lecture,
    sheet: Option<SheetForm>,
    dialog: Option<toolbar::Dialog>,
    /// Whether file dialogs are the system's (see system_dialog.rs).
    system_dialogs: bool,
    toasts: Toasts,
    // The last scene error, shown above the image.
    error: Option<String>,
    close_at: Option<Instant>,
    hall: Hall,
    // egui's zoom factor (the UI scale), remembered between runs.
    ui_scale: f32,
    history: History,
    // Whether the first window was checked against its screen (`fit.rs`).
    fitted: bool,
    tev: Option<crate::render::tev::TevStream>,
    // What keys, buttons and menus asked for since the last frame (command.rs).
    commands: Vec<command::Command>,
    // Snapshots being written (snapshot.rs).
    saving: Vec<snapshot::Saving>,
    // A scene opened, being rendered before it replaces the one shown (arrival.rs).
    arriving: Option<arrival::Arriving>,
}

/// Opens the previewer window and runs it until it is closed.
pub fn run(options: AppOptions) -> eframe::Result {
    let native = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("raylab")
            // Maximized on the first run (a 1280×800 window overflows a 720p laptop's
            // screen); afterwards eframe restores the size and state the user left.
            .with_maximized(true)
            .with_inner_size([1280.0, 720.0])
            .with_min_inner_size([640.0, 400.0])
            .with_drag_and_drop(true),
        persist_window: options.persist,
        ..Default::default()
    };
    eframe::run_native(
        "raylab",
        native,
        Box::new(move |cc| Ok(Box::new(RaylabApp::new(cc, options)?))),
    )
}

/// The image size for a scene at a resolution scale.
fn render_size(scene: &Scene, resolution: f32) -> (u32, u32) {
    let side = |v: u32| ((v as f32 * resolution).round() as u32).max(1);
    (side(scene.width), side(scene.height))
}

/// The built-in default scene: compiled in and tested, so failing to load it is a bug.
fn default_scene() -> Scene {
    match BUILTIN_SCENES[0].load() {
        Ok(scene) => scene,
        Err(e) => panic!("the built-in default scene does not load: {e}"),
    }
}

impl RaylabApp {
    /// Builds the app: opens the scene (or the remembered one), starts the engine.
    pub fn new(
        cc: &eframe::CreationContext<'_>,
        mut options: AppOptions,
    ) -> Result<Self, EngineError> {
        let remembered = options.persist.then(|| persist::load(cc)).flatten();
        let first_run = options.persist && remembered.is_none();
        if let Some(dir) = remembered.as_ref().and_then(|r| r.snapshot_dir.clone()) {
            options.snapshot_dir = dir;
        }
        let ui_scale = remembered
            .as_ref()
            .map_or(1.0, |r| r.ui_scale.clamp(0.5, 3.0));
        cc.egui_ctx.set_zoom_factor(ui_scale);
        let mut error = None;
        let wanted = options
            .scene
            .clone()
            .or_else(|| remembered.as_ref().map(|r| r.scene.clone().into()));
        let scene = match wanted.as_deref().map(Scene::load) {
            Some(Ok(scene)) => scene,
            Some(Err(e)) => {
                error = Some(e.to_string());
                default_scene()
            }
            None => default_scene(),
        };
        let scene = Arc::new(scene);
        // The remembered settings belong to the remembered scene only.
        let settings = match remembered {
            Some(r) if r.scene == scene.source.reference() && r.params.validate().is_ok() => {
                Settings {
                    params: r.params,
                    camera: r.camera.unwrap_or_else(|| scene.camera.clone()),
                    resolution: r.resolution.clamp(0.1, 4.0),
                    unlimited: r.unlimited,
                    calm: r.calm,
                }
            }
            _ => Settings {
                params: scene.params.clone(),
                camera: scene.camera.clone(),
                resolution: 1.0,
                unlimited: false,
                calm: true,
            },
        };
        let config = options
            .threads
            .map_or_else(EngineConfig::with_ui, |threads| EngineConfig {
                threads,
                ..EngineConfig::with_ui()
            });
        let told = Told {
            scene: Arc::clone(&scene),
            camera: settings.camera.clone(),
            size: render_size(&scene, settings.resolution),
            unlimited: settings.unlimited,
            calm: settings.calm,
        };
        let main = Side::new(
            &cc.egui_ctx,
            "raylab-image",
            told,
            settings.params.clone(),
            config,
            crate::render::FilmCache::default(),
        )?;
        // Tooltips wait a little, not to cover readouts under a pointer passing over.
        cc.egui_ctx
            .global_style_mut(|style| style.interaction.tooltip_delay = 0.6);
        let mut toasts = Toasts::default();
        if first_run {
            // The first run: where the lecture is, and how to present it.
            toasts.info("The Lecture menu has the slides; F5 presents them; F1 lists every key.");
        }
        scene.warnings.iter().for_each(|w| toasts.warn(w));
        let mut loader = Loader::new(&cc.egui_ctx);
        loader.watch(&scene);
        let tev = options
            .tev
            .as_deref()
            .map(|address| tev::start(&cc.egui_ctx, address));
        let system_dialogs = options.system_dialogs && system_dialog::available();
        Ok(RaylabApp {
            close_at: options.close_after.map(|d| Instant::now() + d),
            tev,
            options,
            scene,
            settings,
            main,
            compare: None,
            view: ViewState::default(),
            instruments: Instruments::default(),
            loader,
            lecture: Lecture::default(),
            sheet: None,
            dialog: None,
            system_dialogs,
            toasts,
            error,
            hall: Hall::default(),
            ui_scale,
            history: History::default(),
            fitted: false,
            commands: Vec::new(),
            saving: Vec::new(),
            arriving: None,
        })
    }

    /// The controls over the window's settings (the side panel's, and the slide's in
    /// presentation mode), opening the sections of the parameters in `open`.
    fn with_controls<T>(
        &mut self,
        open: &'static [&'static str],
        f: impl FnOnce(&mut Controls) -> T,
    ) -> T {
        let s = &mut self.settings;
        f(&mut Controls {
            params: &mut s.params,
            camera: &mut s.camera,
            unlimited: &mut s.unlimited,
            click_to_focus: &mut self.instruments.click_to_focus,
            resolution: &mut s.resolution,
            scene: &self.scene,
            open,
        })
    }

    /// Tells the engines what the controls changed (each is told only what differs). A
    /// scene arriving has its engines told already, and the controls are the last scene's.
    fn sync_engines(&mut self) {
        if self.arriving.is_some() {
            return;
        }
        let told = self.told();
        let params = &self.settings.params;
        self.main.sync(&told, params);
        if let Some(c) = &mut self.compare {
            for (side, p) in c.sides.iter_mut().zip(c.kind.others(params)) {
                side.sync(&told, &p);
            }
        }
    }

    /// What the engines render, by the controls.
    fn told(&self) -> Told {
        Told {
            scene: Arc::clone(&self.scene),
            camera: self.settings.camera.clone(),
            size: render_size(&self.scene, self.settings.resolution),
            unlimited: self.settings.unlimited,
            calm: self.settings.calm,
        }
    }

    /// The cost heat map's scale: 0 to the chosen top, or (fitting each image) the
    /// smallest and largest rays per sample over both sides, so that the two sides of an
    /// A/B view are coloured alike.
    fn cost_scale(&self) -> Option<(f32, f32)> {
        if let Some(top) = self.instruments.cost_top {
            return Some((0.0, top));
        }
        std::iter::once(self.main.cost_range())
            .chain(self.compare_engines().map(Side::cost_range))
            .flatten()
            .reduce(|(lo, hi), (l, h)| (lo.min(l), hi.max(h)))
    }

    /// Undoes the last parameter change (`redo` false) or redoes the last undone.
    fn step_history(&mut self, redo: bool) {
        let current = &self.settings.params;
        let to = if redo {
            self.history.redo(current)
        } else {
            self.history.undo(current)
        };
        match to {
            Some(p) => {
                self.settings.params = p;
                self.keep_side_a();
            }
            None => self.toasts.info(if redo {
                "Nothing to redo"
            } else {
                "Nothing to undo"
            }),
        }
    }

    /// Parameters and camera back to the scene's.
    fn reset_to_defaults(&mut self) {
        self.settings.params = self.scene.params.clone();
        self.keep_side_a();
        self.settings.camera = self.scene.camera.clone();
        self.view.fit();
    }
}

impl RaylabApp {
    /// The window at a desk: toolbar, status bar, controls, instruments and the image.
    fn desk_ui(&mut self, ui: &mut egui::Ui) {
        let ctx = ui.ctx().clone();
        let toolbar = Panel::top("toolbar").show(ui, |ui| self.toolbar_ui(ui));
        Panel::bottom("status").show(ui, |ui| self.status_ui(ui));
        Panel::left("controls")
            .resizable(true)
            .default_size(320.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    let open = self.lecture.take_open();
                    self.with_controls(open, |c| controls_ui(ui, c));
                });
            });
        self.instruments_dock_ui(ui);
        CentralPanel::default().show(ui, |ui| self.image_panel_ui(ui));
        self.dialog_ui(&ctx);
        // A slide's caption runs along the image's bottom: messages go under the toolbar.
        let top = self
            .lecture
            .shown()
            .is_some()
            .then_some(toolbar.response.rect.max.y);
        self.toasts.ui(&ctx, top);
    }
}

impl eframe::App for RaylabApp {
    fn logic(&mut self, ctx: &egui::Context, _frame: &mut eframe::Frame) {
        self.fit_to_screen(ctx);
        self.receive_scenes(ctx);
        self.render_ahead();
        self.loader.poll();
        self.receive_sheet();
        self.dropped_files(ctx);
        self.receive_saves();
        self.sync_engines();
        // A pass that failed inside raylab stops its generation: the banner says so (once
        // a frame, so that Dismiss holds until the next failure).
        self.check_tev();
        if self.receive_main(ctx) {
            self.stream_to_tev();
            if let Some(failure) = self.main.frame().and_then(|f| f.progress.failure.clone()) {
                self.error = Some(format!("The render stopped: {failure}"));
            }
        }
        for side in self.compare.iter_mut().flat_map(|c| &mut c.sides) {
            side.receive();
        }
        // The heat map's scale from the frames just taken, for both sides alike.
        let cost = self
            .instruments
            .show_cost
            .then(|| self.cost_scale())
            .flatten();
        let exposure = self.settings.params.exposure;
        let sharp = self.view.sharp();
        self.main.upload(ctx, exposure, cost, sharp);
        for side in self.compare.iter_mut().flat_map(|c| &mut c.sides) {
            side.upload(ctx, exposure, cost, sharp);
        }
        self.receive_inspection(ctx);
        self.refresh_inspection(ctx);
        // Nothing here repaints by itself: an idle window sleeps until the engines, the
        // loader, a contact sheet or the user wake it.
        if let Some(t) = self.close_at {
            match t.checked_duration_since(Instant::now()) {
                Some(left) if !left.is_zero() => ctx.request_repaint_after(left),
                _ => ctx.send_viewport_cmd(egui::ViewportCommand::Close),
            }
        }
    }

    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        let before = self.settings.clone();
        self.read_keys(&ctx);
        self.settle_ui(&ctx);
        self.ui_scale = ctx.zoom_factor();
        let held = ctx.input(|i| i.pointer.any_down());
        self.history.observe(&self.settings.params, held);
        if self.hall.presenting {
            self.hall_style_ui(&ctx);
            self.presentation_ui(ui);
            // Clear of the caption strip along the bottom.
            self.toasts.ui(&ctx, Some(0.0));
        } else {
            self.desk_ui(ui);
        }
        self.help_ui(&ctx);
        self.instruments.end_frame(&ctx);
        self.apply_commands(&ctx);
        // What the controls and commands changed reaches the engines now, not in the next
        // frame: the first preview (a millisecond's work) is there for the next frame.
        if self.settings != before {
            self.sync_engines();
            ctx.request_repaint();
        }
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        if self.options.persist {
            let s = &self.settings;
            persist::save(
                storage,
                &self.scene,
                s,
                self.ui_scale,
                &self.options.snapshot_dir,
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn snapshots_go_to_a_folder_of_the_users_not_where_raylab_was_started() {
        let dir = default_snapshot_dir();
        assert_eq!(dir.file_name().and_then(|n| n.to_str()), Some("raylab"));
        if dirs::home_dir().is_some() {
            assert!(dir.is_absolute(), "{}", dir.display());
        }
    }
}
