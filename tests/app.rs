//! The previewer window, driven through its accessibility tree as a user would: by the
//! labels of its controls (egui_kittest, no display needed).

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use raylab::app::{AppOptions, RaylabApp};
use raylab::lecture::LECTURE;
use raylab::optics::FresnelMode;
use raylab::render::{Sidecar, sidecar_path, to_srgba8};
use std::path::Path;
use std::time::{Duration, Instant};

fn app(scene: &str, snapshots: &Path) -> Harness<'static, RaylabApp> {
    let options = AppOptions {
        scene: Some(scene.to_string()),
        snapshot_dir: snapshots.to_path_buf(),
        threads: Some(1),
        persist: false,
        ..Default::default()
    };
    Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_eframe(move |cc| RaylabApp::new(cc, options.clone()).expect("the engine starts"))
}

/// Steps the UI until `done` holds, with the workers rendering in between.
fn step_until(h: &mut Harness<'static, RaylabApp>, what: &str, done: impl Fn(&RaylabApp) -> bool) {
    let deadline = Instant::now() + Duration::from_secs(30);
    while !done(h.state()) {
        assert!(
            Instant::now() < deadline,
            "timed out waiting for {what} (slide {:?}, loading {}, scene {}, caption {})",
            h.state().slide(),
            h.state().is_loading(),
            h.state().scene().source.reference(),
            h.state().caption().is_some()
        );
        h.step();
        std::thread::sleep(Duration::from_millis(5));
    }
    h.step();
}

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
    assert!(image::open(&mine).is_ok(), "a PNG now");
    assert!(dir.path().join("mine.png.json").is_file());
}

#[test]
fn a_bad_scene_shows_its_error_and_keeps_the_old_scene() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 0]\n[[sphere]]\ncenter = [0, 1, 0]\nradius = -2\n").unwrap();
    let mut h = app("default", dir.path());
    h.step();
    h.state_mut().open_scene(bad.to_str().unwrap());
    step_until(&mut h, "the load to finish", |a| !a.is_loading());
    let error = h.state().error().expect("an error").to_string();
    assert!(
        error.ends_with("bad.toml:6:10: must be greater than 0 and at most 1e6, got -2"),
        "{error}"
    );
    // Shown in the window, and the old scene still there.
    h.get_by_label(&error);
    assert_eq!(h.state().scene().name, "default");
    // Fixing the file opens it (the failed file is watched).
    std::thread::sleep(Duration::from_millis(1100));
    std::fs::write(&bad, "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 0]\n[[sphere]]\ncenter = [0, 1, 0]\nradius = 2\n").unwrap();
    step_until(&mut h, "the fixed scene", |a| a.scene().name == "bad");
    assert_eq!(h.state().error(), None);
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
fn the_inspector_shows_the_tree_of_the_clicked_pixel() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("glass", dir.path());
    step_until(&mut h, "a full frame", |a| {
        a.latest_frame().is_some_and(|f| !f.is_preview())
    });
    h.get_by_label("Instruments").click();
    h.run_steps(3);
    h.get_by_label("Ray-tree inspector: click a pixel").click();
    h.run_steps(3);
    h.key_press(egui::Key::Escape);
    h.run_steps(3);
    // Click the glass sphere: a little left of the image's centre, above the middle. The
    // image lies between the controls and the instruments' dock.
    // The controls panel is 320 points wide; the dock starts left of its heading.
    let left = 320.0;
    let right = h.get_by_label("Ray-tree inspector").rect().min.x - 8.0;
    let shown_width = right - left;
    let centre = egui::pos2(
        (left + right) / 2.0 - 0.05 * shown_width,
        800.0 / 2.0 - 0.11 * shown_width * 9.0 / 16.0,
    );
    click_at(&mut h, centre);
    h.run_steps(1);
    let tree = h.state().inspected_tree().expect("a tree");
    let root = &tree.nodes[0];
    let hit = root.hit.expect("the camera ray hits something");
    assert_eq!(
        h.state().scene().object_names[hit.object as usize],
        "glass sphere"
    );
    assert_eq!(hit.n1_n2, Some((1.0, 1.5)));
    h.get_by_label("Camera ray, level 0: glass sphere (glass) — split into child rays");
    // Moving the IOR re-inspects the same pixel.
    h.get_by_role_and_label(Role::Slider, "IOR")
        .set_value_accesskit(2.0);
    h.run_steps(3);
    let hit = h.state().inspected_tree().unwrap().nodes[0].hit.unwrap();
    assert_eq!(hit.n1_n2, Some((1.0, 2.0)));
    // The Fresnel plot opens from the same menu.
    h.get_by_label("Instruments").click();
    h.run_steps(3);
    h.get_by_label("Fresnel plot").click();
    h.run_steps(3);
    // Both directions at once: into the glass, and out of it, where the critical angle
    // for n = 2.0 is asin(1/2) = 30°.
    h.get_by_label("Air into material");
    h.get_by_label("Material out to air");
    h.query_all_by_label_contains("critical 30.00°")
        .next()
        .expect("the critical angle for n = 2");
}

