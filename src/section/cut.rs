//! The scene cut by a section plane: spheres become circles, planes lines, quads and
//! triangles segments (a mesh's cut is its triangles' segments, a polyline).

use super::SectionPlane;
use crate::geometry::Shape;
use crate::math::Vec3;
use glam::Vec2;

/// A piece of a shape's cut, in the plane's coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Piece {
    /// A sphere's cut.
    Circle {
        /// Centre.
        center: Vec2,
        /// Radius.
        radius: f32,
    },
    /// A flat piece's cut.
    Segment(Vec2, Vec2),
    /// An infinite plane's cut: the line through `point` along `dir`.
    Line {
        /// A point of it.
        point: Vec2,
        /// Its direction.
        dir: Vec2,
    },
}

/// The cut of `shape`, where it is at frame time `time`, by `plane`.
pub(super) fn cut(shape: &Shape, plane: &SectionPlane, time: f32) -> Vec<Piece> {
    match shape {
        Shape::Sphere(s) => {
            let c = s.center_at(time);
            let d = plane.distance(c);
            let r2 = s.radius * s.radius - d * d;
            match r2 > 0.0 {
                true => vec![Piece::Circle {
                    center: plane.to_plane(c),
                    radius: r2.sqrt(),
                }],
                false => Vec::new(),
            }
        }
        Shape::Plane(p) => {
            // In the plane's coordinates s, the points with n·(o + s.x x + s.y y − q) = 0:
            // a line with normal a = (n·x, n·y), a·s = n·(q − o).
            let a = Vec2::new(p.normal.dot(plane.x), p.normal.dot(plane.y));
            if a.length_squared() < 1e-10 {
                return Vec::new();
            }
            let c = p.normal.dot(p.point - plane.origin);
            vec![Piece::Line {
                point: a * (c / a.length_squared()),
                dir: a.perp(),
            }]
        }
        Shape::Quad(q) => {
            let corners = [
                q.corner,
                q.corner + q.edge_u,
                q.corner + q.edge_u + q.edge_v,
                q.corner + q.edge_v,
            ];
            cut_polygon(&corners, plane).into_iter().collect()
        }
        Shape::Mesh(m) => {
            let shift = m.velocity * time;
            let positions = m.positions();
            m.indices()
                .iter()
                .filter_map(|t| {
                    let at = |i: u32| positions.get(i as usize).map(|p| *p + shift);
                    let corners = [at(t[0])?, at(t[1])?, at(t[2])?];
                    cut_polygon(&corners, plane)
                })
                .collect()
        }
        Shape::Instance(instance) => (0..instance.triangle_count())
            .filter_map(|i| cut_polygon(&instance.corners_at(i, time), plane))
            .collect(),
    }
}

/// The segment where a flat convex polygon crosses `plane`, if it does.
pub(super) fn cut_polygon(corners: &[Vec3], plane: &SectionPlane) -> Option<Piece> {
    let d: Vec<f32> = corners.iter().map(|p| plane.distance(*p)).collect();
    let mut crossings = Vec::with_capacity(2);
    for i in 0..corners.len() {
        let j = (i + 1) % corners.len();
        if (d[i] <= 0.0) != (d[j] <= 0.0) {
            let t = d[i] / (d[i] - d[j]);
            crossings.push(plane.to_plane(corners[i] + t * (corners[j] - corners[i])));
        }
    }
    match crossings[..] {
        [a, b, ..] => Some(Piece::Segment(a, b)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Mesh, Plane, Quad, Sphere};

    /// The plane z = 0, x and y its own.
    fn xy() -> SectionPlane {
        SectionPlane {
            origin: Vec3::ZERO,
            x: Vec3::X,
            y: Vec3::Y,
            normal: Vec3::Z,
        }
    }

    #[test]
    fn a_sphere_cut_off_centre_is_a_smaller_circle() {
        let s = Shape::Sphere(Sphere::new(Vec3::new(1.0, 2.0, 0.6), 1.0));
        let pieces = cut(&s, &xy(), 0.0);
        let [Piece::Circle { center, radius }] = pieces[..] else {
            panic!("{pieces:?}")
        };
        assert!((center - Vec2::new(1.0, 2.0)).length() < 1e-6);
        assert!((radius - 0.8).abs() < 1e-6, "√(1 − 0.36) = 0.8: {radius}");
        let far = Shape::Sphere(Sphere::new(Vec3::new(0.0, 0.0, 1.5), 1.0));
        assert!(cut(&far, &xy(), 0.0).is_empty());
    }

    #[test]
    fn a_plane_cuts_a_line_and_a_quad_a_segment() {
        let floor = Shape::Plane(Plane::new(Vec3::new(0.0, -1.0, 0.0), Vec3::Y));
        let [Piece::Line { point, dir }] = cut(&floor, &xy(), 0.0)[..] else {
            panic!()
        };
        assert!((point.y + 1.0).abs() < 1e-6 && dir.y.abs() < 1e-6);
        let quad = Shape::Quad(Quad::new(
            Vec3::new(-1.0, 0.0, -1.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 2.0),
        ));
        let [Piece::Segment(a, b)] = cut(&quad, &xy(), 0.0)[..] else {
            panic!()
        };
        // Where z = 0: half-way up edge_v, so y = 0.5, x from −1 to 1.
        let (lo, hi) = if a.x < b.x { (a, b) } else { (b, a) };
        assert!((lo - Vec2::new(-1.0, 0.5)).length() < 1e-6, "{lo}");
        assert!((hi - Vec2::new(1.0, 0.5)).length() < 1e-6, "{hi}");
    }

    #[test]
    fn a_box_cut_through_its_middle_is_its_outline() {
        let mesh = Mesh::cuboid(Vec3::splat(-1.0), Vec3::splat(1.0)).unwrap();
        let pieces = cut(&Shape::Mesh(mesh), &xy(), 0.0);
        // Two triangles per side face cross z = 0 (top and bottom faces do not).
        assert_eq!(pieces.len(), 8, "{pieces:?}");
        for p in pieces {
            let Piece::Segment(a, b) = p else { panic!() };
            for q in [a, b] {
                let on_edge = (q.x.abs() - 1.0).abs() < 1e-5 || (q.y.abs() - 1.0).abs() < 1e-5;
                assert!(on_edge, "{q} lies on the square's outline");
            }
        }
    }
}
