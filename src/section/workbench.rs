//! The interface workbench: the lecture's Snell and Fresnel figure, live. One flat
//! interface between η1 (above) and η2 (below), one ray arriving at θi, and what the
//! interface does with it: the reflected and refracted rays with widths R and T = 1 − R,
//! the angles, F_s and F_p, exact R and Schlick's, the critical and Brewster angles.

use super::{Anchor, Dash, Diagram, Ink, Item, Label, RayLine, angle_marks, degrees, index};
use crate::material::{Microfacet, Side};
use crate::math::Vec3;
use crate::optics::{FresnelMode, FresnelRow, brewster_angle, critical_angle, fresnel_row};
use crate::tracer::{End, RayKind};
use glam::Vec2;
use std::f32::consts::PI;

/// One interface, one incoming ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Workbench {
    /// The index of refraction the ray comes from (above the interface).
    pub n1: f32,
    /// The index of refraction beyond it (below).
    pub n2: f32,
    /// The angle of incidence, degrees from the normal, 0 to 90.
    pub theta_i: f32,
    /// The interface's GGX roughness α: 0 is smooth; above, the figure draws the rough
    /// interface's reflection and transmission lobes.
    pub roughness: f32,
}

/// Directions per lobe's outline across its half of the plane, and again within
/// [`FINE`] of its smooth ray.
const LOBE_STEPS: usize = 180;
/// The span about a lobe's smooth ray traced finely (radians, 12°): a transmission lobe
/// of small α is about a degree wide.
const FINE: f32 = 0.21;

/// The largest angle of incidence the workbench takes: at 90° the ray runs along the
/// interface and never meets it.
pub const MAX_ANGLE: f32 = 89.9;

impl Workbench {
    /// The numbers at this angle: θt, F_s, F_p, exact R and Schlick's, exactly as
    /// `raylab fresnel` prints them.
    pub fn row(&self) -> FresnelRow {
        fresnel_row(self.n1, self.n2, self.theta_i as f64)
    }

    /// The critical angle in degrees, past which light is totally reflected; `None` when
    /// η1 ≤ η2.
    pub fn critical_angle(&self) -> Option<f32> {
        critical_angle(self.n1, self.n2).map(f32::to_degrees)
    }

    /// Brewster's angle in degrees, where R_p = 0.
    pub fn brewster_angle(&self) -> f32 {
        brewster_angle(self.n1, self.n2).to_degrees()
    }

    /// The same interface seen from the other side: η1 and η2 swapped.
    pub fn swapped(self) -> Workbench {
        Workbench {
            n1: self.n2,
            n2: self.n1,
            ..self
        }
    }

    /// The angle of incidence of a ray arriving from the diagram's point `p` (the pointer
    /// dragging it), 0 to [`MAX_ANGLE`]: from above the interface, on either side of the
    /// normal.
    pub fn angle_at(p: Vec2) -> f32 {
        let theta = p.x.abs().atan2(p.y.max(0.0)).to_degrees();
        theta.clamp(0.0, MAX_ANGLE)
    }

