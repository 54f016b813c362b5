//! The `raylab` binary, run as a user runs it.
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

mod common;

use common::{fails, raylab, stderr};
use std::path::Path;
use std::process::Command;

#[test]
fn render_writes_the_image_and_a_sidecar_that_reproduces_it() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let o = raylab(
        &[
            "render",
            "-o",
            "a.png",
            "--size",
            "64x36",
            "--spp",
            "2",
            "--set",
            "max_depth=3",
        ],
        d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let summary = stderr(&o);
    assert_eq!(summary.lines().count(), 1, "one summary line: {summary}");
    for word in [
        "64x36",
        "2 spp",
        "rays/s",
        "rays/pixel",
        "pruned",
        "wrote a.png",
    ] {
        assert!(summary.contains(word), "`{word}` missing from: {summary}");
    }
    let img = image::open(d.join("a.png")).unwrap();
    assert_eq!((img.width(), img.height()), (64, 36));

    let sidecar: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("a.png.json")).unwrap()).unwrap();
    assert_eq!(sidecar["scene"], "builtin:default");
    assert_eq!(sidecar["raylab_version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(
        (sidecar["width"].as_u64(), sidecar["height"].as_u64()),
        (Some(64), Some(36))
    );
    assert_eq!(sidecar["params"]["spp"], 2);
    assert_eq!(sidecar["params"]["max_depth"], 3);
    assert_eq!(sidecar["params"]["seed"], 0);

    // From another folder, the sidecar alone reproduces the image bit for bit.
    let other = tempfile::tempdir().unwrap();
    let json = d.join("a.png.json");
    let o = raylab(
        &[
            "render",
            "--params",
            json.to_str().unwrap(),
            "-o",
            "again.png",
            "-q",
        ],
        other.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        std::fs::read(d.join("a.png")).unwrap(),
        std::fs::read(other.path().join("again.png")).unwrap()
    );
}

#[test]
fn thread_count_does_not_change_a_single_byte() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (threads, out) in [("1", "t1.png"), ("2", "t2.png")] {
        let o = raylab(
            &[
                "render",
                "bunny",
                "-o",
                out,
                "--size",
                "80x60",
                "--spp",
                "4",
                "--threads",
                threads,
                "-q",
            ],
            d,
        );
        assert!(o.status.success(), "{}", stderr(&o));
    }
    assert_eq!(
        std::fs::read(d.join("t1.png")).unwrap(),
        std::fs::read(d.join("t2.png")).unwrap()
    );
}

#[test]
fn a_scene_file_renders_and_exr_holds_linear_radiance() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("flat.toml"),
        "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n[background]\ncolor = [2.5, 0.5, 0.25]\n",
    )
    .unwrap();
    let o = raylab(
        &[
            "render",
            "flat.toml",
            "-o",
            "flat.exr",
            "--size",
            "8x4",
            "--spp",
            "1",
        ],
        d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let img = image::open(d.join("flat.exr")).unwrap().to_rgb32f();
    assert_eq!(
        img.get_pixel(3, 2).0,
        [2.5, 0.5, 0.25],
        "EXR keeps radiance above 1, unclamped"
    );
    let sidecar = std::fs::read_to_string(d.join("flat.exr.json")).unwrap();
    assert!(sidecar.contains("flat.toml"), "{sidecar}");
}

