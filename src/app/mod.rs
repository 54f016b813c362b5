//! The previewer: an egui/eframe window over the progressive engine. The only module that
//! knows egui.
//!
//! The window never waits: frames arrive from the engine over a channel (with a repaint
//! request), scenes load on a thread of their own, and every change of a control is sent
//! to the engine at the end of the frame in which it happened.

mod controls;
mod files;
mod instruments;
mod view;

pub use controls::{Controls, controls_ui};
pub use files::{Choice, FileDialog, Purpose, snapshot_path, timestamp};
pub use instruments::{
    CompareKind, Inspection, LECTURE, Slide, fresnel_plot_ui, inspector_ui, sample_pattern_ui,
};
pub use view::{ViewEvent, ViewState, image_ui};

use crate::camera::Camera;
use crate::params::Params;
use crate::render::{
    Engine, EngineConfig, EngineError, Frame, Sidecar, sidecar_path, to_srgba8, write_image,
};
use crate::scene::{BUILTIN_SCENES, Scene, SceneError, SceneSource};
use crate::tracer::pick;
use crossbeam_channel::{Receiver, Sender};
use egui::{CentralPanel, Color32, Key, KeyboardShortcut, Modifiers, Panel, RichText};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant, SystemTime};

/// How the window starts.
#[derive(Clone, Debug)]
pub struct AppOptions {
    /// The scene to open (a file or built-in name); `None` reopens the last one.
    pub scene: Option<String>,
    /// Where snapshots go.
    pub snapshot_dir: PathBuf,
    /// Where the scene picker looks for scene files.
    pub scenes_dir: PathBuf,
    /// Worker threads; `None` leaves one core to the window.
    pub threads: Option<usize>,
    /// Close the window after this long (for scripted runs).
    pub close_after: Option<Duration>,
    /// Remember the scene, parameters and camera between runs.
    pub persist: bool,
}

impl Default for AppOptions {
    fn default() -> Self {
        AppOptions {
            scene: None,
            snapshot_dir: PathBuf::from("screenshots"),
            scenes_dir: PathBuf::from("scenes"),
            threads: None,
            close_after: None,
            persist: true,
        }
    }
}

/// What the window remembers between runs.
#[derive(Clone, Debug, Serialize, Deserialize)]
struct Persisted {
    scene: String,
    params: Params,
    camera: Camera,
    resolution: f32,
    unlimited: bool,
}

const STORAGE_KEY: &str = "raylab";

/// Why a scene is being loaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum LoadPurpose {
    /// Opened by the user: the scene's defaults replace the parameters.
    Open,
    /// Its file changed on disk: parameters the user changed are kept.
    Reload,
}

struct Loaded {
    purpose: LoadPurpose,
    result: Result<Scene, SceneError>,
}

/// What an engine was last told, so that each frame sends it only what changed.
struct Sent {
    scene: Arc<Scene>,
    camera: Camera,
    size: (u32, u32),
}

impl Sent {
    /// Tells `engine` about a new scene, camera, size or parameters. A new scene resets
    /// the engine's camera to the scene's, so the camera is compared after it.
    fn sync(
        &mut self,
        engine: &mut Engine,
        scene: &Arc<Scene>,
        camera: &Camera,
        size: (u32, u32),
        params: Params,
    ) {
        if !Arc::ptr_eq(&self.scene, scene) {
            engine.set_scene(Arc::clone(scene));
            self.scene = Arc::clone(scene);
            self.camera = scene.camera.clone();
        }
        if params.validate().is_ok() && &params != engine.params() {
            engine.set_params(params);
        }
        if *camera != self.camera {
            engine.set_camera(camera.clone());
            self.camera = camera.clone();
        }
        if size != self.size {
            engine.resize(size.0, size.1);
            self.size = size;
        }
    }
}

/// The A/B view: side B's own engine and image, and where the divider is.
struct Compare {
    kind: CompareKind,
    engine: Engine,
    frame: Option<Frame>,
    texture: Option<egui::TextureHandle>,
    stale: bool,
    // The exposure its texture was made with.
    shown_exposure: f32,
    sent: Sent,
    // The divider's position across the image, 0 (all B) to 1 (all A).
    divider: f32,
}

/// The contact sheet window.
struct SheetForm {
    param: String,
    values: String,
    running: Option<Receiver<Result<PathBuf, String>>>,
}

struct Toast {
    text: String,
    error: bool,
    until: Instant,
}

/// The previewer application.
pub struct RaylabApp {
    options: AppOptions,
    engine: Engine,
    scene: Arc<Scene>,
    params: Params,
    camera: Camera,
    // What the engine was last told.
    sent: Sent,
    unlimited: bool,
    paused: bool,
    resolution: f32,
    frame: Option<Frame>,
    texture: Option<egui::TextureHandle>,
    texture_stale: bool,
    shown_exposure: f32,
    view: ViewState,
    click_to_focus: bool,
    // Instruments.
    show_fresnel: bool,
    inspect_mode: bool,
    inspection: Option<Inspection>,
    show_patterns: bool,
    show_cost: bool,
    shown_cost: bool,
    compare: Option<Compare>,
    // The contact sheet window: the parameter, its values, and a sheet being rendered.
    sheet: Option<SheetForm>,
    // The lecture slide being shown: its parameters wait for its scene to load.
    pending_slide: Option<&'static Slide>,
    caption: Option<&'static str>,
    error: Option<String>,
    toasts: Vec<Toast>,
    dialog: Option<FileDialog>,
    loads: (Sender<Loaded>, Receiver<Loaded>),
    loading: usize,
    // The scene file to reload when it changes, when it was last seen to change, and
    // whether it is the scene shown (reload) or one that failed to open (open again).
    watched: Option<(PathBuf, Option<SystemTime>, LoadPurpose)>,
    // The file of the last Open, to watch if it fails.
    opening: Option<PathBuf>,
    last_poll: Instant,
    close_at: Option<Instant>,
}

