//! Helpers shared by the window tests of the lecture: a slide waited for, a clicker's
//! presses, the texts drawn.

#![allow(dead_code)] // Each window test file uses its own share of these.
#![allow(clippy::unwrap_used)]

use crate::window::step_until;
use egui_kittest::Harness;
use raylab::app::RaylabApp;
use raylab::lecture::LECTURE;

/// Steps until slide `i` is shown: its scene loaded, its caption up, a frame of its
/// picture on screen (the strip's words wait for it).
pub fn wait_for_slide(h: &mut Harness<'static, RaylabApp>, i: usize) {
    let (title, scene) = (LECTURE[i].title, LECTURE[i].scene);
    step_until(h, title, |a| {
        // Not loading: a slide on the scene already shown must still arrive.
        !a.is_loading()
            && a.slide() == Some(i)
            && a.scene().source.reference() == format!("builtin:{scene}")
            && a.caption().is_some()
            && a.latest_frame()
                .is_some_and(|f| f.generation == a.engine().generation())
    });
}

/// `n` presses of `key` that land in one frame, then its release.
pub fn presses_in_one_frame(h: &mut Harness<'static, RaylabApp>, key: egui::Key, n: usize) {
    for pressed in [vec![true; n], vec![false]].concat() {
        h.input_mut().events.push(egui::Event::Key {
            key,
            pressed,
            modifiers: egui::Modifiers::NONE,
            repeat: false,
            physical_key: None,
        });
    }
    h.step();
}

/// Every piece of text the last frame drew where it can be seen: its size (points) and
/// its words.
pub fn texts(h: &Harness<'static, RaylabApp>) -> Vec<(f32, String)> {
    fn walk(shape: &egui::Shape, clip: egui::Rect, out: &mut Vec<(f32, String)>) {
        match shape {
            egui::Shape::Vec(shapes) => shapes.iter().for_each(|s| walk(s, clip, out)),
            egui::Shape::Text(t) => {
                let rect = t.galley.rect.translate(t.pos.to_vec2());
                if !rect.intersects(clip) {
                    return;
                }
                let job = &t.galley.job;
                for section in &job.sections {
                    let r = &section.byte_range;
                    let text = &job.text[r.start.0..r.end.0];
                    if !text.trim().is_empty() {
                        out.push((section.format.font_id.size, text.to_string()));
                    }
                }
            }
            _ => {}
        }
    }
    let screen = h.ctx.content_rect();
    let mut out = Vec::new();
    for clipped in &h.output().shapes {
        walk(
            &clipped.shape,
            clipped.clip_rect.intersect(screen),
            &mut out,
        );
    }
    out
}
