//! Dielectrics in images: energy conservation (white furnace), Beer–Lambert absorption,
//! the stochastic tree converging to the split tree, and total internal reflection in
//! nested media, each against a closed form.

use raylab::camera::Camera;
use raylab::geometry::{Mesh, Shape, Sphere};
use raylab::light::Background;
use raylab::material::{Dielectric, Emissive, Material};
use raylab::math::{Color, Ray, SampleStream, Vec3};
use raylab::params::{MAX_DEPTH, Params, TreeMode};
use raylab::render::{Film, render};
use raylab::scene::{Scene, SceneDesc};
use raylab::tracer::{Media, Stats, Tracer};

fn glass(ior: f32, absorption: Color) -> Material {
    Material::Dielectric(Dielectric {
        absorption,
        ..Dielectric::clear(ior)
    })
}

fn scene(
    objects: Vec<(Shape, Material)>,
    camera: Camera,
    background: Color,
    medium_ior: f32,
) -> Scene {
    let mut desc = SceneDesc::empty(camera);
    for (i, (shape, material)) in objects.into_iter().enumerate() {
        desc.add(format!("object {i}"), shape, material);
    }
    desc.background = Background::Constant(background);
    desc.medium_ior = medium_ior;
    desc.build()
}

fn sphere(center: Vec3, radius: f32) -> Shape {
    Shape::Sphere(Sphere::new(center, radius))
}

fn mean(film: &Film) -> f64 {
    film.pixels().map(|c| c.x as f64).sum::<f64>() / (film.width() * film.height()) as f64
}

#[test]
fn white_furnace_a_clear_sphere_in_a_uniform_environment_vanishes() {
    // The sphere fills most of the view, rim included. Every split conserves energy
    // (R + (1 − R) = 1), so with the whole tree every pixel sees exactly the environment.
    let camera = Camera::looking_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y, 32.0);
    let s = scene(
        vec![(sphere(Vec3::ZERO, 1.0), glass(1.5, Color::ZERO))],
        camera,
        Color::ONE,
        1.0,
    );
    let full = Params {
        spp: 4,
        max_depth: MAX_DEPTH,
        min_weight: 0.0,
        ..Params::default()
    };
    let (film, stats) = render(&s, &full, 32, 32, &()).unwrap();
    assert!(stats.refraction_rays > 0 && stats.reflection_rays > 0);
    for (i, c) in film.pixels().enumerate() {
        assert!(
            (c - Color::ONE).abs().max_element() < 1e-3,
            "pixel {i}: {c:?}"
        );
    }
    // With the tree cut shallower, energy goes missing, more at every step down.
    let mut last = f64::INFINITY;
    for max_depth in (0..=8).rev() {
        let m = mean(
            &render(
                &s,
                &Params {
                    max_depth,
                    ..full.clone()
                },
                32,
                32,
                &(),
            )
            .unwrap()
            .0,
        );
        assert!(
            m < last,
            "mean {m} at max_depth {max_depth} is not below {last}"
        );
        last = m;
    }
    assert!(
        last < 0.5,
        "with no children only reflection-free misses remain: {last}"
    );
}

#[test]
fn white_furnace_rough_glass_creates_no_light_and_loses_what_single_scattering_loses() {
    // A rough sphere in a white environment, the whole tree: at each hit the two jittered
    // children carry F·G1 and (1 − F)·G1, at most 1 between them, so no pixel exceeds 1
    // (up to rounding); the facets' shadowing loses light, more as α grows; nearly smooth
    // glass loses little.
    let camera = Camera::looking_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y, 32.0);
    let frosted = |roughness| {
        Material::Dielectric(Dielectric {
            roughness,
            ..Dielectric::clear(1.5)
        })
    };
    let params = Params {
        spp: 8,
        max_depth: 12,
        min_weight: 0.0,
        ..Params::default()
    };
    let mut means = Vec::new();
    for alpha in [0.02, 0.2, 0.6] {
        let s = scene(
            vec![(sphere(Vec3::ZERO, 1.0), frosted(alpha))],
            camera.clone(),
            Color::ONE,
            1.0,
        );
        let (film, _) = render(&s, &params, 32, 32, &()).unwrap();
        for (i, c) in film.pixels().enumerate() {
            assert!(c.max_element() <= 1.0 + 1e-5, "α {alpha}, pixel {i}: {c:?}");
        }
        means.push(mean(&film));
    }
    // (Even nearly smooth, the facets seen at grazing angles at the rim shadow a few
    // percent: 1.3 % over the image at α = 0.02.)
    assert!(means[0] > 0.98, "nearly smooth: {means:?}");
    assert!(
        means[0] > means[1] && means[1] > means[2],
        "rougher loses more: {means:?}"
    );
}

