//! The previewer window, driven through its accessibility tree as a user would: by the
//! labels of its controls (egui_kittest, no display needed). Its instruments and its
//! lecture have files of their own (instruments.rs, lecture_window.rs).
// The window's own: built with the window (the `gui` feature) only.
#![cfg(feature = "gui")]

#[path = "common/window.rs"]
mod window;

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use raylab::app::{AppOptions, RaylabApp};
use raylab::optics::FresnelMode;
use raylab::render::{Sidecar, sidecar_path};
use std::path::Path;
use std::time::{Duration, Instant};
use window::{app, step_until};

#[test]
fn moving_the_ior_slider_sets_the_engines_ior_and_restarts_it() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("default", dir.path());
    step_until(&mut h, "the first frame", |a| a.latest_frame().is_some());
    let before = h.state().engine().generation();
    h.get_by_role_and_label(Role::Slider, "IOR")
        .set_value_accesskit(2.0);
    h.step();
    h.step();
    assert_eq!(h.state().engine().params().ior, Some(2.0));
    assert!(h.state().engine().generation() > before, "a new generation");
    // The preset buttons set it too, and Scene gives each material its own back.
    h.get_by_label("Water").click();
    h.step();
    h.step();
    assert_eq!(h.state().engine().params().ior, Some(1.33));
    h.get_by_label("Scene IOR").click();
    h.step();
    h.step();
    assert_eq!(h.state().engine().params().ior, None);
    // The frames that follow belong to the new generation.
    let generation = h.state().engine().generation();
    step_until(&mut h, "a frame of the new generation", |a| {
        a.latest_frame().is_some_and(|f| f.generation == generation)
    });
}

#[test]
fn switching_the_fresnel_mode() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("glazed", dir.path());
    h.step();
    assert_eq!(h.state().engine().params().fresnel, None);
    h.get_by_role_and_label(Role::ComboBox, "Fresnel").click();
    h.run_steps(3);
    h.get_by_label("Schlick").click();
    h.step();
    h.step();
    assert_eq!(
        h.state().engine().params().fresnel,
        Some(FresnelMode::Schlick)
    );
    h.get_by_role_and_label(Role::ComboBox, "Fresnel").click();
    h.run_steps(3);
    h.get_by_label("constant k").click();
    h.step();
    h.step();
    assert_eq!(
        h.state().engine().params().fresnel,
        Some(FresnelMode::Constant)
    );
}

#[test]
fn save_writes_the_png_and_a_sidecar_with_the_right_parameters() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("default", dir.path());
    h.get_by_role_and_label(Role::Slider, "Max depth")
        .set_value_accesskit(3.0);
    h.run_steps(2);
    let generation = h.state().engine().generation();
    step_until(&mut h, "the finished image", |a| {
        a.latest_frame()
            .is_some_and(|f| f.generation == generation && f.progress.done())
    });
    h.get_by_label("Save snapshot").click();
    h.step();
    // Written on a thread of its own: the window goes on meanwhile, and says when.
    assert!(h.state().saving());
    step_until(&mut h, "the snapshot written", |a| !a.saving());
    let files: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .collect();
    let png = files
        .iter()
        .find(|p| p.extension().is_some_and(|e| e == "png"))
        .expect("a PNG");
    assert!(
        png.file_name()
            .unwrap()
            .to_string_lossy()
            .starts_with("default-")
    );
    let sidecar = Sidecar::read(&sidecar_path(png)).unwrap();
    assert_eq!(sidecar.scene, "builtin:default");
    assert_eq!(sidecar.params.max_depth, 3);
    assert_eq!(&sidecar.params, h.state().engine().params());
    assert_eq!((sidecar.width, sidecar.height), (960, 540));
    assert!(h.state().toasts().iter().any(|t| t.starts_with("Saved")));
    let img = image::open(png).unwrap();
    assert_eq!((img.width(), img.height()), (960, 540));
}

#[test]
fn a_window_closed_just_after_ctrl_s_still_writes_the_snapshot_whole() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("default", dir.path());
    step_until(&mut h, "a full frame", |a| {
        a.latest_frame().is_some_and(|f| !f.is_preview())
    });
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    h.step();
    assert!(h.state().saving());
    // Closed before the writing thread is done: the window waits for it.
    drop(h);
    let png = std::fs::read_dir(dir.path())
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .find(|p| p.extension().is_some_and(|e| e == "png"))
        .expect("a PNG");
    let img = image::open(&png).expect("a whole PNG");
    assert_eq!((img.width(), img.height()), (960, 540));
    assert!(Sidecar::read(&sidecar_path(&png)).is_ok());
}

