//! The lecture hall: presentation mode (the image alone, fullscreen, the slide's caption
//! large under it, the keys a presentation clicker sends to step through the slides), the
//! UI scale with a projector preset, and the help overlay listing every shortcut.

use super::RaylabApp;
use super::command::{COMMANDS, Command, EGUI_KEYS};
use super::widgets::Controls;
use super::widgets::{param_ui, step_param};
use crate::lecture::LECTURE;
use egui::{Color32, RichText};

/// Every keyboard shortcut, as the help overlay lists it: the keys, and what they do
/// (the commands' table, and the keys egui answers itself).
pub(crate) fn shortcuts() -> impl Iterator<Item = (&'static str, &'static str)> {
    COMMANDS
        .iter()
        .filter(|c| !c.keys_text.is_empty())
        .map(|c| (c.keys_text, c.what))
        .chain(EGUI_KEYS.iter().copied())
}

/// How long a window may take to become fullscreen or leave it.
const SETTLE: std::time::Duration = std::time::Duration::from_millis(1500);

/// UI scales offered in the View menu: a name and egui's zoom factor.
pub(crate) const UI_SCALES: &[(&str, f32)] = &[
    ("laptop (100 %)", 1.0),
    ("desk (125 %)", 1.25),
    ("projector (175 %)", 1.75),
    ("hall (225 %)", 2.25),
];

/// The caption's text height in presentation mode, for an image area `height` points
/// tall: a line is 1/26 of the screen, about 41 px at 1080p and 28 px at 720p, readable
/// from the back of a hall (never under 20).
pub(crate) fn caption_size(height: f32) -> f32 {
    (height / 26.0).max(20.0)
}

/// A style whose every text is `size` points (and whose sliders, boxes and spacing grow
/// with it), for what presentation mode shows a hall.
pub(crate) fn hall_style(style: &mut egui::Style, size: f32) {
    for font in style.text_styles.values_mut() {
        font.size = size;
    }
    let s = &mut style.spacing;
    s.interact_size = egui::vec2(size * 2.0, size * 1.3);
    s.slider_width = size * 8.0;
    s.icon_width = size * 0.9;
    s.icon_width_inner = size * 0.5;
    s.icon_spacing = size * 0.3;
    s.item_spacing = egui::vec2(size * 0.4, size * 0.25);
    s.button_padding = egui::vec2(size * 0.3, size * 0.1);
    // Labels as bright as the caption's text: grey is lost on a projector.
    style.visuals.override_text_color = Some(Color32::from_gray(235));
    // No tooltips: the caption explains, and a tooltip left where a slider was released
    // covers the title and image for as long as the mouse rests. (egui waits this long
    // for the mouse to be still; an infinite wait asks for no repaint.)
    style.interaction.tooltip_delay = f32::INFINITY;
    style.interaction.tooltip_grace_time = 0.0;
}

/// What the hall adds to the window's state.
#[derive(Debug, Default)]
pub(crate) struct Hall {
    /// Presentation mode is on.
    pub presenting: bool,
    /// The help overlay is open.
    pub help: bool,
    /// The window's style before presentation mode made every text the caption's size.
    desk_style: Option<std::sync::Arc<egui::Style>>,
    /// The text size presentation mode last set (the style is set again only when the
    /// screen's height changes it: egui lays a frame out again after a change of style).
    hall_size: f32,
    /// Until when to keep drawing after entering or leaving fullscreen: the window's new
    /// size can arrive after the frame drawn for it, which then stayed on screen (the
    /// toolbar gone, half the window black) until the next repaint.
    settle_until: Option<std::time::Instant>,
    /// The strip's height as last drawn: a change is laid out again at once.
    strip_height: f32,
}

