//! The documentation says what raylab does: every `raylab` command in README.md and docs/
//! runs (but those that open the window), the lecture page holds the slides as the code
//! has them, and the scene format's page states the defaults the loader uses.
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

mod common;

use raylab::material::Material;
use raylab::math::Color;
use raylab::scene::Scene;
use std::path::{Path, PathBuf};

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The page's text, its line ends as the code writes them.
fn read(page: &str) -> String {
    line_ends(&std::fs::read_to_string(repo().join(page)).unwrap_or_else(|e| panic!("{page}: {e}")))
}

/// `text` with LF line ends: a checkout may end lines with CR LF (.gitattributes asks for
/// LF, but an archive or an editor may not keep it).
fn line_ends(text: &str) -> String {
    text.replace("\r\n", "\n")
}

#[test]
fn the_checks_read_a_page_with_cr_lf_line_ends_as_the_page() {
    for page in RUN.iter().chain(&["docs/scenes.md"]) {
        let lf = read(page);
        let crlf = lf.replace('\n', "\r\n");
        assert_eq!(line_ends(&crlf), lf, "{page}");
        assert_eq!(shell_lines(&crlf), shell_lines(&lf), "{page}");
        assert!(
            !shell_lines(&crlf).iter().any(|l| l.contains('\r')),
            "{page}"
        );
    }
}

/// The lines of the page's ```sh blocks, comments cut off, blank lines left out.
fn shell_lines(text: &str) -> Vec<String> {
    let mut lines = Vec::new();
    let mut inside = false;
    for line in text.lines() {
        let trimmed = line.trim();
        if trimmed.starts_with("```") {
            inside = !inside && trimmed == "```sh";
            continue;
        }
        if inside {
            let command = trimmed.split(" #").next().unwrap_or_default().trim();
            if !command.is_empty() {
                lines.push(command.to_string());
            }
        }
    }
    lines
}

/// The arguments of a `raylab` command line that does not open the window (a subcommand
/// follows), or `None` for any other line.
fn raylab_args(line: &str) -> Option<Vec<String>> {
    let line = line
        .strip_prefix("cargo run --release -- ")
        .map(|rest| format!("raylab {rest}"))
        .unwrap_or_else(|| line.to_string());
    let words: Vec<String> = line.split_whitespace().map(String::from).collect();
    const COMMANDS: &[&str] = &[
        "render", "scenes", "params", "fresnel", "sweep", "bench", "lecture", "inspect", "compare",
    ];
    match words.as_slice() {
        [first, command, ..] if first == "raylab" && COMMANDS.contains(&command.as_str()) => {
            Some(words[1..].to_vec())
        }
        _ => None,
    }
}

/// Copies the folder `from` into `to`, recursively.
fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap().flatten() {
        let target = to.join(entry.file_name());
        if entry.path().is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), target).unwrap();
        }
    }
}

/// Runs every `raylab` command of `page`, in order, in a folder of its own holding a copy
/// of `scenes/` (as the repository's folder does), and expects each to succeed.
fn commands_of_page_run(page: &str) {
    let dir = tempfile::tempdir().unwrap();
    copy_dir(&repo().join("scenes"), &dir.path().join("scenes"));
    let mut ran = 0;
    for line in shell_lines(&read(page)) {
        let Some(args) = raylab_args(&line) else {
            continue;
        };
        assert!(
            !line.contains(['|', '>', '<', '&', ';']),
            "{page}: `{line}`: write commands the test can run as they are"
        );
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = common::raylab(&args, dir.path());
        assert!(
            o.status.success(),
            "{page}: `{line}` failed: {}",
            common::stderr(&o)
        );
        ran += 1;
    }
    assert!(ran > 0, "{page} has no raylab command");
}

#[test]
fn the_readme_commands_run() {
    commands_of_page_run("README.md");
}

#[test]
fn the_command_line_page_commands_run() {
    commands_of_page_run("docs/cli.md");
}

#[test]
fn the_lecture_page_commands_run() {
    commands_of_page_run("docs/lecture.md");
}

#[test]
fn the_parameter_page_commands_run() {
    commands_of_page_run("docs/parameters.md");
}

#[test]
fn the_window_page_commands_run() {
    commands_of_page_run("docs/window.md");
}

#[test]
fn the_performance_page_commands_run() {
    commands_of_page_run("docs/performance.md");
}

/// The pages whose commands the tests above run.
const RUN: &[&str] = &[
    "README.md",
    "docs/cli.md",
    "docs/lecture.md",
    "docs/parameters.md",
    "docs/window.md",
    "docs/performance.md",
];

#[test]
fn every_page_with_a_raylab_command_is_run() {
    let mut pages = vec!["README.md".to_string()];
    for entry in std::fs::read_dir(repo().join("docs")).unwrap().flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.ends_with(".md") {
            pages.push(format!("docs/{name}"));
        }
    }
    for page in pages {
        let commands = shell_lines(&read(&page))
            .iter()
            .filter(|l| raylab_args(l).is_some())
            .count();
        assert!(
            commands == 0 || RUN.contains(&page.as_str()),
            "{page} has {commands} raylab commands that no test runs"
        );
    }
}

