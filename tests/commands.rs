//! The `raylab` commands besides render, sweep and bench (`scenes`, `lecture`, `fresnel`,
//! `params`, `inspect`), run as a user runs them, and the documentation of every option.
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

mod common;

use common::{fails, raylab, stderr};
use std::path::Path;
use std::process::Command;

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

#[test]
fn render_slide_makes_the_three_panes_of_regular_random_and_jittered() {
    let dir = tempfile::tempdir().unwrap();
    let n = 1 + raylab::lecture::LECTURE
        .iter()
        .position(|s| s.title == "Regular, random and jittered samples")
        .unwrap();
    let size = ["--size", "66x36", "--spp", "2", "-q"];
    let run = |args: &[&str]| {
        let o = raylab(&[args, &size[..]].concat(), dir.path());
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    };
    run(&["render", "--slide", &n.to_string(), "-o", "slide.png"]);
    let img = |f: &str| image::open(dir.path().join(f)).unwrap().to_rgb8();
    let panes: Vec<_> = ["regular", "random", "jittered"]
        .iter()
        .map(|pattern| {
            let file = format!("{pattern}.png");
            let set = format!("pattern={pattern}");
            run(&["render", "antialiasing", "--set", &set, "-o", &file]);
            img(&file)
        })
        .collect();
    let slide = img("slide.png");
    // A third of the width each, left to right, each exactly as rendered on its own.
    for y in 0..36 {
        for x in 0..66 {
            let pane = &panes[x as usize / 22];
            assert_eq!(slide.get_pixel(x, y), pane.get_pixel(x, y), "({x}, {y})");
        }
    }
    assert!(
        panes[0] != panes[1] && panes[1] != panes[2],
        "the panes differ"
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

#[test]
fn section_writes_a_pixels_tree_and_the_workbench_as_svg_and_png() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // The workbench at 30° from air into glass: θt = asin(sin 30° / 1.5) = 19.47°.
    let o = raylab(&["section", "--angle", "30", "-o", "snell.svg"], d);
    assert!(o.status.success(), "{}", stderr(&o));
    let svg = std::fs::read_to_string(d.join("snell.svg")).unwrap();
    assert!(svg.starts_with("<svg"), "{svg}");
    for text in ["θi = 30.0°", "θt = 19.5°", "η1 = 1.0", "η2 = 1.5"] {
        assert!(
            svg.contains(&format!(">{text}</text>")),
            "{text} in:\n{svg}"
        );
    }
    let o = raylab(
        &[
            "section", "--n1", "1.5", "--n2", "1", "--angle", "50", "-o", "tir.svg",
        ],
        d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let svg = std::fs::read_to_string(d.join("tir.svg")).unwrap();
    assert!(svg.contains(">total internal reflection</text>"));
    assert!(svg.contains(">critical angle 41.8°</text>"));
    // Rough: the lobes, and the title says so.
    let rough = [
        "section",
        "--angle",
        "40",
        "--roughness",
        "0.2",
        "-o",
        "rough.svg",
    ];
    let o = raylab(&rough, d);
    assert!(o.status.success(), "{}", stderr(&o));
    let svg = std::fs::read_to_string(d.join("rough.svg")).unwrap();
    assert!(svg.contains("rough: GGX α = 0.2"), "{svg}");
    fails(
        &[
            "section",
            "--angle",
            "40",
            "--roughness",
            "2",
            "-o",
            "x.svg",
        ],
        d,
        "out of range",
    );
    // A pixel's section, as a PNG of the size asked for.
    let args = [
        "section", "glass", "--pixel", "40,22", "--size", "80x45", "--figure", "480x360", "-o",
        "tree.png",
    ];
    let o = raylab(&args, d);
    assert!(o.status.success(), "{}", stderr(&o));
    let png = image::open(d.join("tree.png")).unwrap();
    assert_eq!((png.width(), png.height()), (480, 360));
    fails(
        &["section", "--angle", "30", "-o", "x.pdf"],
        d,
        "must end in .svg or .png",
    );
    fails(
        &["section", "--angle", "95", "-o", "x.svg"],
        d,
        "out of range",
    );
    fails(&["section", "glass", "-o", "x.svg"], d, "--pixel");
    fails(
        &[
            "section", "glass", "--pixel", "80,0", "--size", "80x45", "-o", "x.svg",
        ],
        d,
        "outside the 80x45 image",
    );
    assert!(!d.join("x.svg").exists() && !d.join("x.pdf").exists());
    // The lens bench of a pixel through the double Gauss: its stop, its film, its angles.
    let bench = [
        "section",
        "real-lens",
        "--pixel",
        "50,10",
        "--size",
        "96x64",
        "--lens-bench",
        "-o",
        "bench.svg",
    ];
    let o = raylab(&bench, d);
    assert!(o.status.success(), "{}", stderr(&o));
    let svg = std::fs::read_to_string(d.join("bench.svg")).unwrap();
    for text in [">stop</text>", ">film</text>", "θi/θt at each surface"] {
        assert!(svg.contains(text), "{text} in:\n{svg}");
    }
    fails(
        &[
            "section",
            "glass",
            "--pixel",
            "4,4",
            "--size",
            "80x45",
            "--lens-bench",
            "-o",
            "x.svg",
        ],
        d,
        "the camera has the thin lens",
    );
    assert!(!d.join("x.svg").exists());
}

#[test]
fn the_workbench_shows_what_raylab_fresnel_prints_at_every_angle() {
    for (n1, n2) in [("1.0", "1.5"), ("1.5", "1.0"), ("1.0", "2.42")] {
        let rows = fresnel_rows(&["fresnel", "--n1", n1, "--n2", n2, "--step", "0.5"]);
        assert_eq!(rows.len(), 181);
        for row in rows {
            let theta_i: f32 = row[0].parse().unwrap();
            if theta_i > raylab::section::MAX_ANGLE {
                continue;
            }
            let bench = raylab::section::Workbench {
                n1: n1.parse().unwrap(),
                n2: n2.parse().unwrap(),
                theta_i,
                roughness: 0.0,
            };
            let r = bench.row();
            let theta_t = r.theta_t.map(|t| format!("{t:.4}")).unwrap_or_default();
            let mine = [
                theta_t,
                format!("{:.6}", r.f_s),
                format!("{:.6}", r.f_p),
                format!("{:.6}", r.r_exact),
                format!("{:.6}", r.r_schlick),
            ];
            assert_eq!(&row[1..6], &mine[..], "{n1} -> {n2} at {theta_i}°");
        }
    }
}

#[test]
fn completions_and_the_manual_page_are_made_from_the_command_line_itself() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = |args: &[&str]| {
        let o = raylab(args, d);
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
        String::from_utf8(o.stdout).unwrap()
    };
    // Every shell's script knows the subcommands and their options, the newest too.
    for shell in ["bash", "zsh", "fish", "powershell", "elvish"] {
        let script = out(&["completions", shell]);
        // (Fish names a long option without its dashes: `-l crop`.)
        for word in ["render", "compare", "crop", "reference", "threads"] {
            assert!(script.contains(word), "{shell}: no `{word}`");
        }
    }
    let bash = out(&["completions", "bash"]);
    assert!(bash.contains("complete -F _raylab"), "{bash}");
    assert!(bash.contains("--crop") && bash.contains("--reference"));
    // The manual page: roff, titled with the version and commit `--version` prints.
    let page = out(&["man"]);
    let version = out(&["--version"]);
    let version = version.trim().strip_prefix("raylab ").unwrap();
    assert!(
        page.contains(&format!(".TH raylab 1  \"raylab {version}\"")),
        "{}",
        &page[..page.len().min(300)]
    );
    assert!(page.contains(".SH NAME") && page.contains("render"));
    fails(&["completions", "tcsh"], d, "tcsh");
}
