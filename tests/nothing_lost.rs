//! Nothing the user made is lost, and nothing slips past a check: numbers beyond f32,
//! writes cut short, outputs that cannot be written, full streams (issue 30).

mod common;

use common::{fails, raylab, stderr};
use raylab::params::{Kind, TABLE};

/// Every real parameter, with a value beyond f32's range in its own sign.
fn overflowing() -> Vec<(&'static str, &'static str)> {
    TABLE
        .iter()
        .filter(|s| matches!(s.kind, Kind::Number { .. } | Kind::WordOrNumber { .. }))
        .map(|s| {
            let negative = matches!(s.kind, Kind::Number { min, .. } if min < 0.0);
            (s.name, if negative { "-1e39" } else { "1e39" })
        })
        .collect()
}

#[test]
fn numbers_beyond_f32_are_refused_from_every_source_naming_it() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    let reals = overflowing();
    assert_eq!(reals.len(), 15, "the real parameters: {reals:?}");
    let o = raylab(
        &[
            "render", "-o", "good.png", "--size", "8x8", "--spp", "1", "-q",
        ],
        dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let good = std::fs::read_to_string(dir.join("good.png.json")).unwrap();
    for (name, value) in reals {
        // On the command line: the option and the parameter whose value it is, even with
        // a good value set beside it.
        let set = format!("{name}={value}");
        let err = fails(
            &[
                "render", "-o", "x.png", "--size", "8x8", "--set", "spp=2", "--set", &set,
            ],
            dir,
            &format!("--set: bad value for `{name}`: must be"),
        );
        assert!(err.contains("1e39") || err.contains("1e+39"), "{err}");
        // In a scene's [params]: the file, line and column of the value.
        std::fs::write(
            dir.join("s.toml"),
            format!(
                "[camera]\nposition = [0.0, 1.0, 5.0]\nlook_at = [0.0, 1.0, 0.0]\n[params]\n{name} = {value}\n"
            ),
        )
        .unwrap();
        fails(
            &["render", "s.toml", "-o", "x.png"],
            dir,
            &format!(
                "s.toml:5:{}: in [params]: bad value for `{name}`",
                name.len() + 4
            ),
        );
        // In a sidecar: the file, line and column of the value, not an option.
        let key = format!("\"{name}\": ");
        let at = good.find(&key).expect("every parameter is in the sidecar");
        let end = at + key.len() + good[at + key.len()..].find([',', '\n']).unwrap();
        let bad = format!("{}{key}{value}{}", &good[..at], &good[end..]);
        std::fs::write(dir.join("bad.json"), &bad).unwrap();
        let line = bad[..at].matches('\n').count() + 1;
        let err = fails(
            &["render", "--params", "bad.json", "-o", "x.png"],
            dir,
            &format!("bad.json:{line}:"),
        );
        assert!(!err.contains("--set") && !err.contains("--spp"), "{err}");
        assert!(err.contains(&format!("bad value for `{name}`")), "{err}");
    }
    assert!(!dir.join("x.png").exists(), "nothing rendered");
}

#[test]
fn a_bad_value_among_several_sets_is_named_by_its_own_parameter() {
    let d = tempfile::tempdir().unwrap();
    let err = fails(
        &[
            "render",
            "-o",
            "x.png",
            "--set",
            "ior=2",
            "--set",
            "aperture=500",
            "--set",
            "max_depth=3",
        ],
        d.path(),
        "bad value for `aperture`: must be between 0 and 100",
    );
    assert!(err.contains("got 500"), "{err}");
}

/// A glTF file of one triangle, its buffer inline; `extra` is added to its top level.
fn triangle_gltf(extra: &str) -> String {
    use base64::Engine as _;
    let bytes: Vec<u8> = [0f32, 0., 0., 1., 0., 0., 0., 1., 0.]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let uri = base64::engine::general_purpose::STANDARD.encode(bytes);
    format!(
        r#"{{"asset": {{"version": "2.0"}}, {extra}
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
  "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}], "scene": 0,
  "buffers": [{{"byteLength": 36, "uri": "data:application/octet-stream;base64,{uri}"}}],
  "bufferViews": [{{"buffer": 0, "byteLength": 36}}],
  "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}}]}}"#
    )
}

const TRIANGLE_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