#[test]
fn a_failed_save_says_so_and_keeps_the_image() {
    let dir = tempfile::tempdir().unwrap();
    // A file where the snapshot folder should be: nothing can be written there.
    let blocked = dir.path().join("not-a-folder");
    std::fs::write(&blocked, b"").unwrap();
    let mut h = app("default", &blocked);
    step_until(&mut h, "a full frame", |a| {
        a.latest_frame().is_some_and(|f| !f.is_preview())
    });
    h.get_by_label("Save snapshot").click();
    h.step();
    step_until(&mut h, "the snapshot tried", |a| !a.saving());
    assert!(
        h.state()
            .toasts()
            .iter()
            .any(|t| t.starts_with("Not saved")),
        "{:?}",
        h.state().toasts()
    );
    assert!(h.state().latest_frame().is_some());
}

#[test]
fn save_as_asks_before_replacing_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let mine = dir.path().join("mine.png");
    std::fs::write(&mine, b"the user's own").unwrap();
    let mut h = app("default", dir.path());
    step_until(&mut h, "a full frame", |a| {
        a.latest_frame().is_some_and(|f| !f.is_preview())
    });
    h.get_by_label("Save as…").click();
    h.run_steps(3);
    // The places to go: the home folder at least, and the root or the drives.
    h.get_by_label("Home");
    // Picking the existing file and saving asks first; keeping it leaves it alone.
    h.get_by_label("mine.png").click();
    h.run_steps(2);
    h.get_by_label("Save").click();
    h.run_steps(3);
    let question = "mine.png exists. Replace it (and its sidecar)?";
    h.get_by_label(question);
    h.get_by_label("Keep it").click();
    h.run_steps(3);
    assert!(h.query_by_label(question).is_none());
    assert_eq!(std::fs::read(&mine).unwrap(), b"the user's own");
    // Asked again, replacing writes the image and its sidecar.
    h.get_by_label("Save").click();
    h.run_steps(3);
    h.get_by_label("Replace").click();
    h.run_steps(3);
    step_until(&mut h, "the snapshot written", |a| !a.saving());
    assert!(image::open(&mine).is_ok(), "a PNG now");
    assert!(dir.path().join("mine.png.json").is_file());
}

#[test]
fn a_bad_scene_shows_its_error_and_keeps_the_old_scene() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 0]\n[[sphere]]\ncenter = [0, 1, 0]\nradius = -2\n").unwrap();
    // A 720p laptop's window, an instrument open beside the image.
    let mut h = window::app_sized("default", dir.path(), (1280.0, 720.0));
    h.step();
    window::choose_from_menu(&mut h, "Instruments", "Fresnel plot");
    h.key_press(egui::Key::Escape);
    h.state_mut().open_scene(bad.to_str().unwrap());
    step_until(&mut h, "the load to finish", |a| !a.is_loading());
    let error = h.state().error().expect("an error").to_string();
    assert!(
        error.ends_with("bad.toml:6:10: must be greater than 0 and at most 1e6, got -2"),
        "{error}"
    );
    // Shown in the window, whole and with its button, left of the dock (it ran under
    // it); and the old scene still there.
    let dock = h.get_by_label("Fresnel plot").rect().left();
    for node in [h.get_by_label(&error), h.get_by_label("Dismiss")] {
        let r = node.rect();
        assert!(r.right() <= dock, "{r:?} under the dock at {dock}");
    }
    assert_eq!(h.state().scene().name, "default");
    // Fixing the file opens it (the failed file is watched).
    std::thread::sleep(Duration::from_millis(1100));
    std::fs::write(&bad, "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 0]\n[[sphere]]\ncenter = [0, 1, 0]\nradius = 2\n").unwrap();
    step_until(&mut h, "the fixed scene", |a| a.scene().name == "bad");
    assert_eq!(h.state().error(), None);
}

