//! The lecture's formulas: ideal reflection, Snell's law, total internal reflection, the
//! exact Fresnel equations and Schlick's approximation.
//!
//! Angles are measured from the normal; `n1` is the index of refraction on the side the
//! light arrives from, `n2` the other side's.

pub mod dispersion;
pub mod lens;
pub mod microfacet;
pub mod polarization;

use crate::math::Vec3;
use crate::math::lanes::{Real, Vector, clamp, is_finite};

/// Ideal mirror reflection of the incoming direction `d` about the unit normal `n`:
/// r = d − 2 (d·n) n. Works for `n` on either side of the surface.
#[inline]
pub fn reflect(d: Vec3, n: Vec3) -> Vec3 {
    reflect_of::<f32>(d, n)
}

/// [`reflect`] for one ray or one per lane.
#[inline(always)]
pub(crate) fn reflect_of<R: Real>(d: R::V3, n: R::V3) -> R::V3 {
    d - n.scale(R::splat(2.0) * d.dot(n))
}

/// cos θt from Snell's law n1 sin θi = n2 sin θt, or `None` under total internal
/// reflection (sin θt > 1, possible only when n1 > n2).
#[inline]
pub fn cos_transmitted(cos_i: f32, n1: f32, n2: f32) -> Option<f32> {
    let (cos_t, ok) = cos_transmitted_of(cos_i, n1, n2);
    ok.then_some(cos_t)
}

/// [`cos_transmitted`] for one ray or one per lane: cos θt = √(1 − sin²θt) with
/// sin²θt = (n1/n2)² (1 − cos²θi), and where it exists (sin²θt ≤ 1; NaN elsewhere).
#[inline(always)]
pub(crate) fn cos_transmitted_of<R: Real>(cos_i: R, n1: R, n2: R) -> (R, R::Mask) {
    let (zero, one) = (R::splat(0.0), R::splat(1.0));
    let eta = n1 / n2;
    let sin2_i = one - cos_i * cos_i;
    // max(sin²θi, 0), 0 for NaN as f32::max gives it.
    let sin2_t = eta * eta * R::select(zero.less(sin2_i), sin2_i, zero);
    ((one - sin2_t).sqrt(), sin2_t.less_eq(one))
}

/// Refraction of the unit direction `d` through a surface with unit normal `n` (either
/// side) from index `n1` into `n2`: t = η d + (η cos θi − cos θt) n', with η = n1/n2 and n'
/// the normal facing against `d`. `None` under total internal reflection.
#[inline]
pub fn refract(d: Vec3, n: Vec3, n1: f32, n2: f32) -> Option<Vec3> {
    let (t, ok) = refract_of::<f32>(d, n, n1, n2);
    ok.then_some(t)
}

/// [`refract`] for one ray or one per lane: the refracted direction, and where it exists.
#[inline(always)]
pub(crate) fn refract_of<R: Real>(d: R::V3, n: R::V3, n1: R, n2: R) -> (R::V3, R::Mask) {
    let n = R::V3::select(R::splat(0.0).less(d.dot(n)), n.neg(), n);
    let cos_i = clamp(-d.dot(n), R::splat(0.0), R::splat(1.0));
    let (cos_t, ok) = cos_transmitted_of(cos_i, n1, n2);
    let eta = n1 / n2;
    (
        (d.scale(eta) + n.scale(eta * cos_i - cos_t)).normalize(),
        ok,
    )
}

/// The exact Fresnel equations for a dielectric interface, as in the lecture:
///
/// F_s = (n1 cos θi − n2 cos θt) / (n1 cos θi + n2 cos θt),
/// F_p = (n2 cos θi − n1 cos θt) / (n2 cos θi + n1 cos θt),
/// R = (F_s² + F_p²) / 2 for unpolarized light.
///
/// Returns (F_s, F_p, R): the amplitude ratios of the two polarizations (signed; F_p
/// passes through 0 at Brewster's angle) and the reflectance. Under total internal
/// reflection all light is reflected: F_s = F_p = 1 (in magnitude) and R = 1.
pub fn fresnel_exact(cos_i: f32, n1: f32, n2: f32) -> (f32, f32, f32) {
    fresnel_exact_of(cos_i, n1, n2)
}

