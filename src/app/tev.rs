//! Streaming the window's image into tev (View > Stream to tev, or `raylab --tev`): each
//! frame after a pass, as `raylab render --tev` streams each pass.

use super::RaylabApp;
use crate::render::tev::{TEV_ADDRESS, TevStream};

/// The image's name in tev: one image, made again when the render's size changes.
pub(super) const TEV_IMAGE: &str = "raylab";

impl RaylabApp {
    /// The View menu's toggle.
    pub(super) fn tev_menu_ui(&mut self, ui: &mut egui::Ui) {
        let address = self.options.tev.clone().unwrap_or(TEV_ADDRESS.to_string());
        let mut on = self.tev.is_some();
        if ui
            .checkbox(&mut on, "Stream to tev")
            .on_hover_text(format!(
                "Each pass's image, linear, into the tev viewer running at {address} \
                 (raylab --tev=HOST:PORT for another address)."
            ))
            .changed()
        {
            self.tev = on.then(|| TevStream::start(&address, TEV_IMAGE));
        }
    }

    /// Sends the newest frame after a pass (not a preview) to tev, if streaming; a stream
    /// that stopped (tev not there, or closed) is turned off with a message.
    pub(super) fn stream_to_tev(&mut self) {
        let Some(tev) = &self.tev else {
            return;
        };
        if let Some(error) = tev.error() {
            self.toasts.error(format!("Streaming stopped: {error}"));
            self.tev = None;
            return;
        }
        if let Some(frame) = self.main.frame().filter(|f| !f.is_preview()) {
            let (w, h) = frame.grid_size();
            tev.send(w, h, std::sync::Arc::clone(&frame.pixels));
        }
    }

    /// Whether the window streams to tev (for the tests).
    pub fn streams_to_tev(&self) -> bool {
        self.tev.is_some()
    }
}
