//! The section view and the interface workbench in the dock: the library's diagrams
//! ([`crate::section`]) painted with egui, the hovered ray linked to the image's overlay
//! and the tree list, the workbench's angle dragged with the mouse, and the pixels that
//! meet glass at that angle outlined in the image.

use super::inspector::Inspection;
use crate::camera::Camera;
use crate::params::Params;
use crate::scene::Scene;
use crate::section::{
    Anchor, Bench, Canvas, Dash, Diagram, Fit, MAX_ZOOM, Room, Stroke, Theme, Workbench, section,
};
use egui::{Color32, Pos2, Sense, pos2};
use glam::Vec2;
use std::sync::Arc;
use std::thread::JoinHandle;

/// Which diagram the section view shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SectionMode {
    /// The inspected pixel's ray tree in its plane.
    Pixel,
    /// One flat interface and one ray: the lecture's Snell and Fresnel figure.
    Workbench,
    /// The camera's real lens cut through its axis, and the inspected pixel's rays through
    /// its glass.
    LensBench,
}

/// The section view's state.
pub(crate) struct SectionState {
    pub(crate) mode: SectionMode,
    /// The workbench's angle of incidence, degrees.
    pub(crate) angle: f32,
    /// The workbench seen from inside: from the material out to the scene's medium.
    pub(crate) out: bool,
    /// Outline the image's pixels that meet a dielectric at the workbench's angle.
    pub(crate) outline: bool,
    /// How far the pixel's section is zoomed in on its first hit (a click on another
    /// pixel shows the whole tree again).
    zoom: f32,
    incidence: Option<Incidence>,
}

impl Default for SectionState {
    fn default() -> Self {
        SectionState {
            mode: SectionMode::Pixel,
            angle: 30.0,
            out: false,
            outline: true,
            zoom: 1.0,
            incidence: None,
        }
    }
}

/// What the incidence map was computed for.
#[derive(Clone, PartialEq)]
struct IncidenceKey {
    scene: usize,
    camera: Camera,
    params: Params,
    size: (u32, u32),
}

/// The image's first-hit angles (computed off the UI thread) and the outline drawn from
/// them at one angle.
struct Incidence {
    key: IncidenceKey,
    job: Option<JoinHandle<AngleMap>>,
    map: Option<AngleMap>,
    texture: Option<(f32, egui::TextureHandle)>,
}

/// The angle of incidence at each pixel's first surface, row by row, and the image size
/// (width, height) it was computed at: the map shown while a new one is computed may be
/// of another size (another slide's image).
type AngleMap = (Vec<Option<f32>>, (u32, u32));

impl SectionState {
    /// How many pixels the outline covers at the workbench's angle, once the angles are
    /// computed.
    pub(crate) fn outlined(&self) -> Option<usize> {
        let (map, _) = self.incidence.as_ref()?.map.as_ref()?;
        let band = crate::render::incidence_band(map, self.angle);
        Some(band.iter().filter(|&&b| b).count())
    }

    /// How far the pixel's section is zoomed in on its first hit.
    pub(crate) fn zoom(&self) -> f32 {
        self.zoom
    }

    /// Zooms the pixel's section `zoom` times in on its first hit (1: the whole tree).
    pub(crate) fn zoom_to(&mut self, zoom: f32) {
        self.zoom = zoom;
    }

    /// The outline of the pixels that meet a dielectric within the band of the workbench's
    /// angle (asked while [`super::Instruments::outline_shown`]), for the image of `size` seen through `camera` with `params`: a texture to lay
    /// over the image, once the angles are computed (on a thread of its own, started here
    /// the first time they are asked for).
    pub(crate) fn outline_texture(
        &mut self,
        ctx: &egui::Context,
        scene: &Arc<Scene>,
        camera: &Camera,
        params: &Params,
        size: (u32, u32),
    ) -> Option<&egui::TextureHandle> {
        let key = IncidenceKey {
            scene: Arc::as_ptr(scene) as usize,
            camera: camera.clone(),
            params: params.clone(),
            size,
        };
        // One computation at a time: while the controls move, the outline waits for the
        // one running and then starts on what they show by then.
        let stale = self.incidence.as_ref().is_none_or(|i| i.key != key);
        let running = self.incidence.as_ref().is_some_and(|i| i.job.is_some());
        if stale && !running {
            let (scene, camera, params) = (scene.clone(), camera.clone(), params.clone());
            let job = std::thread::spawn(move || {
                let map = crate::render::incidence_map(&scene, &camera, &params, size.0, size.1);
                (map, size)
            });
            // The outline shown so far stays until the new one is ready.
            let (map, texture) = match self.incidence.take() {
                Some(i) => (i.map, i.texture),
                None => (None, None),
            };
            self.incidence = Some(Incidence {
                key,
                job: Some(job),
                map,
                texture,
            });
        }
        let angle = self.angle;
        let i = self.incidence.as_mut()?;
        if i.job.as_ref().is_some_and(|j| j.is_finished()) {
            i.map = i.job.take().and_then(|j| j.join().ok());
            i.texture = None;
        } else if i.job.is_some() || stale {
            ctx.request_repaint_after(std::time::Duration::from_millis(50));
        }
        let (map, (width, height)) = i.map.as_ref()?;
        if i.texture.as_ref().is_none_or(|(a, _)| *a != angle) {
            let band = crate::render::incidence_band(map, angle);
            let pixels = band
                .iter()
                .map(|&b| match b {
                    true => Color32::from_rgb(255, 0, 220),
                    false => Color32::TRANSPARENT,
                })
                .collect();
            let image = egui::ColorImage::new([*width as usize, *height as usize], pixels);
            let texture = ctx.load_texture("incidence-band", image, egui::TextureOptions::NEAREST);
            i.texture = Some((angle, texture));
        }
        i.texture.as_ref().map(|(_, t)| t)
    }
}

