//! Streaming the window's image into tev (View > Stream to tev, or `raylab --tev`): each
//! frame after a pass, as `raylab render --tev` streams each pass.

use super::RaylabApp;
use crate::render::tev::{TEV_ADDRESS, TevStream};

/// The image's name in tev: one image, made again when the render's size changes.
const TEV_IMAGE: &str = "raylab";

/// A stream to tev at `address` that wakes the window if it stops.
pub(super) fn start(ctx: &egui::Context, address: &str) -> TevStream {
    let ctx = ctx.clone();
    TevStream::start(address, TEV_IMAGE, move || ctx.request_repaint())
}

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
            self.tev = on.then(|| start(ui.ctx(), &address));
            // The image shown goes at once (a finished one sends no more frames).
            self.stream_to_tev();
        }
    }

    /// Stops a stream that stopped on its own (tev not there, or closed), with a message.
    pub(super) fn check_tev(&mut self) {
        if let Some(error) = self.tev.as_ref().and_then(TevStream::error) {
            self.toasts.error(format!("Streaming stopped: {error}"));
            self.tev = None;
        }
    }

    /// Sends the newest frame after a pass (not a preview) to tev, if streaming.
    pub(super) fn stream_to_tev(&mut self) {
        let Some(tev) = &self.tev else {
            return;
        };
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