/// Renders `scene` in `dir` at 8×8, 1 spp; its stderr, after checking it succeeded.
fn renders(scene: &str, dir: &std::path::Path) -> String {
    let o = raylab(
        &[
            "render", scene, "-o", "r.png", "--size", "8x8", "--spp", "1",
        ],
        dir,
    );
    assert!(o.status.success(), "{scene}: {}", stderr(&o));
    stderr(&o)
}

#[test]
fn messages_point_where_the_mistake_is() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    // A value inside a material's table: its own line and column, not the header's.
    let e = common::scene_error(
        "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 0]\n[material.g]\ntype = \"dielectric\"\nior = 9.5\n",
        dir,
    );
    assert!(e.starts_with("t.toml:6:7: "), "{e}");
    let e = common::scene_error(
        "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 0]\n[material.g]\ncolor = [1, 1, 1]\ntype = \"difuse\"\n",
        dir,
    );
    assert!(e.starts_with("t.toml:6:8: unknown variant `difuse`"), "{e}");
    // An error in a material library names the library, not the OBJ.
    std::fs::write(
        dir.join("m.obj"),
        format!("mtllib m.mtl\nusemtl red\n{TRIANGLE_OBJ}"),
    )
    .unwrap();
    for (mtl, at) in [
        ("newmtl red\nKd 1 0 0\nNi abc\n", "m.mtl:3:4: `Ni`"),
        ("newmtl red\nKd 1 0 0\nNs 1e39\n", "m.mtl:3:4: `Ns`"),
        (
            "newmtl red\nTf 1 1\n",
            "m.mtl:2:1: `Tf` needs three numbers",
        ),
    ] {
        std::fs::write(dir.join("m.mtl"), mtl).unwrap();
        let err = fails(&["render", "m.obj", "-o", "x.png"], dir, at);
        assert!(!err.contains("m.obj"), "{err}");
    }
    // A model opened alone: its own name, no line of a text the user never wrote.
    std::fs::create_dir(dir.join("folder.obj")).unwrap();
    let err = fails(&["render", "folder.obj", "-o", "x.png"], dir, "folder.obj");
    assert!(!err.contains(":5:"), "{err}");
    // A missing material library: rendered grey, with a warning naming it.
    std::fs::write(
        dir.join("lost.obj"),
        format!("mtllib gone.mtl\n{TRIANGLE_OBJ}"),
    )
    .unwrap();
    let said = renders("lost.obj", dir);
    assert!(
        said.starts_with("warning: ") && said.contains("`gone.mtl`"),
        "{said}"
    );
    // Byte-order marks, as Windows editors write them, in every format read.
    const BOM: &str = "\u{feff}";
    std::fs::write(dir.join("bom.gltf"), format!("{BOM}{}", triangle_gltf(""))).unwrap();
    renders("bom.gltf", dir);
    let sidecar = std::fs::read_to_string(dir.join("r.png.json")).unwrap();
    std::fs::write(dir.join("bom.json"), format!("{BOM}{sidecar}")).unwrap();
    let o = raylab(
        &["render", "--params", "bom.json", "-o", "b.png", "-q"],
        dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    std::fs::write(
        dir.join("bom.obj"),
        format!("{BOM}mtllib bom.mtl\nusemtl red\n{TRIANGLE_OBJ}"),
    )
    .unwrap();
    std::fs::write(dir.join("bom.mtl"), format!("{BOM}newmtl red\nKd 1 0 0\n")).unwrap();
    let said = renders("bom.obj", dir);
    assert!(!said.contains("warning"), "{said}");
    let scene = raylab::scene::Scene::load(dir.join("bom.obj")).unwrap();
    assert_eq!(scene.shapes.len(), 2, "the triangle on the floor");
    assert!(
        scene.material_names.iter().any(|n| n.ends_with(":red")),
        "the library's material: {:?}",
        scene.material_names
    );
    std::fs::write(
        dir.join("bom.toml"),
        format!("{BOM}[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 0]\n"),
    )
    .unwrap();
    renders("bom.toml", dir);
    // A compressed mesh is named as what it is, not as missing data.
    std::fs::write(
        dir.join("draco.gltf"),
        triangle_gltf(
            r#""extensionsUsed": ["KHR_draco_mesh_compression"], "extensionsRequired": ["KHR_draco_mesh_compression"],"#,
        ),
    )
    .unwrap();
    fails(
        &["render", "draco.gltf", "-o", "x.png"],
        dir,
        "needs the glTF extension KHR_draco_mesh_compression (Draco-compressed meshes)",
    );
}