#[test]
fn bad_input_exits_2_with_one_clear_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fails(
        &["render", "-o", "x.png", "--set", "max_dpeth=3"],
        d,
        "unknown parameter `max_dpeth`",
    );
    fails(
        &["render", "-o", "x.png", "--set", "min_weight=2"],
        d,
        "min_weight",
    );
    fails(&["render", "-o", "x.png", "--set", "spp"], d, "NAME=VALUE");
    fails(&["render", "-o", "x.png", "--spp", "0"], d, "spp");
    fails(
        &["render", "-o", "x.png", "--size", "0x10"],
        d,
        "between 1 and 16384",
    );
    fails(&["render", "-o", "x.png", "--size", "big"], d, "WxH");
    fails(&["render", "-o", "x.png", "--threads", "0"], d, "threads");
    fails(&["render", "-o", "x.jpg"], d, ".png or .exr");
    fails(&["render", "-o", "no/such/dir/x.png"], d, "does not exist");
    fails(
        &["render", "nowhere.toml", "-o", "x.png"],
        d,
        "nowhere.toml: no such scene file",
    );
    fails(
        &["render", "--params", "missing.json", "-o", "x.png"],
        d,
        "missing.json",
    );
    std::fs::write(
        d.join("bad.json"),
        "{ \"scene\": \"default\",\n  \"widht\": 3 }",
    )
    .unwrap();
    fails(
        &["render", "--params", "bad.json", "-o", "x.png"],
        d,
        "bad.json:2:",
    );
    std::fs::write(
        d.join("typo.toml"),
        "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfvo = 40\n",
    )
    .unwrap();
    fails(
        &["render", "typo.toml", "-o", "x.png"],
        d,
        "typo.toml:4:1: unknown field `fvo`",
    );
    assert!(!d.join("x.png").exists(), "nothing is written on error");
}

#[test]
fn scenes_lists_every_built_in_scene_and_scene_file_with_its_description() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let o = raylab(&["scenes"], repo);
    assert!(o.status.success());
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    let line = |start: &str| {
        out.lines()
            .find(|l| l.split_whitespace().next() == Some(start))
            .unwrap_or_else(|| panic!("`{start}` not listed:\n{out}"))
    };
    for b in raylab::scene::BUILTIN_SCENES {
        let l = line(b.name);
        assert!(
            l.contains(&b.description()) && l.ends_with("(built in)"),
            "{l}"
        );
        let file = format!("scenes{}{}.toml", std::path::MAIN_SEPARATOR, b.name);
        assert!(line(&file).contains(&b.description()), "{file}");
    }
    // Run elsewhere, only the built-in scenes.
    let dir = tempfile::tempdir().unwrap();
    let o = raylab(&["scenes"], dir.path());
    let listed = String::from_utf8_lossy(&o.stdout).lines().count();
    assert_eq!(listed, raylab::scene::BUILTIN_SCENES.len());
}

#[test]
fn lecture_lists_the_slides_and_render_slide_makes_the_windows_split() {
    let dir = tempfile::tempdir().unwrap();
    let o = raylab(&["lecture"], dir.path());
    assert!(o.status.success());
    let list = String::from_utf8_lossy(&o.stdout).into_owned();
    let lines: Vec<&str> = list.lines().collect();
    assert!(lines.len() >= 13, "{list}");
    assert!(lines[0].trim_start().starts_with("1. "), "{list}");
    let split = lines
        .iter()
        .position(|l| l.contains("What the ray tree misses"))
        .expect("the A/B slide is listed")
        + 1;
    // The split slide: its left half is the lecture's tracer, its right half path tracing
    // with photons, each exactly as rendered on its own.
    let n = split.to_string();
    let size = ["--size", "64x36", "--spp", "2", "-q"];
    let run = |args: &[&str]| {
        let o = raylab(&[args, &size[..]].concat(), dir.path());
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    };
    run(&["render", "--slide", &n, "-o", "slide.png"]);
    assert!(
        !dir.path().join("slide.png.json").exists(),
        "no sidecar for a split"
    );
    run(&["render", "default", "-o", "a.png"]);
    run(&[
        "render",
        "default",
        "--set",
        "transport=photons",
        "-o",
        "b.png",
    ]);
    let img = |f: &str| image::open(dir.path().join(f)).unwrap().to_rgb8();
    let (slide, a, b) = (img("slide.png"), img("a.png"), img("b.png"));
    for y in 0..36 {
        for x in 0..64 {
            let want = if x < 32 {
                a.get_pixel(x, y)
            } else {
                b.get_pixel(x, y)
            };
            assert_eq!(slide.get_pixel(x, y), want, "({x}, {y})");
        }
    }
    assert_ne!(a, b, "the two sides differ");
    // --caption adds the caption under the same picture, in a strip of its own.
    run(&["render", "--slide", &n, "--caption", "-o", "captioned.png"]);
    let captioned = img("captioned.png");
    assert_eq!(captioned.width(), 64);
    assert!(
        captioned.height() > 36 + 12,
        "a strip of text under the image"
    );
    for y in 0..36 {
        for x in 0..64 {
            assert_eq!(captioned.get_pixel(x, y), slide.get_pixel(x, y));
        }
    }
    let lit = (36..captioned.height())
        .flat_map(|y| (0..64).map(move |x| (x, y)))
        .filter(|&(x, y)| captioned.get_pixel(x, y).0[0] > 128)
        .count();
    assert!(lit > 50, "text drawn: {lit} bright pixels");
    // Text cannot go into a file of linear radiance.
    fails(
        &["render", "--slide", &n, "--caption", "-o", "x.exr"],
        dir.path(),
        "needs a .png output",
    );
    // A slide that is not there is bad input, said once.
    fails(
        &["render", "--slide", "99", "-o", "x.png"],
        dir.path(),
        "there is no slide 99",
    );
}

