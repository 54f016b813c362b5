//! Distribution ray tracing in images, each against a closed form or a high-sample
//! reference: antialiasing by pattern, the thin lens's circle of confusion, motion smear,
//! and penumbrae from area lights.

use raylab::camera::Camera;
use raylab::geometry::{Plane, Quad, Shape, Sphere};
use raylab::light::{Light, LightShape};
use raylab::material::{Diffuse, Emissive, Material};
use raylab::math::{Color, Pattern, Ray, SampleStream, Vec3};
use raylab::params::Params;
use raylab::render::{Film, render};
use raylab::scene::{Scene, SceneDesc};
use raylab::tracer::{Media, Stats, Tracer};

fn scene(objects: Vec<(Shape, Material)>, lights: Vec<Light>, camera: Camera) -> Scene {
    let mut desc = SceneDesc::empty(camera);
    for (i, (shape, material)) in objects.into_iter().enumerate() {
        desc.add(format!("object {i}"), shape, material);
    }
    desc.lights = lights;
    desc.build()
}

fn glow() -> Material {
    Material::Emissive(Emissive::solid(Color::ONE))
}

fn white() -> Material {
    Material::Diffuse(Diffuse::solid(Color::ONE))
}

fn rmse(a: &Film, b: &Film) -> f64 {
    let se: f64 = a
        .pixels()
        .zip(b.pixels())
        .map(|(x, y)| ((x - y).length_squared() / 3.0) as f64)
        .sum();
    (se / (a.width() * a.height()) as f64).sqrt()
}

#[test]
fn at_16_spp_jittered_beats_random_and_sobol_beats_both() {
    let s = Scene::load("antialiasing").unwrap();
    let (w, h) = (160, 90);
    let reference = render(
        &s,
        &Params {
            spp: 1024,
            pattern: Pattern::Sobol,
            seed: 99,
            ..s.params.clone()
        },
        w,
        h,
        &(),
    )
    .unwrap()
    .0;
    let error = |pattern| {
        // The mean over four seeds, so one lucky seed decides nothing.
        (0..4)
            .map(|seed| {
                let p = Params {
                    spp: 16,
                    pattern,
                    seed,
                    ..s.params.clone()
                };
                rmse(&render(&s, &p, w, h, &()).unwrap().0, &reference)
            })
            .sum::<f64>()
            / 4.0
    };
    let (regular, random, jittered, sobol) = (
        error(Pattern::Regular),
        error(Pattern::Random),
        error(Pattern::Jittered),
        error(Pattern::Sobol),
    );
    println!(
        "16-spp RMSE: regular {regular:.5}, random {random:.5}, jittered {jittered:.5}, sobol {sobol:.5}"
    );
    assert!(
        jittered < 0.85 * random,
        "jittered {jittered} vs random {random}"
    );
    assert!(sobol < jittered, "sobol {sobol} vs jittered {jittered}");
}

/// The fraction of a disk of radius `r` centred at `x` that lies at negative coordinates
/// (the circular segment), for the thin-lens blur of a step edge at 0.
fn disk_left_fraction(x: f64, r: f64) -> f64 {
    if x <= -r {
        1.0
    } else if x >= r {
        0.0
    } else {
        let d = x / r;
        (d.acos() - d * (1.0 - d * d).sqrt()) / std::f64::consts::PI
    }
}