/// The section view: a toggle between the pixel's section and the workbench, then the
/// diagram. Returns the tree node whose ray the pointer hovers in it.
/// In a `hall` the diagrams go without their title, notes and hints: the tab names them,
/// and every line of text is large. Under the Fresnel plot in a hall (`shared`) the
/// workbench is its drawing alone: dragging on it sets the angle, which it writes.
pub(crate) fn section_ui(
    ui: &mut egui::Ui,
    state: &mut SectionState,
    inspection: Option<&Inspection>,
    (scene, ior, roughness): (&Scene, f32, f32),
    highlight: Option<usize>,
    (hall, shared): (bool, bool),
) -> Option<usize> {
    // A slide picks the mode in a hall, where every row is dear.
    if !hall {
        ui.horizontal(|ui| {
        ui.selectable_value(&mut state.mode, SectionMode::Pixel, "Pixel's section")
            .on_hover_text("The inspected pixel's ray tree, in the plane of its camera ray and the normal where it first meets a surface.");
        ui.selectable_value(&mut state.mode, SectionMode::Workbench, "Interface workbench")
            .on_hover_text("One flat interface, one ray: drag the angle.");
        ui.selectable_value(&mut state.mode, SectionMode::LensBench, "Lens bench")
            .on_hover_text("The camera's real lens (the Lens menu under Camera) cut through its axis: its elements, its stop, the film, and the inspected pixel's rays through the glass with their angles at each surface.");
        });
    }
    match state.mode {
        SectionMode::Pixel => match inspection {
            Some(i) => pixel_ui(ui, i, scene, highlight, &mut state.zoom, hall),
            None => {
                ui.label(
                    "Click a pixel of the image: its ray tree is drawn here in its own plane.",
                );
                None
            }
        },
        SectionMode::Workbench => {
            workbench_ui(
                ui,
                state,
                (scene.medium_ior, ior, roughness),
                (hall, shared),
            );
            None
        }
        SectionMode::LensBench => {
            match inspection {
                Some(i) => lens_bench_ui(ui, i, hall),
                None => {
                    ui.label("Click a pixel of the image: the lens bench draws its rays through the camera's lens.");
                }
            }
            None
        }
    }
}

/// The lens bench of the inspected pixel's sample, or why there is none.
fn lens_bench_ui(ui: &mut egui::Ui, inspection: &Inspection, hall: bool) {
    let (w, h) = inspection.size;
    let camera = &inspection.camera;
    let frame = camera.frame(w as f32 / h as f32, camera.exposure(&inspection.params));
    let Some(lens) = frame.real_lens() else {
        ui.label("The camera has the thin lens, an ideal disk with no glass to draw: choose a real lens under the Lens menu under Camera.");
        return;
    };
    let bench = Bench {
        lens,
        film: inspection.film,
        sample: inspection.lens_point,
    };
    let Some(mut diagram) = bench.diagram() else {
        ui.label("No ray from this pixel's film point gets through the lens.");
        return;
    };
    if !hall {
        let (x, y) = inspection.pixel;
        diagram.title = format!("Lens bench at pixel ({x}, {y}), sample 0");
    }
    let (response, painter) = canvas(ui, "Lens bench diagram", Sense::hover(), 200.0);
    let rect = response.rect;
    let size = Vec2::new(rect.width(), rect.height());
    let fit = Fit::new(
        &diagram,
        Vec2::new(rect.min.x, rect.min.y),
        size,
        text_height(ui),
    );
    paint_on(&painter, &diagram, &fit, None);
}

