//! Presentation mode, driven as a lecturer at a projector would: a clicker's keys, the
//! shortcut list, progress, and text a hall can read (every text at the caption's size,
//! captions of three lines, messages clear of them).
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
use raylab::app::RaylabApp;
use raylab::lecture::LECTURE;
use slides::{presses_in_one_frame, texts, wait_for_slide};
use window::{app, app_sized, choose_from_menu, step_until};

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
    presses_in_one_frame(&mut h, egui::Key::PageDown, 3);
    assert_eq!(h.state().slide(), Some(3));
    shows(&mut h, 3);
    presses_in_one_frame(&mut h, egui::Key::PageUp, 3);
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
fn presentation_mode_shows_progress_and_space_does_not_pause_it() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app_sized("default", dir.path(), (1920.0, 1080.0));
    h.step();
    h.key_press(egui::Key::F5);
    h.key_press(egui::Key::PageDown);
    wait_for_slide(&mut h, 0);
    step_until(&mut h, "a full frame", |a| {
        a.latest_frame().is_some_and(|f| !f.is_preview())
    });
    h.run_steps(2);
    let target = LECTURE[0]
        .params
        .iter()
        .find(|(n, _)| *n == "spp")
        .unwrap()
        .1;
    assert!(
        h.query_all_by_label_contains(&format!("/ {target} spp"))
            .next()
            .is_some(),
        "the samples done of the target"
    );
    // A clicker's Space leaves the lecture refining.
    h.key_press(egui::Key::Space);
    h.run_steps(2);
    assert!(h.query_all_by_label_contains("paused").next().is_none());
    // Out of presentation the window's own sizes are back, Space pauses, and
    // presentation mode says so.
    h.key_press(egui::Key::Escape);
    h.run_steps(2);
    let large: Vec<_> = texts(&h).into_iter().filter(|(p, _)| *p > 25.0).collect();
    assert!(large.is_empty(), "the hall's sizes stayed: {large:?}");
    h.key_press(egui::Key::Space);
    h.run_steps(2);
    h.key_press(egui::Key::F5);
    h.run_steps(2);
    assert!(
        h.query_all_by_label_contains("paused").next().is_some(),
        "paused, shown in presentation mode"
    );
}

/// Whether `text` is a number as plots write them ("0.5", "30", "−0.1", "90°").
fn numeric(text: &str) -> bool {
    text.chars()
        .all(|c| c.is_ascii_digit() || " .,-−+°%".contains(c))
}

#[test]
fn every_text_in_presentation_mode_is_the_captions_size() {
    present_every_slide(|h, slide, size| {
        let caption = size.1 / 26.0;
        let seen = texts(h);
        assert!(seen.len() >= 3, "{}: {seen:?}", slide.title);
        for (points, text) in seen {
            // Numbers in plots may be half the caption's size; every word is its size.
            let least = if numeric(&text) {
                caption / 2.0
            } else {
                caption
            };
            assert!(
                points >= least - 0.01,
                "`{}` at {size:?}: `{text}` is {points:.1} points, under {least:.1}",
                slide.title
            );
        }
    });
}

