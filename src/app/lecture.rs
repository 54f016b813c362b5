//! The Lecture menu: one entry per slide of [`crate::lecture::LECTURE`], each loading its
//! scene and parameters, opening what the slide opens and showing its caption.

use super::RaylabApp;
use super::command::Command;
use super::instruments::SectionMode;
use crate::lecture::{Instrument, LECTURE, Shown, Slide};
use crate::render::Prerender;
use crate::scene::Scene;
use egui::Color32;

/// The slide asked for and the caption shown.
#[derive(Default)]
pub(crate) struct Lecture {
    // Its parameters wait for its scene to load.
    pending: Option<&'static Slide>,
    // The slide shown (whose caption is shown).
    shown: Option<&'static Slide>,
    // The parameters whose controls to show once, for the slide just arrived.
    open: &'static [&'static str],
    // The slide last asked for (its number in `LECTURE`), for next and previous.
    current: Option<usize>,
    // The slide (and image size) whose neighbours are being rendered ahead, and their
    // images.
    ahead: Option<(usize, (u32, u32))>,
    ahead_jobs: Vec<Prerender>,
}

impl Lecture {
    /// A scene arrived: the pending slide, if it is that slide's scene (its caption is
    /// shown from now on). A scene asked for before the slide (a quick Page Down twice)
    /// leaves the slide pending; any other scene takes the caption down.
    pub(crate) fn arrived(&mut self, scene: &Scene) -> Option<&'static Slide> {
        let slide = self.pending_for(scene);
        self.shown = slide;
        self.open = slide.map_or(&[], |s| s.controls);
        if slide.is_some() {
            self.pending = None;
        } else if self.pending.is_none() {
            // Another scene opened: no slide is shown.
            self.current = None;
        }
        slide
    }

    /// The slide pending, if `scene` is its scene.
    pub(crate) fn pending_for(&self, scene: &Scene) -> Option<&'static Slide> {
        self.pending
            .filter(|s| scene.source.reference() == s.reference())
    }

    /// The number (in the lecture) of the slide last asked for, while it is shown.
    pub(crate) fn current(&self) -> Option<usize> {
        self.current
    }

    /// The slide shown, if any.
    pub(crate) fn shown(&self) -> Option<&'static Slide> {
        self.shown
    }

    /// The caption shown, if any, for what is shown now.
    pub(crate) fn caption(&self, shown: &Shown) -> Option<String> {
        self.shown.map(|s| s.caption(shown))
    }

    /// The parameters whose controls the slide just arrived asks for (once).
    pub(crate) fn take_open(&mut self) -> &'static [&'static str] {
        std::mem::take(&mut self.open)
    }
}

impl RaylabApp {
    /// The Lecture menu's entries.
    pub(super) fn lecture_menu_ui(&mut self, ui: &mut egui::Ui) {
        for (i, slide) in LECTURE.iter().enumerate() {
            if ui.button(format!("{}. {}", i + 1, slide.title)).clicked() {
                self.ask(ui.ctx(), Command::GoToSlide(i));
                ui.close();
            }
        }
    }

    /// Once the slide shown is finished on every side: its neighbours (the next first,
    /// then the previous), each of their sides, rendered ahead by the idle workers at the
    /// size the window would show them, so that Page Down and Page Up show finished
    /// images at once.
    pub(super) fn render_ahead(&mut self) {
        let (Some(i), Some(_)) = (self.lecture.current, self.lecture.shown) else {
            return;
        };
        let size = super::render_size(&self.scene, self.settings.resolution);
        if self.lecture.ahead == Some((i, size)) || !self.all_sides().all(|(_, s)| s.settled()) {
            return;
        }
        self.lecture.ahead = Some((i, size));
        let neighbours = [i + 1, i.wrapping_sub(1)];
        let jobs: Vec<Prerender> = neighbours
            .iter()
            .filter_map(|&j| LECTURE.get(j))
            .flat_map(|slide| self.sides_of(slide))
            .collect();
        self.main
            .engine()
            .prerender(self.main.cache(), jobs.clone());
        self.lecture.ahead_jobs = jobs;
    }

    /// The newest generation the main view's engine was asked for: its frames of older
    /// ones are stale.
    pub fn generation(&self) -> u64 {
        self.main.engine().generation()
    }

    /// Whether the neighbours of the slide shown are rendered ahead, finished.
    pub fn neighbours_ready(&self) -> bool {
        self.lecture.ahead.is_some()
            && self
                .lecture
                .ahead_jobs
                .iter()
                .all(|job| self.main.cache().ready(job))
    }