/// The slide's controls side by side, `gap` apart, each with its parts (slider, readout,
/// name, presets) kept in one row: a control that would not fit in what is left of a row
/// starts the next. egui places a row's parts as they come and cannot know a group's width
/// before laying it out ("Aperture" ran off the screen's edge, and the caption under it
/// widened with it), so each is first laid out unseen to measure it. One wider than the
/// whole strip lets its parts wrap.
fn controls_row_ui(ui: &mut egui::Ui, c: &mut Controls, controls: &[&'static str], gap: f32) {
    ui.horizontal_wrapped(|ui| {
        let row = ui.available_width();
        for (i, &name) in controls.iter().enumerate() {
            let unseen = egui::UiBuilder::new()
                .id_salt(("measured", name))
                .sizing_pass()
                .invisible();
            let width = ui
                .new_child(unseen)
                .horizontal(|ui| param_ui(ui, c, name))
                .response
                .rect
                .width();
            if width > row {
                if i > 0 {
                    ui.end_row();
                }
                param_ui(ui, c, name);
                ui.end_row();
                continue;
            }
            if i > 0 && width > ui.available_size_before_wrap().x {
                ui.end_row();
            }
            ui.horizontal(|ui| param_ui(ui, c, name));
            ui.add_space(gap);
        }
    });
}

impl RaylabApp {
    /// Enters or leaves presentation mode (fullscreen, panels hidden, image fitted).
    pub(super) fn set_presenting(&mut self, ctx: &egui::Context, on: bool) {
        if on && !self.hall.presenting {
            self.hall.desk_style = Some(ctx.global_style());
        }
        if !on && let Some(style) = self.hall.desk_style.take() {
            ctx.set_global_style(style);
            self.hall.hall_size = 0.0;
        }
        self.hall.presenting = on;
        ctx.send_viewport_cmd(egui::ViewportCommand::Fullscreen(on));
        self.hall.settle_until = Some(std::time::Instant::now() + SETTLE);
        self.view.fit();
    }

    /// While the window settles into or out of fullscreen, a frame every 50 ms: the last
    /// one is laid out for the size it ends at.
    pub(super) fn settle_ui(&mut self, ctx: &egui::Context) {
        match self.hall.settle_until {
            Some(t) if std::time::Instant::now() < t => {
                ctx.request_repaint_after(std::time::Duration::from_millis(50));
            }
            Some(_) => self.hall.settle_until = None,
            None => {}
        }
    }

    /// In presentation mode, every text the caption's size for the screen as it is now:
    /// the instruments, the A/B labels, the toasts, the help. Called before anything is
    /// drawn.
    pub(super) fn hall_style_ui(&mut self, ctx: &egui::Context) {
        let size = caption_size(ctx.content_rect().height());
        if let (true, Some(desk)) = (self.hall.presenting, &self.hall.desk_style)
            && (size - self.hall.hall_size).abs() > 0.01
        {
            let mut style = (**desk).clone();
            hall_style(&mut style, size);
            ctx.set_global_style(style);
            self.hall.hall_size = size;
        }
    }

    /// The slide `by` away from the one shown (the first, with none shown yet), within
    /// the lecture.
    pub(super) fn step_slide(&mut self, by: i32) {
        let next = match self.lecture.current() {
            Some(i) => (i as i32 + by).clamp(0, LECTURE.len() as i32 - 1) as usize,
            None => 0,
        };
        if Some(next) != self.lecture.current() {
            self.go_to_slide(next);
        }
    }

    /// The controls the shown slide asks for, as the side panel has them.
    fn with_slide_controls(&mut self, f: impl FnOnce(&mut Controls, &'static [&'static str])) {
        let Some(slide) = self.lecture.shown() else {
            return;
        };
        self.with_controls(&[], |c| f(c, slide.controls));
    }

    /// `]` and `[`: the slide's first control one notch up or down.
    pub(super) fn step_first_control(&mut self, up: bool) {
        self.with_slide_controls(|c, controls| {
            if let Some(name) = controls.first() {
                step_param(c, name, up);
            }
        });
    }

    /// Presentation mode's view: along the bottom a strip of its own (so it covers
    /// nothing) with the slide's number and title, its progress, the controls its caption
    /// asks for and the caption, all at the caption's size; the image above, the
    /// instruments' dock beside it.
    pub(super) fn presentation_ui(&mut self, ui: &mut egui::Ui) {
        let size = caption_size(ui.ctx().content_rect().height());
        // The slide shown (arrived), as its caption: not the one asked for, whose scene
        // may still be loading.
        let title = self.lecture.shown().and_then(|shown| {
            let i = LECTURE.iter().position(|s| std::ptr::eq(s, shown))?;
            Some(format!("{} / {}  {}", i + 1, LECTURE.len(), shown.title))
        });
        let caption = self.caption();
        let controls = self.lecture.shown().map_or(&[][..], |s| s.controls);
        let progress = self.progress_text();
        // Exactly as tall as its words were in the last pass: a panel keeps its height
        // until told, and grows down off the screen (a new slide's longer caption ran off
        // its bottom for a frame, a shorter one left a black band).
        const MARGIN: f32 = 16.0;
        let mut strip = egui::Panel::bottom("caption")
            .frame(egui::Frame::new().fill(Color32::BLACK).inner_margin(MARGIN))
            .resizable(false)
            .show_separator_line(false);
        if self.hall.strip_height > 0.0 {
            strip = strip.exact_size(self.hall.strip_height);
        }
        let words = strip
            .show(ui, |ui| {
                let top = ui.cursor().top();
                ui.horizontal(|ui| {
                    if let Some(title) = title {
                        ui.label(
                            RichText::new(title)
                                .size(size)
                                .color(Color32::WHITE)
                                .strong(),
                        );
                    }
                    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                        ui.label(RichText::new(progress).size(size).color(Color32::GRAY));
                    });
                });
                self.progress_bar_ui(ui, size);
                if !controls.is_empty() {
                    // Each control's parts in a row (its slider, presets, readout), the
                    // controls side by side: the image keeps the height.
                    self.with_controls(&[], |c| controls_row_ui(ui, c, controls, size));
                }
                let text =
                    caption.unwrap_or_else(|| "Page Down: the first slide. Esc: leave.".into());
                let last = ui.label(RichText::new(text).size(size).color(Color32::WHITE));
                last.rect.bottom() - top
            })
            .inner;
        // Words of another height are laid out again at once, in a strip of theirs.
        let height = words + 2.0 * MARGIN;
        if (height - self.hall.strip_height).abs() > 0.5 {
            self.hall.strip_height = height;
            ui.ctx().request_discard("the strip's height changed");
        }
        // The instruments above the strip, beside the image: the caption keeps the
        // screen's whole width.
        self.instruments_dock_ui(ui);
        egui::CentralPanel::default()
            .frame(egui::Frame::new().fill(Color32::BLACK))
            .show(ui, |ui| self.image_panel_ui(ui));
    }

    /// How far the image has refined, as presentation mode says it: samples per pixel of
    /// the target (each side's in an A/B view: "A 1 / 1 · B 37 / 256 spp"), and "paused"
    /// while paused.
    fn progress_text(&self) -> String {
        let comparing = self.compare.is_some();
        let sides: Vec<String> = self
            .all_sides()
            .filter_map(|(letter, side)| {
                let done = side.frame()?.progress.of_target();
                Some(if comparing {
                    format!("{letter} {done}")
                } else {
                    done
                })
            })
            .collect();
        if sides.is_empty() {
            return "starting".into();
        }
        let spp = format!("{} spp", sides.join(" · "));
        if self.main.paused() {
            format!("paused, {spp}")
        } else {
            spp
        }
    }

    /// A thin bar across the strip: the fraction of the target done, of the side least
    /// done.
    fn progress_bar_ui(&self, ui: &mut egui::Ui, size: f32) {
        let fraction = self.progress_fraction();
        let (rect, _) = ui.allocate_exact_size(
            egui::vec2(ui.available_width(), (size / 8.0).max(3.0)),
            egui::Sense::hover(),
        );
        let painter = ui.painter();
        painter.rect_filled(rect, 0.0, Color32::from_gray(40));
        let done =
            egui::Rect::from_min_size(rect.min, egui::vec2(rect.width() * fraction, rect.height()));
        painter.rect_filled(done, 0.0, Color32::from_rgb(70, 130, 220));
    }

    /// The help overlay: every shortcut, centred over the window.
    pub(super) fn help_ui(&mut self, ctx: &egui::Context) {
        if !self.hall.help {
            return;
        }
        let mut open = true;
        egui::Window::new("Keyboard shortcuts")
            .open(&mut open)
            .collapsible(false)
            .resizable(false)
            .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
            .show(ctx, |ui| {
                egui::Grid::new("shortcuts")
                    .num_columns(2)
                    .spacing([24.0, 6.0])
                    .show(ui, |ui| {
                        for (keys, what) in shortcuts() {
                            ui.label(RichText::new(keys).strong());
                            ui.label(what);
                            ui.end_row();
                        }
                    });
            });
        self.hall.help &= open;
    }

    /// The View menu: presentation mode, calm noise, the UI scale, streaming to tev, help.
    pub(super) fn view_menu_ui(&mut self, ui: &mut egui::Ui) {
        for command in [Command::Present, Command::Fit, Command::OneToOne] {
            self.command_item(ui, command);
        }
        ui.checkbox(&mut self.settings.calm, "Calm noise while refining")
            .on_hover_text(
                "Until the image is clean, show it with its noise smoothed along each surface \
                 (edges kept): drags on soft shadows, depth of field and dispersion look \
                 calm. Off: the raw samples. Snapshots, tev and the readouts are raw either way.",
            );
        ui.separator();
        ui.label("UI scale");
        let zoom = ui.ctx().zoom_factor();
        for (name, scale) in UI_SCALES {
            if ui
                .radio((zoom - scale).abs() < 0.01, *name)
                .on_hover_text(
                    "Text and controls this much larger (remembered). Ctrl+= and Ctrl+- step it.",
                )
                .clicked()
            {
                ui.ctx().set_zoom_factor(*scale);
            }
        }
        ui.separator();
        self.tev_menu_ui(ui);
        ui.separator();
        self.command_item(ui, Command::Help);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_docs_list_every_shortcut_as_the_help_does() {
        let docs = include_str!("../../docs/window.md");
        for (keys, what) in shortcuts() {
            assert!(
                docs.contains(&format!("| {keys} | {what} |")),
                "docs/window.md's key table lacks `| {keys} | {what} |`"
            );
        }
    }

    #[test]
    fn the_caption_is_legible_in_a_hall() {
        // 1/26 of the screen: 41.5 px at 1080p, 27.7 at 720p, never under 20.
        assert!((caption_size(1080.0) - 41.54).abs() < 0.01);
        assert!((caption_size(720.0) - 27.69).abs() < 0.01);
        assert_eq!(caption_size(300.0), 20.0);
    }
}