/// [`fresnel_exact`] for one ray or one per lane.
#[inline(always)]
pub(crate) fn fresnel_exact_of<R: Real>(cos_i: R, n1: R, n2: R) -> (R, R, R) {
    let one = R::splat(1.0);
    let cos_i = clamp(cos_i, R::splat(0.0), one);
    let (cos_t, ok) = cos_transmitted_of(cos_i, n1, n2);
    let f_s = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let f_p = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    // At exactly grazing incidence both are -1: all light is reflected.
    let finite = is_finite(f_s) & is_finite(f_p);
    let f_s = R::select(finite, f_s, -one);
    let f_p = R::select(finite, f_p, -one);
    let r = R::splat(0.5) * (f_s * f_s + f_p * f_p);
    // Total internal reflection: F_s = F_p = 1, R = 1.
    (
        R::select(ok, f_s, one),
        R::select(ok, f_p, one),
        R::select(ok, r, one),
    )
}

/// The exact Fresnel reflectances of a conductor (a metal) of complex index η + iκ, seen
/// from a dielectric of index `n1`, for one wavelength (one colour channel). With the
/// relative η' = η/n1, κ' = κ/n1 and θ = θi:
///
/// a² + b² = √((η'² − κ'² − sin²θ)² + 4η'²κ'²),  a = √((a² + b² + η'² − κ'² − sin²θ) / 2),
/// R_s = (a² + b² − 2a cos θ + cos²θ) / (a² + b² + 2a cos θ + cos²θ),
/// R_p = R_s (cos²θ (a² + b²) − 2a cos θ sin²θ + sin⁴θ) / (cos²θ (a² + b²) + 2a cos θ sin²θ + sin⁴θ),
/// R = (R_s + R_p) / 2 for unpolarized light.
///
/// Returns (R_s, R_p, R): reflectances (squared amplitudes; a metal's amplitudes are
/// complex). At normal incidence R = ((η' − 1)² + κ'²) / ((η' + 1)² + κ'²); at grazing
/// incidence R = 1; with κ = 0 these are a dielectric's F_s², F_p² and R.
pub fn fresnel_conductor(cos_i: f32, n1: f32, eta: f32, k: f32) -> (f32, f32, f32) {
    // In f64: a² + b² − 2a cos θ + cos²θ cancels badly near normal incidence in f32.
    let cos = cos_i.clamp(0.0, 1.0) as f64;
    let (eta, k) = (eta as f64 / n1 as f64, k as f64 / n1 as f64);
    let cos2 = cos * cos;
    let sin2 = 1.0 - cos2;
    let t0 = eta * eta - k * k - sin2;
    let a2_plus_b2 = (t0 * t0 + 4.0 * eta * eta * k * k).sqrt();
    let a = (0.5 * (a2_plus_b2 + t0)).max(0.0).sqrt();
    let r_s = (a2_plus_b2 - 2.0 * a * cos + cos2) / (a2_plus_b2 + 2.0 * a * cos + cos2);
    let t1 = cos2 * a2_plus_b2 + sin2 * sin2;
    let t2 = 2.0 * a * cos * sin2;
    let r_p = r_s * (t1 - t2) / (t1 + t2);
    // At grazing incidence both are 0/0 in the limit 1.
    let (r_s, r_p) = if r_s.is_finite() && r_p.is_finite() {
        (r_s, r_p)
    } else {
        (1.0, 1.0)
    };
    (r_s as f32, r_p as f32, (0.5 * (r_s + r_p)) as f32)
}

/// Reflectance at normal incidence, R0 = ((n1 − n2) / (n1 + n2))².
#[inline]
pub fn r0(n1: f32, n2: f32) -> f32 {
    let r = (n1 - n2) / (n1 + n2);
    r * r
}

/// Schlick's approximation R = R0 + (1 − R0)(1 − cos θ)^5, with θ the angle on the less
/// dense side: θi going into the denser medium, θt coming out of it. So it reaches 1 at the
/// critical angle, and is 1 beyond it (total internal reflection).
pub fn schlick(cos_i: f32, n1: f32, n2: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let cos = if n1 <= n2 {
        cos_i
    } else {
        match cos_transmitted(cos_i, n1, n2) {
            Some(cos_t) => cos_t,
            None => return 1.0,
        }
    };
    let r0 = r0(n1, n2);
    r0 + (1.0 - r0) * (1.0 - cos).powi(5)
}

