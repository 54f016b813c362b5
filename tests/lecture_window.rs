//! The lecture in the window, driven as a lecturer would: the Lecture menu, every slide's
//! scene, caption and controls, the pixel a slide inspects. (Presentation mode and a
//! clicker's keys: `presentation_window.rs`.)
// The window's own: built with the window (the `gui` feature) only.
#![cfg(feature = "gui")]
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

#[path = "common/slides.rs"]
mod slides;
#[path = "common/window.rs"]
mod window;

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use raylab::app::{Open, RaylabApp};
use raylab::lecture::{Comparison, Instrument, LECTURE};
use raylab::params::{Kind, TABLE, spec};
use slides::{presses_in_one_frame, texts, wait_for_slide};
use window::{app, app_sized, choose_from_menu, step_until};

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
    // The slide's camera is a pinhole.
    h.get_by_label("None: a pinhole (aperture 0)");
}

#[test]
fn a_slides_title_and_controls_come_with_its_picture() {
    // In presentation mode the strip names the slide whose picture is on screen: from Page
    // Down until the next slide's first frame it keeps the last slide's title, caption and
    // controls. The title and the controls are checked here; the caption is held with them
    // (one `Strip`), and the tests below read it once the picture has come.
    // (It took the new title at the key press, and the new caption when the scene arrived,
    // a frame or more before the new picture.) Slides 12 and 13 share their scene.
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("default", dir.path());
    h.step();
    h.key_press(egui::Key::F5);
    h.step();
    let title = |i: usize| format!("{} / {}  {}", i + 1, LECTURE.len(), LECTURE[i].title);
    let shown = |h: &Harness<'static, RaylabApp>, i: usize| h.query_by_label(&title(i)).is_some();
    let mut from = 10;
    h.key_press(egui::Key::PageDown);
    wait_for_slide(&mut h, 0);
    presses_in_one_frame(&mut h, egui::Key::PageDown, from);
    wait_for_slide(&mut h, from);
    h.run_steps(2);
    for to in [from + 1, from + 2, from + 3] {
        assert!(shown(&h, from), "{} before Page Down", title(from));
        let asked = h.state().engine().generation();
        h.key_press(egui::Key::PageDown);
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(30);
        // The new slide's controls that the old one has not.
        let new_controls: Vec<&str> = LECTURE[to]
            .controls
            .iter()
            .filter(|c| !LECTURE[from].controls.contains(c))
            .map(|c| spec(c).unwrap().label)
            .collect();
        while !shown(&h, to) {
            assert!(
                shown(&h, from),
                "{} gone before {} came",
                title(from),
                title(to)
            );
            for label in &new_controls {
                assert!(
                    h.query_by_label(label).is_none(),
                    "{label} under {}",
                    title(from)
                );
            }
            assert!(
                std::time::Instant::now() < deadline,
                "{} never came",
                title(to)
            );
            h.step();
            std::thread::sleep(std::time::Duration::from_millis(2));
        }
        let on_screen = h.state().latest_frame().map(|f| f.generation);
        assert!(
            on_screen.is_some_and(|g| g > asked),
            "{} over the last slide's picture (frame {on_screen:?}, asked at {asked})",
            title(to)
        );
        wait_for_slide(&mut h, to);
        from = to;
    }
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
            h.state().compare_sides().len(),
            sides.map_or(0, |c| c.labels().len() - 1),
            "{title}: the A/B view's sides as the slide says"
        );
        // Each side is labelled in the image, with its own samples per pixel.
        let drawn = texts(&h);
        for name in sides.map_or(&[][..], |c| c.labels()) {
            assert!(
                drawn
                    .iter()
                    .any(|(_, t)| t.starts_with(&format!("{name} ("))),
                "{title}: `{name}` labelled"
            );
        }
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
        // The slides about the tree and its section open the inspector on their pixel; no
        // other. The section's slides show it, the workbench's the workbench.
        let pixel = slide
            .instruments
            .iter()
            .any(|i| matches!(i, Instrument::RayTree { .. } | Instrument::Section { .. }));
        assert_eq!(
            h.state().inspected_tree().is_some(),
            pixel,
            "{title}: the inspector as the slide needs"
        );
        for (instrument, label) in [
            ("section", "Section diagram"),
            ("workbench", "Workbench diagram"),
        ] {
            let opens = slide.instruments.iter().any(|i| match i {
                Instrument::Section { .. } => instrument == "section",
                Instrument::Workbench { .. } => instrument == "workbench",
                _ => false,
            });
            let shown = h.query_by_label(label);
            assert_eq!(shown.is_some(), opens, "{title}: the {instrument}");
            // Beside the image, never over it.
            if let Some(node) = shown {
                let image = h.get_by_label("Image").rect();
                assert!(
                    node.rect().left() >= image.right(),
                    "{title}: {label} beside the image"
                );
            }
        }
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

