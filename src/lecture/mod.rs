//! The lecture, slide by slide, as data: each slide a built-in scene, the parameters set on
//! top of the scene's, what the two sides of its A/B view differ in, the instrument it
//! opens, the controls its caption asks the lecturer to change, and the caption itself as a
//! function of the parameters (so it follows what the lecturer changes).
//!
//! The window (its Lecture menu and presentation mode) and the command line
//! (`raylab lecture`, `raylab render --slide N`) both read [`LECTURE`]; this module knows
//! no egui.

mod captions;
mod compare;
mod slides;

pub use compare::Comparison;
pub use slides::LECTURE;

use crate::camera::Camera;
use crate::params::{ParamError, Params};
use crate::scene::{Scene, SceneError};

/// An instrument a slide opens beside the image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Instrument {
    /// The Fresnel plot: the dielectric's reflectance against the angle, compared with a
    /// measured metal's (by its name in [`crate::material::METALS`]) if one is given.
    FresnelPlot {
        /// The metal to compare with.
        metal: Option<&'static str>,
    },
    /// The ray-tree inspector on one pixel, given as a fraction of the image's width and
    /// height.
    RayTree {
        /// Across, 0 to 1.
        x: f32,
        /// Down, 0 to 1.
        y: f32,
    },
    /// The inspector and the section view on one pixel (as for [`Instrument::RayTree`]):
    /// its ray tree drawn in its own plane, with the angles at each interface.
    Section {
        /// Across, 0 to 1.
        x: f32,
        /// Down, 0 to 1.
        y: f32,
        /// How far the section is zoomed in on the first hit (1: the whole tree).
        zoom: f32,
    },
    /// The interface workbench: one flat interface between the scene's medium and the
    /// IOR, one ray at `angle` degrees.
    Workbench {
        /// The angle of incidence, degrees.
        angle: f32,
        /// Seen from inside: from the material out to the medium.
        out: bool,
    },
}

impl Instrument {
    /// What a slide's notes say it opens.
    fn describe(&self) -> String {
        match self {
            Instrument::FresnelPlot { metal: None } => "the Fresnel plot".into(),
            Instrument::FresnelPlot { metal: Some(m) } => format!("the Fresnel plot with {m}"),
            Instrument::RayTree { .. } => "the ray-tree inspector on a pixel".into(),
            Instrument::Section { .. } => "the section view of a pixel's ray tree".into(),
            Instrument::Workbench { angle, out } => format!(
                "the interface workbench at {angle}°{}",
                if *out { ", from inside" } else { "" }
            ),
        }
    }

    /// The pixel it inspects, as fractions of the image's width and height.
    fn pixel(&self) -> Option<(f32, f32)> {
        match *self {
            Instrument::RayTree { x, y } | Instrument::Section { x, y, .. } => Some((x, y)),
            Instrument::FresnelPlot { .. } | Instrument::Workbench { .. } => None,
        }
    }
}

/// What a caption reads: what is shown as it is now.
#[derive(Clone, Copy)]
pub struct Shown<'a> {
    /// The parameters.
    pub params: &'a Params,
    /// The scene.
    pub scene: &'a Scene,
    /// The camera (the user may have moved it).
    pub camera: &'a Camera,
    /// The object the inspected pixel's camera ray meets first (`Some(None)`: nothing);
    /// `None` while no pixel is inspected.
    pub inspected: Option<Option<u32>>,
}

/// A slide's caption.
#[derive(Clone, Copy)]
pub enum Caption {
    /// The same text whatever is shown.
    Fixed(&'static str),
    /// Text that follows what is shown: the parameters, the focus, the inspected pixel.
    Follows(fn(&Shown) -> String),
}

/// The noise target of a slide's adaptive sampling, in percent: a quarter under the
/// clean mark ([`crate::render::CLEAN_NOISE`], 2 %), as the noise the status bar estimates
/// ends near the target, a little over or under it.
pub const SLIDE_NOISE_TARGET: f32 = 1.5;

/// One slide of the lecture.
#[derive(Clone, Copy)]
pub struct Slide {
    /// Its title, in the Lecture menu and over the slide.
    pub title: &'static str,
    /// Its built-in scene.
    pub scene: &'static str,
    /// Parameters set on top of the scene's, by name, as `--set` takes them. The slide's
    /// `spp` is its most samples: enough for the status bar's noise under 2 %
    /// (tests/slides.rs), with adaptive sampling stopping each pixel once it is there,
    /// except where the slide is about the noise of few samples.
    pub params: &'static [(&'static str, &'static str)],
    /// What the sides of its A/B view differ in, if it compares things.
    pub compare: Option<Comparison>,
    /// Where the A/B view's divider starts between two sides, across the image (0: all
    /// B, 1: all A); three sides start evenly spaced ([`Comparison::dividers`]).
    pub divider: f32,
    /// The instruments it opens.
    pub instruments: &'static [Instrument],
    /// The parameters its caption asks the lecturer to change: the window shows their
    /// controls.
    pub controls: &'static [&'static str],
    /// What to look at.
    pub caption: Caption,
    /// Whether adaptive sampling stops each pixel once it is clean (its `noise_target` at
    /// [`SLIDE_NOISE_TARGET`]): on, but where the slide teaches the noise of few samples
    /// ([`Slide::uniform`]).
    pub adaptive: bool,
}

