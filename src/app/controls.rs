//! The side panel: every parameter of the lecture, by topic, each with a tooltip that
//! explains the concept. Labels, ranges and explanations come from the parameter table.

use super::widgets::{Controls, Hint, param_ui};
use egui::{CollapsingHeader, ComboBox, Slider, Ui};

/// A section of the panel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Section {
    Dielectrics,
    RayTree,
    Sampling,
    SoftShadows,
    Glossy,
    Camera,
    Polariser,
    MotionBlur,
    Display,
}

impl Section {
    /// Every section, top to bottom.
    #[cfg(test)]
    const ALL: [Section; 9] = [
        Section::Dielectrics,
        Section::RayTree,
        Section::Sampling,
        Section::SoftShadows,
        Section::Glossy,
        Section::Camera,
        Section::Polariser,
        Section::MotionBlur,
        Section::Display,
    ];

    /// Its heading.
    pub(crate) fn title(self) -> &'static str {
        match self {
            Section::Dielectrics => "Dielectrics and Fresnel",
            Section::RayTree => "Ray tree",
            Section::Sampling => "Sampling and antialiasing",
            Section::SoftShadows => "Soft shadows",
            Section::Glossy => "Glossy reflection",
            Section::Camera => "Camera and depth of field",
            Section::Polariser => "Polariser",
            Section::MotionBlur => "Motion blur",
            Section::Display => "Display",
        }
    }

    /// The parameters whose controls it holds.
    pub(crate) fn params(self) -> &'static [&'static str] {
        match self {
            Section::Dielectrics => &[
                "ior",
                "fresnel",
                "constant_reflectance",
                "absorption_scale",
                "abbe",
                "roughness",
            ],
            Section::RayTree => &["max_depth", "min_weight", "tree", "transport"],
            Section::Sampling => &["spp", "noise_target", "pattern", "seed"],
            Section::SoftShadows => &["light_size"],
            Section::Glossy => &["phong_exponent"],
            Section::Camera => &["lens", "lens_dispersion", "aperture", "focus_distance"],
            Section::Polariser => &["polarizer"],
            Section::MotionBlur => &["shutter_open", "shutter"],
            Section::Display => &["exposure"],
        }
    }

    /// Open at first, before the user folds it.
    fn open_at_first(self) -> bool {
        !matches!(
            self,
            Section::SoftShadows | Section::Glossy | Section::Polariser | Section::MotionBlur
        )
    }

    /// Its header, opened now if `open` names one of its parameters, or `keep_open` asks
    /// it to stay so.
    fn header(self, open: &[&str], keep_open: bool) -> CollapsingHeader {
        let header = CollapsingHeader::new(self.title()).default_open(self.open_at_first());
        let asked = open.iter().any(|p| self.params().contains(p));
        if asked || keep_open {
            header.open(Some(true))
        } else {
            header
        }
    }
}

/// Draws the side panel's sections, each its parameters' controls (`widgets::param_ui`)
/// and what else belongs there.
pub(crate) fn controls_ui(ui: &mut Ui, c: &mut Controls) {
    Section::Dielectrics.header(c.open, false).show(ui, |ui| {
        // Without glass, water or a glaze these controls would only restart the same
        // image.
        let interfaces = c.scene.materials.iter().any(|m| m.dielectric().is_some());
        if !interfaces {
            ui.label("No glass, water or glaze in this scene.");
        }
        ui.add_enabled_ui(interfaces, |ui| params_ui(ui, c, Section::Dielectrics));
    });
    for section in [
        Section::RayTree,
        Section::Sampling,
        Section::SoftShadows,
        Section::Glossy,
    ] {
        section
            .header(c.open, false)
            .show(ui, |ui| params_ui(ui, c, section));
    }
    Section::Camera.header(c.open, false).show(ui, |ui| {
        ui.add(Slider::new(&mut c.camera.fov_deg, 5.0..=120.0).text("Field of view °"))
            .hint("The vertical angle the image spans.");
        params_ui(ui, c, Section::Camera);
        ui.label("Orbit: right-drag. Dolly: Ctrl + wheel.");
    });
    // Kept open while a polariser is on, so the image never hides why it changed.
    let polarizer = c.params.polarizer.is_some();
    for (section, keep_open) in [
        (Section::Polariser, polarizer),
        (Section::MotionBlur, false),
    ] {
        section
            .header(c.open, keep_open)
            .show(ui, |ui| params_ui(ui, c, section));
    }
    Section::Display.header(c.open, false).show(ui, |ui| {
        params_ui(ui, c, Section::Display);
        ComboBox::from_label("Resolution")
            .selected_text(format!("{:.0}%", *c.resolution * 100.0))
            .show_ui(ui, |ui| {
                for r in [0.25f32, 0.5, 1.0, 2.0] {
                    ui.selectable_value(c.resolution, r, format!("{:.0}%", r * 100.0));
                }
            })
            .response
            .hint(
                "Render resolution, as a fraction of the scene's image size. Lower is faster to refine.",
            );
    });
}

/// The controls of `section`'s parameters, in its order.
fn params_ui(ui: &mut Ui, c: &mut Controls, section: Section) {
    for name in section.params() {
        param_ui(ui, c, name);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::TABLE;

    #[test]
    fn every_parameter_has_one_section_and_every_slide_finds_its_controls() {
        for s in TABLE {
            let holding: Vec<_> = Section::ALL
                .iter()
                .filter(|sec| sec.params().contains(&s.name))
                .collect();
            assert_eq!(holding.len(), 1, "`{}` in {holding:?}", s.name);
        }
        for sec in Section::ALL {
            for name in sec.params() {
                assert!(
                    crate::params::spec(name).is_some(),
                    "{sec:?} holds `{name}`"
                );
            }
        }
        for slide in crate::lecture::LECTURE {
            for name in slide.controls {
                assert!(
                    Section::ALL.iter().any(|s| s.params().contains(name)),
                    "`{}` asks for `{name}`",
                    slide.title
                );
            }
        }
    }
}