/// Moves the control of parameter `name` as a lecturer would: a slider to a point a third
/// of the way along its range, a menu to another entry.
fn move_control(h: &mut Harness<'static, RaylabApp>, name: &str) {
    let spec = spec(name).unwrap();
    match spec.kind {
        Kind::Choice(choices) => {
            let now = h.state().params().value_text(name);
            let other = choices
                .iter()
                .find(|c| Some(c.word) != now.as_deref())
                .unwrap();
            h.get_by_role_and_label(Role::ComboBox, spec.label).click();
            h.run_steps(3);
            h.get_by_label(other.label).click();
        }
        _ => {
            let range = spec.slider.unwrap();
            let value = if range.log {
                (range.min.max(1e-3).ln() * 0.63 + range.max.ln() * 0.37).exp()
            } else {
                range.min + 0.37 * (range.max - range.min)
            };
            let value = if matches!(spec.kind, Kind::Count { .. }) {
                value.round()
            } else {
                value
            };
            h.get_by_role_and_label(Role::Slider, spec.label)
                .set_value_accesskit(value);
        }
    }
    h.run_steps(3);
}

/// Whether `caption` asks the lecturer to use the control `label`: "Drag the IOR", "Raise
/// Max depth", "prune by Min weight", "Try Click to focus", "Light transport > ...".
fn asks(caption: &str, label: &str) -> bool {
    let verbs = [
        "Drag the", "Drag", "drag the", "Set the", "Raise", "Lower", "raise", "prune by", "Try",
    ];
    verbs
        .iter()
        .any(|v| names(caption, &format!("{v} {label}")))
        || caption.contains(&format!("{label} > "))
}

/// What a caption calls the control of parameter `name` where that is not its slider's
/// label: the polariser's section, the focus control's button.
fn alias(name: &str) -> &str {
    match name {
        "polarizer" => "Polariser",
        "focus_distance" => "Click to focus",
        other => spec(other).map_or(other, |s| s.label),
    }
}

#[test]
fn every_slide_can_be_taught_without_leaving_presentation_mode() {
    let dir = tempfile::tempdir().unwrap();
    for size in [(1920.0, 1080.0), (1280.0, 720.0)] {
        let mut h = app_sized("default", dir.path(), size);
        h.step();
        h.key_press(egui::Key::F5);
        h.step();
        for (i, slide) in LECTURE.iter().enumerate() {
            h.key_press(egui::Key::PageDown);
            wait_for_slide(&mut h, i);
            h.run_steps(3);
            let title = slide.title;
            assert!(h.state().presenting(), "{title}");
            // The caption asks for the controls the slide shows, and for no other.
            let caption = h.state().caption().unwrap();
            for s in TABLE {
                assert_eq!(
                    asks(&caption, s.label) || asks(&caption, alias(s.name)),
                    slide.controls.contains(&s.name),
                    "`{title}` asks for `{}` and shows it, or neither",
                    s.label
                );
            }
            // Each control the slide shows is there, large, and moving it changes what
            // the engine renders.
            for name in slide.controls {
                let before = h.state().engine().params().clone();
                move_control(&mut h, name);
                let after = h.state().engine().params().clone();
                assert_ne!(before, after, "`{title}` at {size:?}: moving `{name}`");
                // The three panes compare patterns at equal samples: all follow.
                if slide.compare == Some(Comparison::RegularRandomJittered) {
                    for (side, _) in h.state().compare_sides() {
                        assert_eq!(side.spp, after.spp, "`{title}`: every pane follows");
                    }
                }
            }
            // `]` steps the first control.
            if let Some(first) = slide.controls.first() {
                let before = h.state().params().value_text(first);
                h.key_press(egui::Key::CloseBracket);
                h.run_steps(2);
                assert_ne!(
                    h.state().params().value_text(first),
                    before,
                    "`{title}`: ] steps `{first}`"
                );
            }
        }
    }
}

/// Clicks the image where the pinhole ray meets object `name` first (the first such point
/// of a 40 × 24 grid over the image, fitted in the middle of its area).
fn click_on(h: &mut Harness<'static, RaylabApp>, name: &str) {
    let area = h.get_by_label("Image").rect();
    let scene = h.state().scene();
    let aspect = scene.width as f32 / scene.height as f32;
    let fitted = egui::vec2(area.width().min(area.height() * aspect), 0.0);
    let fitted = egui::vec2(fitted.x, fitted.x / aspect);
    let image = egui::Rect::from_center_size(area.center(), fitted);
    let object = scene.object_names.iter().position(|n| n == name).unwrap() as u32;
    let film = (0..24)
        .flat_map(|j| (0..40).map(move |i| ((i as f32 + 0.5) / 40.0, (j as f32 + 0.5) / 24.0)))
        .find(|&(x, y)| {
            raylab::tracer::pick(scene, &scene.camera, aspect, glam::Vec2::new(x, y))
                .is_some_and(|p| p.object == object)
        })
        .unwrap_or_else(|| panic!("{name} is in view"));
    let pos = image.min + egui::vec2(film.0 * image.width(), film.1 * image.height());
    window::click_at(h, pos);
    h.run_steps(2);
}

