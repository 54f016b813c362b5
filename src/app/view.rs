//! The image in the central area: fitted to the window by default, zoomed with the wheel
//! and panned by dragging for pixel-peeping; right-drag orbits and Ctrl + wheel dollies
//! the camera; a click reports the image position.

use super::{RaylabApp, instruments, lecture, render_size};
use crate::camera::Camera;
use crate::tracer::pick;
use egui::RichText;
use egui::{Color32, Pos2, Rect, Sense, Ui, Vec2, pos2, vec2};

/// How the image sits in the view.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct ViewState {
    /// Screen points per image pixel; `None` fits the image to the view.
    pub zoom: Option<f32>,
    /// The image point (in pixels) at the view's centre; `None` is the image's centre.
    pub center: Option<Vec2>,
    /// Screen pixels per image pixel as last drawn (the zoom level shown).
    pub scale: f32,
    /// The image position under the cursor, (0, 0) top left to (1, 1) bottom right.
    pub hover: Option<Vec2>,
}

impl ViewState {
    /// Fit the whole image into the view.
    pub fn fit(&mut self) {
        *self = ViewState {
            scale: self.scale,
            ..ViewState::default()
        };
    }

    /// Whether image pixels are shown as sharp squares: only at a whole zoom of 2 or more,
    /// for pixel-peeping. At any other scale they are filtered smoothly, so that a fitted
    /// image shows no uneven stair steps (at ×1.67 nearest-neighbour doubles every third
    /// pixel: the very artefact the antialiasing slide is about).
    pub fn sharp(&self) -> bool {
        self.scale >= 1.99 && (self.scale - self.scale.round()).abs() < 0.01
    }

    /// One image pixel per screen pixel.
    pub fn one_to_one(&mut self, pixels_per_point: f32) {
        self.zoom = Some(1.0 / pixels_per_point);
    }
}

/// What the user did to the image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum ViewEvent {
    /// A click at this image position, (0, 0) top left to (1, 1) bottom right.
    Click(Vec2),
    /// A right-drag by this many points: orbit the camera.
    Orbit(Vec2),
    /// Ctrl + wheel: move the camera towards (positive) or away from its target.
    Dolly(f32),
}

/// Draws the image (`size` pixels); returns what the user did to it, and where on the
/// screen the image is (for overlays).
pub(crate) fn image_ui(
    ui: &mut Ui,
    view: &mut ViewState,
    texture: Option<&egui::TextureHandle>,
    size: (u32, u32),
) -> (Vec<ViewEvent>, Rect) {
    let area = ui.available_rect_before_wrap();
    let response = ui.allocate_rect(area, Sense::click_and_drag());
    // Named for assistive tools (and for tests that check nothing covers it).
    response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Image, true, "Image"));
    let image = vec2(size.0 as f32, size.1 as f32);
    let fit = (area.width() / image.x)
        .min(area.height() / image.y)
        .max(1e-3);
    let zoom = view.zoom.unwrap_or(fit);
    let center = view.center.unwrap_or(image / 2.0);
    let to_screen = |p: Vec2| area.center() + (p - center) * zoom;
    let to_image = |s: Pos2| center + (s - area.center()) / zoom;
    let rect = Rect::from_min_max(to_screen(Vec2::ZERO), to_screen(image));

    view.scale = zoom * ui.ctx().pixels_per_point();
    view.hover = response
        .hover_pos()
        .map(|pos| to_image(pos) / image)
        .filter(|p| (0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y));
    let painter = ui.painter_at(area);
    painter.rect_filled(area, 0.0, Color32::from_gray(24));
    match texture {
        Some(t) => {
            painter.image(
                t.id(),
                rect,
                Rect::from_min_max(pos2(0.0, 0.0), pos2(1.0, 1.0)),
                Color32::WHITE,
            );
        }
        None => {
            painter.text(
                area.center(),
                egui::Align2::CENTER_CENTER,
                "rendering…",
                egui::TextStyle::Heading.resolve(ui.style()),
                Color32::GRAY,
            );
        }
    }

    let mut events = Vec::new();
    if response.hovered() {
        let (scroll, ctrl, pointer) = ui.input(|i| {
            (
                i.smooth_scroll_delta.y,
                i.modifiers.command || i.modifiers.shift,
                i.pointer.hover_pos(),
            )
        });
        if scroll != 0.0 {
            if ctrl {
                events.push(ViewEvent::Dolly(scroll));
            } else if let Some(cursor) = pointer {
                // Zoom about the cursor: the image point under it stays put.
                let under = to_image(cursor);
                let new_zoom = (zoom * (scroll * 0.0015).exp()).clamp(0.02, 64.0);
                view.zoom = Some(new_zoom);
                view.center = Some(under - (cursor - area.center()) / new_zoom);
            }
        }
    }
    if response.dragged_by(egui::PointerButton::Primary) {
        let delta = response.drag_delta();
        view.zoom = Some(zoom);
        view.center = Some(center - delta / zoom);
    }
    if response.dragged_by(egui::PointerButton::Secondary) {
        events.push(ViewEvent::Orbit(response.drag_delta()));
    }
    if response.double_clicked() {
        view.fit();
    } else if response.clicked()
        && let Some(pos) = response.interact_pointer_pos()
    {
        let p = to_image(pos) / image;
        if (0.0..=1.0).contains(&p.x) && (0.0..=1.0).contains(&p.y) {
            events.push(ViewEvent::Click(p));
        }
    }
    (events, rect)
}

