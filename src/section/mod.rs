//! The lecture's own 2D diagrams: the section of a pixel's ray tree through the scene
//! ([`section`]), and the interface workbench ([`Workbench`]): one flat interface, one ray.
//!
//! Both are a [`Diagram`]: cuts of the scene, rays, angles and labels in the plane's own
//! units (y up). [`paint`] draws one onto any [`Canvas`]: the window's (egui), an SVG
//! ([`to_svg`]) or a PNG ([`to_png`]), so that all three show the same marks in the same
//! colours. This module knows no egui.

mod cut;
mod framing;
mod lens_bench;
mod paint;
mod raster;
mod svg;
mod tree;
mod workbench;

pub use framing::MAX_ZOOM;
pub use lens_bench::Bench;
pub use paint::{Canvas, Fit, Stroke, paint, room};
pub use raster::to_png;
pub use svg::{text_size, to_svg};
pub use tree::{Room, SectionPlane, section};
pub use workbench::{MAX_ANGLE, Workbench};

use crate::tracer::{End, RayKind};
use glam::Vec2;

/// The ink a mark is drawn in: one palette for the window, SVG and PNG ([`Ink::rgba`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ink {
    /// A ray of the tree, by its kind.
    Ray(RayKind),
    /// A dielectric's cut.
    Glass,
    /// A glazed surface's cut.
    Glaze,
    /// A mirror's or metal's cut.
    Metal,
    /// A diffuse surface's cut.
    Matte,
    /// An emitting surface's cut, and the lights.
    Emitter,
    /// A surface normal.
    Normal,
    /// Guides: the image plane, the critical and Brewster angles, angle arcs.
    Guide,
    /// The camera.
    Camera,
    /// Text.
    Text,
    /// Where light stops for a reason the lecture names: total internal reflection,
    /// pruning.
    Stop,
}

/// The background a diagram is drawn on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Theme {
    /// Light marks on near-black: the window's.
    Dark,
    /// Dark marks on white: slides and handouts.
    Light,
}

impl Theme {
    /// The background colour.
    pub fn background(self) -> [u8; 4] {
        match self {
            Theme::Dark => [24, 24, 28, 255],
            Theme::Light => [255, 255, 255, 255],
        }
    }
}

impl Ink {
    /// The colour (RGBA, straight alpha) the ink is drawn in on `theme`'s background. The
    /// rays keep the inspector's colours (white or black, blue, orange, yellow).
    pub fn rgba(self, theme: Theme) -> [u8; 4] {
        let dark = theme == Theme::Dark;
        let pick = |on_dark: [u8; 3], on_light: [u8; 3]| {
            let [r, g, b] = if dark { on_dark } else { on_light };
            [r, g, b, 255]
        };
        match self {
            Ink::Ray(RayKind::Camera) | Ink::Text => pick([240, 240, 240], [20, 20, 20]),
            Ink::Ray(RayKind::Reflect) => pick([90, 200, 255], [0, 105, 190]),
            Ink::Ray(RayKind::Refract) => pick([255, 170, 60], [215, 100, 0]),
            Ink::Ray(RayKind::Shadow) => pick([240, 230, 90], [150, 125, 0]),
            Ink::Glass => pick([120, 190, 230], [60, 140, 200]),
            Ink::Glaze => pick([150, 150, 175], [60, 60, 80]),
            Ink::Metal => pick([200, 200, 210], [110, 110, 125]),
            Ink::Matte => pick([150, 140, 125], [140, 125, 105]),
            Ink::Emitter => pick([255, 220, 120], [210, 160, 0]),
            Ink::Normal | Ink::Guide => pick([160, 160, 170], [120, 120, 130]),
            Ink::Camera => pick([200, 230, 200], [30, 110, 50]),
            Ink::Stop => pick([255, 90, 90], [200, 30, 30]),
        }
    }
}

/// How a line is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dash {
    /// Unbroken.
    Solid,
    /// Long dashes: shadow rays, normals.
    Dashed,
    /// Dots: guides, and rays drawn projected onto the plane they leave.
    Dotted,
}

