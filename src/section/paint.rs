//! Drawing a [`Diagram`] onto a canvas: the one routine the window, the SVG and the PNG
//! share, so that they show the same marks at the same sizes.

use super::{
    ARC_RADIUS, Anchor, Dash, Diagram, Ink, Item, Label, RayLine, Symbol, Theme, clip_segment,
};
use crate::tracer::End;
use glam::Vec2;

/// How a line is stroked, in canvas points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stroke {
    /// Width.
    pub width: f32,
    /// Colour, RGBA with straight alpha.
    pub colour: [u8; 4],
    /// Dashes.
    pub dash: Dash,
    /// The length of a dash (or the gap between dots), for `dash`.
    pub period: f32,
}

/// Something a diagram can be drawn on. Coordinates are canvas points, y down.
pub trait Canvas {
    /// A line through `points`.
    fn polyline(&mut self, points: &[Vec2], stroke: Stroke);
    /// A circle, filled with `fill` and outlined with `stroke` where given.
    fn circle(&mut self, center: Vec2, radius: f32, fill: Option<[u8; 4]>, stroke: Option<Stroke>);
    /// A filled polygon.
    fn polygon(&mut self, points: &[Vec2], fill: [u8; 4]);
    /// One line of text of height `size`, centred vertically on `at`.
    fn text(&mut self, at: Vec2, text: &str, size: f32, colour: [u8; 4], anchor: Anchor);
    /// The labels that follow, up to the next call, belong to the interface of ray-tree
    /// node `node` (`None`: to none). An SVG groups them; other canvases ignore it.
    fn group(&mut self, _node: Option<usize>) {}
}

/// Where a diagram's plane lands on a canvas: the view scaled uniformly into the canvas
/// rectangle, centred, below a band for the title and above one for the notes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// The canvas rectangle: top-left corner and size.
    pub canvas: (Vec2, Vec2),
    /// Text height, in canvas points; every other size scales with it.
    pub text: f32,
    scale: f32,
    // The canvas point of the view's upper-left corner.
    origin: Vec2,
    view: (Vec2, Vec2),
    // The heights of the title's band and the notes' band.
    bands: (f32, f32),
}

/// The width of a character, as a fraction of the text's height (egui's Ubuntu Light
/// averages about half): enough to tell whether two labels would overlap.
const TEXT_WIDTH: f32 = 0.52;

/// Text of this height draws everything at its nominal size (a ray of weight 1 is
/// [`super::RAY_WIDTH`] wide).
const NOMINAL_TEXT: f32 = 15.0;

/// The room the view of a diagram gets on a canvas of `size` with text `text` high, and
/// the heights of the bands above and below it: for the title (if there is one) and for
/// `notes`, wrapped to the canvas's width.
pub fn room(size: Vec2, text: f32, title: bool, notes: &[String]) -> (Vec2, (f32, f32)) {
    let line = 1.35 * text;
    let top = if title { 1.6 } else { 0.5 } * line;
    let bottom = (wrap(notes, size.x, text).len() as f32 + 0.5) * line;
    let margin = 0.5 * text;
    let room = Vec2::new(
        (size.x - 2.0 * margin).max(1.0),
        (size.y - top - bottom).max(1.0),
    );
    (room, (top, bottom))
}

impl Fit {
    /// The fit of `diagram` into the canvas rectangle at `top_left` of `size`, with text
    /// `text` points high.
    pub fn new(diagram: &Diagram, top_left: Vec2, size: Vec2, text: f32) -> Fit {
        let title = !diagram.title.is_empty();
        let (room, (top, bottom)) = room(size, text, title, &diagram.notes);
        let margin = 0.5 * text;
        let (lo, hi) = diagram.view;
        let extent = (hi - lo).max(Vec2::splat(1e-6));
        let scale = (room.x / extent.x).min(room.y / extent.y);
        let used = extent * scale;
        let origin = top_left + Vec2::new(margin, top) + 0.5 * (room - used);
        Fit {
            canvas: (top_left, size),
            text,
            scale,
            origin,
            view: diagram.view,
            bands: (top, bottom),
        }
    }