#[test]
fn nearly_smooth_rough_glass_gives_the_smooth_image_within_noise() {
    // The lecture's glass scene with α = 10⁻³ against α = 0: the same image, but for the
    // numbers the facets draw (which move the soft shadows' draws after them): the mean
    // difference of the pixels within four standard errors of 0.
    let s = Scene::load("glass").unwrap();
    let at = |roughness| {
        let p = Params {
            spp: 16,
            roughness: Some(roughness),
            ..s.params.clone()
        };
        render(&s, &p, 96, 54, &()).unwrap().0
    };
    let (smooth, rough) = (at(0.0), at(1e-3));
    let d: Vec<f64> = smooth
        .pixels()
        .zip(rough.pixels())
        .map(|(a, b)| (a - b).element_sum() as f64 / 3.0)
        .collect();
    let n = d.len() as f64;
    let m = d.iter().sum::<f64>() / n;
    let sd = (d.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    assert!(sd > 0.0, "the draws differ");
    assert!(
        m.abs() < 4.0 * sd / n.sqrt(),
        "mean difference {m}, standard error {}",
        sd / n.sqrt()
    );
}

#[test]
fn a_slab_transmits_beer_lambert_with_fresnel_losses_at_both_faces() {
    // Looking straight through a slab of thickness d at an emitter of radiance 1, with
    // everything else black: T = (1 − R)² e^{−σd} / (1 − R² e^{−2σd}), summing the light
    // that bounces back and forth between the faces (R = 0.04 at normal incidence).
    let sigma = Color::new(0.0, 0.5, 2.0);
    for d in [0.25f32, 1.0, 2.0] {
        let slab = Mesh::cuboid(Vec3::new(-5.0, -5.0, -d), Vec3::new(5.0, 5.0, 0.0)).unwrap();
        let emitter =
            Mesh::cuboid(Vec3::new(-20.0, -20.0, -12.0), Vec3::new(20.0, 20.0, -11.0)).unwrap();
        let camera = Camera::looking_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y, 2.0);
        let s = scene(
            vec![
                (Shape::Mesh(slab), glass(1.5, sigma)),
                (
                    Shape::Mesh(emitter),
                    Material::Emissive(Emissive::solid(Color::ONE)),
                ),
            ],
            camera,
            Color::ZERO,
            1.0,
        );
        let params = Params {
            spp: 1,
            max_depth: MAX_DEPTH,
            min_weight: 0.0,
            ..Params::default()
        };
        let (film, _) = render(&s, &params, 8, 8, &()).unwrap();
        let r = 0.04f32;
        for c in film.pixels() {
            for k in 0..3 {
                let a = (-sigma[k] * d).exp();
                let expected = (1.0 - r).powi(2) * a / (1.0 - r * r * a * a);
                // Rays are within 1° of normal: R and the path length change by < 1e-4.
                assert!(
                    (c[k] - expected).abs() < 2e-4,
                    "d = {d}, channel {k}: {} vs {expected}",
                    c[k]
                );
            }
        }
    }
}