#[test]
fn a_lecture_slide_loads_its_scene_parameters_and_caption() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("default", dir.path());
    h.step();
    h.get_by_label("Lecture").click();
    h.run_steps(3);
    let n = LECTURE
        .iter()
        .position(|s| s.title == "Pruning the ray tree")
        .unwrap();
    h.get_by_label(&format!("{}. Pruning the ray tree", n + 1))
        .click();
    h.run_steps(2);
    step_until(&mut h, "the slide's scene", |a| {
        a.scene().name == "ray-tree"
    });
    assert_eq!(h.state().params().max_depth, 2);
    assert!(h.state().caption().unwrap().contains("depth 2"));
    // Sample patterns for the slide's settings.
    h.get_by_label("Instruments").click();
    h.run_steps(3);
    h.get_by_label("Sample patterns").click();
    h.run_steps(3);
    h.get_by_label("Point on the lens");
}

#[test]
fn a_b_compare_renders_both_sides() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("glazed", dir.path());
    h.step();
    h.get_by_label("Instruments").click();
    h.run_steps(3);
    h.get_by_label("A/B compare").click();
    h.run_steps(3);
    h.get_by_label("constant | Fresnel").click();
    h.run_steps(3);
    assert_eq!(
        h.state().params().fresnel,
        Some(FresnelMode::Constant),
        "side A"
    );
    let (b, _) = h.state().compare_side_b().expect("the A/B view is on");
    assert_eq!(b.fresnel, Some(FresnelMode::Exact), "side B");
    step_until(&mut h, "both sides to finish", |a| {
        a.latest_frame().is_some_and(|f| f.progress.done())
            && a.compare_side_b()
                .is_some_and(|(_, f)| f.is_some_and(|f| f.progress.done()))
    });
    // The two sides differ only in the Fresnel model: the same light, other reflections.
    let a = h.state().latest_frame().unwrap().pixels.clone();
    let b = h
        .state()
        .compare_side_b()
        .unwrap()
        .1
        .unwrap()
        .pixels
        .clone();
    assert_eq!(a.len(), b.len());
    assert!(a.iter().zip(b.iter()).any(|(x, y)| x != y));
    // Other controls move both sides.
    h.get_by_role_and_label(Role::Slider, "Max depth")
        .set_value_accesskit(2.0);
    h.run_steps(3);
    assert_eq!(h.state().compare_side_b().unwrap().0.max_depth, 2);
    // So do the resolution and the scene.
    h.get_by_role_and_label(Role::ComboBox, "Resolution")
        .click();
    h.run_steps(3);
    h.get_by_label("25%").click();
    h.run_steps(3);
    step_until(&mut h, "both sides at 25%", |a| {
        let quarter = |f: &raylab::render::Frame| (f.width, f.height) == (240, 135);
        a.latest_frame().is_some_and(quarter)
            && a.compare_side_b()
                .is_some_and(|(_, f)| f.is_some_and(quarter))
    });
    h.state_mut().open_scene("glass");
    step_until(&mut h, "the new scene", |a| a.scene().name == "glass");
    step_until(
        &mut h,
        "side B finished on it",
        RaylabApp::compare_side_b_settled,
    );
    let (b, frame) = h.state().compare_side_b().unwrap();
    let (b, frame) = (b.clone(), frame.unwrap().clone());
    assert_eq!(b.fresnel, Some(FresnelMode::Exact));
    assert_eq!(
        h.state().params().fresnel,
        Some(FresnelMode::Constant),
        "side A keeps its side"
    );
    let glass = raylab::scene::Scene::load("glass").unwrap();
    let expected: Vec<_> = raylab::render::render(&glass, &b, 240, 135, &())
        .unwrap()
        .0
        .pixels()
        .collect();
    assert!(
        *frame.pixels == expected,
        "side B renders the scene opened, with its parameters"
    );
}

