//! A model placed more than once is read and built once and placed by transforms (a
//! two-level BVH): it renders as copies of it do, and its triangles cost memory once.
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

mod common;

use raylab::geometry::Shape;
use raylab::params::Params;
use raylab::render::render;
use raylab::scene::Scene;
use std::path::Path;

/// The bunny (3,674 triangles) placed at three spots from `files`: turned, scaled, one
/// moving over the frame and one glowing (an emitter sampled triangle by triangle),
/// lit by a point light over a floor.
fn bunnies(files: [&str; 3]) -> String {
    let mut s = String::from(
        "[camera]\nposition = [0, 1.2, 3.6]\nlook_at = [0, 0.4, 0]\nfov = 40\n\
         [material.porcelain]\ntype = \"diffuse\"\ncolor = [0.85, 0.82, 0.75]\n\
         specular = [0.2, 0.2, 0.2]\nexponent = 40\n\
         [material.glow]\ntype = \"emissive\"\ncolor = [1.0, 0.6, 0.3]\nstrength = 2\n\
         [[plane]]\npoint = [0, 0, 0]\nnormal = [0, 1, 0]\n\
         [[point_light]]\nposition = [2, 4, 3]\nintensity = 40\n",
    );
    let spots = [
        (-0.9, 20.0, "porcelain", ""),
        (0.0, -40.0, "porcelain", "velocity = [0, 0.15, 0]\n"),
        (0.9, 100.0, "glow", ""),
    ];
    for (file, (x, turn, material, extra)) in files.iter().zip(spots) {
        s += &format!(
            "[[mesh]]\nfile = \"{file}\"\nmaterial = \"{material}\"\nscale = 0.09\n\
             rotate = [0, {turn}, 0]\ntranslate = [{x}, 0, 0.3]\n{extra}"
        );
    }
    s
}

fn kinds(scene: &Scene) -> (usize, usize) {
    let count = |f: fn(&Shape) -> bool| scene.shapes.iter().filter(|s| f(s)).count();
    (
        count(|s| matches!(s, Shape::Instance(_))),
        count(|s| matches!(s, Shape::Mesh(_))),
    )
}

#[test]
fn a_model_placed_three_times_renders_as_three_copies_of_it_do() {
    let d = tempfile::tempdir().unwrap();
    let bunny = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/models/bunny.obj");
    for name in ["bunny.obj", "bunny2.obj", "bunny3.obj"] {
        std::fs::copy(&bunny, d.path().join(name)).unwrap();
    }
    let load = |files| Scene::from_toml_str(&bunnies(files), "b.toml", d.path()).unwrap();
    let placed = load(["bunny.obj"; 3]);
    let copied = load(["bunny.obj", "bunny2.obj", "bunny3.obj"]);
    assert_eq!(
        kinds(&placed),
        (3, 0),
        "one file placed three times: instances"
    );
    assert_eq!(kinds(&copied), (0, 3), "three files placed once: copies");
    // Path tracing: shadows, the glowing bunny found by light samples and by paths.
    let params = Params {
        spp: 4,
        transport: raylab::params::Transport::Path,
        ..placed.params.clone()
    };
    let (w, h) = (160, 120);
    let a = render(&placed, &params, w, h, &()).unwrap().0;
    let b = render(&copied, &params, w, h, &()).unwrap().0;
    // The same samples, so the same image but where a ray's hit moved by the rounding of
    // a transform (an edge met or missed): a few pixels, none far off on average.
    let (mut differ, mut total) = (0, 0.0f64);
    for (p, q) in a.pixels().zip(b.pixels()) {
        let diff = (p - q).abs().max_element();
        differ += (diff > 1e-3) as usize;
        total += diff as f64;
    }
    let n = (w * h) as usize;
    assert!(differ * 200 < n, "{differ} of {n} pixels differ");
    assert!(
        total / (n as f64) < 1e-3,
        "mean difference {}",
        total / n as f64
    );
    // Not the same image by accident: the glowing bunny lights its neighbours.
    let glow = Scene::from_toml_str(
        &bunnies(["bunny.obj"; 3]).replace("\"glow\"", "\"porcelain\""),
        "b.toml",
        d.path(),
    )
    .unwrap();
    let c = render(&glow, &params, w, h, &()).unwrap().0;
    let changed = a.pixels().zip(c.pixels());
    let changed = changed.filter(|(p, q)| (*p - *q).abs().max_element() > 0.05);
    assert!(changed.count() * 20 > n, "the glow changes the image");
}

#[test]
fn small_models_and_single_placements_stay_copies() {
    let d = tempfile::tempdir().unwrap();
    // A tetrahedron: 4 triangles, tested directly in lanes, cheaper copied than placed.
    std::fs::write(
        d.path().join("tet.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .unwrap();
    let mut text = String::from("[camera]\nposition = [0, 1, 5]\nlook_at = [0, 0, 0]\n");
    for x in 0..3 {
        text += &format!("[[mesh]]\nfile = \"tet.obj\"\ntranslate = [{x}, 0, 0]\n");
    }
    let scene = Scene::from_toml_str(&text, "t.toml", d.path()).unwrap();
    assert_eq!(kinds(&scene), (0, 3));
    let bunny = Scene::load(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/bunny.toml"));
    assert_eq!(
        kinds(&bunny.unwrap()),
        (0, 1),
        "a shipped scene is unchanged"
    );
}
