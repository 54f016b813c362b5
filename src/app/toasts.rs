//! Short messages at the bottom right: what was saved or opened, and what went wrong.

use egui::{Color32, RichText};
use std::time::{Duration, Instant};

struct Toast {
    text: String,
    error: bool,
    until: Instant,
}

/// The messages shown.
#[derive(Default)]
pub(crate) struct Toasts(Vec<Toast>);

impl Toasts {
    fn push(&mut self, text: String, error: bool, seconds: u64) {
        self.0.push(Toast {
            text,
            error,
            until: Instant::now() + Duration::from_secs(seconds),
        });
    }

    /// News, shown for a few seconds.
    pub(crate) fn info(&mut self, text: impl Into<String>) {
        self.push(text.into(), false, 4);
    }

    /// A failure, shown longer.
    pub(crate) fn error(&mut self, text: impl Into<String>) {
        self.push(text.into(), true, 8);
    }

    /// Something a scene's files lack (not fatal), shown as long as a failure.
    pub(crate) fn warn(&mut self, text: impl std::fmt::Display) {
        self.error(format!("Warning: {text}"));
    }

    /// The texts shown.
    pub(crate) fn texts(&self) -> Vec<String> {
        self.0.iter().map(|t| t.text.clone()).collect()
    }

    /// Drops the expired ones and draws the rest: at the bottom right, or, where a caption
    /// runs along the bottom, at the top right from `top` down (clear of the caption).
    pub(crate) fn ui(&mut self, ctx: &egui::Context, top: Option<f32>) {
        let now = Instant::now();
        self.0.retain(|t| t.until > now);
        if self.0.is_empty() {
            return;
        }
        let (align, offset) = match top {
            Some(y) => (egui::Align2::RIGHT_TOP, [-12.0, y + 12.0]),
            None => (egui::Align2::RIGHT_BOTTOM, [-12.0, -36.0]),
        };
        egui::Area::new(egui::Id::unique("raylab-toasts"))
            .anchor(align, offset)
            .order(egui::Order::Foreground)
            .interactable(false)
            .show(ctx, |ui| {
                for t in &self.0 {
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
                            // An area anchored at the right edge starts narrow: give the
                            // text its own width up to 420 points, so a long message wraps
                            // into lines, not a word per line.
                            let font = egui::TextStyle::Body.resolve(ui.style());
                            let size = font.size;
                            let natural = ui
                                .painter()
                                .layout_no_wrap(t.text.clone(), font, Color32::WHITE)
                                .size()
                                .x;
                            ui.set_width(natural.min(34.0 * size));
                            ui.label(RichText::new(&t.text).color(Color32::WHITE));
                        });
                }
            });
        // Expire them even while nothing else happens.
        ctx.request_repaint_after(Duration::from_millis(250));
    }
}