/// Schlick's formula with θi on whichever side the light arrives, as some textbooks write
/// it. A teaching option: coming out of the denser medium it stays near R0 up to the
/// critical angle, then jumps to 1.
pub fn schlick_naive(cos_i: f32, n1: f32, n2: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    if cos_transmitted(cos_i, n1, n2).is_none() {
        return 1.0;
    }
    let r0 = r0(n1, n2);
    r0 + (1.0 - r0) * (1.0 - cos_i).powi(5)
}

/// Brewster's angle θB = atan(n2 / n1), in radians: p-polarized light is not reflected.
pub fn brewster_angle(n1: f32, n2: f32) -> f32 {
    (n2 / n1).atan()
}

/// The critical angle θc = asin(n2 / n1), in radians, beyond which light going from n1
/// into a less dense n2 is totally reflected; `None` when n1 ≤ n2.
pub fn critical_angle(n1: f32, n2: f32) -> Option<f32> {
    (n1 > n2).then(|| (n2 / n1).asin())
}

/// One angle of the Fresnel curves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FresnelRow {
    /// Angle of incidence, degrees.
    pub theta_i: f32,
    /// Angle of refraction, degrees; `None` under total internal reflection.
    pub theta_t: Option<f32>,
    /// Amplitude ratio of s-polarized light (its reflectance is F_s²).
    pub f_s: f32,
    /// Amplitude ratio of p-polarized light (its reflectance is F_p²).
    pub f_p: f32,
    /// Exact reflectance (F_s² + F_p²)/2.
    pub r_exact: f32,
    /// Schlick's approximation, cosine on the less dense side.
    pub r_schlick: f32,
    /// Schlick's approximation with the incident cosine.
    pub r_schlick_naive: f32,
}

/// The Fresnel curves from `n1` into `n2` at every `step` degrees from 0 to 90, with 90
/// itself always included.
pub fn fresnel_table(n1: f32, n2: f32, step: f64) -> Vec<FresnelRow> {
    table_angles(step)
        .into_iter()
        .map(|theta| fresnel_row(n1, n2, theta))
        .collect()
}

/// The Fresnel curves' values from `n1` into `n2` at the angle of incidence `theta`
/// (degrees): one row of [`fresnel_table`], and the interface workbench's numbers.
pub fn fresnel_row(n1: f32, n2: f32, theta: f64) -> FresnelRow {
    let cos_i = (theta.to_radians().cos() as f32).max(0.0);
    let (f_s, f_p, r_exact) = fresnel_exact(cos_i, n1, n2);
    FresnelRow {
        theta_i: theta as f32,
        theta_t: cos_transmitted(cos_i, n1, n2).map(|c| (c as f64).acos().to_degrees() as f32),
        f_s,
        f_p,
        r_exact,
        r_schlick: schlick(cos_i, n1, n2),
        r_schlick_naive: schlick_naive(cos_i, n1, n2),
    }
}

/// Every `step` degrees from 0 to 90, with 90 itself always included.
fn table_angles(step: f64) -> Vec<f64> {
    let steps = (90.0 / step + 1e-9).floor() as usize;
    let mut angles: Vec<f64> = (0..=steps).map(|i| i as f64 * step).collect();
    if angles.last().is_some_and(|&a| (a - 90.0).abs() > 1e-9) {
        angles.push(90.0);
    }
    angles
}

/// One row of a conductor's Fresnel table: reflectances per colour channel (R, G, B).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConductorRow {
    /// Angle of incidence, degrees.
    pub theta_i: f32,
    /// Unpolarized reflectance.
    pub r: [f32; 3],
    /// Reflectance of s-polarized light.
    pub r_s: [f32; 3],
    /// Reflectance of p-polarized light.
    pub r_p: [f32; 3],
}