#[test]
fn thin_lens_keeps_the_focus_plane_sharp_and_blurs_by_the_circle_of_confusion() {
    // An emitting half-plane (x < 0) facing the camera at depth z, on black. The lens of
    // radius a is focused at distance s: a point at depth z spreads over a disk of radius
    // a |1 − z/s| at that depth, so the edge's profile is the disk's segment area.
    // 96 × 8 pixels; the field of view is vertical, so a unit at depth z spans
    // 8 / (2 z tan(fov/2)) pixels.
    let (n, rows, fov) = (96u32, 8u32, 1.0f32);
    let focus = 10.0f32;
    let camera = Camera::looking_at(Vec3::ZERO, -Vec3::Z, Vec3::Y, fov);
    for (depth, aperture) in [(10.0f32, 0.0f32), (10.0, 0.3), (20.0, 0.15), (6.0, 0.1)] {
        let edge = Quad::new(
            Vec3::new(-100.0, -100.0, -depth),
            Vec3::new(100.0, 0.0, 0.0),
            Vec3::new(0.0, 200.0, 0.0),
        );
        let s = scene(vec![(Shape::Quad(edge), glow())], vec![], camera.clone());
        let params = Params {
            spp: 256,
            aperture,
            focus_distance: Some(focus),
            ..Params::default()
        };
        let (film, _) = render(&s, &params, n, rows, &()).unwrap();
        // Pixels per unit at that depth; the disk's radius in pixels.
        let px_per_unit =
            rows as f64 / (2.0 * depth as f64 * (fov as f64 / 2.0).to_radians().tan());
        let r_px = aperture as f64 * (1.0 - depth as f64 / focus as f64).abs() * px_per_unit;
        for x in 0..n {
            let measured: f64 =
                (0..rows).map(|y| film.pixel(x, y).x as f64).sum::<f64>() / rows as f64;
            // The expected value, averaged over the pixel's width (the box filter).
            let expected: f64 = (0..32)
                .map(|k| {
                    let u = x as f64 + (k as f64 + 0.5) / 32.0 - n as f64 / 2.0;
                    if r_px == 0.0 {
                        f64::from(u < 0.0)
                    } else {
                        disk_left_fraction(u, r_px)
                    }
                })
                .sum::<f64>()
                / 32.0;
            assert!(
                (measured - expected).abs() < 0.03,
                "depth {depth}, aperture {aperture} (CoC radius {r_px:.2} px), pixel {x}: {measured:.3} vs {expected:.3}"
            );
        }
        if depth == focus {
            // In focus: only the pixel the edge crosses is partial, whatever the aperture.
            let partial = (0..n)
                .filter(|&x| (0.02..0.98).contains(&film.pixel(x, 0).x))
                .count();
            assert!(
                partial <= 1,
                "aperture {aperture}: {partial} partial pixels at the focus plane"
            );
        }
    }
}

#[test]
fn a_moving_sphere_smears_over_its_travel_and_a_closed_shutter_freezes_it() {
    // An emitting sphere of radius r moving along x by v per frame, seen from far away.
    // Along its centre row the time-averaged coverage is a box of width 2r convolved with
    // a box of width v·shutter: a trapezoid.
    // 120 × 4 pixels, about 14 pixels per unit at the sphere.
    let (n, rows, fov, dist) = (120u32, 4u32, 0.8f32, 20.0f32);
    let camera = Camera::looking_at(Vec3::new(0.0, 0.0, dist), Vec3::ZERO, Vec3::Y, fov);
    let (r, v) = (0.8f32, 3.0f32);
    let mut sphere = Sphere::new(Vec3::new(-2.0, 0.0, 0.0), r);
    sphere.velocity = Vec3::new(v, 0.0, 0.0);
    let s = scene(vec![(Shape::Sphere(sphere), glow())], vec![], camera);
    let px_per_unit = rows as f64 / (2.0 * dist as f64 * (fov as f64 / 2.0).to_radians().tan());
    for (open, shutter) in [(0.0f32, 1.0f32), (0.25, 0.5), (0.5, 0.0)] {
        let params = Params {
            spp: 256,
            shutter_open: open,
            shutter,
            ..Params::default()
        };
        let (film, _) = render(&s, &params, n, rows, &()).unwrap();
        // Centre x over the shutter: from −2 + v·open to −2 + v·(open + shutter).
        let (a, b) = (-2.0 + v * open, -2.0 + v * (open + shutter));
        let coverage = |x: f64| {
            // The fraction of the shutter for which |x − c(t)| < r, c moving a → b.
            let (a, b, r) = (a as f64, b as f64, r as f64);
            if b == a {
                return f64::from((x - a).abs() < r);
            }
            let lo = (x - r).max(a);
            let hi = (x + r).min(b);
            ((hi - lo) / (b - a)).clamp(0.0, 1.0)
        };
        // The row just above centre: its chord is 2r to within 0.4%.
        for px in 0..n {
            let measured = film.pixel(px, 1).x as f64;
            let expected: f64 = (0..16)
                .map(|k| {
                    coverage((px as f64 + (k as f64 + 0.5) / 16.0 - n as f64 / 2.0) / px_per_unit)
                })
                .sum::<f64>()
                / 16.0;
            assert!(
                (measured - expected).abs() < 0.04,
                "shutter {open}+{shutter}, pixel {px}: {measured:.3} vs {expected:.3}"
            );
        }
        if shutter == 0.0 {
            let partial = (0..n)
                .filter(|&x| (0.02..0.98).contains(&film.pixel(x, 1).x))
                .count();
            assert!(
                partial <= 2,
                "a closed shutter is sharp: {partial} partial pixels"
            );
        }
    }
}

