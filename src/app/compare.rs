//! The A/B view: side B renders the same scene with one setting changed (or frozen), in an
//! engine of its own; a divider splits the image between the two sides.

use super::RaylabApp;
use super::side::Side;
use crate::optics::FresnelMode;
use crate::params::{Params, Pattern, Transport, TreeMode};
use crate::render::EngineConfig;
use egui::Color32;

/// What the two sides of the A/B view differ in.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum CompareKind {
    /// Schlick's approximation against the exact Fresnel equations.
    SchlickExact,
    /// Random against jittered samples, at the same samples per pixel.
    RandomJittered,
    /// Constant reflectance against Fresnel.
    ConstantFresnel,
    /// The split ray tree against the stochastic one.
    SplitStochastic,
    /// The lecture's black shadows behind glass against transmissive shadows.
    WhittedTransmissive,
    /// The lecture's tracer against path tracing, the reference.
    WhittedPath,
    /// The lecture's tracer against path tracing with photons (point lights' caustics).
    WhittedPhotons,
    /// One sample at each pixel's centre against four jittered samples: supersampling
    /// (a slide's, not a preset: the sides differ in their sample counts).
    Supersampling,
    /// One ray per pixel to a point light against 256 averaged over the pixel and the
    /// area light: distribution ray tracing's blurs (a slide's, not a preset).
    Blurring,
    /// The parameters as they were when frozen (B) against the controls (A).
    Frozen(Params),
}

impl CompareKind {
    /// The presets, for the menu.
    pub fn presets() -> [(&'static str, CompareKind); 7] {
        [
            ("Schlick | exact", CompareKind::SchlickExact),
            ("random | jittered", CompareKind::RandomJittered),
            ("constant | Fresnel", CompareKind::ConstantFresnel),
            ("split | stochastic tree", CompareKind::SplitStochastic),
            (
                "whitted | transmissive shadows",
                CompareKind::WhittedTransmissive,
            ),
            ("whitted | path", CompareKind::WhittedPath),
            ("whitted | path + photons", CompareKind::WhittedPhotons),
        ]
    }

    /// The labels of side A and side B.
    pub fn labels(&self) -> (&'static str, &'static str) {
        match self {
            CompareKind::SchlickExact => ("A: Schlick", "B: exact Fresnel"),
            CompareKind::RandomJittered => ("A: random", "B: jittered"),
            CompareKind::ConstantFresnel => ("A: constant k", "B: exact Fresnel"),
            CompareKind::SplitStochastic => ("A: split tree", "B: stochastic tree"),
            CompareKind::WhittedTransmissive => ("A: Whitted", "B: transmissive shadows"),
            CompareKind::WhittedPath => ("A: Whitted", "B: path tracing"),
            CompareKind::WhittedPhotons => ("A: Whitted", "B: path tracing + photons"),
            CompareKind::Supersampling => ("A: 1 sample, centre", "B: 4 jittered"),
            CompareKind::Blurring => ("A: 1 ray, point light", "B: 256 rays, area light"),
            CompareKind::Frozen(_) => ("A: the controls", "B: frozen"),
        }
    }

    /// Side A's parameters when the comparison starts.
    pub fn side_a(&self, p: &Params) -> Params {
        let mut p = p.clone();
        match self {
            CompareKind::SchlickExact => p.fresnel = Some(FresnelMode::Schlick),
            CompareKind::RandomJittered => p.pattern = Pattern::Random,
            CompareKind::ConstantFresnel => p.fresnel = Some(FresnelMode::Constant),
            CompareKind::SplitStochastic => p.tree = TreeMode::Split,
            CompareKind::WhittedTransmissive
            | CompareKind::WhittedPath
            | CompareKind::WhittedPhotons => p.transport = Transport::Whitted,
            // The lecture's basic tracer: one ray through each pixel's centre (and, to show
            // what blurring adds, a point light).
            CompareKind::Supersampling | CompareKind::Blurring => {
                p.spp = 1;
                p.pattern = Pattern::Regular;
                if *self == CompareKind::Blurring {
                    p.light_size = 0.0;
                }
            }
            CompareKind::Frozen(_) => {}
        }
        p
    }

    /// Side B's parameters, given side A's: A's with the compared setting changed.
    pub fn side_b(&self, a: &Params) -> Params {
        let mut p = a.clone();
        match self {
            CompareKind::SchlickExact | CompareKind::ConstantFresnel => {
                p.fresnel = Some(FresnelMode::Exact)
            }
            CompareKind::RandomJittered => p.pattern = Pattern::Jittered,
            CompareKind::SplitStochastic => p.tree = TreeMode::Stochastic,
            CompareKind::WhittedTransmissive => p.transport = Transport::TransmissiveShadows,
            CompareKind::WhittedPath => p.transport = Transport::Path,
            CompareKind::WhittedPhotons => p.transport = Transport::Photons,
            CompareKind::Supersampling => {
                p.spp = 4;
                p.pattern = Pattern::Jittered;
            }
            CompareKind::Blurring => {
                p.spp = 256;
                p.pattern = Pattern::Sobol;
                p.light_size = 1.0;
            }
            CompareKind::Frozen(b) => return b.clone(),
        }
        p
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
    /// Splits the view between the controls' parameters (A) and `kind`'s other side (B).
    pub(super) fn start_compare(&mut self, ctx: &egui::Context, kind: CompareKind) {
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
                    divider: 0.5,
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
            let kind = CompareKind::Frozen(self.settings.params.clone());
            self.start_compare(ui.ctx(), kind);
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
        let size = if self.hall.presenting {
            super::present::caption_size(ui.ctx().content_rect().height()) * 0.7
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_differs_in_one_setting_and_keeps_the_rest() {
        let p = Params {
            max_depth: 3,
            spp: 7,
            ..Params::default()
        };
        for (label, kind) in CompareKind::presets() {
            let a = kind.side_a(&p);
            let b = kind.side_b(&a);
            assert_ne!(a, b, "{label}: the sides differ");
            assert_eq!((a.max_depth, a.spp), (3, 7), "{label}: A keeps the rest");
            assert_eq!((b.max_depth, b.spp), (3, 7), "{label}: B keeps the rest");
        }
        for (k, b) in [
            (
                CompareKind::WhittedTransmissive,
                Transport::TransmissiveShadows,
            ),
            (CompareKind::WhittedPath, Transport::Path),
            (CompareKind::WhittedPhotons, Transport::Photons),
        ] {
            let a = k.side_a(&p);
            assert_eq!(a.transport, Transport::Whitted);
            assert_eq!(k.side_b(&a).transport, b);
        }
    }
}