#[test]
fn captions_follow_the_inspected_pixel_and_the_focus() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app_sized("default", dir.path(), (1920.0, 1080.0));
    h.step();
    h.key_press(egui::Key::F5);
    let tree = LECTURE
        .iter()
        .position(|s| s.title == "The ray tree")
        .unwrap();
    for _ in 0..=tree {
        h.key_press(egui::Key::PageDown);
    }
    wait_for_slide(&mut h, tree);
    h.run_steps(3);
    assert!(h.state().caption().unwrap().contains("front sphere"));
    click_on(&mut h, "floor");
    let caption = h.state().caption().unwrap();
    assert!(caption.contains("on the floor"), "{caption}");

    let dof = LECTURE
        .iter()
        .position(|s| s.title == "Depth of field")
        .unwrap();
    for _ in tree..dof {
        h.key_press(egui::Key::PageDown);
    }
    wait_for_slide(&mut h, dof);
    h.run_steps(3);
    assert!(
        h.state()
            .caption()
            .unwrap()
            .contains("the blue sphere is sharp")
    );
    h.get_by_label("Click to focus").click();
    h.run_steps(2);
    click_on(&mut h, "nearest");
    let caption = h.state().caption().unwrap();
    assert!(caption.contains("the red sphere is sharp"), "{caption}");
}

#[test]
fn an_ab_slides_progress_is_its_slowest_sides() {
    // Blurring: side A is one ray a pixel, done at once; side B takes 256.
    let dir = tempfile::tempdir().unwrap();
    let mut h = app_sized("default", dir.path(), (1920.0, 1080.0));
    h.step();
    let i = LECTURE
        .iter()
        .position(|s| s.compare == Some(Comparison::Blurring))
        .unwrap();
    h.key_press(egui::Key::F5);
    for _ in 0..=i {
        h.key_press(egui::Key::PageDown);
    }
    wait_for_slide(&mut h, i);
    step_until(&mut h, "side A finished, B refining", |a| {
        let b_refining = a
            .compare_sides()
            .first()
            .is_some_and(|(_, f)| f.is_some_and(|f| !f.is_preview() && !f.progress.done()));
        a.latest_frame().is_some_and(|f| f.progress.done()) && b_refining
    });
    h.run_steps(2);
    let fraction = h.state().progress_fraction();
    assert!(fraction < 1.0, "the bar waits for side B: {fraction}");
    assert!(
        h.query_all_by_label_contains("A 1 / 1 · B ")
            .next()
            .is_some(),
        "each side's samples in the strip"
    );
    assert!(
        h.query_all_by_label_contains("/ 256 spp").next().is_some(),
        "side B's target"
    );
}

/// What slide `i` opens beside and over its image, as the slide declares it.
fn declared(i: usize) -> Open {
    let slide = &LECTURE[i];
    let has = |kind: fn(&Instrument) -> bool| slide.instruments.iter().any(kind);
    let workbench = has(|i| matches!(i, Instrument::Workbench { .. }));
    Open {
        fresnel_plot: has(|i| matches!(i, Instrument::FresnelPlot { .. })),
        section: has(|i| matches!(i, Instrument::Section { .. })),
        workbench,
        // No slide opens the lens bench.
        lens_bench: false,
        outline: workbench,
        inspected: slide.inspected_pixel((960, 540)).is_some(),
        sides: slide.compare.map_or(0, |c| c.dividers(0.5).len()),
    }
}

#[test]
fn a_slide_opens_what_it_shows_and_nothing_is_left_from_the_last() {
    // Forwards, backwards and in jumps across the lecture by its menu: each slide shows
    // its own instruments, outline and A/B view, and none of the slide before it.
    let dir = tempfile::tempdir().unwrap();
    let mut h = app("default", dir.path());
    h.step();
    let n = LECTURE.len();
    let forwards = 0..n;
    let backwards = (0..n - 1).rev();
    // Each slide to the one 7 on (7 and 19 have no common factor: every slide, and from
    // every other distance than 1).
    let jumps = (1..=n).map(|k| k * 7 % n);
    // Last, the slide that opens the most: the lecture is left from there.
    let opens = |o: Open| {
        [
            o.fresnel_plot,
            o.section,
            o.workbench,
            o.outline,
            o.inspected,
        ]
        .into_iter()
        .filter(|&b| b)
        .count()
            + o.sides
    };
    let busiest = (0..n).max_by_key(|&i| opens(declared(i))).unwrap();
    assert!(opens(declared(busiest)) >= 2);
    let mut from = None;
    for to in forwards.chain(backwards).chain(jumps).chain([busiest]) {
        choose_from_menu(
            &mut h,
            "Lecture",
            &format!("{}. {}", to + 1, LECTURE[to].title),
        );
        wait_for_slide(&mut h, to);
        // The tree a slide inspects may need photons: it arrives on its own thread.
        if declared(to).inspected {
            step_until(&mut h, "the inspected tree", |a| a.open().inspected);
        }
        assert_eq!(
            h.state().open(),
            declared(to),
            "slide {} after {from:?}",
            to + 1
        );
        from = Some(to + 1);
    }
    // Out of the lecture: nothing of the last slide stays.
    h.state_mut().open_scene("default");
    step_until(&mut h, "the scene", |a| {
        !a.is_loading() && a.slide().is_none() && a.scene().name == "default"
    });
    assert_eq!(h.state().open(), Open::default());
}
