//! Path tracing (`transport = "path"`) against closed forms and against the lecture's
//! tracer where the two must agree: light that reaches a surface directly.
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

use raylab::camera::Camera;
use raylab::geometry::{Plane, Quad, Shape, Sphere};
use raylab::light::{Background, Light, LightShape};
use raylab::material::{Diffuse, Emissive, Glossy, Material, Texture};
use raylab::math::{Color, Vec3};
use raylab::params::{Params, Transport};
use raylab::render::{Film, render};
use raylab::scene::{Scene, SceneDesc};

fn path(spp: u32, seed: u64) -> Params {
    Params {
        spp,
        seed,
        transport: Transport::Path,
        ..Params::default()
    }
}

fn rendered(scene: &Scene, params: &Params) -> Film {
    render(scene, params, 32, 24, &()).unwrap().0
}

/// The mean of `a − b` over all pixels and channels, and its standard error: the pixels'
/// noise is independent, so the spread of their differences measures it.
fn mean_difference(a: &Film, b: &Film) -> (f64, f64) {
    let d: Vec<f64> = a
        .pixels()
        .zip(b.pixels())
        .flat_map(|(x, y)| (x - y).to_array())
        .map(f64::from)
        .collect();
    let n = d.len() as f64;
    let mean = d.iter().sum::<f64>() / n;
    let var = d.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

fn image_mean(f: &Film) -> f64 {
    let s: f64 = f
        .pixels()
        .map(|c| c.to_array().iter().sum::<f32>() as f64)
        .sum();
    s / (3 * f.pixels().count()) as f64
}

/// Asserts that two renders of the same light have the same mean within 4 standard
/// errors, and that the test could tell: the error is under 1 % of the image's mean.
fn assert_same_mean(a: &Film, b: &Film, what: &str) {
    let (d, se) = mean_difference(a, b);
    let mean = 0.5 * (image_mean(a) + image_mean(b));
    assert!(
        se < 0.01 * mean,
        "{what}: too noisy to tell ({se} of {mean})"
    );
    assert!(
        d.abs() < 4.0 * se,
        "{what}: means differ by {d} ({:.1} standard errors; image mean {mean})",
        d / se
    );
}

#[test]
fn a_diffuse_sphere_in_a_uniform_environment_renders_albedo_times_l() {
    // Lit by a uniform environment L, a convex Lambertian surface of albedo a reflects
    // a·L: whichever direction the path takes off the sphere, it sees L, weighted
    // f cos θ / p = a. The lecture's tracer cannot (its ambient term stands in for it).
    let (a, l) = (Color::new(0.8, 0.5, 0.2), Color::new(1.0, 2.0, 0.5));
    let camera = Camera::looking_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y, 32.0);
    let mut desc = SceneDesc::empty(camera);
    desc.add(
        "sphere",
        Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0)),
        Material::Diffuse(Diffuse::solid(a)),
    );
    desc.background = Background::Constant(l);
    let scene = desc.build();
    let film = rendered(&scene, &path(8, 1));
    let frame = scene.camera.pinhole(32.0 / 24.0);
    let mut on_sphere = 0;
    for y in 0..24 {
        for x in 0..32 {
            let film_xy = glam::Vec2::new((x as f32 + 0.5) / 32.0, (y as f32 + 0.5) / 24.0);
            let ray = frame.ray(film_xy, glam::Vec2::ZERO, 0.0);
            // Pixels wholly on or off the sphere: the distance of the centre ray from
            // the sphere's centre, with a pixel's margin.
            let miss = ray.origin.cross(ray.dir).length();
            let expected = if miss < 0.9 {
                on_sphere += 1;
                a * l
            } else if miss > 1.1 {
                l
            } else {
                continue;
            };
            let got = film.pixel(x, y);
            assert!(
                (got - expected).abs().max_element() < 1e-4,
                "pixel ({x}, {y}): {got} against {expected}"
            );
        }
    }
    assert!(on_sphere > 100, "{on_sphere} pixels on the sphere");
}

