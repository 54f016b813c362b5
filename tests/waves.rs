//! The ray tree walked in waves, with the hit search in SIMD lanes, against the recursive
//! walk it stands in for: every width gives the same image bit for bit; the waves give the
//! recursion's image bit for bit where a sample's random numbers are drawn in the same
//! order (every built-in scene and slide), and the same image within noise where they are
//! not.
#![allow(clippy::unwrap_used)]

use raylab::lecture::{LECTURE, slide_setup};
use raylab::math::Color;
use raylab::math::lanes::Width;
use raylab::params::{Params, Transport, TreeMode};
use raylab::render::{Film, render_pass_by, render_preview};
use raylab::scene::{BUILTIN_SCENES, Scene};
use raylab::tracer::{Stats, Tracer, Traversal, pick};
use std::path::Path;
use std::sync::Arc;

const SIZE: (u32, u32) = (40, 30);

fn render(scene: &Scene, params: &Params, traversal: Traversal) -> (Film, Stats) {
    let mut film = Film::new(SIZE.0, SIZE.1);
    let stats = render_pass_by(
        traversal,
        scene,
        &scene.camera,
        params,
        &mut film,
        params.spp,
        &(),
    )
    .unwrap();
    (film, stats)
}

fn bits(film: &Film) -> Vec<[u32; 3]> {
    film.pixels()
        .map(|p| p.to_array().map(f32::to_bits))
        .collect()
}

/// Each built-in scene and each side of each slide, at 4 samples a pixel.
fn cases() -> Vec<(String, Arc<Scene>, Params)> {
    let mut out = Vec::new();
    for b in BUILTIN_SCENES {
        let scene = Arc::new(Scene::load(b.name).unwrap());
        let params = Params {
            spp: 4,
            ..scene.params.clone()
        };
        out.push((b.name.to_string(), scene, params));
    }
    for n in 1..=LECTURE.len() {
        let setup = slide_setup(n).unwrap();
        let scene = Arc::new(setup.scene);
        let mut sides = vec![setup.params.clone()];
        sides.extend(setup.slide.others(&setup.params));
        for (k, p) in sides.into_iter().enumerate() {
            let params = Params { spp: 4, ..p };
            out.push((format!("slide {n}, side {k}"), Arc::clone(&scene), params));
        }
    }
    out
}

/// Every width there is here, the scalar one first.
fn widths() -> Vec<Width> {
    Width::ALL.into_iter().filter(|w| w.runs_here()).collect()
}

#[test]
fn every_width_and_the_recursion_give_every_scene_and_slide_bit_for_bit() {
    let mut dispersive = 0;
    for (name, scene, params) in cases() {
        let (reference, reference_stats) = render(&scene, &params, Traversal::Recursive);
        for w in widths() {
            let (film, stats) = render(&scene, &params, Traversal::Waves(w));
            assert_eq!(bits(&film), bits(&reference), "{name}: {w:?} lanes");
            assert_eq!(film.cost(), reference.cost(), "{name}: rays per pixel");
            assert_eq!(stats, reference_stats, "{name}: {w:?} lanes");
        }
        // Only paths, photons and the polariser take the recursion.
        let in_waves = Tracer::new(&scene, &params, SIZE.0, SIZE.1).traces_waves();
        let tree = !params.transport.traces_paths() && params.polarizer.is_none();
        assert_eq!(in_waves, tree, "{name}");
        dispersive += scene.materials.iter().any(|m| m.needs_wavelength()) as u32;
    }
    // Dispersion's scene and slide, where the waves split into wavelengths, among them.
    assert!(dispersive >= 2, "{dispersive} dispersive cases");
}

#[test]
fn the_preview_is_the_recursions_first_sample_at_each_blocks_centre() {
    for name in ["default", "glass", "depth-of-field"] {
        let scene = Scene::load(name).unwrap();
        let params = scene.params.clone();
        let (w, h, block) = (50, 30, 4);
        let (grid, _) = render_preview(&scene, &scene.camera, &params, w, h, block, &()).unwrap();
        let tracer = Tracer::new(&scene, &params, w, h);
        let centre = |i: u32, size: u32| (i * block + block / 2).min(size - 1);
        for (k, c) in grid.iter().enumerate() {
            let (i, j) = (k as u32 % w.div_ceil(block), k as u32 / w.div_ceil(block));
            let expected = tracer.sample(centre(i, w), centre(j, h), 0, &mut Stats::default());
            assert_eq!(
                c.to_array(),
                expected.to_array(),
                "{name}: block ({i}, {j})"
            );
        }
    }
}

