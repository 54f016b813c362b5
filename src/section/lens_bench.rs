//! The lens bench: a real lens cut through its axis and one film point (the meridional
//! plane), its elements, its stop and the film, with that film point's rays traced out
//! through the glass: a fan across the pupil in the plane, and the inspected sample's own
//! ray, whose angles of incidence and refraction at every surface the notes give.
//!
//! The plane's units are millimetres; the scene is to the left, the film to the right, so
//! light runs left to right as lens drawings show it (the rays are traced the other way,
//! from the film).

use super::{Anchor, Dash, Diagram, Ink, Item, Label, RayLine, Symbol, degrees};
use crate::math::Vec3;
use crate::optics::lens::{RealLens, SurfaceProfile};
use crate::tracer::{End, RayKind};
use glam::Vec2;

/// Rays in the fan across the pupil's diameter in the plane.
const FAN: usize = 9;
/// Segments per surface's arc.
const ARC: usize = 24;

/// What the bench shows: the lens, the film point (0 to 1 across and down the image) and
/// the inspected sample's lens point (unit square). Its rays are traced at n_d.
#[derive(Clone, Copy, Debug)]
pub struct Bench<'l> {
    /// The camera's real lens, focused and stopped as it renders.
    pub lens: &'l RealLens,
    /// The image position.
    pub film: Vec2,
    /// The inspected sample's point on the lens (unit square).
    pub sample: Vec2,
}

/// One ray's way out: the points it reaches (the film point, then each surface) and, if
/// it gets out, where it leaves and its direction.
struct Way {
    points: Vec<Vec3>,
    out: Option<(Vec3, Vec3)>,
}

impl Bench<'_> {
    fn way(&self, lens: Vec2) -> Way {
        let mut points = Vec::with_capacity(32);
        let out = self
            .lens
            .traced(self.film, lens, None, |p| points.push(p))
            .map(|r| (r.origin, r.dir));
        Way { points, out }
    }

    /// The bench's diagram, untitled; `None` where no ray from the film point gets
    /// through the lens's bounds (a point outside its image circle).
    pub fn diagram(&self) -> Option<Diagram> {
        let surfaces = self.lens.profile();
        let own = self.way(self.sample);
        let film_point = *own.points.first()?;
        // The plane's vertical: from the axis towards the film point (up, on the axis).
        let radial = Vec2::new(film_point.x, film_point.y);
        let e = radial.try_normalize().unwrap_or(Vec2::Y);
        let to_plane = |p: Vec3| Vec2::new(-p.z, Vec2::new(p.x, p.y).dot(e));
        let off_plane = |p: Vec3| Vec2::new(p.x, p.y).perp_dot(e).abs();

        let front = surfaces.first()?.z;
        let film_z = self.lens.film_z();
        let length = front - film_z;
        let height = surfaces
            .iter()
            .map(|s| s.clear_radius)
            .fold(radial.length(), f32::max);
        // Room on the left for the rays leaving towards the scene.
        let (left, right) = (-front - 0.45 * length, -film_z + 0.06 * length);
        let view = (
            Vec2::new(left, -1.25 * height),
            Vec2::new(right, 1.25 * height),
        );
        let mut d = Diagram {
            view,
            ..Default::default()
        };
        elements(&mut d, &surfaces, height, film_z);
        let film_half = radial.length().max(0.3 * height);
        d.items.push(Item::Line {
            a: Vec2::new(-film_z, -film_half),
            b: Vec2::new(-film_z, film_half),
            ink: Ink::Camera,
            width: 2.5,
            dash: Dash::Solid,
        });
        d.labels
            .push(label(Vec2::new(-film_z, -film_half), "film", 16.0));
        // The axis.
        d.items.push(Item::Line {
            a: Vec2::new(left, 0.0),
            b: Vec2::new(right, 0.0),
            ink: Ink::Guide,
            width: 1.0,
            dash: Dash::Dotted,
        });
        let mut through = 0;
        for k in 0..FAN {
            let u = (k as f32 + 0.5) / FAN as f32;
            let way = self.way(Vec2::new(u, 0.5));
            through += way.out.is_some() as usize;
            draw_way(&mut d, &way, &to_plane, left, 0.2, false);
        }
        let projected = own.points.iter().any(|&p| off_plane(p) > 1e-3 * height);
        draw_way(&mut d, &own, &to_plane, left, 0.6, projected);
        d.notes = notes(self.lens, &surfaces, &own, through);
        Some(d)
    }
}

/// A label under (or, with a negative `offset`, over) `at`, centred.
fn label(at: Vec2, text: &str, offset: f32) -> Label {
    Label {
        at,
        offset: Vec2::new(0.0, offset),
        text: text.to_string(),
        ink: Ink::Text,
        anchor: Anchor::Middle,
        node: None,
        instead: None,
    }
}

