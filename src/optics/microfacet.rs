//! Rough interfaces as microfacets (Walter, Marschner, Li and Torrance, "Microfacet Models
//! for Refraction through Rough Surfaces", EGSR 2007): a surface of tiny flat facets whose
//! normals m spread about the macro normal n by the GGX (Trowbridge–Reitz) distribution of
//! roughness α, each facet reflecting and refracting as the lecture's smooth interface does
//! (Snell's law, Fresnel at the facet's own angle). A ray's facet is drawn among those it
//! can see (Heitz, "Sampling the GGX Distribution of Visible Normals", JCGT 2018), so that
//! the jittered reflected ray carries F · G1(o) and the jittered refracted ray (1 − F) · G1(o).
//!
//! Vectors here are in the macro surface's frame: n = +z, every direction pointing away
//! from the surface.

use crate::math::Vec3;
use glam::Vec2;
use std::f32::consts::PI;

/// The GGX distribution of facet normals, D(m) = α² / (π ((m_x² + m_y²) + α² m_z²)²) for
/// m above the surface (m_z > 0), else 0: the density of facet area per unit solid angle
/// of normals, projected, ∫ D(m) m_z dω_m = 1. Written with m_x² + m_y² rather than
/// 1 − m_z², so that a smooth surface's peak (small α, m_z ≈ 1) does not cancel.
#[inline]
pub fn ggx_d(m: Vec3, alpha: f32) -> f32 {
    if m.z <= 0.0 {
        return 0.0;
    }
    let a2 = alpha * alpha;
    let k = m.x * m.x + m.y * m.y + a2 * m.z * m.z;
    a2 / (PI * k * k)
}

/// Smith's masking G1 of the facets seen along a direction at cos θv from the normal:
/// 2 / (1 + √(1 + α² tan²θv)) = 2 |cos θv| / (|cos θv| + √(α² + (1 − α²) cos²θv)). 1 at
/// normal incidence, 0 at grazing; α → 0 gives 1.
#[inline]
pub fn smith_g1(cos_v: f32, alpha: f32) -> f32 {
    let c = cos_v.abs();
    if c == 0.0 {
        return 0.0;
    }
    let a2 = alpha * alpha;
    2.0 * c / (c + (a2 + (1.0 - a2) * c * c).sqrt())
}