#[cfg(unix)]
#[test]
fn file_names_that_are_not_utf8_open() {
    use std::os::unix::ffi::OsStrExt;
    let d = tempfile::tempdir().unwrap();
    let name = std::ffi::OsStr::from_bytes(b"caf\xe9.obj");
    std::fs::write(d.path().join(name), TRIANGLE_OBJ).unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_raylab"))
        .arg("render")
        .arg(name)
        .args(["-o", "r.png", "--size", "8x8", "--spp", "1", "-q"])
        .current_dir(d.path())
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
}

#[cfg(target_os = "linux")]
#[test]
fn a_full_stream_is_an_error_not_a_panic_nor_silence() {
    let d = tempfile::tempdir().unwrap();
    let full = || std::fs::File::create("/dev/full").unwrap();
    let run = |args: &[&str], stdout_full: bool| {
        let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_raylab"));
        c.args(args).current_dir(d.path());
        if stdout_full {
            c.stdout(full());
        } else {
            c.stderr(full());
        }
        c.output().unwrap()
    };
    // The summary lost after a good render: the image is there, the status says the loss.
    let o = run(
        &["render", "-o", "r.png", "--size", "8x8", "--spp", "1"],
        false,
    );
    assert_eq!(o.status.code(), Some(1));
    assert!(d.path().join("r.png").is_file());
    for args in [
        &["params"][..],
        &["scenes"],
        &["lecture"],
        &["fresnel"],
        &["inspect", "glass", "--pixel", "1,1", "--size", "8x8"],
    ] {
        let o = run(args, true);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.starts_with("error: cannot write to standard output:"),
            "{args:?}: {err}"
        );
    }
}

#[test]
fn an_image_carries_its_parameters_and_reproduces_from_itself() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    for ext in ["png", "exr"] {
        let (a, b) = (format!("a.{ext}"), format!("b.{ext}"));
        let o = raylab(
            &[
                "render", "glass", "-o", &a, "--size", "24x16", "--spp", "2", "--set", "ior=1.7",
                "-q",
            ],
            dir,
        );
        assert!(o.status.success(), "{}", stderr(&o));
        // The sidecar gone, the image alone says how it was made.
        std::fs::remove_file(dir.join(format!("{a}.json"))).unwrap();
        let o = raylab(&["render", "--params", &a, "-o", &b, "-q"], dir);
        assert!(o.status.success(), "{}", stderr(&o));
        if ext == "png" {
            let same = std::fs::read(dir.join(&a)).unwrap() == std::fs::read(dir.join(&b)).unwrap();
            assert!(same, "a PNG reproduces byte for byte");
        } else {
            // EXR's header attributes come in no fixed order: the pixels are the same.
            let pixels = |p: &str| image::open(dir.join(p)).unwrap().into_rgb32f().into_raw();
            assert!(
                pixels(&a) == pixels(&b),
                "an EXR reproduces pixel for pixel"
            );
        }
        let carried = raylab::render::Sidecar::read(&dir.join(&b)).unwrap();
        assert_eq!(carried.params.ior, Some(1.7));
    }
    // The image read is not replaced by its own re-render.
    let before = std::fs::read(dir.join("a.png")).unwrap();
    fails(
        &[
            "render", "--params", "a.png", "-o", "a.png", "--set", "ior=2",
        ],
        dir,
        "a.png: is the image this render reads its parameters from; not replaced",
    );
    assert!(std::fs::read(dir.join("a.png")).unwrap() == before);
    // An image raylab did not write says so in one line.
    image::RgbImage::new(2, 2)
        .save(dir.join("plain.png"))
        .unwrap();
    fails(
        &["render", "--params", "plain.png", "-o", "x.png"],
        dir,
        "plain.png: carries no raylab parameters",
    );
}

#[test]
fn outputs_that_cannot_be_written_are_refused_before_the_render() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    let render = |out: &str, words: &str| {
        fails(
            &["render", "glass", "-o", out, "--size", "8x8", "--spp", "1"],
            dir,
            words,
        )
    };
    // Its sidecar's name would pass the file system's 255 bytes.
    let long = format!("{}.png", "n".repeat(250));
    render(&long, "259 bytes long with its sidecar's .json");
    render("missing/x.png", "the folder missing does not exist");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::create_dir(dir.join("ro")).unwrap();
        std::fs::set_permissions(dir.join("ro"), std::fs::Permissions::from_mode(0o555)).unwrap();
        // Root writes anywhere: the check is then what the file system says.
        let writable = std::fs::write(dir.join("ro/probe"), "").is_ok();
        if !writable {
            render("ro/x.png", "no new file can be made in ro");
        }
    }
    assert_eq!(
        std::fs::read_dir(dir).unwrap().flatten().count(),
        usize::from(cfg!(unix))
    );
}

