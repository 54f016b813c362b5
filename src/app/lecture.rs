//! The Lecture menu: one entry per slide, each loading its scene and parameters and showing
//! a caption that says what to look at.

use super::RaylabApp;
use super::compare::CompareKind;
use crate::params::{ParamError, Params};
use crate::scene::{Scene, SceneError};
use egui::Color32;

/// One slide of the lecture: a scene, parameters, and what to look at.
pub(crate) struct Slide {
    /// Menu entry.
    pub title: &'static str,
    /// The built-in scene.
    pub scene: &'static str,
    /// Parameters set on top of the scene's, as `--set` would.
    pub params: &'static [(&'static str, &'static str)],
    /// The caption shown over the image.
    pub caption: &'static str,
    /// The A/B comparison the slide opens, if it compares two things.
    pub compare: Option<CompareKind>,
}

/// The lecture, slide by slide.
pub(crate) const LECTURE: &[Slide] = &[
    Slide {
        title: "Metals vs dielectrics",
        scene: "metals",
        params: &[],
        caption: "Left: dielectrics. The black glaze and the glass reflect 4% head-on and 100% only at grazing. Right: silver, gold and copper (measured η + iκ) reflect 80–97% at every angle, coloured: it depends on angle, but not much. Instruments > Fresnel plot > Compare with a metal.",
        compare: None,
    },
    Slide {
        title: "Fresnel reflection on the black glazed sphere",
        scene: "glazed",
        params: &[],
        caption: "Left: constant reflectance, 10% at every angle. Right: Fresnel, 4% head-on rising to 100% at grazing angles: the bright rim that makes it look glazed.",
        compare: None,
    },
    Slide {
        title: "Snell's law",
        scene: "glass",
        params: &[],
        caption: "n1 sin θi = n2 sin θt: the refracted rays bend towards the normal going in and away coming out, so the sphere is a lens and shows the floor upside down. Drag the IOR.",
        compare: None,
    },
    Slide {
        title: "Total internal reflection",
        scene: "tir",
        params: &[],
        caption: "Inside the prism light meets the back faces at 45°, beyond the critical angle asin(1/n) for n > 1.41: a perfect mirror. Set the IOR below 1.41 and the red wall appears.",
        compare: None,
    },
    Slide {
        title: "Pruning the ray tree",
        scene: "ray-tree",
        params: &[("max_depth", "2")],
        caption: "Every hit on glass spawns a reflected and a refracted ray. Cut at depth 2, the far spheres go dark; raise Max depth, or prune by weight instead.",
        compare: None,
    },
    Slide {
        title: "Antialiasing: 1 against 4 samples",
        scene: "antialiasing",
        params: &[("spp", "4"), ("pattern", "jittered")],
        caption: "Four jittered samples per pixel, averaged (a box filter). Set Samples per pixel to 1 and Pattern to regular to see the aliasing they remove.",
        compare: None,
    },
    Slide {
        title: "Soft shadows",
        scene: "soft-shadows",
        params: &[],
        caption: "Each sample's shadow ray goes to a different point of the area light: the penumbra. Drag Light size; at 0 the light is a point and shadows are hard.",
        compare: None,
    },
    Slide {
        title: "Glossy reflection",
        scene: "glossy",
        params: &[],
        caption: "Reflected rays jittered over a Phong lobe cos^n around the mirror direction: n = 10 to 10,000 from left to right.",
        compare: None,
    },
    Slide {
        title: "Depth of field",
        scene: "depth-of-field",
        params: &[],
        caption: "Eye rays from random points on the lens meet on the plane of focus: the blue sphere is sharp, the others blur by their circle of confusion. Try Click to focus.",
        compare: None,
    },
    Slide {
        title: "Motion blur",
        scene: "motion-blur",
        params: &[],
        caption: "Each sample has a time in the shutter interval; moving spheres smear over their travel. Set the shutter interval to 0 to freeze them.",
        compare: None,
    },
    Slide {
        title: "F_s and F_p: polarisation at Brewster's angle",
        scene: "polarization",
        // The scene's own polariser is vertical.
        params: &[],
        caption: "Reflection polarises: R_s > R_p, and at Brewster's angle (53° on water, 56° on glaze) R_p = 0, so the reflection is s only, along the surface. A vertical polariser cuts it: the glare on the pond fades and the tiles show; a dark band crosses the sphere. Polariser > Horizontal brings it back.",
        compare: None,
    },
    Slide {
        title: "Dispersion",
        scene: "dispersion",
        params: &[],
        caption: "n depends on the wavelength: n(λ) = A + B/λ² through n_d and the Abbe number. Through the flint prism the white slit spreads into its spectrum, blue bent most; the lamps seen in the diamond fringe with colour. Drag the Abbe number (0: none).",
        compare: None,
    },
    Slide {
        title: "What the ray tree misses",
        scene: "default",
        params: &[("spp", "64")],
        caption: "Left, the lecture's tracer: light comes only along shadow rays and mirror directions, so shadows get a flat ambient. Right, path tracing with photons (the reference): the blue sky lights the shadows, the glass focuses it into its own shadow, and the lamp's light through the glass lands in a bright caustic at its right foot. Drag the divider right: the lecture's tracer leaves that shadow black. Light transport > transmissive shadows is the common fix: tinted, but not focused.",
        compare: Some(CompareKind::WhittedPhotons),
    },
];

impl Slide {
    /// The built-in scene's reference.
    fn reference(&self) -> String {
        format!("builtin:{}", self.scene)
    }

    /// `base` with the slide's parameters set on top, through the checked path: a name or
    /// value that `--set` would refuse is an error here too.
    pub(crate) fn apply(&self, base: &Params) -> Result<Params, ParamError> {
        let mut p = base.clone();
        for (name, value) in self.params {
            p.set(name, value)?;
        }
        Ok(p)
    }
}

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
    /// Its caption.
    pub caption: &'static str,
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
        params,
        side_b,
        caption: slide.caption,
    })
}

/// The slide asked for and the caption shown.
#[derive(Default)]
pub(crate) struct Lecture {
    // Its parameters wait for its scene to load.
    pending: Option<&'static Slide>,
    caption: Option<&'static str>,
    // The slide last asked for (its number in `LECTURE`), for next and previous.
    current: Option<usize>,
}

impl Lecture {
    /// A scene arrived: the pending slide, if it is that slide's scene (its caption is
    /// shown from now on); any other scene takes the caption down.
    pub(crate) fn arrived(&mut self, scene: &Scene) -> Option<&'static Slide> {
        let slide = self
            .pending
            .take()
            .filter(|s| scene.source.reference() == s.reference());
        self.caption = slide.map(|s| s.caption);
        if slide.is_none() {
            // Another scene opened: no slide is shown.
            self.current = None;
        }
        slide
    }

    /// The number (in the lecture) of the slide last asked for, while it is shown.
    pub(crate) fn current(&self) -> Option<usize> {
        self.current
    }

    /// The caption shown, if any.
    pub(crate) fn caption(&self) -> Option<&'static str> {
        self.caption
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
            caption: "",
            compare: None,
        };
        assert!(matches!(
            slide.apply(&Params::default()),
            Err(ParamError::Unknown { .. })
        ));
    }
}