#[test]
fn the_lecture_page_holds_every_slide_as_the_code_has_it() {
    let slides = raylab::lecture::markdown().unwrap();
    assert!(
        read("docs/lecture.md").contains(&slides),
        "docs/lecture.md differs from the lecture in src/lecture/slides.rs; paste the output \
         of `raylab lecture --markdown`:\n{slides}"
    );
}

/// The row of the scene page's table whose first cell is `key` (in backticks).
fn row<'a>(page: &'a str, key: &str) -> &'a str {
    let start = format!("| `{key}` |");
    page.lines()
        .find(|l| l.starts_with(&start))
        .unwrap_or_else(|| panic!("docs/scenes.md has no row for `{key}`"))
}

/// The scene `body` (tables after a camera) loaded from text.
fn scene(body: &str) -> Scene {
    let text = format!("[camera]\nposition = [0.0, 1.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\n{body}");
    Scene::from_toml_str(&text, "t.toml", Path::new(".")).unwrap()
}

#[test]
fn the_scene_page_states_the_defaults_the_loader_uses() {
    let page = read("docs/scenes.md");
    let bare = scene("");
    // What the page says of each key left out, and what the loader makes of it.
    assert!(row(&page, "fov").contains("default 45"));
    assert_eq!(bare.camera.fov_deg, 45.0);
    assert!(row(&page, "width`, `height").contains("default 640 × 360"));
    assert_eq!((bare.width, bare.height), (640, 360));
    assert!(row(&page, "ambient").contains("Default black"));
    assert_eq!(bare.ambient, Color::ZERO);
    assert!(row(&page, "medium_ior").contains("1.0 (air, the default)"));
    assert_eq!(bare.medium_ior, 1.0);

    let material = |def: &str| {
        let s = scene(&format!(
            "[material.m]\n{def}\n[[sphere]]\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nmaterial = \"m\"\n"
        ));
        s.materials[s.object_materials[0] as usize].clone()
    };
    let diffuse = row(&page, "diffuse");
    assert!(diffuse.contains("`specular` ([r, g, b] reflectance 0..1, default 0)"));
    assert!(diffuse.contains("`exponent` (> 0, default 20)"));
    let Material::Diffuse(d) = material("type = \"diffuse\"\ncolor = [0.5, 0.5, 0.5]") else {
        panic!("a diffuse material");
    };
    assert_eq!((d.specular, d.exponent), (Color::ZERO, 20.0));
    // The highlight's reflectance is a colour, as the page says.
    let Material::Diffuse(d) =
        material("type = \"diffuse\"\ncolor = [0.5, 0.5, 0.5]\nspecular = [0.1, 0.2, 0.3]")
    else {
        panic!("a diffuse material");
    };
    assert_eq!(d.specular, Color::new(0.1, 0.2, 0.3));

    let dielectric = row(&page, "dielectric");
    for said in [
        "`fresnel` (default `exact`)",
        "`constant_reflectance` (0..1, default 0.04)",
        "default 0), `abbe` (0..100, default 0), `roughness` (0..1, default 0), `ior_fixed` (default false)",
    ] {
        assert!(dielectric.contains(said), "{said}");
    }
    let Material::Dielectric(g) = material("type = \"dielectric\"\nior = 1.5") else {
        panic!("a dielectric");
    };
    assert_eq!(g.fresnel, raylab::optics::FresnelMode::Exact);
    assert_eq!((g.constant_reflectance, g.abbe), (0.04, 0.0));
    assert_eq!(g.roughness, 0.0);
    assert_eq!((g.absorption, g.ior_fixed), (Color::ZERO, false));

    assert!(row(&page, "glazed").contains("`ior` (default 1.5)"));
    let Material::Glazed(z) = material("type = \"glazed\"\ncolor = [0.0, 0.0, 0.0]") else {
        panic!("a glaze");
    };
    assert_eq!(z.coat.ior, 1.5);

    assert!(row(&page, "emissive").contains("`strength` (≥ 0, default 1)"));
    let Material::Emissive(e) = material("type = \"emissive\"\ncolor = [2.0, 3.0, 4.0]") else {
        panic!("an emitter");
    };
    assert_eq!(
        e.radiance,
        raylab::material::Texture::Solid(Color::new(2.0, 3.0, 4.0))
    );
}

#[test]
fn the_scene_page_example_loads() {
    let page = read("docs/scenes.md");
    let example = page
        .split("```toml\n")
        .nth(1)
        .and_then(|rest| rest.split("```").next())
        .expect("the page's example");
    let scene = Scene::from_toml_str(example, "example.toml", Path::new("."))
        .unwrap_or_else(|e| panic!("the example: {e}"));
    assert_eq!((scene.width, scene.height), (960, 540));
    assert_eq!(scene.params.spp, 16);
}