#[test]
fn the_contact_sheet_button_saves_a_sheet() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("glazed", dir.path());
    h.step();
    h.get_by_label("Instruments").click();
    h.run_steps(3);
    h.get_by_label("Contact sheet…").click();
    h.run_steps(3);
    h.get_by_label("Render sheet").click();
    h.run_steps(2);
    step_until(&mut h, "the sheet", |a| {
        a.toasts().iter().any(|t| t.contains("contact sheet"))
    });
    let sheet = std::fs::read_dir(dir.path())
        .unwrap()
        .flatten()
        .find(|e| e.file_name().to_string_lossy().contains("-sweep-spp-"))
        .expect("the sheet file");
    let img = image::open(sheet.path()).unwrap();
    // Three tiles of half the scene's 960×540.
    assert_eq!(img.width(), 3 * 480 + 4 * 8);
}

#[test]
fn the_cost_heat_map_shows_rays_per_sample() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("ray-tree", dir.path());
    step_until(&mut h, "a full frame", |a| {
        a.latest_frame().is_some_and(|f| !f.is_preview())
    });
    h.get_by_label("Instruments").click();
    h.run_steps(3);
    h.get_by_label("Cost heat map").click();
    h.run_steps(3);
    h.key_press(egui::Key::Escape);
    h.run_steps(2);
    let frame = h.state().latest_frame().unwrap();
    let max = frame.cost.iter().cloned().fold(0.0f32, f32::max);
    assert!(
        max > 4.0,
        "glass spheres make deep trees: {max} rays per sample"
    );
    // The image shown is the heat map: not the render, and brighter where rays cost more
    // (black through purple, red and orange to pale yellow).
    let exposure = h.state().params().exposure;
    let shown = h.state().shown_pixels().to_vec();
    assert_eq!(shown.len(), 4 * frame.cost.len());
    assert_ne!(shown, to_srgba8(&frame.pixels, exposure));
    let mut by_cost: Vec<(f32, u32)> = frame
        .cost
        .iter()
        .zip(shown.chunks(4))
        .map(|(&c, p)| (c, p[..3].iter().map(|&v| v as u32).sum()))
        .collect();
    by_cost.sort_by(|a, b| a.0.total_cmp(&b.0));
    for w in by_cost.windows(2) {
        // Each channel is rounded on its own: the sum may step back by a unit or two.
        assert!(
            w[1].1 + 2 >= w[0].1,
            "cost {} then {}: {w:?}",
            w[0].0,
            w[1].0
        );
    }
    let (cheapest, dearest) = (by_cost[0], by_cost[by_cost.len() - 1]);
    assert!(dearest.1 > cheapest.1 + 200, "{cheapest:?} {dearest:?}");
    assert!(
        h.query_all_by_label_contains("rays/sample")
            .next()
            .is_some(),
        "the heat map's scale in the status bar"
    );
    // One fixed scale, 0 to 32 by default: pruning the tree changes the colours' costs,
    // not the scale.
    let scale = |h: &Harness<'static, RaylabApp>| {
        h.query_all_by_label_contains(" rays/sample")
            .next()
            .and_then(|n| n.accesskit_node().value())
            .unwrap_or_default()
    };
    assert_eq!(scale(&h), "cost 0–32 rays/sample");
    let max_before = max;
    h.get_by_role_and_label(Role::Slider, "Max depth")
        .set_value_accesskit(2.0);
    h.run_steps(2);
    let generation = h.state().engine().generation();
    step_until(&mut h, "a frame at depth 2", |a| {
        a.latest_frame()
            .is_some_and(|f| f.generation == generation && !f.is_preview())
    });
    let frame = h.state().latest_frame().unwrap();
    let max = frame.cost.iter().cloned().fold(0.0f32, f32::max);
    assert!(
        max < max_before,
        "a shallower tree costs less: {max} against {max_before}"
    );
    assert_eq!(scale(&h), "cost 0–32 rays/sample");
    // Off again, the render is shown.
    h.get_by_label("Instruments").click();
    h.run_steps(3);
    h.get_by_label("Cost heat map").click();
    h.run_steps(3);
    let frame = h.state().latest_frame().unwrap();
    assert_eq!(
        h.state().shown_pixels(),
        to_srgba8(&frame.pixels, h.state().params().exposure)
    );
}

