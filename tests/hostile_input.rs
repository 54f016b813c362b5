//! Input that once crashed raylab, hung it or slipped through unchecked: each is refused in
//! one line naming the file (and line:column where it has lines), or bounded.

mod common;

use common::{fails, raylab, read_json, scene_error, stderr};
use raylab::camera::Camera;
use raylab::math::Vec3;
use raylab::params::Params;
use raylab::render::render;
use raylab::scene::SceneDesc;

const CAMERA: &str = "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 0]\n";

fn assert_starts(e: &str, prefix: &str, words: &str) {
    assert!(e.starts_with(prefix), "expected `{prefix}…`, got: {e}");
    assert!(e.contains(words), "expected `{words}` in: {e}");
}

#[test]
fn geometry_beyond_what_the_bvh_handles_is_refused_where_it_is_written() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    // Each of these once panicked inside the BVH builder.
    std::fs::write(dir.join("tri.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    // (objects after the camera, where the error is, what it says); the first four once
    // panicked inside the BVH builder.
    let cases = [
        (
            "[[sphere]]\ncenter = [0, 1, 0]\nradius = 1e20\n",
            "6:10",
            "at most 1e6",
        ),
        (
            "[[sphere]]\ncenter = [0, 1, 0]\nradius = 1\nvelocity = [3e38, 0, 0]\n",
            "7:12",
            "largest coordinate",
        ),
        (
            "[[mesh]]\nfile = \"tri.obj\"\nscale = 1e30\n",
            "6:9",
            "at most 1e6",
        ),
        (
            "[[mesh]]\nfile = \"tri.obj\"\nscale = 1e6\ntranslate = [1e6, 0, 0]\n",
            "5:8",
            "the mesh reaches beyond",
        ),
        // Within the limits point by point, beyond them as a whole: named by the object.
        (
            "[[sphere]]\nname = \"far\"\ncenter = [999999, 1, 0]\nradius = 100\n",
            "4:1",
            "object `far` reaches beyond",
        ),
    ];
    for (objects, at, words) in cases {
        let e = scene_error(&format!("{CAMERA}{objects}"), dir);
        assert_starts(&e, &format!("t.toml:{at}: "), words);
    }
    // An OBJ vertex far out or not a number: the OBJ's own line and column.
    std::fs::write(
        dir.join("far.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1e20 0\nf 1 2 3\n",
    )
    .unwrap();
    let e = scene_error(&format!("{CAMERA}[[mesh]]\nfile = \"far.obj\"\n"), dir);
    assert!(e.contains("far.obj:3:5: vertex coordinate 1e20"), "{e}");
    // The camera: also once accepted from sidecars, now one check for both.
    let e = scene_error("[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 5]\n", dir);
    assert_starts(&e, "t.toml:1:1: ", "must differ");
    let e = scene_error(
        "# c\ncamera = { position = [0, 1, 5], look_at = [0, 1, 5] }\n",
        dir,
    );
    assert_starts(&e, "t.toml:2:10: ", "must differ");
}

#[test]
fn a_short_mtl_colour_is_an_error_not_a_crash() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    std::fs::write(
        dir.join("m.obj"),
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n",
    )
    .unwrap();
    for mtl in ["newmtl a\nKd 1\n", "newmtl a\nKd\n", "newmtl a\nKe 1 2\n"] {
        std::fs::write(dir.join("m.mtl"), mtl).unwrap();
        let e = scene_error(&format!("{CAMERA}[[mesh]]\nfile = \"m.obj\"\n"), dir);
        assert!(e.contains("m.mtl:2:1: `K"), "{e}");
        assert!(e.contains("three numbers"), "{e}");
    }
}

#[test]
fn a_camera_ray_that_is_not_finite_is_counted_and_dropped() {
    // Only code can build such a camera now (files are checked); the tracer still guards.
    let camera = Camera::looking_at(Vec3::splat(f32::INFINITY), Vec3::ZERO, Vec3::Y, 40.0);
    let scene = SceneDesc::empty(camera).build();
    let (film, stats) = render(&scene, &Params::default(), 4, 4, &()).unwrap();
    assert_eq!(stats.samples, 16 * Params::default().spp as u64);
    assert_eq!(stats.non_finite, stats.samples, "{stats:?}");
    assert_eq!(stats.camera_rays, 0, "{stats:?}");
    assert!(film.pixels().all(|c| c == raylab::math::Color::ZERO));
}

#[test]
fn sidecar_fields_are_checked_like_the_scene_files() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    let o = raylab(
        &["render", "-o", "s.png", "--size", "8x8", "--spp", "1", "-q"],
        dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let mut good = read_json(&dir.join("s.png.json"));
    // At the pixel budget: one more row is too many.
    good["width"] = 4096.into();
    let camera = serde_json::json!({
        "position": [0.0, 1.0, 5.0], "look_at": [0.0, 1.0, 0.0], "up": [0.0, 1.0, 0.0], "fov_deg": 40.0
    });
    let cases: Vec<(&str, serde_json::Value, &str)> = vec![
        ("width", 0.into(), "width must be between 1 and 16384"),
        ("height", 0.into(), "height must be between 1 and 16384"),
        ("width", 16385.into(), "width must be between 1 and 16384"),
        ("height", 4097.into(), "more than the 16777216"),
        ("samples", 0.into(), "`samples` must be between 1"),
        (
            "samples",
            4294967295u32.into(),
            "`samples` must be between 1",
        ),
    ];
    let mut cameras = Vec::new();
    for (field, value) in [
        ("look_at", serde_json::json!([0.0, 1.0, 5.0])),
        ("up", serde_json::json!([0.0, 0.0, 1.0])),
        ("fov_deg", serde_json::json!(0.0)),
        ("fov_deg", serde_json::json!(180.0)),
    ] {
        let mut c = camera.clone();
        c[field] = value;
        cameras.push(c);
    }
    let all = cases
        .into_iter()
        .chain(cameras.into_iter().map(|c| ("camera", c, "camera: ")));
    for (n, (field, value, words)) in all.enumerate() {
        let mut sidecar = good.clone();
        sidecar[field] = value;
        let name = format!("bad{n}.json");
        std::fs::write(dir.join(&name), sidecar.to_string()).unwrap();
        fails(
            &["render", "--params", &name, "-o", "x.png"],
            dir,
            &format!("{name}:1:"),
        );
        fails(&["render", "--params", &name, "-o", "x.png"], dir, words);
    }
    assert!(!dir.join("x.png").exists(), "nothing is written on error");
}

#[test]
fn sizes_and_parameters_beyond_the_renderer_are_refused() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    fails(
        &["render", "-o", "x.png", "--size", "16384x16384"],
        dir,
        "more than the 16777216",
    );
    fails(
        &[
            "render",
            "-o",
            "x.png",
            "--size",
            "8x8",
            "--set",
            "aperture=100",
            "--set",
            "focus_distance=3e38",
        ],
        dir,
        "at most 4000000",
    );
    std::fs::write(
        dir.join("huge.toml"),
        format!("{CAMERA}[image]\nwidth = 16384\nheight = 16384\n"),
    )
    .unwrap();
    fails(
        &["render", "huge.toml", "-o", "x.png"],
        dir,
        "huge.toml:4:1: [image]: 16384x16384",
    );
}