/// A floor seen from above, under `lights` and `emitters` (quads), nothing else: only
/// direct light, which every transport must get right.
fn floor_scene(floor: Material, lights: Vec<Light>, emitters: &[(Quad, Color)]) -> Scene {
    // Below the lights: it sees the floor, not the lights' backs (which only an emitting
    // surface, lit on both sides, would show).
    let camera = Camera::looking_at(Vec3::new(0.0, 1.2, 3.5), Vec3::ZERO, Vec3::Y, 50.0);
    let mut desc = SceneDesc::empty(camera);
    desc.add(
        "floor",
        Shape::Plane(Plane::new(Vec3::ZERO, Vec3::Y)),
        floor,
    );
    for (i, (quad, radiance)) in emitters.iter().enumerate() {
        desc.add(
            format!("emitter {i}"),
            Shape::Quad(quad.clone()),
            Material::Emissive(Emissive::solid(*radiance)),
        );
    }
    desc.lights = lights;
    desc.background = Background::Constant(Color::ZERO);
    desc.build()
}

/// A rectangle light of `size`² centred `height` above the floor at `x`, facing down.
fn rect_light(x: f32, height: f32, size: f32, intensity: f32) -> Light {
    Light {
        shape: LightShape::Rect {
            center: Vec3::new(x, height, 0.0),
            edge_u: Vec3::X * size,
            edge_v: Vec3::Z * size,
        },
        intensity: Color::splat(intensity),
        scale: 1.0,
    }
}

#[test]
fn direct_light_matches_the_lecture_tracer_on_smooth_and_glossy_floors() {
    // With one surface and no sky, every path is one bounce: the lecture's tracer (light
    // samples on a diffuse floor, jittered reflected rays on a glossy one) and path
    // tracing (both, weighed by multiple importance) estimate the same integral. A broken
    // weight shows as a difference in the mean.
    let lights = || {
        vec![
            rect_light(-1.0, 2.0, 1.0, 6.0),
            Light {
                shape: LightShape::Sphere {
                    center: Vec3::new(1.2, 1.5, -0.5),
                    radius: 0.3,
                },
                intensity: Color::new(2.0, 3.0, 4.0),
                scale: 1.0,
            },
            Light::point(Vec3::new(0.0, 2.5, 1.0), Color::splat(3.0)),
        ]
    };
    let phong = Material::Diffuse(Diffuse {
        albedo: Texture::Solid(Color::new(0.6, 0.5, 0.4)),
        specular: Color::splat(0.3),
        exponent: 30.0,
        emission: None,
    });
    let glossy = Material::Glossy(Glossy {
        reflectance: Color::new(0.9, 0.7, 0.5),
        exponent: 40.0,
    });
    for (name, floor) in [("Phong", phong), ("glossy", glossy)] {
        // The glossy floor sees the point light in neither tracer: no ray can hit it.
        let scene = floor_scene(floor, lights(), &[]);
        let whitted = Params {
            spp: 512,
            seed: 2,
            ..Params::default()
        };
        let a = rendered(&scene, &whitted);
        let b = rendered(&scene, &path(512, 3));
        assert_same_mean(&a, &b, name);
    }
}

#[test]
fn an_emitting_quad_lights_like_the_rectangle_light_it_replaces() {
    // The same rectangle as a light and as an emitting surface of radiance I / A: path
    // tracing samples both (the light, and the scene's emitters) and must see the same.
    let (size, intensity) = (1.2f32, 5.0f32);
    let quad = Quad::new(
        Vec3::new(-0.5 - size / 2.0, 2.0, -size / 2.0),
        Vec3::X * size,
        Vec3::Z * size,
    );
    let floor = || Material::Diffuse(Diffuse::solid(Color::splat(0.7)));
    let as_light = floor_scene(floor(), vec![rect_light(-0.5, 2.0, size, intensity)], &[]);
    let radiance = Color::splat(intensity / (size * size));
    let as_surface = floor_scene(floor(), vec![], &[(quad, radiance)]);
    let a = rendered(&as_light, &path(256, 4));
    let b = rendered(&as_surface, &path(256, 5));
    assert_same_mean(&a, &b, "emitting quad");
}