/// A small symbol at a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Symbol {
    /// The camera, looking along the unit direction (in the plane).
    Camera(Vec2),
    /// A light.
    Light,
    /// An end: a ray that stops here for the reason its label gives.
    Cross,
    /// A point where a ray meets a surface.
    Dot,
}

/// One ray drawn in a diagram.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayLine {
    /// Where it starts, in the plane.
    pub a: Vec2,
    /// Where it ends (cut at the view's edge if it leaves it).
    pub b: Vec2,
    /// Its kind, which gives its colour.
    pub kind: RayKind,
    /// The weight it carries (1 for the camera ray, then R and 1 − R at each split): its
    /// width is proportional to it.
    pub weight: f32,
    /// Its node in the ray tree, if it is one.
    pub node: Option<usize>,
    /// Whether it leaves the plane: it is then drawn projected onto it, dotted.
    pub projected: bool,
    /// Why it ended.
    pub end: End,
}

/// A ray of weight 1 is this wide, in canvas points; widths are proportional to weight.
pub const RAY_WIDTH: f32 = 6.0;
/// Shadow rays are drawn this wide, in canvas points.
pub const SHADOW_WIDTH: f32 = 1.5;
/// No ray is drawn thinner than this, in canvas points, however small its weight.
pub const HAIRLINE: f32 = 0.6;

impl RayLine {
    /// Its width in canvas points: [`RAY_WIDTH`] × its weight, never under [`HAIRLINE`];
    /// a shadow ray, which carries light to its hit rather than weight from the camera,
    /// is drawn [`SHADOW_WIDTH`] wide.
    pub fn width(&self) -> f32 {
        match self.kind {
            RayKind::Shadow => SHADOW_WIDTH,
            _ => (RAY_WIDTH * self.weight).max(HAIRLINE),
        }
    }

    /// How it is dashed: shadow rays dashed, rays that leave the plane dotted.
    pub fn dash(&self) -> Dash {
        if self.projected {
            Dash::Dotted
        } else if self.kind == RayKind::Shadow {
            Dash::Dashed
        } else {
            Dash::Solid
        }
    }
}

/// One mark of a diagram, in the plane's units (y up).
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    /// A circle: a sphere's cut.
    Circle {
        /// Centre.
        center: Vec2,
        /// Radius.
        radius: f32,
        /// Its ink.
        ink: Ink,
    },
    /// A closed polygon, filled: a medium (the workbench's lower side).
    Region {
        /// Corners, in order.
        points: Vec<Vec2>,
        /// Its ink.
        ink: Ink,
    },
    /// A straight mark: a surface's cut, a normal, a guide, the image plane.
    Line {
        /// One end.
        a: Vec2,
        /// The other end.
        b: Vec2,
        /// Its ink.
        ink: Ink,
        /// Width in canvas points.
        width: f32,
        /// How it is dashed.
        dash: Dash,
    },
    /// A ray.
    Ray(RayLine),
    /// An angle at `center` between two directions, drawn as an arc of [`ARC_RADIUS`]
    /// canvas points: from angle `from` to angle `to` (radians, counter-clockwise from +x).
    Arc {
        /// The vertex.
        center: Vec2,
        /// Start direction.
        from: f32,
        /// End direction.
        to: f32,
        /// Its ink.
        ink: Ink,
    },
    /// A symbol at a point.
    Mark {
        /// Where.
        at: Vec2,
        /// What.
        symbol: Symbol,
        /// Its ink.
        ink: Ink,
    },
}

/// Angle arcs are this far from their vertex, in canvas points.
pub const ARC_RADIUS: f32 = 34.0;

/// How a label sits on its point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Anchor {
    /// Text starts at the point.
    Start,
    /// Text is centred on it.
    Middle,
    /// Text ends at it.
    End,
}

/// A piece of text at a point of the plane, moved by `offset` canvas points (y down) so
/// that it sits beside what it names at any zoom.
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    /// The point it names.
    pub at: Vec2,
    /// Where the text's anchor is from it, in canvas points, y down.
    pub offset: Vec2,
    /// The text.
    pub text: String,
    /// Its ink.
    pub ink: Ink,
    /// How it sits on its anchor.
    pub anchor: Anchor,
    /// The ray-tree node whose interface it labels, if any (an SVG groups them).
    pub node: Option<usize>,
    /// Another place for it (offset and anchor), tried where the first would overlap a
    /// label already drawn: the other end of an angle's arc.
    pub instead: Option<(Vec2, Anchor)>,
}