/// A conductor's Fresnel curves ([`fresnel_conductor`]) seen from a dielectric of index
/// `n1`, per channel of `eta` + i`k`, at every `step` degrees from 0 to 90.
pub fn conductor_table(n1: f32, eta: [f32; 3], k: [f32; 3], step: f64) -> Vec<ConductorRow> {
    table_angles(step)
        .into_iter()
        .map(|theta| {
            let cos_i = (theta.to_radians().cos() as f32).max(0.0);
            let channels: [(f32, f32, f32); 3] =
                std::array::from_fn(|c| fresnel_conductor(cos_i, n1, eta[c], k[c]));
            ConductorRow {
                theta_i: theta as f32,
                r: channels.map(|c| c.2),
                r_s: channels.map(|c| c.0),
                r_p: channels.map(|c| c.1),
            }
        })
        .collect()
}

/// How the reflectance of a dielectric or glazed surface is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FresnelMode {
    /// The exact Fresnel equations.
    Exact,
    /// Schlick's approximation, cosine on the less dense side.
    Schlick,
    /// Schlick's approximation with the incident cosine always (teaching option).
    SchlickNaive,
    /// A constant reflectance k at every angle (1 under total internal reflection).
    Constant,
}

impl FresnelMode {
    /// Every mode, in menu order.
    pub const ALL: [FresnelMode; 4] = [
        FresnelMode::Exact,
        FresnelMode::Schlick,
        FresnelMode::SchlickNaive,
        FresnelMode::Constant,
    ];

