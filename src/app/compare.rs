//! The A/B view: side B renders the same scene with one setting changed (or frozen), in an
//! engine of its own; a divider splits the image between the two sides.

use super::RaylabApp;
use super::side::Side;
use crate::lecture::Comparison;
use crate::params::Params;
use crate::render::EngineConfig;
use egui::Color32;

/// What the two sides of the A/B view differ in: one of the lecture's comparisons, or
/// the parameters frozen at a moment (B) against the controls (A).
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum CompareKind {
    /// A comparison of the lecture's (a preset or a slide's).
    Lecture(Comparison),
    /// The parameters as they were when frozen (B) against the controls (A).
    Frozen(Params),
}

impl CompareKind {
    /// The labels of side A and side B.
    fn labels(&self) -> (&'static str, &'static str) {
        match self {
            CompareKind::Lecture(c) => c.labels(),
            CompareKind::Frozen(_) => ("A: the controls", "B: frozen"),
        }
    }

    /// Side A's parameters when the comparison starts.
    fn side_a(&self, p: &Params) -> Params {
        match self {
            CompareKind::Lecture(c) => c.side_a(p),
            CompareKind::Frozen(_) => p.clone(),
        }
    }

    /// Side B's parameters, given side A's.
    pub(super) fn side_b(&self, a: &Params) -> Params {
        match self {
            CompareKind::Lecture(c) => c.side_b(a),
            CompareKind::Frozen(b) => b.clone(),
        }
    }
}

/// Side B and where the divider is.
pub(crate) struct Compare {
    pub(crate) kind: CompareKind,
    pub(crate) side: Side,
    // The divider's position across the image, 0 (all B) to 1 (all A).
    divider: f32,
}

impl RaylabApp {
    /// Splits the view between the controls' parameters (A) and `kind`'s other side (B),
    /// the divider first at `divider` across the image.
    pub(super) fn start_compare(&mut self, ctx: &egui::Context, kind: CompareKind, divider: f32) {
        self.settings.params = kind.side_a(&self.settings.params);
        let b = kind.side_b(&self.settings.params);
        match Side::new(
            ctx,
            "raylab-image-b",
            self.told(),
            b,
            EngineConfig::with_ui(),
        ) {
            Ok(side) => {
                self.compare = Some(Compare {
                    kind,
                    side,
                    divider,
                })
            }
            Err(e) => self.toasts.error(format!("Cannot compare: {e}")),
        }
    }

    /// While comparing, side A keeps its side of the comparison when the parameters are
    /// replaced (a scene opened, Reset).
    pub(super) fn keep_side_a(&mut self) {
        if let Some(c) = &self.compare {
            self.settings.params = c.kind.side_a(&self.settings.params);
        }
    }

    /// The A/B compare menu.
    pub(super) fn compare_menu_ui(&mut self, ui: &mut egui::Ui) {
        for (label, c) in Comparison::PRESETS {
            if ui.button(label).clicked() {
                self.start_compare(ui.ctx(), CompareKind::Lecture(c), 0.5);
                ui.close();
            }
        }
        let frozen = ui
            .button("the controls | frozen copy")
            .on_hover_text("B keeps the parameters as they are now; change A with the controls.");
        if frozen.clicked() {
            let kind = CompareKind::Frozen(self.settings.params.clone());
            self.start_compare(ui.ctx(), kind, 0.5);
            ui.close();
        }
        if ui
            .add_enabled(self.compare.is_some(), egui::Button::new("Off"))
            .clicked()
        {
            self.compare = None;
            ui.close();
        }
    }

    /// Draws side B right of the divider, the divider, and the two sides' labels.
    pub(super) fn compare_overlay_ui(&mut self, ui: &mut egui::Ui, image: egui::Rect) {
        let a_spp = self.main.frame().map_or(0, |f| f.progress.spp);
        let Some(c) = &mut self.compare else { return };
        let x = image.min.x + c.divider * image.width();
        let clip = egui::Rect::from_min_max(egui::pos2(x, image.min.y), image.max)
            .intersect(ui.clip_rect());
        if let Some(t) = c.side.texture() {
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
        let b_spp = c.side.frame().map_or(0, |f| f.progress.spp);
        // In a hall the labels grow with the caption.
        // In a hall the labels are the caption's size.
        let size = if self.hall.presenting {
            super::present::caption_size(ui.ctx().content_rect().height())
        } else {
            15.0
        };
        // Labels on dark plates: legible over a white sky too.
        let label = |text: String, anchor: egui::Pos2, align: egui::Align2| {
            let galley =
                painter.layout_no_wrap(text, egui::FontId::proportional(size), Color32::WHITE);
            let rect = align.anchor_size(anchor, galley.size());
            painter.rect_filled(rect.expand(5.0), 4.0, Color32::from_black_alpha(170));
            painter.galley(rect.min, galley, Color32::WHITE);
        };
        label(
            format!("{a} ({a_spp} spp)"),
            image.min + egui::vec2(12.0, 12.0),
            egui::Align2::LEFT_TOP,
        );
        label(
            format!("{b} ({b_spp} spp)"),
            egui::pos2(image.max.x - 12.0, image.min.y + 12.0),
            egui::Align2::RIGHT_TOP,
        );
    }
}
