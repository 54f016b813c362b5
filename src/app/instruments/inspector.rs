//! The ray-tree inspector: the whole tree of one sample, as nested sections with the
//! lecture's quantities at each hit, and drawn over the image.

/// The ray tree of one pixel, as the inspector shows it.
pub(crate) struct Inspection {
    /// The pixel.
    pub pixel: (u32, u32),
    /// The image size it belongs to.
    pub size: (u32, u32),
    /// The parameters it was traced with.
    pub params: crate::params::Params,
    /// The camera it was traced through.
    pub camera: crate::camera::Camera,
    /// Its tree for sample 0.
    pub tree: crate::tracer::RayTree,
    /// The radiance the sample returned.
    pub radiance: crate::math::Color,
    /// Its image position (0 to 1 across and down), for the lens bench.
    pub film: glam::Vec2,
    /// Its point on the lens (unit square), for the lens bench.
    pub lens_point: glam::Vec2,
}

/// A ray's colour by its kind: the section view's palette, so that the overlay, the list
/// and the section agree.
fn kind_color(kind: crate::tracer::RayKind) -> egui::Color32 {
    let [r, g, b, a] = crate::section::Ink::Ray(kind).rgba(crate::section::Theme::Dark);
    egui::Color32::from_rgba_unmultiplied(r, g, b, a)
}

/// Draws the recorded rays over the image: each segment projected through the camera,
/// ray `highlight` (hovered here, in the section view or in the list) with a halo. Returns
/// the ray the pointer at `pointer` is over, if any.
pub(crate) fn draw_tree_overlay(
    painter: &egui::Painter,
    image: egui::Rect,
    frame: &crate::camera::CameraFrame,
    tree: &crate::tracer::RayTree,
    highlight: Option<usize>,
    pointer: Option<egui::Pos2>,
) -> Option<usize> {
    let mut hovered: Option<(usize, f32)> = None;
    let to_screen = |p: crate::math::Vec3| {
        frame
            .project(p)
            .map(|f| image.min + egui::vec2(f.x * image.width(), f.y * image.height()))
    };
    // Widths grow with the image: 2-point rays on a 540-point image, thicker on a
    // projector's full-screen image, where 1 px lines vanish from the back of the hall.
    let u = (image.height() / 540.0).max(1.0);
    for (i, n) in tree.nodes.iter().enumerate() {
        let lit = highlight == Some(i);
        // The camera ray runs along the line of sight: it would project to a dot. A ring
        // marks where it meets the scene instead.
        if n.kind == crate::tracer::RayKind::Camera {
            if let Some(b) = to_screen(n.end_point) {
                let stroke = egui::Stroke::new(2.0 * u, kind_color(n.kind));
                painter.circle_stroke(b, 9.0 * u, stroke);
                let rim = egui::Stroke::new(u, egui::Color32::BLACK);
                painter.circle_stroke(b, 10.5 * u, rim);
            }
            continue;
        }
        // A segment behind the camera cannot be drawn; pruned branches have no length.
        let (Some(a), Some(b)) = (to_screen(n.ray.origin), to_screen(n.end_point)) else {
            continue;
        };
        let width = if n.kind == crate::tracer::RayKind::Shadow {
            u
        } else {
            2.0 * u
        };
        if lit {
            let halo = egui::Stroke::new(width + 6.0 * u, egui::Color32::from_white_alpha(110));
            painter.line_segment([a, b], halo);
        }
        painter.line_segment([a, b], egui::Stroke::new(width, kind_color(n.kind)));
        if let Some(p) = pointer {
            let v = |q: egui::Pos2| glam::Vec2::new(q.x, q.y);
            let d = crate::section::distance_to_segment(v(p), v(a), v(b));
            if d <= 6.0 * u && hovered.is_none_or(|(_, best)| d < best) {
                hovered = Some((i, d));
            }
        }
        if n.hit.is_some() {
            painter.circle_filled(b, 3.0 * u, kind_color(n.kind));
        }
    }
    hovered.map(|(i, _)| i)
}

/// The inspector: the tree as nested sections, each ray with the lecture's quantities.
/// Returns the ray whose entry the pointer hovers; ray `highlight`'s entry stands out.
pub(crate) fn inspector_ui(
    ui: &mut egui::Ui,
    inspection: &Inspection,
    names: &[String],
    materials: &[String],
    highlight: Option<usize>,
) -> Option<usize> {
    let c = inspection.radiance;
    ui.label(format!(
        "Pixel ({}, {}), sample 0: radiance ({:.3}, {:.3}, {:.3}), {} rays",
        inspection.pixel.0,
        inspection.pixel.1,
        c.x,
        c.y,
        c.z,
        inspection.tree.nodes.len()
    ));
    ui.label("White: camera ray. Blue: reflected. Orange: refracted. Yellow: shadow rays.");
    let mut hovered = None;
    egui::ScrollArea::vertical()
        .max_height(460.0)
        .show(ui, |ui| {
            let list = List {
                inspection,
                names,
                materials,
                highlight,
            };
            for root in inspection.tree.roots() {
                node_ui(ui, &list, root, &mut hovered);
            }
        });
    hovered
}

/// What the tree list draws from.
struct List<'a> {
    inspection: &'a Inspection,
    names: &'a [String],
    materials: &'a [String],
    highlight: Option<usize>,
}

fn node_ui(ui: &mut egui::Ui, list: &List, id: usize, hovered: &mut Option<usize>) {
    let tree = &list.inspection.tree;
    let Some(n) = tree.nodes.get(id) else { return };
    let title = n.title(list.names, list.materials);
    let mut text = egui::RichText::new(title).color(kind_color(n.kind));
    if list.highlight == Some(id) {
        text = text
            .strong()
            .background_color(egui::Color32::from_white_alpha(40));
    }
    let header = egui::CollapsingHeader::new(text)
        .id_salt(("ray-node", id))
        .default_open(n.depth < 3)
        .show(ui, |ui| {
            egui::Grid::new(("ray-grid", id))
                .num_columns(2)
                .show(ui, |ui| {
                    for (label, value) in n.rows() {
                        let response = ui.label(label);
                        ui.label(value);
                        ui.end_row();
                        if label == crate::tracer::STOKES_ROW {
                            response.on_hover_text("How this ray's light counts through the polariser and the interfaces above (green), per Stokes component in its s/p frame: unpolarised light counts I, light polarised along s I + Q, along p I − Q.");
                        }
                    }
                });
            for (child, _) in tree.children(id) {
                node_ui(ui, list, child, hovered);
            }
        });
    if header.header_response.hovered() {
        *hovered = Some(id);
    }
}
