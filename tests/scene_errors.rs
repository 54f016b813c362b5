//! Every kind of bad scene input gives one line naming the file and line:column.

mod common;

use common::scene_error;
use raylab::scene::Scene;
use std::path::Path;

const CAMERA: &str = "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 0]\n";

fn err(text: &str) -> String {
    scene_error(text, Path::new("."))
}

fn assert_at(e: &str, location: &str, words: &str) {
    assert!(
        e.starts_with(&format!("{location}: ")),
        "expected location {location}, got: {e}"
    );
    assert!(e.contains(words), "expected `{words}` in: {e}");
}

#[test]
fn syntax_error() {
    let e = err(&format!(
        "{CAMERA}[[sphere]]\ncenter = [0, 0, 0\nradius = 1\n"
    ));
    // Arrays may span lines: the parser notices at the next line.
    assert_at(&e, "t.toml:6:1", "missing comma");
}

#[test]
fn unknown_key() {
    let e = err(&format!(
        "{CAMERA}[[sphere]]\ncenter = [0, 0, 0]\nradus = 1\n"
    ));
    assert_at(&e, "t.toml:6:1", "unknown field `radus`");
}

#[test]
fn wrong_type() {
    let e = err(&format!(
        "{CAMERA}[[sphere]]\ncenter = [0, 0, 0]\nradius = \"big\"\n"
    ));
    assert_at(&e, "t.toml:6:10", "invalid type");
}

#[test]
fn non_finite_number() {
    let e = err(&format!(
        "{CAMERA}[[sphere]]\ncenter = [0, nan, 0]\nradius = 1\n"
    ));
    assert_at(&e, "t.toml:5:10", "non-finite");
    let e = err(&format!(
        "{CAMERA}[[point_light]]\nposition = [0, 5, 0]\nintensity = inf\n"
    ));
    assert_at(&e, "t.toml:6:13", "not a finite number");
}

#[test]
fn negative_radius() {
    let e = err(&format!(
        "{CAMERA}[[sphere]]\ncenter = [0, 0, 0]\nradius = -1\n"
    ));
    assert_at(&e, "t.toml:6:10", "greater than 0");
}

#[test]
fn zero_image_size() {
    let e = err(&format!("[image]\nwidth = 0\nheight = 10\n{CAMERA}"));
    assert_at(&e, "t.toml:2:9", "between 1 and");
}

#[test]
fn spp_zero_and_unknown_parameter() {
    let e = err(&format!("[params]\nspp = 0\n{CAMERA}"));
    assert_at(&e, "t.toml:2:7", "spp");
    let e = err(&format!("[params]\nmax_dpeth = 3\n{CAMERA}"));
    assert_at(&e, "t.toml:2:1", "unknown parameter `max_dpeth`");
}

#[test]
fn unknown_material() {
    let e = err(&format!(
        "{CAMERA}[material.red]\ntype = \"diffuse\"\ncolor = [1, 0, 0]\n[[sphere]]\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"blue\"\n"
    ));
    assert_at(&e, "t.toml:10:12", "unknown material `blue` (defined: red)");
}

#[test]
fn bad_material_fields() {
    let e = err(&format!(
        "{CAMERA}[material.m]\ntype = \"mirror\"\ncolor = [1, 0, 0]\n"
    ));
    assert!(e.starts_with("t.toml:"), "{e}");
    assert!(e.contains("unknown field `color`"), "{e}");
    let e = err(&format!("{CAMERA}[material.m]\ntype = \"velvet\"\n"));
    assert!(e.contains("unknown variant `velvet`"), "{e}");
    let e = err(&format!(
        "{CAMERA}[material.m]\ntype = \"diffuse\"\ncolor = [1.5, 0, 0]\n"
    ));
    assert!(e.contains("between 0 and 1"), "{e}");
}

#[test]
fn missing_camera_and_degenerate_camera() {
    let e = err("[[sphere]]\ncenter = [0, 0, 0]\nradius = 1\n");
    assert!(e.contains("missing field `camera`"), "{e}");
    let e = err("[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 5]\n");
    assert!(e.contains("must differ"), "{e}");
    let e = err("[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 0]\nfov = 200\n");
    assert_at(&e, "t.toml:4:7", "below 180");
}