/// The `.tmp` files in `dir`.
fn temporaries(dir: &std::path::Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .expect("the folder is there")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect()
}

#[cfg(unix)]
#[test]
fn a_kill_at_any_moment_leaves_a_matching_pair_and_the_next_write_cleans_up() {
    use std::time::{Duration, Instant};
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    let args = |seed: u64| {
        [
            "render", "glass", "-o", "k.png", "--size", "480x270", "--spp", "1", "-q", "--seed",
        ]
        .iter()
        .map(|s| s.to_string())
        .chain([seed.to_string()])
        .collect::<Vec<_>>()
    };
    let start = Instant::now();
    let o = raylab(&args(0).iter().map(String::as_str).collect::<Vec<_>>(), dir);
    assert!(o.status.success(), "{}", stderr(&o));
    let whole = start.elapsed();
    // Kills from a third of the way in to past the end, so that many land in the write.
    let kills = 24;
    let mut outcomes = std::collections::BTreeSet::new();
    for (n, signal) in (1..=kills).zip(["-KILL", "-INT"].into_iter().cycle()) {
        let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_raylab"))
            .args(args(n))
            .current_dir(dir)
            .spawn()
            .unwrap();
        let at = whole.mul_f64(0.3 + 1.0 * n as f64 / kills as f64);
        std::thread::sleep(at.min(Duration::from_secs(10)));
        let _ = std::process::Command::new("kill")
            .args([signal, &child.id().to_string()])
            .status();
        let _ = child.wait();
        // The image's own parameters and its sidecar's (if there is one) agree.
        let image = raylab::render::Sidecar::read(&dir.join("k.png")).unwrap();
        let sidecar = raylab::render::Sidecar::read(&dir.join("k.png.json")).ok();
        if let Some(sidecar) = &sidecar {
            assert_eq!(image.params.seed, sidecar.params.seed, "kill {n} at {at:?}");
        }
        outcomes.insert((image.params.seed == n, sidecar.is_some()));
        if signal == "-INT" {
            // Its own: the run killed before it left its files to the next write.
            let own = format!("raylab-{}-", child.id());
            let left = temporaries(dir).into_iter().filter(|n| n.contains(&own));
            assert_eq!(left.count(), 0, "Ctrl-C cleans up: {:?}", temporaries(dir));
        }
    }
    // Some kills came before the new image, some after: the test saw both sides.
    assert!(outcomes.contains(&(false, true)), "{outcomes:?}");
    assert!(outcomes.contains(&(true, true)), "{outcomes:?}");
    let o = raylab(
        &args(99).iter().map(String::as_str).collect::<Vec<_>>(),
        dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(temporaries(dir).is_empty(), "{:?}", temporaries(dir));
}

/// An OBJ grid of `n` × `n` squares (2n² triangles) on the unit square of the x–z plane.
fn grid_obj(n: usize) -> String {
    let mut s = String::new();
    for i in 0..=n {
        for j in 0..=n {
            s += &format!("v {} 0 {}\n", i as f32 / n as f32, j as f32 / n as f32);
        }
    }
    for i in 0..n {
        for j in 0..n {
            let a = i * (n + 1) + j + 1;
            let (b, c, d) = (a + 1, a + n + 1, a + n + 2);
            s += &format!("f {a} {b} {d}\nf {a} {d} {c}\n");
        }
    }
    s
}

/// A scene placing the model `file(i)` at the i-th of `count` spots side by side.
fn placed(file: impl Fn(usize) -> String, count: usize) -> String {
    let mut s = String::from("[camera]\nposition = [0.5, 2, 3]\nlook_at = [0.5, 0, 0.5]\n");
    for i in 0..count {
        s += &format!(
            "[[mesh]]\nfile = \"{}\"\ntranslate = [{}, 0, 0]\n",
            file(i),
            i as f32 * 1.1
        );
    }
    s
}

#[test]
fn a_scene_beyond_the_memory_limit_is_refused_before_it_is_built() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    // Eight files of one grid, each placed once (copies), and one placed 40 times
    // (shared: its triangles built once).
    for i in 0..8 {
        std::fs::write(dir.join(format!("grid{i}.obj")), grid_obj(100)).unwrap();
    }
    let each = placed(|i| format!("grid{i}.obj"), 8);
    std::fs::write(dir.join("many.toml"), each).unwrap();
    std::fs::write(dir.join("one.toml"), placed(|_| "grid0.obj".into(), 40)).unwrap();
    let run = |limit: &str, args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_raylab"))
            .args(args)
            .env("RAYLAB_MEMORY_LIMIT", limit)
            .current_dir(dir)
            .output()
            .unwrap()
    };
    // 20,000 triangles a copy: the limit is passed at the 8th (8 × 20,000 × 340 B).
    let o = run(
        "50M",
        &["render", "many.toml", "-o", "x.png", "--size", "8x8"],
    );
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.starts_with("error: many.toml:26:8: with this mesh, the scene's 160000 triangles need about 54 MB, more than raylab's limit of 52 MB (RAYLAB_MEMORY_LIMIT)\n"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    for (limit, scene) in [("1G", "many.toml"), ("50M", "one.toml")] {
        let o = run(
            limit,
            &["render", scene, "-o", "x.png", "--size", "8x8", "-q"],
        );
        assert!(o.status.success(), "{scene}: {}", stderr(&o));
    }
    // A film, a contact sheet: said before any work.
    let o = run(
        "50M",
        &["render", "glass", "-o", "x.png", "--size", "1000x1000"],
    );
    assert!(stderr(&o).contains("a 1000x1000 render's film and file need about 90 MB"));
    let values = vec!["1"; 2000].join(",");
    let o = run(
        "50M",
        &[
            "sweep",
            "glass",
            "--param",
            &format!("spp={values}"),
            "-o",
            "s.png",
            "--size",
            "96x54",
        ],
    );
    assert!(stderr(&o).contains("2000 values: the contact sheet's pixels need about"));
}

