//! A slide changes whole, in one frame: in every frame from the key press or menu click
//! until the new slide is shown, everything on screen (title, caption, controls,
//! instruments, the workbench's outline, the A/B sides, the picture) belongs to one
//! slide, the last or the next; and the strip keeps its height once the new slide is up.
// The window's own: built with the window (the `gui` feature) only.
#![cfg(feature = "gui")]
#![allow(clippy::unwrap_used)]

#[path = "common/slides.rs"]
mod slides;
#[path = "common/window.rs"]
mod window;

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use raylab::app::{Open, RaylabApp};
use raylab::lecture::{Instrument, LECTURE, Shown, Slide};
use raylab::params::{Kind, Params, TABLE};
use raylab::scene::Scene;
use slides::texts;
use std::time::{Duration, Instant};
use window::app_sized;

/// The window under test.
type Window = Harness<'static, RaylabApp>;
/// What checks each frame of a change.
type Check<'a> = dyn FnMut(&Window) + 'a;

/// Side A's parameters on `slide` over its scene's `base`: the slide's, then its
/// comparison's side A.
fn side_a(slide: &Slide, base: &Params) -> Params {
    let p = slide.params_on(base).unwrap();
    slide.compare.map_or_else(|| p.clone(), |c| c.side_a(&p))
}

/// What `slide` opens beside and over the image.
fn opens(slide: &Slide) -> Open {
    let has = |f: fn(&Instrument) -> bool| slide.instruments.iter().any(f);
    Open {
        fresnel_plot: has(|i| matches!(i, Instrument::FresnelPlot { .. })),
        section: has(|i| matches!(i, Instrument::Section { .. })),
        workbench: has(|i| matches!(i, Instrument::Workbench { .. })),
        // No slide opens the lens bench.
        lens_bench: false,
        outline: has(|i| matches!(i, Instrument::Workbench { .. })),
        inspected: has(|i| matches!(i, Instrument::RayTree { .. } | Instrument::Section { .. })),
        sides: slide.compare.map_or(0, |c| c.labels().len() - 1),
    }
}

/// Whether `h`'s last frame shows slide `k` and nothing of another: why not, if not.
fn shows(h: &Window, k: usize) -> Result<(), String> {
    let slide = &LECTURE[k];
    let app = h.state();
    // The picture: rendered from the slide's scene and side A's parameters.
    let (scene, params) = app.picture().ok_or("no picture")?;
    if scene.source.reference() != slide.reference() {
        return Err(format!("a picture of {}", scene.source.reference()));
    }
    let a = side_a(slide, &scene.params);
    if !params.same_image(&a) {
        return Err("a picture of other parameters".into());
    }
    // The A/B view's other sides, each of the slide's scene and its parameters.
    let others = slide.compare.map_or_else(Vec::new, |_| slide.others(&a));
    let pictures = app.compare_pictures();
    if pictures.len() != others.len() {
        return Err(format!("{} A/B sides", pictures.len()));
    }
    for (picture, p) in pictures.iter().zip(&others) {
        let same = |(s, q): &(&Scene, &Params)| {
            s.source.reference() == slide.reference() && q.same_image(p)
        };
        if !picture.as_ref().is_some_and(same) {
            return Err("an A/B side without its picture".into());
        }
    }
    // The instruments and the outline.
    if app.open() != opens(slide) {
        return Err(format!("{:?} open", app.open()));
    }
    let labelled = |label: &str| h.query_by_label(label).is_some();
    for (label, shown) in [
        ("Fresnel plot", opens(slide).fresnel_plot),
        ("Section diagram", opens(slide).section),
        ("Workbench diagram", opens(slide).workbench),
    ] {
        if labelled(label) != shown {
            return Err(format!("{label} shown: {}", !shown));
        }
    }
    // The caption, as the slide words it for the picture.
    let inspected = app
        .inspected_tree()
        .map(|t| t.nodes.first().and_then(|n| n.hit.map(|hit| hit.object)));
    let caption = slide.caption(&Shown {
        params,
        scene,
        camera: &scene.camera,
        inspected,
    });
    let drawn = texts(h);
    if !drawn.iter().any(|(_, t)| *t == caption) {
        return Err(format!("no caption `{caption}`"));
    }
    if app.presenting() {
        // The title, and the controls the slide asks for and no other.
        let title = |i: usize| format!("{} / {}  {}", i + 1, LECTURE.len(), LECTURE[i].title);
        if !labelled(&title(k)) {
            return Err("no title".into());
        }
        if let Some(other) = (0..LECTURE.len()).find(|&i| i != k && labelled(&title(i))) {
            return Err(format!("the title of slide {}", other + 1));
        }
        for spec in TABLE {
            let role = match spec.kind {
                Kind::Choice(_) => Role::ComboBox,
                _ => Role::Slider,
            };
            let shown = h.query_by_role_and_label(role, spec.label).is_some();
            if shown != slide.controls.contains(&spec.name) {
                return Err(format!("{} shown: {shown}", spec.label));
            }
        }
        // Everything in the strip on the screen: every control's parts, the caption.
        let screen = h.ctx.content_rect();
        let strip_top = image_area(h).bottom();
        // (Every node with a place on the screen: the tree's root has none.)
        let placed = egui_kittest::kittest::by().predicate(|n| n.bounding_box().is_some());
        for node in h.query_all(placed) {
            let r = node.rect();
            if r.top() >= strip_top && r.right() > screen.right() + 0.5 {
                return Err(format!("{node:?} at {r:?}, off the screen"));
            }
        }
        let bottom = h.get_by_label(&caption).rect().max.y;
        if bottom > screen.max.y + 0.5 {
            return Err(format!(
                "the caption's bottom at {bottom}, under {screen:?}"
            ));
        }
    }
    Ok(())
}