#[test]
fn stochastic_tree_converges_to_the_split_tree() {
    // Same camera rays (same seed), the whole tree (no weight pruning, same depth): the
    // stochastic estimate's expectation is the split value, and its error falls as 1/√N.
    let s = Scene::load("glass").unwrap();
    let base = Params {
        max_depth: 16,
        min_weight: 0.0,
        ..Params::default()
    };
    let (w, h) = (48, 27);
    let rmse = |spp: u32| {
        let split = render(
            &s,
            &Params {
                spp,
                ..base.clone()
            },
            w,
            h,
            &(),
        )
        .unwrap()
        .0;
        let stoch = render(
            &s,
            &Params {
                spp,
                tree: TreeMode::Stochastic,
                ..base.clone()
            },
            w,
            h,
            &(),
        )
        .unwrap()
        .0;
        let (mut se, mut diff) = (0.0f64, 0.0f64);
        for (a, b) in split.pixels().zip(stoch.pixels()) {
            let d = (b - a).to_array().map(f64::from);
            se += d.iter().map(|x| x * x).sum::<f64>() / 3.0;
            diff += d.iter().sum::<f64>() / 3.0;
        }
        let n = (w * h) as f64;
        ((se / n).sqrt(), diff / n)
    };
    let (rmse_16, _) = rmse(16);
    let (rmse_256, bias_256) = rmse(256);
    let ratio = rmse_256 / rmse_16;
    assert!(
        rmse_16 > 1e-3,
        "the stochastic tree should be noisy at 16 spp: {rmse_16}"
    );
    assert!(
        (0.15..0.35).contains(&ratio),
        "RMSE should fall 4× from 16 to 256 spp: ratio {ratio}"
    );
    // The image mean agrees to within a few standard errors of a mean over all pixels.
    let standard_error = rmse_256 / ((w * h) as f64).sqrt();
    assert!(
        bias_256.abs() < 4.0 * standard_error + 1e-5,
        "mean difference {bias_256} vs σ {standard_error}"
    );
}

/// Parallel rays along −z on a fine grid over the disk of radius `r` around the z axis,
/// each traced with max_depth 1: returns (rays, total internal reflection events).
fn tir_fraction(s: &Scene, r: f32, start_z: f32) -> f64 {
    let params = Params {
        max_depth: 1,
        min_weight: 0.0,
        ..Params::default()
    };
    let tracer = Tracer::new(s, &params, 1, 1);
    let mut stats = Stats::default();
    let mut rays = 0u64;
    let n = 300;
    for j in 0..n {
        for i in 0..n {
            let x = r * (2.0 * (i as f32 + 0.5) / n as f32 - 1.0);
            let y = r * (2.0 * (j as f32 + 0.5) / n as f32 - 1.0);
            if x * x + y * y >= r * r {
                continue;
            }
            rays += 1;
            let ray = Ray::new(Vec3::new(x, y, start_z), -Vec3::Z, 0.0);
            let mut rng = SampleStream::new(0, 0, 0);
            tracer.trace(&ray, 0, 1.0, &Media::default(), &mut rng, &mut stats);
        }
    }
    stats.tir_events as f64 / rays as f64
}

#[test]
fn total_internal_reflection_at_an_air_bubble_in_water() {
    // Parallel light meeting a sphere at impact parameter b has sin θi = b/r, so the part of
    // its disk beyond the critical angle asin(n2/n1) is 1 − (n2/n1)².
    let expected = 1.0 - (1.0f64 / 1.33).powi(2);
    let camera = Camera::looking_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y, 30.0);
    let bubble = || {
        (
            sphere(Vec3::new(0.0, 0.0, -2.0), 0.5),
            glass(1.0, Color::ZERO),
        )
    };

    // The whole scene is water: the ray starts in the surrounding medium of index 1.33.
    let in_water = scene(vec![bubble()], camera.clone(), Color::ONE, 1.33);
    let f = tir_fraction(&in_water, 0.5, 0.0);
    assert!(
        (f - expected).abs() < 2e-3,
        "camera in water: {f} vs {expected}"
    );

    // A tank of water around the bubble, the ray from the air: entering the tank (at normal
    // incidence, no bending) pushes water onto the ray's media, so the bubble is met from
    // water, not air. max_depth 1: the tank face is level 0, the bubble level 1.
    let tank = Mesh::cuboid(Vec3::new(-3.0, -3.0, -4.0), Vec3::new(3.0, 3.0, -1.0)).unwrap();
    let in_tank = scene(
        vec![(Shape::Mesh(tank), glass(1.33, Color::ZERO)), bubble()],
        camera.clone(),
        Color::ONE,
        1.0,
    );
    let f = tir_fraction(&in_tank, 0.5, 0.0);
    assert!(
        (f - expected).abs() < 2e-3,
        "bubble in a tank: {f} vs {expected}"
    );

    // Glass in water: entering the denser glass never reflects totally.
    let glass_in_water = scene(
        vec![(
            sphere(Vec3::new(0.0, 0.0, -2.0), 0.5),
            glass(1.5, Color::ZERO),
        )],
        camera,
        Color::ONE,
        1.33,
    );
    assert_eq!(tir_fraction(&glass_in_water, 0.5, 0.0), 0.0);
}