/// A drawing in a plane: marks, labels and lines of notes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Diagram {
    /// One line saying what it shows.
    pub title: String,
    /// The rectangle of the plane shown: its lower-left and upper-right corners.
    pub view: (Vec2, Vec2),
    /// The marks, drawn in order.
    pub items: Vec<Item>,
    /// The labels, drawn over the marks.
    pub labels: Vec<Label>,
    /// Lines of text in the bottom-left corner: the numbers, a legend.
    pub notes: Vec<String>,
}

impl Diagram {
    /// The rays it draws.
    pub fn rays(&self) -> impl Iterator<Item = &RayLine> {
        self.items.iter().filter_map(|i| match i {
            Item::Ray(r) => Some(r),
            _ => None,
        })
    }

    /// The tree node of the ray nearest to `p` (in the plane) within `tolerance`, if any:
    /// what the pointer hovers.
    pub fn ray_near(&self, p: Vec2, tolerance: f32) -> Option<usize> {
        self.rays()
            .filter_map(|r| Some((r.node?, distance_to_segment(p, r.a, r.b))))
            .filter(|&(_, d)| d <= tolerance)
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(node, _)| node)
    }
}

/// An angle in degrees as the diagrams write it: one decimal and a degree sign.
pub fn degrees(angle: f32) -> String {
    format!("{angle:.1}°")
}

/// An index of refraction as the diagrams write it: up to three decimals, no trailing
/// zeros (1.5, 1.33, 1.517).
pub fn index(n: f32) -> String {
    let s = format!("{n:.3}");
    let s = s.trim_end_matches('0');
    let s = s
        .strip_suffix('.')
        .map_or(s.to_string(), |t| format!("{t}.0"));
    s.to_string()
}

/// The marks of the angle at `vertex` from the direction `from` (a normal) to `to` (a
/// ray): its arc, and `text` just beyond the ray on the side away from the normal, so
/// that the label crosses neither line.
fn angle_marks(
    vertex: Vec2,
    from: Vec2,
    to: Vec2,
    text: String,
    node: Option<usize>,
) -> (Item, Label) {
    let (a0, a1) = (from.y.atan2(from.x), to.y.atan2(to.x));
    // The short way round from one to the other.
    let delta =
        (a1 - a0 + std::f32::consts::PI).rem_euclid(std::f32::consts::TAU) - std::f32::consts::PI;
    let arc = Item::Arc {
        center: vertex,
        from: a0,
        to: a0 + delta,
        ink: Ink::Guide,
    };
    // Past the arc's end (the ray), or else past its start (the normal).
    let place = |at: f32| {
        let dir = Vec2::new(at.cos(), -at.sin());
        let anchor = match dir.x {
            x if x > 0.3 => Anchor::Start,
            x if x < -0.3 => Anchor::End,
            _ => Anchor::Middle,
        };
        ((ARC_RADIUS + 12.0) * dir, anchor)
    };
    let (offset, anchor) = place(a0 + delta + 0.22f32.copysign(delta));
    let label = Label {
        at: vertex,
        offset,
        text,
        ink: Ink::Text,
        anchor,
        node,
        instead: Some(place(a0 - 0.22f32.copysign(delta))),
    };
    (arc, label)
}

/// The distance from `p` to the segment from `a` to `b` (the hover tests of the diagrams
/// and of the image's overlay).
pub(crate) fn distance_to_segment(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + t * ab)
}

