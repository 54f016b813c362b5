//! The lights' sampling against closed forms, and their lanes against one sample.

use super::*;
use crate::math::SampleStream;

/// The irradiance estimate at `p` (normal `n`) from `samples` samples of `light`.
fn irradiance(light: &Light, p: Vec3, n: Vec3, samples: u32) -> f64 {
    let light = light.prepare();
    let mut sum = 0.0f64;
    for i in 0..samples {
        let u = SampleStream::with_pattern(crate::math::Pattern::Sobol, samples, 1, 0, i).next_2d();
        if let Some(s) = light.sample(p, u) {
            sum += (s.value.x * s.dir.dot(n).max(0.0)) as f64;
        }
    }
    sum / samples as f64
}

#[test]
fn lanes_aim_at_each_samples_point_bit_for_bit() {
    use crate::math::lanes::{Lanes, V3};
    let rect = Light {
        shape: LightShape::Rect {
            center: Vec3::new(0.3, 3.0, -0.5),
            edge_u: Vec3::new(1.5, 0.0, 0.2),
            edge_v: Vec3::new(0.0, 0.1, 1.0),
        },
        intensity: Color::new(40.0, 30.0, 20.0),
        scale: 0.7,
    };
    let point = Light {
        shape: LightShape::Sphere {
            center: Vec3::new(-2.0, 4.0, 1.0),
            radius: 0.5,
        },
        scale: 0.0,
        ..rect.clone()
    };
    // A rectangle shrunk to a point still shines only forwards.
    let tiny = Light {
        scale: 0.0,
        ..rect.clone()
    };
    // A spot among the points: those outside its cone are dark.
    let spot = Light::spot(
        Vec3::new(0.5, 1.0, 0.0),
        Cone {
            axis: Vec3::new(0.0, -1.0, 0.0),
            cos_inner: 0.8,
            cos_outer: 0.5,
        },
        Color::new(40.0, 30.0, 20.0),
    );
    const N: usize = 8;
    for light in [rect, point, tiny, spot].map(|l| l.prepare()) {
        assert!(light.aims_at_points());
        let (mut lit, mut dark) = (0, 0);
        for k in 0..64 {
            // Points below and above the rectangle (seen from behind), one on it.
            let p = V3::<Lanes<N>>::from_fn(|i| {
                let j = (k * N + i) as f32;
                Vec3::new(
                    (j * 0.37).sin() * 3.0,
                    (j * 0.11).cos() * 4.0,
                    (j * 0.53).sin(),
                )
            });
            let p = if k == 0 {
                V3::splat(Vec3::new(0.3, 3.0, -0.5))
            } else {
                p
            };
            let u = (
                Lanes::from_fn(|i| ((k * N + i) as f32 * 0.618).fract()),
                Lanes::from_fn(|i| ((k * N + i) as f32 * 0.414).fract()),
            );
            let q = light.point_of::<Lanes<N>>(u).expect("a point");
            let (dir, dist, factor, valid) = light.toward::<Lanes<N>>(p, q);
            for i in 0..N {
                let one = light.sample(p.get(i), Vec2::new(u.0.0[i], u.1.0[i]));
                assert_eq!(valid.0[i] != 0, one.is_some(), "lane {i} of {k}");
                let Some(one) = one else {
                    dark += 1;
                    continue;
                };
                lit += 1;
                let bits = |v: Vec3| v.to_array().map(f32::to_bits);
                assert_eq!(bits(dir.get(i)), bits(one.dir));
                assert_eq!(dist.0[i].to_bits(), one.dist.to_bits());
                let value = light.base() * factor.0[i];
                assert_eq!(bits(value), bits(one.value));
            }
        }
        assert!(lit > 100, "{lit} lit");
        let shaped = light.normal.is_some() || light.cone.is_some();
        assert!(
            dark > 0 || !shaped,
            "{dark} from behind or outside the cone"
        );
    }
}

#[test]
fn disk_light_sampling_converges_to_the_analytic_irradiance() {
    // On the axis of a disk of radius R and radiance L at height h: E = π L R² / (h² + R²).
    let (radius, h) = (1.5f32, 2.0f32);
    let light = Light {
        shape: LightShape::Disk {
            center: Vec3::new(0.0, h, 0.0),
            normal: -Vec3::Y,
            radius,
        },
        intensity: Color::splat(3.0),
        scale: 1.0,
    };
    let l = light.radiance().x as f64;
    let expected =
        std::f64::consts::PI * l * (radius * radius) as f64 / (h * h + radius * radius) as f64;
    let got = irradiance(&light, Vec3::ZERO, Vec3::Y, 1 << 14);
    assert!(
        (got - expected).abs() < 1e-3 * expected,
        "{got} vs {expected}"
    );
    // From behind, nothing.
    assert!(
        light
            .prepare()
            .sample(Vec3::new(0.0, 5.0, 0.0), Vec2::splat(0.5))
            .is_none()
    );
}