    /// The figure: the interface and its normal, the denser medium shaded, the three rays
    /// with widths 1, R and T, the angles as arcs with their values, the critical and
    /// Brewster angles as dotted guides, and the numbers beneath.
    pub fn diagram(&self) -> Diagram {
        let row = self.row();
        let theta = self.theta_i.to_radians();
        let (sin, cos) = theta.sin_cos();
        let from = Vec2::new(-sin, cos);
        let mut d = Diagram {
            title: format!(
                "Interface: η1 = {} above, η2 = {} below",
                index(self.n1),
                index(self.n2)
            ),
            view: (Vec2::new(-1.3, -1.1), Vec2::new(1.3, 1.2)),
            ..Default::default()
        };
        let (lo, hi) = d.view;
        // The denser medium shaded, up to the view's edge.
        let denser = if self.n2 >= self.n1 { lo.y } else { hi.y };
        d.items.push(Item::Region {
            points: vec![
                Vec2::new(lo.x, 0.0),
                Vec2::new(hi.x, 0.0),
                Vec2::new(hi.x, denser),
                Vec2::new(lo.x, denser),
            ],
            ink: Ink::Glass,
        });
        let line = |a, b, ink, width, dash| Item::Line {
            a,
            b,
            ink,
            width,
            dash,
        };
        d.items.push(line(
            Vec2::new(lo.x, 0.0),
            Vec2::new(hi.x, 0.0),
            Ink::Glass,
            2.5,
            Dash::Solid,
        ));
        d.items.push(line(
            Vec2::new(0.0, -1.05),
            Vec2::new(0.0, 1.05),
            Ink::Normal,
            1.3,
            Dash::Dashed,
        ));
        // The guides, in the incoming ray's quarter, of two lengths so that their labels
        // stay apart when the angles are close. Their labels go after the angles': where
        // they would overlap (a hall's large text), the angle dragged is written.
        let mut guides = Vec::new();
        let mut guide = |angle: f32, length: f32, text: String| {
            let dir = length * Vec2::new(-angle.to_radians().sin(), angle.to_radians().cos());
            d.items
                .push(line(Vec2::ZERO, dir, Ink::Guide, 1.5, Dash::Dotted));
            // Above its end and to the right, clear of the guide running down to the hit.
            guides.push(plain(dir, Vec2::new(4.0, -12.0), text, Anchor::Start));
        };
        if let Some(c) = self.critical_angle() {
            guide(c, 1.05, format!("critical angle {}", degrees(c)));
        }
        let b = self.brewster_angle();
        guide(b, 0.75, format!("Brewster's angle {}", degrees(b)));

        let r = row.r_exact;
        let ray = |to: Vec2, kind, weight, start: bool| {
            let (a, b) = if start {
                (to, Vec2::ZERO)
            } else {
                (Vec2::ZERO, to)
            };
            Item::Ray(RayLine {
                a,
                b,
                kind,
                weight,
                node: None,
                projected: false,
                end: if start { End::Split } else { End::Miss },
            })
        };
        d.items.push(ray(from, RayKind::Camera, 1.0, true));
        let reflected = Vec2::new(sin, cos);
        d.items.push(ray(reflected, RayKind::Reflect, r, false));
        let mut angle = |from: Vec2, to: Vec2, text: String| {
            let (arc, label) = angle_marks(Vec2::ZERO, from, to, text, None);
            d.items.push(arc);
            d.labels.push(label);
        };
        angle(Vec2::Y, from, format!("θi = {}", degrees(self.theta_i)));
        angle(
            Vec2::Y,
            reflected,
            format!("θr = {}", degrees(self.theta_i)),
        );
        match row.theta_t {
            Some(t) => {
                let t_rad = t.to_radians();
                let to = Vec2::new(t_rad.sin(), -t_rad.cos());
                angle(-Vec2::Y, to, format!("θt = {}", degrees(t)));
                d.items.push(ray(to, RayKind::Refract, 1.0 - r, false));
            }
            None => d.labels.push(Label {
                ink: Ink::Stop,
                ..plain(
                    Vec2::new(0.45, -0.45),
                    Vec2::ZERO,
                    "total internal reflection".into(),
                    Anchor::Middle,
                )
            }),
        }
        d.labels.push(plain(
            Vec2::new(1.25, 0.0),
            Vec2::new(0.0, -14.0),
            format!("η1 = {}", index(self.n1)),
            Anchor::End,
        ));
        d.labels.push(plain(
            Vec2::new(1.25, 0.0),
            Vec2::new(0.0, 14.0),
            format!("η2 = {}", index(self.n2)),
            Anchor::End,
        ));
        d.labels.extend(guides);
        d.notes = self.notes(&row);
        if self.roughness > 0.0 {
            let theta_t = row.theta_t.map(|t| t.to_radians());
            self.lobes(&mut d, [Some(self.theta_i.to_radians()), theta_t]);
        }
        d
    }