#[test]
fn the_inspector_shows_a_path_as_a_chain_of_vertices() {
    // In path mode a sample is one path: each ray has at most one reflected or refracted
    // child, light samples hang off the diffuse vertices, and the radiance recorded on
    // the camera ray is the sample's.
    let scene = Scene::load("default").unwrap();
    let params = Params {
        transport: Transport::Path,
        ..scene.params.clone()
    };
    let tracer = raylab::tracer::Tracer::new(&scene, &params, 96, 54);
    let (mut longest, mut entered) = (0, 0);
    for sample in 0..16 {
        // A pixel on the glass sphere, whose paths pass through it to the floor.
        let (tree, c) = tracer.inspect(73, 30, sample);
        let root = &tree.nodes[0];
        assert_eq!(root.kind, raylab::tracer::RayKind::Camera);
        assert!(
            (root.radiance - c).abs().max_element() <= 1e-4 * (1.0 + c.max_element()),
            "sample {sample}: {} recorded, {c} traced",
            root.radiance
        );
        let mut chain = 0;
        for (i, _) in tree.nodes.iter().enumerate() {
            let bounces = tree
                .children(i)
                .filter(|(_, n)| n.kind != raylab::tracer::RayKind::Shadow)
                .count();
            assert!(bounces <= 1, "sample {sample}: node {i} branches");
            chain += bounces;
        }
        longest = longest.max(chain);
        if tree
            .nodes
            .iter()
            .any(|n| n.kind == raylab::tracer::RayKind::Refract)
        {
            entered += 1;
        }
    }
    // The glass reflects a few per cent: most paths enter it.
    assert!(entered >= 12, "{entered} of 16 paths enter the glass");
    assert!(
        longest >= 3,
        "paths through the sphere have several vertices"
    );
}

const ROOM: f32 = 4.0;
const ALBEDO: f32 = 0.5;
const INTENSITY: f32 = 10.0;
const LIGHT_RADIUS: f32 = 0.3;

/// The power arriving on the inside of a closed spherical room of radius [`ROOM`] and
/// albedo [`ALBEDO`], lit by a sphere light of radius `light_radius` (0: a point light) at
/// its centre, with `glass` (a clear sphere) inside or not, by `transport`: ∮ E dA, measured by rays that start a hair
/// inside the wall and look at it (L = a/π E), at a stratified grid of points. Returned
/// per batch of samples (independent estimates), and the bottom cap's share
/// (y < −0.99 R, under the glass) of the last batch.
fn room_power(
    glass: Option<(Vec3, f32)>,
    transport: Transport,
    light_radius: f32,
    batches: u32,
) -> (Vec<f64>, f64) {
    let (room, albedo, intensity) = (ROOM, ALBEDO, INTENSITY);
    let mut desc = SceneDesc::empty(Camera::looking_at(Vec3::ZERO, Vec3::NEG_Y, Vec3::Z, 40.0));
    desc.add(
        "room",
        Shape::Sphere(Sphere::new(Vec3::ZERO, room)),
        Material::Diffuse(Diffuse::solid(Color::splat(albedo))),
    );
    if let Some((center, radius)) = glass {
        desc.add(
            "glass",
            Shape::Sphere(Sphere::new(center, radius)),
            Material::Dielectric(raylab::material::Dielectric::clear(1.5)),
        );
    }
    desc.lights = vec![Light {
        shape: LightShape::Sphere {
            center: Vec3::ZERO,
            radius: light_radius,
        },
        intensity: Color::splat(intensity),
        scale: 1.0,
    }];
    desc.background = Background::Constant(Color::ZERO);
    let scene = desc.build();
    let params = Params {
        transport,
        max_depth: raylab::params::MAX_DEPTH,
        ..Params::default()
    };
    let mut tracer = raylab::tracer::Tracer::new(&scene, &params, 1, 1);
    let (nz, nphi) = (96u32, 192u32);
    let area = 4.0 * std::f64::consts::PI * (room as f64).powi(2);
    let mut powers = Vec::new();
    let mut cap_share = 0.0;
    for batch in 0..batches {
        // Each batch a pass of its own (with its own photons, where there are some).
        tracer.prepare_photons(batch);
        let (mut sum, mut cap) = (0.0f64, 0.0f64);
        for i in 0..nz * nphi {
            let mut rng = raylab::math::SampleStream::new(7, i, batch);
            // A point in stratum i, uniform in area: z uniform (Archimedes), φ uniform.
            let u = rng.next_2d();
            let z = 1.0 - 2.0 * ((i / nphi) as f32 + u.x) / nz as f32;
            let phi = 2.0 * std::f32::consts::PI * ((i % nphi) as f32 + u.y) / nphi as f32;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let out = Vec3::new(r * phi.cos(), z, r * phi.sin());
            let ray = raylab::math::Ray::new(out * (room - 1e-3), out, 0.0);
            let l = tracer.radiance(&ray, &mut rng, &mut Default::default());
            let e =
                (l.x as f64 + l.y as f64 + l.z as f64) / 3.0 * std::f64::consts::PI / albedo as f64;
            sum += e;
            if z < -0.99 {
                cap += e;
            }
        }
        let n = (nz * nphi) as f64;
        powers.push(sum / n * area);
        cap_share = cap / sum;
    }
    (powers, cap_share)
}

