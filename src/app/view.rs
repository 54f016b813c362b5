//! The image in the central area: fitted to the window by default, zoomed with the wheel
//! and panned by dragging for pixel-peeping; right-drag orbits and Ctrl + wheel dollies
//! the camera; a click reports the image position.

use egui::{Color32, Pos2, Rect, Sense, Ui, Vec2, pos2, vec2};

/// How the image sits in the view.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ViewState {
    /// Screen points per image pixel; `None` fits the image to the view.
    pub zoom: Option<f32>,
    /// The image point (in pixels) at the view's centre; `None` is the image's centre.
    pub center: Option<Vec2>,
}

impl ViewState {
    /// Fit the whole image into the view.
    pub fn fit(&mut self) {
        *self = ViewState::default();
    }

    /// One image pixel per screen pixel.
    pub fn one_to_one(&mut self, pixels_per_point: f32) {
        self.zoom = Some(1.0 / pixels_per_point);
    }
}

/// What the user did to the image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ViewEvent {
    /// A click at this image position, (0, 0) top left to (1, 1) bottom right.
    Click(Vec2),
    /// A right-drag by this many points: orbit the camera.
    Orbit(Vec2),
    /// Ctrl + wheel: move the camera towards (positive) or away from its target.
    Dolly(f32),
}

/// Draws the image (`size` pixels); returns what the user did to it, and where on the
/// screen the image is (for overlays).
pub fn image_ui(
    ui: &mut Ui,
    view: &mut ViewState,
    texture: Option<&egui::TextureHandle>,
    size: (u32, u32),
) -> (Vec<ViewEvent>, Rect) {
    let area = ui.available_rect_before_wrap();
    let response = ui.allocate_rect(area, Sense::click_and_drag());
    let image = vec2(size.0 as f32, size.1 as f32);
    let fit = (area.width() / image.x)
        .min(area.height() / image.y)
        .max(1e-3);
    let zoom = view.zoom.unwrap_or(fit);
    let center = view.center.unwrap_or(image / 2.0);
    let to_screen = |p: Vec2| area.center() + (p - center) * zoom;
    let to_image = |s: Pos2| center + (s - area.center()) / zoom;
    let rect = Rect::from_min_max(to_screen(Vec2::ZERO), to_screen(image));

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
                egui::FontId::proportional(18.0),
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
