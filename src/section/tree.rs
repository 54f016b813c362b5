//! The section view: the scene cut by the plane that holds a pixel's camera ray and the
//! normal where it first meets a surface, with the pixel's ray tree drawn in it true to
//! scale, and the lecture's angles and indices at each interface.

use super::cut::{Piece, cut, cut_polygon};
use super::framing::{first_frame, shown_points, view_of, within, zoomed};
use super::{
    Anchor, Dash, Diagram, Ink, Item, Label, RayLine, Symbol, angle_marks, clip_segment, degrees,
    index,
};
use crate::camera::CameraFrame;
use crate::material::Material;
use crate::math::{Vec3, orthonormal_basis};
use crate::scene::Scene;
use crate::tracer::{End, RayKind, RayTree, TreeNode};
use glam::Vec2;

/// A plane with a frame of its own: points of space become 2D points of the diagram.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SectionPlane {
    /// The diagram's (0, 0).
    pub origin: Vec3,
    /// The diagram's x axis, a unit vector in the plane.
    pub x: Vec3,
    /// The diagram's y axis (up), a unit vector in the plane.
    pub y: Vec3,
    /// The plane's unit normal, x × y.
    pub normal: Vec3,
}

impl SectionPlane {
    /// The plane of `tree`'s camera ray and the normal where it first meets a surface,
    /// framed as a textbook draws an interface: the hit at the origin, the normal up, the
    /// ray coming in from the left. Head on, or where the ray meets nothing, the plane
    /// holds the ray and the camera's `up` instead. `None` for an empty tree.
    pub fn of_tree(tree: &RayTree, up: Vec3) -> Option<SectionPlane> {
        let root = tree.nodes.first()?;
        let d = root.ray.dir.normalize_or(Vec3::Z);
        let (origin, y, x) = match root.hit {
            Some(h) => {
                let n = h.normal.normalize_or(-d);
                let y = if n.dot(d) > 0.0 { -n } else { n };
                // Along the surface, the way the ray travels; head on, the image's right.
                let along = d - d.dot(y) * y;
                let x = if along.length() > 1e-4 {
                    along.normalize()
                } else {
                    y.cross(up).normalize_or(orthonormal_basis(y).0)
                };
                (h.point, y, x)
            }
            None => {
                let y = (up - up.dot(d) * d).normalize_or(orthonormal_basis(d).0);
                (root.ray.origin, y, d)
            }
        };
        let y = x.cross(y).cross(x).normalize_or(y);
        Some(SectionPlane {
            origin,
            x,
            y,
            normal: x.cross(y),
        })
    }

    /// The point of the diagram where `p` lands, projected onto the plane.
    pub fn to_plane(&self, p: Vec3) -> Vec2 {
        let r = p - self.origin;
        Vec2::new(r.dot(self.x), r.dot(self.y))
    }

    /// The point of space at the diagram's point `q`.
    pub fn to_space(&self, q: Vec2) -> Vec3 {
        self.origin + q.x * self.x + q.y * self.y
    }

    /// How far `p` lies off the plane, signed along its normal.
    pub fn distance(&self, p: Vec3) -> f32 {
        (p - self.origin).dot(self.normal)
    }
}

/// The canvas a section is drawn for, and how far it is zoomed in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Room {
    /// The canvas's size, in points.
    pub size: Vec2,
    /// Its text height, in points.
    pub text: f32,
    /// 1 shows the whole tree; more zooms in on the first hit, up to [`MAX_ZOOM`](super::MAX_ZOOM).
    pub zoom: f32,
    /// With its title and legend (a hall's dock has no room for them: its tab names it).
    pub titled: bool,
}

/// Interfaces are labelled where the ray meeting them carries at least this much of its
/// sample (the camera ray carries 1): the faint internal bounces would bury the rest.
pub const LABEL_WEIGHT: f32 = 0.1;