/// Opens the previewer window and runs it until it is closed.
pub fn run(options: AppOptions) -> eframe::Result {
    let native = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("raylab")
            .with_inner_size([1280.0, 800.0])
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

/// The parameters after the scene's defaults change from `old` to `new`: a parameter the
/// user left at the old default takes the new one; one the user changed stays.
fn merge_defaults(current: &Params, old: &Params, new: &Params) -> Params {
    let json = |p: &Params| {
        serde_json::to_value(p)
            .ok()
            .and_then(|v| v.as_object().cloned())
            .unwrap_or_default()
    };
    let (cur, old, new) = (json(current), json(old), json(new));
    let merged: serde_json::Map<String, serde_json::Value> = cur
        .iter()
        .map(|(k, v)| {
            let v = if old.get(k) == Some(v) {
                new.get(k).unwrap_or(v)
            } else {
                v
            };
            (k.clone(), v.clone())
        })
        .collect();
    serde_json::from_value(serde_json::Value::Object(merged)).unwrap_or_else(|_| current.clone())
}

impl RaylabApp {
    /// Builds the app: opens the scene (or the remembered one), starts the engine.
    pub fn new(cc: &eframe::CreationContext<'_>, options: AppOptions) -> Result<Self, EngineError> {
        let remembered: Option<Persisted> = if options.persist {
            cc.storage.and_then(|s| eframe::get_value(s, STORAGE_KEY))
        } else {
            None
        };
        let mut error = None;
        let wanted = options
            .scene
            .clone()
            .or_else(|| remembered.as_ref().map(|r| r.scene.clone()));
        let scene = match wanted.as_deref().map(Scene::load) {
            Some(Ok(scene)) => scene,
            Some(Err(e)) => {
                error = Some(e.to_string());
                BUILTIN_SCENES[0]
                    .load()
                    .unwrap_or_else(|_| unreachable_default())
            }
            None => BUILTIN_SCENES[0]
                .load()
                .unwrap_or_else(|_| unreachable_default()),
        };
        let scene = Arc::new(scene);
        // The remembered parameters belong to the remembered scene only.
        let (params, camera, resolution, unlimited) = match remembered {
            Some(r) if r.scene == scene.source.reference() && r.params.validate().is_ok() => (
                r.params,
                r.camera,
                r.resolution.clamp(0.1, 4.0),
                r.unlimited,
            ),
            _ => (scene.params.clone(), scene.camera.clone(), 1.0, false),
        };
        let (w, h) = render_size(&scene, resolution);
        let ctx = cc.egui_ctx.clone();
        let config = options
            .threads
            .map_or_else(EngineConfig::with_ui, |threads| EngineConfig { threads });
        let mut engine = Engine::new(
            Arc::clone(&scene),
            params.clone(),
            w,
            h,
            config,
            move || ctx.request_repaint(),
        )?;
        if camera != scene.camera {
            engine.set_camera(camera.clone());
        }
        if unlimited {
            engine.set_unlimited(true);
        }
        let close_at = options.close_after.map(|d| Instant::now() + d);
        let mut app = RaylabApp {
            options,
            engine,
            sent: Sent {
                scene: Arc::clone(&scene),
                camera: camera.clone(),
                size: (w, h),
            },
            camera,
            params,
            unlimited,
            paused: false,
            resolution,
            frame: None,
            texture: None,
            texture_stale: false,
            shown_exposure: 0.0,
            view: ViewState::default(),
            click_to_focus: false,
            error,
            toasts: Vec::new(),
            dialog: None,
            loads: crossbeam_channel::unbounded(),
            loading: 0,
            watched: None,
            opening: None,
            last_poll: Instant::now(),
            close_at,
            show_fresnel: false,
            inspect_mode: false,
            inspection: None,
            show_patterns: false,
            show_cost: false,
            shown_cost: false,
            compare: None,
            sheet: None,
            pending_slide: None,
            caption: None,
            scene,
        };
        app.watch_scene_file();
        Ok(app)
    }

    /// The scene shown.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The parameters the controls hold.
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// The engine (for its parameters and generation).
    pub fn engine(&self) -> &Engine {
        &self.engine
    }

    /// The last scene error shown, if any.
    pub fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }

    /// The newest frame received.
    pub fn latest_frame(&self) -> Option<&Frame> {
        self.frame.as_ref()
    }

    /// The messages shown at the bottom right.
    pub fn toasts(&self) -> Vec<String> {
        self.toasts.iter().map(|t| t.text.clone()).collect()
    }

    /// The inspected ray tree, if a pixel was clicked in inspect mode.
    pub fn inspection(&self) -> Option<&Inspection> {
        self.inspection.as_ref()
    }

    /// Side B's parameters and its newest frame, while the A/B view is on.
    pub fn compare_side_b(&self) -> Option<(&Params, Option<&Frame>)> {
        self.compare
            .as_ref()
            .map(|c| (c.engine.params(), c.frame.as_ref()))
    }

    /// Whether side B's newest frame is finished and of its engine's newest generation.
    pub fn compare_side_b_settled(&self) -> bool {
        self.compare.as_ref().is_some_and(|c| {
            c.frame
                .as_ref()
                .is_some_and(|f| f.generation == c.engine.generation() && f.progress.done())
        })
    }

    /// The caption of the lecture slide shown, if any.
    pub fn caption(&self) -> Option<&str> {
        self.caption
    }

    /// Whether a scene is loading.
    pub fn is_loading(&self) -> bool {
        self.loading > 0
    }

    fn toast(&mut self, text: impl Into<String>, error: bool) {
        self.toasts.push(Toast {
            text: text.into(),
            error,
            until: Instant::now() + Duration::from_secs(if error { 8 } else { 4 }),
        });
    }

    /// Loads a scene file, built-in name or OBJ file on a thread of its own.
    pub fn open_scene(&mut self, reference: &str) {
        self.load(reference.to_string(), LoadPurpose::Open);
    }

    fn load(&mut self, reference: String, purpose: LoadPurpose) {
        if purpose == LoadPurpose::Open {
            self.opening = Some(PathBuf::from(&reference)).filter(|p| p.is_file());
        }
        let tx = self.loads.0.clone();
        self.loading += 1;
        std::thread::spawn(move || {
            let result = Scene::load(&reference);
            let _ = tx.send(Loaded { purpose, result });
        });
    }

    fn watch_scene_file(&mut self) {
        self.watched = match &self.scene.source {
            SceneSource::File(path) => Some((path.clone(), modified(path), LoadPurpose::Reload)),
            _ => None,
        };
    }

    fn receive_scenes(&mut self) {
        while let Ok(loaded) = self.loads.1.try_recv() {
            self.loading = self.loading.saturating_sub(1);
            match loaded.result {
                Ok(scene) => {
                    let scene = Arc::new(scene);
                    self.params = match loaded.purpose {
                        LoadPurpose::Open => {
                            let mut p = scene.params.clone();
                            // A lecture slide sets its parameters on top of its scene's.
                            if let Some(slide) = self.pending_slide.take().filter(|s| {
                                scene.source.reference() == format!("builtin:{}", s.scene)
                            }) {
                                for (name, value) in slide.params {
                                    let _ = p.set(name, value);
                                }
                                self.caption = Some(slide.caption);
                            } else {
                                self.caption = None;
                            }
                            p
                        }
                        LoadPurpose::Reload => {
                            merge_defaults(&self.params, &self.scene.params, &scene.params)
                        }
                    };
                    let keep_camera =
                        loaded.purpose == LoadPurpose::Reload && self.camera != self.scene.camera;
                    if !keep_camera {
                        self.camera = scene.camera.clone();
                    }
                    let verb = if loaded.purpose == LoadPurpose::Open {
                        "Opened"
                    } else {
                        "Reloaded"
                    };
                    let text = format!("{verb} {}", scene.name);
                    self.keep_side_a();
                    // sync_engine tells the engine at the end of the frame.
                    self.scene = scene;
                    self.inspection = None;
                    self.error = None;
                    self.view.fit();
                    self.watch_scene_file();
                    self.toast(text, false);
                }
                Err(e) => {
                    // The scene shown stays; the message says what is wrong and where. A
                    // file that failed to open is watched: fixing it opens it.
                    if loaded.purpose == LoadPurpose::Open
                        && let Some(path) = self.opening.take()
                    {
                        self.watched = Some((path.clone(), modified(&path), LoadPurpose::Open));
                    }
                    self.error = Some(e.to_string());
                    self.toast("The scene has an error: see above the image", true);
                }
            }
        }
    }

    fn poll_scene_file(&mut self) {
        if self.last_poll.elapsed() < Duration::from_millis(500) {
            return;
        }
        self.last_poll = Instant::now();
        if let Some((path, seen, purpose)) = &mut self.watched {
            let now = modified(path);
            if now != *seen {
                *seen = now;
                let (reference, purpose) = (path.display().to_string(), *purpose);
                self.load(reference, purpose);
            }
        }
    }

    fn receive_frames(&mut self) {
        if let Some(frame) = self.engine.frames().try_iter().last() {
            self.paused = frame.progress.paused;
            self.frame = Some(frame);
            self.texture_stale = true;
        }
    }

    fn upload_texture(&mut self, ctx: &egui::Context) {
        if self.params.exposure != self.shown_exposure || self.show_cost != self.shown_cost {
            self.texture_stale = true;
        }
        let Some(frame) = &self.frame else { return };
        if !self.texture_stale {
            return;
        }
        let rgba = if self.show_cost && !frame.cost.is_empty() {
            let (lo, hi) = instruments::cost_range(&frame.cost);
            instruments::heat_map_rgba(&frame.cost, lo, hi)
        } else {
            to_srgba8(&frame.pixels, self.params.exposure)
        };
        self.shown_cost = self.show_cost;
        let size = (frame.width, frame.height);
        upload(ctx, &mut self.texture, "raylab-image", size, &rgba);
        self.shown_exposure = self.params.exposure;
        self.texture_stale = false;
    }

    /// Sends what the controls changed to the engine.
    fn sync_engine(&mut self) {
        let size = render_size(&self.scene, self.resolution);
        self.sent.sync(
            &mut self.engine,
            &self.scene,
            &self.camera,
            size,
            self.params.clone(),
        );
    }

    fn toggle_pause(&mut self) {
        if self.paused {
            self.engine.resume();
        } else {
            self.engine.pause();
        }
        self.paused = !self.paused;
    }

    /// While comparing, side A keeps its side of the comparison when the parameters are
    /// replaced (a scene opened, Reset).
    fn keep_side_a(&mut self) {
        if let Some(c) = &self.compare {
            self.params = c.kind.side_a(&self.params);
        }
    }

    /// Parameters and camera back to the scene's.
    pub fn reset_to_defaults(&mut self) {
        self.params = self.scene.params.clone();
        self.keep_side_a();
        self.camera = self.scene.camera.clone();
        self.view.fit();
    }

    /// Writes the newest full frame to `path` (PNG or EXR) with its sidecar.
    pub fn save_to(&mut self, path: &Path) -> Result<PathBuf, String> {
        let Some(frame) = self.frame.as_ref().filter(|f| !f.preview) else {
            return Err("Nothing to save yet: wait for the first pass".into());
        };
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        }
        // The frame's own parameters: those the engine rendered it with.
        let params = self.engine.params().clone();
        write_image(
            path,
            frame.width,
            frame.height,
            &frame.pixels,
            self.params.exposure,
        )
        .map_err(|e| e.to_string())?;
        let spp = frame.progress.spp;
        let sidecar = Sidecar {
            raylab_version: crate::VERSION.to_string(),
            scene: self.scene.source.reference(),
            width: frame.width,
            height: frame.height,
            params: Params {
                exposure: self.params.exposure,
                ..params.clone()
            },
            samples: (spp != params.spp).then_some(spp),
            camera: (self.sent.camera != self.scene.camera).then(|| self.sent.camera.clone()),
            image: path.file_name().map(|n| n.to_string_lossy().into_owned()),
            seconds: Some(frame.progress.elapsed.as_secs_f64()),
            stats: Some(frame.progress.stats),
        };
        let json = sidecar_path(path);
        sidecar.write(&json).map_err(|e| e.to_string())?;
        Ok(path.to_path_buf())
    }

    /// Ctrl+S: `screenshots/<scene>-<timestamp>.png` and its sidecar.
    pub fn save_snapshot(&mut self) {
        let path = snapshot_path(
            &self.options.snapshot_dir,
            &self.scene.name,
            SystemTime::now(),
        );
        self.report_save(&path);
    }

    fn report_save(&mut self, path: &Path) {
        match self.save_to(path) {
            Ok(p) => {
                let text = format!("Saved {} and {}", p.display(), sidecar_path(&p).display());
                self.toast(text, false);
            }
            Err(e) => self.toast(format!("Not saved: {e}"), true),
        }
    }

    fn shortcuts(&mut self, ctx: &egui::Context) {
        let (save, open) = ctx.input_mut(|i| {
            (
                i.consume_shortcut(&KeyboardShortcut::new(Modifiers::COMMAND, Key::S)),
                i.consume_shortcut(&KeyboardShortcut::new(Modifiers::COMMAND, Key::O)),
            )
        });
        if save {
            self.save_snapshot();
        }
        if open {
            self.open_dialog();
        }
        if ctx.egui_wants_keyboard_input() || self.dialog.is_some() {
            return;
        }
        let (space, r, f, one) = ctx.input(|i| {
            let plain = i.modifiers.is_none();
            (
                plain && i.key_pressed(Key::Space),
                plain && i.key_pressed(Key::R),
                plain && i.key_pressed(Key::F),
                plain && i.key_pressed(Key::Num1),
            )
        });
        if space {
            self.toggle_pause();
        }
        if r {
            self.engine.restart_now();
        }
        if f {
            self.view.fit();
        }
        if one {
            self.view.one_to_one(ctx.pixels_per_point());
        }
    }

    fn open_dialog(&mut self) {
        let dir = std::env::current_dir().map_or(self.options.scenes_dir.clone(), |d| {
            d.join(&self.options.scenes_dir)
        });
        let dir = if dir.is_dir() {
            dir
        } else {
            std::env::current_dir().unwrap_or_default()
        };
        self.dialog = Some(FileDialog::new(Purpose::Open, dir, String::new()));
    }

    fn save_as_dialog(&mut self) {
        let dir = &self.options.snapshot_dir;
        let dir = if dir.is_dir() {
            dir.clone()
        } else {
            std::env::current_dir().unwrap_or_default()
        };
        let name = snapshot_path(&dir, &self.scene.name, SystemTime::now())
            .file_name()
            .map_or("image.png".into(), |n| n.to_string_lossy().into_owned());
        self.dialog = Some(FileDialog::new(Purpose::SaveAs, dir, name));
    }

    fn dropped_files(&mut self, ctx: &egui::Context) {
        let dropped: Vec<PathBuf> = ctx.input(|i| {
            i.raw
                .dropped_files
                .iter()
                .map(|f| f.path().to_path_buf())
                .collect()
        });
        for path in dropped {
            let ext = path
                .extension()
                .map(|e| e.to_string_lossy().to_ascii_lowercase());
            if matches!(ext.as_deref(), Some("toml") | Some("obj")) {
                self.open_scene(&path.display().to_string());
            } else {
                self.toast(
                    format!(
                        "{}: drop a scene (.toml) or mesh (.obj) file",
                        path.display()
                    ),
                    true,
                );
            }
        }
    }

    fn toolbar_ui(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            let current = self.scene.source.reference();
            let mut chosen = None;
            egui::ComboBox::from_label("Scene")
                .selected_text(self.scene.name.as_str())
                .width(220.0)
                .height(560.0)
                .show_ui(ui, |ui| {
                    for b in BUILTIN_SCENES {
                        let reference = format!("builtin:{}", b.name);
                        if ui.selectable_label(current == reference, b.name).on_hover_text(b.description()).clicked() {
                            chosen = Some(reference);
                        }
                    }
                    ui.separator();
                    for path in scene_files(&self.options.scenes_dir) {
                        let label = path.display().to_string();
                        if ui.selectable_label(false, &label).clicked() {
                            chosen = Some(label);
                        }
                    }
                    ui.separator();
                    if ui.selectable_label(false, "Open…").clicked() {
                        chosen = Some(String::new());
                    }
                })
                .response
                .on_hover_text("Built-in scenes, the files in scenes/, or Open… (Ctrl+O). You can also drop a .toml or .obj file on the window.");
            match chosen {
                Some(r) if r.is_empty() => self.open_dialog(),
                Some(r) => self.open_scene(&r),
                None => {}
            }
            if self.loading > 0 {
                ui.spinner();
            }
            ui.separator();
            let pause = if self.paused { "Resume" } else { "Pause" };
            if ui.button(pause).on_hover_text("Pause or resume refining (Space).").clicked() {
                self.toggle_pause();
            }
            if ui.button("Restart").on_hover_text("Start refining again from the first sample (R).").clicked() {
                self.engine.restart_now();
            }
            if ui.button("Reset").on_hover_text("Every parameter and the camera back to the scene's defaults.").clicked() {
                self.reset_to_defaults();
            }
            ui.separator();
            if ui.button("Save snapshot").on_hover_text("Save the image and its parameters to screenshots/ (Ctrl+S).").clicked() {
                self.save_snapshot();
            }
            if ui.button("Save as…").on_hover_text("Choose where, and PNG or EXR.").clicked() {
                self.save_as_dialog();
            }
            ui.separator();
            if ui.button("Fit").on_hover_text("Fit the image to the window (F).").clicked() {
                self.view.fit();
            }
            if ui.button("1:1").on_hover_text("One image pixel per screen pixel (1).").clicked() {
                self.view.one_to_one(ui.ctx().pixels_per_point());
            }
            ui.separator();
            ui.menu_button("Instruments", |ui| {
                ui.checkbox(&mut self.show_fresnel, "Fresnel plot")
                    .on_hover_text("R_s, R_p, exact R, Schlick and naive Schlick against the angle, for the current IOR.");
                ui.checkbox(&mut self.inspect_mode, "Ray-tree inspector: click a pixel")
                    .on_hover_text("Click a pixel to see the whole ray tree of its first sample, drawn over the image.");
                ui.checkbox(&mut self.show_cost, "Cost heat map")
                    .on_hover_text("Rays traced per sample in each pixel, black (few) to yellow (many): where the ray tree is deep. Compare pruning by depth and by weight.");
                ui.menu_button("A/B compare", |ui| {
                    for (label, kind) in CompareKind::presets() {
                        if ui.button(label).clicked() {
                            self.start_compare(ui.ctx(), kind);
                            ui.close();
                        }
                    }
                    let frozen = ui
                        .button("the controls | frozen copy")
                        .on_hover_text("B keeps the parameters as they are now; change A with the controls.");
                    if frozen.clicked() {
                        self.start_compare(ui.ctx(), CompareKind::Frozen(self.params.clone()));
                        ui.close();
                    }
                    if ui.add_enabled(self.compare.is_some(), egui::Button::new("Off")).clicked() {
                        self.compare = None;
                        ui.close();
                    }
                });
                if ui.button("Contact sheet…").on_hover_text("One labelled image per value of a parameter, side by side, saved as a PNG.").clicked() {
                    self.sheet = Some(SheetForm {
                        param: "spp".into(),
                        values: "1,4,16".into(),
                        running: None,
                    });
                    ui.close();
                }
                ui.checkbox(&mut self.show_patterns, "Sample patterns")
                    .on_hover_text("Where one pixel's samples fall: in the pixel, on the lens, in the shutter interval.");
            });
            ui.menu_button("Lecture", |ui| {
                for slide in LECTURE {
                    if ui.button(slide.title).clicked() {
                        self.pending_slide = Some(slide);
                        self.open_scene(&format!("builtin:{}", slide.scene));
                        ui.close();
                    }
                }
            });
        });
    }

    fn status_ui(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            let Some(f) = &self.frame else {
                ui.label("starting…");
                return;
            };
            let p = &f.progress;
            let (fraction, text) = match p.target {
                Some(t) => (p.spp as f32 / t.max(1) as f32, format!("{} / {} spp", p.spp, t)),
                None => (1.0, format!("{} spp (no limit)", p.spp)),
            };
            ui.add(egui::ProgressBar::new(fraction.min(1.0)).text(text).desired_width(220.0))
                .on_hover_text("Samples per pixel done, of the target.");
            ui.separator();
            ui.label(format!("{:.2} M rays/s", p.rays_per_second / 1e6));
            ui.separator();
            ui.label(format!("{:.1} s", p.elapsed.as_secs_f32())).on_hover_text("Time since the image started.");
            if let Some(eta) = p.eta.filter(|_| !p.done()) {
                ui.separator();
                ui.label(format!("{:.1} s left", eta.as_secs_f32()));
            }
            if let Some(noise) = p.noise {
                ui.separator();
                let converged = if noise < 0.005 { " (converged)" } else { "" };
                ui.label(format!("noise {:.2}%{converged}", noise * 100.0))
                    .on_hover_text("Estimated standard error of the pixels, relative to the image's brightness, from the difference of the even and odd samples' means.");
            }
            if self.paused {
                ui.separator();
                ui.label(RichText::new("paused").strong());
            }
            if self.show_cost && !f.cost.is_empty() {
                let (lo, hi) = instruments::cost_range(&f.cost);
                ui.separator();
                ui.label(format!("cost: {lo:.1} (black) to {hi:.1} (yellow) rays per sample"));
            }
            ui.separator();
            ui.label(format!("{}×{}", f.width, f.height));
        });
    }

    fn image_panel_ui(&mut self, ui: &mut egui::Ui) {
        if let Some(e) = self.error.clone() {
            egui::Frame::new()
                .fill(Color32::from_rgb(110, 24, 24))
                .inner_margin(6.0)
                .show(ui, |ui| {
                    ui.horizontal(|ui| {
                        ui.label(RichText::new("Error:").color(Color32::WHITE).strong());
                        ui.label(RichText::new(&e).color(Color32::WHITE).monospace());
                        if ui.small_button("Dismiss").clicked() {
                            self.error = None;
                        }
                    });
                });
        }
        let size = self
            .frame
            .as_ref()
            .map_or(render_size(&self.scene, self.resolution), |f| {
                (f.width, f.height)
            });
        let (events, image_rect) = image_ui(ui, &mut self.view, self.texture.as_ref(), size);
        self.compare_overlay_ui(ui, image_rect);
        let aspect = size.0 as f32 / size.1 as f32;
        if let Some(inspection) = &self.inspection {
            let frame = self.camera.pinhole(aspect);
            instruments::draw_tree_overlay(
                &ui.painter_at(ui.min_rect()),
                image_rect,
                &frame,
                &inspection.tree,
            );
        }
        if let Some(caption) = self.caption {
            let area = ui.min_rect();
            let galley = ui.painter().layout(
                caption.to_string(),
                egui::FontId::proportional(16.0),
                Color32::WHITE,
                area.width() - 40.0,
            );
            let pos = egui::pos2(area.min.x + 20.0, area.max.y - galley.size().y - 20.0);
            let back = egui::Rect::from_min_size(pos, galley.size()).expand(8.0);
            ui.painter()
                .rect_filled(back, 4.0, Color32::from_black_alpha(180));
            ui.painter().galley(pos, galley, Color32::WHITE);
        }
        for event in events {
            match event {
                ViewEvent::Click(film) if self.click_to_focus => {
                    let aspect = size.0 as f32 / size.1 as f32;
                    match pick(
                        &self.scene,
                        &self.camera,
                        aspect,
                        glam::Vec2::new(film.x, film.y),
                    ) {
                        Some(hit) => {
                            self.params.focus_distance = Some(hit.depth.max(0.01));
                            let name = self.scene.object_names[hit.object as usize].clone();
                            self.toast(format!("Focused on {name} at {:.2}", hit.depth), false);
                        }
                        None => self.toast("Nothing there to focus on", true),
                    }
                    self.click_to_focus = false;
                }
                ViewEvent::Click(film) if self.inspect_mode => {
                    let x = ((film.x * size.0 as f32) as u32).min(size.0 - 1);
                    let y = ((film.y * size.1 as f32) as u32).min(size.1 - 1);
                    self.inspect((x, y), size);
                }
                ViewEvent::Click(_) => {}
                ViewEvent::Orbit(delta) => orbit(&mut self.camera, delta),
                ViewEvent::Dolly(amount) => dolly(&mut self.camera, amount),
            }
        }
    }

    /// Splits the view between the controls' parameters (A) and `kind`'s other side (B).
    fn start_compare(&mut self, ctx: &egui::Context, kind: CompareKind) {
        self.params = kind.side_a(&self.params);
        let (w, h) = render_size(&self.scene, self.resolution);
        let ctx = ctx.clone();
        let b = kind.side_b(&self.params);
        match Engine::new(
            Arc::clone(&self.scene),
            b,
            w,
            h,
            EngineConfig::with_ui(),
            move || ctx.request_repaint(),
        ) {
            Ok(mut engine) => {
                engine.set_unlimited(self.unlimited);
                let sent = Sent {
                    scene: Arc::clone(&self.scene),
                    camera: self.scene.camera.clone(),
                    size: (w, h),
                };
                self.compare = Some(Compare {
                    kind,
                    engine,
                    frame: None,
                    texture: None,
                    stale: false,
                    shown_exposure: f32::NAN,
                    sent,
                    divider: 0.5,
                });
            }
            Err(e) => self.toast(format!("Cannot compare: {e}"), true),
        }
    }

    /// Keeps side B in step with the controls (scene, camera, size, and its side of the
    /// parameters), and takes its frames.
    fn sync_compare(&mut self, ctx: &egui::Context) {
        let Some(c) = &mut self.compare else { return };
        let size = render_size(&self.scene, self.resolution);
        let b = c.kind.side_b(&self.params);
        c.sent
            .sync(&mut c.engine, &self.scene, &self.sent.camera, size, b);
        if let Some(frame) = c.engine.frames().try_iter().last() {
            c.frame = Some(frame);
            c.stale = true;
        }
        if let Some(f) = &c.frame
            && (c.stale || self.params.exposure != c.shown_exposure)
        {
            let rgba = to_srgba8(&f.pixels, self.params.exposure);
            upload(
                ctx,
                &mut c.texture,
                "raylab-image-b",
                (f.width, f.height),
                &rgba,
            );
            c.stale = false;
            c.shown_exposure = self.params.exposure;
        }
    }

    /// Draws side B right of the divider, the divider, and the two sides' labels.
    fn compare_overlay_ui(&mut self, ui: &mut egui::Ui, image: egui::Rect) {
        let Some(c) = &mut self.compare else { return };
        let x = image.min.x + c.divider * image.width();
        let clip = egui::Rect::from_min_max(egui::pos2(x, image.min.y), image.max)
            .intersect(ui.clip_rect());
        if let Some(t) = &c.texture {
            let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
            ui.painter()
                .with_clip_rect(clip)
                .image(t.id(), image, uv, Color32::WHITE);
        }
        let handle = egui::Rect::from_center_size(
            egui::pos2(x, image.center().y),
            egui::vec2(14.0, image.height()),
        );
        let response = ui.interact(handle, egui::Id::unique("ab-divider"), egui::Sense::drag());
        if response.dragged() {
            c.divider =
                ((x + response.drag_delta().x - image.min.x) / image.width()).clamp(0.0, 1.0);
        }
        let painter = ui.painter();
        painter.line_segment(
            [egui::pos2(x, image.min.y), egui::pos2(x, image.max.y)],
            egui::Stroke::new(2.0, Color32::WHITE),
        );
        painter.circle_filled(egui::pos2(x, image.center().y), 7.0, Color32::WHITE);
        let (a, b) = c.kind.labels();
        let spp = |f: &Option<Frame>| f.as_ref().map_or(0, |f| f.progress.spp);
        let a_text = format!("{a} ({} spp)", spp(&self.frame));
        let b_text = format!("{b} ({} spp)", spp(&c.frame));
        // Labels on dark plates: legible over a white sky too.
        let label = |text: String, anchor: egui::Pos2, align: egui::Align2| {
            let galley =
                painter.layout_no_wrap(text, egui::FontId::proportional(15.0), Color32::WHITE);
            let rect = align.anchor_size(anchor, galley.size());
            painter.rect_filled(rect.expand(5.0), 4.0, Color32::from_black_alpha(170));
            painter.galley(rect.min, galley, Color32::WHITE);
        };
        label(
            a_text,
            image.min + egui::vec2(12.0, 12.0),
            egui::Align2::LEFT_TOP,
        );
        label(
            b_text,
            egui::pos2(image.max.x - 12.0, image.min.y + 12.0),
            egui::Align2::RIGHT_TOP,
        );
    }

    /// Records the ray tree of `pixel`'s first sample with the current parameters and camera.
    fn inspect(&mut self, pixel: (u32, u32), size: (u32, u32)) {
        let tracer = crate::tracer::Tracer::with_camera(
            &self.scene,
            &self.camera,
            &self.params,
            size.0,
            size.1,
        );
        let (tree, radiance) = tracer.inspect(pixel.0, pixel.1, 0);
        self.inspection = Some(Inspection {
            pixel,
            size,
            params: self.params.clone(),
            camera: self.camera.clone(),
            tree,
            radiance,
        });
    }

    /// Keeps the inspected tree in step with the controls.
    fn refresh_inspection(&mut self) {
        if let Some(i) = &self.inspection
            && (i.params != self.params || i.camera != self.camera)
            && self.params.validate().is_ok()
        {
            let (pixel, size) = (i.pixel, i.size);
            self.inspect(pixel, size);
        }
    }

    /// The contact sheet window, and the sheet rendering in the background.
    fn sheet_ui(&mut self, ctx: &egui::Context) {
        let Some(form) = &mut self.sheet else { return };
        if let Some(rx) = &form.running
            && let Ok(result) = rx.try_recv()
        {
            form.running = None;
            match result {
                Ok(path) => self.toasts.push(Toast {
                    text: format!("Saved the contact sheet {}", path.display()),
                    error: false,
                    until: Instant::now() + Duration::from_secs(6),
                }),
                Err(e) => self.toasts.push(Toast {
                    text: format!("No contact sheet: {e}"),
                    error: true,
                    until: Instant::now() + Duration::from_secs(8),
                }),
            }
        }
        let mut open = true;
        let mut start = false;
        egui::Window::new("Contact sheet").open(&mut open).show(ctx, |ui| {
            egui::ComboBox::from_label("Parameter").selected_text(form.param.as_str()).show_ui(ui, |ui| {
                for name in Params::names() {
                    ui.selectable_value(&mut form.param, name.clone(), name);
                }
            });
            ui.horizontal(|ui| {
                ui.label("Values");
                ui.text_edit_singleline(&mut form.values).on_hover_text("Comma separated, as --set takes them: 1,4,16 or schlick,exact.");
            });
            ui.label("Each image is half the scene's size, with the other parameters as they are now.");
            if form.running.is_some() {
                ui.horizontal(|ui| {
                    ui.spinner();
                    ui.label("rendering…");
                });
            } else if ui.button("Render sheet").clicked() {
                start = true;
            }
        });
        if start {
            let values: Vec<String> = form
                .values
                .split(',')
                .map(|v| v.trim().to_string())
                .filter(|v| !v.is_empty())
                .collect();
            let (tx, rx) = crossbeam_channel::bounded(1);
            form.running = Some(rx);
            let scene = Arc::clone(&self.scene);
            let camera = self.camera.clone();
            let params = self.params.clone();
            let name = form.param.clone();
            let path = self.options.snapshot_dir.join(format!(
                "{}-sweep-{name}-{}.png",
                scene.name,
                timestamp(SystemTime::now())
            ));
            let ctx = ctx.clone();
            std::thread::spawn(move || {
                let (w, h) = ((scene.width / 2).max(1), (scene.height / 2).max(1));
                let result = crate::render::contact_sheet(
                    &scene,
                    &camera,
                    &params,
                    w,
                    h,
                    &name,
                    &values,
                    &(),
                )
                .map_err(|e| e.to_string())
                .and_then(|sheet| {
                    if let Some(dir) = path.parent() {
                        std::fs::create_dir_all(dir)
                            .map_err(|e| format!("{}: {e}", dir.display()))?;
                    }
                    sheet
                        .save(&path)
                        .map_err(|e| format!("{}: {e}", path.display()))?;
                    Ok(path)
                });
                let _ = tx.send(result);
                ctx.request_repaint();
            });
        }
        if !open {
            self.sheet = None;
        }
    }

    fn instruments_ui(&mut self, ctx: &egui::Context) {
        self.refresh_inspection();
        self.sheet_ui(ctx);
        if self.show_fresnel {
            let ior = self.params.ior.or_else(|| {
                self.scene
                    .materials
                    .iter()
                    .find_map(|m| m.dielectric().filter(|d| !d.ior_fixed).map(|d| d.ior))
            });
            let marker = self
                .inspection
                .as_ref()
                .and_then(|i| i.tree.nodes.first())
                .and_then(|n| n.hit)
                .map(|h| (h.theta_i, h.n1_n2.is_none_or(|(n1, n2)| n1 <= n2)));
            let mut open = true;
            egui::Window::new("Fresnel plot")
                .open(&mut open)
                .default_width(520.0)
                .show(ctx, |ui| {
                    fresnel_plot_ui(ui, ior.unwrap_or(1.5), marker);
                });
            self.show_fresnel = open;
        }
        if self.inspect_mode || self.inspection.is_some() {
            let mut open = true;
            egui::Window::new("Ray-tree inspector")
                .open(&mut open)
                .default_width(460.0)
                .show(ctx, |ui| {
                    ui.checkbox(
                        &mut self.inspect_mode,
                        "Clicking the image inspects a pixel",
                    );
                    match &self.inspection {
                        Some(i) => inspector_ui(
                            ui,
                            i,
                            &self.scene.object_names,
                            &self.scene.material_names,
                        ),
                        None => {
                            ui.label("Click a pixel of the image.");
                        }
                    }
                });
            if !open {
                self.inspect_mode = false;
                self.inspection = None;
            }
        }
        if self.show_patterns {
            let mut open = true;
            egui::Window::new("Sample patterns")
                .open(&mut open)
                .show(ctx, |ui| {
                    sample_pattern_ui(ui, self.params.pattern, self.params.spp, self.params.seed);
                });
            self.show_patterns = open;
        }
    }

    fn dialog_ui(&mut self, ctx: &egui::Context) {
        let Some(dialog) = &mut self.dialog else {
            return;
        };
        let purpose = dialog.purpose;
        match dialog.ui(ctx) {
            Choice::Pending => {}
            Choice::Cancelled => self.dialog = None,
            Choice::File(path) => {
                self.dialog = None;
                match purpose {
                    Purpose::Open => self.open_scene(&path.display().to_string()),
                    Purpose::SaveAs => self.report_save(&path),
                }
            }
        }
    }

    fn toasts_ui(&mut self, ctx: &egui::Context) {
        let now = Instant::now();
        self.toasts.retain(|t| t.until > now);
        if self.toasts.is_empty() {
            return;
        }
        egui::Area::new(egui::Id::unique("raylab-toasts"))
            .anchor(egui::Align2::RIGHT_BOTTOM, [-12.0, -36.0])
            .order(egui::Order::Foreground)
            .interactable(false)
            .show(ctx, |ui| {
                for t in &self.toasts {
                    let fill = if t.error {
                        Color32::from_rgb(130, 30, 30)
                    } else {
                        Color32::from_rgb(30, 70, 40)
                    };
                    egui::Frame::new()
                        .fill(fill)
                        .corner_radius(4.0)
                        .inner_margin(8.0)
                        .show(ui, |ui| {
                            ui.label(RichText::new(&t.text).color(Color32::WHITE));
                        });
                }
            });
        ctx.request_repaint_after(Duration::from_millis(250));
    }
}

