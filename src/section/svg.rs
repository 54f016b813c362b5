//! A diagram as SVG, the format a lecturer pastes into slides: every label a real text
//! element, the labels of each interface grouped (`<g class="interface">`).

use super::paint::{Canvas, Stroke};
use super::{Anchor, Dash, Diagram, Fit, Theme, paint};
use glam::Vec2;
use std::fmt::Write;

/// `diagram` as an SVG document of `width` × `height` points in `theme`'s colours.
pub fn to_svg(diagram: &Diagram, width: u32, height: u32, theme: Theme) -> String {
    let (w, h) = (width.max(1) as f32, height.max(1) as f32);
    let mut svg = Svg {
        out: format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" font-family=\"Ubuntu, 'Segoe UI', 'Helvetica Neue', Arial, sans-serif\">\n"
        ),
        group: None,
    };
    let fit = Fit::new(
        diagram,
        Vec2::ZERO,
        Vec2::new(w, h),
        text_size(width, height),
    );
    paint(diagram, &mut svg, &fit, theme, None);
    svg.out.push_str("</svg>\n");
    svg.out
}

/// The text height for a picture of `w` × `h` points: 1/36 of its height (15 points at
/// 540), never under 11.
pub fn text_size(w: u32, h: u32) -> f32 {
    (h.min(w * 3 / 4) as f32 / 36.0).max(11.0)
}

struct Svg {
    out: String,
    group: Option<usize>,
}

/// `c` as the value of `attribute` (`fill` or `stroke`), with its opacity where it has
/// one: `fill="#rrggbb" fill-opacity="0.5"`.
fn colour(attribute: &str, c: [u8; 4]) -> String {
    let opacity = match c[3] {
        255 => String::new(),
        a => format!(" {attribute}-opacity=\"{:.3}\"", a as f32 / 255.0),
    };
    format!(
        "{attribute}=\"#{:02x}{:02x}{:02x}\"{opacity}",
        c[0], c[1], c[2]
    )
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

impl Canvas for Svg {
    fn polyline(&mut self, points: &[Vec2], stroke: Stroke) {
        let mut list = String::new();
        for p in points {
            let _ = write!(list, "{:.2},{:.2} ", p.x, p.y);
        }
        let dash = match stroke.dash {
            Dash::Solid => String::new(),
            Dash::Dashed => format!(
                " stroke-dasharray=\"{:.2} {:.2}\"",
                stroke.period,
                0.7 * stroke.period
            ),
            Dash::Dotted => format!(" stroke-dasharray=\"0.01 {:.2}\"", stroke.period),
        };
        let _ = writeln!(
            self.out,
            "<polyline points=\"{}\" fill=\"none\" {} stroke-width=\"{:.2}\" stroke-linecap=\"round\" stroke-linejoin=\"round\"{dash}/>",
            list.trim_end(),
            colour("stroke", stroke.colour),
            stroke.width
        );
    }

    fn circle(&mut self, c: Vec2, r: f32, fill: Option<[u8; 4]>, stroke: Option<Stroke>) {
        let fill = fill.map_or("fill=\"none\"".into(), |f| colour("fill", f));
        let stroke = stroke.map_or(String::new(), |s| {
            format!(
                " {} stroke-width=\"{:.2}\"",
                colour("stroke", s.colour),
                s.width
            )
        });
        let _ = writeln!(
            self.out,
            "<circle cx=\"{:.2}\" cy=\"{:.2}\" r=\"{:.2}\" {fill}{stroke}/>",
            c.x, c.y, r
        );
    }

    fn polygon(&mut self, points: &[Vec2], fill: [u8; 4]) {
        let mut list = String::new();
        for p in points {
            let _ = write!(list, "{:.2},{:.2} ", p.x, p.y);
        }
        let _ = writeln!(
            self.out,
            "<polygon points=\"{}\" {}/>",
            list.trim_end(),
            colour("fill", fill)
        );
    }

    fn text(&mut self, at: Vec2, text: &str, size: f32, c: [u8; 4], anchor: Anchor) {
        let anchor = match anchor {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        };
        let _ = writeln!(
            self.out,
            "<text x=\"{:.2}\" y=\"{:.2}\" font-size=\"{:.1}\" {} text-anchor=\"{anchor}\" dominant-baseline=\"central\">{}</text>",
            at.x,
            at.y,
            size,
            colour("fill", c),
            escape(text)
        );
    }

    fn group(&mut self, node: Option<usize>) {
        if node == self.group {
            return;
        }
        if self.group.is_some() {
            self.out.push_str("</g>\n");
        }
        if let Some(n) = node {
            let _ = writeln!(self.out, "<g class=\"interface\" data-node=\"{n}\">");
        }
        self.group = node;
    }
}
