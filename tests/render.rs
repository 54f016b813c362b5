//! Rendering: determinism, and images checked against closed forms.
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

mod common;

use common::{bits, in_pool};
use raylab::camera::Camera;
use raylab::geometry::{Plane, Shape};
use raylab::light::{Background, Light};
use raylab::material::{Diffuse, Emissive, Material, Mirror, Texture};
use raylab::math::{Color, Vec3};
use raylab::params::{Params, Transport};
use raylab::render::{Crop, Film, render, render_crop_pass, render_pass};
use raylab::scene::{Scene, SceneDesc};
use std::f32::consts::PI;
use std::path::Path;

#[test]
fn same_image_for_any_thread_count() {
    let scene = Scene::load("bunny").unwrap();
    let params = Params {
        spp: 3,
        ..scene.params.clone()
    };
    let one = in_pool(1, || render(&scene, &params, 97, 61, &()).unwrap().0);
    let two = in_pool(2, || render(&scene, &params, 97, 61, &()).unwrap().0);
    let five = in_pool(5, || render(&scene, &params, 97, 61, &()).unwrap().0);
    assert_eq!(bits(&one), bits(&two));
    assert_eq!(bits(&one), bits(&five));
    // Paths and photons too (the photons are shot in parallel, collected in order).
    let scene = Scene::load("default").unwrap();
    for transport in [Transport::Path, Transport::Photons] {
        let params = Params {
            spp: 2,
            transport,
            ..scene.params.clone()
        };
        let one = in_pool(1, || render(&scene, &params, 64, 36, &()).unwrap().0);
        let three = in_pool(3, || render(&scene, &params, 64, 36, &()).unwrap().0);
        assert_eq!(bits(&one), bits(&three), "{transport:?}");
    }
}

#[test]
fn same_image_for_any_split_into_passes() {
    for transport in [Transport::Whitted, Transport::Photons] {
        same_image_for_any_split_into_passes_in(transport);
    }
}

fn same_image_for_any_split_into_passes_in(transport: Transport) {
    let scene = Scene::load("default").unwrap();
    let params = Params {
        spp: 8,
        transport,
        ..scene.params.clone()
    };
    let (whole, stats_whole) = render(&scene, &params, 80, 45, &()).unwrap();
    let mut film = Film::new(80, 45);
    let mut stats = raylab::tracer::Stats::default();
    for _ in 0..8 {
        stats += render_pass(&scene, &scene.camera, &params, &mut film, 1, &()).unwrap();
    }
    assert_eq!(film.spp(), 8);
    assert_eq!(bits(&whole), bits(&film));
    assert_eq!(stats_whole, stats);
    // 3 + 5 as well.
    let mut split = Film::new(80, 45);
    render_pass(&scene, &scene.camera, &params, &mut split, 3, &()).unwrap();
    render_pass(&scene, &scene.camera, &params, &mut split, 5, &()).unwrap();
    assert_eq!(bits(&whole), bits(&split));
    // And a different seed gives a different image.
    let other = render(&scene, &Params { seed: 1, ..params }, 80, 45, &())
        .unwrap()
        .0;
    assert_ne!(bits(&whole), bits(&other));
}

#[test]
fn a_crop_holds_the_whole_images_pixels_bit_for_bit() {
    // Lens and wavelength samples, paths with photons: every draw of a sample is the
    // whole image's (the same pixel, the same sample number).
    let cases = [
        ("depth-of-field", Transport::Whitted),
        ("dispersion", Transport::Whitted),
        ("default", Transport::Photons),
    ];
    let (w, h) = (40, 30);
    let (x0, y0, x1, y1) = (7u32, 5u32, 29u32, 21u32);
    for (name, transport) in cases {
        let scene = Scene::load(name).unwrap();
        let params = Params {
            spp: 3,
            transport,
            ..scene.params.clone()
        };
        let whole = render(&scene, &params, w, h, &()).unwrap().0;
        let mut crop = Film::new(x1 - x0, y1 - y0);
        let at = Crop {
            size: (w, h),
            origin: (x0, y0),
        };
        render_crop_pass(&scene, &scene.camera, &params, &mut crop, at, 3, &()).unwrap();
        let whole_bits = bits(&whole);
        let expected: Vec<[u32; 3]> = (y0..y1)
            .flat_map(|y| (x0..x1).map(move |x| (x, y)))
            .map(|(x, y)| whole_bits[(y * w + x) as usize])
            .collect();
        assert_eq!(bits(&crop), expected, "{name}");
    }
}