    /// The reflectance at incidence cosine `cos_i` from `n1` into `n2`; `k` is the
    /// constant mode's reflectance.
    #[inline]
    pub fn reflectance(self, cos_i: f32, n1: f32, n2: f32, k: f32) -> f32 {
        match self {
            FresnelMode::Exact => fresnel_exact(cos_i, n1, n2).2,
            FresnelMode::Schlick => schlick(cos_i, n1, n2),
            FresnelMode::SchlickNaive => schlick_naive(cos_i, n1, n2),
            FresnelMode::Constant => {
                if cos_transmitted(cos_i.clamp(0.0, 1.0), n1, n2).is_some() {
                    k
                } else {
                    1.0
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conductor_fresnel_matches_the_amplitude_equations_and_its_limits() {
        // Gold-, silver- and aluminium-like constants, and a dielectric (κ = 0), from air
        // and from water.
        for (eta, k) in [
            (0.18, 3.42),
            (0.05, 4.2),
            (1.35, 7.5),
            (1.5, 0.0),
            (2.4, 0.0),
        ] {
            for n1 in [1.0, 1.33] {
                let normal = ((eta / n1 - 1.0f64).powi(2) + (k / n1).powi(2))
                    / ((eta / n1 + 1.0f64).powi(2) + (k / n1).powi(2));
                let (_, _, r) = fresnel_conductor(1.0, n1 as f32, eta as f32, k as f32);
                assert!((r as f64 - normal).abs() < 1e-6, "R(0) {r} vs {normal}");
                for deg in 0..90 {
                    let theta = deg as f64;
                    let (r_s, r_p, r) = fresnel_conductor(
                        theta.to_radians().cos() as f32,
                        n1 as f32,
                        eta as f32,
                        k as f32,
                    );
                    // The amplitude equations with the complex index: |r_s|², |r_p|².
                    let (a_s, a_p) = polarization::fresnel_amplitudes(
                        theta.to_radians().cos() as f32,
                        n1 as f32,
                        eta as f32,
                        k as f32,
                    );
                    let (e_s, e_p) = (a_s.norm2(), a_p.norm2());
                    assert!(
                        (r_s as f64 - e_s).abs() < 1e-6,
                        "R_s at {deg}°: {r_s} vs {e_s}"
                    );
                    assert!(
                        (r_p as f64 - e_p).abs() < 1e-6,
                        "R_p at {deg}°: {r_p} vs {e_p}"
                    );
                    assert!((r - 0.5 * (r_s + r_p)).abs() < 1e-7);
                    if k == 0.0 && eta > n1 {
                        let (f_s, f_p, r_d) =
                            fresnel_exact(theta.to_radians().cos() as f32, n1 as f32, eta as f32);
                        assert!((r_s - f_s * f_s).abs() < 1e-6 && (r_p - f_p * f_p).abs() < 1e-6);
                        assert!((r - r_d).abs() < 1e-6);
                    }
                }
                assert_eq!(
                    fresnel_conductor(0.0, n1 as f32, eta as f32, k as f32).2,
                    1.0
                );
                let near_grazing = fresnel_conductor(1e-4, n1 as f32, eta as f32, k as f32).2;
                assert!(near_grazing > 0.99, "R near grazing {near_grazing}");
            }
        }
    }
    use std::f32::consts::FRAC_PI_2;

    fn deg(a: f32) -> f32 {
        a.to_radians()
    }

    #[test]
    fn reflection_keeps_the_tangent_and_flips_the_normal_part() {
        let d = Vec3::new(1.0, -1.0, 0.0).normalize();
        let r = reflect(d, Vec3::Y);
        assert!((r - Vec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-6);
        assert!((reflect(d, -Vec3::Y) - r).length() < 1e-6);
    }

    #[test]
    fn normal_incidence_reflectance_is_r0() {
        for (n1, n2) in [(1.0f32, 1.5f32), (1.5, 1.0), (1.0, 1.33), (1.0, 2.42)] {
            let expected = ((n2 - n1) / (n2 + n1)).powi(2);
            assert!((fresnel_exact(1.0, n1, n2).2 - expected).abs() < 1e-7);
            assert!((schlick(1.0, n1, n2) - expected).abs() < 1e-7);
        }
        assert!(
            (fresnel_exact(1.0, 1.0, 1.5).2 - 0.04).abs() < 1e-7,
            "4% for air to glass"
        );
    }

    #[test]
    fn f_p_vanishes_at_brewsters_angle() {
        for (n1, n2) in [(1.0, 1.5), (1.5, 1.0), (1.0, 2.42)] {
            let (f_s, f_p, _) = fresnel_exact(brewster_angle(n1, n2).cos(), n1, n2);
            assert!(f_p.abs() < 1e-6, "F_p = {f_p} at Brewster for {n1} -> {n2}");
            assert!(f_s.abs() > 0.1);
        }
    }

    #[test]
    fn grazing_and_beyond_critical_reflect_everything() {
        assert!((fresnel_exact(0.0, 1.0, 1.5).2 - 1.0).abs() < 1e-6);
        assert!(fresnel_exact(deg(89.99).cos(), 1.0, 1.5).2 > 0.99);
        let rising = (0..=90).map(|a| fresnel_exact(deg(a as f32).cos(), 1.0, 1.5).2);
        let r: Vec<f32> = rising.collect();
        assert!(
            r.windows(2).skip(57).all(|w| w[1] > w[0]),
            "R rises from Brewster to grazing"
        );
        let crit = critical_angle(1.5, 1.0).unwrap();
        assert!((crit.to_degrees() - 41.8103).abs() < 1e-3);
        for a in [crit + 1e-3, deg(50.0), deg(80.0), FRAC_PI_2] {
            for mode in FresnelMode::ALL {
                assert_eq!(
                    mode.reflectance(a.cos(), 1.5, 1.0, 0.1),
                    1.0,
                    "{mode:?} at {a}"
                );
            }
        }
        // Just inside the critical angle the exact R is already close to 1, Schlick is
        // near 1, and naive Schlick is still near R0: its jump.
        let just_below = (crit - 1e-4).cos();
        assert!(fresnel_exact(just_below, 1.5, 1.0).2 > 0.9);
        assert!(schlick(just_below, 1.5, 1.0) > 0.9);
        assert!(schlick_naive(just_below, 1.5, 1.0) < 0.1);
        assert_eq!(critical_angle(1.0, 1.5), None);
    }

    #[test]
    fn reciprocity_same_reflectance_from_both_sides() {
        for a in 0..90 {
            let cos_i = deg(a as f32).cos();
            let cos_t = cos_transmitted(cos_i, 1.0, 1.5).unwrap();
            let outside = fresnel_exact(cos_i, 1.0, 1.5).2;
            let inside = fresnel_exact(cos_t, 1.5, 1.0).2;
            // Near grazing, cos θt inside sits close to the critical angle, where f32
            // loses digits: hence 1e-4.
            assert!(
                (outside - inside).abs() < 1e-4,
                "at {a}°: {outside} vs {inside}"
            );
            assert!((schlick(cos_i, 1.0, 1.5) - schlick(cos_t, 1.5, 1.0)).abs() < 1e-4);
        }
    }

    #[test]
    fn refract_obeys_snells_law() {
        for (n1, n2) in [(1.0, 1.5), (1.5, 1.0), (1.33, 1.0), (1.0, 2.42)] {
            for a in 0..90 {
                let theta_i = deg(a as f32);
                let d = Vec3::new(theta_i.sin(), -theta_i.cos(), 0.0);
                match refract(d, Vec3::Y, n1, n2) {
                    Some(t) => {
                        assert!((t.length() - 1.0).abs() < 1e-5);
                        assert!(t.y < 0.0, "continues through the surface");
                        let sin_t = t.x;
                        assert!(
                            (n1 * theta_i.sin() - n2 * sin_t).abs() < 1e-5,
                            "{n1}->{n2} at {a}°"
                        );
                        // Also with the normal on the other side.
                        assert!((refract(d, -Vec3::Y, n1, n2).unwrap() - t).length() < 1e-6);
                    }
                    None => assert!(n1 * theta_i.sin() > n2, "TIR only past the critical angle"),
                }
            }
        }
    }

    #[test]
    fn reflected_plus_transmitted_is_one() {
        for (n1, n2) in [(1.0, 1.5), (1.5, 1.0)] {
            for a in 0..=90 {
                let cos_i = deg(a as f32).cos();
                let (f_s, f_p, r) = fresnel_exact(cos_i, n1, n2);
                let Some(cos_t) = cos_transmitted(cos_i, n1, n2) else {
                    assert_eq!(r, 1.0);
                    continue;
                };
                // Transmittance from the transmitted amplitudes: T = (n2 cos θt)/(n1 cos θi) t².
                if cos_i > 1e-3 {
                    let t_s = 2.0 * n1 * cos_i / (n1 * cos_i + n2 * cos_t);
                    let t_p = 2.0 * n1 * cos_i / (n2 * cos_i + n1 * cos_t);
                    let factor = n2 * cos_t / (n1 * cos_i);
                    let t = 0.5 * factor * (t_s * t_s + t_p * t_p);
                    assert!(
                        (r + t - 1.0).abs() < 1e-5,
                        "{n1}->{n2} at {a}°: R + T = {}",
                        r + t
                    );
                    assert!((f_s * f_s + factor * t_s * t_s - 1.0).abs() < 1e-5);
                    assert!((f_p * f_p + factor * t_p * t_p - 1.0).abs() < 1e-5);
                }
            }
        }
    }

    #[test]
    fn schlick_is_close_to_exact_for_air_to_glass() {
        // |Schlick − exact| for n = 1.5 stays under 0.02 up to 79.4°, peaks at 0.0357 near
        // 85° (computed in f64), and returns to 0 at grazing.
        let mut worst: f32 = 0.0;
        for hundredth in 0..=9000 {
            let a = hundredth as f32 / 100.0;
            let cos_i = deg(a).cos();
            let err = (schlick(cos_i, 1.0, 1.5) - fresnel_exact(cos_i, 1.0, 1.5).2).abs();
            if a <= 79.0 {
                assert!(err < 0.02, "at {a}°: error {err}");
            }
            worst = worst.max(err);
        }
        assert!(worst < 0.036 && worst > 0.035, "largest error {worst}");
        // Out of the glass, Schlick with cos θt is the same curve, reaching 1 at the
        // critical angle.
        for hundredth in 0..4181 {
            let cos_i = deg(hundredth as f32 / 100.0).cos();
            let err = (schlick(cos_i, 1.5, 1.0) - fresnel_exact(cos_i, 1.5, 1.0).2).abs();
            assert!(
                err < 0.036,
                "inside out at {}°: {err}",
                hundredth as f32 / 100.0
            );
        }
    }

    #[test]
    fn brewster_is_atan_of_the_ratio() {
        assert!((brewster_angle(1.0, 1.5).to_degrees() - 56.3099).abs() < 1e-3);
    }
}
