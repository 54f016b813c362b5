//! The side panel: every parameter of the lecture, by topic, each with a tooltip that
//! explains the concept. Labels, ranges and explanations come from the parameter table.

use crate::camera::Camera;
use crate::material::Material;
use crate::optics::{FresnelMode, brewster_angle, critical_angle};
use crate::params::{Params, SliderRange, choice_of, choices, spec};
use crate::scene::Scene;
use egui::{CollapsingHeader, ComboBox, DragValue, Slider, Ui};

/// What the side panel edits.
pub(crate) struct Controls<'a> {
    /// The parameter model.
    pub params: &'a mut Params,
    /// The camera (field of view).
    pub camera: &'a mut Camera,
    /// Run on past the target samples per pixel.
    pub unlimited: &'a mut bool,
    /// The next click on the image sets the focus distance.
    pub click_to_focus: &'a mut bool,
    /// Render resolution as a fraction of the scene's image size.
    pub resolution: &'a mut f32,
    /// The scene, for its own values (shown while a parameter keeps them).
    pub scene: &'a Scene,
    /// Parameters whose sections to open now (a lecture slide just arrived that asks for
    /// them).
    pub open: &'a [&'static str],
}

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
            ],
            Section::RayTree => &["max_depth", "min_weight", "tree", "transport"],
            Section::Sampling => &["spp", "pattern", "seed"],
            Section::SoftShadows => &["light_size"],
            Section::Glossy => &["phong_exponent"],
            Section::Camera => &["aperture", "focus_distance"],
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

/// A tooltip that stays away while a mouse button is held: mid-drag it would pop up over
/// the readouts the drag is about (the Brewster and critical angles, the f-number).
trait Hint {
    fn hint(self, text: impl Into<egui::WidgetText>) -> Self;
}

impl Hint for egui::Response {
    fn hint(self, text: impl Into<egui::WidgetText>) -> Self {
        if self.ctx.input(|i| i.pointer.any_down()) {
            self
        } else {
            self.on_hover_text(text)
        }
    }
}

/// The IOR the `ior` parameter would replace: the first dielectric's that is not fixed.
fn scene_ior(scene: &Scene) -> Option<f32> {
    scene
        .materials
        .iter()
        .find_map(|m| m.dielectric().filter(|d| !d.ior_fixed).map(|d| d.ior))
}

/// The Abbe number the `abbe` parameter replaces: the scene's first dispersive-capable
/// dielectric's (not a glaze's coat, which ignores it).
fn scene_abbe(scene: &Scene) -> Option<f32> {
    scene.materials.iter().find_map(|m| {
        if let Material::Dielectric(d) = m
            && !d.ior_fixed
        {
            Some(d.abbe)
        } else {
            None
        }
    })
}

/// The reflectance k the `constant_reflectance` parameter replaces: the scene's first
/// constant-model interface's (a dielectric or glaze), else its first interface's.
fn scene_k(scene: &Scene) -> Option<f32> {
    let interfaces = || scene.materials.iter().filter_map(|m| m.dielectric());
    interfaces()
        .find(|d| d.fresnel == FresnelMode::Constant)
        .or_else(|| interfaces().next())
        .map(|d| d.constant_reflectance)
}

fn scene_exponent(scene: &Scene) -> Option<f32> {
    scene.materials.iter().find_map(|m| m.phong_exponent())
}

/// A slider for parameter `name`, with the table's label and range.
fn param_slider<'a, N: egui::emath::Numeric>(value: &'a mut N, name: &str) -> Slider<'a> {
    let spec = spec(name);
    let range = spec.and_then(|s| s.slider).unwrap_or(SliderRange {
        min: 0.0,
        max: 1.0,
        log: false,
    });
    let slider = Slider::new(value, N::from_f64(range.min)..=N::from_f64(range.max))
        .text(spec.map_or(name, |s| s.label))
        .logarithmic(range.log);
    if range.log && range.min == 0.0 {
        slider.smallest_positive(1e-5)
    } else {
        slider
    }
}

/// The table's tooltip for parameter `name`.
fn tip(name: &str) -> String {
    spec(name).map_or_else(String::new, |s| s.tooltip())
}

/// A menu of the choice parameter `name`, its entries and their tooltips from the table;
/// `own` is an entry for "no override" where the parameter is one (`None`).
fn choice_menu<T>(ui: &mut Ui, name: &str, value: &mut T, own: Option<(T, &str, &str)>)
where
    T: Copy + PartialEq + serde::Serialize + serde::de::DeserializeOwned,
{
    let label = spec(name).map_or(name, |s| s.label);
    let selected = match &own {
        Some((none, text, _)) if value == none => text.to_string(),
        _ => choice_of(name, value).map_or_else(String::new, |c| c.label.to_string()),
    };
    ComboBox::from_label(label)
        .selected_text(selected)
        .show_ui(ui, |ui| {
            if let Some((none, text, hint)) = own {
                ui.selectable_value(value, none, text).hint(hint);
            }
            for (v, c) in choices::<T>(name) {
                ui.selectable_value(value, v, c.label).hint(c.explain);
            }
        })
        .response
        .hint(tip(name));
}