/// A facet normal drawn from those visible along `v` (v_z > 0), with density
/// [`visible_normal_pdf`], from two uniform numbers `u` (Heitz 2018): the view stretched
/// to the unit-roughness configuration, a point drawn on the projected hemisphere (a disk
/// whose far half is squashed by the view's tilt), lifted onto the hemisphere, and the
/// normal there stretched back.
#[inline]
pub fn sample_visible_normal(v: Vec3, alpha: f32, u: Vec2) -> Vec3 {
    let vh = Vec3::new(alpha * v.x, alpha * v.y, v.z).normalize();
    let len2 = vh.x * vh.x + vh.y * vh.y;
    let t1 = if len2 > 0.0 {
        Vec3::new(-vh.y, vh.x, 0.0) / len2.sqrt()
    } else {
        Vec3::X
    };
    let t2 = vh.cross(t1);
    let r = u.x.sqrt();
    let phi = 2.0 * PI * u.y;
    let (sin, cos) = phi.sin_cos();
    let p1 = r * cos;
    let s = 0.5 * (1.0 + vh.z);
    let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * (r * sin);
    let nh = p1 * t1 + p2 * t2 + (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt() * vh;
    Vec3::new(alpha * nh.x, alpha * nh.y, nh.z.max(0.0)).normalize()
}

/// The density per solid angle of normals with which [`sample_visible_normal`] draws `m`
/// seen along `v`: D_v(m) = G1(v) max(0, v·m) D(m) / v_z.
#[inline]
pub fn visible_normal_pdf(v: Vec3, m: Vec3, alpha: f32) -> f32 {
    let vm = v.dot(m);
    if vm <= 0.0 || v.z <= 0.0 {
        return 0.0;
    }
    smith_g1(v.z, alpha) * vm * ggx_d(m, alpha) / v.z
}

/// The facet normal that reflects `v` into `o` (both above the surface): the half vector
/// (v + o) / |v + o|. `None` where the two are opposite.
#[inline]
pub fn reflection_normal(v: Vec3, o: Vec3) -> Option<Vec3> {
    let h = v + o;
    (h.length_squared() > 0.0).then(|| h.normalize())
}

/// The facet normal that refracts `v` (on the side of index `n1`) into `o` (on the side
/// of `n2`), facing `v`'s side: −(n1 v + n2 o), normalised and turned to +z (Walter's
/// generalized half vector). `None` where no facet does: `v` and `o` on one side of it, or
/// the two opposite with equal indices.
#[inline]
pub fn refraction_normal(v: Vec3, o: Vec3, n1: f32, n2: f32) -> Option<Vec3> {
    let h = -(n1 * v + n2 * o);
    if h.length_squared() == 0.0 {
        return None;
    }
    let m = h.normalize() * h.z.signum();
    (v.dot(m) > 0.0 && o.dot(m) < 0.0).then_some(m)
}

/// dω_m / dω_o for a refraction from `v` (index `n1`) into `o` (index `n2`) through the
/// facet `m`: n2² |o·m| / (n1 (v·m) + n2 (o·m))² (Walter 2007, eq. 17).
#[inline]
pub fn refraction_jacobian(v: Vec3, o: Vec3, m: Vec3, n1: f32, n2: f32) -> f32 {
    let om = o.dot(m);
    let denom = n1 * v.dot(m) + n2 * om;
    n2 * n2 * om.abs() / (denom * denom)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A direction at polar angle θ (from +z) and azimuth φ.
    fn dir(theta: f32, phi: f32) -> Vec3 {
        Vec3::new(
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        )
    }

    /// ∫ f dω over the upper hemisphere by the midpoint rule in (cos θ, φ).
    fn hemisphere(f: impl Fn(Vec3) -> f64, n: usize) -> f64 {
        let mut sum = 0.0;
        for i in 0..n {
            let z = (i as f64 + 0.5) / n as f64;
            let s = (1.0 - z * z).sqrt();
            for j in 0..2 * n {
                let phi = std::f64::consts::PI * (j as f64 + 0.5) / n as f64;
                let d = Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, z as f32);
                sum += f(d);
            }
        }
        sum * 2.0 * std::f64::consts::PI / (2 * n * n) as f64
    }

    #[test]
    fn the_projected_facet_area_is_the_surfaces_and_each_view_sees_its_own_shadow() {
        for alpha in [0.2f32, 0.5, 1.0] {
            // ∫ D(m) cos θm dω = 1: the facets' area projected is the surface's.
            let area = hemisphere(|m| (ggx_d(m, alpha) * m.z) as f64, 800);
            assert!((area - 1.0).abs() < 1e-3, "α {alpha}: {area}");
            // ∫ G1(v) max(0, v·m) D(m) dω = v_z: the facets seen along v, projected onto
            // the view, cover the surface seen along v (Smith's G1 is that normalisation).
            for theta in [0.0f32, 0.6, 1.2, 1.5] {
                let v = dir(theta, 0.3);
                let seen = hemisphere(|m| (visible_normal_pdf(v, m, alpha) * v.z) as f64, 800);
                assert!(
                    (seen - v.z as f64).abs() < 2e-3,
                    "α {alpha}, θ {theta}: {seen}"
                );
            }
        }
    }

    #[test]
    fn visible_normals_are_drawn_with_their_density() {
        // Histogram of drawn normals over cells of (cos θm, φm) against the density
        // integrated over each cell: a chi-square-like bound per cell from the count.
        let (alpha, v) = (0.4f32, dir(1.0, 0.7));
        let (nz, nphi, draws) = (8usize, 16usize, 400_000u32);
        let mut counts = vec![0u32; nz * nphi];
        let cell = |m: Vec3| {
            let iz = ((m.z * nz as f32) as usize).min(nz - 1);
            let phi = m.y.atan2(m.x).rem_euclid(2.0 * PI);
            let ip = ((phi / (2.0 * PI) * nphi as f32) as usize).min(nphi - 1);
            iz * nphi + ip
        };
        for k in 0..draws {
            // A (0, 2) sequence's first two dimensions: van der Corput and k / draws.
            let u = Vec2::new(
                k.reverse_bits() as f32 / 2f32.powi(32),
                k as f32 / draws as f32,
            );
            let m = sample_visible_normal(v, alpha, u);
            assert!(m.z >= 0.0 && v.dot(m) >= -1e-6 && (m.length() - 1.0).abs() < 1e-5);
            counts[cell(m)] += 1;
        }
        let mut expected = vec![0f64; nz * nphi];
        let n = 600;
        for i in 0..n {
            let z = (i as f32 + 0.5) / n as f32;
            let s = (1.0 - z * z).sqrt();
            for j in 0..4 * n {
                let phi = 2.0 * PI * (j as f32 + 0.5) / (4 * n) as f32;
                let m = Vec3::new(s * phi.cos(), s * phi.sin(), z);
                let w = (2.0 * PI / (4 * n * n) as f32) as f64;
                expected[cell(m)] += visible_normal_pdf(v, m, alpha) as f64 * w;
            }
        }
        for (c, (&got, &p)) in counts.iter().zip(&expected).enumerate() {
            let mean = p * draws as f64;
            // Stratified draws come closer than independent ones; 4σ of a binomial count
            // plus the quadrature's own error bounds either.
            let bound = 4.0 * mean.sqrt() + 1e-3 * draws as f64 * p.max(1e-3) + 2.0;
            assert!(
                (got as f64 - mean).abs() < bound,
                "cell {c}: {got} drawn, {mean:.1} expected"
            );
        }
    }

    #[test]
    fn the_half_vectors_give_back_the_facet() {
        // v 0.3 rad from m: within the critical angle leaving glass (0.73 rad).
        let v = dir(0.5, 1.5);
        let m = dir(0.25, 2.0);
        assert!(v.dot(m) > 0.73f32.cos());
        let o = 2.0 * v.dot(m) * m - v;
        assert!((reflection_normal(v, o).unwrap() - m).length() < 1e-5);
        // Refraction into glass (1 → 1.5) and out of it (1.5 → 1), through the facet m.
        for (n1, n2) in [(1.0f32, 1.5f32), (1.5, 1.0)] {
            let t = crate::optics::refract(-v, m, n1, n2).unwrap();
            assert!((refraction_normal(v, t, n1, n2).unwrap() - m).length() < 1e-5);
        }
        // A direction on the viewer's side is no refraction.
        assert!(refraction_normal(v, o, 1.0, 1.5).is_none());
    }

    #[test]
    fn a_smooth_limit_keeps_its_peak() {
        // α = 10⁻⁴: D at the normal is 1/(π α²) without cancelling to infinity.
        let alpha = 1e-4f32;
        let d = ggx_d(Vec3::Z, alpha);
        assert!((d / (1.0 / (PI * alpha * alpha)) - 1.0).abs() < 1e-5);
        assert!((smith_g1(0.3, alpha) - 1.0).abs() < 1e-6);
        let m = sample_visible_normal(dir(0.8, 1.0), alpha, Vec2::new(0.9, 0.4));
        assert!(m.z > 0.999_999);
    }
}