/// The section of `tree`, the ray tree of `pixel` in `scene` seen through `frame`: the
/// scene cut by [`SectionPlane::of_tree`]'s plane (circles, lines, segments, filled by
/// material), the tree's rays drawn in it (their widths by weight; shadow rays dashed;
/// rays that leave the plane dotted, projected onto it), the camera, the image plane and
/// the lights marked, and at each interface the normal, θi, θr, θt and η1, η2. `None` for
/// an empty tree.
///
/// The view is shaped to fill the canvas `on` describes (as [`super::Fit`] places it
/// there), so that what reaches the canvas's edge is cut there, and zoomed in on the
/// first hit by its `zoom`.
pub fn section(
    scene: &Scene,
    frame: &CameraFrame,
    tree: &RayTree,
    pixel: (u32, u32),
    on: Room,
) -> Option<Diagram> {
    let corners = frame.film_corners(1.0);
    let up = (corners[0] - corners[3]).normalize_or(Vec3::Y);
    let plane = SectionPlane::of_tree(tree, up)?;
    let root = tree.nodes.first()?;
    let eye = root.ray.origin;
    // The diagram's scale: how far the camera ray goes before it meets something.
    let reach = root.hit.map_or(10.0, |h| h.point.distance(eye)).max(1e-3);
    let off_plane = 1e-3 * reach;
    let ends: Vec<(Vec3, Vec3)> = tree.nodes.iter().map(|n| ray_ends(n, reach)).collect();

    let at_eye = plane.to_plane(eye);
    let lights: Vec<Vec3> = scene.lights.iter().map(|l| l.center()).collect();
    let shown = shown_points(tree, &ends, |p| plane.to_plane(p), at_eye, &lights, reach);
    // A hall's large text has no room for the indices at each interface: one line under
    // the drawing gives the first interface's.
    let notes = match (on.titled, root.hit.and_then(|h| h.n1_n2)) {
        (true, _) => vec![
            "Width: the ray's weight. Dashed: shadow rays. Dotted: rays that leave this plane, drawn projected onto it.".to_string(),
        ],
        (false, Some((n1, n2))) => vec![format!("η1 = {}, η2 = {}", index(n1), index(n2))],
        (false, None) => Vec::new(),
    };
    let (room, _) = super::paint::room(on.size, on.text, on.titled, &notes);
    let aspect = room.x / room.y;
    let whole = view_of(shown.into_iter(), aspect);
    let first = plane.to_plane(root.hit.map_or(eye, |h| h.point));
    let (near, through_id) = first_frame(tree, |p| plane.to_plane(p), first, reach, aspect);
    let view = zoomed(whole, near, first, on.zoom);
    let mut d = Diagram {
        title: match on.titled {
            true => format!("Section through pixel ({}, {}), sample 0", pixel.0, pixel.1),
            false => String::new(),
        },
        view,
        notes,
        ..Default::default()
    };
    scene_cut(&mut d, scene, &plane, root.ray.time);
    let look = frame.forward();
    let look = Vec2::new(look.dot(plane.x), look.dot(plane.y));
    place(
        &mut d,
        first,
        at_eye,
        Symbol::Camera(look),
        Ink::Camera,
        "camera",
    );
    if within(at_eye, view) {
        image_plane(&mut d, frame, &plane, eye, reach);
    }
    for c in lights {
        let text = match plane.distance(c).abs() > off_plane {
            true => "light (projected)",
            false => "light",
        };
        place(
            &mut d,
            first,
            plane.to_plane(c),
            Symbol::Light,
            Ink::Emitter,
            text,
        );
    }
    let marks = rays(&mut d, tree, &ends, (&plane, off_plane), on.titled);
    rank_labels(&mut d, marks, through_id);
    Some(d)
}

