//! The window's instruments, driven as a user would: the ray-tree inspector, the A/B view,
//! the contact sheet, the cost heat map, the Fresnel plot.
// The window's own: built with the window (the `gui` feature) only.
#![cfg(feature = "gui")]

#[path = "common/window.rs"]
mod window;

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use raylab::app::RaylabApp;
use raylab::optics::FresnelMode;
use raylab::render::to_srgba8;
use window::{app, click_at, glass_sphere, step_until};

/// Opens the inspector from the Instruments menu and clicks the glass sphere.
fn click_on_the_glass_sphere_with_the_inspector(h: &mut Harness<'static, RaylabApp>) {
    h.get_by_label("Instruments").click();
    h.run_steps(3);
    h.get_by_label("Ray-tree inspector: click a pixel").click();
    h.run_steps(3);
    h.key_press(egui::Key::Escape);
    h.run_steps(3);
    let centre = glass_sphere(h, "Ray-tree inspector");
    click_at(h, centre);
    h.run_steps(1);
}

#[test]
fn the_inspector_shows_the_tree_of_the_clicked_pixel() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("glass", dir.path());
    step_until(&mut h, "a full frame", |a| {
        a.latest_frame().is_some_and(|f| !f.is_preview())
    });
    click_on_the_glass_sphere_with_the_inspector(&mut h);
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

/// Side B's parameters and newest frame, while the A/B view is on.
fn side_b(app: &RaylabApp) -> Option<(&raylab::params::Params, Option<&raylab::render::Frame>)> {
    app.compare_sides().first().copied()
}

#[test]
fn a_b_compare_renders_both_sides() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("glazed", dir.path());
    h.step();
    window::compare_with(&mut h, "constant | Fresnel");
    assert_eq!(
        h.state().params().fresnel,
        Some(FresnelMode::Constant),
        "side A"
    );
    let (b, _) = side_b(h.state()).expect("the A/B view is on");
    assert_eq!(b.fresnel, Some(FresnelMode::Exact), "side B");
    step_until(&mut h, "both sides to finish", |a| {
        a.latest_frame().is_some_and(|f| f.progress.done())
            && side_b(a).is_some_and(|(_, f)| f.is_some_and(|f| f.progress.done()))
    });
    // The status bar says how far each side has come.
    h.run_steps(2);
    let target = side_b(h.state()).unwrap().0.spp;
    assert!(
        h.query_all_by_label_contains(&format!("B: {target} / {target} spp"))
            .next()
            .is_some(),
        "side B's progress in the status bar"
    );
    // The two sides differ only in the Fresnel model: the same light, other reflections.
    let a = h.state().latest_frame().unwrap().pixels.clone();
    let b = side_b(h.state()).unwrap().1.unwrap().pixels.clone();
    assert_eq!(a.len(), b.len());
    assert!(a.iter().zip(b.iter()).any(|(x, y)| x != y));
    // Other controls move both sides.
    h.get_by_role_and_label(Role::Slider, "Max depth")
        .set_value_accesskit(2.0);
    h.run_steps(3);
    assert_eq!(side_b(h.state()).unwrap().0.max_depth, 2);
    // So do the resolution and the scene.
    h.get_by_role_and_label(Role::ComboBox, "Resolution")
        .scroll_to_me();
    h.run_steps(3);
    h.get_by_role_and_label(Role::ComboBox, "Resolution")
        .click();
    h.run_steps(3);
    h.get_by_label("25%").click();
    h.run_steps(3);
    step_until(&mut h, "both sides at 25%", |a| {
        let quarter = |f: &raylab::render::Frame| (f.width, f.height) == (240, 135);
        a.latest_frame().is_some_and(quarter)
            && side_b(a).is_some_and(|(_, f)| f.is_some_and(quarter))
    });
    h.state_mut().open_scene("glass");
    step_until(&mut h, "the new scene", |a| a.scene().name == "glass");
    step_until(&mut h, "side B finished on it", RaylabApp::compare_settled);
    let (b, frame) = side_b(h.state()).unwrap();
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
    // The form is in the dock beside the image: it covers no control, nor the image.
    let form = h.get_by_label("Render sheet").rect();
    let image = h.get_by_label("Image").rect();
    assert!(form.left() >= image.right(), "{form:?} beside {image:?}");
    for control in ["Scene", "Instruments"] {
        let c = h.get_by_label(control).rect();
        assert!(!form.intersects(c), "{form:?} covers {control} at {c:?}");
    }
    let ior = h.get_by_role_and_label(Role::Slider, "IOR").rect();
    assert!(!form.intersects(ior));
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
    // (The picture the window shows: calmed while the image is on its way.)
    assert_eq!(
        h.state().shown_pixels(),
        to_srgba8(frame.shown().0, h.state().params().exposure)
    );
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
fn a_tree_that_needs_photons_is_traced_off_the_windows_thread_and_arrives() {
    // With photons the inspected sample first needs its 20,000 photons shot: the window
    // does that on a thread of its own, and the tree arrives frames later, the same as
    // traced in place.
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string("scenes/glass.toml").unwrap();
    let text = text.replace("max_depth = 10", "max_depth = 10\ntransport = \"photons\"");
    let path = dir.path().join("glass-photons.toml");
    std::fs::write(&path, text).unwrap();
    let mut h = app(path.to_str().unwrap(), dir.path());
    step_until(&mut h, "a full frame", |a| {
        a.latest_frame().is_some_and(|f| !f.is_preview())
    });
    click_on_the_glass_sphere_with_the_inspector(&mut h);
    // The click's frame did not wait for the photons.
    assert!(h.state().tracing_inspection());
    assert!(h.state().inspected_tree().is_none());
    step_until(&mut h, "the tree", |a| a.inspected_tree().is_some());
    assert!(!h.state().tracing_inspection());
    let a = h.state();
    let pixel = a.inspected_pixel().unwrap();
    let mut tracer =
        raylab::tracer::Tracer::with_camera(a.scene(), &a.scene().camera, a.params(), 960, 540);
    tracer.prepare_photons(0);
    let (tree, _) = tracer.inspect(pixel.0, pixel.1, 0);
    assert_eq!(a.inspected_tree(), Some(&tree));
}