/// The image's area: its bottom is the strip's top.
fn image_area(h: &Window) -> egui::Rect {
    h.get_by_label("Image").rect()
}

/// Changes from slide `from` to slide `to` by `act` (the first steps of which may be
/// frames of their own, each checked), then steps frame by frame until `to` is shown
/// whole, checking that every frame shows `from` or `to` whole, never `from` once `to`
/// was shown, and (`to` shown) the image's area steady.
fn change(h: &mut Window, from: usize, to: usize, act: impl FnOnce(&mut Window, &mut Check)) {
    let what = format!("slide {} to {}", from + 1, to + 1);
    let mut arrived = false;
    let mut area = None;
    let mut check = |h: &Window| {
        let now = shows(h, to);
        if now.is_ok() {
            arrived = true;
            let here = image_area(h);
            assert_eq!(*area.get_or_insert(here), here, "{what}: the strip moved");
            return;
        }
        assert!(!arrived, "{what}: slide {} left: {now:?}", to + 1);
        if let Err(why) = shows(h, from) {
            panic!(
                "{what}: a frame of neither: as slide {}: {why}; as {}: {now:?}",
                from + 1,
                to + 1
            );
        }
    };
    act(h, &mut check);
    let deadline = Instant::now() + Duration::from_secs(30);
    // The new slide shown, and loaded (no scene on its way), and three more frames.
    let mut after = 0;
    while after < 3 {
        assert!(Instant::now() < deadline, "{what}: never came");
        h.step();
        check(h);
        if shows(h, to).is_ok() && !h.state().is_loading() {
            after += 1;
        }
        std::thread::sleep(Duration::from_millis(2));
    }
}

/// A key press, its frame checked.
fn press(key: egui::Key) -> impl FnOnce(&mut Window, &mut Check) {
    move |h, check| {
        h.key_press(key);
        check(h);
    }
}

/// Slide `i`'s entry in the Lecture menu, clicked; each frame checked.
fn from_menu(i: usize) -> impl FnOnce(&mut Window, &mut Check) {
    move |h, check| {
        let item = format!("{}. {}", i + 1, LECTURE[i].title);
        h.get_by_label("Lecture").click();
        for _ in 0..3 {
            h.step();
            check(h);
        }
        h.get_by_label(&item).click();
        h.step();
        check(h);
    }
}

#[test]
fn a_slide_changes_whole_in_one_frame_forwards_and_backwards() {
    let dir = tempfile::tempdir().unwrap();
    // A 720p laptop, a 1366x768 one, a 1080p projector.
    for size in [(1280.0, 720.0), (1366.0, 768.0), (1920.0, 1080.0)] {
        let mut h = app_sized("default", dir.path(), size);
        h.step();
        h.key_press(egui::Key::F5);
        h.key_press(egui::Key::PageDown);
        slides::wait_for_slide(&mut h, 0);
        h.run_steps(3);
        shows(&h, 0).unwrap();
        for to in 1..LECTURE.len() {
            change(&mut h, to - 1, to, press(egui::Key::PageDown));
        }
        for to in (0..LECTURE.len() - 1).rev() {
            change(&mut h, to + 1, to, press(egui::Key::PageUp));
        }
    }
}

#[test]
fn from_every_slide_to_every_other_by_the_lecture_menu_no_frame_mixes_two() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = app_sized("default", dir.path(), (1280.0, 720.0));
    h.step();
    let mut from = 0;
    window::choose_from_menu(&mut h, "Lecture", &format!("1. {}", LECTURE[0].title));
    slides::wait_for_slide(&mut h, 0);
    h.run_steps(3);
    // Every ordered pair once: from each slide to each later one and back.
    for start in 0..LECTURE.len() {
        if start != from {
            change(&mut h, from, start, from_menu(start));
            from = start;
        }
        for to in start + 1..LECTURE.len() {
            change(&mut h, start, to, from_menu(to));
            change(&mut h, to, start, from_menu(start));
        }
    }
}

#[test]
fn an_ab_view_kept_across_an_open_changes_scene_with_its_picture() {
    // A/B on at the desk, another scene opened (not a slide): in every frame each side
    // shows the scene the main view shows; the comparison stays.
    let dir = tempfile::tempdir().unwrap();
    let mut h = app_sized("glazed", dir.path(), (1280.0, 720.0));
    h.step();
    window::compare_with(&mut h, "constant | Fresnel");
    window::step_until(&mut h, "both sides' pictures", |a| {
        a.picture().is_some() && a.compare_pictures().iter().all(Option::is_some)
    });
    h.state_mut().open_scene("default");
    let deadline = Instant::now() + Duration::from_secs(30);
    let scene_of = |a: &RaylabApp| a.picture().map(|(s, _)| s.source.reference());
    loop {
        h.step();
        let app = h.state();
        let main = scene_of(app);
        for side in app.compare_pictures() {
            let side = side.map(|(s, _)| s.source.reference());
            assert_eq!(side, main, "side B's picture of another scene than A's");
        }
        if main.as_deref() == Some("builtin:default") && !app.is_loading() {
            break;
        }
        assert!(Instant::now() < deadline, "the scene never came");
        std::thread::sleep(Duration::from_millis(2));
    }
    assert_eq!(h.state().compare_sides().len(), 1, "the comparison stays");
}
