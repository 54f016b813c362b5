//! Pure sampling functions: they take uniform numbers, not a random generator, so tests
//! can check them exactly. Directions come in a local frame whose z axis is the axis of
//! the distribution; [`crate::math::orthonormal_basis`] places them in the world.

use crate::math::Vec3;
use crate::math::lanes::Real;
use glam::Vec2;
use std::f32::consts::{FRAC_PI_4, PI};

/// Maps the unit square to the unit disk, keeping areas in proportion and strata compact
/// (Shirley and Chiu's concentric map): lens samples, and points on disk lights.
///
/// In the wedge where |x| > |y| the point is r (cos φ, sin φ) with r = x, φ = π/4 · y/x;
/// in the other, r (sin φ, cos φ) with r = y, φ = π/4 · x/y (the angle π/2 − φ). Either
/// way |φ| ≤ π/4, where `sin_cos_quarter` needs no range reduction.
pub fn concentric_disk(u: Vec2) -> Vec2 {
    let (x, y) = concentric_disk_of(u.x, u.y);
    Vec2::new(x, y)
}

/// [`concentric_disk`] for one point or one per lane, the wedges chosen by `select`: the
/// point (u_x, u_y) of the unit square, mapped to (x, y) in the unit disk.
#[inline(always)]
pub(crate) fn concentric_disk_of<R: Real>(u_x: R, u_y: R) -> (R, R) {
    let (one, two, zero) = (R::splat(1.0), R::splat(2.0), R::splat(0.0));
    let (o_x, o_y) = (two * u_x - one, two * u_y - one);
    // |x| > |y|: r = x, φ = π/4 · y/x; else r = y, φ = π/4 · x/y.
    let wide = o_y.abs().less(o_x.abs());
    let r = R::select(wide, o_x, o_y);
    let ratio = R::select(wide, o_y, o_x) / r;
    let (sin, cos) = sin_cos_quarter(R::splat(FRAC_PI_4) * ratio);
    let centre = o_x.equal(zero) & o_y.equal(zero);
    let x = R::select(wide, r * cos, r * sin);
    let y = R::select(wide, r * sin, r * cos);
    (R::select(centre, zero, x), R::select(centre, zero, y))
}

/// (sin φ, cos φ) for |φ| ≤ π/4, by the minimax polynomials of Cephes' `sinf`/`cosf`
/// (within 2 ulp there): the lens is sampled for every eye ray, and a library call to
/// `sincosf` cost more than the rest of the thin-lens ray.
///
/// sin φ ≈ φ + φ³(s₁ + φ²(s₂ + φ² s₃)),  cos φ ≈ 1 − φ²/2 + φ⁴(c₁ + φ²(c₂ + φ² c₃)).
#[inline(always)]
fn sin_cos_quarter<R: Real>(phi: R) -> (R, R) {
    let c = R::splat;
    let z = phi * phi;
    let sin = phi + phi * z * (c(-1.666_665_5e-1) + z * (c(8.332_161e-3) + z * c(-1.951_529_6e-4)));
    let cos = c(1.0) - c(0.5) * z
        + z * z * (c(4.166_664_6e-2) + z * (c(-1.388_731_6e-3) + z * c(2.443_315_7e-5)));
    (sin, cos)
}

/// A direction from the Phong lobe cos^n α about the z axis, by inverting its CDF:
/// cos α = u₁^(1/(n+1)), φ = 2π u₂. Its density is [`phong_lobe_pdf`].
pub fn phong_lobe(u: Vec2, exponent: f32) -> Vec3 {
    let cos_a = u.x.powf(1.0 / (exponent + 1.0));
    let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3::new(sin_a * phi.cos(), sin_a * phi.sin(), cos_a)
}

/// The density of [`phong_lobe`] per unit solid angle: p(α) = (n+1)/(2π) cos^n α for
/// α < 90°, 0 beyond.
pub fn phong_lobe_pdf(cos_a: f32, exponent: f32) -> f32 {
    if cos_a <= 0.0 {
        0.0
    } else {
        (exponent + 1.0) / (2.0 * PI) * cos_a.powf(exponent)
    }
}

/// A direction from the cosine-weighted hemisphere about the z axis (Malley's method: a
/// uniform point of the disk, lifted to the hemisphere). Density cos θ / π.
pub fn cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = concentric_disk(u);
    Vec3::new(d.x, d.y, (1.0 - d.length_squared()).max(0.0).sqrt())
}

/// A direction uniform over the cone of half-angle acos(`cos_max`) about the z axis:
/// the directions towards a sphere light. Density 1 / (2π (1 − cos_max)).
pub fn uniform_cone(u: Vec2, cos_max: f32) -> Vec3 {
    let cos_t = 1.0 - u.x * (1.0 - cos_max);
    let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3::new(sin_t * phi.cos(), sin_t * phi.sin(), cos_t)
}