/// Shows every slide in presentation mode, on a projector's 1920 × 1080 and a laptop's
/// 1280 × 720, and calls `check` on each once it is shown.
fn present_every_slide(
    mut check: impl FnMut(&mut Harness<'static, RaylabApp>, &raylab::lecture::Slide, (f32, f32)),
) {
    let dir = tempfile::tempdir().unwrap();
    for size in [(1920.0, 1080.0), (1280.0, 720.0)] {
        let mut h = app_sized("default", dir.path(), size);
        h.step();
        h.key_press(egui::Key::F5);
        for (i, slide) in LECTURE.iter().enumerate() {
            h.key_press(egui::Key::PageDown);
            wait_for_slide(&mut h, i);
            h.run_steps(4);
            check(&mut h, slide, size);
        }
    }
}

/// The rows the last frame laid the text `text` out in, if it drew it.
fn rows_of(h: &Harness<'static, RaylabApp>, text: &str) -> Option<usize> {
    fn walk(shape: &egui::Shape, text: &str) -> Option<usize> {
        match shape {
            egui::Shape::Vec(shapes) => shapes.iter().find_map(|s| walk(s, text)),
            egui::Shape::Text(t) if t.galley.job.text == text => Some(t.galley.rows.len()),
            _ => None,
        }
    }
    h.output().shapes.iter().find_map(|c| walk(&c.shape, text))
}

#[test]
fn every_caption_fits_in_three_lines_in_a_hall() {
    let mut long = Vec::new();
    present_every_slide(|h, slide, size| {
        let caption = h.state().caption().unwrap();
        let rows = rows_of(h, &caption).expect("the caption is drawn");
        if rows > 3 {
            long.push(format!("`{}` at {size:?}: {rows} lines", slide.title));
        }
    });
    assert!(long.is_empty(), "captions over three lines: {long:#?}");
}

/// Where the last frame drew the text starting with `start`, if it drew it.
fn text_rect(h: &Harness<'static, RaylabApp>, start: &str) -> Option<egui::Rect> {
    fn walk(shape: &egui::Shape, start: &str) -> Option<egui::Rect> {
        match shape {
            egui::Shape::Vec(shapes) => shapes.iter().find_map(|s| walk(s, start)),
            egui::Shape::Text(t) if t.galley.job.text.starts_with(start) => {
                Some(t.galley.rect.translate(t.pos.to_vec2()))
            }
            _ => None,
        }
    }
    h.output().shapes.iter().find_map(|c| walk(&c.shape, start))
}

#[test]
fn messages_keep_clear_of_a_slides_caption() {
    let dir = tempfile::tempdir().unwrap();
    for presenting in [false, true] {
        let mut h = app_sized("default", dir.path(), (1280.0, 720.0));
        h.step();
        let slide = &LECTURE[1];
        choose_from_menu(&mut h, "Lecture", &format!("2. {}", slide.title));
        wait_for_slide(&mut h, 1);
        if presenting {
            h.key_press(egui::Key::F5);
            h.run_steps(3);
        }
        // A message: nothing to undo on a slide just opened.
        h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
        h.run_steps(3);
        let message = text_rect(&h, "Nothing to undo").expect("the message is shown");
        let caption = h.state().caption().unwrap();
        let first_words: String = caption.chars().take(12).collect();
        let caption = text_rect(&h, &first_words).expect("the caption is shown");
        // The caption's text spans its block: clear of it means above or below it.
        assert!(
            message.max.y < caption.min.y || message.min.y > caption.max.y,
            "presenting {presenting}: the message {message:?} covers the caption {caption:?}"
        );
    }
}

#[test]
fn no_tooltip_covers_a_slide_in_presentation_mode() {
    // Resting the mouse on the strip's IOR slider (as after a drag) shows no tooltip in
    // presentation mode; at the desk the same rest shows it.
    let dir = tempfile::tempdir().unwrap();
    let mut h = app_sized("default", dir.path(), (1920.0, 1080.0));
    h.step();
    choose_from_menu(&mut h, "Lecture", &format!("2. {}", LECTURE[1].title));
    wait_for_slide(&mut h, 1);
    let tip = raylab::params::spec("ior").unwrap().tooltip();
    let rest_on_the_ior_slider = |h: &mut Harness<'static, RaylabApp>| {
        let slider = h.get_by_role_and_label(Role::Slider, "IOR").rect();
        h.hover_at(slider.center());
        // Each step is a quarter second: three seconds' rest.
        h.run_steps(12);
        h.query_by_label(&tip).is_some()
    };
    h.key_press(egui::Key::F5);
    h.run_steps(3);
    assert!(h.state().presenting());
    assert!(
        !rest_on_the_ior_slider(&mut h),
        "a tooltip in presentation mode"
    );
    h.key_press(egui::Key::Escape);
    h.run_steps(3);
    assert!(rest_on_the_ior_slider(&mut h), "no tooltip at the desk");
}

#[test]
fn the_strip_keeps_every_control_and_the_caption_on_the_screen_whatever_they_read() {
    // A control's readout widens with its value ("16.971", "100"): stepped through its
    // range with ] and [, every slide's controls and caption stay on the screen (slide
    // 15's Aperture ran off its right edge at 1080p, the caption widened with it).
    present_every_slide(|h, slide, size| {
        if slide.controls.is_empty() {
            return;
        }
        for (key, presses) in [
            (egui::Key::CloseBracket, 1),
            (egui::Key::CloseBracket, 3),
            (egui::Key::CloseBracket, 40),
            (egui::Key::OpenBracket, 80),
        ] {
            for _ in 0..presses {
                h.key_press(key);
            }
            h.run_steps(3);
            let screen = h.ctx.content_rect();
            let strip_top = h.get_by_label("Image").rect().bottom();
            let placed = egui_kittest::kittest::by().predicate(|n| n.bounding_box().is_some());
            for node in h.query_all(placed) {
                let r = node.rect();
                assert!(
                    r.top() < strip_top || r.right() <= screen.right() + 0.5,
                    "{} at {size:?}, {presses} x {key:?}: {node:?} at {r:?}, off the screen",
                    slide.title
                );
            }
        }
    });
}