fn grey(albedo: f32) -> Material {
    Material::Diffuse(Diffuse::solid(Color::splat(albedo)))
}

/// A camera at height `height` looking straight down at the plane y = 0.
fn top_down(
    material: Material,
    lights: Vec<Light>,
    height: f32,
    fov: f32,
    background: Color,
) -> Scene {
    let mut desc = SceneDesc::empty(Camera::looking_at(
        Vec3::new(0.0, height, 0.0),
        Vec3::ZERO,
        Vec3::Z,
        fov,
    ));
    desc.add(
        "floor",
        Shape::Plane(Plane::new(Vec3::ZERO, Vec3::Y)),
        material,
    );
    desc.lights = lights;
    desc.background = Background::Constant(background);
    desc.build()
}

#[test]
fn diffuse_floor_under_a_point_light_matches_the_closed_form() {
    floor_under_a_point_light(0.6, 0.0, Transport::Whitted);
}

#[test]
fn a_glowing_floor_adds_its_emission_to_the_closed_form_in_every_transport() {
    // A glowing diffuse surface (glTF's emission over its base colour) is lit as any
    // diffuse one, its glow added: L = Le + (a/π) I cos θ / d². Path tracing's bounce off
    // the floor meets the black sky, so its sum is the same one.
    for transport in [Transport::Whitted, Transport::Path] {
        floor_under_a_point_light(0.6, 0.25, transport);
    }
}

/// A floor of albedo `albedo` glowing with radiance `glow` under a point light, seen from
/// above at 64 samples a pixel in `transport`, against the closed form
/// L(r) = Le + (a/π) I cos θ / d² = Le + (a/π) I h / (h² + r²)^{3/2} for a light at height h.
fn floor_under_a_point_light(albedo: f32, glow: f32, transport: Transport) {
    let (intensity, h) = (5.0f32, 1.0f32);
    let material = Material::Diffuse(Diffuse {
        emission: (glow > 0.0).then_some(Texture::Solid(Color::splat(glow))),
        ..Diffuse::solid(Color::splat(albedo))
    });
    let scene = top_down(
        material,
        vec![Light::point(
            Vec3::new(0.0, h, 0.0),
            Color::splat(intensity),
        )],
        2.0,
        60.0,
        Color::ZERO,
    );
    let spp = 64;
    let params = Params {
        spp,
        transport,
        ..Params::default()
    };
    let (n, side) = (24u32, 2.0 * 2.0 * (30f32).to_radians().tan());
    let (film, _) = render(&scene, &params, n, n, &()).unwrap();
    let radiance =
        |x: f32, z: f32| glow + albedo / PI * intensity * h / (h * h + x * x + z * z).powf(1.5);
    for py in 0..n {
        for px in 0..n {
            // The pixel's footprint on the floor: its mean and spread from a 16×16 grid.
            let (mut mean, mut sq) = (0.0f64, 0.0f64);
            for j in 0..16 {
                for i in 0..16 {
                    let u = (px as f32 + (i as f32 + 0.5) / 16.0) / n as f32;
                    let v = (py as f32 + (j as f32 + 0.5) / 16.0) / n as f32;
                    // Image right is world -x (looking down with +z up), image down is -z.
                    let l = radiance(-(u - 0.5) * side, -(v - 0.5) * side) as f64;
                    mean += l / 256.0;
                    sq += l * l / 256.0;
                }
            }
            let sigma = (sq - mean * mean).max(0.0).sqrt();
            // Four standard errors of a 64-sample mean, plus the grid's own error.
            let tolerance = 4.0 * sigma / (spp as f64).sqrt() + 1e-4 * mean;
            let got = film.pixel(px, py).x as f64;
            assert!(
                (got - mean).abs() <= tolerance,
                "{transport:?}, glow {glow}: pixel ({px}, {py}): {got} vs {mean} ± {tolerance}"
            );
        }
    }
}