/// The part of the segment from `a` to `b` inside the rectangle `view`, if any
/// (Liang–Barsky).
fn clip_segment(a: Vec2, b: Vec2, view: (Vec2, Vec2)) -> Option<(Vec2, Vec2)> {
    let d = b - a;
    let (mut t0, mut t1) = (0.0f32, 1.0f32);
    for (p, q) in [
        (-d.x, a.x - view.0.x),
        (d.x, view.1.x - a.x),
        (-d.y, a.y - view.0.y),
        (d.y, view.1.y - a.y),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 <= t1).then(|| (a + t0 * d, a + t1 * d))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_and_angles_read_as_the_lecture_writes_them() {
        assert_eq!(index(1.5), "1.5");
        assert_eq!(index(1.0), "1.0");
        assert_eq!(index(1.333), "1.333");
        assert_eq!(index(2.42), "2.42");
        assert_eq!(degrees(19.471), "19.5°");
    }

    #[test]
    fn every_character_the_diagrams_write_is_in_the_typeface() {
        use ab_glyph::Font;
        let font = ab_glyph::FontRef::try_from_slice(epaint_default_fonts::UBUNTU_LIGHT).unwrap();
        let mut diagrams: Vec<Diagram> = [(1.0, 1.5, 30.0), (1.5, 1.0, 60.0)]
            .into_iter()
            .map(|(n1, n2, theta_i)| {
                Workbench {
                    n1,
                    n2,
                    theta_i,
                    roughness: 0.3,
                }
                .diagram()
            })
            .collect();
        let scene = crate::scene::Scene::load("ray-tree").unwrap();
        let params = crate::params::Params {
            max_depth: 2,
            ..scene.params.clone()
        };
        let tracer = crate::tracer::Tracer::new(&scene, &params, 96, 54);
        let (tree, _) = tracer.inspect(40, 27, 0);
        let room = Room {
            size: Vec2::new(640.0, 480.0),
            text: 15.0,
            zoom: 1.0,
            titled: true,
        };
        diagrams.push(section(&scene, tracer.frame(), &tree, (40, 27), room).unwrap());
        let lens = crate::optics::lens::LensModel::Singlet50
            .prescription()
            .unwrap();
        let lens =
            crate::optics::lens::RealLens::new(&lens, 2000.0, 8.0, 27.0, 1.5, false).unwrap();
        let bench = Bench {
            lens: &lens,
            film: Vec2::new(0.8, 0.2),
            sample: Vec2::new(0.3, 0.7),
        };
        diagrams.push(bench.diagram().unwrap());
        for d in &diagrams {
            let texts = d.labels.iter().map(|l| &l.text).chain(&d.notes);
            for text in texts.chain([&d.title]) {
                for c in text.chars().filter(|c| !c.is_whitespace()) {
                    assert_ne!(font.glyph_id(c).0, 0, "`{c}` in `{text}`");
                }
            }
        }
    }

    #[test]
    fn segments_are_clipped_to_the_view() {
        let view = (Vec2::new(0.0, 0.0), Vec2::new(1.0, 1.0));
        let (a, b) = clip_segment(Vec2::new(-1.0, 0.5), Vec2::new(2.0, 0.5), view).unwrap();
        assert!((a - Vec2::new(0.0, 0.5)).length() < 1e-6);
        assert!((b - Vec2::new(1.0, 0.5)).length() < 1e-6);
        assert!(clip_segment(Vec2::new(-1.0, 2.0), Vec2::new(2.0, 2.0), view).is_none());
        let inside = (Vec2::new(0.2, 0.2), Vec2::new(0.3, 0.4));
        assert_eq!(clip_segment(inside.0, inside.1, view), Some(inside));
    }

    #[test]
    fn the_hovered_ray_is_the_nearest_within_the_tolerance() {
        let ray = |node, y| {
            Item::Ray(RayLine {
                a: Vec2::new(0.0, y),
                b: Vec2::new(1.0, y),
                kind: RayKind::Reflect,
                weight: 1.0,
                node: Some(node),
                projected: false,
                end: End::Miss,
            })
        };
        let d = Diagram {
            items: vec![ray(3, 0.0), ray(7, 0.1)],
            ..Default::default()
        };
        assert_eq!(d.ray_near(Vec2::new(0.5, 0.08), 0.05), Some(7));
        assert_eq!(d.ray_near(Vec2::new(0.5, 0.02), 0.05), Some(3));
        assert_eq!(d.ray_near(Vec2::new(0.5, 0.5), 0.05), None);
    }
}