/// Puts an RGBA image into the texture in `slot`, creating it the first time. Sharp pixels
/// when zoomed in for pixel-peeping, smooth when fitted smaller.
fn upload(
    ctx: &egui::Context,
    slot: &mut Option<egui::TextureHandle>,
    name: &str,
    size: (u32, u32),
    rgba: &[u8],
) {
    let image = egui::ColorImage::from_rgba_unmultiplied([size.0 as usize, size.1 as usize], rgba);
    let options = egui::TextureOptions {
        magnification: egui::TextureFilter::Nearest,
        minification: egui::TextureFilter::Linear,
        ..Default::default()
    };
    match slot {
        Some(t) => t.set(image, options),
        None => *slot = Some(ctx.load_texture(name, image, options)),
    }
}

/// Turns the camera about its target: horizontal drag about the up axis, vertical about
/// the camera's right axis (stopping short of the poles).
fn orbit(camera: &mut Camera, delta: egui::Vec2) {
    let offset = camera.position - camera.look_at;
    let up = camera.up.normalize();
    let yaw = glam::Quat::from_axis_angle(up.into(), -delta.x * 0.005);
    let mut offset: crate::math::Vec3 = yaw * offset;
    let right = offset.cross(up).normalize_or_zero();
    let pitched: crate::math::Vec3 =
        glam::Quat::from_axis_angle(right.into(), delta.y * 0.005) * offset;
    if pitched.normalize().dot(up).abs() < 0.995 {
        offset = pitched;
    }
    camera.position = camera.look_at + offset;
}