    /// Every side of `slide` as the window would render it: its scene through its own
    /// camera, each side's parameters, at the window's resolution.
    fn sides_of(&self, slide: &Slide) -> Vec<Prerender> {
        let Ok(scene) = Scene::load(slide.reference()) else {
            return Vec::new();
        };
        let Ok(a) = slide.params_on(&scene.params) else {
            return Vec::new();
        };
        let size = super::render_size(&scene, self.settings.resolution);
        let scene = std::sync::Arc::new(scene);
        let mut sides = vec![a.clone()];
        sides.extend(slide.others(&a));
        sides
            .into_iter()
            .map(|params| Prerender {
                scene: std::sync::Arc::clone(&scene),
                camera: scene.camera.clone(),
                params,
                size,
            })
            .collect()
    }

    /// Opens slide `i` of the lecture: its scene, then its parameters and caption.
    pub(super) fn go_to_slide(&mut self, i: usize) {
        let Some(slide) = LECTURE.get(i) else {
            return;
        };
        log::info!("slide {}: {}", i + 1, slide.title);
        self.lecture.pending = Some(slide);
        self.lecture.current = Some(i);
        // The last slide's neighbours are not this one's: their work is dropped (what they
        // have is kept in the cache) until this slide is finished and asks for its own.
        self.lecture.ahead = None;
        self.lecture.ahead_jobs.clear();
        self.main.engine().prerender(self.main.cache(), Vec::new());
        self.open_scene(slide.reference());
    }

    /// `slide`'s scene has arrived (with the slide's parameters, `arrival.rs`): the
    /// slide's own instruments replace those open (none, if it has none).
    pub(super) fn arrive_at_slide(&mut self, slide: &Slide) {
        self.leave_slide();
        let fresnel_metal = slide.instruments.iter().find_map(|i| match i {
            Instrument::FresnelPlot { metal } => Some(*metal),
            _ => None,
        });
        let i = &mut self.instruments;
        i.show_fresnel = fresnel_metal.is_some();
        i.fresnel_metal = fresnel_metal
            .flatten()
            .and_then(|name| crate::material::METALS.iter().position(|m| m.name == name));
        for instrument in slide.instruments {
            match *instrument {
                Instrument::Section { zoom, .. } => {
                    i.show_section = true;
                    i.section.mode = SectionMode::Pixel;
                    i.section.zoom_to(zoom);
                }
                Instrument::Workbench { angle, out } => {
                    i.show_section = true;
                    i.section.mode = SectionMode::Workbench;
                    i.section.outline = true;
                    i.section.angle = angle;
                    i.section.out = out;
                }
                Instrument::FresnelPlot { .. } | Instrument::RayTree { .. } => {}
            }
        }
    }

    /// Clears whatever a slide can show: its A/B view, its instruments (the Fresnel plot,
    /// the section view or workbench and the workbench's outline of the image), the
    /// inspected pixel and clicks that inspect. The next slide sets what it shows itself;
    /// a scene that is no slide starts without them.
    pub(super) fn leave_slide(&mut self) {
        self.compare = None;
        let i = &mut self.instruments;
        i.show_fresnel = false;
        i.fresnel_metal = None;
        i.show_section = false;
        // The workbench's outline is drawn while the workbench is the section's mode.
        i.section.mode = SectionMode::Pixel;
        i.hall_tab = None;
        i.inspect_mode = false;
        i.forget_inspection();
    }

    /// Once `slide`'s scene is shown: the pixel its inspector shows.
    pub(super) fn show_slide(&mut self, slide: &Slide, ctx: &egui::Context) {
        // A slide about the ray tree opens the inspector on its pixel; the others leave
        // clicks on the image to the view.
        let size = super::render_size(&self.scene, self.settings.resolution);
        let pixel = slide.inspected_pixel(size);
        self.instruments.inspect_mode = pixel.is_some();
        if let Some(pixel) = pixel {
            self.inspect(ctx, pixel, size);
        }
    }
}

/// The caption, on a dark plate along the bottom of `area`.
pub(crate) fn caption_ui(ui: &egui::Ui, area: egui::Rect, caption: &str) {
    let galley = ui.painter().layout(
        caption.to_string(),
        egui::FontId::proportional(16.0),
        Color32::WHITE,
        area.width() - 40.0,
    );
    let pos = egui::pos2(area.min.x + 20.0, area.max.y - galley.size().y - 20.0);
    let back = egui::Rect::from_min_size(pos, galley.size()).expand(8.0);
    ui.painter()
        .rect_filled(back, 4.0, Color32::from_black_alpha(180));
    ui.painter().galley(pos, galley, Color32::WHITE);
}
