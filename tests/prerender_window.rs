//! Presentation mode: once a slide is finished, its neighbours are rendered ahead, and
//! Page Down shows the next slide finished in its first frame.
// The window's own: built with the window (the `gui` feature) only.
#![cfg(feature = "gui")]
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

#[path = "common/window.rs"]
mod window;

use raylab::lecture::LECTURE;
use window::{app_sized, step_until};

#[test]
fn page_down_shows_the_next_slide_finished_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app_sized("default", dir.path(), (1280.0, 720.0));
    h.step();
    h.key_press(egui::Key::F5);
    h.key_press(egui::Key::PageDown);
    step_until(&mut h, "the first slide, finished", |a| {
        a.slide() == Some(0) && a.caption().is_some() && a.progress_fraction() >= 1.0
    });
    step_until(&mut h, "its neighbour rendered ahead", |a| {
        a.neighbours_ready()
    });
    h.key_press(egui::Key::PageDown);
    let scene = format!("builtin:{}", LECTURE[1].scene);
    step_until(&mut h, "the second slide's first frame", |a| {
        a.slide() == Some(1)
            && a.scene().source.reference() == scene
            && a.latest_frame()
                .is_some_and(|f| f.generation == a.generation())
    });
    let frame = h.state().latest_frame().unwrap();
    assert!(
        !frame.is_preview(),
        "a preview: the slide was not rendered ahead"
    );
    assert!(frame.progress.done(), "{:?}", frame.progress);
}