fn fresnel_rows(args: &[&str]) -> Vec<Vec<String>> {
    csv_rows(
        args,
        "theta_i_deg,theta_t_deg,f_s,f_p,r_exact,r_schlick,r_schlick_naive",
    )
}

/// The rows of the CSV `raylab args` prints under `header`.
fn csv_rows(args: &[&str], header: &str) -> Vec<Vec<String>> {
    let o = raylab(args, Path::new("."));
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some(header));
    lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

#[test]
fn fresnel_prints_a_conductors_curves_per_channel() {
    let (eta, k) = ([0.18f64, 0.42, 1.37], [3.42f64, 2.35, 1.77]);
    let rows = csv_rows(
        &[
            "fresnel",
            "--eta",
            "0.18,0.42,1.37",
            "--k",
            "3.42,2.35,1.77",
            "--step",
            "5",
        ],
        "theta_i_deg,r_exact_r,r_exact_g,r_exact_b,r_s_r,r_s_g,r_s_b,r_p_r,r_p_g,r_p_b",
    );
    assert_eq!(rows.len(), 19);
    let value = |row: &[String], i: usize| row[i].parse::<f64>().unwrap();
    for c in 0..3 {
        // Head-on: ((η − 1)² + κ²) / ((η + 1)² + κ²), and s = p.
        let r0 = ((eta[c] - 1.0).powi(2) + k[c] * k[c]) / ((eta[c] + 1.0).powi(2) + k[c] * k[c]);
        for i in [1 + c, 4 + c, 7 + c] {
            assert!((value(&rows[0], i) - r0).abs() < 2e-6, "{:?}", rows[0]);
        }
        // Grazing: everything reflected; in between R_p ≤ R ≤ R_s.
        assert_eq!(value(&rows[18], 1 + c), 1.0);
        for row in &rows[1..18] {
            assert!(
                value(row, 7 + c) <= value(row, 1 + c) && value(row, 1 + c) <= value(row, 4 + c)
            );
        }
    }
    fails(
        &["fresnel", "--eta", "1,2", "--k", "1,1,1"],
        Path::new("."),
        "three numbers",
    );
    fails(&["fresnel", "--eta", "1,2,3"], Path::new("."), "--k");
}

#[test]
fn fresnel_prints_a_measured_metal_by_name() {
    let header = "theta_i_deg,r_exact_r,r_exact_g,r_exact_b,r_s_r,r_s_g,r_s_b,r_p_r,r_p_g,r_p_b";
    let copper = raylab::material::metal("copper").unwrap();
    let by_name = csv_rows(&["fresnel", "--metal", "copper", "--step", "10"], header);
    let fmt = |v: [f32; 3]| v.map(|x| x.to_string()).join(",");
    let by_index = csv_rows(
        &[
            "fresnel",
            "--eta",
            &fmt(copper.eta),
            "--k",
            &fmt(copper.k),
            "--step",
            "10",
        ],
        header,
    );
    assert_eq!(by_name, by_index);
    fails(
        &["fresnel", "--metal", "brass"],
        Path::new("."),
        "unknown metal `brass` (known: gold, silver, copper",
    );
    fails(
        &[
            "fresnel", "--metal", "gold", "--eta", "1,1,1", "--k", "1,1,1",
        ],
        Path::new("."),
        "cannot be used with",
    );
}