#[test]
fn a_scene_whose_files_lack_something_opens_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("lost.obj");
    std::fs::write(
        &obj,
        "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    let warned = |a: &RaylabApp| {
        a.toasts()
            .iter()
            .any(|t| t.starts_with("Warning: ") && t.contains("`gone.mtl`"))
    };
    // Opened first, and opened later.
    let mut h = window::app(obj.to_str().unwrap(), dir.path());
    h.step();
    assert!(warned(h.state()), "{:?}", h.state().toasts());
    let mut h = app("default", dir.path());
    h.step();
    assert!(!warned(h.state()));
    h.state_mut().open_scene(&obj);
    step_until(&mut h, "the warning", warned);
    assert_eq!(h.state().scene().name, "lost");
}

#[test]
fn space_pauses_and_reset_restores_the_scene_defaults() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("default", dir.path());
    step_until(&mut h, "a full frame", |a| {
        a.latest_frame().is_some_and(|f| !f.is_preview())
    });
    h.key_press(egui::Key::Space);
    h.step();
    step_until(&mut h, "the pause", |a| {
        a.latest_frame().is_some_and(|f| f.progress.paused)
    });
    h.get_by_label("Resume");
    // The section is folded at first: open it, as a user would.
    h.get_by_label("Soft shadows").click();
    h.step();
    h.get_by_role_and_label(Role::Slider, "Light size")
        .set_value_accesskit(3.0);
    h.step();
    assert_eq!(h.state().params().light_size, 3.0);
    h.get_by_label("Reset").click();
    h.step();
    assert_eq!(h.state().params(), &h.state().scene().params);
}

#[test]
fn every_label_and_formula_tooltip_draws_with_the_bundled_fonts() {
    // egui's test harness refuses to draw a glyph its fonts lack: showing every section,
    // the tooltips with formulas, the dialogs and the scene list finds any.
    let dir = tempfile::tempdir().unwrap();
    // A scene with glass and glazes: without them the dielectric controls are off, and
    // a control that is off shows no tooltip.
    let mut h = app("metals", dir.path());
    h.step();
    for section in [
        "Soft shadows",
        "Glossy reflection",
        "Polariser",
        "Motion blur",
    ] {
        h.get_by_label(section).scroll_to_me();
        h.run_steps(3);
        h.get_by_label(section).click();
        h.step();
    }
    // Every parameter the table gives a slider has one in the panel, under the table's
    // label (a name the panel misspelt would show the raw name instead).
    for spec in raylab::params::TABLE.iter().filter(|s| s.slider.is_some()) {
        h.get_by_role_and_label(Role::Slider, spec.label);
    }
    // Each control's tooltip, found by a phrase of it, with its formula's glyphs.
    let tooltip = |h: &mut Harness<'static, RaylabApp>, phrase: &str| {
        h.run_steps(40);
        assert!(
            h.query_all_by_label_contains(phrase).next().is_some(),
            "no tooltip saying `{phrase}`"
        );
    };
    for (slider, phrase) in [
        ("IOR", "n1 sin θi = n2 sin θt"),
        ("Min weight", "Pruning by attenuation"),
        ("Samples per pixel", "falls like 1/√n"),
        ("Focus distance", "2a|z − s|/s"),
        ("Aperture", "Thin lens"),
        ("Light size", "similar triangles"),
        ("Phong exponent", "cos^n α"),
        ("Shutter interval", "freezes them"),
        ("Exposure (stops)", "2^exposure"),
        ("Absorption ×", "exp(−σ d)"),
        ("Max depth", "Pruning by depth"),
        ("Abbe number", "n(λ) = A + B/λ²"),
    ] {
        // The panel scrolls on a small window: bring the slider into view, as a user would.
        h.get_by_role_and_label(Role::Slider, slider).scroll_to_me();
        h.run_steps(3);
        h.get_by_role_and_label(Role::Slider, slider).hover();
        tooltip(&mut h, phrase);
    }
    h.get_by_role_and_label(Role::ComboBox, "Fresnel").click();
    h.run_steps(3);
    for (mode, phrase) in [
        ("exact (Fs, Fp)", "R = (Fs² + Fp²)/2"),
        ("Schlick", "(1 − R0)(1 − cos θ)^5"),
        ("naive Schlick", "jumps to 1"),
        ("constant k", "no brighter rim"),
    ] {
        h.get_by_label(mode).hover();
        tooltip(&mut h, phrase);
    }
    h.key_press(egui::Key::Escape);
    h.run_steps(3);
    h.get_by_role_and_label(Role::ComboBox, "Pattern").click();
    h.run_steps(3);
    h.get_by_label("jittered").hover();
    h.run_steps(40);
    h.key_press(egui::Key::Escape);
    h.run_steps(3);
    // The scene list, then Open… and Save as….
    h.get_by_role_and_label(Role::ComboBox, "Scene").click();
    h.run_steps(3);
    h.get_by_label("Open…").scroll_to_me();
    h.run_steps(3);
    h.get_by_label("Open…").click();
    h.run_steps(3);
    h.get_by_label("Open a scene or model");
    h.get_by_label("Cancel").click();
    h.run_steps(3);
    h.get_by_label("Save as…").click();
    h.run_steps(3);
    h.get_by_label("Save the image as…");
    h.get_by_label("Cancel").click();
    h.run_steps(3);
}