#[test]
fn a_ray_tree_without_a_weight_limit_is_cut_by_the_ray_budget() {
    // Once about 1.27x more rays each level, to depth 64: days at 960x540.
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    let o = raylab(
        &[
            "render",
            "tir",
            "-o",
            "t.png",
            "--size",
            "24x14",
            "--spp",
            "1",
            "--set",
            "max_depth=64",
            "--set",
            "min_weight=0",
            "-v",
        ],
        dir,
    );
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("by the ray budget"), "{err}");
    let sidecar = read_json(&dir.join("t.png.json"));
    let stats = &sidecar["stats"];
    let budget = raylab::tracer::MAX_TREE_RAYS as u64;
    assert!(stats["pruned_by_budget"].as_u64().unwrap() > 0, "{stats}");
    let (samples, rays) = (
        stats["samples"].as_u64().unwrap(),
        stats["reflection_rays"].as_u64().unwrap() + stats["refraction_rays"].as_u64().unwrap(),
    );
    assert!(
        rays <= samples * budget,
        "{rays} child rays for {samples} samples"
    );
}

#[test]
fn nothing_the_user_has_is_replaced_or_lost() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    let small = ["--size", "8x8", "--spp", "1", "-q"];
    let render = |args: &[&str]| {
        let all: Vec<&str> = args.iter().chain(&small).copied().collect();
        let o = raylab(&all, dir);
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    };
    // A file of the user's that happens to share the image's stem is not touched.
    std::fs::write(dir.join("keep.json"), "my notes").unwrap();
    render(&["render", "-o", "keep.png"]);
    assert_eq!(
        std::fs::read_to_string(dir.join("keep.json")).unwrap(),
        "my notes"
    );
    // Two images of one name, two sidecars.
    render(&["render", "glass", "-o", "keep.exr"]);
    assert_eq!(
        read_json(&dir.join("keep.png.json"))["scene"],
        "builtin:default"
    );
    assert_eq!(
        read_json(&dir.join("keep.exr.json"))["scene"],
        "builtin:glass"
    );
    // Nothing but the images and their sidecars: no temporary file is left behind.
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "keep.exr",
            "keep.exr.json",
            "keep.json",
            "keep.png",
            "keep.png.json"
        ]
    );
    // Writing over the image -o names is what was asked, and the summary says so.
    let o = raylab(
        &["render", "-o", "keep.png", "--size", "8x8", "--spp", "1"],
        dir,
    );
    assert!(
        stderr(&o).contains("wrote keep.png (replacing the file there)"),
        "{}",
        stderr(&o)
    );
    // The sidecar being read is never overwritten, nor a file that is not a sidecar.
    let input = std::fs::read(dir.join("keep.png.json")).unwrap();
    fails(
        &[
            "render",
            "--params",
            "keep.png.json",
            "-o",
            "keep.png",
            "--size",
            "4x4",
        ],
        dir,
        "keep.png.json: is the sidecar this render reads",
    );
    assert_eq!(std::fs::read(dir.join("keep.png.json")).unwrap(), input);
    std::fs::write(dir.join("other.png.json"), "{ \"mine\": 1 }").unwrap();
    fails(
        &["render", "-o", "other.png"],
        dir,
        "other.png.json: exists and is not a raylab sidecar",
    );
    assert!(!dir.join("other.png").exists());
}