#[test]
fn a_closed_room_receives_all_the_light_with_or_without_a_glass_sphere() {
    // Energy conservation through caustics. Every watt the light emits, Φ = 4π I, reaches
    // the walls; they reflect a fraction a of it, which arrives again, less what falls
    // back on the light (lights absorb what meets them): from anywhere on the wall of a
    // room of radius R the light of radius ρ at its centre covers a fraction h = (ρ/R)²
    // of the cosine-weighted hemisphere. So ∮ E dA = Φ / (1 − a (1 − h)). A clear glass
    // sphere between the light and the floor reflects and refracts but absorbs nothing:
    // what it takes from the floor below (its shadow, less the caustic it focuses there)
    // it sends elsewhere, and the sum holds (to about 0.05 %: the little the glass turns
    // back onto the light, or towards it from the walls). Paths find the light through
    // the glass by themselves: a lost or doubled caustic shows.
    let phi = 4.0 * std::f64::consts::PI * INTENSITY as f64;
    let h = (LIGHT_RADIUS as f64 / ROOM as f64).powi(2);
    let expected = phi / (1.0 - ALBEDO as f64 * (1.0 - h));
    let mut caps = Vec::new();
    let batches = 40;
    for glass in [None, Some((Vec3::new(0.0, -2.0, 0.0), 1.0f32))] {
        let (powers, cap) = room_power(glass, Transport::Path, LIGHT_RADIUS, batches);
        let mean = powers.iter().sum::<f64>() / batches as f64;
        let var = powers.iter().map(|p| (p - mean).powi(2)).sum::<f64>() / (batches - 1) as f64;
        let se = (var / batches as f64).sqrt();
        assert!(se < 0.005 * expected, "{glass:?}: too noisy to tell ({se})");
        assert!(
            (mean - expected).abs() < 4.0 * se,
            "{glass:?}: {mean} against Φ/(1 − a(1 − h)) = {expected} ({:.1} standard errors)",
            (mean - expected) / se
        );
        caps.push(cap);
    }
    // The sphere does redistribute the light: its caustic brightens the floor below it
    // (4.6 times, with the seeds here).
    assert!(
        caps[1] > 2.0 * caps[0],
        "floor cap's share: {} without the sphere, {} with",
        caps[0],
        caps[1]
    );
}