#[test]
fn fresnel_prints_the_curves_as_csv() {
    let rows = fresnel_rows(&["fresnel", "--n1", "1.0", "--n2", "1.5"]);
    assert_eq!(
        rows.len(),
        91,
        "0 to 90 degrees inclusive in 1-degree steps"
    );
    let num = |r: &Vec<String>, k: usize| r[k].parse::<f64>().unwrap();
    assert_eq!(num(&rows[0], 0), 0.0);
    assert!((num(&rows[0], 4) - 0.04).abs() < 1e-6, "R0 = 4%");
    assert!((num(&rows[90], 4) - 1.0).abs() < 1e-6, "R = 1 at grazing");
    // F_p changes sign at Brewster's angle, 56.31 degrees.
    assert!(num(&rows[56], 3) > 0.0 && num(&rows[57], 3) < 0.0);
    // Snell: sin θt = sin θi / 1.5.
    let theta_t = num(&rows[30], 1).to_radians();
    assert!((theta_t.sin() - 0.5 / 1.5).abs() < 1e-4);

    // Inside out: theta_t is empty and R = 1 beyond the critical angle, 41.81 degrees.
    let rows = fresnel_rows(&["fresnel", "--n1", "1.5", "--n2", "1.0", "--step", "0.5"]);
    assert_eq!(rows.len(), 181);
    let at = |deg: f64| rows.iter().find(|r| num(r, 0) == deg).unwrap();
    assert!(!at(41.5)[1].is_empty());
    assert!(at(42.0)[1].is_empty());
    assert_eq!(num(at(42.0), 4), 1.0);
    assert_eq!(num(at(42.0), 5), 1.0);
    // Naive Schlick is still near R0 just below the critical angle.
    assert!(num(at(41.5), 6) < 0.1 && num(at(41.5), 4) > 0.3);

    // A step that does not divide 90 still ends at 90.
    let rows = fresnel_rows(&["fresnel", "--step", "7"]);
    assert_eq!(rows.last().map(|r| r[0].as_str()), Some("90"));

    fails(&["fresnel", "--n2", "9"], Path::new("."), "out of range");
    fails(&["fresnel", "--step", "0"], Path::new("."), "out of range");
}

#[test]
fn bench_reports_latency_pass_time_and_rays_per_second() {
    let o = raylab(
        &[
            "bench",
            "--size",
            "64x36",
            "--changes",
            "5",
            "--threads",
            "1",
        ],
        Path::new("."),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("change -> first frame: median"), "{out}");
    assert!(
        out.contains("p95")
            && out.contains("1-spp pass")
            && out.contains("M samples/s")
            && out.contains("M rays/s"),
        "{out}"
    );
}

