//! A diagram as a PNG: shapes anti-aliased by tiny-skia, text in egui's own typeface
//! (the captions' rasteriser).

use super::paint::{Canvas, Stroke};
use super::svg::text_size;
use super::{Anchor, Dash, Diagram, Fit, Theme, paint};
use glam::Vec2;
use image::RgbImage;
use tiny_skia::{FillRule, Paint, PathBuilder, Pixmap, Transform};

/// `diagram` drawn in a `width` × `height` image in `theme`'s colours (sizes as
/// [`super::to_svg`] draws them). `None` only for a zero-sized image.
pub fn to_png(diagram: &Diagram, width: u32, height: u32, theme: Theme) -> Option<RgbImage> {
    let mut canvas = Raster {
        pixmap: Pixmap::new(width, height)?,
        texts: Vec::new(),
    };
    let (w, h) = (width as f32, height as f32);
    let fit = Fit::new(
        diagram,
        Vec2::ZERO,
        Vec2::new(w, h),
        text_size(width, height),
    );
    paint(diagram, &mut canvas, &fit, theme, None);
    let mut img = RgbImage::new(width, height);
    for (p, q) in img.pixels_mut().zip(canvas.pixmap.pixels()) {
        let c = q.demultiply();
        p.0 = [c.red(), c.green(), c.blue()];
    }
    // Text last: it lies over every mark in the painter's order too.
    for (at, text, size, c, align) in canvas.texts {
        crate::render::text::draw_text(&mut img, &text, (at.x, at.y), size, c, align);
    }
    Some(img)
}

type Text = (Vec2, String, f32, [u8; 3], f32);

struct Raster {
    pixmap: Pixmap,
    texts: Vec<Text>,
}

fn paint_of(c: [u8; 4]) -> Paint<'static> {
    let mut paint = Paint::default();
    paint.set_color_rgba8(c[0], c[1], c[2], c[3]);
    paint.anti_alias = true;
    paint
}

/// The path through `points`, back to the first where `closed`; `None` for fewer than two.
fn path_through(points: &[Vec2], closed: bool) -> Option<tiny_skia::Path> {
    let mut pb = PathBuilder::new();
    for (i, p) in points.iter().enumerate() {
        match i {
            0 => pb.move_to(p.x, p.y),
            _ => pb.line_to(p.x, p.y),
        }
    }
    if closed {
        pb.close();
    }
    pb.finish()
}

impl Raster {
    fn fill(&mut self, path: &tiny_skia::Path, colour: [u8; 4]) {
        let paint = paint_of(colour);
        let (rule, at) = (FillRule::Winding, Transform::identity());
        self.pixmap.fill_path(path, &paint, rule, at, None);
    }

    fn stroke(&mut self, path: &tiny_skia::Path, s: Stroke) {
        let dash = match s.dash {
            Dash::Solid => None,
            Dash::Dashed => tiny_skia::StrokeDash::new(vec![s.period, 0.7 * s.period], 0.0),
            Dash::Dotted => tiny_skia::StrokeDash::new(vec![0.01, s.period], 0.0),
        };
        let stroke = tiny_skia::Stroke {
            width: s.width,
            line_cap: tiny_skia::LineCap::Round,
            line_join: tiny_skia::LineJoin::Round,
            dash,
            ..Default::default()
        };
        let paint = paint_of(s.colour);
        self.pixmap
            .stroke_path(path, &paint, &stroke, Transform::identity(), None);
    }
}

impl Canvas for Raster {
    fn polyline(&mut self, points: &[Vec2], stroke: Stroke) {
        if let Some(path) = path_through(points, false) {
            self.stroke(&path, stroke);
        }
    }

    fn circle(&mut self, c: Vec2, r: f32, fill: Option<[u8; 4]>, stroke: Option<Stroke>) {
        let Some(path) = PathBuilder::from_circle(c.x, c.y, r.max(0.01)) else {
            return;
        };
        if let Some(f) = fill {
            self.fill(&path, f);
        }
        if let Some(s) = stroke {
            self.stroke(&path, s);
        }
    }

    fn polygon(&mut self, points: &[Vec2], fill: [u8; 4]) {
        if let Some(path) = path_through(points, true) {
            self.fill(&path, fill);
        }
    }

    fn text(&mut self, at: Vec2, text: &str, size: f32, c: [u8; 4], anchor: Anchor) {
        let align = match anchor {
            Anchor::Start => 0.0,
            Anchor::Middle => 0.5,
            Anchor::End => 1.0,
        };
        self.texts
            .push((at, text.to_string(), size, [c[0], c[1], c[2]], align));
    }
}