/// A slide of `title` on the built-in scene `scene`, the rest set by the builder methods
/// below; every slide says something ([`Slide::says`] or [`Slide::follows`]).
pub const fn slide(title: &'static str, scene: &'static str) -> Slide {
    Slide {
        title,
        scene,
        params: &[],
        compare: None,
        divider: 0.5,
        instruments: &[],
        controls: &[],
        caption: Caption::Fixed(""),
        adaptive: true,
    }
}

impl Slide {
    /// With these parameters set on top of the scene's.
    pub const fn set(self, params: &'static [(&'static str, &'static str)]) -> Slide {
        Slide { params, ..self }
    }

    /// Comparing images that differ as `compare` says.
    pub const fn compare(self, compare: Comparison) -> Slide {
        Slide {
            compare: Some(compare),
            ..self
        }
    }

    /// With the A/B view's divider first at `divider` across the image.
    pub const fn divider(self, divider: f32) -> Slide {
        Slide { divider, ..self }
    }

    /// Opening `instruments`.
    pub const fn open(self, instruments: &'static [Instrument]) -> Slide {
        Slide {
            instruments,
            ..self
        }
    }

    /// Asking the lecturer to change these parameters.
    pub const fn asks(self, controls: &'static [&'static str]) -> Slide {
        Slide { controls, ..self }
    }

    /// Teaching the noise of few samples: every pixel gets every sample, so raising the
    /// samples shows the noise falling everywhere alike.
    pub const fn uniform(self) -> Slide {
        Slide {
            adaptive: false,
            ..self
        }
    }

    /// With this caption.
    pub const fn says(self, caption: &'static str) -> Slide {
        Slide {
            caption: Caption::Fixed(caption),
            ..self
        }
    }

    /// With a caption that follows what is shown.
    pub const fn follows(self, caption: fn(&Shown) -> String) -> Slide {
        Slide {
            caption: Caption::Follows(caption),
            ..self
        }
    }

    /// The built-in scene's reference.
    pub fn reference(&self) -> String {
        format!("builtin:{}", self.scene)
    }

    /// Its caption for what is shown.
    pub fn caption(&self, shown: &Shown) -> String {
        match self.caption {
            Caption::Fixed(text) => text.to_string(),
            Caption::Follows(f) => f(shown),
        }
    }

    /// What the inspected pixel's ray meets first on an image of `size`, where the slide
    /// opens the inspector on a pixel (`None` if it does not): as the window shows it.
    pub fn inspected(
        &self,
        scene: &Scene,
        camera: &Camera,
        size: (u32, u32),
    ) -> Option<Option<u32>> {
        let (x, y) = self.inspected_pixel(size)?;
        let film = glam::Vec2::new(
            (x as f32 + 0.5) / size.0 as f32,
            (y as f32 + 0.5) / size.1 as f32,
        );
        let aspect = size.0 as f32 / size.1 as f32;
        Some(crate::tracer::pick(scene, camera, aspect, film).map(|p| p.object))
    }

    /// The pixel the slide's inspector opens on, in an image of `size`.
    pub fn inspected_pixel(&self, size: (u32, u32)) -> Option<(u32, u32)> {
        let (x, y) = self.instruments.iter().find_map(Instrument::pixel)?;
        let at = |f: f32, n: u32| ((f * n as f32) as u32).min(n.max(1) - 1);
        Some((at(x, size.0), at(y, size.1)))
    }

    /// The parameters the slide shows on a scene whose own are `base`: the slide's set on
    /// top through the checked path (a name or value `--set` would refuse is an error here
    /// too), then side A's of its comparison.
    pub fn params_on(&self, base: &Params) -> Result<Params, ParamError> {
        let p = self.set_on(base)?;
        Ok(match self.compare {
            Some(c) => c.side_a(&p),
            None => p,
        })
    }

    /// `base` with the slide's parameters set on top.
    fn set_on(&self, base: &Params) -> Result<Params, ParamError> {
        let mut p = base.clone();
        if self.adaptive {
            p.noise_target = Some(SLIDE_NOISE_TARGET);
        }
        for (name, value) in self.params {
            p.set(name, value)?;
        }
        Ok(p)
    }

    /// The parameters of the sides after A (B, and C), given side A's: none where the
    /// slide compares nothing.
    pub fn others(&self, a: &Params) -> Vec<Params> {
        self.compare.map_or_else(Vec::new, |c| c.others(a))
    }

    /// Where its A/B view's dividers start, across the image: none where it compares
    /// nothing.
    pub fn dividers(&self) -> Vec<f32> {
        self.compare
            .map_or_else(Vec::new, |c| c.dividers(self.divider))
    }
}