/// Draws the side panel's sections.
pub(crate) fn controls_ui(ui: &mut Ui, c: &mut Controls) {
    Section::Dielectrics
        .header(c.open, false)
        .show(ui, |ui| dielectrics_ui(ui, c));
    Section::RayTree
        .header(c.open, false)
        .show(ui, |ui| ray_tree_ui(ui, c.params));
    Section::Sampling
        .header(c.open, false)
        .show(ui, |ui| sampling_ui(ui, c));
    Section::SoftShadows.header(c.open, false).show(ui, |ui| {
        ui.add(param_slider(&mut c.params.light_size, "light_size"))
            .hint(tip("light_size"));
    });
    Section::Glossy
        .header(c.open, false)
        .show(ui, |ui| glossy_ui(ui, c));
    Section::Camera
        .header(c.open, false)
        .show(ui, |ui| camera_ui(ui, c));
    // Kept open while a polariser is on, so the image never hides why it changed.
    Section::Polariser
        .header(c.open, c.params.polarizer.is_some())
        .show(ui, |ui| polariser_ui(ui, c.params));
    Section::MotionBlur
        .header(c.open, false)
        .show(ui, |ui| motion_blur_ui(ui, c.params));
    Section::Display
        .header(c.open, false)
        .show(ui, |ui| display_ui(ui, c));
}

fn dielectrics_ui(ui: &mut Ui, c: &mut Controls) {
    // Without glass, water or a glaze these controls would only restart the same image.
    let interfaces = c.scene.materials.iter().any(|m| m.dielectric().is_some());
    if !interfaces {
        ui.label("No glass, water or glaze in this scene.");
    }
    let p = &mut *c.params;
    ui.add_enabled_ui(interfaces, |ui| {
        let mut ior = p.ior.or(scene_ior(c.scene)).unwrap_or(1.5);
        let slider = ui
            .add(param_slider(&mut ior, "ior").fixed_decimals(3))
            .hint(tip("ior"));
        if slider.changed() {
            p.ior = Some(ior);
        }
        ui.horizontal(|ui| {
            for (name, value) in [("Water", 1.33), ("Glass", 1.5), ("Diamond", 2.42)] {
                let preset = ui
                    .selectable_label(p.ior == Some(value), name)
                    .hint(format!("n = {value}"));
                if preset.clicked() {
                    p.ior = Some(value);
                }
            }
            if ui
                .add_enabled(p.ior.is_some(), egui::Button::new("Scene IOR"))
                .hint("Each material's own index of refraction, as in the scene file.")
                .clicked()
            {
                p.ior = None;
            }
        });
        let crit = critical_angle(ior, 1.0)
            .map_or("none".to_string(), |a| format!("{:.1}°", a.to_degrees()));
        let brewster = brewster_angle(1.0, ior).to_degrees();
        ui.label(format!("Brewster {brewster:.1}°, critical (inside to air) {crit}"))
            .hint(
                "Brewster's angle atan(n2/n1): p-polarized light is not reflected (Fp = 0). \
                 Critical angle asin(n2/n1), from the denser side: beyond it light is totally reflected.",
            );
        let own = (None, "each material's own", "Keep each material's own reflectance model.");
        choice_menu(ui, "fresnel", &mut p.fresnel, Some(own));
        let mut k = p.constant_reflectance.or(scene_k(c.scene)).unwrap_or(0.04);
        if ui
            .add(param_slider(&mut k, "constant_reflectance"))
            .hint(tip("constant_reflectance"))
            .changed()
        {
            p.constant_reflectance = Some(k);
        }
        ui.add(param_slider(&mut p.absorption_scale, "absorption_scale"))
            .hint(tip("absorption_scale"));
        let mut abbe = p.abbe.or(scene_abbe(c.scene)).unwrap_or(0.0);
        if ui
            .add(param_slider(&mut abbe, "abbe").fixed_decimals(1))
            .hint(tip("abbe"))
            .changed()
        {
            p.abbe = Some(abbe);
        }
        if abbe > 0.0 {
            let n = |lambda| crate::optics::dispersion::ior_at(ior, abbe, lambda);
            ui.label(format!(
                "n = {:.4} at 450 nm, {:.4} at 650 nm",
                n(450.0),
                n(650.0)
            ))
            .hint("Cauchy's n(λ) = A + B/λ², through n_d = IOR and the Abbe number.");
        }
    });
}

fn ray_tree_ui(ui: &mut Ui, p: &mut Params) {
    ui.add(param_slider(&mut p.max_depth, "max_depth"))
        .hint(tip("max_depth"));
    // A path tracer follows one path and ends it by Russian roulette: the tree's weight
    // limit and branching do not apply.
    let tree = !p.transport.traces_paths();
    let no_tree = "Path tracing follows one path per sample (Russian roulette ends the faint ones): there is no tree to prune or split.";
    ui.add_enabled(tree, param_slider(&mut p.min_weight, "min_weight"))
        .hint(tip("min_weight"))
        .on_disabled_hover_text(no_tree);
    ui.add_enabled_ui(tree, |ui| {
        ui.horizontal(|ui| {
            for (mode, c) in choices("tree") {
                ui.radio_value(&mut p.tree, mode, c.label)
                    .hint(c.explain)
                    .on_disabled_hover_text(no_tree);
            }
        });
    });
    choice_menu(ui, "transport", &mut p.transport, None);
}