/// A pane of glass before a wall, under an area light, with a mirror behind the camera:
/// a hit's reflected ray comes back by the mirror and draws its light samples two levels
/// down, after the refracted ray has drawn its own one level down. The waves draw level by
/// level and the recursion depth first, so their numbers differ here.
const PANE: &str = r#"
description = "glass pane, mirror behind the camera, area light"
[image]
width = 40
height = 30
[params]
spp = 16
max_depth = 4
[camera]
position = [0.0, 1.0, 4.0]
look_at = [0.0, 1.0, 0.0]
fov = 50
[material.glass]
type = "dielectric"
ior = 1.5
[material.wall]
type = "diffuse"
color = [0.8, 0.7, 0.6]
[material.mirror]
type = "mirror"
reflectance = [0.9, 0.9, 0.9]
[[quad]]
corner = [-3.0, -2.0, 0.0]
edge_u = [6.0, 0.0, 0.0]
edge_v = [0.0, 6.0, 0.0]
material = "glass"
[[plane]]
point = [0.0, 0.0, -2.0]
normal = [0.0, 0.0, 1.0]
material = "wall"
[[plane]]
point = [0.0, 0.0, 6.0]
normal = [0.0, 0.0, -1.0]
material = "mirror"
[[rect_light]]
center = [0.0, 3.0, -1.0]
edge_u = [1.0, 0.0, 0.0]
edge_v = [0.0, 0.0, 1.0]
intensity = 30.0
"#;