#[test]
fn sample_patterns_say_when_the_camera_takes_no_point_on_the_lens_or_no_time() {
    let dir = tempfile::tempdir().unwrap();
    let lens = "Point on the lens";
    let pinhole = "None: a pinhole (aperture 0)";
    let time = "Time in the shutter interval";
    let mut h = app("default", dir.path());
    h.step();
    window::choose_from_menu(&mut h, "Instruments", "Sample patterns");
    h.step();
    // A pinhole with a shutter of 0: neither panel has marks, and each says why.
    h.get_by_label(lens);
    h.get_by_label(pinhole);
    h.query_all_by_label_contains("Time in the shutter interval: none")
        .next()
        .expect("the shutter's panel says it is unused");
    // An aperture: the lens samples are drawn.
    h.get_by_role_and_label(Role::Slider, "Aperture")
        .set_value_accesskit(0.1);
    h.run_steps(3);
    h.get_by_label(lens);
    assert!(h.query_by_label(pinhole).is_none());
    assert!(h.query_by_label(time).is_none());
}

#[test]
fn a_noisy_image_on_its_way_is_shown_calmed_and_the_view_menu_shows_it_raw() {
    // The soft-shadow scene on its way to 256 spp is noisy: the window shows the calmed
    // picture (its 2 × 2 cells), says so in the status bar, and keeps the film's own
    // pixels for the readouts; View > Calm noise while refining off shows the film itself.
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("soft-shadows", dir.path());
    step_until(&mut h, "a calmed frame", |a| {
        a.latest_frame()
            .is_some_and(|f| f.calm.is_some() && !f.is_preview())
    });
    let frame = h.state().latest_frame().unwrap();
    let exposure = h.state().params().exposure;
    let calm = frame.calm.as_ref().unwrap();
    assert_eq!(h.state().shown_pixels(), to_srgba8(&calm.pixels, exposure));
    let cells = frame.width.div_ceil(calm.block) * frame.height.div_ceil(calm.block);
    assert_eq!(
        (calm.block, calm.pixels.len()),
        (raylab::render::CALM_BLOCK, cells as usize)
    );
    assert!(
        h.query_by_label("calmed").is_some(),
        "the status bar says so"
    );
    window::choose_from_menu(&mut h, "View", "Calm noise while refining");
    step_until(&mut h, "a raw frame", |a| {
        a.latest_frame()
            .is_some_and(|f| f.calm.is_none() && !f.is_preview())
    });
    let frame = h.state().latest_frame().unwrap();
    assert!(
        !frame.progress.done(),
        "still on its way: raw because calm is off"
    );
    assert_eq!(h.state().shown_pixels(), to_srgba8(&frame.pixels, exposure));
    assert!(h.query_by_label("calmed").is_none());
}

#[test]
fn a_change_that_keeps_part_of_the_image_says_in_the_status_bar_how_much_it_re_renders() {
    // The glass scene at its target, then the index of refraction moved: only the pixels
    // that met glass start again, and the status bar says what share while they catch up.
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("glass", dir.path());
    step_until(&mut h, "the finished image", |a| {
        a.latest_frame().is_some_and(|f| f.progress.done())
    });
    h.get_by_role_and_label(Role::Slider, "IOR")
        .set_value_accesskit(1.8);
    h.step();
    let generation = h.state().engine().generation();
    step_until(&mut h, "a frame of the change on its way", |a| {
        a.latest_frame()
            .is_some_and(|f| f.generation == generation && !f.progress.done())
    });
    h.step();
    let reached = h.state().latest_frame().unwrap().progress.reached;
    assert!(reached > 0.0 && reached < 0.5, "{reached} re-rendered");
    let said = format!("re-rendering {:.0}%", reached * 100.0);
    assert!(
        h.query_by_label(&said).is_some(),
        "the status bar says {said}"
    );
    step_until(&mut h, "the finished image", |a| {
        a.latest_frame()
            .is_some_and(|f| f.generation == generation && f.progress.done())
    });
    h.step();
    assert!(
        h.query_by_label(&said).is_none(),
        "and stops saying it once done"
    );
}