/// The direction `local` (z up) expressed in the frame whose z axis is the unit `axis`.
pub fn to_world(local: Vec3, axis: Vec3) -> Vec3 {
    let (t, b) = crate::math::orthonormal_basis(axis);
    local.x * t + local.y * b + local.z * axis
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn concentric_disk_stays_in_the_unit_disk_and_reaches_its_rim() {
        let mut max_r: f32 = 0.0;
        for i in 0..=64 {
            for j in 0..=64 {
                let p = concentric_disk(Vec2::new(i as f32 / 64.0, j as f32 / 64.0));
                assert!(p.length() <= 1.0 + 1e-6);
                max_r = max_r.max(p.length());
            }
        }
        assert!((max_r - 1.0).abs() < 1e-6);
        assert_eq!(concentric_disk(Vec2::splat(0.5)), Vec2::ZERO);
    }

    #[test]
    fn sin_cos_quarter_matches_the_library_within_two_ulp() {
        for i in -1000..=1000 {
            let phi = FRAC_PI_4 * i as f32 / 1000.0;
            let (sin, cos) = sin_cos_quarter(phi);
            let (exact_sin, exact_cos) = ((phi as f64).sin(), (phi as f64).cos());
            assert!(
                (sin as f64 - exact_sin).abs()
                    <= 2.0 * f32::EPSILON as f64 * exact_sin.abs().max(1e-30) + 1e-12,
                "sin {phi}"
            );
            assert!(
                (cos as f64 - exact_cos).abs() <= 2.0 * f32::EPSILON as f64,
                "cos {phi}"
            );
        }
    }

    #[test]
    fn concentric_disk_preserves_area() {
        // The image of every cell of a 32×32 grid has area π/1024: measured as the area of
        // the polygon through 16 points along its mapped boundary.
        let n = 32;
        for i in 0..n {
            for j in 0..n {
                let (x0, y0) = (i as f32 / n as f32, j as f32 / n as f32);
                let h = 1.0 / n as f32;
                let mut boundary = Vec::new();
                let k = 4;
                for s in 0..k {
                    boundary.push(Vec2::new(x0 + h * s as f32 / k as f32, y0));
                }
                for s in 0..k {
                    boundary.push(Vec2::new(x0 + h, y0 + h * s as f32 / k as f32));
                }
                for s in 0..k {
                    boundary.push(Vec2::new(x0 + h - h * s as f32 / k as f32, y0 + h));
                }
                for s in 0..k {
                    boundary.push(Vec2::new(x0, y0 + h - h * s as f32 / k as f32));
                }
                let pts: Vec<Vec2> = boundary.into_iter().map(concentric_disk).collect();
                let area: f32 = (0..pts.len())
                    .map(|a| pts[a].perp_dot(pts[(a + 1) % pts.len()]))
                    .sum::<f32>()
                    / 2.0;
                let expected = PI / (n * n) as f32;
                assert!(
                    (area.abs() - expected).abs() < 0.01 * expected,
                    "cell ({i}, {j}): {area} vs {expected}"
                );
            }
        }
    }

    #[test]
    fn phong_pdf_integrates_to_one() {
        for n in [1.0f32, 10.0, 100.0, 1000.0] {
            // ∫ p dω = ∫₀^{π/2} p(α) 2π sin α dα, by the midpoint rule on 200,000 steps.
            let steps = 200_000;
            let h = std::f32::consts::FRAC_PI_2 / steps as f32;
            let total: f64 = (0..steps)
                .map(|k| {
                    let a = (k as f32 + 0.5) * h;
                    (phong_lobe_pdf(a.cos(), n) * 2.0 * PI * a.sin() * h) as f64
                })
                .sum();
            assert!((total - 1.0).abs() < 1e-3, "exponent {n}: {total}");
        }
    }

    #[test]
    fn phong_samples_follow_the_pdf_chi_square() {
        // 20 bins of cos α with equal probability under the pdf (the CDF of cos α is
        // cos^(n+1) α), by 8 bins of φ; 100,000 samples from a hashed uniform source.
        for n in [5.0f32, 50.0] {
            let (bins_a, bins_phi) = (20, 8);
            let mut counts = vec![0f64; bins_a * bins_phi];
            let samples = 100_000;
            let mut rng = crate::math::SampleStream::new(7, 0, 0);
            for _ in 0..samples {
                let d = phong_lobe(rng.next_2d(), n);
                let cdf = d.z.max(0.0).powf(n + 1.0);
                let phi = d.y.atan2(d.x).rem_euclid(2.0 * PI);
                let a = ((cdf * bins_a as f32) as usize).min(bins_a - 1);
                let p = ((phi / (2.0 * PI) * bins_phi as f32) as usize).min(bins_phi - 1);
                counts[a * bins_phi + p] += 1.0;
            }
            let expected = samples as f64 / (bins_a * bins_phi) as f64;
            let chi2: f64 = counts
                .iter()
                .map(|c| (c - expected).powi(2) / expected)
                .sum();
            // 159 degrees of freedom: the 99.9th percentile is about 225.
            assert!(chi2 < 225.0, "exponent {n}: chi-square {chi2}");
        }
    }

    #[test]
    fn cone_samples_stay_in_the_cone_and_cover_it() {
        let cos_max = 0.9f32;
        let mut min_cos: f32 = 1.0;
        for i in 0..100 {
            for j in 0..10 {
                let d = uniform_cone(Vec2::new(i as f32 / 100.0, j as f32 / 10.0), cos_max);
                assert!((d.length() - 1.0).abs() < 1e-5 && d.z >= cos_max - 1e-6);
                min_cos = min_cos.min(d.z);
            }
        }
        assert!(min_cos < cos_max + 0.002);
        let w = to_world(Vec3::Z, Vec3::new(0.0, 1.0, 0.0));
        assert!((w - Vec3::Y).length() < 1e-6);
    }
}
