//! The A/B view: side B (and C) renders the same scene with one setting changed (or
//! frozen), each in an engine of its own; dividers split the image between the sides.

use super::RaylabApp;
use super::side::{Side, Told};
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
    /// The labels of the sides, A first.
    fn labels(&self) -> &'static [&'static str] {
        match self {
            CompareKind::Lecture(c) => c.labels(),
            CompareKind::Frozen(_) => &["A: the controls", "B: frozen"],
        }
    }

    /// Side A's parameters when the comparison starts.
    pub(super) fn side_a(&self, p: &Params) -> Params {
        match self {
            CompareKind::Lecture(c) => c.side_a(p),
            CompareKind::Frozen(_) => p.clone(),
        }
    }

    /// The parameters of the sides after A (B, and C), given side A's.
    pub(super) fn others(&self, a: &Params) -> Vec<Params> {
        match self {
            CompareKind::Lecture(c) => c.others(a),
            CompareKind::Frozen(b) => vec![b.clone()],
        }
    }
}

/// The sides after A (B, and C) and where the dividers are.
pub(crate) struct Compare {
    pub(crate) kind: CompareKind,
    pub(crate) sides: Vec<Side>,
    // The dividers' positions across the image, left to right, 0 to 1: side A left of
    // the first, each other side right of its own.
    pub(super) dividers: Vec<f32>,
}

// The names of the sides' textures, B first.
const TEXTURES: [&str; 2] = ["raylab-image-b", "raylab-image-c"];

impl RaylabApp {
    /// Splits the view between the controls' parameters (A) and `kind`'s other sides (B,
    /// and C), the dividers first at `dividers` across the image.
    pub(super) fn start_compare(
        &mut self,
        ctx: &egui::Context,
        kind: CompareKind,
        dividers: Vec<f32>,
    ) {
        self.settings.params = kind.side_a(&self.settings.params);
        let (told, a) = (self.told(), self.settings.params.clone());
        if let Some(c) = self.new_compare(ctx, &told, kind, dividers, &a) {
            self.compare = Some(c);
        }
    }

    /// The sides after A of `kind`'s comparison, side A's parameters `a`, each rendering
    /// `told` in an engine of its own (none, said in a message, if they cannot start).
    pub(super) fn new_compare(
        &mut self,
        ctx: &egui::Context,
        told: &Told,
        kind: CompareKind,
        dividers: Vec<f32>,
        a: &Params,
    ) -> Option<Compare> {
        let started: Result<Vec<Side>, _> = kind
            .others(a)
            .into_iter()
            .zip(TEXTURES)
            .map(|(p, name)| {
                let cache = self.main.cache().clone();
                Side::new(ctx, name, told.clone(), p, EngineConfig::with_ui(), cache)
            })
            .collect();
        match started {
            Ok(sides) => Some(Compare {
                kind,
                sides,
                dividers,
            }),
            Err(e) => {
                self.toasts.error(format!("Cannot compare: {e}"));
                None
            }
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
        // The comparison shown is marked, whether a slide or the menu started it.
        let on = self.compare.as_ref().map(|c| match &c.kind {
            CompareKind::Lecture(k) => Some(*k),
            CompareKind::Frozen(_) => None,
        });
        for (label, c) in Comparison::PRESETS {
            let shown = on == Some(Some(c));
            if ui.selectable_label(shown, label).clicked() {
                self.start_compare(ui.ctx(), CompareKind::Lecture(c), c.dividers(0.5));
                ui.close();
            }
        }
        let shown = on == Some(None);
        let frozen = ui
            .selectable_label(shown, "the controls | frozen copy")
            .on_hover_text("B keeps the parameters as they are now; change A with the controls.");
        if frozen.clicked() {
            let kind = CompareKind::Frozen(self.settings.params.clone());
            self.start_compare(ui.ctx(), kind, vec![0.5]);
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

    /// Draws each side after A right of its divider, the dividers, and the sides' labels.
    pub(super) fn compare_overlay_ui(&mut self, ui: &mut egui::Ui, image: egui::Rect) {
        let a_spp = self.main.frame().map_or(0, |f| f.progress.spp);
        // In a hall the labels are the caption's size.
        let size = if self.hall.presenting {
            super::present::caption_size(ui.ctx().content_rect().height())
        } else {
            15.0
        };
        let Some(c) = &mut self.compare else { return };
        let across = |d: f32| image.min.x + d * image.width();
        let edges: Vec<f32> = c.dividers.iter().map(|&d| across(d)).collect();
        let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
        for (i, side) in c.sides.iter().enumerate() {
            let (x0, x1) = (edges[i], edges.get(i + 1).copied().unwrap_or(image.max.x));
            let pane = egui::Rect::from_x_y_ranges(x0..=x1.max(x0), image.y_range());
            if let Some(t) = side.texture() {
                ui.painter()
                    .with_clip_rect(pane.intersect(ui.clip_rect()))
                    .image(t.id(), image, uv, Color32::WHITE);
            }
        }
        for (i, &x) in edges.iter().enumerate() {
            let handle = egui::Rect::from_center_size(
                egui::pos2(x, image.center().y),
                egui::vec2(14.0, image.height()),
            );
            let response = ui.interact(
                handle,
                egui::Id::unique(("ab-divider", i)),
                egui::Sense::drag(),
            );
            if response.dragged() {
                // A divider moves between its neighbours, so the sides keep their order.
                let low = if i == 0 { 0.0 } else { c.dividers[i - 1] };
                let high = c.dividers.get(i + 1).copied().unwrap_or(1.0);
                c.dividers[i] =
                    ((x + response.drag_delta().x - image.min.x) / image.width()).clamp(low, high);
            }
            let painter = ui.painter();
            painter.line_segment(
                [egui::pos2(x, image.min.y), egui::pos2(x, image.max.y)],
                egui::Stroke::new(2.0, Color32::WHITE),
            );
            painter.circle_filled(egui::pos2(x, image.center().y), 7.0, Color32::WHITE);
        }
        let painter = ui.painter();
        // Labels on dark plates: legible over a white sky too.
        let label = |text: String, anchor: egui::Pos2, align: egui::Align2| {
            let galley =
                painter.layout_no_wrap(text, egui::FontId::proportional(size), Color32::WHITE);
            let rect = align.anchor_size(anchor, galley.size());
            painter.rect_filled(rect.expand(5.0), 4.0, Color32::from_black_alpha(170));
            painter.galley(rect.min, galley, Color32::WHITE);
        };
        let spp = std::iter::once(a_spp).chain(
            c.sides
                .iter()
                .map(|s| s.frame().map_or(0, |f| f.progress.spp)),
        );
        let last = c.sides.len();
        let top = image.min.y + 12.0;
        for (i, (name, spp)) in c.kind.labels().iter().zip(spp).enumerate() {
            // A at the image's left, the last side at its right, one between at the
            // left of its pane.
            let (x, align) = match i {
                0 => (image.min.x + 12.0, egui::Align2::LEFT_TOP),
                i if i == last => (image.max.x - 12.0, egui::Align2::RIGHT_TOP),
                i => (edges[i - 1] + 12.0, egui::Align2::LEFT_TOP),
            };
            label(format!("{name} ({spp} spp)"), egui::pos2(x, top), align);
        }
    }
}