    /// The canvas point of the plane's point `p`.
    pub fn to_canvas(&self, p: Vec2) -> Vec2 {
        self.origin
            + Vec2::new(
                (p.x - self.view.0.x) * self.scale,
                (self.view.1.y - p.y) * self.scale,
            )
    }

    /// The plane's point under the canvas point `c`.
    pub fn to_plane(&self, c: Vec2) -> Vec2 {
        let d = (c - self.origin) / self.scale;
        Vec2::new(self.view.0.x + d.x, self.view.1.y - d.y)
    }

    /// Canvas points per plane unit.
    pub fn scale(&self) -> f32 {
        self.scale
    }

    /// One nominal point at this text size.
    fn unit(&self) -> f32 {
        self.text / NOMINAL_TEXT
    }
}

/// Where `label` lands on the canvas with `offset` and `anchor`: its rectangle (kept
/// inside the canvas, above its notes' band: a label near its edge is moved in, not cut), and the point and anchor to draw its text at.
fn label_rect(
    fit: &Fit,
    label: &Label,
    offset: Vec2,
    anchor: Anchor,
) -> ((Vec2, Vec2), (Vec2, Anchor)) {
    let (top_left, size) = fit.canvas;
    let at = fit.to_canvas(label.at) + offset * fit.unit();
    let width = TEXT_WIDTH * fit.text * label.text.chars().count() as f32;
    let left = match anchor {
        Anchor::Start => at.x,
        Anchor::Middle => at.x - 0.5 * width,
        Anchor::End => at.x - width,
    };
    let inside = |lo: f32, extent: f32, from: f32, to: f32| {
        (from - lo).max(0.0) - (lo + extent - to).max(0.0)
    };
    let half = 0.6 * fit.text;
    // Above the notes' band: a label moved in over the notes was written over them (the
    // title is short, at the left: the band's right stays free).
    let bottom = top_left.y + size.y - fit.bands.1;
    let shift = Vec2::new(
        inside(left, width, top_left.x, top_left.x + size.x),
        inside(at.y - half, 2.0 * half, top_left.y, bottom),
    );
    let (left, at) = (left + shift.x, at + shift);
    let rect = (
        Vec2::new(left, at.y - half),
        Vec2::new(left + width, at.y + half),
    );
    (rect, (at, anchor))
}

/// Whether two rectangles (corners) overlap.
fn overlap(a: &(Vec2, Vec2), b: &(Vec2, Vec2)) -> bool {
    a.0.x < b.1.x && b.0.x < a.1.x && a.0.y < b.1.y && b.0.y < a.1.y
}

