//! The section view and the interface workbench in the window, driven as a student would:
//! pick a pixel, hover its rays, drag the workbench's angle.
// The window's own: built with the window (the `gui` feature) only.
#![cfg(feature = "gui")]

#[path = "common/window.rs"]
mod window;

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glam::Vec2;
use raylab::app::RaylabApp;
use raylab::section::{Fit, Room, Workbench, section};
use window::{app, click_at, glass_sphere, step_until};

/// Opens the section view from the Instruments menu.
fn open_section(h: &mut Harness<'static, RaylabApp>) {
    h.get_by_label("Instruments").click();
    h.run_steps(3);
    h.get_by_label("Section view and interface workbench")
        .click();
    h.run_steps(3);
    h.key_press(egui::Key::Escape);
    h.run_steps(3);
}

/// The window's body text height: what the section view's labels are drawn at.
fn body_text(h: &Harness<'static, RaylabApp>) -> f32 {
    egui::TextStyle::Body.resolve(&h.ctx.global_style()).size
}

/// A press, moves and release at `points`, as a user drags.
fn drag(h: &mut Harness<'static, RaylabApp>, points: &[egui::Pos2]) {
    let button = |pos, pressed| egui::Event::PointerButton {
        pos,
        button: egui::PointerButton::Primary,
        pressed,
        modifiers: egui::Modifiers::NONE,
    };
    h.hover_at(points[0]);
    h.run_steps(2);
    h.event(button(points[0], true));
    h.run_steps(2);
    for p in &points[1..] {
        h.hover_at(*p);
        h.run_steps(2);
    }
    h.event(button(points[points.len() - 1], false));
    h.run_steps(2);
}

#[test]
fn a_picked_pixels_section_links_its_rays_to_the_tree_list() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("glass", dir.path());
    step_until(&mut h, "a full frame", |a| {
        a.latest_frame().is_some_and(|f| !f.is_preview())
    });
    open_section(&mut h);
    h.get_by_label("Click a pixel of the image: its ray tree is drawn here in its own plane.");
    let centre = glass_sphere(&h, "Section view");
    click_at(&mut h, centre);
    h.run_steps(2);
    let tree = h.state().inspected_tree().expect("a tree").clone();
    assert!(tree.nodes[0].hit.unwrap().n1_n2.is_some(), "the glass");
    // The section draws that tree: hovering its refracted child's line hovers that ray.
    let canvas = h.get_by_label("Section diagram").rect();
    let scene = h.state().scene();
    let frame_size = h
        .state()
        .latest_frame()
        .map(|f| (f.width, f.height))
        .unwrap();
    let camera = &scene.camera;
    let params = h.state().params().clone();
    let frame = camera.frame(
        frame_size.0 as f32 / frame_size.1 as f32,
        camera.exposure(&params),
    );
    let room = Room {
        size: Vec2::new(canvas.width(), canvas.height()),
        text: body_text(&h),
        zoom: 1.0,
        titled: true,
    };
    let inspected = h
        .state()
        .inspected_pixel()
        .expect("the inspector keeps its pixel");
    let diagram = section(scene, &frame, &tree, inspected, room).unwrap();
    let fit = Fit::new(
        &diagram,
        Vec2::new(canvas.min.x, canvas.min.y),
        room.size,
        room.text,
    );
    let (id, _) = tree
        .children(0)
        .find(|(_, n)| n.kind == raylab::tracer::RayKind::Refract)
        .expect("a refracted child");
    let ray = diagram.rays().find(|r| r.node == Some(id)).unwrap();
    let at = fit.to_canvas(ray.a + 0.5 * (ray.b - ray.a));
    h.hover_at(egui::pos2(at.x, at.y));
    h.run_steps(3);
    assert_eq!(h.state().hovered_ray(), Some(id), "the section's ray");
    // And back: hovering the camera ray's entry in the tree list hovers ray 0.
    let entry = h
        .get_by_label("Camera ray, level 0: glass sphere (glass) — split into child rays")
        .rect();
    h.hover_at(entry.center());
    h.run_steps(3);
    assert_eq!(h.state().hovered_ray(), Some(0), "the list's entry");
    // Nothing under the pointer: nothing highlighted.
    h.hover_at(egui::pos2(5.0, 795.0));
    h.run_steps(3);
    assert_eq!(h.state().hovered_ray(), None);
}

