//! The first window fits the screen it opens on: a 1280×720 window and its title bar are
//! taller than a 720p laptop's screen, which would cut off the status bar.

use super::RaylabApp;
use egui::Vec2;

/// Room left for a taskbar or dock beside the window, in points.
const TASKBAR: f32 = 48.0;

/// The inner size that makes a window of `outer` size (title bar and borders included)
/// with `inner` content fit a `monitor`, leaving room for a taskbar; `None` if it fits.
pub(crate) fn fitting_inner_size(monitor: Vec2, outer: Vec2, inner: Vec2) -> Option<Vec2> {
    let frame = (outer - inner).max(Vec2::ZERO);
    let room = (monitor - frame - Vec2::new(0.0, TASKBAR)).max(Vec2::new(320.0, 240.0));
    let fitted = inner.min(room);
    (fitted != inner).then_some(fitted)
}

impl RaylabApp {
    /// Once the window's size and its monitor's are known: shrinks a window that does not
    /// fit (maximized or fullscreen windows fit by definition).
    pub(super) fn fit_to_screen(&mut self, ctx: &egui::Context) {
        if self.fitted {
            return;
        }
        let info = ctx.input(|i| i.viewport().clone());
        let (Some(monitor), Some(outer), Some(inner)) = (
            info.monitor_size,
            info.outer_rect.map(|r| r.size()),
            info.inner_rect.map(|r| r.size()),
        ) else {
            return;
        };
        self.fitted = true;
        if info.maximized == Some(true) || info.fullscreen == Some(true) {
            return;
        }
        if let Some(size) = fitting_inner_size(monitor, outer, inner) {
            ctx.send_viewport_cmd(egui::ViewportCommand::InnerSize(size));
            ctx.send_viewport_cmd(egui::ViewportCommand::OuterPosition(egui::pos2(0.0, 0.0)));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_window_taller_than_a_720p_screen_is_made_to_fit_and_one_that_fits_stays() {
        // 1280×720 content under a 30-point title bar, on a 1280×720 screen.
        let v = Vec2::new;
        let fitted = fitting_inner_size(v(1280.0, 720.0), v(1280.0, 750.0), v(1280.0, 720.0));
        assert_eq!(fitted, Some(v(1280.0, 720.0 - 30.0 - TASKBAR)));
        // On a 1080p screen it fits as it is.
        assert_eq!(
            fitting_inner_size(v(1920.0, 1080.0), v(1280.0, 750.0), v(1280.0, 720.0)),
            None
        );
        // Never smaller than a usable window.
        let tiny = fitting_inner_size(v(300.0, 200.0), v(1280.0, 750.0), v(1280.0, 720.0));
        assert_eq!(tiny, Some(v(320.0, 240.0)));
    }
}