impl RaylabApp {
    /// The central area: the scene's error if any, the image with its overlays (side B,
    /// the inspected rays, the slide's caption), and what clicks and drags on it do.
    pub(super) fn image_panel_ui(&mut self, ui: &mut egui::Ui) {
        if let Some(e) = self.error.clone() {
            egui::Frame::new()
                .fill(Color32::from_rgb(110, 24, 24))
                .inner_margin(6.0)
                .show(ui, |ui| {
                    // The button first and the message wrapped under it: a long message on
                    // one row ran under the instruments' dock, and its button with it.
                    ui.horizontal(|ui| {
                        ui.label(RichText::new("Error:").color(Color32::WHITE).strong());
                        if ui.small_button("Dismiss").clicked() {
                            self.error = None;
                        }
                    });
                    let message = RichText::new(&e).color(Color32::WHITE).monospace();
                    ui.add(egui::Label::new(message).wrap_mode(egui::TextWrapMode::Wrap));
                });
        }
        let size = self
            .main
            .frame()
            .map_or(render_size(&self.scene, self.settings.resolution), |f| {
                (f.width, f.height)
            });
        let aspect = size.0 as f32 / size.1 as f32;
        let (events, image_rect) = image_ui(ui, &mut self.view, self.main.texture(), size);
        self.compare_overlay_ui(ui, image_rect);
        let ctx = ui.ctx().clone();
        let s = &self.settings;
        if self.instruments.outline_shown()
            && let Some(outline) = self.instruments.section.outline_texture(
                &ctx,
                &self.scene,
                &s.camera,
                &s.params,
                size,
            )
        {
            let whole = Rect::from_min_max(pos2(0.0, 0.0), pos2(1.0, 1.0));
            ui.painter_at(image_rect.intersect(ui.min_rect())).image(
                outline.id(),
                image_rect,
                whole,
                Color32::WHITE,
            );
        }
        if let Some(i) = &self.instruments.inspection {
            // Clipped to the image: rays leaving it stop at its edge, off the caption and
            // the status bar.
            let painter = ui.painter_at(image_rect.intersect(ui.min_rect()));
            let pointer = ui.input(|i| i.pointer.hover_pos());
            let hovered = instruments::draw_tree_overlay(
                &painter,
                image_rect,
                &i.camera.pinhole(aspect),
                &i.tree,
                self.instruments.hover,
                pointer.filter(|p| image_rect.contains(*p)),
            );
            self.instruments.hovered(hovered);
        }
        if let Some(scale) = self
            .instruments
            .show_cost
            .then(|| self.cost_scale())
            .flatten()
        {
            instruments::draw_colour_bar(&ui.painter_at(image_rect), image_rect, scale);
        }
        // Presentation mode shows the caption in a strip of its own.
        if let Some(caption) = self.caption().filter(|_| !self.hall.presenting) {
            lecture::caption_ui(ui, ui.min_rect(), &caption);
        }
        for event in events {
            match event {
                ViewEvent::Click(film) if self.instruments.click_to_focus => {
                    self.focus_on(glam::Vec2::new(film.x, film.y), aspect);
                    self.instruments.click_to_focus = false;
                }
                ViewEvent::Click(film) if self.instruments.inspect_mode => {
                    let x = ((film.x * size.0 as f32) as u32).min(size.0 - 1);
                    let y = ((film.y * size.1 as f32) as u32).min(size.1 - 1);
                    self.inspect(ui.ctx(), (x, y), size);
                    // A new pixel's section starts whole.
                    self.instruments.section.zoom_to(1.0);
                }
                ViewEvent::Click(_) => {}
                ViewEvent::Orbit(delta) => orbit(&mut self.settings.camera, delta),
                ViewEvent::Dolly(amount) => dolly(&mut self.settings.camera, amount),
            }
        }
    }

