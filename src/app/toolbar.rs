//! The toolbar (scene picker, refining, snapshots, view, menus: their buttons queue the
//! commands of `command.rs`), the status bar, and the file dialogs and dropped files they
//! lead to.

use super::RaylabApp;
use super::command::Command;
use super::files::{Choice, FileDialog, Purpose, snapshot_path};
use super::system_dialog::SystemDialog;
use crate::scene::BUILTIN_SCENES;
use egui::RichText;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

impl RaylabApp {
    pub(super) fn toolbar_ui(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            self.scene_picker_ui(ui);
            if self.is_loading() {
                ui.spinner();
            }
            ui.separator();
            let (can_undo, can_redo) = self.history.can();
            for (command, enabled) in [
                (Command::Pause, true),
                (Command::Restart, true),
                (Command::Undo, can_undo),
                (Command::Redo, can_redo),
                (Command::Reset, true),
            ] {
                self.command_button(ui, command, enabled);
            }
            ui.separator();
            for command in [Command::Save, Command::SaveAs] {
                self.command_button(ui, command, true);
            }
            ui.separator();
            for command in [Command::Fit, Command::OneToOne] {
                self.command_button(ui, command, true);
            }
            ui.separator();
            ui.menu_button("Instruments", |ui| self.instruments_menu_ui(ui));
            ui.menu_button("Lecture", |ui| self.lecture_menu_ui(ui));
            ui.menu_button("View", |ui| self.view_menu_ui(ui));
        });
    }

    fn scene_picker_ui(&mut self, ui: &mut egui::Ui) {
        let current = self.scene.source.reference();
        let mut chosen = None;
        egui::ComboBox::from_label("Scene")
            .selected_text(self.scene.name.as_str())
            .width(220.0)
            .height(560.0)
            .show_ui(ui, |ui| {
                for b in BUILTIN_SCENES {
                    let reference = format!("builtin:{}", b.name);
                    let item = ui.selectable_label(current == reference, b.name);
                    if item.on_hover_text(b.description()).clicked() {
                        chosen = Some(reference);
                    }
                }
                ui.separator();
                // The files in scenes/ that are the built-in scenes as shipped are listed
                // once, as built in; one the user changed is listed as a file.
                let edited = scene_files(&self.options.scenes_dir)
                    .into_iter()
                    .filter(|p| !is_builtin_copy(p));
                for path in edited {
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
            Some(r) if r.is_empty() => self.ask(ui.ctx(), Command::Open),
            Some(r) => self.open_scene(&r),
            None => {}
        }
    }

    pub(super) fn status_ui(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            let Some(f) = self.main.frame() else {
                ui.label("starting…");
                return;
            };
            let p = &f.progress;
            let limit = if p.target.is_none() { " (no limit)" } else { "" };
            let text = format!("{} spp{limit}", p.of_target());
            ui.add(egui::ProgressBar::new(p.fraction()).text(text).desired_width(220.0))
                .on_hover_text("Samples per pixel done, of the target.");
            // Sides B and C refine in engines of their own, each at its own pace.
            for (letter, side) in self.all_sides().skip(1) {
                let Some(f) = side.frame() else { continue };
                ui.label(format!("{letter}: {} spp", f.progress.of_target()))
                    .on_hover_text(format!("Side {letter}'s samples per pixel, of its target."));
            }
            ui.separator();
            ui.label(format!("{:.2} M rays/s", p.rays_per_second / 1e6));
            ui.separator();
            ui.label(format!("{:.1} s", p.elapsed.as_secs_f32())).on_hover_text("Time since the image started.");
            // The view is clean when its slowest side is: the longest time left.
            let eta = self
                .all_sides()
                .filter_map(|(_, side)| side.frame())
                .filter(|f| !f.progress.done())
                .filter_map(|f| f.progress.eta)
                .max();
            if let Some(eta) = eta {
                ui.separator();
                ui.label(format!("{:.1} s left", eta.as_secs_f32()))
                    .on_hover_text("Until every side shown reaches its target, at the pace of the last passes.");
            }
            if let Some(noise) = p.noise {
                ui.separator();
                // Under 2 %, what each lecture slide's target reaches (tests/slides.rs).
                let clean = if noise < crate::render::CLEAN_NOISE { " (clean)" } else { "" };
                ui.label(format!("noise {:.2}%{clean}", noise * 100.0))
                    .on_hover_text("Estimated standard error of the pixels, relative to the image's brightness, from the difference of two halves of the samples (alternate octaves of sample numbers). Under 2 % the image reads as clean.");
            }
            if f.calm.is_some() {
                ui.separator();
                ui.label("calmed").on_hover_text(
                    "Shown with its noise smoothed along each surface until it is clean (View > Calm noise while refining). Snapshots and readouts are the raw samples.",
                );
            }
            if p.reached < 1.0 && !p.done() {
                ui.separator();
                ui.label(format!("re-rendering {:.0}%", p.reached * 100.0)).on_hover_text(
                    "The share of the pixels the last change could alter (their samples met what it changed): they start again; the rest keep their samples, bit for bit.",
                );
            }
            if let Some(done) = p.pixels_done {
                ui.separator();
                ui.label(format!("{:.0}% of pixels done", done * 100.0))
                    .on_hover_text("Adaptive sampling (Sampling > noise target): pixels whose noise, and their neighbours', is under the target take no more samples.");
            }
            if self.main.paused() {
                ui.separator();
                ui.label(RichText::new("paused").strong());
            }
            if let Some((lo, hi)) = self.instruments.show_cost.then(|| self.cost_scale()).flatten() {
                ui.separator();
                ui.label(format!("cost {lo:.0}–{hi:.0} rays/sample"))
                    .on_hover_text("The heat map's scale: black at the first, pale yellow at the second (Instruments > Heat map).");
            }
            ui.separator();
            ui.label(format!("{}×{}", f.width, f.height));
            ui.separator();
            ui.label(format!("zoom {:.0} %", self.view.scale * 100.0))
                .on_hover_text("Screen pixels per image pixel. Pixels are sharp squares at whole zooms of 2 or more (wheel to zoom, 1 for 1:1, F to fit), smoothly filtered otherwise.");
            if let Some(text) = pixel_readout(f, self.view.hover, self.settings.params.exposure) {
                ui.separator();
                ui.label(RichText::new(text).monospace())
                    .on_hover_text("The pixel under the cursor: its mean linear radiance, and the sRGB value shown (after the exposure).");
            }
        });
    }

    pub(super) fn open_dialog(&mut self, ctx: &egui::Context) {
        let cwd = std::env::current_dir().unwrap_or_default();
        let dir = cwd.join(&self.options.scenes_dir);
        let dir = if dir.is_dir() { dir } else { cwd };
        self.dialog = Some(self.file_dialog(ctx, Purpose::Open, dir, String::new()));
    }

    pub(super) fn save_as_dialog(&mut self, ctx: &egui::Context) {
        let dir = &self.options.snapshot_dir;
        let dir = if dir.is_dir() {
            dir.clone()
        } else {
            std::env::current_dir().unwrap_or_default()
        };
        let name = snapshot_path(&dir, &self.scene.name, SystemTime::now())
            .file_name()
            .map_or("image.png".into(), |n| n.to_string_lossy().into_owned());
        self.dialog = Some(self.file_dialog(ctx, Purpose::SaveAs, dir, name));
    }

    /// The system's file dialog where there is one, else raylab's own.
    fn file_dialog(
        &self,
        ctx: &egui::Context,
        purpose: Purpose,
        dir: PathBuf,
        name: String,
    ) -> Dialog {
        if self.system_dialogs {
            Dialog::System(SystemDialog::open(ctx, purpose, &dir, &name))
        } else {
            Dialog::Own(FileDialog::new(purpose, dir, name))
        }
    }

    pub(super) fn dialog_ui(&mut self, ctx: &egui::Context) {
        let (purpose, choice) = match &mut self.dialog {
            None => return,
            Some(Dialog::Own(own)) => (own.purpose, own.ui(ctx)),
            Some(Dialog::System(system)) => match system.ui(ctx) {
                Some(choice) => (system.purpose(), choice),
                None => {
                    // It failed to appear, or the user asked for raylab's: raylab's
                    // from now on.
                    log::info!("the system's file dialog gave way to raylab's");
                    self.system_dialogs = false;
                    if let Some(Dialog::System(system)) = self.dialog.take() {
                        self.dialog = Some(Dialog::Own(system.instead()));
                    }
                    return;
                }
            },
        };
        match choice {
            Choice::Pending => {}
            Choice::Cancelled => self.dialog = None,
            Choice::File(path) => {
                self.dialog = None;
                match purpose {
                    Purpose::Open => self.open_scene(&path),
                    // Snapshots go where the user last saved from now on.
                    Purpose::SaveAs => self.save_to(ctx, &path, true),
                }
            }
        }
    }

    /// Scene and model files dropped on the window open; anything else is refused.
    pub(super) fn dropped_files(&mut self, ctx: &egui::Context) {
        let dropped: Vec<PathBuf> = ctx.input(|i| {
            i.raw
                .dropped_files
                .iter()
                .map(|f| f.path().to_path_buf())
                .collect()
        });
        for path in dropped {
            if crate::scene::opens(&path) {
                self.open_scene(&path);
            } else {
                self.toasts.error(format!(
                    "{}: drop a scene (.toml) or a model (.obj, .gltf, .glb)",
                    path.display()
                ));
            }
        }
    }
}