#[test]
fn the_status_bar_reads_out_the_pixel_under_the_cursor_and_the_zoom() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("default", dir.path());
    step_until(&mut h, "a full pass", |a| {
        a.latest_frame().is_some_and(|f| !f.is_preview())
    });
    // The zoom level of the fitted image.
    h.query_all_by_label_contains("zoom ")
        .next()
        .expect("the zoom level is shown");
    // Hover over the middle of the window's central area: the image is fitted there.
    h.hover_at(egui::pos2(800.0, 400.0));
    h.run_steps(2);
    let readout = h
        .query_all_by_label_contains(" lin ")
        .next()
        .expect("the pixel readout")
        .accesskit_node()
        .value()
        .unwrap_or_default();
    // "(x, y) lin r g b · sRGB R G B", and x, y inside the image.
    let numbers: Vec<f32> = readout
        .split(|c: char| !(c.is_ascii_digit() || c == '.'))
        .filter(|t| !t.is_empty())
        .filter_map(|t| t.parse().ok())
        .collect();
    assert_eq!(numbers.len(), 8, "{readout}");
    let frame = h.state().latest_frame().unwrap();
    assert!(numbers[0] < frame.width as f32 && numbers[1] < frame.height as f32);
    let pixel = frame.pixels[(numbers[1] as u32 * frame.width + numbers[0] as u32) as usize];
    assert!(
        (numbers[2] - pixel.x).abs() < 1e-3,
        "{readout} against {pixel}"
    );
}

#[test]
fn ctrl_z_undoes_a_parameter_change_and_ctrl_shift_z_redoes_it() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("default", dir.path());
    h.run_steps(2);
    h.get_by_role_and_label(Role::Slider, "IOR")
        .set_value_accesskit(2.0);
    h.run_steps(3);
    assert_eq!(h.state().params().ior, Some(2.0));
    h.get_by_label("Water").click();
    h.run_steps(3);
    assert_eq!(h.state().params().ior, Some(1.33));
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(3);
    assert_eq!(h.state().params().ior, Some(2.0), "undo: back to 2.0");
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(3);
    assert_eq!(h.state().params().ior, None, "undo again: the scene's own");
    assert_eq!(
        h.state().engine().params().ior,
        None,
        "and the engine follows"
    );
    h.key_press_modifiers(
        egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
        egui::Key::Z,
    );
    h.run_steps(3);
    assert_eq!(h.state().params().ior, Some(2.0), "redo");
    // The toolbar's buttons do the same.
    h.get_by_label("Undo").click();
    h.run_steps(3);
    assert_eq!(h.state().params().ior, None);
    h.get_by_label("Redo").click();
    h.run_steps(3);
    assert_eq!(h.state().params().ior, Some(2.0));
}

#[test]
fn dielectric_controls_show_the_scenes_values_and_rest_without_glass() {
    let dir = tempfile::tempdir().unwrap();
    // The glazed scene's constant sphere has k = 0.10: the slider says so.
    let mut h = app("glazed", dir.path());
    h.run_steps(3);
    let k = h
        .get_by_role_and_label(Role::Slider, "k (constant)")
        .accesskit_node()
        .numeric_value();
    assert_eq!(k, Some(0.1f32 as f64));
    // Soft shadows has no glass, water or glaze: the IOR slider is off, with a reason.
    let mut h = app("soft-shadows", dir.path());
    h.run_steps(3);
    assert!(
        h.get_by_role_and_label(Role::Slider, "IOR")
            .accesskit_node()
            .is_disabled()
    );
    h.get_by_label("No glass, water or glaze in this scene.");
}