/// A slide set up without the window (`raylab render --slide N`), as the window shows it.
pub struct SlideSetup {
    /// The slide.
    pub slide: &'static Slide,
    /// Its scene.
    pub scene: Scene,
    /// The scene's parameters with the slide's on top (side A, where it compares).
    pub params: Params,
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

/// Slide `number` (from 1, as the Lecture menu numbers them): its scene loaded and its
/// parameters set.
pub fn slide_setup(number: usize) -> Result<SlideSetup, SlideError> {
    let slide = number
        .checked_sub(1)
        .and_then(|i| LECTURE.get(i))
        .ok_or(SlideError::NoSuchSlide(number, LECTURE.len()))?;
    let scene = Scene::load(slide.reference())?;
    let params = slide.params_on(&scene.params)?;
    Ok(SlideSetup {
        slide,
        scene,
        params,
    })
}

/// The lecture as Markdown, slide by slide, as `docs/lecture.md` shows it (`raylab lecture
/// --markdown`): each slide's number and title, its scene and parameters, what its sides
/// compare, what it opens and asks for, and its caption as it first reads.
pub fn markdown() -> Result<String, SlideError> {
    let mut out = String::new();
    for number in 1..=LECTURE.len() {
        let setup = slide_setup(number)?;
        let s = setup.slide;
        out += &format!(
            "### {number}. {}

",
            s.title
        );
        let mut facts = vec![format!("scene `{}`", s.scene)];
        if !s.params.is_empty() {
            let set: Vec<String> = s.params.iter().map(|(n, v)| format!("`{n}={v}`")).collect();
            facts.push(set.join(" "));
        }
        if let Some(c) = s.compare {
            facts.push(format!("A/B view, {}", c.labels().join(" | ")));
        }
        if !s.instruments.is_empty() {
            let opens: Vec<String> = s.instruments.iter().map(Instrument::describe).collect();
            facts.push(format!("opens {}", opens.join(" and ")));
        }
        if !s.controls.is_empty() {
            let asks: Vec<String> = s.controls.iter().map(|n| format!("`{n}`")).collect();
            facts.push(format!("asks for {}", asks.join(", ")));
        }
        let scene = &setup.scene;
        let shown = Shown {
            params: &setup.params,
            scene,
            camera: &scene.camera,
            inspected: s.inspected(scene, &scene.camera, (scene.width, scene.height)),
        };
        out += &format!("{}.\n\n{}\n\n", facts.join("; "), s.caption(&shown));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::BUILTIN_SCENES;

    #[test]
    fn every_slide_names_what_exists() {
        for s in LECTURE {
            let t = s.title;
            assert!(
                BUILTIN_SCENES.iter().any(|b| b.name == s.scene),
                "slide `{t}`: no built-in scene `{}`",
                s.scene
            );
            let scene = Scene::load(s.reference()).unwrap();
            let set = s
                .set_on(&scene.params)
                .unwrap_or_else(|e| panic!("slide `{t}`: {e}"));
            for (name, value) in s.params {
                assert_eq!(set.value_text(name).as_deref(), Some(*value), "{t}: {name}");
            }
            let p = s.params_on(&scene.params).unwrap();
            for name in s.controls {
                assert!(
                    crate::params::spec(name).is_some(),
                    "slide `{t}` asks for `{name}`, which is no parameter"
                );
            }
            for i in s.instruments {
                if let Instrument::FresnelPlot { metal: Some(m) } = i {
                    assert!(
                        crate::material::metal(m).is_some(),
                        "slide `{t}`: metal {m}"
                    );
                }
                if let Some((x, y)) = i.pixel() {
                    assert!((0.0..1.0).contains(&x) && (0.0..1.0).contains(&y), "{t}");
                }
                if let Instrument::Workbench { angle, .. } = i {
                    assert!((0.0..=crate::section::MAX_ANGLE).contains(angle), "{t}");
                }
                if let Instrument::Section { zoom, .. } = i {
                    assert!((1.0..=crate::section::MAX_ZOOM).contains(zoom), "{t}");
                }
            }
            for b in s.others(&p) {
                assert_ne!(p, b, "slide `{t}`: its sides differ");
            }
            let shown = Shown {
                params: &p,
                scene: &scene,
                camera: &scene.camera,
                inspected: None,
            };
            assert!(!s.caption(&shown).is_empty(), "slide `{t}`: a caption");
        }
        let mut titles: Vec<_> = LECTURE.iter().map(|s| s.title).collect();
        titles.sort();
        titles.dedup();
        assert_eq!(titles.len(), LECTURE.len(), "titles are unique");
    }

    #[test]
    fn a_misspelt_parameter_is_an_error_not_ignored() {
        const TYPO: Slide = slide("typo", "default").set(&[("max_dpeth", "2")]);
        assert!(matches!(
            TYPO.params_on(&Params::default()),
            Err(ParamError::Unknown { .. })
        ));
    }

    #[test]
    fn the_pruning_caption_follows_max_depth() {
        let slide = LECTURE
            .iter()
            .find(|s| s.title == "Pruning the ray tree")
            .unwrap();
        let scene = Scene::load(slide.reference()).unwrap();
        let at = |max_depth| {
            let params = Params {
                max_depth,
                ..Params::default()
            };
            slide.caption(&Shown {
                params: &params,
                scene: &scene,
                camera: &scene.camera,
                inspected: None,
            })
        };
        assert!(at(2).contains("Cut at depth 2"), "{}", at(2));
        // Raised past the cut, it no longer says the tree is cut.
        assert!(
            at(8).contains("At depth 8") && !at(8).contains("Cut at"),
            "{}",
            at(8)
        );
    }

    fn slide_titled(title: &str) -> &'static Slide {
        LECTURE.iter().find(|s| s.title == title).unwrap()
    }

    #[test]
    fn the_depth_of_field_caption_names_the_sphere_in_focus() {
        let slide = slide_titled("Depth of field");
        let setup =
            slide_setup(LECTURE.iter().position(|s| std::ptr::eq(s, slide)).unwrap() + 1).unwrap();
        let scene = &setup.scene;
        let caption = |params: &Params| {
            slide.caption(&Shown {
                params,
                scene,
                camera: &scene.camera,
                inspected: None,
            })
        };
        assert!(caption(&setup.params).contains("the blue sphere is sharp"));
        // Focused at the nearest (red) sphere's depth, as Click to focus would set it.
        let nearest = scene
            .object_names
            .iter()
            .position(|n| n == "nearest")
            .unwrap();
        let crate::geometry::Shape::Sphere(s) = &scene.shapes[nearest] else {
            panic!("the nearest sphere");
        };
        let forward = scene.camera.pinhole(1.0).forward();
        let depth = (s.center - scene.camera.position).dot(forward);
        let near = Params {
            focus_distance: Some(depth),
            ..setup.params.clone()
        };
        assert!(
            caption(&near).contains("the red sphere is sharp"),
            "{}",
            caption(&near)
        );
        assert!(caption(&near).contains(&format!("{depth:.1} units")));
        // Focused far behind every sphere: none is named sharp.
        let far = Params {
            focus_distance: Some(100.0),
            ..setup.params.clone()
        };
        assert!(
            caption(&far).contains("no sphere lies there"),
            "{}",
            caption(&far)
        );
        let pinhole = Params {
            aperture: 0.0,
            ..setup.params.clone()
        };
        assert!(caption(&pinhole).contains("everything is sharp"));
    }

    #[test]
    fn the_ray_tree_caption_names_what_the_inspected_pixel_meets() {
        let slide = slide_titled("The ray tree");
        let scene = Scene::load(slide.reference()).unwrap();
        let caption = |inspected| {
            slide.caption(&Shown {
                params: &scene.params,
                scene: &scene,
                camera: &scene.camera,
                inspected,
            })
        };
        let id = |name: &str| scene.object_names.iter().position(|n| n == name).unwrap() as u32;
        // The slide's own pixel is on the front sphere.
        let own = slide.inspected(&scene, &scene.camera, (scene.width, scene.height));
        assert_eq!(own, Some(Some(id("front sphere"))));
        assert!(caption(own).contains("off and through the front sphere"));
        let floor = caption(Some(Some(id("floor"))));
        assert!(
            floor.contains("on the floor") && !floor.contains("front sphere"),
            "{floor}"
        );
        assert!(caption(Some(None)).contains("meets nothing"));
        assert!(caption(None).contains("Click a pixel"));
    }

    #[test]
    fn no_slide_number_beyond_the_lecture() {
        let n = LECTURE.len();
        for bad in [0, n + 1] {
            assert!(matches!(
                slide_setup(bad),
                Err(SlideError::NoSuchSlide(b, m)) if b == bad && m == n
            ));
        }
        assert_eq!(slide_setup(n).unwrap().slide.title, LECTURE[n - 1].title);
    }
}
