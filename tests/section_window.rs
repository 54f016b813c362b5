//! The section view and the interface workbench in the window, driven as a student would:
//! pick a pixel, hover its rays, drag the workbench's angle.
// The window's own: built with the window (the `gui` feature) only.
#![cfg(feature = "gui")]

#[path = "common/slides.rs"]
mod slides;
#[path = "common/window.rs"]
mod window;

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glam::Vec2;
use raylab::app::RaylabApp;
use raylab::section::{Anchor, Canvas, Fit, Room, Stroke, Theme, Workbench, paint, section};
use window::{app, choose_from_menu, click_at, glass_sphere, step_until};

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

/// The section of `tree` as the window draws it (its inspected pixel, its camera, at
/// `zoom`, `titled` or not as at a desk or in a hall), and where it is fitted on the
/// window's "Section diagram" canvas at the window's body text.
fn window_section(
    h: &Harness<'static, RaylabApp>,
    tree: &raylab::tracer::RayTree,
    zoom: f32,
    titled: bool,
) -> (raylab::section::Diagram, Fit) {
    let canvas = h.get_by_label("Section diagram").rect();
    let app = h.state();
    let scene = app.scene();
    let frame = app.latest_frame().expect("a frame");
    let camera = &scene.camera;
    let aspect = frame.width as f32 / frame.height as f32;
    let view = camera.frame(aspect, camera.exposure(app.params()));
    let room = Room {
        size: Vec2::new(canvas.width(), canvas.height()),
        text: body_text(h),
        zoom,
        titled,
    };
    let pixel = app
        .inspected_pixel()
        .expect("the inspector keeps its pixel");
    let diagram = section(scene, &view, tree, pixel, room).expect("a tree with a hit");
    let top_left = Vec2::new(canvas.min.x, canvas.min.y);
    let fit = Fit::new(&diagram, top_left, room.size, room.text);
    (diagram, fit)
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
    let (diagram, fit) = window_section(&h, &tree, 1.0, true);
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
        roughness: 0.0,
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
fn in_a_hall_the_plot_and_the_workbench_share_the_dock_in_view_and_others_get_tabs() {
    // Slide 6's caption speaks of the plot and the workbench: both in view, whole, above
    // the strip, at 1080p and 720p. Another instrument open gets a tab of its own.
    let dir = tempfile::tempdir().unwrap();
    for size in [(1920.0, 1080.0), (1280.0, 720.0)] {
        let mut h = window::app_sized("default", dir.path(), size);
        h.step();
        window::choose_from_menu(
            &mut h,
            "Lecture",
            "6. Reflectance against angle: metal and glass",
        );
        step_until(&mut h, "the slide", |a| {
            a.slide() == Some(5) && a.caption().is_some() && !a.is_loading()
        });
        h.key_press(egui::Key::F5);
        h.run_steps(4);
        assert!(h.state().presenting());
        let image = h.get_by_label("Image").rect();
        // The plot's last legend entry (the glass's curve) and the workbench's drawing,
        // under the plot, both beside the image and above the strip.
        let glass = h.get_by_label("—\u{a0}R n = 1.50").rect();
        let canvas = h.get_by_label("Workbench diagram").rect();
        for (what, r) in [("the plot's legend", glass), ("the workbench", canvas)] {
            assert!(
                r.left() >= image.right() && r.bottom() <= image.bottom() + 1.0,
                "{size:?}: {what} at {r:?}, the image at {image:?}"
            );
        }
        assert!(
            canvas.top() > glass.bottom(),
            "{size:?}: the workbench under the plot"
        );
        assert!(
            canvas.height() > 0.25 * image.height(),
            "{size:?}: room to draw: {canvas:?}"
        );
        // The workbench's controls stay at the desk: dragging its drawing sets the angle.
        assert!(
            h.query_by_role_and_label(Role::Slider, "Angle of incidence")
                .is_none()
        );
        // Sample patterns opened at the desk: behind their tab; picked, they replace both.
        h.key_press(egui::Key::Escape);
        h.run_steps(2);
        window::choose_from_menu(&mut h, "Instruments", "Sample patterns");
        h.key_press(egui::Key::Escape);
        h.key_press(egui::Key::F5);
        h.run_steps(4);
        h.get_by_label("Workbench diagram");
        h.get_by_label("Sample patterns").click();
        h.run_steps(3);
        assert!(h.query_by_label("Workbench diagram").is_none());
        assert!(h.query_by_label("—\u{a0}R n = 1.50").is_none());
        h.get_by_label("Fresnel plot").click();
        h.run_steps(3);
        h.get_by_label("Workbench diagram");
    }
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

/// A canvas that keeps the texts painted on it: the tree node whose interface each
/// labels, its words and its height.
#[derive(Default)]
struct Drawn {
    group: Option<usize>,
    texts: Vec<(Option<usize>, String, f32)>,
}

impl Canvas for Drawn {
    fn polyline(&mut self, _: &[Vec2], _: Stroke) {}
    fn circle(&mut self, _: Vec2, _: f32, _: Option<[u8; 4]>, _: Option<Stroke>) {}
    fn polygon(&mut self, _: &[Vec2], _: [u8; 4]) {}
    fn text(&mut self, _: Vec2, text: &str, size: f32, _: [u8; 4], _: Anchor) {
        self.texts.push((self.group, text.to_string(), size));
    }
    fn group(&mut self, node: Option<usize>) {
        self.group = node;
    }
}

#[test]
fn snells_section_keeps_its_hit_and_labels_legible_over_the_iors_range() {
    // The caption says "Drag the IOR": over the slider's range the section keeps the
    // glass as large, its hit in view and every label of the way in and out drawn, at the
    // caption's size. (Framed by the whole tree, IOR 2.19 sent a refracted ray far across
    // the floor and the sphere shrank to a few dozen points, its labels dropped.)
    let dir = tempfile::tempdir().unwrap();
    for size in [(1920.0, 1080.0), (1280.0, 720.0)] {
        let mut h = window::app_sized("default", dir.path(), size);
        h.step();
        h.key_press(egui::Key::F5);
        h.key_press(egui::Key::PageDown);
        h.key_press(egui::Key::PageDown);
        slides::wait_for_slide(&mut h, 1);
        h.run_steps(3);
        let text = body_text(&h);
        assert!(
            (text - size.1 / 26.0).abs() < 0.01,
            "the caption's size: {text}"
        );
        let mut chords = Vec::new();
        for ior in [1.0, 1.25, 1.5, 1.75, 2.0, 2.19, 2.5] {
            h.get_by_role_and_label(Role::Slider, "IOR")
                .set_value_accesskit(ior);
            h.run_steps(3);
            let what = format!("{size:?} at IOR {ior}");
            let tree = h.state().inspected_tree().unwrap().clone();
            let hit = tree.nodes[0].hit.unwrap();
            assert_eq!(
                hit.n1_n2,
                Some((1.0, ior as f32)),
                "{what}: the tree follows"
            );
            let zoom = h.state().section_zoom();
            let (diagram, fit) = window_section(&h, &tree, zoom, false);
            let canvas = h.get_by_label("Section diagram").rect();
            let mut drawn = Drawn::default();
            paint(&diagram, &mut drawn, &fit, Theme::Dark, None);
            // The hit, and the way through the glass, in view and large.
            let (refracted, _) = tree
                .children(0)
                .find(|(_, n)| n.kind == raylab::tracer::RayKind::Refract)
                .unwrap();
            let through = diagram.rays().find(|r| r.node == Some(refracted)).unwrap();
            let (a, b) = (fit.to_canvas(through.a), fit.to_canvas(through.b));
            for (end, p) in [("in", a), ("out", b)] {
                assert!(
                    canvas.contains(egui::pos2(p.x, p.y)),
                    "{what}: the way {end} at {p} off the canvas {canvas:?}"
                );
            }
            let chord = a.distance(b);
            chords.push(chord);
            assert!(
                chord > 0.25 * canvas.width().min(canvas.height()),
                "{what}: the way through the glass {chord} points long in {canvas:?}"
            );
            // Every label of the way in, and the bends of the way out (its θr, equal to
            // its θi, may yield to them), drawn, none left out for want of room; and the
            // indices in the line under the drawing. All at the caption's size.
            let wanted = diagram.labels.iter().filter(|l| {
                l.node == Some(0) || (l.node == Some(refracted) && !l.text.starts_with("θr"))
            });
            let indices = format!("η1 = 1.0, η2 = {}", raylab::section::index(ior as f32));
            let expected = wanted
                .map(|l| (l.node, l.text.clone()))
                .chain([(None, indices)]);
            for (node, words) in expected {
                let shown = drawn
                    .texts
                    .iter()
                    .any(|(n, t, s)| *n == node && *t == words && *s == text);
                assert!(shown, "{what}: `{words}` not drawn");
            }
        }
        // The glass keeps its size over the range: within a factor of two.
        let (lo, hi) = chords
            .iter()
            .fold((f32::MAX, 0.0f32), |(l, h), &c| (l.min(c), h.max(c)));
        assert!(
            hi < 2.0 * lo,
            "{size:?}: the way through the glass from {lo} to {hi} points"
        );
    }
}

#[test]
fn the_lens_bench_draws_the_picked_pixels_rays_through_the_real_lens() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("real-lens", dir.path());
    step_until(&mut h, "a frame", |a| a.latest_frame().is_some());
    open_section(&mut h);
    h.get_by_label("Lens bench").click();
    h.run_steps(3);
    h.get_by_label(
        "Click a pixel of the image: the lens bench draws its rays through the camera's lens.",
    );
    let picked = glass_sphere(&h, "Section view");
    click_at(&mut h, picked);
    h.run_steps(3);
    assert!(h.state().inspected_pixel().is_some(), "a pixel picked");
    h.get_by_label("Lens bench diagram");
    assert!(h.state().open().lens_bench);
    // The thin lens has no glass to draw: the bench says so instead.
    choose_from_menu(&mut h, "Lens", "thin lens (the lecture)");
    step_until(&mut h, "the pixel traced again", |a| {
        a.inspected_pixel().is_some() && a.params().lens == raylab::params::LensModel::Thin
    });
    h.run_steps(3);
    assert!(h.query_by_label("Lens bench diagram").is_none());
    h.get_by_label("The camera has the thin lens, an ideal disk with no glass to draw: choose a real lens under the Lens menu under Camera.");
}
