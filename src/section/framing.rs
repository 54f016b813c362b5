//! How a section is framed: the view that holds the whole tree, the first object's frame,
//! and the zoom between them.

use crate::math::Vec3;
use crate::tracer::{End, RayKind, RayTree};
use glam::Vec2;

/// The deepest zoom into a section.
pub const MAX_ZOOM: f32 = 50.0;

/// The zoom that frames the first object the camera ray meets, its way through it and
/// no more (see `zoomed`).
const FRAME_ZOOM: f32 = 3.0;

/// What the whole tree's view holds: where the tree's rays meet things, and the camera
/// (at `at_eye` in the plane) and the `lights` where they are near enough to show without
/// shrinking that (the others are marked at its edge); around a lone hit, at least 0.4 of
/// the camera ray's length (`reach`) and a margin.
pub(super) fn shown_points(
    tree: &RayTree,
    ends: &[(Vec3, Vec3)],
    to_plane: impl Fn(Vec3) -> Vec2,
    at_eye: Vec2,
    lights: &[Vec3],
    reach: f32,
) -> Vec<Vec2> {
    let mut core = Vec::new();
    for (n, &(a, b)) in tree.nodes.iter().zip(ends) {
        if n.kind != RayKind::Camera {
            core.push(to_plane(a));
        }
        if !matches!(n.end, End::Miss | End::Lit | End::Occluded) {
            core.push(to_plane(b));
        }
    }
    let (lo, hi) = bounds(core.iter().copied());
    let extent = ((hi - lo).max_element()).max(0.4 * reach);
    let near = |p: Vec2| p.distance(0.5 * (lo + hi)) < 1.5 * extent;
    let mut shown = core;
    shown.extend(
        [at_eye]
            .into_iter()
            .chain(lights.iter().map(|c| to_plane(*c)))
            .filter(|p| near(*p)),
    );
    if shown.len() < 3 {
        shown.extend([
            lo - Vec2::splat(0.2 * extent),
            hi + Vec2::splat(0.2 * extent),
        ]);
    }
    shown
}

/// The first object's frame, shaped to `aspect`: the camera ray's way through it, from
/// where it enters (`first`) to where the refracted ray meets the next surface, with 0.3
/// of that around; for a surface it does not enter, 0.4 of the camera ray's length
/// (`reach`) about the hit. And the refracted ray's node, if any.
pub(super) fn first_frame(
    tree: &RayTree,
    to_plane: impl Fn(Vec3) -> Vec2,
    first: Vec2,
    reach: f32,
    aspect: f32,
) -> ((Vec2, Vec2), Option<usize>) {
    let refracted = tree.children(0).find(|(_, n)| n.kind == RayKind::Refract);
    let through = refracted
        .and_then(|(_, n)| n.hit)
        .map(|h| to_plane(h.point));
    let chord = through.map_or(0.4 * reach, |b| b.distance(first).max(1e-3 * reach));
    let pad = Vec2::splat(0.3 * chord);
    let far = through.unwrap_or(first);
    let corners = [first - pad, first + pad, far - pad, far + pad];
    (
        view_of(corners.into_iter(), aspect),
        refracted.map(|(i, _)| i),
    )
}

/// The smallest rectangle holding the finite `points` (a unit square about the origin
/// if there are none).
fn bounds(points: impl Iterator<Item = Vec2>) -> (Vec2, Vec2) {
    let (mut lo, mut hi) = (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
    for p in points.filter(|p| p.is_finite()) {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    match lo.is_finite() && hi.is_finite() {
        true => (lo, hi),
        false => (Vec2::splat(-1.0), Vec2::splat(1.0)),
    }
}

/// The rectangle around `points`, padded, widened or heightened to `aspect` (width over
/// height).
/// The view at `zoom`: `whole` at 1; narrowing geometrically to `near` (the first
/// object's frame) at [`FRAME_ZOOM`], so that a slide's framing keeps the first hit and
/// its labels the same size whatever the rest of the tree reaches (a refracted ray sent
/// far across the floor by a higher IOR zoomed the sphere out to a few pixels); past it,
/// further in about the first hit, `first`.
pub(super) fn zoomed(
    whole: (Vec2, Vec2),
    near: (Vec2, Vec2),
    first: Vec2,
    zoom: f32,
) -> (Vec2, Vec2) {
    let zoom = zoom.clamp(1.0, MAX_ZOOM);
    let t = (zoom.ln() / FRAME_ZOOM.ln()).min(1.0);
    let size = |v: (Vec2, Vec2)| (v.1 - v.0).max(Vec2::splat(1e-6));
    let centre = |v: (Vec2, Vec2)| 0.5 * (v.0 + v.1);
    let (w, n) = (size(whole), size(near));
    // w^(1 − t) n^t, each axis.
    let mut half = 0.5
        * Vec2::new(
            w.x.powf(1.0 - t) * n.x.powf(t),
            w.y.powf(1.0 - t) * n.y.powf(t),
        );
    let mut about = centre(whole).lerp(centre(near), t);
    let past = zoom / FRAME_ZOOM;
    if past > 1.0 {
        half /= past;
        about += (1.0 - 1.0 / past) * (first - about);
    }
    (about - half, about + half)
}

pub(super) fn view_of(points: impl Iterator<Item = Vec2>, aspect: f32) -> (Vec2, Vec2) {
    let (lo, hi) = bounds(points);
    let size = (hi - lo).max(Vec2::splat(1e-3));
    let size = size + Vec2::splat(0.16 * size.max_element());
    let aspect = if aspect.is_finite() && aspect > 0.0 {
        aspect
    } else {
        1.0
    };
    let size = size.max(Vec2::new(size.y * aspect, size.x / aspect));
    let centre = 0.5 * (lo + hi);
    (centre - 0.5 * size, centre + 0.5 * size)
}

pub(super) fn within(p: Vec2, view: (Vec2, Vec2)) -> bool {
    p.cmpge(view.0).all() && p.cmple(view.1).all()
}