#[test]
fn sphere_light_irradiance_is_that_of_a_point_of_equal_intensity() {
    // A sphere light's far field: E = I cos θ / d² (exact outside the sphere, for a
    // surface that sees the whole sphere).
    let light = Light {
        shape: LightShape::Sphere {
            center: Vec3::new(0.0, 3.0, 0.0),
            radius: 0.8,
        },
        intensity: Color::splat(5.0),
        scale: 1.0,
    };
    let got = irradiance(&light, Vec3::ZERO, Vec3::Y, 1 << 12);
    assert!((got - 5.0 / 9.0).abs() < 1e-4, "{got}");
}

#[test]
fn rect_light_at_size_zero_is_a_forward_point_light() {
    let rect = Light {
        shape: LightShape::Rect {
            center: Vec3::new(0.0, 2.0, 0.0),
            edge_u: Vec3::X,
            edge_v: Vec3::Z,
        },
        intensity: Color::splat(4.0),
        scale: 0.0,
    };
    // edge_u × edge_v = x × z = −y: it shines down.
    let point = rect.prepare();
    let s = point.sample(Vec3::ZERO, Vec2::splat(0.3)).unwrap();
    assert!((s.value.x - 4.0 / 4.0).abs() < 1e-6 && (s.dir - Vec3::Y).length() < 1e-6);
    assert!(
        point
            .sample(Vec3::new(0.0, 4.0, 0.0), Vec2::splat(0.3))
            .is_none()
    );
    assert!(
        point
            .hit(&Ray::new(Vec3::ZERO, Vec3::Y, 0.0), f32::INFINITY)
            .is_none(),
        "a point is never hit"
    );
    // At size 1 it is seen from below, and is dark from above.
    let big = rect.scaled(1.0).prepare();
    let (t, l) = big
        .hit(&Ray::new(Vec3::ZERO, Vec3::Y, 0.0), f32::INFINITY)
        .unwrap();
    assert!((t - 2.0).abs() < 1e-6 && (l.x - 4.0).abs() < 1e-6);
    let (_, back) = big
        .hit(
            &Ray::new(Vec3::new(0.0, 4.0, 0.0), -Vec3::Y, 0.0),
            f32::INFINITY,
        )
        .unwrap();
    assert_eq!(back, Color::ZERO);
    // Scaling keeps the intensity: the on-axis irradiance far away is unchanged.
    let far = Vec3::new(0.0, -200.0, 0.0);
    for size in [0.0, 0.5, 2.0] {
        let e = irradiance(&rect.scaled(size), far, Vec3::Y, 256);
        assert!(
            (e - 4.0 / 202.0f64.powi(2)).abs() < 1e-3 * 4.0 / 202.0f64.powi(2),
            "size {size}: {e}"
        );
    }
}

#[test]
fn a_spot_lights_its_cone_as_gltf_says_and_nothing_outside() {
    // A spot 2 above the floor, shining straight down, inner cone 20°, outer 30°. On the
    // floor at angle θ from the axis: E = I f(θ) cos θ / d², d = 2 / cos θ, with
    // f = 1 inside 20°, 0 beyond 30°, and t², t = (cos θ − cos 30°)/(cos 20° − cos 30°),
    // between (KHR_lights_punctual's reference falloff).
    let (inner, outer) = (20f32.to_radians(), 30f32.to_radians());
    let cone = Cone {
        axis: -Vec3::Y,
        cos_inner: inner.cos(),
        cos_outer: outer.cos(),
    };
    let spot = Light::spot(Vec3::new(0.0, 2.0, 0.0), cone, Color::splat(8.0));
    for degrees in [0.0f32, 10.0, 19.0, 22.0, 25.0, 28.0, 31.0, 60.0] {
        let theta = degrees.to_radians();
        let p = Vec3::new(2.0 * theta.tan(), 0.0, 0.0);
        let d2 = (2.0 / theta.cos()).powi(2);
        let f = if theta <= inner {
            1.0
        } else if theta >= outer {
            0.0
        } else {
            ((theta.cos() - outer.cos()) / (inner.cos() - outer.cos())).powi(2)
        };
        let expected = (8.0 * f * theta.cos() / d2) as f64;
        let got = irradiance(&spot, p, Vec3::Y, 4);
        assert!(
            (got - expected).abs() <= 1e-5 * expected.max(1e-3),
            "at {degrees}°: {got} vs {expected}"
        );
        // Photons leave it with the same intensity.
        let dir = (p - spot.center()).normalize();
        let i = spot.point_intensity(dir).expect("a point").x;
        assert!((i - 8.0 * f).abs() < 1e-5, "at {degrees}°: {i}");
    }
    // A spot stays a point at every light size: no area, nothing to hit.
    let big = spot.scaled(3.0).prepare();
    assert!(!big.can_be_seen() && big.aims_at_points());
    // Beyond the cone no shadow ray is asked for.
    assert!(
        spot.prepare()
            .sample(Vec3::new(5.0, 0.0, 0.0), Vec2::splat(0.5))
            .is_none()
    );
}