fn sampling_ui(ui: &mut Ui, c: &mut Controls) {
    let p = &mut *c.params;
    ui.add(param_slider(&mut p.spp, "spp")).hint(tip("spp"));
    ui.checkbox(c.unlimited, "Keep refining")
        .hint("Run on past the target, until paused.");
    choice_menu(ui, "pattern", &mut p.pattern, None);
    ui.horizontal(|ui| {
        ui.add(DragValue::new(&mut p.seed)).hint(tip("seed"));
        ui.label("Seed");
    });
}

fn glossy_ui(ui: &mut Ui, c: &mut Controls) {
    let p = &mut *c.params;
    let mut n = p
        .phong_exponent
        .or(scene_exponent(c.scene))
        .unwrap_or(100.0);
    if ui
        .add(param_slider(&mut n, "phong_exponent"))
        .hint(tip("phong_exponent"))
        .changed()
    {
        p.phong_exponent = Some(n);
    }
    if ui
        .add_enabled(p.phong_exponent.is_some(), egui::Button::new("Scene n"))
        .hint("Each glossy material's own exponent.")
        .clicked()
    {
        p.phong_exponent = None;
    }
}

fn camera_ui(ui: &mut Ui, c: &mut Controls) {
    let p = &mut *c.params;
    ui.add(Slider::new(&mut c.camera.fov_deg, 5.0..=120.0).text("Field of view °"))
        .hint("The vertical angle the image spans.");
    ui.add(param_slider(&mut p.aperture, "aperture"))
        .hint(tip("aperture"));
    let f = c
        .camera
        .f_number(p.aperture)
        .map_or("pinhole".to_string(), |n| format!("f/{n:.1}"));
    ui.label(format!("{f} (35 mm equivalent, 1 unit = 1 m)"));
    let mut d = p.focus_distance.unwrap_or(c.camera.look_distance());
    if ui
        .add(param_slider(&mut d, "focus_distance"))
        .hint(tip("focus_distance"))
        .changed()
    {
        p.focus_distance = Some(d);
    }
    ui.horizontal(|ui| {
        ui.toggle_value(c.click_to_focus, "Click to focus").hint(
            "Then click the image: the focus distance becomes the depth of the point clicked.",
        );
        if ui
            .add_enabled(p.focus_distance.is_some(), egui::Button::new("Look-at"))
            .hint("Focus on the camera's look-at point.")
            .clicked()
        {
            p.focus_distance = None;
        }
    });
    ui.label("Orbit: right-drag. Dolly: Ctrl + wheel.");
}

fn polariser_ui(ui: &mut Ui, p: &mut Params) {
    let mut on = p.polarizer.is_some();
    if ui
        .checkbox(&mut on, "Linear polariser in front of the lens")
        .hint(tip("polarizer"))
        .changed()
    {
        p.polarizer = on.then_some(90.0);
    }
    let mut angle = p.polarizer.unwrap_or(90.0);
    let slider = ui
        .add_enabled(on, param_slider(&mut angle, "polarizer").fixed_decimals(0))
        .hint(tip("polarizer"));
    if slider.changed() {
        p.polarizer = Some(angle);
    }
    ui.horizontal(|ui| {
        for (label, a, hint) in [
            (
                "Horizontal",
                0.0,
                "Passes horizontally polarised light: the glare off a floor or water stays.",
            ),
            (
                "Vertical",
                90.0,
                "Passes vertically polarised light: the s-polarised glare off a floor or water at Brewster's angle is cut.",
            ),
        ] {
            let button = egui::Button::selectable(p.polarizer == Some(a), label);
            if ui.add_enabled(on, button).hint(hint).clicked() {
                p.polarizer = Some(a);
            }
        }
    });
    ui.label(format!(
        "Brewster: {:.1}° on water, {:.1}° on glass",
        brewster_angle(1.0, 1.33).to_degrees(),
        brewster_angle(1.0, 1.5).to_degrees()
    ));
}

fn motion_blur_ui(ui: &mut Ui, p: &mut Params) {
    ui.add(param_slider(&mut p.shutter_open, "shutter_open"))
        .hint(tip("shutter_open"));
    // The interval ends within the frame: the slider stops at 1 − opening.
    let max = 1.0 - p.shutter_open;
    p.shutter = p.shutter.min(max);
    let label = spec("shutter").map_or("shutter", |s| s.label);
    ui.add(Slider::new(&mut p.shutter, 0.0..=max).text(label))
        .hint(tip("shutter"));
}

fn display_ui(ui: &mut Ui, c: &mut Controls) {
    ui.add(param_slider(&mut c.params.exposure, "exposure"))
        .hint(tip("exposure"));
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
                assert!(spec(name).is_some(), "{sec:?} holds `{name}`");
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