/// Whether the scene file at `path` is a built-in scene as it ships (same name, same text).
fn is_builtin_copy(path: &Path) -> bool {
    let Some(stem) = path.file_stem().and_then(|s| s.to_str()) else {
        return false;
    };
    crate::scene::builtin(stem)
        .is_some_and(|b| crate::scene::input::read_text(path).is_ok_and(|text| text == b.text))
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

/// The pixel of `frame` at image position `hover` (0..1 across and down): its coordinates,
/// linear radiance and displayed sRGB value at `exposure`. None for a preview (its values
/// are blocks, not pixels) or off the image.
/// An open file dialog: the system's, or raylab's own.
pub(super) enum Dialog {
    /// The platform's (see system_dialog.rs).
    System(SystemDialog),
    /// Drawn by raylab with egui.
    Own(FileDialog),
}

pub(crate) fn pixel_readout(
    frame: &crate::render::Frame,
    hover: Option<egui::Vec2>,
    exposure: f32,
) -> Option<String> {
    let h = hover?;
    if frame.is_preview() {
        return None;
    }
    let x = ((h.x * frame.width as f32) as u32).min(frame.width - 1);
    let y = ((h.y * frame.height as f32) as u32).min(frame.height - 1);
    let c = *frame.pixels.get((y * frame.width + x) as usize)?;
    let shown = (c * exposure.exp2()).to_array().map(crate::math::srgb8);
    Some(format!(
        "({x}, {y}) lin {:.3} {:.3} {:.3} · sRGB {} {} {}",
        c.x, c.y, c.z, shown[0], shown[1], shown[2]
    ))
}
