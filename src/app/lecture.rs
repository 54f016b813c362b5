//! The Lecture menu: one entry per slide, each loading its scene and parameters and showing
//! a caption that says what to look at.

use super::RaylabApp;
pub(crate) use super::slides::{LECTURE, Slide};
use crate::params::{ParamError, Params};
use crate::scene::{Scene, SceneError};
use egui::Color32;

/// Side B's parameters from side A's, in a slide that compares two things.
pub type SideB = Box<dyn Fn(&Params) -> Params>;

/// A slide set up without the window (`raylab render --slide N`).
pub struct SlideSetup {
    /// Its title.
    pub title: &'static str,
    /// Its scene.
    pub scene: Scene,
    /// The scene's parameters with the slide's on top (side A, where it compares).
    pub params: Params,
    /// Where the slide compares two things: side B's parameters from side A's.
    pub side_b: Option<SideB>,
    /// Its caption as it reads for the parameters given: it follows them, as in the
    /// window.
    pub caption: fn(&Params) -> String,
}

/// A slide that cannot be set up.
#[derive(Debug, thiserror::Error)]
pub enum SlideError {
    /// The number is not a slide's.
    #[error(
        "there is no slide {0}: the lecture's slides are 1 to {1} (`raylab lecture` lists them)"
    )]
    NoSuchSlide(usize, usize),
    /// Its scene does not load.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// Its parameters are refused.
    #[error(transparent)]
    Param(#[from] ParamError),
}

/// Slide `number` (from 1, as the Lecture menu numbers them), set up as the window shows it.
pub fn slide_setup(number: usize) -> Result<SlideSetup, SlideError> {
    let slide = number
        .checked_sub(1)
        .and_then(|i| LECTURE.get(i))
        .ok_or(SlideError::NoSuchSlide(number, LECTURE.len()))?;
    let scene = Scene::load(&slide.reference())?;
    let mut params = slide.apply(&scene.params)?;
    if let Some(kind) = &slide.compare {
        params = kind.side_a(&params);
    }
    let side_b = slide.compare.clone().map(|kind| {
        let b: SideB = Box::new(move |a| kind.side_b(a));
        b
    });
    Ok(SlideSetup {
        title: slide.title,
        scene,
        caption: slide.caption,
        params,
        side_b,
    })
}

/// The slide asked for and the caption shown.
#[derive(Default)]
pub(crate) struct Lecture {
    // Its parameters wait for its scene to load.
    pending: Option<&'static Slide>,
    // The slide shown (whose caption is shown).
    shown: Option<&'static Slide>,
    // The control sections to open once, for the slide just arrived.
    open: &'static [&'static str],
    // The slide last asked for (its number in `LECTURE`), for next and previous.
    current: Option<usize>,
}

impl Lecture {
    /// A scene arrived: the pending slide, if it is that slide's scene (its caption is
    /// shown from now on). A scene asked for before the slide (a quick Page Down twice)
    /// leaves the slide pending; any other scene takes the caption down.
    pub(crate) fn arrived(&mut self, scene: &Scene) -> Option<&'static Slide> {
        let slide = self
            .pending
            .filter(|s| scene.source.reference() == s.reference());
        self.shown = slide;
        self.open = slide.map_or(&[], |s| s.open);
        if slide.is_some() {
            self.pending = None;
        } else if self.pending.is_none() {
            // Another scene opened: no slide is shown.
            self.current = None;
        }
        slide
    }

    /// The number (in the lecture) of the slide last asked for, while it is shown.
    pub(crate) fn current(&self) -> Option<usize> {
        self.current
    }

    /// The caption shown, if any, for the parameters `params` as they are now.
    pub(crate) fn caption(&self, params: &Params) -> Option<String> {
        self.shown.map(|s| (s.caption)(params))
    }

    /// The control sections the slide just arrived opens (once).
    pub(crate) fn take_open(&mut self) -> &'static [&'static str] {
        std::mem::take(&mut self.open)
    }
}

impl RaylabApp {
    /// The Lecture menu's entries.
    pub(super) fn lecture_menu_ui(&mut self, ui: &mut egui::Ui) {
        for (i, slide) in LECTURE.iter().enumerate() {
            if ui.button(format!("{}. {}", i + 1, slide.title)).clicked() {
                self.go_to_slide(i);
                ui.close();
            }
        }
    }

    /// Opens slide `i` of the lecture: its scene, then its parameters and caption.
    pub(super) fn go_to_slide(&mut self, i: usize) {
        let slide = &LECTURE[i];
        self.lecture.pending = Some(slide);
        self.lecture.current = Some(i);
        self.open_scene(&slide.reference());
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_slide_loads_its_scene_and_applies_its_parameters() {
        for slide in LECTURE {
            let scene = Scene::load(&slide.reference())
                .unwrap_or_else(|e| panic!("slide `{}`: {e}", slide.title));
            let p = slide
                .apply(&scene.params)
                .unwrap_or_else(|e| panic!("slide `{}`: {e}", slide.title));
            for (name, value) in slide.params {
                assert_eq!(p.value_text(name).as_deref(), Some(*value), "{name}");
            }
            if let Some(kind) = &slide.compare {
                let a = kind.side_a(&p);
                assert_ne!(
                    a,
                    kind.side_b(&a),
                    "slide `{}`: its sides differ",
                    slide.title
                );
            }
        }
    }

    #[test]
    fn a_misspelt_parameter_is_an_error_not_ignored() {
        let slide = Slide {
            title: "typo",
            scene: "default",
            params: &[("max_dpeth", "2")],
            caption: |_| String::new(),
            compare: None,
            open: &[],
            plot: None,
            inspect: None,
        };
        assert!(matches!(
            slide.apply(&Params::default()),
            Err(ParamError::Unknown { .. })
        ));
    }
}
