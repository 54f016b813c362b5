//! Light transports against closed forms: transmissive shadows under a glass slab, and a
//! white furnace in every transport.
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

mod common;

use raylab::camera::Camera;
use raylab::geometry::{Mesh, Plane, Shape};
use raylab::light::{Background, Light};
use raylab::material::{Dielectric, Diffuse, Material};
use raylab::math::{Color, Vec3};
use raylab::optics::fresnel_exact;
use raylab::params::{Params, Pattern, Transport};
use raylab::render::render;
use raylab::scene::SceneDesc;
use std::f64::consts::PI;

#[test]
fn transmissive_shadows_under_a_slab_match_the_closed_form() {
    // A diffuse floor (albedo a) under a point light of intensity I at height h, with a
    // horizontal glass slab (index n, thickness d, absorption σ) in between; the camera
    // looks at the floor from under the slab. A shadow ray to the light crosses the slab
    // straight: the floor's radiance is (a/π) I cos θ / r² · (1 − R)² e^{−σ d / cos θ},
    // R the exact Fresnel reflectance at θ from the air on both faces (a real ray bends
    // and meets the same R going in and out; the straight one takes it so). The
    // lecture's tracer leaves it black. A dispersive slab gives the same: a ray from the
    // camera straight to the floor carries no wavelength, so its shadow ray sees n_d.
    for abbe in [0.0, 30.0] {
        slab_shadow_matches_the_closed_form(abbe);
    }
}

fn slab_shadow_matches_the_closed_form(abbe: f32) {
    let (albedo, intensity, h) = (0.7f32, 9.0f32, 3.0f32);
    let (n, d, sigma) = (1.5f32, 0.4f32, Color::new(0.1, 0.6, 1.5));
    let camera = Camera::looking_at(Vec3::new(0.0, 0.6, 2.5), Vec3::ZERO, Vec3::Y, 40.0);
    let mut desc = SceneDesc::empty(camera);
    desc.add(
        "floor",
        Shape::Plane(Plane::new(Vec3::ZERO, Vec3::Y)),
        Material::Diffuse(Diffuse::solid(Color::splat(albedo))),
    );
    let slab = Mesh::cuboid(Vec3::new(-20.0, 1.5, -20.0), Vec3::new(20.0, 1.5 + d, 20.0)).unwrap();
    desc.add(
        "slab",
        Shape::Mesh(slab),
        Material::Dielectric(Dielectric {
            absorption: sigma,
            abbe,
            ..Dielectric::clear(n)
        }),
    );
    desc.lights = vec![Light::point(
        Vec3::new(0.0, h, 0.0),
        Color::splat(intensity),
    )];
    desc.background = Background::Constant(Color::ZERO);
    let scene = desc.build();
    let (width, height) = (32u32, 24u32);
    // One sample at each pixel's centre, where the closed form is evaluated.
    let with = |transport| Params {
        spp: 1,
        pattern: Pattern::Regular,
        transport,
        ..Params::default()
    };
    let (film, _) = render(
        &scene,
        &with(Transport::TransmissiveShadows),
        width,
        height,
        &(),
    )
    .unwrap();
    let (whitted, _) = render(&scene, &with(Transport::Whitted), width, height, &()).unwrap();
    let frame = scene.camera.pinhole(width as f32 / height as f32);
    let mut checked = 0;
    for y in 0..height {
        for x in 0..width {
            let ray = common::pixel_centre_ray(&frame, (x, y), (width, height));
            if ray.dir.y >= -1e-3 {
                continue; // above the horizon: no floor
            }
            let t = -ray.origin.y / ray.dir.y;
            let p = ray.origin + t * ray.dir;
            let to_light = Vec3::new(0.0, h, 0.0) - p;
            let r2 = to_light.length_squared() as f64;
            let l = to_light.normalize();
            let cos = l.y; // at the floor, and the angle of incidence on the slab
            let (_, _, r) = fresnel_exact(cos, 1.0, n);
            let path = d as f64 / cos as f64;
            let expected = sigma.to_array().map(|s| {
                albedo as f64 / PI * intensity as f64 * cos as f64 / r2
                    * (1.0 - r as f64).powi(2)
                    * (-(s as f64) * path).exp()
            });
            let got = film.pixel(x, y).to_array();
            for c in 0..3 {
                assert!(
                    (got[c] as f64 - expected[c]).abs() < 1e-4 * (1.0 + expected[c]),
                    "pixel ({x}, {y}) channel {c}: {} against {}",
                    got[c],
                    expected[c]
                );
            }
            assert_eq!(
                whitted.pixel(x, y),
                Color::ZERO,
                "the lecture's tracer: black"
            );
            checked += 1;
        }
    }
    assert!(checked > 300, "{checked} floor pixels");
}

#[test]
fn a_white_furnace_stays_uniform_in_every_transport() {
    // A clear sphere in a uniform environment: every split conserves energy, so every
    // pixel sees the environment. There are no lights, hence no shadow rays: what this
    // checks of a transport is that it leaves the camera's ray tree as it is.
    let camera = Camera::looking_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y, 32.0);
    let mut desc = SceneDesc::empty(camera);
    desc.add(
        "sphere",
        Shape::Sphere(raylab::geometry::Sphere::new(Vec3::ZERO, 1.0)),
        Material::Dielectric(Dielectric::clear(1.5)),
    );
    desc.background = Background::Constant(Color::ONE);
    let scene = desc.build();
    for transport in [
        Transport::Whitted,
        Transport::TransmissiveShadows,
        Transport::Path,
        Transport::Photons,
    ] {
        let params = Params {
            spp: 4,
            max_depth: raylab::params::MAX_DEPTH,
            min_weight: 0.0,
            transport,
            ..Params::default()
        };
        let (film, _) = render(&scene, &params, 32, 32, &()).unwrap();
        for (i, c) in film.pixels().enumerate() {
            assert!(
                (c - Color::ONE).abs().max_element() < 1e-3,
                "{transport:?}, pixel {i}: {c}"
            );
        }
    }
}