/// The canvas's text height: the window's body text (the caption's size in a hall).
fn text_height(ui: &egui::Ui) -> f32 {
    egui::TextStyle::Body.resolve(ui.style()).size
}

/// A canvas as wide as the dock and a little less tall (at least `least`), labelled
/// `name` for assistive tools.
fn canvas(
    ui: &mut egui::Ui,
    name: &str,
    sense: Sense,
    least: f32,
) -> (egui::Response, egui::Painter) {
    // As wide as the dock shows (a hall's wide rows widen what scrolls), square or as
    // tall as the dock still shows.
    let shown = ui.clip_rect().right() - ui.cursor().left();
    let width = ui.available_width().min(shown).max(200.0);
    let visible = ui.clip_rect().bottom() - ui.cursor().top();
    let height = width.min(visible.max(least));
    let (response, painter) = ui.allocate_painter(egui::vec2(width, height), sense);
    let name = name.to_string();
    response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Canvas, true, &name));
    (response, painter)
}

/// The inspected pixel's section, zoomed by the wheel about its first hit (a double click
/// shows it whole again).
fn pixel_ui(
    ui: &mut egui::Ui,
    inspection: &Inspection,
    scene: &Scene,
    highlight: Option<usize>,
    zoom: &mut f32,
    hall: bool,
) -> Option<usize> {
    if !hall {
        ui.label("Wheel: zoom in on the first hit. Double click: the whole tree.");
    }
    let (response, painter) = canvas(ui, "Section diagram", Sense::click(), 200.0);
    if response.hovered() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        *zoom = (*zoom * (scroll * 0.004).exp()).clamp(1.0, MAX_ZOOM);
    }
    if response.double_clicked() {
        *zoom = 1.0;
    }
    let rect = response.rect;
    let room = Room {
        size: Vec2::new(rect.width(), rect.height()),
        text: text_height(ui),
        zoom: *zoom,
        titled: !hall,
    };
    let (size, text) = (room.size, room.text);
    let (w, h) = inspection.size;
    let frame = inspection.camera.frame(
        w as f32 / h as f32,
        inspection.camera.exposure(&inspection.params),
    );
    let diagram = section(scene, &frame, &inspection.tree, inspection.pixel, room)?;
    let fit = Fit::new(&diagram, Vec2::new(rect.min.x, rect.min.y), size, text);
    let hovered = response
        .hover_pos()
        .and_then(|p| diagram.ray_near(fit.to_plane(Vec2::new(p.x, p.y)), 8.0 / fit.scale()));
    paint_on(&painter, &diagram, &fit, hovered.or(highlight));
    hovered
}

fn workbench_ui(
    ui: &mut egui::Ui,
    state: &mut SectionState,
    (medium, ior, roughness): (f32, f32, f32),
    (hall, shared): (bool, bool),
) {
    let (n1, n2) = if state.out {
        (ior, medium)
    } else {
        (medium, ior)
    };
    if !shared {
        workbench_controls_ui(ui, state, (n1, n2));
    }
    // Under the plot, what is left of the dock's view, however little.
    let least = if shared { 100.0 } else { 200.0 };
    let bench = Workbench {
        n1,
        n2,
        theta_i: state.angle,
        roughness,
    };
    let (response, painter) = canvas(ui, "Workbench diagram", Sense::click_and_drag(), least);
    let rect = response.rect;
    let size = Vec2::new(rect.width(), rect.height());
    let text = text_height(ui);
    // In a hall the drawing, at the caption's size, and one line of notes (R, and
    // Schlick's): its angles, the rays' widths and the guides say what the rest would.
    let diagram = |theta_i| {
        let bench = Workbench { theta_i, ..bench };
        let mut d = bench.diagram();
        if hall {
            d.title.clear();
            d.notes = vec![bench.hall_note()];
        }
        d
    };
    let fit = Fit::new(
        &diagram(state.angle),
        Vec2::new(rect.min.x, rect.min.y),
        size,
        text,
    );
    if let Some(p) = response
        .interact_pointer_pos()
        .filter(|_| response.is_pointer_button_down_on() || response.clicked())
    {
        state.angle = Workbench::angle_at(fit.to_plane(Vec2::new(p.x, p.y)));
    }
    paint_on(&painter, &diagram(state.angle), &fit, None);
}