#[test]
fn a_mirror_reflects_its_reflectance_times_the_background() {
    let k = 0.7f32;
    let sky = Color::new(0.2, 0.5, 1.0);
    let mirror = Material::Mirror(Mirror {
        reflectance: Color::splat(k),
    });
    let scene = top_down(mirror, vec![], 2.0, 40.0, sky);
    let run = |max_depth, min_weight| {
        let params = Params {
            spp: 1,
            max_depth,
            min_weight,
            ..Params::default()
        };
        let (film, s) = render(&scene, &params, 8, 8, &()).unwrap();
        let pixels: Vec<Color> = film.pixels().collect();
        (
            pixels,
            (s.reflection_rays, s.pruned_by_depth, s.pruned_by_weight),
        )
    };
    let (pixels, counts) = run(8, 0.0);
    for c in pixels {
        assert!((c - k * sky).abs().max_element() < 1e-6, "{c:?}");
    }
    assert_eq!(counts, (64, 0, 0));

    // Pruned by depth: no reflected ray at max_depth 0, and the mirror is black.
    let (pixels, counts) = run(0, 0.0);
    assert!(pixels.iter().all(|&c| c == Color::ZERO));
    assert_eq!(counts, (0, 64, 0));

    // Pruned by weight: a branch of weight 0.7 is cut at min_weight 0.8.
    let (pixels, counts) = run(8, 0.8);
    assert!(pixels.iter().all(|&c| c == Color::ZERO));
    assert_eq!(counts, (0, 0, 64));
}

#[test]
fn facing_mirrors_prune_at_the_depth_limit_with_geometric_weights() {
    // Two parallel mirrors: a ray bounces between them until a pruning rule stops it. With
    // reflectance k, the path weight after n bounces is k^n, so weight pruning at ε stops
    // at n = ceil(log ε / log k) bounces and depth pruning at max_depth.
    let k = 0.5f32;
    let text = format!(
        "[camera]\nposition = [0, 0.5, 0]\nlook_at = [0, 0.5, -1]\nfov = 10\n\
         [background]\ncolor = [1, 1, 1]\n\
         [material.m]\ntype = \"mirror\"\nreflectance = [{k}, {k}, {k}]\n\
         [[plane]]\npoint = [0, 0, -1]\nnormal = [0, 0, 1]\nmaterial = \"m\"\n\
         [[plane]]\npoint = [0, 0, 1]\nnormal = [0, 0, -1]\nmaterial = \"m\"\n"
    );
    let scene = Scene::from_toml_str(&text, "mirrors.toml", std::path::Path::new(".")).unwrap();
    let one_pixel = |max_depth, min_weight| {
        let params = Params {
            spp: 1,
            max_depth,
            min_weight,
            ..Params::default()
        };
        render(&scene, &params, 1, 1, &()).unwrap().1
    };
    let s = one_pixel(5, 0.0);
    assert_eq!(
        (s.reflection_rays, s.pruned_by_depth, s.pruned_by_weight),
        (5, 1, 0)
    );
    // 0.5^3 = 0.125 ≥ 0.1 is traced; 0.5^4 = 0.0625 < 0.1 is cut.
    let s = one_pixel(20, 0.1);
    assert_eq!(
        (s.reflection_rays, s.pruned_by_depth, s.pruned_by_weight),
        (3, 0, 1)
    );
}

#[test]
fn non_finite_samples_are_dropped_and_counted_never_written() {
    // An object emitting infinite radiance (only possible from code; files refuse it).
    let glow = Material::Emissive(Emissive::solid(Color::new(f32::INFINITY, 1.0, f32::NAN)));
    let scene = top_down(glow, vec![], 2.0, 40.0, Color::ONE);
    let (film, stats) = render(
        &scene,
        &Params {
            spp: 2,
            ..Params::default()
        },
        4,
        4,
        &(),
    )
    .unwrap();
    assert_eq!(
        stats.non_finite, 32,
        "every sample hits the floor and is dropped"
    );
    assert!(film.pixels().all(|c| c.is_finite()));
    let png = film.to_srgb8(0.0);
    assert!(
        png.pixels().all(|p| p.0 == [0, 0, 0]),
        "a pixel with no valid sample shows black"
    );
}