/// The surfaces' arcs (numbered from the front), the glass between them filled, and the
/// stop's blades, on a bench `height` mm high whose film is at `film_z`.
fn elements(d: &mut Diagram, surfaces: &[SurfaceProfile], height: f32, film_z: f32) {
    let arc = |s: &SurfaceProfile, from: f32, to: f32| -> Vec<Vec2> {
        (0..=ARC)
            .map(|j| {
                let h = from + (to - from) * j as f32 / ARC as f32;
                Vec2::new(-s.z_at(h), h)
            })
            .collect()
    };
    let length = surfaces.first().map_or(0.0, |s| s.z) - film_z;
    // Where the last label above a rim is.
    let mut above = None;
    for (i, (s, number)) in surfaces.iter().zip(numbers(surfaces)).enumerate() {
        let h = s.clear_radius;
        let Some(number) = number else {
            // The stop.
            for sign in [-1.0, 1.0] {
                d.items.push(Item::Line {
                    a: Vec2::new(-s.z, sign * h),
                    b: Vec2::new(-s.z, sign * (h.max(0.85 * height) + 0.15 * height)),
                    ink: Ink::Stop,
                    width: 3.0,
                    dash: Dash::Solid,
                });
            }
            d.labels
                .push(label(Vec2::new(-s.z, 1.15 * height), "stop", -14.0));
            continue;
        };
        let outline = arc(s, -h, h);
        if s.ior > 1.0
            && let Some(next) = surfaces.get(i + 1)
        {
            let back = next.clear_radius;
            let points = outline
                .iter()
                .copied()
                .chain(arc(next, back, -back))
                .collect();
            d.items.push(Item::Region {
                points,
                ink: Ink::Glass,
            });
        }
        for pair in outline.windows(2) {
            d.items.push(Item::Line {
                a: pair[0],
                b: pair[1],
                ink: Ink::Glass,
                width: 1.5,
                dash: Dash::Solid,
            });
        }
        // Above the surface's rim, or below it where the last label above is too near to
        // read both (a cemented pair, a thin element).
        let x = -s.z_at(h);
        let below = above.is_some_and(|last: f32| (x - last).abs() < 0.05 * length);
        let text = number.to_string();
        if below {
            d.labels.push(label(Vec2::new(x, -h), &text, 12.0));
            above = None;
        } else {
            d.labels.push(label(Vec2::new(x, h), &text, -12.0));
            above = Some(x);
        }
    }
}

/// A ray's way drawn `weight` wide: its segments, and out to the view's `left` edge where
/// it gets out, or a cross where the lens blocks it; dotted where it leaves the plane.
fn draw_way(
    d: &mut Diagram,
    way: &Way,
    to_plane: &impl Fn(Vec3) -> Vec2,
    left: f32,
    weight: f32,
    projected: bool,
) {
    let ray = |a: Vec2, b: Vec2, end: End| {
        Item::Ray(RayLine {
            a,
            b,
            kind: RayKind::Camera,
            weight,
            node: None,
            projected,
            end,
        })
    };
    let points: Vec<Vec2> = way.points.iter().map(|&p| to_plane(p)).collect();
    for pair in points.windows(2).filter(|p| p[0] != p[1]) {
        d.items.push(ray(pair[0], pair[1], End::Split));
    }
    match way.out {
        Some((origin, dir)) => {
            // On to the left edge: -z falls to it along the direction's z.
            let t = ((-left) - origin.z).max(0.0) / dir.z.max(1e-3);
            let (a, b) = (to_plane(origin), to_plane(origin + t * dir));
            d.items.push(ray(a, b, End::Miss));
        }
        None => {
            if let Some(&at) = points.last() {
                d.items.push(Item::Mark {
                    at,
                    symbol: Symbol::Cross,
                    ink: Ink::Stop,
                });
            }
        }
    }
}

/// Each surface's number as the bench labels it, from the front, the stop unnumbered.
fn numbers(surfaces: &[SurfaceProfile]) -> Vec<Option<usize>> {
    surfaces
        .iter()
        .scan(0, |n, s| {
            Some((!s.stop).then(|| {
                *n += 1;
                *n
            }))
        })
        .collect()
}