/// Draws `diagram` on `canvas` as `fit` places it, in `theme`'s colours; the ray of tree
/// node `highlight` (what the pointer hovers, here or in the tree list) stands out.
pub fn paint(
    diagram: &Diagram,
    canvas: &mut impl Canvas,
    fit: &Fit,
    theme: Theme,
    highlight: Option<usize>,
) {
    let u = fit.unit();
    let (top_left, size) = fit.canvas;
    canvas.polygon(
        &[
            top_left,
            top_left + Vec2::new(size.x, 0.0),
            top_left + size,
            top_left + Vec2::new(0.0, size.y),
        ],
        theme.background(),
    );
    let stroke = |ink: Ink, width: f32, dash: Dash| Stroke {
        width: width * u,
        colour: ink.rgba(theme),
        dash,
        period: if dash == Dash::Dotted { 3.0 } else { 7.0 } * u,
    };
    for item in &diagram.items {
        match item {
            Item::Circle {
                center,
                radius,
                ink,
            } => canvas.circle(
                fit.to_canvas(*center),
                radius * fit.scale(),
                Some(alpha(ink.rgba(theme), 60)),
                Some(stroke(*ink, 1.5, Dash::Solid)),
            ),
            Item::Region { points, ink } => {
                let points: Vec<Vec2> = points.iter().map(|p| fit.to_canvas(*p)).collect();
                canvas.polygon(&points, alpha(ink.rgba(theme), 50));
            }
            Item::Line {
                a,
                b,
                ink,
                width,
                dash,
            } => {
                if let Some((a, b)) = clip_segment(*a, *b, fit.view) {
                    let points = [fit.to_canvas(a), fit.to_canvas(b)];
                    canvas.polyline(&points, stroke(*ink, *width, *dash));
                }
            }
            Item::Ray(ray) => {
                let lit = highlight.is_some() && ray.node == highlight;
                paint_ray(canvas, fit, theme, ray, lit);
            }
            Item::Arc {
                center,
                from,
                to,
                ink,
            } => {
                let c = fit.to_canvas(*center);
                let r = ARC_RADIUS * u;
                let points: Vec<Vec2> = (0..=24)
                    .map(|i| {
                        let a = from + (to - from) * i as f32 / 24.0;
                        c + r * Vec2::new(a.cos(), -a.sin())
                    })
                    .collect();
                canvas.polyline(&points, stroke(*ink, 1.3, Dash::Solid));
            }
            Item::Mark { at, symbol, ink } => {
                paint_symbol(canvas, fit.to_canvas(*at), *symbol, ink.rgba(theme), u);
            }
        }
    }
    // The title's and notes' bands cover whatever of a cut spills out of the view.
    let (top, bottom) = (top_left.y + fit.bands.0, top_left.y + size.y - fit.bands.1);
    for (y0, y1) in [(top_left.y, top), (bottom, top_left.y + size.y)] {
        if y1 > y0 {
            let (a, b) = (
                Vec2::new(top_left.x, y0),
                Vec2::new(top_left.x + size.x, y1),
            );
            canvas.polygon(
                &[a, Vec2::new(b.x, a.y), b, Vec2::new(a.x, b.y)],
                theme.background(),
            );
        }
    }
    let text = Ink::Text.rgba(theme);
    // A label that would overlap one already drawn is left out: at this size there is no
    // room for it (zoomed in, there is). The diagram lists the most important first.
    let mut taken: Vec<(Vec2, Vec2)> = Vec::new();
    let mut placed = Vec::new();
    for label in &diagram.labels {
        // Where it is placed first, else where `instead` says.
        let places = std::iter::once((label.offset, label.anchor)).chain(label.instead);
        let free = places
            .map(|(offset, anchor)| label_rect(fit, label, offset, anchor))
            .find(|(rect, _)| !taken.iter().any(|r| overlap(rect, r)));
        if let Some((rect, at)) = free {
            taken.push(rect);
            placed.push((label, at));
        }
    }
    // Written interface by interface (an SVG groups each one's labels), the others last.
    placed.sort_by_key(|(label, _)| label.node.unwrap_or(usize::MAX));
    for (label, (at, anchor)) in placed {
        canvas.group(label.node);
        canvas.text(at, &label.text, fit.text, label.ink.rgba(theme), anchor);
    }
    canvas.group(None);
    let line = 1.35 * fit.text;
    let left = top_left.x + 0.5 * fit.text;
    if !diagram.title.is_empty() {
        let at = Vec2::new(left, top_left.y + 0.8 * line);
        canvas.text(at, &diagram.title, fit.text, text, Anchor::Start);
    }
    let notes = wrap(&diagram.notes, size.x, fit.text);
    let n = notes.len();
    for (i, note) in notes.iter().enumerate() {
        let y = top_left.y + size.y - (n - i) as f32 * line;
        canvas.text(Vec2::new(left, y), note, fit.text, text, Anchor::Start);
    }
}

/// `notes` broken at spaces into lines that fit a canvas `width` wide at text `text`
/// high (by the estimate of [`TEXT_WIDTH`]).
fn wrap(notes: &[String], width: f32, text: f32) -> Vec<String> {
    let room = ((width - text) / (TEXT_WIDTH * text)).max(10.0) as usize;
    let mut lines = Vec::new();
    for note in notes {
        let mut line = String::new();
        for word in note.split_whitespace() {
            if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > room {
                lines.push(std::mem::take(&mut line));
            }
            if !line.is_empty() {
                line.push(' ');
            }
            line.push_str(word);
        }
        lines.push(line);
    }
    lines
}

/// `c` with its alpha set to `a`.
fn alpha(c: [u8; 4], a: u8) -> [u8; 4] {
    [c[0], c[1], c[2], a]
}