#[test]
fn a_folder_of_scenes_and_renders_moves_as_a_whole() {
    let d = tempfile::tempdir().unwrap();
    let project = d.path().join("project");
    std::fs::create_dir_all(project.join("scenes")).unwrap();
    std::fs::create_dir_all(project.join("renders")).unwrap();
    std::fs::write(
        project.join("scenes/ball.toml"),
        format!("{CAMERA}[[sphere]]\ncenter = [0, 1, 0]\nradius = 1\n"),
    )
    .unwrap();
    let o = raylab(
        &[
            "render",
            "../scenes/ball.toml",
            "-o",
            "a.png",
            "--size",
            "8x8",
            "--spp",
            "2",
            "-q",
        ],
        &project.join("renders"),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let sidecar = read_json(&project.join("renders/a.png.json"));
    assert_eq!(sidecar["scene"], "../scenes/ball.toml");
    // Moved elsewhere, the render still reproduces bit for bit from its sidecar.
    let moved = d.path().join("moved");
    std::fs::rename(&project, &moved).unwrap();
    let o = raylab(
        &[
            "render",
            "--params",
            "renders/a.png.json",
            "-o",
            "b.png",
            "-q",
        ],
        &moved,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    // The same pixels; each image names the scene relative to its own folder.
    let pixels = |p: &str| image::open(moved.join(p)).unwrap().into_rgb8().into_raw();
    assert_eq!(pixels("renders/a.png"), pixels("b.png"));
    let carried = |p: &str| raylab::render::Sidecar::read(&moved.join(p)).unwrap();
    let (a, b) = (carried("renders/a.png"), carried("b.png"));
    assert_eq!(
        std::fs::canonicalize(&a.scene).unwrap(),
        std::fs::canonicalize(&b.scene).unwrap()
    );
    assert_eq!(a.params, b.params);
}

#[cfg(unix)]
#[test]
fn devices_pipes_and_folders_are_refused_without_blocking() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    // A pipe with no writer: opening it would block for ever.
    let made = std::process::Command::new("mkfifo")
        .arg(dir.join("pipe"))
        .status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo");
    std::fs::create_dir(dir.join("folder.toml")).unwrap();
    for path in ["/dev/zero", "pipe", "folder.toml"] {
        fails(&["render", path, "-o", "x.png"], dir, "not a regular file");
        fails(
            &["render", "--params", path, "-o", "x.png"],
            dir,
            "not a regular file",
        );
        std::fs::write(
            dir.join("mesh.toml"),
            format!("{CAMERA}[[mesh]]\nfile = \"{path}\"\n"),
        )
        .unwrap();
        // (A `.toml` is no model format: refused by its name before it is opened.)
        let why = if path.ends_with(".toml") {
            "mesh.toml:5:8: unsupported model format `.toml`"
        } else {
            "mesh.toml:5:8: cannot read OBJ file"
        };
        fails(&["render", "mesh.toml", "-o", "x.png"], dir, why);
        // A material library that cannot be read is left out, as a missing one is.
        std::fs::write(
            dir.join("m.obj"),
            format!("mtllib {path}\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
        )
        .unwrap();
        let o = raylab(
            &["render", "m.obj", "-o", "m.png", "--size", "8x8", "-q"],
            dir,
        );
        assert!(o.status.success(), "{path}: {}", stderr(&o));
    }
}

#[test]
fn parameters_set_together_are_checked_together_and_errors_are_said_once() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    // motion-blur's shutter is open for the whole frame: opening it later is valid only
    // once it is also shortened, whichever comes first on the command line.
    for order in [
        ["shutter_open=0.5", "shutter=0.5"],
        ["shutter=0.5", "shutter_open=0.5"],
    ] {
        let o = raylab(
            &[
                "render",
                "motion-blur",
                "-o",
                "m.png",
                "--size",
                "8x8",
                "--spp",
                "1",
                "-q",
                "--set",
                order[0],
                "--set",
                order[1],
            ],
            dir,
        );
        assert!(o.status.success(), "{order:?}: {}", stderr(&o));
    }
    let err = fails(
        &["render", "--params", "missing.json", "-o", "x.png"],
        dir,
        "missing.json: ",
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    let said = err.trim_start_matches("error: missing.json: ");
    assert!(!said.contains(": "), "the reason once: {err}");
    // A key with a newline in it is shown escaped, on the one line.
    std::fs::write(
        dir.join("key.json"),
        "{ \"scene\": \"default\", \"a\\nb\": 1 }",
    )
    .unwrap();
    let err = fails(
        &["render", "--params", "key.json", "-o", "x.png"],
        dir,
        "key.json:1:",
    );
    assert_eq!(err.lines().count(), 1, "{err}");
}

#[test]
fn an_output_that_cannot_be_written_is_refused_before_the_render() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    // A folder where the image should go: refused before any time is spent, untouched.
    std::fs::create_dir(dir.join("taken.png")).unwrap();
    std::fs::write(dir.join("taken.png/inside"), "mine").unwrap();
    let err = fails(
        &[
            "render",
            "-o",
            "taken.png",
            "--size",
            "8x8",
            "--spp",
            "1",
            "-q",
        ],
        dir,
        "taken.png: cannot be written: is a folder",
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    assert_eq!(
        std::fs::read_to_string(dir.join("taken.png/inside")).unwrap(),
        "mine"
    );
    let left: Vec<_> = std::fs::read_dir(dir).unwrap().collect();
    assert_eq!(left.len(), 1, "no temporary file left: {left:?}");
}
