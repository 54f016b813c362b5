//! `raylab render`, `sweep` and `bench`, run as a user runs them; the other commands are in
//! commands.rs.
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

mod common;

use common::{fails, raylab, stderr};
use std::path::Path;

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
    // The summary and what was written, each within 80 columns.
    let lines: Vec<&str> = summary.lines().collect();
    assert_eq!(lines.len(), 2, "{summary}");
    assert!(lines.iter().all(|l| l.len() <= 80), "{summary}");
    for word in ["64x36", "2 spp", "M rays/s", "noise"] {
        assert!(lines[0].contains(word), "`{word}` missing from: {summary}");
    }
    assert_eq!(lines[1], "wrote a.png and a.png.json");
    // -v adds the details between them, each line within 80 columns too.
    let o = raylab(
        &[
            "render", "-o", "v.png", "--size", "64x36", "--spp", "2", "-v",
        ],
        d,
    );
    let verbose = stderr(&o);
    let lines: Vec<&str> = verbose.lines().collect();
    assert!(lines.len() >= 5, "{verbose}");
    assert!(lines.iter().all(|l| l.len() <= 80), "{verbose}");
    for word in [
        "rays/pixel",
        "total internal reflections",
        "pruned",
        "non-finite",
    ] {
        assert!(verbose.contains(word), "`{word}` missing from: {verbose}");
    }
    let img = image::open(d.join("a.png")).unwrap();
    assert_eq!((img.width(), img.height()), (64, 36));

    let sidecar: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("a.png.json")).unwrap()).unwrap();
    assert_eq!(sidecar["scene"], "builtin:default");
    assert_eq!(sidecar["raylab_version"], env!("CARGO_PKG_VERSION"));
    // The commit the binary was built from, where git knows it: this clone's HEAD.
    let head = std::process::Command::new("git")
        .args(["rev-parse", "--short=12", "HEAD"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string());
    if let Some(head) = &head {
        assert_eq!(sidecar["raylab_commit"], head.as_str());
    }
    // The PNG names its software with the same version and commit.
    let png = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(d.join("a.png")).unwrap(),
    ))
    .read_info()
    .unwrap();
    let software = png
        .info()
        .uncompressed_latin1_text
        .iter()
        .find(|t| t.keyword == "Software");
    let expected = match &head {
        Some(head) => format!("raylab {} (commit {head})", env!("CARGO_PKG_VERSION")),
        None => format!("raylab {}", env!("CARGO_PKG_VERSION")),
    };
    assert_eq!(software.map(|t| t.text.as_str()), Some(expected.as_str()));
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
        // A sweep takes --threads too.
        let sheet = format!("sheet-{out}");
        let o = raylab(
            &[
                "sweep",
                "glass",
                "--param",
                "ior=1.2,1.5",
                "--size",
                "40x30",
                "--spp",
                "4",
                "--threads",
                threads,
                "-q",
                "-o",
                &sheet,
            ],
            d,
        );
        assert!(o.status.success(), "{}", stderr(&o));
    }
    same_bytes(d, "sheet-t1.png", "sheet-t2.png");
    same_bytes(d, "t1.png", "t2.png");
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

/// A flat linear-RGB EXR of `value` everywhere, `w` × `h`, written by the image crate.
fn flat_exr(path: &Path, (w, h): (u32, u32), value: f32) {
    image::Rgb32FImage::from_pixel(w, h, image::Rgb([value; 3]))
        .save(path)
        .unwrap();
}

#[test]
fn compare_prints_the_closed_form_metrics_and_draws_the_difference() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    flat_exr(&d.join("half.exr"), (8, 4), 0.5);
    flat_exr(&d.join("quarter.exr"), (8, 4), 0.25);
    let o = raylab(&["compare", "half.exr", "quarter.exr", "-o", "diff.png"], d);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    // (0.5 − 0.25)² = 0.0625; over 0.25² + 0.01 = 0.0725.
    assert!(out.contains("MSE 6.2500e-2"), "{out}");
    assert!(
        out.contains(&format!("relative MSE {:.4e}", 0.0625 / 0.0725)),
        "{out}"
    );
    let diff = image::open(d.join("diff.png")).unwrap().into_rgb8();
    assert_eq!(diff.dimensions(), (8, 4));
    // Differing everywhere by the scale: the false colour's top everywhere.
    assert!(
        diff.pixels()
            .all(|p| p.0 == diff.get_pixel(0, 0).0 && p.0[0] > 200)
    );

    // A render against itself: nothing differs.
    let o = raylab(
        &[
            "render", "glass", "--size", "32x18", "--spp", "2", "-o", "a.png", "-q",
        ],
        d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let o = raylab(&["compare", "a.png", "a.png"], d);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("MSE 0.0000e0") && out.contains("RMS error 0.000 %"),
        "{out}"
    );

    // Images of two sizes, and a file that is not an image: one line, exit 2.
    let err = fails(&["compare", "a.png", "half.exr"], d, "32x18");
    assert!(err.contains("8x4") && err.contains("a.png") && err.contains("half.exr"));
    std::fs::write(d.join("notes.png"), "not an image").unwrap();
    fails(
        &["compare", "notes.png", "a.png"],
        d,
        "notes.png: cannot read the image",
    );
}