/// A ray: its line (with a halo when `lit`), and what its end means: a dot where it meets
/// a surface, an arrowhead where it leaves the view, a cross where it was cut.
fn paint_ray(canvas: &mut impl Canvas, fit: &Fit, theme: Theme, ray: &RayLine, lit: bool) {
    // The refracted ray that does not exist: its label says so, beyond the interface.
    if ray.end == End::TotalInternalReflection {
        return;
    }
    let u = fit.unit();
    // Only what lies in the view: a ray that goes on beyond it ends in an arrowhead.
    let Some((a, b)) = clip_segment(ray.a, ray.b, fit.view) else {
        return;
    };
    let beyond = !(ray.b.cmpge(fit.view.0).all() && ray.b.cmple(fit.view.1).all());
    let (a, b) = (fit.to_canvas(a), fit.to_canvas(b));
    let colour = Ink::Ray(ray.kind).rgba(theme);
    let width = ray.width() * u;
    if lit {
        let halo = Stroke {
            width: width + 6.0 * u,
            colour: alpha(Ink::Text.rgba(theme), 110),
            dash: Dash::Solid,
            period: 0.0,
        };
        canvas.polyline(&[a, b], halo);
    }
    let dash = ray.dash();
    let period = if dash == Dash::Dotted {
        2.0 * width.max(1.5 * u)
    } else {
        8.0 * u
    };
    canvas.polyline(
        &[a, b],
        Stroke {
            width,
            colour,
            dash,
            period,
        },
    );
    let along = (b - a).normalize_or_zero();
    match ray.end {
        _ if beyond => {
            // An arrowhead: it goes on out of the picture.
            let side = Vec2::new(-along.y, along.x);
            let head = 9.0 * u;
            canvas.polygon(
                &[
                    b,
                    b - head * along + 0.5 * head * side,
                    b - head * along - 0.5 * head * side,
                ],
                colour,
            );
        }
        End::DepthLimit | End::WeightLimit | End::BudgetLimit => {
            paint_symbol(canvas, b, Symbol::Cross, Ink::Stop.rgba(theme), u);
        }
        End::Miss | End::TotalInternalReflection | End::Split | End::Continued | End::Roulette => {}
        End::LightHit | End::Absorbed | End::Lit | End::Occluded => {
            paint_symbol(canvas, b, Symbol::Dot, colour, u);
        }
    }
}

/// A symbol centred on the canvas point `at`, `u` canvas points to the nominal point.
fn paint_symbol(canvas: &mut impl Canvas, at: Vec2, symbol: Symbol, colour: [u8; 4], u: f32) {
    let line = |width: f32| Stroke {
        width: width * u,
        colour,
        dash: Dash::Solid,
        period: 0.0,
    };
    match symbol {
        Symbol::Camera(dir) => {
            // A pyramid seen side on: its apex the eye, opening the way it looks.
            let d = Vec2::new(dir.x, -dir.y).normalize_or(Vec2::X);
            let side = Vec2::new(-d.y, d.x);
            let (length, half) = (22.0 * u, 11.0 * u);
            let points = [
                at,
                at + length * d + half * side,
                at + length * d - half * side,
            ];
            canvas.polygon(&points, alpha(colour, 90));
            canvas.polyline(&[points[0], points[1], points[2], points[0]], line(1.5));
        }
        Symbol::Light => {
            canvas.circle(at, 6.0 * u, Some(colour), None);
            for i in 0..8 {
                let a = i as f32 * std::f32::consts::FRAC_PI_4;
                let d = Vec2::new(a.cos(), a.sin());
                canvas.polyline(&[at + 9.0 * u * d, at + 13.0 * u * d], line(1.5));
            }
        }
        Symbol::Cross => {
            let r = 6.0 * u;
            canvas.polyline(&[at - Vec2::splat(r), at + Vec2::splat(r)], line(2.5));
            canvas.polyline(&[at + Vec2::new(-r, r), at + Vec2::new(r, -r)], line(2.5));
        }
        Symbol::Dot => canvas.circle(at, 3.0 * u, Some(colour), None),
    }
}