#[test]
fn bad_background_and_quad() {
    let e = err(&format!(
        "{CAMERA}[background]\ncolor = [1, 1, 1]\nzenith = [0, 0, 1]\n"
    ));
    assert!(e.contains("either `color`"), "{e}");
    let e = err(&format!(
        "{CAMERA}[[quad]]\ncorner = [0, 0, 0]\nedge_u = [1, 0, 0]\nedge_v = [2, 0, 0]\n"
    ));
    assert!(e.starts_with("t.toml:4:") && e.contains("parallel"), "{e}");
}

#[test]
fn missing_obj() {
    let dir = tempfile::tempdir().unwrap();
    let e = scene_error(
        &format!("{CAMERA}[[mesh]]\nfile = \"nope.obj\"\n"),
        dir.path(),
    );
    assert_at(&e, "t.toml:5:8", "cannot read OBJ file");
    assert!(e.contains("nope.obj"), "{e}");
}

#[test]
fn malformed_obj_names_the_obj_line() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("bad.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n",
    )
    .unwrap();
    let e = scene_error(
        &format!("{CAMERA}[[mesh]]\nfile = \"bad.obj\"\n"),
        dir.path(),
    );
    assert!(e.contains("bad.obj:4: "), "{e}");
    std::fs::write(
        dir.path().join("oob.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
    )
    .unwrap();
    let e = scene_error(
        &format!("{CAMERA}[[mesh]]\nfile = \"oob.obj\"\n"),
        dir.path(),
    );
    assert!(
        e.contains("oob.obj:4:7: face refers to vertex 4, but there are 3"),
        "{e}"
    );
    std::fs::write(
        dir.path().join("nan.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n",
    )
    .unwrap();
    let e = scene_error(
        &format!("{CAMERA}[[mesh]]\nfile = \"nan.obj\"\n"),
        dir.path(),
    );
    assert!(
        e.contains("nan.obj:3:5: vertex coordinate nan is not a finite number"),
        "{e}"
    );
}

#[test]
fn scene_files_that_do_not_exist_or_are_not_scenes() {
    let e = Scene::load("no/such/scene.toml").unwrap_err().to_string();
    assert!(e.starts_with("no/such/scene.toml: "), "{e}");
    let e = Scene::load("builtin:nope").unwrap_err().to_string();
    assert!(e.contains("built-in: default"), "{e}");
}

#[test]
fn a_good_scene_with_a_mesh_and_its_mtl_loads() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("tri.mtl"), "newmtl glow\nKe 1 1 1\n").unwrap();
    std::fs::write(
        dir.path().join("tri.obj"),
        "mtllib tri.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl glow\nf 1 2 3\n",
    )
    .unwrap();
    let scene = Scene::from_toml_str(
        &format!("{CAMERA}[[mesh]]\nfile = \"tri.obj\"\n"),
        "t.toml",
        dir.path(),
    )
    .unwrap();
    assert_eq!(scene.material_names, vec!["tri.obj:glow".to_string()]);
    assert_eq!(scene.materials[0].kind(), "emissive");
}

#[test]
fn an_obj_file_opens_as_a_framed_scene() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("tri.obj");
    std::fs::write(&obj, "v 10 10 10\nv 12 10 10\nv 10 13 10\nf 1 2 3\n").unwrap();
    let scene = Scene::load(obj.to_str().unwrap()).unwrap();
    assert_eq!(scene.name, "tri");
    assert!(scene.object_names.iter().any(|n| n == "floor"));
    // The camera looks at the middle of the mesh.
    let c = raylab::math::Vec3::new(11.0, 11.5, 10.0);
    assert!((scene.camera.look_at - c).length() < 1e-5);
    let e = Scene::load(dir.path().join("missing.obj").to_str().unwrap()).unwrap_err();
    assert!(e.to_string().contains("missing.obj"), "{e}");
    std::fs::write(dir.path().join("bad.obj"), "v 1 2\nf 1 2 3\n").unwrap();
    let e = Scene::load(dir.path().join("bad.obj").to_str().unwrap()).unwrap_err();
    assert!(e.to_string().contains("bad.obj:1"), "{e}");
}