/// Each of `tree`'s rays (drawn from and to `ends`; projected where an end is more than
/// `off_plane` from the plane), its end's label, and the marks at the interfaces it meets
/// (not of rays that leave the plane, nor too faint to label);
/// returned, the interfaces' labels, without their indices where the diagram is not
/// `titled` (a hall: one line of notes gives them).
fn rays(
    d: &mut Diagram,
    tree: &RayTree,
    ends: &[(Vec3, Vec3)],
    (plane, off_plane): (&SectionPlane, f32),
    titled: bool,
) -> Vec<(Mark, Label)> {
    let mut marks = Vec::new();
    for (i, (n, &(a, b))) in tree.nodes.iter().zip(ends).enumerate() {
        let projected = plane.distance(a).abs() > off_plane || plane.distance(b).abs() > off_plane;
        let (a2, b2) = (plane.to_plane(a), plane.to_plane(b));
        let weight = match n.kind {
            RayKind::Camera => 1.0,
            _ => n.path_weight,
        };
        d.items.push(Item::Ray(RayLine {
            a: a2,
            b: b2,
            kind: n.kind,
            weight,
            node: Some(i),
            projected,
            end: n.end,
        }));
        end_label(d, tree, i, (a2, b2), plane);
        if !projected && weight >= LABEL_WEIGHT {
            let labels = interface(d, tree, i, plane);
            marks.extend(
                labels
                    .into_iter()
                    .filter(|(m, _)| titled || *m != Mark::Index),
            );
        }
    }
    marks
}

/// Orders `d`'s labels, with the interfaces' `marks`, by rank: where labels would
/// overlap, the first drawn stays. First the bends at the way into the first object and
/// out of it (node 0 and the refracted ray `through`: what the Snell slide writes), then
/// the reflections and indices there, then the other rays' labels, then the rest (camera,
/// lights).
fn rank_labels(d: &mut Diagram, marks: Vec<(Mark, Label)>, through: Option<usize>) {
    let rank = |l: &Label, mark: Option<Mark>| {
        let way = matches!(l.node, Some(n) if n == 0 || Some(n) == through);
        match (way, mark, l.node) {
            (true, Some(Mark::Bend), _) => 0,
            (true, Some(Mark::Mirror), _) => 1,
            (true, Some(Mark::Index), _) => 2,
            (_, _, Some(_)) => 3,
            (_, _, None) => 4,
        }
    };
    let mut ranked: Vec<(u8, Label)> = d.labels.drain(..).map(|l| (rank(&l, None), l)).collect();
    ranked.extend(marks.into_iter().map(|(m, l)| (rank(&l, Some(m)), l)));
    ranked.sort_by_key(|(r, _)| *r);
    d.labels = ranked.into_iter().map(|(_, l)| l).collect();
}

/// Where node `n`'s ray is drawn from and to: its hit or end, or for a branch pruned
/// before it was traced, a stub a tenth of `reach` long along its would-be direction.
fn ray_ends(n: &TreeNode, reach: f32) -> (Vec3, Vec3) {
    let a = n.ray.origin;
    match n.end {
        End::DepthLimit | End::WeightLimit | End::BudgetLimit => (a, a + 0.1 * reach * n.ray.dir),
        _ => (a, n.end_point),
    }
}

fn label(at: Vec2, offset: Vec2, text: &str, anchor: Anchor, node: Option<usize>) -> Label {
    Label {
        at,
        offset,
        text: text.into(),
        ink: Ink::Text,
        anchor,
        node,
        instead: None,
    }
}

/// What a material's cut is drawn in.
fn ink_of(m: &Material) -> Ink {
    match m {
        Material::Dielectric(_) => Ink::Glass,
        Material::Glazed(_) => Ink::Glaze,
        Material::Mirror(_) | Material::Glossy(_) | Material::Conductor(_) => Ink::Metal,
        Material::Diffuse(_) => Ink::Matte,
        Material::Emissive(_) => Ink::Emitter,
    }
}