#[test]
fn sweep_writes_a_labelled_contact_sheet() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let o = raylab(
        &[
            "sweep",
            "glazed",
            "--param",
            "fresnel=constant,exact",
            "--size",
            "60x40",
            "-o",
            "sheet.png",
        ],
        d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let sheet = image::open(d.join("sheet.png")).unwrap();
    // Two tiles of 60×40 with 8-pixel gaps, and a 16-pixel label band (a tenth of the
    // tile, at least 16).
    assert_eq!(
        (sheet.width(), sheet.height()),
        (2 * 60 + 3 * 8, 40 + 16 + 2 * 8)
    );
    // Without -o: SCENE-PARAM.png here, then numbered rather than replaced; -q says
    // nothing.
    let sweep = [
        "sweep", "glazed", "--param", "spp=1,2", "--size", "16x9", "-q",
    ];
    for expected in ["glazed-spp.png", "glazed-spp-2.png"] {
        let o = raylab(&sweep, d);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(stderr(&o).is_empty(), "{}", stderr(&o));
        assert!(d.join(expected).is_file(), "{expected}");
    }
    // As an animation: one labelled frame per value; --spp and --seed apply to each.
    let o = raylab(
        &[
            "sweep",
            "glazed",
            "--param",
            "max_depth=1,2,3",
            "--size",
            "32x18",
            "--spp",
            "2",
            "--seed",
            "3",
            "-o",
            "deck.gif",
        ],
        d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    use image::AnimationDecoder;
    let gif = std::fs::File::open(d.join("deck.gif")).unwrap();
    let frames = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(gif))
        .unwrap()
        .into_frames()
        .collect_frames()
        .unwrap();
    assert_eq!(frames.len(), 3);
    assert_eq!(frames[0].buffer().dimensions(), (32, 18 + 16));
    fails(
        &["sweep", "glazed", "--param", "spp=1", "-o", "x.jpg"],
        d,
        ".png contact sheet or a .gif animation",
    );
    fails(
        &["sweep", "glazed", "--param", "fresnel=fancy", "-o", "x.png"],
        d,
        "fresnel",
    );
    fails(
        &["sweep", "glazed", "--param", "nope=1", "-o", "x.png"],
        d,
        "unknown parameter",
    );
    fails(
        &["sweep", "glazed", "--param", "spp", "-o", "x.png"],
        d,
        "NAME=VALUE",
    );
    assert!(!d.join("x.png").exists());
}

#[test]
fn params_prints_every_parameter_with_its_default_and_range() {
    let dir = tempfile::tempdir().unwrap();
    let o = raylab(&["params"], dir.path());
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    for spec in raylab::params::TABLE {
        let line = out
            .lines()
            .find(|l| l.split_whitespace().next() == Some(spec.name))
            .unwrap_or_else(|| panic!("no line for {}:\n{out}", spec.name));
        assert!(line.contains(&spec.range_text()), "{line}");
    }
    assert!(
        out.lines()
            .any(|l| l.starts_with("min_weight") && l.contains("0.001"))
    );
    let md = raylab(&["params", "--markdown"], dir.path());
    assert_eq!(
        String::from_utf8_lossy(&md.stdout),
        raylab::params::markdown_table()
    );
}

#[test]
fn a_reader_that_stops_early_ends_the_program_quietly() {
    // `raylab fresnel --step 0.01 | head -1`: 9001 rows, far more than a pipe holds, and
    // nobody reads them: the program must end without a panic or an error.
    let dir = tempfile::tempdir().unwrap();
    for args in [&["fresnel", "--step", "0.01"][..], &["params"][..]] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_raylab"))
            .args(args)
            .current_dir(dir.path())
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("the binary runs");
        drop(child.stdout.take());
        let o = child.wait_with_output().unwrap();
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).is_empty(), "{args:?}: {}", stderr(&o));
    }
}

#[test]
fn render_without_o_names_the_image_after_the_scene_and_never_replaces_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("glass.png"), b"the user's own").unwrap();
    let o = raylab(&["render", "glass", "--size", "16x9", "--spp", "1"], d);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("wrote glass-2.png"), "{}", stderr(&o));
    assert_eq!(
        std::fs::read(d.join("glass.png")).unwrap(),
        b"the user's own"
    );
    assert!(d.join("glass-2.png.json").is_file());
    let o = raylab(&["render", "--slide", "2", "--size", "16x9", "-q"], d);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(d.join("slide-2.png").is_file());
}

#[test]
fn a_model_format_raylab_does_not_read_is_named_as_such() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for name in ["bunny.ply", "scene.pbrt", "model.fbx"] {
        std::fs::write(d.join(name), "ply\nformat ascii 1.0\n").unwrap();
        let err = fails(&["render", name, "-o", "x.png"], d, "unsupported format");
        assert!(err.contains(name), "{err}");
        assert!(!err.contains("TOML"), "{err}");
    }
    assert!(!d.join("x.png").exists());
}