#[test]
fn dragging_the_workbench_sets_the_angle_and_outlines_the_image() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("glass", dir.path());
    step_until(&mut h, "a full frame", |a| {
        a.latest_frame().is_some_and(|f| !f.is_preview())
    });
    open_section(&mut h);
    h.get_by_label("Interface workbench").click();
    h.run_steps(3);
    let canvas = h.get_by_label("Workbench diagram").rect();
    let size = Vec2::new(canvas.width(), canvas.height());
    let bench = Workbench {
        n1: 1.0,
        n2: 1.5,
        theta_i: h.state().workbench_angle(),
    };
    let fit = Fit::new(
        &bench.diagram(),
        Vec2::new(canvas.min.x, canvas.min.y),
        size,
        body_text(&h),
    );
    // Drag the ray's end round from 20° to 60° from the normal.
    let point = |deg: f32| {
        let r = deg.to_radians();
        let p = fit.to_canvas(0.8 * Vec2::new(-r.sin(), r.cos()));
        egui::pos2(p.x, p.y)
    };
    drag(&mut h, &[point(20.0), point(40.0), point(60.0)]);
    let angle = h.state().workbench_angle();
    assert!((angle - 60.0).abs() < 0.5, "dragged to 60°: {angle}");
    h.get_by_role_and_label(Role::Slider, "Angle of incidence");
    // The pixels whose camera ray meets the glass at 60° ± 0.5° are outlined.
    step_until(&mut h, "the image's angles", |a| {
        a.outlined_pixels().is_some()
    });
    let outlined = h.state().outlined_pixels().unwrap();
    assert!(outlined > 0, "a ring on the sphere");
    // Past any angle the glass shows, none are.
    drag(&mut h, &[point(89.5)]);
    assert!(h.state().workbench_angle() > 89.0);
    let grazing = h.state().outlined_pixels().unwrap();
    assert!(
        grazing < outlined,
        "{grazing} at grazing, {outlined} at 60°"
    );
}

#[test]
fn in_a_hall_the_dock_shows_one_instrument_and_a_tab_for_each() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = window::app_sized("default", dir.path(), (1920.0, 1080.0));
    h.step();
    let slide = "6. Reflectance against angle: metal and glass";
    window::choose_from_menu(&mut h, "Lecture", slide);
    step_until(&mut h, "the slide", |a| {
        a.slide() == Some(5) && a.caption().is_some() && !a.is_loading()
    });
    h.key_press(egui::Key::F5);
    h.run_steps(3);
    assert!(h.state().presenting());
    // The plot first; the workbench behind its tab, drawn once the tab is picked.
    h.get_by_label("Fresnel plot");
    assert!(h.query_by_label("Workbench diagram").is_none());
    h.get_by_label("Section view").click();
    h.run_steps(3);
    let canvas = h.get_by_label("Workbench diagram").rect();
    let image = h.get_by_label("Image").rect();
    assert!(
        canvas.left() >= image.right(),
        "beside the image, not over it"
    );
    assert!(canvas.height() > 200.0, "room to draw: {canvas:?}");
    assert!(h.query_by_label("Compare with a metal:").is_none());
}

#[test]
fn snells_slide_opens_the_section_zoomed_on_its_pixels_sphere() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("default", dir.path());
    h.step();
    window::choose_from_menu(&mut h, "Lecture", "2. Snell's law");
    step_until(&mut h, "the slide", |a| {
        a.slide() == Some(1) && a.caption().is_some() && !a.is_loading()
    });
    h.run_steps(3);
    h.get_by_label("Section diagram");
    let hit = h.state().inspected_tree().unwrap().nodes[0].hit.unwrap();
    assert_eq!(hit.n1_n2, Some((1.0, 1.5)), "the pixel meets the glass");
    assert_eq!(h.state().section_zoom(), 3.0);
}