/// The workbench's indices with a button that swaps its sides, its angle's slider, and
/// the outline of that angle in the image.
fn workbench_controls_ui(ui: &mut egui::Ui, state: &mut SectionState, (n1, n2): (f32, f32)) {
    ui.horizontal(|ui| {
        ui.label(format!("η1 = {}, η2 = {}", crate::section::index(n1), crate::section::index(n2)));
        if ui
            .button("Swap sides")
            .on_hover_text("The same interface seen from the other side: light going out of the material, where total internal reflection can happen.")
            .clicked()
        {
            state.out = !state.out;
        }
    });
    ui.add(
        egui::Slider::new(&mut state.angle, 0.0..=crate::section::MAX_ANGLE)
            .text("Angle of incidence")
            .suffix("°")
            .fixed_decimals(1),
    );
    ui.checkbox(&mut state.outline, "Outline this angle in the image")
        .on_hover_text(format!(
            "Pixels whose camera ray first meets a dielectric at this angle of incidence, ±{}°, outlined in magenta on the image.",
            crate::render::INCIDENCE_BAND
        ));
}

/// Paints `diagram` as `fit` places it, in the window's dark colours.
fn paint_on(painter: &egui::Painter, diagram: &Diagram, fit: &Fit, highlight: Option<usize>) {
    let mut canvas = EguiCanvas { painter };
    crate::section::paint(diagram, &mut canvas, fit, Theme::Dark, highlight);
}

struct EguiCanvas<'p> {
    painter: &'p egui::Painter,
}

fn colour(c: [u8; 4]) -> Color32 {
    Color32::from_rgba_unmultiplied(c[0], c[1], c[2], c[3])
}

fn at(v: Vec2) -> Pos2 {
    pos2(v.x, v.y)
}

impl Canvas for EguiCanvas<'_> {
    fn polyline(&mut self, points: &[Vec2], stroke: Stroke) {
        let points: Vec<Pos2> = points.iter().map(|p| at(*p)).collect();
        let line = egui::Stroke::new(stroke.width, colour(stroke.colour));
        match stroke.dash {
            Dash::Solid => {
                self.painter.line(points, line);
            }
            Dash::Dashed => {
                let gap = 0.7 * stroke.period;
                self.painter
                    .extend(egui::Shape::dashed_line(&points, line, stroke.period, gap));
            }
            Dash::Dotted => {
                let radius = 0.5 * stroke.width;
                self.painter.extend(egui::Shape::dotted_line(
                    &points,
                    line.color,
                    stroke.period,
                    radius,
                ));
            }
        }
    }

    fn circle(&mut self, c: Vec2, r: f32, fill: Option<[u8; 4]>, stroke: Option<Stroke>) {
        let fill = fill.map_or(Color32::TRANSPARENT, colour);
        let stroke = stroke.map_or(egui::Stroke::NONE, |s| {
            egui::Stroke::new(s.width, colour(s.colour))
        });
        self.painter.circle(at(c), r, fill, stroke);
    }

    fn polygon(&mut self, points: &[Vec2], fill: [u8; 4]) {
        let points = points.iter().map(|p| at(*p)).collect();
        self.painter.add(egui::Shape::convex_polygon(
            points,
            colour(fill),
            egui::Stroke::NONE,
        ));
    }

    fn text(&mut self, p: Vec2, text: &str, size: f32, c: [u8; 4], anchor: Anchor) {
        let align = match anchor {
            Anchor::Start => egui::Align2::LEFT_CENTER,
            Anchor::Middle => egui::Align2::CENTER_CENTER,
            Anchor::End => egui::Align2::RIGHT_CENTER,
        };
        self.painter.text(
            at(p),
            align,
            text,
            egui::FontId::proportional(size),
            colour(c),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_outline_computed_for_another_image_size_is_drawn_at_its_own_size() {
        // The outline of the last image stays shown while the next one's is computed; if
        // the next slide's image has another size, its texture must keep the old map's
        // size (built at the new one, the window aborted in the GPU upload).
        let ctx = egui::Context::default();
        let scene = Arc::new(Scene::load("glass").unwrap());
        let mut state = SectionState {
            mode: SectionMode::Workbench,
            ..SectionState::default()
        };
        let params = scene.params.clone();
        let (small, large) = ((80, 48), (96, 54));
        // The first map, computed to the end.
        while state.incidence.as_ref().is_none_or(|i| i.map.is_none()) {
            state.outline_texture(&ctx, &scene, &scene.camera, &params, small);
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        // Another size and another angle: the texture is rebuilt from the old map at once.
        state.angle += 5.0;
        let texture = state.outline_texture(&ctx, &scene, &scene.camera, &params, large);
        let [w, h] = texture.unwrap().size();
        // Usually the old map (the new one is still being computed): its texels, its size.
        let (map, _) = state.incidence.as_ref().unwrap().map.as_ref().unwrap();
        assert_eq!(
            w * h,
            map.len(),
            "a {w}×{h} texture of {} texels",
            map.len()
        );
    }
}