/// Irradiance-proportional radiance of a white floor at (x, 0, 0), averaged over
/// `samples` light samples, under an occluding half-plane (x < 0 at height `h`) if `occluder`.
fn floor_profile(
    light: &Light,
    h: f32,
    occluder: bool,
    size: f32,
    xs: &[f32],
    samples: u32,
) -> Vec<f64> {
    let mut objects = vec![(Shape::Plane(Plane::new(Vec3::ZERO, Vec3::Y)), white())];
    if occluder {
        let q = Quad::new(
            Vec3::new(-50.0, h, -50.0),
            Vec3::new(0.0, 0.0, 100.0),
            Vec3::new(50.0, 0.0, 0.0),
        );
        objects.push((Shape::Quad(q), white()));
    }
    let camera = Camera::looking_at(Vec3::new(0.0, 5.0, 5.0), Vec3::ZERO, Vec3::Y, 40.0);
    let s = scene(objects, vec![light.clone()], camera);
    let params = Params {
        light_size: size,
        ..Params::default()
    };
    let tracer = Tracer::new(&s, &params, 1, 1);
    xs.iter()
        .enumerate()
        .map(|(i, &x)| {
            let mut stats = Stats::default();
            // Straight down onto the floor from below the occluder.
            let ray = Ray::new(Vec3::new(x, 0.5 * h, 0.0), -Vec3::Y, 0.0);
            (0..samples)
                .map(|k| {
                    let mut rng =
                        SampleStream::with_pattern(Pattern::Sobol, samples, 5, i as u32, k);
                    tracer
                        .trace(&ray, 0, 1.0, &Media::default(), &mut rng, &mut stats)
                        .x as f64
                })
                .sum::<f64>()
                / samples as f64
        })
        .collect()
}

#[test]
fn penumbrae_grow_with_the_light_as_similar_triangles_predict() {
    // A rectangular light of width w (along x) at height H, an occluding edge at height h
    // over x = 0. From a floor point x the edge hides the part of the light with
    // coordinate below x (1 − H/h): the visible fraction ramps linearly across a penumbra
    // of width w h / (H − h), centred on the hard shadow's edge at x = 0.
    let (big_h, h, w) = (4.0f32, 1.0f32, 1.2f32);
    let light = Light {
        shape: LightShape::Rect {
            center: Vec3::new(0.0, big_h, 0.0),
            edge_u: Vec3::new(w, 0.0, 0.0),
            edge_v: Vec3::new(0.0, 0.0, 0.1),
        },
        intensity: Color::splat(10.0),
        scale: 1.0,
    };
    // edge_u × edge_v must point down.
    assert!(Vec3::new(w, 0.0, 0.0).cross(Vec3::new(0.0, 0.0, 0.1)).y < 0.0);
    let xs: Vec<f32> = (-40..=40).map(|i| i as f32 * 0.02).collect();
    for size in [0.5f32, 1.0, 2.0] {
        let lit = floor_profile(&light, h, false, size, &xs, 256);
        let shadowed = floor_profile(&light, h, true, size, &xs, 256);
        let width = size * w;
        let penumbra = width * h / (big_h - h);
        for (k, &x) in xs.iter().enumerate() {
            let x_light = x * (1.0 - big_h / h);
            let expected = ((width / 2.0 - x_light) / width).clamp(0.0, 1.0) as f64;
            let measured = shadowed[k] / lit[k];
            assert!(
                (measured - expected).abs() < 0.03,
                "light size {size} (penumbra {penumbra:.3}), x = {x:.2}: {measured:.3} vs {expected:.3}"
            );
        }
    }
    // Size → 0 converges to the point light: the same lit floor, and a hard shadow.
    let point = floor_profile(&light, h, true, 0.0, &xs, 4);
    let tiny = floor_profile(&light, h, true, 1e-3, &xs, 64);
    let tiny_penumbra = 1e-3 * w * h / (big_h - h);
    for (k, &x) in xs.iter().enumerate() {
        if x.abs() <= tiny_penumbra {
            continue; // inside the tiny light's own penumbra: half of it is visible at x = 0
        }
        assert!(
            (tiny[k] - point[k]).abs() <= 1e-3 * point[k].max(1e-3),
            "x = {x}: {} vs {}",
            tiny[k],
            point[k]
        );
        assert_eq!(
            point[k] == 0.0,
            x < 0.0,
            "x = {x}: the point light's shadow edge is at 0"
        );
    }
}