#[test]
fn the_cost_of_a_pixel_is_the_rays_its_samples_traced() {
    let mirror = top_down(
        Material::Mirror(Mirror {
            reflectance: Color::splat(0.7),
        }),
        vec![],
        2.0,
        40.0,
        Color::ONE,
    );
    let cost = |scene: &Scene, max_depth| {
        let params = Params {
            spp: 3,
            max_depth,
            ..Params::default()
        };
        render(scene, &params, 6, 6, &()).unwrap().0.cost()
    };
    assert!(
        cost(&mirror, 8).iter().all(|&c| c == 2.0),
        "camera + reflection"
    );
    assert!(
        cost(&mirror, 0).iter().all(|&c| c == 1.0),
        "the reflection pruned"
    );
    let lit = top_down(
        grey(0.5),
        vec![Light::point(Vec3::new(0.0, 1.0, 0.0), Color::ONE)],
        2.0,
        40.0,
        Color::ZERO,
    );
    assert!(
        cost(&lit, 8).iter().all(|&c| c == 2.0),
        "camera + shadow ray"
    );
}

/// The pixels, at 4 spp, of an image of `size` that sees one emitting quad (its lower left
/// corner and its width and height, in the plane z = 0) from 5 units in front with a
/// field of view of `fov` degrees; `board` is the emitter's material, in scene-file lines.
fn board_pixels(size: (u32, u32), fov: f32, board: &str, quad: ([f32; 2], [f32; 2])) -> Vec<Color> {
    let ([x, y], [w, h]) = quad;
    let text = format!(
        "[image]\nwidth = {}\nheight = {}\n\
         [camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov = {fov}\n\
         [material.board]\ntype = \"emissive\"\n{board}\n\
         [[quad]]\ncorner = [{x}, {y}, 0]\nedge_u = [{w}, 0, 0]\nedge_v = [0, {h}, 0]\n\
         material = \"board\"\n",
        size.0, size.1
    );
    let scene = Scene::from_toml_str(&text, "board.toml", Path::new(".")).unwrap();
    let params = Params {
        spp: 4,
        ..scene.params.clone()
    };
    let (film, _) = render(&scene, &params, size.0, size.1, &()).unwrap();
    film.pixels().collect()
}

#[test]
fn a_checker_scaled_apart_along_u_and_v_gives_a_wide_quad_square_cells() {
    // A 4 × 2 emitting quad filling an 8 × 4 image, 4 cells along u and 2 along v: each
    // cell 1 × 1 in the world, 2 × 2 pixels, alternating along both rows and columns.
    let px = board_pixels(
        (8, 4),
        22.619865,
        "color = [1, 1, 1]\nchecker = { color = [0, 0, 0], scale = [4, 2] }",
        ([-2.0, -1.0], [4.0, 2.0]),
    );
    // The centre of each 2 × 2 block of pixels: white where floor(u 4) + floor(v 2) is
    // even (the image's top row is the quad's upper half, v cell 1).
    for v_cell in 0..2usize {
        for u_cell in 0..4usize {
            let y = 2 * (1 - v_cell) + 1;
            let c = px[y * 8 + u_cell * 2 + 1];
            let white = (u_cell + v_cell) % 2 == 0;
            let want = if white { Color::ONE } else { Color::ZERO };
            assert_eq!(c, want, "cell ({u_cell}, {v_cell})");
        }
    }
}

#[test]
fn a_textured_emitter_shows_its_checker_squares_at_their_radiance() {
    // One emitting quad filling the view, 2 × 2 squares: seen directly, each pixel is the
    // radiance of its square (× strength), exactly.
    let px = board_pixels(
        (8, 8),
        20.0,
        "color = [1, 0.5, 0.25]\nchecker = { color = [0, 2, 0], scale = 2 }\nstrength = 2",
        ([-2.0, -2.0], [4.0, 4.0]),
    );
    let (a, b) = (Color::new(2.0, 1.0, 0.5), Color::new(0.0, 4.0, 0.0));
    // The view spans the quad's middle: the four corners of the image lie in four squares.
    let corners = [px[0], px[7], px[56], px[63]];
    assert!(corners.iter().all(|&c| c == a || c == b), "{corners:?}");
    assert_eq!(corners.iter().filter(|&&c| c == a).count(), 2);
    assert_eq!(corners[0], corners[3], "diagonal squares alike");
    assert_ne!(corners[0], corners[1], "neighbours differ");
}
