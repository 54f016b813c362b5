//! The side panel: every parameter of the lecture, by topic, each with a tooltip that
//! explains the concept.

use crate::camera::Camera;
use crate::material::Material;
use crate::math::Pattern;
use crate::optics::{FresnelMode, brewster_angle, critical_angle};
use crate::params::{Params, SliderRange, Transport, TreeMode, spec};
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
    /// Sections to open now (a lecture slide just arrived that names their controls).
    pub open: &'a [&'static str],
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

/// The panel section `name`, opened now if `open` asks for it.
fn section(open: &[&str], name: &str) -> CollapsingHeader {
    let header = CollapsingHeader::new(name);
    if open.contains(&name) {
        header.open(Some(true))
    } else {
        header
    }
}

/// The IOR the `ior` parameter would replace: the first dielectric's that is not fixed.
fn scene_ior(scene: &Scene) -> Option<f32> {
    scene.materials.iter().find_map(|m| match m.dielectric() {
        Some(d) if !d.ior_fixed => Some(d.ior),
        _ => None,
    })
}

/// The Abbe number the `abbe` parameter replaces: the scene's first dielectric's.
fn scene_abbe(scene: &Scene) -> Option<f32> {
    scene.materials.iter().find_map(|m| match m {
        Material::Dielectric(d) if !d.ior_fixed => Some(d.abbe),
        _ => None,
    })
}

/// The reflectance k the `constant_reflectance` parameter replaces: the scene's first
/// constant-model interface's (a dielectric or glaze), else its first interface's.
fn scene_k(scene: &Scene) -> Option<f32> {
    let interfaces = || scene.materials.iter().filter_map(Material::dielectric);
    interfaces()
        .find(|d| d.fresnel == FresnelMode::Constant)
        .or_else(|| interfaces().next())
        .map(|d| d.constant_reflectance)
}

fn scene_exponent(scene: &Scene) -> Option<f32> {
    scene.materials.iter().find_map(Material::phong_exponent)
}

fn transport_label(t: Transport) -> &'static str {
    match t {
        Transport::Whitted => "Whitted (the lecture)",
        Transport::TransmissiveShadows => "transmissive shadows",
        Transport::Path => "path tracing (reference)",
        Transport::Photons => "path tracing + photons",
    }
}

fn fresnel_label(mode: Option<FresnelMode>) -> &'static str {
    match mode {
        None => "each material's own",
        Some(FresnelMode::Exact) => "exact (Fs, Fp)",
        Some(FresnelMode::Schlick) => "Schlick",
        Some(FresnelMode::SchlickNaive) => "naive Schlick",
        Some(FresnelMode::Constant) => "constant k",
    }
}

fn pattern_tip(p: Pattern) -> &'static str {
    match p {
        Pattern::Regular => {
            "Sample positions on a fixed grid: the same in every pixel, so regular structures alias."
        }
        Pattern::Random => {
            "Independent uniform random positions: no aliasing, but clumps and gaps make noise."
        }
        Pattern::Jittered => {
            "One random position in each cell of a grid (stratified): random, yet evenly spread."
        }
        Pattern::Sobol => {
            "Owen-scrambled Sobol points: evenly spread at every power-of-two count, so each progressive pass stays stratified."
        }
    }
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