/// Opens the toolbar menu `menu` and clicks its entry `item`, once the menu shows it (a
/// scene still loading can hold the menu's first frames back).
fn choose_from_menu(h: &mut Harness<'static, RaylabApp>, menu: &str, item: &str) {
    for _ in 0..20 {
        if h.query_by_label(item).is_none() {
            h.get_by_label(menu).click();
            h.run_steps(3);
        }
        if let Some(entry) = h.query_by_label(item) {
            entry.click();
            h.run_steps(2);
            return;
        }
    }
    panic!("the {menu} menu never showed `{item}`");
}

/// Steps until slide `i` is shown: its scene loaded, its caption up.
fn wait_for_slide(h: &mut Harness<'static, RaylabApp>, i: usize) {
    let (title, scene) = (LECTURE[i].title, LECTURE[i].scene);
    step_until(h, title, |a| {
        // Not loading: a slide on the scene already shown must still arrive.
        !a.is_loading()
            && a.slide() == Some(i)
            && a.scene().source.reference() == format!("builtin:{scene}")
            && a.caption().is_some()
    });
}

#[test]
fn presentation_mode_steps_through_the_slides_with_a_clickers_keys() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("default", dir.path());
    h.step();
    let shows = wait_for_slide;
    h.key_press(egui::Key::F5);
    h.step();
    assert!(h.state().presenting(), "F5 enters presentation mode");
    // The toolbar and the controls are hidden.
    assert!(h.query_by_label("Instruments").is_none());
    assert!(h.query_by_role_and_label(Role::Slider, "IOR").is_none());
    h.key_press(egui::Key::PageDown);
    shows(&mut h, 0);
    h.key_press(egui::Key::ArrowRight);
    shows(&mut h, 1);
    h.key_press(egui::Key::PageUp);
    shows(&mut h, 0);
    // Before the first slide there is none: Page Up stays.
    h.key_press(egui::Key::ArrowLeft);
    h.run_steps(3);
    assert_eq!(h.state().slide(), Some(0));
    // Three presses that land in one frame (a quick clicker, xdotool) step three slides.
    // (The harness's own key_press gives each event a frame of its own.)
    let three_in_one_frame = |h: &mut Harness<'static, RaylabApp>, key| {
        for pressed in [true, true, true, false] {
            h.input_mut().events.push(egui::Event::Key {
                key,
                pressed,
                modifiers: egui::Modifiers::NONE,
                repeat: false,
                physical_key: None,
            });
        }
        h.step();
    };
    three_in_one_frame(&mut h, egui::Key::PageDown);
    assert_eq!(h.state().slide(), Some(3));
    shows(&mut h, 3);
    three_in_one_frame(&mut h, egui::Key::PageUp);
    assert_eq!(h.state().slide(), Some(0));
    shows(&mut h, 0);
    // The caption is on screen, in the strip below the image.
    let caption = h.state().caption().unwrap().to_string();
    h.get_by_label(&caption);
    h.key_press(egui::Key::Escape);
    h.step();
    assert!(!h.state().presenting(), "Esc leaves");
    h.get_by_label("Instruments");
}

#[test]
fn f1_lists_every_shortcut_and_esc_closes_the_list() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("default", dir.path());
    h.step();
    h.key_press(egui::Key::F1);
    h.run_steps(2);
    assert!(h.state().help_open());
    h.get_by_label("Keyboard shortcuts");
    h.get_by_label("F5 or F11");
    h.get_by_label("Page Down, Right or Down arrow");
    h.key_press(egui::Key::Escape);
    h.run_steps(2);
    assert!(!h.state().help_open());
    assert!(h.query_by_label("F5 or F11").is_none());
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

/// Whether `text` names the control `label` as the panel writes it (a whole word or
/// words, same case: "raise Max depth", not "the ray tree").
fn names(text: &str, label: &str) -> bool {
    text.match_indices(label).any(|(i, _)| {
        let before = text[..i].chars().next_back();
        let after = text[i + label.len()..].chars().next();
        !before.is_some_and(char::is_alphanumeric) && !after.is_some_and(char::is_alphanumeric)
    })
}

