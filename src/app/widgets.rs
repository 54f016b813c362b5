//! One control per parameter, as the side panel shows it and as presentation mode shows
//! the ones a slide asks for: its slider, menu or buttons, with its readouts. Labels,
//! ranges and explanations come from the parameter table.

use crate::camera::Camera;
use crate::material::Material;
use crate::optics::{FresnelMode, brewster_angle, critical_angle};
use crate::params::{
    Kind, LensDispersion, LensModel, Params, SliderRange, choice_of, choices, spec,
};
use crate::scene::Scene;
use egui::{ComboBox, DragValue, Slider, Ui};

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

/// A tooltip that stays away while a mouse button is held: mid-drag it would pop up over
/// the readouts the drag is about (the Brewster and critical angles, the f-number).
pub(crate) trait Hint {
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

/// The first dielectric's roughness the `roughness` parameter reaches: the slider's value
/// until it is moved.
fn scene_roughness(scene: &Scene) -> Option<f32> {
    scene.materials.iter().find_map(Material::roughness)
}

/// The Abbe number the `abbe` parameter replaces: the scene's first dielectric's that is
/// not fixed (not a glaze's coat, which ignores it).
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

/// The IOR shown: the parameter's, or the scene's own.
fn shown_ior(p: &Params, scene: &Scene) -> f32 {
    p.ior.or(scene_ior(scene)).unwrap_or(1.5)
}

/// A slider for parameter `name`, with the table's label and range.
fn param_slider<'a, N: egui::emath::Numeric>(value: &'a mut N, name: &str) -> Slider<'a> {
    let spec = spec(name);
    let range = slider_range(name);
    let slider = Slider::new(value, N::from_f64(range.min)..=N::from_f64(range.max))
        .text(spec.map_or(name, |s| s.label))
        .logarithmic(range.log);
    if range.log && range.min == 0.0 {
        slider.smallest_positive(1e-5)
    } else {
        slider
    }
}

