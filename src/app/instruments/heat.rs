//! The cost heat map: rays traced per sample in each pixel, black to pale yellow.

use crate::render::ramp::inferno;

/// The cost heat map as RGBA: rays per sample from `lo` (black) to `hi` (pale yellow).
pub(crate) fn heat_map_rgba(cost: &[f32], lo: f32, hi: f32) -> Vec<u8> {
    let span = (hi - lo).max(1e-6);
    cost.iter()
        .flat_map(|&c| {
            let [r, g, b] = inferno((c - lo) / span);
            [r, g, b, 255]
        })
        .collect()
}

/// The smallest and largest values of `cost`.
pub(crate) fn cost_range(cost: &[f32]) -> (f32, f32) {
    cost.iter().fold((f32::INFINITY, 0.0f32), |(lo, hi), &c| {
        (lo.min(c), hi.max(c))
    })
}

/// The heat map's colour bar, in the image's bottom left corner: the ramp from `lo` to `hi`
/// rays per sample, with its ends labelled.
pub(crate) fn draw_colour_bar(painter: &egui::Painter, image: egui::Rect, (lo, hi): (f32, f32)) {
    let size = egui::vec2(220.0, 14.0);
    let min = image.left_bottom() + egui::vec2(12.0, -12.0 - size.y - 18.0);
    let back = egui::Rect::from_min_size(min - egui::vec2(6.0, 6.0), size + egui::vec2(12.0, 30.0));
    painter.rect_filled(back, 4.0, egui::Color32::from_black_alpha(170));
    let steps = 64;
    for k in 0..steps {
        let t = (k as f32 + 0.5) / steps as f32;
        let [r, g, b] = inferno(t);
        let x0 = min.x + size.x * k as f32 / steps as f32;
        let rect = egui::Rect::from_min_max(
            egui::pos2(x0, min.y),
            egui::pos2(x0 + size.x / steps as f32 + 0.5, min.y + size.y),
        );
        painter.rect_filled(rect, 0.0, egui::Color32::from_rgb(r, g, b));
    }
    // Numbers, at half the body text's size or 13 points, whichever is larger (a hall's
    // text is large).
    let body = egui::TextStyle::Body
        .resolve(painter.ctx().global_style().as_ref())
        .size;
    let font = egui::FontId::proportional((body * 0.5).max(13.0));
    let white = egui::Color32::WHITE;
    let y = min.y + size.y + 2.0;
    painter.text(
        egui::pos2(min.x, y),
        egui::Align2::LEFT_TOP,
        format!("{lo:.0}"),
        font.clone(),
        white,
    );
    painter.text(
        egui::pos2(min.x + size.x, y),
        egui::Align2::RIGHT_TOP,
        format!("{hi:.0} rays per sample"),
        font,
        white,
    );
}