#[test]
fn inspect_prints_the_tree_of_the_sample_render_traces() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let args = ["inspect", "glass", "--pixel", "40,22", "--size", "80x45"];
    let o = raylab(&args, d);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    let mut lines = text.lines();
    assert!(
        lines
            .next()
            .unwrap()
            .starts_with("glass 80x45, pixel (40, 22), sample 0")
    );
    assert!(
        lines
            .next()
            .unwrap()
            .starts_with("Camera ray, level 0: glass sphere (glass)"),
        "{text}"
    );
    assert!(text.contains("R exact, Schlick"), "{text}");
    assert!(text.contains("  Refract ray, level 1"), "{text}");

    // As JSON: the radiance is the pixel's value in a 1-sample render, bit for bit.
    let o = raylab(&[&args[..], &["--json", "--set", "spp=1"]].concat(), d);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let rays = json["rays"].as_array().unwrap();
    assert!(rays.len() > 3);
    assert_eq!(rays[0]["kind"], "Camera");
    assert!(rays[1..].iter().all(|r| r["parent"].is_u64()));
    let o = raylab(
        &[
            "render", "glass", "--size", "80x45", "--spp", "1", "-q", "-o", "g.exr",
        ],
        d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    // The EXR's header carries the parameters it was rendered with.
    let meta = exr::meta::MetaData::read_from_file(d.join("g.exr"), false).unwrap();
    let spp = meta.headers[0]
        .own_attributes
        .other
        .get(&exr::meta::attribute::Text::from("raylab:spp"));
    assert!(
        matches!(spp, Some(exr::meta::attribute::AttributeValue::Text(t)) if t == "1"),
        "{spp:?}"
    );
    let image = image::open(d.join("g.exr")).unwrap().into_rgb32f();
    let pixel = image.get_pixel(40, 22).0;
    for (c, value) in pixel.iter().enumerate() {
        assert_eq!(
            json["radiance"][c].as_f64().unwrap() as f32,
            *value,
            "channel {c}"
        );
    }
    fails(
        &["inspect", "glass", "--pixel", "80,0", "--size", "80x45"],
        d,
        "outside the 80x45 image",
    );
    fails(&["inspect", "glass", "--pixel", "3"], d, "X,Y");
}

/// The long options a `--help` text lists (`--spp <N>` gives `--spp`), but `--help`.
fn long_options(help: &str) -> Vec<String> {
    help.lines()
        .map(str::trim_start)
        .filter(|l| l.starts_with('-'))
        .filter_map(|l| l.split([' ', ',']).find(|w| w.starts_with("--")))
        .map(|w| w.split('=').next().unwrap_or(w).to_string())
        .filter(|w| w != "--help" && w != "--version")
        .collect()
}

/// Whether `text` has `option` as a whole word (`--spp`, not `--spp-max`).
fn mentions(text: &str, option: &str) -> bool {
    text.match_indices(option).any(|(i, _)| {
        !text[i + option.len()..]
            .chars()
            .next()
            .is_some_and(|c| c.is_alphanumeric() || c == '-' || c == '_')
    })
}

#[test]
fn the_docs_name_every_subcommand_and_option_the_help_lists() {
    let dir = tempfile::tempdir().unwrap();
    let docs = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/cli.md");
    let readme = std::fs::read_to_string(docs).unwrap();
    let top = String::from_utf8_lossy(&raylab(&["--help"], dir.path()).stdout).into_owned();
    let commands: Vec<String> = top
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .filter(|c| c != "help")
        .collect();
    assert!(commands.len() >= 8, "{commands:?}");
    let mut missing = Vec::new();
    for c in &commands {
        if !readme.contains(&format!("-- {c}")) && !readme.contains(&format!("raylab {c}")) {
            missing.push(format!("the subcommand `{c}`"));
        }
        let help = raylab(&[c.as_str(), "--help"], dir.path());
        for option in long_options(&String::from_utf8_lossy(&help.stdout)) {
            if !mentions(&readme, &option) {
                missing.push(format!("`{c} {option}`"));
            }
        }
    }
    for option in long_options(&top) {
        if !mentions(&readme, &option) {
            missing.push(format!("`raylab {option}`"));
        }
    }
    assert!(
        missing.is_empty(),
        "docs/cli.md does not mention: {missing:?}"
    );
}