#[cfg(target_os = "linux")]
#[test]
fn under_a_two_gigabyte_address_space_every_big_job_renders_or_is_refused_in_a_line() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    // 200,000 triangles: 40 placements would be 8 million copied; shared, they are
    // built once (0.1 aborted here).
    std::fs::write(dir.join("grid.obj"), grid_obj(316)).unwrap();
    std::fs::write(dir.join("many.toml"), placed(|_| "grid.obj".into(), 40)).unwrap();
    let values = vec!["1"; 2000].join(",");
    let sweep = format!("sweep glass --param spp={values} -o s.png --size 480x270");
    for (job, refused) in [
        ("render many.toml -o a.png --size 64x36 --spp 1", false),
        ("render glass -o c.png --size 4096x4096 --spp 1", true),
        (sweep.as_str(), true),
    ] {
        let o = common::under_two_gigabytes(job, dir);
        let err = stderr(&o);
        let name = &job[..30.min(job.len())];
        if refused {
            assert_eq!(o.status.code(), Some(2), "{name}: {err}");
            assert!(
                err.contains("half the address space ulimit -v allows"),
                "{name}: {err}"
            );
            assert_eq!(err.lines().count(), 1, "{name}: {err}");
        } else {
            assert!(o.status.success(), "{name}: {err}");
        }
    }
}

#[test]
fn a_z_up_model_stands_up() {
    let d = tempfile::tempdir().unwrap();
    // A triangle standing 2 units along z: lying on its back unless z is up.
    std::fs::write(
        d.path().join("z.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 0 2\nf 1 2 3\n",
    )
    .unwrap();
    let extent = |up: &str| {
        let scene = raylab::scene::Scene::from_toml_str(
            &format!(
                "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 0]\n[[mesh]]\nfile = \"z.obj\"\n{up}"
            ),
            "t.toml",
            d.path(),
        )
        .unwrap();
        let raylab::geometry::Shape::Mesh(mesh) = &scene.shapes[0] else {
            panic!("a mesh")
        };
        let ys = mesh.positions().iter().map(|p| p.y);
        ys.clone().fold(f32::MIN, f32::max) - ys.fold(f32::MAX, f32::min)
    };
    assert_eq!(extent(""), 0.0);
    assert!((extent("up = \"z\"\n") - 2.0).abs() < 1e-6);
    let e = common::scene_error(
        "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 1, 0]\n[[mesh]]\nfile = \"z.obj\"\nup = \"w\"\n",
        d.path(),
    );
    assert!(e.starts_with("t.toml:6:6: unknown variant `w`"), "{e}");
}
