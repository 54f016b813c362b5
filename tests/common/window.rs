//! Helpers shared by the tests that drive the window through its accessibility tree
//! (egui_kittest, no display needed): a window on a scene, stepping it until something
//! holds, menus and clicks.

#![allow(dead_code)] // Each window test file uses its own share of these.

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use raylab::app::{AppOptions, RaylabApp};
use std::path::Path;
use std::time::{Duration, Instant};

pub fn app(scene: &str, snapshots: &Path) -> Harness<'static, RaylabApp> {
    app_sized(scene, snapshots, (1280.0, 800.0))
}

/// A window of `size` (width, height) on `scene`, its snapshots going to `snapshots`.
pub fn app_sized(scene: &str, snapshots: &Path, size: (f32, f32)) -> Harness<'static, RaylabApp> {
    let options = AppOptions {
        scene: Some(scene.into()),
        snapshot_dir: snapshots.to_path_buf(),
        threads: Some(1),
        persist: false,
        ..Default::default()
    };
    Harness::builder()
        .with_size(egui::vec2(size.0, size.1))
        .build_eframe(move |cc| RaylabApp::new(cc, options.clone()).expect("the engine starts"))
}

/// Steps the UI until `done` holds, with the workers rendering in between.
pub fn step_until(
    h: &mut Harness<'static, RaylabApp>,
    what: &str,
    done: impl Fn(&RaylabApp) -> bool,
) {
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

/// Opens the toolbar menu `menu` and clicks its entry `item`, once the menu shows it (a
/// scene still loading can hold the menu's first frames back).
pub fn choose_from_menu(h: &mut Harness<'static, RaylabApp>, menu: &str, item: &str) {
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

/// Turns the A/B view on from the Instruments menu, comparing `preset` (its menu entry).
pub fn compare_with(h: &mut Harness<'static, RaylabApp>, preset: &str) {
    for label in ["Instruments", "A/B compare", preset] {
        h.get_by_label(label).click();
        h.run_steps(3);
    }
}

/// A click at `pos` as a user makes it: hover, press, release.
pub fn click_at(h: &mut Harness<'static, RaylabApp>, pos: egui::Pos2) {
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

/// Where the glass scene's glass sphere is in an 800-point-high window: a little left of
/// the image's centre, above the middle. The image lies between the controls (320 points
/// wide) and the instruments' dock, whose first heading is `dock_heading`.
pub fn glass_sphere(h: &Harness<'static, RaylabApp>, dock_heading: &str) -> egui::Pos2 {
    let left = 320.0;
    let right = h.get_by_label(dock_heading).rect().min.x - 8.0;
    let shown_width = right - left;
    egui::pos2(
        (left + right) / 2.0 - 0.05 * shown_width,
        800.0 / 2.0 - 0.11 * shown_width * 9.0 / 16.0,
    )
}