#[test]
fn where_the_numbers_are_drawn_in_another_order_the_image_is_the_same_within_noise() {
    let scene = Scene::from_toml_str(PANE, "pane.toml", Path::new(".")).unwrap();
    let params = scene.params.clone();
    let (reference, _) = render(&scene, &params, Traversal::Recursive);
    let (waves, _) = render(&scene, &params, Traversal::Waves(Width::best()));
    assert_ne!(
        bits(&waves),
        bits(&reference),
        "the scene must draw out of order"
    );
    // Per pixel, the two estimates' difference has mean 0 if they estimate the same image;
    // its mean over the image is then within a few standard errors of 0 (pixels are
    // independent).
    let luminance = |c: Color| c.dot(Color::new(0.2126, 0.7152, 0.0722)) as f64;
    let d: Vec<f64> = waves
        .pixels()
        .zip(reference.pixels())
        .map(|(a, b)| luminance(a) - luminance(b))
        .collect();
    let n = d.len() as f64;
    let mean = d.iter().sum::<f64>() / n;
    let sd = (d.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    let total = reference.pixels().map(luminance).sum::<f64>() / n;
    assert!(sd > 0.0 && total > 0.0);
    assert!(
        mean.abs() < 4.0 * sd / n.sqrt(),
        "mean difference {mean} against a standard error of {}",
        sd / n.sqrt()
    );
}

/// Asserts that `scene` is traced in waves with `params` and that every width gives the
/// recursion's image and counts bit for bit (`what` names the case); returns them.
fn the_waves_are_the_recursion(scene: &Scene, params: &Params, what: &str) -> (Film, Stats) {
    assert!(
        Tracer::new(scene, params, SIZE.0, SIZE.1).traces_waves(),
        "{what}"
    );
    let (reference, reference_stats) = render(scene, params, Traversal::Recursive);
    for w in widths() {
        let (film, stats) = render(scene, params, Traversal::Waves(w));
        let (a, b) = (bits(&film), bits(&reference));
        let differ = a.iter().zip(&b).filter(|(a, b)| a != b).count();
        assert_eq!(differ, 0, "{what}: {w:?}: pixels that differ");
        assert_eq!(stats, reference_stats, "{what}: {w:?}");
    }
    (reference, reference_stats)
}

/// A crown-glass ball inside a flint one, over a floor under a point light (which draws
/// no numbers, so that the waves draw in the recursion's order): a ray meets
/// the flint, splits into its wavelengths, and each then meets the crown from inside the
/// flint, whose index there is its wavelength's. Lanes that split hits at one index for
/// every ray would refract it there at n_d.
const NESTED_PRISMS: &str = r#"
description = "a crown ball inside a flint one"
[image]
width = 40
height = 30
[params]
spp = 4
max_depth = 6
[camera]
position = [0.0, 1.0, 4.0]
look_at = [0.0, 1.0, 0.0]
fov = 40
[material.flint]
type = "dielectric"
ior = 1.785
abbe = 25.8
[material.crown]
type = "dielectric"
ior = 1.52
[material.floor]
type = "diffuse"
color = [0.8, 0.7, 0.6]
[[sphere]]
center = [0.0, 1.0, 0.0]
radius = 1.0
material = "flint"
[[sphere]]
center = [0.2, 1.1, 0.3]
radius = 0.45
material = "crown"
[[plane]]
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "floor"
[[point_light]]
position = [1.0, 3.0, 2.0]
intensity = 30.0
"#;

#[test]
fn the_waves_split_into_wavelengths_as_the_recursion_does_in_either_tree() {
    let nested = Scene::from_toml_str(NESTED_PRISMS, "nested.toml", Path::new(".")).unwrap();
    let dispersion = Scene::load("dispersion").unwrap();
    for (name, scene) in [("nested", &nested), ("dispersion", &dispersion)] {
        for tree in [TreeMode::Split, TreeMode::Stochastic] {
            let params = Params {
                spp: 4,
                tree,
                ..scene.params.clone()
            };
            the_waves_are_the_recursion(scene, &params, &format!("{name}, {tree:?}"));
        }
    }
}

/// Glowing diffuse surfaces (emission over a base colour, as glTF's emissive materials
/// are): a floor and a ball in the open, seen directly, in a mirror and through glass, and
/// a ball inside absorbing glass (where the waves shade a hit by its full scatter, not
/// their diffuse shortcut), under ambient light and two point lights (which draw no
/// numbers, so that the waves draw in the recursion's order).
const GLOWING: &str = r#"
description = "glowing diffuse surfaces beside, behind and inside glass"
ambient = [0.05, 0.04, 0.03]
[image]
width = 40
height = 30
[params]
spp = 4
max_depth = 6
[camera]
position = [0.0, 1.0, 4.0]
look_at = [0.0, 1.0, 0.0]
fov = 50
[material.tinted]
type = "dielectric"
ior = 1.5
absorption = [0.8, 0.3, 0.1]
[material.glass]
type = "dielectric"
ior = 1.5
[material.mirror]
type = "mirror"
reflectance = [0.9, 0.9, 0.9]
[material.ember]
type = "diffuse"
color = [0.5, 0.2, 0.1]
specular = [0.3, 0.3, 0.3]
exponent = 30
emission = [2.0, 0.8, 0.2]
[material.floor]
type = "diffuse"
color = [0.7, 0.7, 0.7]
emission = [0.02, 0.05, 0.1]
[[sphere]]
center = [-1.2, 1.0, 0.0]
radius = 0.8
material = "tinted"
[[sphere]]
center = [-1.2, 1.0, 0.0]
radius = 0.3
material = "ember"
[[sphere]]
center = [1.0, 0.6, 0.5]
radius = 0.5
material = "glass"
[[sphere]]
center = [1.2, 0.7, -1.0]
radius = 0.6
material = "ember"
[[quad]]
corner = [-3.0, 0.0, -2.5]
edge_u = [6.0, 0.0, 0.0]
edge_v = [0.0, 3.0, 0.0]
material = "mirror"
[[plane]]
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "floor"
[[point_light]]
position = [1.0, 3.0, 2.0]
intensity = 20.0
[[point_light]]
position = [-2.0, 2.5, 1.0]
intensity = 10.0
"#;

#[test]
fn glowing_surfaces_give_the_recursions_image_at_every_width_in_either_tree() {
    let scene = Scene::from_toml_str(GLOWING, "glowing.toml", Path::new(".")).unwrap();
    let plain = Scene::from_toml_str(
        &GLOWING.replace("emission = ", "# emission = "),
        "plain.toml",
        Path::new("."),
    )
    .unwrap();
    for tree in [TreeMode::Split, TreeMode::Stochastic] {
        let params = Params {
            tree,
            ..scene.params.clone()
        };
        let (reference, reference_stats) =
            the_waves_are_the_recursion(&scene, &params, &format!("{tree:?}"));
        // The glow is seen, and it is all that differs from the same surfaces unlit by it:
        // each pixel at least as bright as without, and the image brighter.
        let (dark, dark_stats) = render(&plain, &params, Traversal::Recursive);
        assert_eq!(dark_stats, reference_stats, "{tree:?}: the same rays");
        let (lit, unlit): (Vec<Color>, Vec<Color>) =
            (reference.pixels().collect(), dark.pixels().collect());
        assert!(
            lit.iter().zip(&unlit).all(|(a, b)| a.cmpge(*b).all()),
            "{tree:?}"
        );
        let sum = |p: &[Color]| p.iter().map(|c| c.element_sum()).sum::<f32>();
        assert!(
            sum(&lit) > 1.2 * sum(&unlit),
            "{tree:?}: {} vs {}",
            sum(&lit),
            sum(&unlit)
        );
    }
}

/// One of every material kind (each Fresnel mode of a dielectric, an absorbing and a
/// dispersive one, a glaze of each reflectance, a smooth and a rough conductor, a glossy
/// metal, a mirror, a plain, a specular and a glowing diffuse, a light; and a glass box), in rows over a
/// checkered floor before a mirror, under ambient light, two point lights and an area
/// light (whose points are drawn: `{light}` turns it off where the split tree needs the
/// recursion's order of draws).
const EVERY_KIND: &str = r#"
description = "one of every material kind"
ambient = [0.03, 0.03, 0.03]
[image]
width = 40
height = 30
[params]
spp = 4
max_depth = 5
[camera]
position = [0.0, 3.6, 6.0]
look_at = [0.0, 0.2, 0.0]
fov = 62
[material.exact]
type = "dielectric"
ior = 1.5
[material.schlick]
type = "dielectric"
ior = 1.6
fresnel = "schlick"
[material.naive]
type = "dielectric"
ior = 1.45
fresnel = "schlick_naive"
[material.constant]
type = "dielectric"
ior = 1.33
fresnel = "constant"
constant_reflectance = 0.1
[material.tinted]
type = "dielectric"
ior = 1.5
absorption = [0.9, 0.2, 0.05]
[material.flint]
type = "dielectric"
ior = 1.7
abbe = 30
[material.frosted]
type = "dielectric"
ior = 1.5
roughness = 0.3
[material.frosted_flint]
type = "dielectric"
ior = 1.7
abbe = 30
roughness = 0.15
[material.glaze]
type = "glazed"
color = [0.0, 0.0, 0.0]
[material.glaze_constant]
type = "glazed"
color = [0.2, 0.4, 0.7]
fresnel = "constant"
constant_reflectance = 0.08
[material.gold]
type = "conductor"
metal = "gold"
[material.brushed]
type = "conductor"
metal = "aluminium"
exponent = 300
[material.glossy]
type = "glossy"
reflectance = [0.8, 0.6, 0.5]
exponent = 80
[material.mirror]
type = "mirror"
reflectance = [0.9, 0.9, 0.9]
[material.chalk]
type = "diffuse"
color = [0.7, 0.2, 0.2]
[material.plastic]
type = "diffuse"
color = [0.1, 0.5, 0.2]
specular = [0.4, 0.4, 0.4]
exponent = 40
[material.ember]
type = "diffuse"
color = [0.5, 0.2, 0.1]
emission = [1.5, 0.6, 0.1]
[material.lamp]
type = "emissive"
color = [4.0, 3.5, 3.0]
[material.floor]
type = "diffuse"
color = [0.8, 0.8, 0.8]
checker = { color = [0.2, 0.2, 0.2], scale = 0.5 }
{spheres}
[[box]]
min = [2.7, 0.0, -1.0]
max = [3.5, 1.6, -0.4]
rotate = [0.0, 35.0, 0.0]
material = "exact"
[[quad]]
corner = [-5.0, 0.0, -2.5]
edge_u = [10.0, 0.0, 0.0]
edge_v = [0.0, 3.5, 0.0]
material = "mirror"
[[plane]]
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "floor"
[[point_light]]
position = [1.0, 4.0, 3.0]
intensity = 30.0
[[point_light]]
position = [-3.0, 2.5, 2.0]
intensity = 12.0
{light}
"#;

/// The area light of [`EVERY_KIND`].
const AREA_LIGHT: &str = r#"
[[rect_light]]
center = [0.0, 3.5, 1.0]
edge_u = [1.0, 0.0, 0.0]
edge_v = [0.0, 0.0, 1.0]
intensity = 20.0
"#;

#[test]
fn one_of_every_material_kind_gives_the_recursions_image_at_every_width() {
    let kinds = [
        "exact",
        "schlick",
        "naive",
        "constant",
        "tinted",
        "flint",
        "frosted",
        "frosted_flint",
        "glaze",
        "glaze_constant",
        "gold",
        "brushed",
        "glossy",
        "mirror",
        "chalk",
        "plastic",
        "ember",
        "lamp",
    ];
    // Two rows of spheres, the dielectrics in front.
    let spheres = |kinds: &[&str]| -> String {
        let at = |i: usize| (-3.15 + 0.9 * (i % 8) as f32, 1.2 - 1.6 * (i / 8) as f32);
        kinds
            .iter()
            .enumerate()
            .map(|(i, m)| {
                let (x, z) = at(i);
                format!(
                    "[[sphere]]\ncenter = [{x}, 0.45, {z}]\nradius = 0.42\nmaterial = \"{m}\"\n"
                )
            })
            .collect()
    };
    let scene_with = |light: &str, spheres: &str| {
        let text = EVERY_KIND
            .replace("{spheres}", spheres)
            .replace("{light}", light);
        Scene::from_toml_str(&text, "every_kind.toml", Path::new(".")).unwrap()
    };
    // In the split tree, the kinds that draw numbers at a hit (glossy lobes, rough glass's
    // facets) are there in the stochastic tree only: below a split, the waves draw a
    // level's numbers before the level below, the recursion one branch after another (the
    // same image within noise: `where_the_numbers_are_drawn_in_another_order_...`).
    let still: Vec<&str> = kinds
        .into_iter()
        .filter(|k| !["glossy", "brushed", "frosted", "frosted_flint"].contains(k))
        .collect();
    let lit = scene_with(AREA_LIGHT, &spheres(&kinds));
    let point_lit = scene_with("", &spheres(&still));
    // Every kind is in the picture: each object (the spheres, then the box, the mirror
    // and the floor) is the first hit of some camera ray.
    for (scene, spheres) in [(&lit, kinds.len()), (&point_lit, still.len())] {
        let mut seen = vec![false; spheres + 3];
        for (x, y) in (0..SIZE.0).flat_map(|x| (0..SIZE.1).map(move |y| (x, y))) {
            let film = glam::Vec2::new(
                (x as f32 + 0.5) / SIZE.0 as f32,
                (y as f32 + 0.5) / SIZE.1 as f32,
            );
            let aspect = SIZE.0 as f32 / SIZE.1 as f32;
            if let Some(p) = pick(scene, &scene.camera, aspect, film) {
                seen[p.object as usize] = true;
            }
        }
        let hidden: Vec<_> = (0..seen.len()).filter(|&i| !seen[i]).collect();
        assert!(hidden.is_empty(), "objects out of sight: {hidden:?}");
    }
    let mut all = Stats::default();
    for transport in [Transport::Whitted, Transport::TransmissiveShadows] {
        for (tree, scene) in [(TreeMode::Stochastic, &lit), (TreeMode::Split, &point_lit)] {
            let params = Params {
                tree,
                transport,
                ..scene.params.clone()
            };
            let what = format!("{transport:?}, {tree:?}");
            let (film, stats) = the_waves_are_the_recursion(scene, &params, &what);
            assert!(
                stats.refraction_rays > 0 && stats.shadow_rays > 0,
                "{what}: {stats:?}"
            );
            assert!(film.pixels().all(|p| p.is_finite()), "{what}");
            all += stats;
        }
    }
    // Total internal reflection is met too (inside the box).
    assert!(all.tir_events > 0, "{all:?}");
}