    /// Click to focus: the focus distance becomes the depth of the point at `film`.
    fn focus_on(&mut self, film: glam::Vec2, aspect: f32) {
        match pick(&self.scene, &self.settings.camera, aspect, film) {
            Some(hit) => {
                self.settings.params.focus_distance = Some(hit.depth.max(0.01));
                let name = &self.scene.object_names[hit.object as usize];
                self.toasts
                    .info(format!("Focused on {name} at {:.2}", hit.depth));
            }
            None => self.toasts.error("Nothing there to focus on"),
        }
    }
}

/// Turns the camera about its target: horizontal drag about the up axis, vertical about
/// the camera's right axis (stopping short of the poles).
pub(crate) fn orbit(camera: &mut Camera, delta: egui::Vec2) {
    let offset = camera.position - camera.look_at;
    let up = camera.up.normalize();
    let yaw = glam::Quat::from_axis_angle(up.into(), -delta.x * 0.005);
    let mut offset: crate::math::Vec3 = yaw * offset;
    let right = offset.cross(up).normalize_or_zero();
    let pitched: crate::math::Vec3 =
        glam::Quat::from_axis_angle(right.into(), delta.y * 0.005) * offset;
    if pitched.normalize().dot(up).abs() < 0.995 {
        offset = pitched;
    }
    camera.position = camera.look_at + offset;
}

/// Moves the camera towards its target (positive) or away, by a factor per wheel step.
pub(crate) fn dolly(camera: &mut Camera, amount: f32) {
    let offset = camera.position - camera.look_at;
    let scale = (-amount * 0.002).exp().clamp(0.5, 2.0);
    let new = offset * scale;
    if new.length() > 1e-3 {
        camera.position = camera.look_at + new;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixels_are_squares_only_at_whole_zooms_of_two_or_more() {
        let at = |scale| ViewState {
            scale,
            ..ViewState::default()
        };
        assert!(!at(1.0).sharp(), "1:1 needs no squares");
        assert!(!at(1.67).sharp(), "a fitted ×1.67 is filtered");
        assert!(!at(2.5).sharp());
        assert!(at(2.0).sharp() && at(3.0).sharp() && at(8.0).sharp());
    }

    #[test]
    fn orbit_keeps_the_distance_and_dolly_changes_it() {
        let mut c = Camera::looking_at(
            crate::math::Vec3::new(0.0, 1.0, 5.0),
            crate::math::Vec3::ZERO,
            crate::math::Vec3::Y,
            40.0,
        );
        let d = c.look_distance();
        orbit(&mut c, egui::vec2(120.0, -40.0));
        assert!((c.look_distance() - d).abs() < 1e-4);
        assert!(c.position.x.abs() > 0.1);
        dolly(&mut c, 100.0);
        assert!(c.look_distance() < d);
    }
}