    /// The rough interface's two lobes in the plane of incidence: for each direction o
    /// leaving the hit, f cos θo of the reflection lobe (above) and of the transmission lobe
    /// (below) as the split tree's jittered children carry it ([`Microfacet::lobe`], exact
    /// Fresnel at each facet), drawn as a polar outline, each to its own peak (the rays'
    /// widths give their shares): their shapes show how far each child is jittered. Into
    /// glass the refracted lobe is the narrower (refraction bends less than reflection
    /// turns), so each lobe is traced finely about its smooth ray, `smooth` (radians from
    /// the normal, towards +x).
    fn lobes(&self, d: &mut Diagram, smooth: [Option<f32>; 2]) {
        let facets = Microfacet {
            alpha: self.roughness,
            n1: self.n1,
            n2: self.n2,
            fresnel: FresnelMode::Exact,
            constant_reflectance: 0.0,
        };
        let theta = self.theta_i.to_radians();
        // Towards the viewer, back along the incoming ray: the plane's (x, y) is the
        // surface frame's (x, z).
        let v = Vec3::new(-theta.sin(), 0.0, theta.cos());
        let half_pi = std::f32::consts::FRAC_PI_2;
        for ((side, kind), about) in [
            (Side::Reflect, RayKind::Reflect),
            (Side::Transmit, RayKind::Refract),
        ]
        .into_iter()
        .zip(smooth)
        {
            let sign = if side == Side::Reflect { 1.0 } else { -1.0 };
            let coarse = (0..=LOBE_STEPS).map(|k| (k as f32 / LOBE_STEPS as f32 - 0.5) * PI);
            let fine = about.into_iter().flat_map(|a| {
                (0..=LOBE_STEPS).map(move |k| a + (k as f32 / LOBE_STEPS as f32 - 0.5) * FINE)
            });
            let mut phis: Vec<f32> = coarse.chain(fine).filter(|p| p.abs() < half_pi).collect();
            phis.sort_by(f32::total_cmp);
            let points: Vec<(Vec2, f32)> = phis
                .iter()
                .map(|&phi| {
                    let o = Vec3::new(phi.sin(), 0.0, sign * phi.cos());
                    let f_cos = facets.lobe(v, o, side).map_or(0.0, |l| l.0);
                    (Vec2::new(o.x, o.z), f_cos)
                })
                .collect();
            let peak = points.iter().map(|p| p.1).fold(0.0, f32::max);
            if peak <= 0.0 {
                continue;
            }
            let polar: Vec<Vec2> = points.iter().map(|(o, f)| *o * (f / peak)).collect();
            for pair in polar.windows(2).filter(|p| p[0] != p[1]) {
                d.items.push(Item::Line {
                    a: pair[0],
                    b: pair[1],
                    ink: Ink::Ray(kind),
                    width: 2.0,
                    dash: Dash::Solid,
                });
            }
        }
        d.title = format!("{}, rough: GGX α = {}", d.title, self.roughness);
        d.notes.push(format!(
            "Lobes (α = {}): f cos θo of the jittered reflected (above) and refracted (below) rays in this plane, each to its own peak; the straight rays are the smooth interface's.",
            self.roughness
        ));
    }

    /// The line a hall has room for: R and Schlick's approximation of it at the angle.
    pub fn hall_note(&self) -> String {
        let row = self.row();
        format!("R = {:.3}, Schlick {:.3}", row.r_exact, row.r_schlick)
    }

    /// The numbers, a line each.
    fn notes(&self, row: &FresnelRow) -> Vec<String> {
        let t = row
            .theta_t
            .map_or("none: total internal reflection".into(), degrees);
        let critical = self
            .critical_angle()
            .map_or("none (η1 ≤ η2)".into(), degrees);
        vec![
            format!("θi = {}, θt = {t}", degrees(row.theta_i)),
            format!(
                "R = {:.4} (Schlick {:.4}), T = 1 − R = {:.4}",
                row.r_exact,
                row.r_schlick,
                1.0 - row.r_exact
            ),
            format!(
                "F_s = {:.4}, F_p = {:.4}: R_s = {:.4}, R_p = {:.4}",
                row.f_s,
                row.f_p,
                row.f_s * row.f_s,
                row.f_p * row.f_p
            ),
            format!(
                "critical angle {critical}, Brewster's angle {}",
                degrees(self.brewster_angle())
            ),
        ]
    }
}