fn slider_range(name: &str) -> SliderRange {
    spec(name).and_then(|s| s.slider).unwrap_or(SliderRange {
        min: 0.0,
        max: 1.0,
        log: false,
    })
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

/// The slider of a parameter that overrides the scene's own value (`None`: the scene's,
/// `own`, shown until the slider moves; 0 without one), with `decimals` decimals; returns
/// the value shown.
fn own_or_set_slider(
    ui: &mut Ui,
    value: &mut Option<f32>,
    own: Option<f32>,
    name: &str,
    decimals: usize,
) -> f32 {
    let mut shown = value.or(own).unwrap_or(0.0);
    if ui
        .add(param_slider(&mut shown, name).fixed_decimals(decimals))
        .hint(tip(name))
        .changed()
    {
        *value = Some(shown);
    }
    shown
}

/// Parameter `name`'s control (with its readouts), or `false` if it has none.
pub(crate) fn param_ui(ui: &mut Ui, c: &mut Controls, name: &str) -> bool {
    let p = &mut *c.params;
    match name {
        "ior" => ior_ui(ui, p, c.scene),
        "abbe" => {
            let abbe = own_or_set_slider(ui, &mut p.abbe, scene_abbe(c.scene), name, 1);
            if abbe > 0.0 {
                let ior = shown_ior(p, c.scene);
                let n = |lambda| crate::optics::dispersion::ior_at(ior, abbe, lambda);
                ui.label(format!(
                    "n = {:.4} at 450 nm, {:.4} at 650 nm",
                    n(450.0),
                    n(650.0)
                ))
                .hint("Cauchy's n(λ) = A + B/λ², through n_d = IOR and the Abbe number.");
            }
        }
        "roughness" => {
            own_or_set_slider(ui, &mut p.roughness, scene_roughness(c.scene), name, 2);
        }
        "fresnel" => {
            let own = (
                None,
                "each material's own",
                "Keep each material's own reflectance model.",
            );
            choice_menu(ui, "fresnel", &mut p.fresnel, Some(own));
        }
        "constant_reflectance" => {
            let mut k = p.constant_reflectance.or(scene_k(c.scene)).unwrap_or(0.04);
            if ui.add(param_slider(&mut k, name)).hint(tip(name)).changed() {
                p.constant_reflectance = Some(k);
            }
        }
        "absorption_scale" => slider_ui(ui, &mut p.absorption_scale, name),
        "max_depth" => slider_ui(ui, &mut p.max_depth, name),
        "min_weight" => {
            ui.add_enabled(
                !p.transport.traces_paths(),
                param_slider(&mut p.min_weight, name),
            )
            .hint(tip(name))
            .on_disabled_hover_text(NO_TREE);
        }
        "tree" => {
            ui.add_enabled_ui(!p.transport.traces_paths(), |ui| {
                ui.horizontal(|ui| {
                    for (mode, choice) in choices("tree") {
                        ui.radio_value(&mut p.tree, mode, choice.label)
                            .hint(choice.explain)
                            .on_disabled_hover_text(NO_TREE);
                    }
                });
            });
        }
        "transport" => choice_menu(ui, name, &mut p.transport, None),
        "lens" => choice_menu(ui, name, &mut p.lens, None),
        "lens_dispersion" => {
            let mut on = p.lens_dispersion == LensDispersion::On;
            let label = "Chromatic aberration (the glass disperses)";
            let check = egui::Checkbox::new(&mut on, label);
            if ui
                .add_enabled(p.lens != LensModel::Thin, check)
                .hint(tip(name))
                .on_disabled_hover_text("The thin lens is ideal: it has no glass to disperse.")
                .changed()
            {
                p.lens_dispersion = if on {
                    LensDispersion::On
                } else {
                    LensDispersion::Off
                };
            }
        }
        "spp" => {
            slider_ui(ui, &mut p.spp, name);
            ui.checkbox(c.unlimited, "Keep refining")
                .hint("Run on past the target, until paused.");
        }
        "noise_target" => {
            let label = "Adaptive sampling: stop clean pixels";
            let clean = crate::render::CLEAN_NOISE * 100.0;
            switched_slider(ui, &mut p.noise_target, name, label, clean, 2);
        }
        "pattern" => choice_menu(ui, name, &mut p.pattern, None),
        "seed" => {
            ui.horizontal(|ui| {
                ui.add(DragValue::new(&mut p.seed)).hint(tip(name));
                ui.label("Seed");
            });
        }
        "light_size" => slider_ui(ui, &mut p.light_size, name),
        "phong_exponent" => {
            let mut n = p
                .phong_exponent
                .or(scene_exponent(c.scene))
                .unwrap_or(100.0);
            if ui.add(param_slider(&mut n, name)).hint(tip(name)).changed() {
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
        "aperture" => {
            slider_ui(ui, &mut p.aperture, name);
            let f = c
                .camera
                .f_number(p.lens, p.aperture)
                .map_or("pinhole".to_string(), |n| format!("f/{n:.1}"));
            if p.lens == LensModel::Thin {
                ui.label(format!("{f} (35 mm equivalent, 1 unit = 1 m)"));
            } else {
                ui.label(format!("{f} (the lens's own focal length, 1 unit = 1 m)"));
            }
        }
        "focus_distance" => focus_ui(ui, c),
        "polarizer" => polarizer_ui(ui, p),
        "shutter_open" => slider_ui(ui, &mut p.shutter_open, name),
        "shutter" => {
            // The interval ends within the frame: the slider stops at 1 − opening.
            let max = 1.0 - p.shutter_open;
            p.shutter = p.shutter.min(max);
            let label = spec(name).map_or(name, |s| s.label);
            ui.add(Slider::new(&mut p.shutter, 0.0..=max).text(label))
                .hint(tip(name));
        }
        "exposure" => slider_ui(ui, &mut p.exposure, name),
        _ => return false,
    }
    true
}

const NO_TREE: &str = "Path tracing follows one path per sample (Russian roulette ends the faint ones): there is no tree to prune or split.";

fn slider_ui<N: egui::emath::Numeric>(ui: &mut Ui, value: &mut N, name: &str) {
    ui.add(param_slider(value, name)).hint(tip(name));
}

fn ior_ui(ui: &mut Ui, p: &mut Params, scene: &Scene) {
    let mut ior = shown_ior(p, scene);
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
    let crit =
        critical_angle(ior, 1.0).map_or("none".to_string(), |a| format!("{:.1}°", a.to_degrees()));
    let brewster = brewster_angle(1.0, ior).to_degrees();
    ui.label(format!("Brewster {brewster:.1}°, critical (inside to air) {crit}"))
        .hint(
            "Brewster's angle atan(n2/n1): p-polarized light is not reflected (Fp = 0). \
             Critical angle asin(n2/n1), from the denser side: beyond it light is totally reflected.",
        );
}

fn focus_ui(ui: &mut Ui, c: &mut Controls) {
    let p = &mut *c.params;
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
}

/// A parameter that is off (`None`) or a number: a checkbox `label` that turns it on at
/// `default`, and its slider, live while it is on. Returns whether it is on.
fn switched_slider(
    ui: &mut Ui,
    value: &mut Option<f32>,
    name: &str,
    label: &str,
    default: f32,
    decimals: usize,
) -> bool {
    let mut on = value.is_some();
    if ui.checkbox(&mut on, label).hint(tip(name)).changed() {
        *value = on.then_some(default);
    }
    let mut v = value.unwrap_or(default);
    let slider = param_slider(&mut v, name).fixed_decimals(decimals);
    if ui.add_enabled(on, slider).hint(tip(name)).changed() {
        *value = Some(v);
    }
    on
}

fn polarizer_ui(ui: &mut Ui, p: &mut Params) {
    let label = "Linear polariser in front of the lens";
    let on = switched_slider(ui, &mut p.polarizer, "polarizer", label, 90.0, 0);
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

/// Steps parameter `name` one notch `up` (or down), as the `]` and `[` keys do in
/// presentation mode: a twentieth of a linear slider's range, a factor of 2^¼ on a
/// logarithmic one, one on a count, the next or previous choice. Returns whether it moved.
pub(crate) fn step_param(c: &mut Controls, name: &str, up: bool) -> bool {
    let Some(spec) = spec(name) else {
        return false;
    };
    let p = &mut *c.params;
    let value = match name {
        "ior" => shown_ior(p, c.scene) as f64,
        "abbe" => p.abbe.or(scene_abbe(c.scene)).unwrap_or(0.0) as f64,
        "roughness" => p.roughness.or(scene_roughness(c.scene)).unwrap_or(0.0) as f64,
        "focus_distance" => p.focus_distance.unwrap_or(c.camera.look_distance()) as f64,
        "polarizer" => p.polarizer.unwrap_or(90.0) as f64,
        "constant_reflectance" => {
            p.constant_reflectance.or(scene_k(c.scene)).unwrap_or(0.04) as f64
        }
        "phong_exponent" => p
            .phong_exponent
            .or(scene_exponent(c.scene))
            .unwrap_or(100.0) as f64,
        _ => match p.value_text(name).and_then(|t| t.parse::<f64>().ok()) {
            Some(v) => v,
            None => return step_choice(p, name, spec.kind, up),
        },
    };
    let range = slider_range(name);
    let next = match spec.kind {
        Kind::Count { .. } => value + if up { 1.0 } else { -1.0 },
        _ if range.log => {
            let v = value.max(range.min.max(1e-4));
            v * if up {
                2f64.powf(0.25)
            } else {
                2f64.powf(-0.25)
            }
        }
        _ => value + (range.max - range.min) / 20.0 * if up { 1.0 } else { -1.0 },
    };
    let next = next.clamp(range.min, range.max);
    let text = if matches!(spec.kind, Kind::Count { .. }) {
        format!("{}", next.round())
    } else {
        format!("{}", (next as f32 * 1e4).round() / 1e4)
    };
    let before = p.clone();
    p.set(name, &text).is_ok() && *p != before
}

/// The next (or previous) value of the choice parameter `name`, wrapping round.
fn step_choice(p: &mut Params, name: &str, kind: Kind, up: bool) -> bool {
    let Kind::Choice(all) = kind else {
        return false;
    };
    let now = p.value_text(name);
    let i = all
        .iter()
        .position(|c| Some(c.word) == now.as_deref())
        .unwrap_or(0);
    let n = all.len();
    let next = if up { (i + 1) % n } else { (i + n - 1) % n };
    p.set(name, all[next].word).is_ok()
}