#[test]
fn photons_carry_a_point_lights_caustic_and_conserve_its_energy() {
    // The closed room again, lit by a point light, which no path can find through the
    // glass: path tracing alone loses the light the glass passes on to the walls; with
    // photons it arrives, and ∮ E dA = Φ / (1 − a) (a point light absorbs nothing), up to
    // the photon map's blur, which moves light but keeps it.
    let phi = 4.0 * std::f64::consts::PI * INTENSITY as f64;
    let expected = phi / (1.0 - ALBEDO as f64);
    let glass = Some((Vec3::new(0.0, -2.0, 0.0), 1.0f32));
    let batches = 40;
    let mean_and_error = |transport| {
        let (powers, cap) = room_power(glass, transport, 0.0, batches);
        let mean = powers.iter().sum::<f64>() / batches as f64;
        let var = powers.iter().map(|p| (p - mean).powi(2)).sum::<f64>() / (batches - 1) as f64;
        (mean, (var / batches as f64).sqrt(), cap)
    };
    let (with_photons, se, cap) = mean_and_error(Transport::Photons);
    assert!(se < 0.005 * expected, "too noisy to tell ({se})");
    assert!(
        (with_photons - expected).abs() < 4.0 * se,
        "photons: {with_photons} against Φ/(1 − a) = {expected} ({:.1} standard errors)",
        (with_photons - expected) / se
    );
    let (path_only, se_path, cap_path) = mean_and_error(Transport::Path);
    assert!(
        path_only < expected - 10.0 * se_path.max(se),
        "path tracing alone misses the caustic: {path_only} against {expected}"
    );
    assert!(
        cap > 2.0 * cap_path,
        "the caustic under the glass: {cap} against {cap_path}"
    );
}

/// A floor lit by an emitting ball and quad, seen directly and through a glass ball, under
/// a point light; the emitters' material is `emitter`.
fn emitters_scene(emitter: &str) -> Scene {
    let text = format!(
        r#"
[camera]
position = [0.0, 1.2, 4.0]
look_at = [0.0, 0.5, 0.0]
fov = 50
[material.floor]
type = "diffuse"
color = [0.7, 0.6, 0.5]
[material.glass]
type = "dielectric"
ior = 1.5
[material.emitter]
{emitter}
[[plane]]
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "floor"
[[sphere]]
center = [0.6, 0.5, 0.8]
radius = 0.5
material = "glass"
[[sphere]]
center = [-0.8, 0.6, 0.0]
radius = 0.4
material = "emitter"
[[quad]]
corner = [0.5, 1.5, -1.0]
edge_u = [1.0, 0.0, 0.0]
edge_v = [0.0, 0.0, 1.0]
material = "emitter"
[[point_light]]
position = [0.0, 3.0, 1.0]
intensity = 5.0
"#
    );
    Scene::from_toml_str(&text, "emitters.toml", std::path::Path::new(".")).unwrap()
}

#[test]
fn a_black_glowing_surface_is_the_light_of_its_emission_in_every_transport() {
    // A glowing diffuse surface of albedo 0 reflects nothing: it must give the image of a
    // light of the same radiance bit for bit, in every transport (its light samples, MIS
    // weights and emission the same; only its shadow rays, which add 0, differ).
    let light = emitters_scene("type = \"emissive\"\ncolor = [3.0, 2.0, 1.0]");
    let glowing =
        emitters_scene("type = \"diffuse\"\ncolor = [0.0, 0.0, 0.0]\nemission = [3.0, 2.0, 1.0]");
    let transports = [
        Transport::Whitted,
        Transport::TransmissiveShadows,
        Transport::Path,
        Transport::Photons,
    ];
    for transport in transports {
        let params = Params {
            spp: 8,
            transport,
            ..Params::default()
        };
        let bits = |f: &Film| -> Vec<[u32; 3]> {
            f.pixels().map(|c| c.to_array().map(f32::to_bits)).collect()
        };
        let (a, b) = (rendered(&light, &params), rendered(&glowing, &params));
        assert_eq!(bits(&a), bits(&b), "{transport:?}");
        assert!(image_mean(&a) > 0.05, "{transport:?}: {}", image_mean(&a));
    }
}