/// Every object's cut, clipped to the view.
fn scene_cut(d: &mut Diagram, scene: &Scene, plane: &SectionPlane, time: f32) {
    let view = d.view;
    let far = 4.0 * (view.1 - view.0).max_element();
    for (j, shape) in scene.shapes.iter().enumerate() {
        let ink = scene
            .object_materials
            .get(j)
            .and_then(|&m| scene.materials.get(m as usize))
            .map_or(Ink::Matte, ink_of);
        for piece in cut(shape, plane, time) {
            let segment = match piece {
                Piece::Circle { center, radius } => {
                    d.items.push(Item::Circle {
                        center,
                        radius,
                        ink,
                    });
                    continue;
                }
                Piece::Segment(a, b) => (a, b),
                Piece::Line { point, dir } => {
                    let dir = dir.normalize_or_zero();
                    (point - far * dir, point + far * dir)
                }
            };
            if let Some((a, b)) = clip_segment(segment.0, segment.1, view) {
                d.items.push(Item::Line {
                    a,
                    b,
                    ink,
                    width: 2.5,
                    dash: Dash::Solid,
                });
            }
        }
    }
}

/// `symbol` at `at` with its name, or where `at` lies outside the view, at the view's
/// edge on the way to it from `from` (the first hit: the camera's mark then sits on the
/// camera ray), named "to the …".
fn place(d: &mut Diagram, from: Vec2, at: Vec2, symbol: Symbol, ink: Ink, name: &str) {
    let (lo, hi) = d.view;
    let (at, text) = match within(at, d.view) {
        true => (at, name.to_string()),
        false => {
            // Where the line leaves the view, drawn back a little inside it.
            let edge = clip_segment(from, at, d.view).map_or(from, |(_, b)| b);
            let inside = edge - 0.04 * (hi - lo).max_element() * (at - from).normalize_or_zero();
            (inside, format!("to the {name}"))
        }
    };
    d.items.push(Item::Mark { at, symbol, ink });
    // Beside it, towards the middle of the view.
    let (offset, anchor) = match at.x > lo.x + 0.7 * (hi.x - lo.x) {
        true => (Vec2::new(-18.0, 0.0), Anchor::End),
        false => (Vec2::new(18.0, 0.0), Anchor::Start),
    };
    d.labels.push(label(at, offset, &text, anchor, None));
}

/// The image plane's cut, a quarter of the way from the eye to the first hit.
fn image_plane(d: &mut Diagram, frame: &CameraFrame, plane: &SectionPlane, eye: Vec3, reach: f32) {
    // As far along the view as the eye is from the lens centre's plane (a thin lens's
    // rays start off centre), and a quarter of the way on.
    let distance = 0.25 * reach + (eye - frame.origin()).dot(frame.forward());
    if let Some(Piece::Segment(a, b)) = cut_polygon(&frame.film_corners(distance), plane) {
        d.items.push(Item::Line {
            a,
            b,
            ink: Ink::Guide,
            width: 2.0,
            dash: Dash::Solid,
        });
        let top = if a.y > b.y { a } else { b };
        d.labels.push(label(
            top,
            Vec2::new(0.0, -14.0),
            "image plane",
            Anchor::Middle,
            None,
        ));
    }
}

/// What a ray's end means, where the lecture names it: total internal reflection, the
/// cuts by depth, weight and budget, and where a shadow ray is blocked.
fn end_label(
    d: &mut Diagram,
    tree: &RayTree,
    i: usize,
    (a, b): (Vec2, Vec2),
    plane: &SectionPlane,
) {
    let Some(n) = tree.nodes.get(i) else { return };
    let text = match n.end {
        End::TotalInternalReflection => "total internal reflection",
        End::DepthLimit => "cut: depth limit",
        End::WeightLimit => "cut: weight < min",
        End::BudgetLimit => "cut: ray budget",
        End::Occluded => "blocked",
        _ => return,
    };
    let away = match n.end {
        // Beyond the interface, where the refracted ray would have gone: against the
        // normal of the hit it would have left from.
        End::TotalInternalReflection => {
            let normal = n
                .parent
                .and_then(|p| tree.nodes.get(p)?.hit)
                .map(|h| h.normal);
            let normal = normal.map_or(Vec2::Y, |v| Vec2::new(v.dot(plane.x), v.dot(plane.y)));
            -normal.normalize_or(Vec2::Y)
        }
        _ => (b - a).normalize_or_zero(),
    };
    d.labels.push(Label {
        ink: Ink::Stop,
        ..label(
            b,
            Vec2::new(away.x, -away.y) * 24.0,
            text,
            Anchor::Middle,
            Some(i),
        )
    });
}