#[test]
fn every_slide_loads_and_its_caption_names_only_controls_in_view() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("default", dir.path());
    h.step();
    for (i, slide) in LECTURE.iter().enumerate() {
        let (title, sides) = (slide.title, slide.compare);
        choose_from_menu(&mut h, "Lecture", &format!("{}. {title}", i + 1));
        wait_for_slide(&mut h, i);
        h.run_steps(3);
        assert_eq!(
            h.state().compare_side_b().is_some(),
            sides.is_some(),
            "{title}: the A/B view as the slide says"
        );
        // The slides about reflectance against angle show the Fresnel plot; no other.
        let plotted = title.starts_with("Reflectance against angle")
            || title.starts_with("Fresnel's formulas");
        assert_eq!(
            h.query_by_label("Fresnel plot").is_some(),
            plotted,
            "{title}: the Fresnel plot as the slide needs"
        );
        // Its instruments sit in the dock beside the image, clear of it and of the
        // controls (the IOR slider the Fresnel plot follows among them).
        let image = h.get_by_label("Image").rect();
        let ior = h.get_by_role_and_label(Role::Slider, "IOR").rect();
        for instrument in ["Fresnel plot", "Ray-tree inspector"] {
            for node in h.query_all_by_label(instrument) {
                let r = node.rect();
                assert!(
                    !r.intersects(image) && !r.intersects(ior) && r.left() >= image.right(),
                    "{title}: {instrument} at {r:?} covers the image {image:?} or IOR {ior:?}"
                );
            }
        }
        // The slide about the tree opens the inspector on its pixel; no other.
        assert_eq!(
            h.state().inspected_tree().is_some(),
            title == "The ray tree",
            "{title}: the inspector as the slide needs"
        );
        let caption = h.state().caption().unwrap();
        for spec in raylab::params::TABLE {
            if names(&caption, spec.label) {
                assert!(
                    h.query_all_by_label_contains(spec.label).next().is_some(),
                    "slide `{title}` names `{}`, which is not in view",
                    spec.label
                );
            }
        }
    }
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

/// A click at `pos` as a user makes it: hover, press, release.
fn click_at(h: &mut Harness<'static, RaylabApp>, pos: egui::Pos2) {
    h.hover_at(pos);
    h.run_steps(2);
    for pressed in [true, false] {
        h.event(egui::Event::PointerButton {
            pos,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: egui::Modifiers::NONE,
        });
        h.run_steps(2);
    }
}

#[test]
fn the_fresnel_plot_marks_an_inspected_ray_only_where_it_meets_glass() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("glass", dir.path());
    step_until(&mut h, "a full frame", |a| {
        a.latest_frame().is_some_and(|f| !f.is_preview())
    });
    for item in ["Fresnel plot", "Ray-tree inspector: click a pixel"] {
        h.get_by_label("Instruments").click();
        h.run_steps(3);
        h.get_by_label(item).click();
        h.run_steps(3);
        h.key_press(egui::Key::Escape);
        h.run_steps(2);
    }
    // The image lies between the 320-point controls and the dock.
    let (left, right) = (320.0, h.get_by_label("Fresnel plot").rect().min.x - 8.0);
    let width = right - left;
    let (mid_x, mid_y) = ((left + right) / 2.0, 400.0);
    // The floor, near the image's bottom edge.
    click_at(&mut h, egui::pos2(mid_x, mid_y + 0.22 * width * 9.0 / 16.0));
    let hit = h.state().inspected_tree().unwrap().nodes[0].hit.unwrap();
    assert_eq!(h.state().scene().object_names[hit.object as usize], "floor");
    assert!(
        h.query_all_by_label_contains("inspected ray")
            .next()
            .is_none()
    );
    // The glass sphere: marked at its angle of incidence.
    click_at(
        &mut h,
        egui::pos2(mid_x - 0.05 * width, mid_y - 0.11 * width * 9.0 / 16.0),
    );
    let hit = h.state().inspected_tree().unwrap().nodes[0].hit.unwrap();
    assert_eq!(
        h.state().scene().object_names[hit.object as usize],
        "glass sphere"
    );
    h.query_all_by_label_contains("inspected ray")
        .next()
        .expect("the plot marks the ray on glass");
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
