//! The contact sheet form, in the instruments' dock: one labelled image per value of a
//! parameter, rendered on a thread of its own and saved beside the snapshots.

use super::RaylabApp;
use super::files::timestamp;
use crate::params::Params;
use crossbeam_channel::Receiver;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::SystemTime;

/// The form: the parameter, its values, and a sheet being rendered.
pub(crate) struct SheetForm {
    param: String,
    values: String,
    running: Option<Receiver<Result<PathBuf, String>>>,
}

impl RaylabApp {
    /// Opens the form.
    pub(super) fn open_sheet_form(&mut self) {
        self.sheet = Some(SheetForm {
            param: "spp".into(),
            values: "1,4,16".into(),
            running: None,
        });
    }

    /// Takes a finished sheet's result.
    pub(super) fn receive_sheet(&mut self) {
        let Some(form) = &mut self.sheet else { return };
        let Some(result) = form.running.as_ref().and_then(|rx| rx.try_recv().ok()) else {
            return;
        };
        form.running = None;
        match result {
            Ok(path) => self
                .toasts
                .info(format!("Saved the contact sheet {}", path.display())),
            Err(e) => self.toasts.error(format!("No contact sheet: {e}")),
        }
    }

    /// The form, in the dock beside the image (where it covers no control); `open` turns
    /// false when it is closed.
    pub(super) fn sheet_form_ui(&mut self, ui: &mut egui::Ui, open: bool) {
        let ctx = ui.ctx().clone();
        let Some(form) = &mut self.sheet else { return };
        let mut start = false;
        {
            egui::ComboBox::from_label("Parameter")
                .selected_text(form.param.as_str())
                .show_ui(ui, |ui| {
                    for name in Params::names() {
                        ui.selectable_value(&mut form.param, name.clone(), name);
                    }
                });
            ui.horizontal(|ui| {
                ui.label("Values");
                ui.text_edit_singleline(&mut form.values).on_hover_text(
                    "Comma separated, as --set takes them: 1,4,16 or schlick,exact.",
                );
            });
            ui.label(
                "Each image is half the scene's size, with the other parameters as they are now.",
            );
            if form.running.is_some() {
                ui.horizontal(|ui| {
                    ui.spinner();
                    ui.label("rendering…");
                });
            } else if ui.button("Render sheet").clicked() {
                start = true;
            }
        }
        if start {
            self.start_sheet(&ctx);
        }
        if !open {
            self.sheet = None;
        }
    }

    fn start_sheet(&mut self, ctx: &egui::Context) {
        let Some(form) = &mut self.sheet else { return };
        let sweep = crate::render::Sweep::of(&form.param, &form.values);
        let (tx, rx) = crossbeam_channel::bounded(1);
        form.running = Some(rx);
        let scene = Arc::clone(&self.scene);
        let camera = self.settings.camera.clone();
        let params = self.settings.params.clone();
        let path = self.options.snapshot_dir.join(format!(
            "{}-sweep-{}-{}.png",
            scene.name,
            sweep.name,
            timestamp(SystemTime::now())
        ));
        let ctx = ctx.clone();
        std::thread::spawn(move || {
            let (w, h) = ((scene.width / 2).max(1), (scene.height / 2).max(1));
            // Each frame is placed in the sheet as it is made; the sheet is written whole.
            let tile = crate::render::frame_size((w, h));
            let mut sheet = crate::render::ContactSheet::new(sweep.values.len(), tile);
            let result = crate::render::sweep_each(
                &scene,
                &camera,
                &params,
                (w, h),
                &sweep,
                &(),
                &mut |frame| {
                    sheet.add(&frame);
                    Ok(())
                },
            )
            .map_err(|e| e.to_string())
            .and_then(|()| {
                if let Some(dir) = path.parent() {
                    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
                }
                crate::render::output::save_image(&sheet.finish(), &path, image::ImageFormat::Png)
                    .map_err(|e| format!("{}: {e}", path.display()))?;
                Ok(path)
            });
            let _ = tx.send(result);
            ctx.request_repaint();
        });
    }
}