/// What an interface's label says: how the ray bends (θi, θt), how it reflects (θr), or
/// an index (η1, η2). Where labels would overlap, the first kept on the way through the
/// first object is the bend: the Snell slide's subject.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mark {
    Bend,
    Mirror,
    Index,
}

/// The lecture's marks at node `i`'s hit, if it meets an interface between two indices:
/// the normal and the arcs of the angles θi, θr and θt; returned, their labels with
/// theirs values, and η1, η2 on their sides.
fn interface(
    d: &mut Diagram,
    tree: &RayTree,
    i: usize,
    plane: &SectionPlane,
) -> Vec<(Mark, Label)> {
    let Some(n) = tree.nodes.get(i) else {
        return Vec::new();
    };
    let Some(h) = n.hit else {
        return Vec::new();
    };
    // An interface between two indices, or a mirror (a reflected child and no indices).
    let mirror = tree.children(i).any(|(_, c)| c.kind == RayKind::Reflect);
    if h.n1_n2.is_none() && !mirror {
        return Vec::new();
    }
    let in_plane = |v: Vec3| Vec2::new(v.dot(plane.x), v.dot(plane.y));
    let p = plane.to_plane(h.point);
    let normal = in_plane(h.normal).normalize_or(Vec2::Y);
    let length = 0.12 * (d.view.1 - d.view.0).max_element();
    d.items.push(Item::Line {
        a: p - length * normal,
        b: p + length * normal,
        ink: Ink::Normal,
        width: 1.3,
        dash: Dash::Dashed,
    });
    let toward_eye = in_plane(-n.ray.dir).normalize_or_zero();
    let mut labels = Vec::new();
    let mut angle = |from: Vec2, to: Vec2, text: String, mark: Mark| {
        let (arc, label) = angle_marks(p, from, to, text, Some(i));
        d.items.push(arc);
        labels.push((mark, label));
    };
    angle(
        normal,
        toward_eye,
        format!("θi = {}", degrees(h.theta_i)),
        Mark::Bend,
    );
    for (_, child) in tree.children(i) {
        let dir = in_plane(child.ray.dir).normalize_or_zero();
        match (child.kind, child.end) {
            (_, End::TotalInternalReflection) | (RayKind::Shadow | RayKind::Camera, _) => {}
            (RayKind::Reflect, _) => angle(
                normal,
                dir,
                format!("θr = {}", degrees(h.theta_i)),
                Mark::Mirror,
            ),
            (RayKind::Refract, _) => {
                if let Some(t) = h.theta_t {
                    angle(-normal, dir, format!("θt = {}", degrees(t)), Mark::Bend);
                }
            }
        }
    }
    // The indices on their sides of the interface, beside the normal's ends.
    let along = Vec2::new(normal.x, -normal.y);
    let side = Vec2::new(-along.y, along.x) * 10.0;
    let Some((n1, n2)) = h.n1_n2 else {
        return labels;
    };
    let indices = [
        (1.0, format!("η1 = {}", index(n1))),
        (-1.0, format!("η2 = {}", index(n2))),
    ]
    .into_iter()
    .map(|(sign, text)| {
        let at = p + sign * length * normal;
        let label = label(at, side + sign * along * 4.0, &text, Anchor::Start, Some(i));
        (Mark::Index, label)
    });
    labels.extend(indices);
    labels
}