#[test]
fn render_with_a_reference_measures_each_pass_and_keeps_the_image() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let base = ["render", "glass", "--size", "48x27", "-q"];
    let run = |extra: &[&str]| {
        let args: Vec<&str> = base.iter().chain(extra).copied().collect();
        let o = raylab(&args, d);
        assert!(o.status.success(), "{}", stderr(&o));
        String::from_utf8_lossy(&o.stdout).into_owned()
    };
    run(&["--spp", "16", "-o", "same.exr"]);
    run(&["--spp", "256", "-o", "reference.exr"]);
    // Against itself: the last pass has no error at all.
    let out = run(&["--spp", "16", "--reference", "same.exr", "-o", "again.exr"]);
    assert!(
        out.lines().last().unwrap().contains("MSE 0.0000e0"),
        "{out}"
    );
    // Against 256 samples: a line and a sidecar entry per pass, at 1, 2, 4, 8, 16 samples,
    // the error falling with them, and the image the same as without a reference.
    let out = run(&[
        "--spp",
        "16",
        "--reference",
        "reference.exr",
        "-o",
        "measured.png",
    ]);
    assert_eq!(out.lines().count(), 5, "{out}");
    let sidecar = common::read_json(&d.join("measured.png.json"));
    let passes = sidecar["reference"]["passes"].as_array().unwrap();
    let samples: Vec<u64> = passes
        .iter()
        .map(|p| p["samples"].as_u64().unwrap())
        .collect();
    assert_eq!(samples, [1, 2, 4, 8, 16]);
    let error = |i: usize| passes[i]["rms_shown"].as_f64().unwrap();
    // 16 times the samples: at least √16 / 2 = 2 times less error, whatever the pattern.
    assert!(error(4) < error(0) / 2.0, "{passes:?}");
    run(&["--spp", "16", "-o", "plain.png"]);
    same_bytes(d, "measured.png", "plain.png");
    // A reference of another size: one line, exit 2, nothing rendered.
    fails(
        &[
            "render",
            "glass",
            "--size",
            "20x10",
            "--reference",
            "same.exr",
            "-o",
            "x.png",
        ],
        d,
        "same.exr is 48x27 and the render is 20x10",
    );
    assert!(!d.join("x.png").exists());
}

#[test]
fn a_crop_is_the_whole_renders_pixels_and_its_sidecar_renders_it_again() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let run = |extra: &[&str]| {
        let base = [
            "render",
            "depth-of-field",
            "--size",
            "64x36",
            "--spp",
            "4",
            "-q",
        ];
        let args: Vec<&str> = base.iter().chain(extra).copied().collect();
        let o = raylab(&args, d);
        assert!(o.status.success(), "{}", stderr(&o));
    };
    run(&["-o", "full.png"]);
    run(&["--crop", "10,5,50,30", "-o", "crop.png"]);
    let full = image::open(d.join("full.png")).unwrap().into_rgb8();
    let crop = image::open(d.join("crop.png")).unwrap().into_rgb8();
    assert_eq!(crop.dimensions(), (40, 25));
    for (x, y, p) in crop.enumerate_pixels() {
        assert_eq!(p, full.get_pixel(x + 10, y + 5), "({x}, {y})");
    }
    let sidecar = common::read_json(&d.join("crop.png.json"));
    assert_eq!(sidecar["crop"], serde_json::json!([10, 5, 50, 30]));
    assert_eq!(
        (sidecar["width"].as_u64(), sidecar["height"].as_u64()),
        (Some(64), Some(36))
    );
    let o = raylab(
        &["render", "--params", "crop.png", "-o", "again.png", "-q"],
        d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    same_bytes(d, "crop.png", "again.png");
    // Outside the image, not four numbers, or with adaptive sampling (which decides by
    // the whole image): one line, exit 2.
    for (crop, set, words) in [
        (
            "0,0,65,10",
            "seed=0",
            "not a rectangle inside the 64x36 image",
        ),
        ("0,0,8", "seed=0", "four whole numbers"),
        ("0,0,8,8", "noise_target=2", "noise_target=off"),
    ] {
        let args = [
            "render", "glass", "--size", "64x36", "--set", set, "--crop", crop,
        ];
        fails(&args, d, words);
    }
}

/// Asserts that files `a` and `b` of folder `d` hold the same bytes.
fn same_bytes(d: &Path, a: &str, b: &str) {
    let read = |f: &str| std::fs::read(d.join(f)).unwrap_or_else(|e| panic!("{f}: {e}"));
    assert!(read(a) == read(b), "{a} and {b} differ");
}

/// Without a display (Linux: neither DISPLAY nor WAYLAND_DISPLAY), the window cannot
/// open: one line saying what to do, no source path of the machine that built it.
#[cfg(all(target_os = "linux", feature = "gui"))]
#[test]
fn a_window_that_cannot_open_says_why_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_raylab"))
        .current_dir(dir.path())
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        // (Should a window open after all, it closes.)
        .env("RAYLAB_CLOSE_AFTER", "1")
        .output()
        .unwrap();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(
        err.starts_with("error: cannot open the window: no display to open it on"),
        "{err}"
    );
    assert!(!err.contains(".rs:") && !err.contains(".cargo"), "{err}");
}