#[test]
fn a_sliders_tooltip_shows_on_hover_but_not_while_it_is_dragged() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("glass", dir.path());
    h.run_steps(3);
    let tip = raylab::params::TABLE
        .iter()
        .find(|s| s.name == "ior")
        .unwrap()
        .tooltip();
    let slider = h.get_by_role_and_label(Role::Slider, "IOR").rect();
    let (from, to) = (slider.left_center(), slider.center());
    // Resting on the slider shows its explanation (each step is a quarter second).
    h.hover_at(from);
    h.run_steps(6);
    assert!(
        h.query_by_label(&tip).is_some(),
        "the tooltip shows on hover"
    );
    // Pressed there, dragged and held still: the tooltip goes, and the readouts beside
    // the slider stay in view.
    h.event(egui::Event::PointerButton {
        pos: from,
        button: egui::PointerButton::Primary,
        pressed: true,
        modifiers: egui::Modifiers::NONE,
    });
    h.run_steps(1);
    h.hover_at(to);
    h.run_steps(8);
    assert!(h.query_by_label(&tip).is_none(), "no tooltip mid-drag");
    h.event(egui::Event::PointerButton {
        pos: to,
        button: egui::PointerButton::Primary,
        pressed: false,
        modifiers: egui::Modifiers::NONE,
    });
    h.run_steps(2);
    let ior = h.state().params().ior;
    assert!(
        ior.is_some_and(|n| n > 1.2),
        "the drag moved the IOR: {ior:?}"
    );
}

#[test]
fn a_drag_on_a_refined_image_shows_within_one_frame() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("glass", dir.path());
    step_until(&mut h, "the target reached", |a| {
        a.latest_frame()
            .is_some_and(|f| f.progress.done() && !f.is_preview())
    });
    let before = h.state().engine().generation();
    // The frame in which the slider moves tells the engine at once...
    h.get_by_role_and_label(Role::Slider, "IOR")
        .set_value_accesskit(1.7);
    h.step();
    let generation = h.state().engine().generation();
    assert!(generation > before, "the move started a new image");
    // ...so the engine's first preview waits for the very next frame, which shows it.
    let deadline = Instant::now() + Duration::from_secs(20);
    while h.state().engine().frames().is_empty() {
        assert!(Instant::now() < deadline, "no preview came");
        std::thread::sleep(Duration::from_millis(2));
    }
    h.step();
    let shown = h.state().latest_frame().unwrap();
    assert_eq!(
        shown.generation, generation,
        "the next frame shows the new image"
    );
}

#[test]
fn small_things_a_first_user_sees() {
    let dir = tempfile::tempdir().unwrap();
    // The scene picker lists a shipped scene once (built in), and a scene file the user
    // changed as a file.
    let scenes = dir.path().join("scenes");
    std::fs::create_dir(&scenes).unwrap();
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    std::fs::copy(repo.join("glass.toml"), scenes.join("glass.toml")).unwrap();
    let edited = std::fs::read_to_string(repo.join("tir.toml")).unwrap() + "\n# mine\n";
    std::fs::write(scenes.join("tir.toml"), edited).unwrap();
    let options = AppOptions {
        scene: Some("default".into()),
        snapshot_dir: dir.path().to_path_buf(),
        scenes_dir: scenes.clone(),
        threads: Some(1),
        // As on a first run: nothing remembered.
        persist: true,
        ..Default::default()
    };
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_eframe(move |cc| RaylabApp::new(cc, options.clone()).expect("the engine starts"));
    h.step();
    assert!(
        h.state()
            .toasts()
            .iter()
            .any(|t| t.contains("F5 presents them")),
        "the first run says where the lecture is: {:?}",
        h.state().toasts()
    );
    h.get_by_role_and_label(Role::ComboBox, "Scene").click();
    h.run_steps(3);
    let shown = |h: &Harness<'static, RaylabApp>, file: &str| {
        h.query_all_by_label_contains(file).next().is_some()
    };
    assert!(
        !shown(&h, "glass.toml"),
        "a shipped copy is listed as built in only"
    );
    assert!(shown(&h, "tir.toml"), "a changed scene file is listed");
    h.key_press(egui::Key::Escape);
    // The default scene's target reads as clean (its noise ends under 2 %).
    step_until(&mut h, "the target reached", |a| {
        a.latest_frame().is_some_and(|f| f.progress.done())
    });
    h.run_steps(2);
    assert!(h.query_all_by_label_contains("(clean)").next().is_some());
}