fn plain(at: Vec2, offset: Vec2, text: String, anchor: Anchor) -> Label {
    Label {
        at,
        offset,
        text,
        ink: Ink::Text,
        anchor,
        node: None,
        instead: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dragging_above_the_interface_sets_the_angle_from_the_normal() {
        assert!((Workbench::angle_at(Vec2::new(-1.0, 1.0)) - 45.0).abs() < 1e-4);
        assert!((Workbench::angle_at(Vec2::new(1.0, 1.0)) - 45.0).abs() < 1e-4);
        assert_eq!(Workbench::angle_at(Vec2::new(0.0, 1.0)), 0.0);
        // Below the interface: as far as the workbench goes.
        assert_eq!(Workbench::angle_at(Vec2::new(-1.0, -1.0)), MAX_ANGLE);
    }

    /// The points of the lobe outlines of `bench`: reflection's, then transmission's.
    fn lobe_points(bench: Workbench) -> (Vec<Vec2>, Vec<Vec2>) {
        let d = bench.diagram();
        let mut lobes = (Vec::new(), Vec::new());
        for item in &d.items {
            if let Item::Line {
                a,
                ink: Ink::Ray(kind),
                ..
            } = item
            {
                match kind {
                    RayKind::Reflect => lobes.0.push(*a),
                    RayKind::Refract => lobes.1.push(*a),
                    _ => {}
                }
            }
        }
        lobes
    }

    #[test]
    fn the_rough_lobes_peak_near_the_mirror_and_snell_directions_and_widen_with_alpha() {
        let bench = |roughness| Workbench {
            n1: 1.0,
            n2: 1.5,
            theta_i: 30.0,
            roughness,
        };
        // Smooth: no lobes.
        let (r, t) = lobe_points(bench(0.0));
        assert!(r.is_empty() && t.is_empty());
        let spread = |points: &[Vec2]| {
            let far = points.iter().map(|p| p.length()).fold(0.0, f32::max);
            let peak = points.iter().find(|p| p.length() == far).copied().unwrap();
            // The angle from the normal (up or down) where the outline reaches furthest,
            // and how wide it is at half its reach.
            let angle = peak.x.atan2(peak.y.abs()).to_degrees();
            let half: Vec<f32> = points
                .iter()
                .filter(|p| p.length() > 0.5 * far)
                .map(|p| p.x.atan2(p.y.abs()).to_degrees())
                .collect();
            let width = half.iter().fold(f32::MIN, |a, &b| a.max(b))
                - half.iter().fold(f32::MAX, |a, &b| a.min(b));
            (angle, width)
        };
        let theta_t = (30f32.to_radians().sin() / 1.5).asin().to_degrees();
        let (mut last_r, mut last_t) = (0.0, 0.0);
        for alpha in [0.05, 0.15, 0.3] {
            let (r, t) = lobe_points(bench(alpha));
            let ((angle_r, width_r), (angle_t, width_t)) = (spread(&r), spread(&t));
            // At small α each lobe peaks within a few degrees of its smooth ray: the
            // mirror direction (30° on the other side of the normal) and Snell's θt.
            if alpha == 0.05 {
                assert!(
                    (angle_r - 30.0).abs() < 3.0,
                    "reflection peaks at {angle_r}°"
                );
                assert!(
                    (angle_t - theta_t).abs() < 3.0,
                    "transmission peaks at {angle_t}°"
                );
            }
            assert!(
                width_r > last_r && width_t > last_t,
                "α = {alpha}: widths {width_r}° and {width_t}° after {last_r}° and {last_t}°"
            );
            (last_r, last_t) = (width_r, width_t);
        }
        // Into glass refraction bends the ray less than reflection turns it as the facet
        // tilts: the refracted lobe is the narrower.
        let (r, t) = lobe_points(bench(0.15));
        assert!(spread(&t).1 < 0.6 * spread(&r).1);
    }
}