/// The angles of incidence and refraction of the way `own` at each surface it crosses
/// but the stop: (its index, its number from the front, θi, θt in degrees), back to front
/// as it meets them.
fn angles(surfaces: &[SurfaceProfile], own: &Way) -> Vec<(usize, usize, f32, f32)> {
    let numbers = numbers(surfaces);
    // points[0] is the film point; points[k] is on surface n − k (the ray meets them
    // from the back).
    let n = surfaces.len();
    let mut out = Vec::new();
    for k in 1..own.points.len() {
        let surface = &surfaces[n - k];
        let Some(number) = numbers[n - k] else {
            continue;
        };
        let p = own.points[k];
        let arriving = (p - own.points[k - 1]).normalize_or_zero();
        let leaving = match own.points.get(k + 1) {
            Some(&q) => (q - p).normalize_or_zero(),
            None => match own.out {
                Some((_, dir)) => dir,
                None => break,
            },
        };
        if arriving == Vec3::ZERO || leaving == Vec3::ZERO {
            break;
        }
        let normal = surface.normal_at(p);
        let angle = |d: Vec3| d.dot(normal).abs().min(1.0).acos().to_degrees();
        out.push((n - k, number, angle(arriving), angle(leaving)));
    }
    out
}

/// The bench's notes: the lens, what gets through, the sample's angles, a legend.
fn notes(lens: &RealLens, surfaces: &[SurfaceProfile], own: &Way, through: usize) -> Vec<String> {
    let paraxial = lens.paraxial();
    let mut notes = vec![format!(
        "f = {:.1} mm, f/{:.1} as stopped; film {:.1} mm behind the last surface. {through} of the {FAN} rays across the pupil get through.",
        paraxial.efl,
        lens.f_number(),
        surfaces.last().map_or(0.0, |s| s.z) - lens.film_z(),
    )];
    let angles = angles(surfaces, own);
    if !angles.is_empty() {
        let list: Vec<String> = angles
            .iter()
            .map(|(_, n, i, t)| format!("{n}: {}/{}", degrees(*i), degrees(*t)))
            .collect();
        notes.push(format!(
            "This sample's ray, θi/θt at each surface from the film out: {}{}",
            list.join(", "),
            if own.out.is_none() {
                "; then blocked (×)"
            } else {
                ""
            }
        ));
    }
    notes.push(
        "Fine lines: this film point's rays across the pupil, in this plane. Heavy: this sample's ray (dotted where it leaves the plane). Red: the stop. Numbers: the surfaces, from the front.".to_string(),
    );
    notes
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optics::lens::LensModel;

    fn double_gauss() -> RealLens {
        let prescription = LensModel::DoubleGauss50.prescription().unwrap();
        RealLens::new(&prescription, 2000.0, 20.0, 27.0, 1.5, false).unwrap()
    }

    /// The bench of `lens` at image position `film`, its sample at lens point `sample`.
    fn bench(lens: &RealLens, film: Vec2, sample: Vec2) -> Bench<'_> {
        Bench { lens, film, sample }
    }

    #[test]
    fn the_angles_at_every_surface_obey_snells_law() {
        // n_behind sin θi = n_front sin θt at each surface the sample's ray crosses, the
        // ray leaving each medium for the one in front of it.
        let lens = double_gauss();
        let bench = bench(&lens, Vec2::new(0.7, 0.3), Vec2::new(0.3, 0.6));
        let surfaces = lens.profile();
        let own = bench.way(bench.sample);
        assert!(own.out.is_some(), "the ray gets through");
        let angles = angles(&surfaces, &own);
        // Every surface but the stop, numbered 10 (the back) to 1.
        let numbers: Vec<usize> = angles.iter().map(|a| a.1).collect();
        assert_eq!(numbers, (1..=10).rev().collect::<Vec<_>>());
        for (j, _, theta_i, theta_t) in angles {
            let behind = surfaces[j].ior.max(1.0);
            let front = if j == 0 {
                1.0
            } else {
                surfaces[j - 1].ior.max(1.0)
            };
            let (si, st) = (theta_i.to_radians().sin(), theta_t.to_radians().sin());
            assert!(
                (behind * si - front * st).abs() < 1e-4,
                "surface {j}: {behind} sin {theta_i}° against {front} sin {theta_t}°"
            );
        }
    }

    #[test]
    fn the_bench_draws_every_surface_the_stop_the_film_and_the_fan() {
        let lens = double_gauss();
        let bench = bench(&lens, Vec2::splat(0.5), Vec2::splat(0.5));
        let d = bench.diagram().unwrap();
        let labels: Vec<&str> = d.labels.iter().map(|l| l.text.as_str()).collect();
        for text in ["1", "10", "stop", "film"] {
            assert!(labels.contains(&text), "{text} in {labels:?}");
        }
        assert!(!labels.contains(&"11"), "the stop is not numbered");
        // Each of the fan's rays and the sample's leaves the lens (at f/2.5, on the axis)
        // and reaches the view's left edge.
        let out: Vec<_> = d.rays().filter(|r| r.end == End::Miss).collect();
        assert_eq!(out.len(), FAN + 1);
        for r in out {
            assert!((r.b.x - d.view.0.x).abs() < 1e-3, "{r:?}");
        }
        // On the axis, within the pupil's bounds, every ray of the fan gets through.
        assert!(d.notes[0].contains("9 of the 9 rays"), "{}", d.notes[0]);
    }
}