/// Draws the side panel's sections.
pub(crate) fn controls_ui(ui: &mut Ui, c: &mut Controls) {
    let p = &mut *c.params;
    section(c.open, "Dielectrics and Fresnel").default_open(true).show(ui, |ui| {
        // Without glass, water or a glaze these controls would only restart the same image.
        let interfaces = c.scene.materials.iter().any(|m| m.dielectric().is_some());
        if !interfaces {
            ui.label("No glass, water or glaze in this scene.");
        }
        ui.add_enabled_ui(interfaces, |ui| {
            let own = scene_ior(c.scene);
            let mut ior = p.ior.or(own).unwrap_or(1.5);
            let slider = ui
                .add(param_slider(&mut ior, "ior").fixed_decimals(3))
                .hint(tip("ior"));
            if slider.changed() {
                p.ior = Some(ior);
            }
            ui.horizontal(|ui| {
                for (name, value, tip) in [("Water", 1.33, "n = 1.33"), ("Glass", 1.5, "n = 1.5"), ("Diamond", 2.42, "n = 2.42")] {
                    if ui.selectable_label(p.ior == Some(value), name).hint(tip).clicked() {
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
            let crit = critical_angle(ior, 1.0).map_or("none".to_string(), |a| format!("{:.1}°", a.to_degrees()));
            ui.label(format!("Brewster {:.1}°, critical (inside to air) {crit}", brewster_angle(1.0, ior).to_degrees()))
                .hint(
                    "Brewster's angle atan(n2/n1): p-polarized light is not reflected (Fp = 0). \
                     Critical angle asin(n2/n1), from the denser side: beyond it light is totally reflected.",
                );
            ComboBox::from_label("Fresnel")
                .selected_text(fresnel_label(p.fresnel))
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut p.fresnel, None, fresnel_label(None))
                        .hint("Keep each material's own reflectance model.");
                    for (mode, tip) in [
                        (FresnelMode::Exact, "R = (Fs² + Fp²)/2, Fs = (n1 cos θi − n2 cos θt)/(n1 cos θi + n2 cos θt), Fp = (n2 cos θi − n1 cos θt)/(n2 cos θi + n1 cos θt)."),
                        (FresnelMode::Schlick, "R ≈ R0 + (1 − R0)(1 − cos θ)^5, with θ on the less dense side, so it reaches 1 at the critical angle."),
                        (FresnelMode::SchlickNaive, "Schlick with the incident angle always, as some textbooks write it: from inside it stays near R0 until it jumps to 1 at the critical angle."),
                        (FresnelMode::Constant, "The same reflectance k at every angle: no brighter rim (the lecture's 'constant' black glazed sphere)."),
                    ] {
                        ui.selectable_value(&mut p.fresnel, Some(mode), fresnel_label(Some(mode))).hint(tip);
                    }
                })
                .response
                .hint(tip("fresnel"));
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
                ui.label(format!("n = {:.4} at 450 nm, {:.4} at 650 nm", n(450.0), n(650.0)))
                    .hint("Cauchy's n(λ) = A + B/λ², through n_d = IOR and the Abbe number.");
            }
            });
    });

    section(c.open, "Ray tree").default_open(true).show(ui, |ui| {
        ui.add(param_slider(&mut p.max_depth, "max_depth"))
            .hint(tip("max_depth"));
        // A path tracer follows one path and ends it by Russian roulette: the tree's
        // weight limit and branching do not apply.
        let tree = !p.transport.traces_paths();
        let no_tree = "Path tracing follows one path per sample (Russian roulette ends the faint ones): there is no tree to prune or split.";
        ui.add_enabled(tree, param_slider(&mut p.min_weight, "min_weight"))
            .hint(tip("min_weight"))
            .on_disabled_hover_text(no_tree);
        ui.add_enabled_ui(tree, |ui| {
            ui.horizontal(|ui| {
                ui.radio_value(&mut p.tree, TreeMode::Split, "Split")
                    .hint("At a dielectric, trace both the reflected ray (weight R) and the refracted ray (weight 1 − R): the whole ray tree.")
                    .on_disabled_hover_text(no_tree);
                ui.radio_value(&mut p.tree, TreeMode::Stochastic, "Stochastic")
                    .hint("Follow one branch, reflected with probability R: one path per sample. Same average, more noise, far fewer rays.")
                    .on_disabled_hover_text(no_tree);
            });
        });
        ComboBox::from_label("Light transport")
            .selected_text(transport_label(p.transport))
            .show_ui(ui, |ui| {
                for (t, hint) in [
                    (Transport::Whitted, "The lecture's tracer: a shadow ray stops at glass and water, so they cast black shadows."),
                    (Transport::TransmissiveShadows, "Shadow rays pass straight through glass and water, keeping 1 − R at each interface and exp(−σ d) inside: tinted shadows, though real glass would bend the light into caustics elsewhere."),
                    (Transport::Path, "Path tracing: light is gathered at every diffuse or glossy surface, by light samples and by the path itself finding lights (through glass too). Colour bleeding, sky light in shadows, caustics from area lights; not from point lights."),
                    (Transport::Photons, "Path tracing, plus photons from the point lights through glass and mirrors, gathered where they land: the caustics a path cannot find. Blurred at first, sharper with every pass."),
                ] {
                    ui.selectable_value(&mut p.transport, t, transport_label(t)).hint(hint);
                }
            })
            .response
            .hint(tip("transport"));
    });

    section(c.open, "Sampling and antialiasing")
        .default_open(true)
        .show(ui, |ui| {
            ui.add(param_slider(&mut p.spp, "spp")).hint(tip("spp"));
            ui.checkbox(c.unlimited, "Keep refining")
                .hint("Run on past the target, until paused.");
            ComboBox::from_label("Pattern")
                .selected_text(p.pattern.name())
                .show_ui(ui, |ui| {
                    for pattern in Pattern::ALL {
                        ui.selectable_value(&mut p.pattern, pattern, pattern.name())
                            .hint(pattern_tip(pattern));
                    }
                })
                .response
                .hint(pattern_tip(p.pattern));
            ui.horizontal(|ui| {
                ui.add(DragValue::new(&mut p.seed)).hint(tip("seed"));
                ui.label("Seed");
            });
        });

    section(c.open, "Soft shadows")
        .default_open(false)
        .show(ui, |ui| {
            ui.add(param_slider(&mut p.light_size, "light_size"))
                .hint(tip("light_size"));
        });

    section(c.open, "Glossy reflection")
        .default_open(false)
        .show(ui, |ui| {
            let own = scene_exponent(c.scene);
            let mut n = p.phong_exponent.or(own).unwrap_or(100.0);
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
        });

    section(c.open, "Camera and depth of field").default_open(true).show(ui, |ui| {
        ui.add(Slider::new(&mut c.camera.fov_deg, 5.0..=120.0).text("Field of view °"))
            .hint("The vertical angle the image spans.");
        ui.add(param_slider(&mut p.aperture, "aperture"))
            .hint(tip("aperture"));
        let f = c.camera.f_number(p.aperture).map_or("pinhole".to_string(), |n| format!("f/{n:.1}"));
        ui.label(format!("{f} (35 mm equivalent, 1 unit = 1 m)"));
        let own = c.camera.look_distance();
        let mut d = p.focus_distance.unwrap_or(own);
        if ui
            .add(param_slider(&mut d, "focus_distance"))
            .hint(tip("focus_distance"))
            .changed()
        {
            p.focus_distance = Some(d);
        }
        ui.horizontal(|ui| {
            ui.toggle_value(c.click_to_focus, "Click to focus")
                .hint("Then click the image: the focus distance becomes the depth of the point clicked.");
            if ui.add_enabled(p.focus_distance.is_some(), egui::Button::new("Look-at")).hint("Focus on the camera's look-at point.").clicked() {
                p.focus_distance = None;
            }
        });
        ui.label("Orbit: right-drag. Dolly: Ctrl + wheel.");
    });

    CollapsingHeader::new("Polariser")
        .default_open(false)
        // Kept open while a polariser is on, so the image never hides why it changed.
        .open((p.polarizer.is_some() || c.open.contains(&"Polariser")).then_some(true))
        .show(ui, |ui| {
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
                    ("Horizontal", 0.0, "Passes horizontally polarised light: the glare off a floor or water stays."),
                    ("Vertical", 90.0, "Passes vertically polarised light: the s-polarised glare off a floor or water at Brewster's angle is cut."),
                ] {
                    if ui.add_enabled(on, egui::Button::selectable(p.polarizer == Some(a), label)).hint(hint).clicked() {
                        p.polarizer = Some(a);
                    }
                }
            });
            ui.label(format!(
                "Brewster: {:.1}° on water, {:.1}° on glass",
                brewster_angle(1.0, 1.33).to_degrees(),
                brewster_angle(1.0, 1.5).to_degrees()
            ));
        });

    section(c.open, "Motion blur")
        .default_open(false)
        .show(ui, |ui| {
            ui.add(param_slider(&mut p.shutter_open, "shutter_open"))
                .hint(tip("shutter_open"));
            p.shutter = p.shutter.min(1.0 - p.shutter_open);
            let max = 1.0 - p.shutter_open;
            // The interval ends within the frame: the slider stops at 1 − opening.
            let label = spec("shutter").map_or("shutter", |s| s.label);
            ui.add(Slider::new(&mut p.shutter, 0.0..=max).text(label))
                .hint(tip("shutter"));
        });

    section(c.open, "Display").default_open(true).show(ui, |ui| {
        ui.add(param_slider(&mut p.exposure, "exposure"))
            .hint(tip("exposure"));
        ComboBox::from_label("Resolution")
            .selected_text(format!("{:.0}%", *c.resolution * 100.0))
            .show_ui(ui, |ui| {
                for r in [0.25f32, 0.5, 1.0, 2.0] {
                    ui.selectable_value(c.resolution, r, format!("{:.0}%", r * 100.0));
                }
            })
            .response
            .hint("Render resolution, as a fraction of the scene's image size. Lower is faster to refine.");
    });
}