#[test]
fn a_conductor_is_a_named_metal_or_its_own_index_and_nothing_in_between() {
    let metal = "[material.gold]\ntype = \"conductor\"\n";
    let sphere = "[[sphere]]\ncenter = [0, 1, 0]\nradius = 1\nmaterial = \"gold\"\n";
    let load = |keys: &str| {
        Scene::from_toml_str(
            &format!("{CAMERA}{metal}{keys}{sphere}"),
            "t.toml",
            Path::new("."),
        )
    };
    let scene = load("eta = [0.18, 0.42, 1.37]\nk = [3.42, 2.35, 1.77]\nexponent = 40\n").unwrap();
    assert_eq!(scene.materials[0].kind(), "conductor");
    assert_eq!(scene.materials[0].phong_exponent(), Some(40.0));
    // A measured metal carries its table's constants exactly.
    let gold = raylab::material::metal("gold").unwrap();
    let expected = raylab::material::Material::Conductor(raylab::material::Conductor {
        eta: gold.eta(),
        k: gold.k(),
        exponent: None,
    });
    assert_eq!(load("metal = \"Gold\"\n").unwrap().materials[0], expected);
    // A refusal of the keys together names the material's table; of one value, the value.
    for (keys, at, words) in [
        (
            "eta = [0.18, 0.42, 1.37]\n",
            "t.toml:4:1",
            "or both `eta` and `k`",
        ),
        (
            "",
            "t.toml:4:1",
            "a conductor needs `metal` (gold, silver, copper, aluminium",
        ),
        (
            "metal = \"brass\"\n",
            "t.toml:6:9",
            "unknown metal `brass` (known: gold, silver",
        ),
        (
            "metal = \"gold\"\nk = [1, 1, 1]\n",
            "t.toml:4:1",
            "either `metal` or `eta` and `k`",
        ),
    ] {
        let e = err(&format!("{CAMERA}{metal}{keys}{sphere}"));
        assert_at(&e, at, words);
    }
}

#[test]
fn a_checkers_scale_is_a_positive_number_or_two() {
    let with = |scale: &str| {
        err(&format!(
            "{CAMERA}[material.m]\ntype = \"diffuse\"\ncolor = [1, 1, 1]\n\
             checker = {{ color = [0, 0, 0], scale = {scale} }}\n"
        ))
    };
    // Located at the checker's value, not at the material's header.
    let at = "t.toml:7:11";
    assert_at(&with("[16, 0]"), at, "must be greater than 0, got 0");
    assert_at(&with("[16]"), at, "[along u, along v]: two numbers");
    assert_at(&with("[1, 2, 3]"), at, "[along u, along v]: two numbers");
    assert_at(&with("-2"), at, "must be greater than 0, got -2");
    assert_at(
        &with("\"fine\""),
        at,
        "expected cells per unit: a number, or [along u, along v]",
    );
}

/// The speed scenes the Mitsuba comparison renders (tests/mitsuba/speed.py) load without a
/// warning, each with the objects its Mitsuba twin (peer.py) has: a scene that stopped
/// loading would silently drop out of the comparison.
#[test]
fn the_speed_scenes_against_mitsuba_load() {
    let objects = [
        ("glass", 2),
        ("dof", 3),
        ("misses", 4),
        ("over", 3),
        ("mesh", 2),
    ];
    for (name, count) in objects {
        let path = format!(
            "{}/tests/mitsuba/speed-{name}.toml",
            env!("CARGO_MANIFEST_DIR")
        );
        let scene = Scene::load(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
        assert_eq!(scene.shapes.len(), count, "{name}");
        assert!(scene.warnings.is_empty(), "{name}: {:?}", scene.warnings);
    }
}