/// Moves the camera towards its target (positive) or away, by a factor per wheel step.
fn dolly(camera: &mut Camera, amount: f32) {
    let offset = camera.position - camera.look_at;
    let scale = (-amount * 0.002).exp().clamp(0.5, 2.0);
    let new = offset * scale;
    if new.length() > 1e-3 {
        camera.position = camera.look_at + new;
    }
}

fn modified(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

/// The scene files in `dir`, sorted.
fn scene_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|d| {
            d.flatten()
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|e| e == "toml"))
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files
}

/// The built-in default scene is compiled in and tested; failing to parse it is a bug.
fn unreachable_default() -> Scene {
    panic!("the built-in default scene does not load: a build error")
}

impl eframe::App for RaylabApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        self.receive_frames();
        self.receive_scenes();
        self.poll_scene_file();
        self.dropped_files(&ctx);
        self.shortcuts(&ctx);
        self.upload_texture(&ctx);

        Panel::top("toolbar").show(ui, |ui| self.toolbar_ui(ui));
        Panel::bottom("status").show(ui, |ui| self.status_ui(ui));
        Panel::left("controls")
            .resizable(true)
            .default_size(320.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    let mut controls = Controls {
                        params: &mut self.params,
                        camera: &mut self.camera,
                        unlimited: &mut self.unlimited,
                        click_to_focus: &mut self.click_to_focus,
                        resolution: &mut self.resolution,
                        scene: &self.scene,
                    };
                    let unlimited = *controls.unlimited;
                    controls_ui(ui, &mut controls);
                    if self.unlimited != unlimited {
                        self.engine.set_unlimited(self.unlimited);
                    }
                });
            });
        CentralPanel::default().show(ui, |ui| self.image_panel_ui(ui));
        self.dialog_ui(&ctx);
        self.toasts_ui(&ctx);
        self.instruments_ui(&ctx);
        self.sync_engine();
        self.sync_compare(&ctx);
        if self.params.exposure != self.shown_exposure {
            ctx.request_repaint();
        }

        // Keep polling the scene file for changes while the window is idle.
        ctx.request_repaint_after(Duration::from_millis(500));
        if self.close_at.is_some_and(|t| Instant::now() >= t) {
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        }
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        if !self.options.persist {
            return;
        }
        let state = Persisted {
            scene: self.scene.source.reference(),
            params: self.params.clone(),
            camera: self.camera.clone(),
            resolution: self.resolution,
            unlimited: self.unlimited,
        };
        eframe::set_value(storage, STORAGE_KEY, &state);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reload_keeps_what_the_user_changed_and_takes_new_defaults() {
        let old = Params::default();
        let new = Params {
            spp: 64,
            max_depth: 3,
            ..Params::default()
        };
        let current = Params {
            max_depth: 12,
            ..Params::default()
        };
        let merged = merge_defaults(&current, &old, &new);
        assert_eq!(merged.spp, 64, "left at the old default: takes the new one");
        assert_eq!(merged.max_depth, 12, "changed by the user: kept");
    }

    #[test]
    fn orbit_keeps_the_distance_and_dolly_changes_it() {
        let mut c = Camera::looking_at(
            crate::math::Vec3::new(0.0, 1.0, 5.0),
            crate::math::Vec3::ZERO,
            crate::math::Vec3::Y,
            40.0,
        );
        let d = c.look_distance();
        orbit(&mut c, egui::vec2(120.0, -40.0));
        assert!((c.look_distance() - d).abs() < 1e-4);
        assert!(c.position.x.abs() > 0.1);
        dolly(&mut c, 100.0);
        assert!(c.look_distance() < d);
    }
}
