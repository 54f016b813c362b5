//! A seeded mutation fuzzer over everything a user hands raylab: scene files, OBJ, MTL and
//! glTF files, sidecars, `--set` assignments and image sizes, and the command line itself.
//! Mutations splice lines, cut them, insert junk, put a byte-order mark first, and
//! replace numbers with values that broke parsers before (beyond f32 and f64 among them).
//! A case fails on a panic, on a loaded scene that renders a non-finite pixel, on accepted
//! parameters that do not read back from their own sidecar unchanged, or on a case that
//! runs for more than a minute (a watchdog ends the run). Failing inputs are shrunk line
//! by line and kept in `tests/fuzz-regressions/`, which every run replays first. Kills at
//! random moments of a render's write check that no image is left beside another
//! render's sidecar and that the next write removes what a kill left.
//!
//! `cargo test --release --test fuzz` runs 10,000 cases in seconds. A longer
//! run: `RAYLAB_FUZZ_CASES=100000 RAYLAB_FUZZ_SEED=7 RAYLAB_FUZZ_KILLS=200 cargo test
//! --release --test fuzz`.
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

mod common;
#[path = "common/mutate.rs"]
mod mutate;

use common::Rng;
use mutate::{BOM, mutate};

use raylab::params::Params;
use raylab::render::{Sidecar, render};
use raylab::scene::{Scene, check_size, load_obj};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// The kinds of input, each with its seeds and how a case is run.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Target {
    Scene,
    Obj,
    Mtl,
    Sidecar,
    Params,
    Gltf,
}

const TARGETS: [Target; 6] = [
    Target::Scene,
    Target::Obj,
    Target::Mtl,
    Target::Sidecar,
    Target::Params,
    Target::Gltf,
];

impl Target {
    fn extension(self) -> &'static str {
        match self {
            Target::Scene => "toml",
            Target::Obj => "obj",
            Target::Mtl => "mtl",
            Target::Sidecar => "json",
            Target::Params => "set",
            Target::Gltf => "gltf",
        }
    }

    fn from_extension(ext: &str) -> Option<Target> {
        TARGETS.into_iter().find(|t| t.extension() == ext)
    }
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A glTF file of one triangle with a glass material, its buffer inline, a key a line.
const GLTF: &str = r#"{
"asset": {"version": "2.0"},
"extensionsUsed": ["KHR_materials_ior", "KHR_materials_transmission"],
"scene": 0,
"scenes": [{"nodes": [0]}],
"nodes": [{"mesh": 0, "translation": [0, 1, 0], "scale": [2, 2, 2]}],
"materials": [{"name": "glass", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0},
"extensions": {"KHR_materials_ior": {"ior": 1.5}, "KHR_materials_transmission": {"transmissionFactor": 1}}}],
"meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
"buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
"bufferViews": [{"buffer": 0, "byteLength": 36}],
"accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
"min": [0, 0, 0], "max": [1, 1, 0]}]
}"#;

/// A glTF file of one textured triangle (its picture a PNG data URI), seen by a camera
/// and lit by a point, a spot and a directional light, a key a line.
const GLTF_LIT: &str = r#"{
"asset": {"version": "2.0"},
"extensionsUsed": ["KHR_lights_punctual"],
"extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1, 0.8, 0.6], "intensity": 12},
{"name": "cone", "type": "spot", "intensity": 5, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}},
{"type": "directional"}]}},
"scene": 0,
"scenes": [{"nodes": [0, 1, 2, 3]}],
"nodes": [{"mesh": 0},
{"camera": 0, "translation": [0, 0, 3]},
{"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 2, 1]},
{"extensions": {"KHR_lights_punctual": {"light": 1}}, "rotation": [-0.70710677, 0, 0, 0.70710677], "children": [4]},
{"extensions": {"KHR_lights_punctual": {"light": 2}}}],
"cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 1.5, "znear": 0.1}}],
"materials": [{"name": "paint", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0,
"baseColorTexture": {"index": 0}}, "emissiveTexture": {"index": 0}, "emissiveFactor": [0, 0, 0]}],
"textures": [{"source": 0, "sampler": 0}],
"samplers": [{"wrapS": 33648, "wrapT": 33071}],
"images": [{"uri": "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAIAAAABCAIAAAB7QOjdAAAAD0lEQVR4nGN4JsLFpXECAActAf81Yl0PAAAAAElFTkSuQmCC"}],
"meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
"buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/"}],
"bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
"accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
"min": [0, 0, 0], "max": [1, 1, 0]},
{"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}]
}"#;

/// The unmutated inputs of each target.
fn seeds(target: Target) -> Vec<String> {
    let read_dir = |dir: &str, ext: &str| -> Vec<String> {
        let mut files: Vec<PathBuf> = std::fs::read_dir(repo().join(dir))
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.to_string_lossy().ends_with(ext))
            .collect();
        files.sort();
        files
            .iter()
            .map(|p| std::fs::read_to_string(p).unwrap())
            .collect()
    };
    match target {
        Target::Scene => read_dir("scenes", ".toml"),
        Target::Obj => read_dir("scenes/models", ".obj"),
        Target::Mtl => vec!["newmtl a\nKd 0.5 0.5 0.5\nKs 0.2 0.2 0.2\nNs 40\nillum 2\nnewmtl b\nKe 1 1 1\n".into()],
        Target::Sidecar => read_dir("screenshots", ".png.json"),
        Target::Gltf => vec![GLTF.into(), GLTF_LIT.into()],
        Target::Params => vec![
            "spp=4\nmax_depth=3\nmin_weight=0.01\nior=1.5\naperture=0.1\nfocus_distance=5\nshutter_open=0\nshutter=1\npattern=sobol\ntree=split\nsize=64x36".into(),
            "abbe=20\npolarizer=45\ntransport=transmissive_shadows\nior=2.4\nsize=64x36".into(),
            "transport=photons\nlight_size=0\nmax_depth=64\nabbe=30\nsize=64x36".into(),
            "transport=path\npolarizer=10\nphong_exponent=3\nsize=64x36".into(),
        ],
    }
}

/// Runs one case: Ok(true) if the input was accepted (and rendered, where it makes an
/// image), Ok(false) if it was refused; Err says what went wrong. Refusals are fine: only
/// panics (caught by the caller) and non-finite pixels fail.
fn run_case(target: Target, input: &str, dir: &Path) -> Result<bool, String> {
    let check_render = |scene: &Scene, params: &Params| -> Result<(), String> {
        // Small and cheap, whatever the input asked for; the budget bounds the tree.
        let params = Params {
            spp: params.spp.min(2),
            ..params.clone()
        };
        let (film, _) = render(scene, &params, 6, 4, &()).map_err(|e| e.to_string())?;
        match film.pixels().find(|c| !c.is_finite()) {
            Some(c) => Err(format!("non-finite pixel {c}")),
            None => Ok(()),
        }
    };
    // Accepted parameters are written to a sidecar and read back as they were: none
    // holds a number its JSON cannot say (an f32 beyond range once became `null`).
    let round_trip = |params: &Params| -> Result<(), String> {
        let json = serde_json::to_value(params).map_err(|e| e.to_string())?;
        let serde_json::Value::Object(map) = json else {
            return Err("parameters are not a JSON object".into());
        };
        match Params::from_json(&map) {
            Ok(back) if back == *params => Ok(()),
            Ok(back) => Err(format!("accepted {params:?}, read back {back:?}")),
            Err(e) => Err(format!("accepted, but its sidecar is refused: {e}")),
        }
    };
    let accepted = match target {
        Target::Scene => {
            let text = input.strip_prefix(BOM).unwrap_or(input);
            let scene = Scene::from_toml_str(text, "fuzz.toml", &repo().join("scenes"));
            if let Ok(scene) = &scene {
                round_trip(&scene.params)?;
                check_render(scene, &scene.params)?;
            }
            scene.is_ok()
        }
        Target::Obj | Target::Mtl => {
            let (obj, mtl) = match target {
                Target::Obj => (input.to_string(), seeds(Target::Mtl)[0].clone()),
                _ => (
                    "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n".to_string(),
                    input.to_string(),
                ),
            };
            let read_mtl = |_: &str| Some(mtl.as_bytes().to_vec());
            load_obj(obj.as_bytes(), "fuzz.obj", &read_mtl).is_ok()
        }
        Target::Gltf => {
            let no_files = |_: &str| Err("no files beside it".to_string());
            let model = raylab::scene::load_gltf(input.as_bytes(), "fuzz.gltf", &no_files);
            // Opened as a user opens it: its camera, lights and textures rendered.
            if model.is_ok() {
                let path = dir.join("fuzz.gltf");
                std::fs::write(&path, input).map_err(|e| e.to_string())?;
                let scene = Scene::load(&path).map_err(|e| format!("read, then refused: {e}"))?;
                check_render(&scene, &scene.params)?;
            }
            model.is_ok()
        }
        Target::Sidecar => {
            let path = dir.join("fuzz.png.json");
            std::fs::write(&path, input).map_err(|e| e.to_string())?;
            let sidecar = Sidecar::read(&path);
            if let Ok(sidecar) = &sidecar {
                check_size(sidecar.width, sidecar.height)?;
                round_trip(&sidecar.params)?;
            }
            sidecar.is_ok()
        }
        Target::Params => {
            let mut params = Params::default();
            let (sizes, sets): (Vec<&str>, Vec<&str>) =
                input.lines().partition(|l| l.starts_with("size="));
            for size in sizes {
                if let Some((w, h)) = size[5..].split_once('x') {
                    let (w, h) = (w.parse().unwrap_or(0), h.parse().unwrap_or(0));
                    let _ = check_size(w, h);
                }
            }
            let set = params.set_all(&sets);
            if set.is_ok() {
                params
                    .validate()
                    .map_err(|e| format!("accepted, then invalid: {e}"))?;
                round_trip(&params)?;
                check_render(&Scene::load("glass").map_err(|e| e.to_string())?, &params)?;
            }
            set.is_ok()
        }
    };
    Ok(accepted)
}

thread_local! {
    /// Whether this thread is running a fuzz case, and the panics seen while it was, with
    /// the last one's message: raylab catches a dependency's panic as a last line of
    /// defence, but the fuzzer counts it as a failure.
    static IN_CASE: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    static CAUGHT: std::cell::RefCell<(u64, String)> = const { std::cell::RefCell::new((0, String::new())) };
}

/// Runs a case with panics caught and counted: whether it was accepted, or what happened.
fn outcome(target: Target, input: &str, dir: &Path) -> Result<bool, String> {
    static HOOK: std::sync::Once = std::sync::Once::new();
    HOOK.call_once(|| {
        let default = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if IN_CASE.get() {
                CAUGHT.with_borrow_mut(|(n, last)| {
                    *n += 1;
                    *last = info.to_string();
                });
            } else {
                // Any other thread's panic (a failing assertion) is reported as usual.
                default(info);
            }
        }))
    });
    let before = CAUGHT.with_borrow(|(n, _)| *n);
    IN_CASE.set(true);
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        run_case(target, input, dir)
    }));
    IN_CASE.set(false);
    let (after, last) = CAUGHT.with_borrow(|(n, last)| (*n, last.clone()));
    if after != before || result.is_err() {
        return Err(format!("panicked: {last}"));
    }
    result.unwrap_or(Ok(false))
}

/// The failing input with as many lines removed as still fail.
fn shrink(target: Target, input: &str, dir: &Path) -> String {
    let mut lines: Vec<&str> = input.lines().collect();
    let mut i = 0;
    while i < lines.len() {
        let mut fewer = lines.clone();
        fewer.remove(i);
        if outcome(target, &fewer.join("\n"), dir).is_err() {
            lines = fewer;
        } else {
            i += 1;
        }
    }
    lines.join("\n")
}

fn regressions() -> PathBuf {
    repo().join("tests/fuzz-regressions")
}

/// Every kept failing input, replayed: none may fail again.
#[test]
fn kept_failures_stay_fixed() {
    let dir = tempfile::tempdir().unwrap();
    let mut files: Vec<PathBuf> = std::fs::read_dir(regressions())
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    let mut replayed = 0;
    for file in files {
        let Some(target) = file
            .extension()
            .and_then(|e| Target::from_extension(&e.to_string_lossy()))
        else {
            continue;
        };
        let input = std::fs::read_to_string(&file).unwrap();
        if let Err(e) = outcome(target, &input, dir.path()) {
            panic!("{}: {e}", file.display());
        }
        replayed += 1;
    }
    assert!(replayed >= 8, "only {replayed} kept inputs replayed");
}

#[test]
fn thousands_of_mutated_inputs_neither_panic_nor_hang_nor_render_nan() {
    let cases: u64 = common::env_number("RAYLAB_FUZZ_CASES", 10_000);
    let seed: u64 = common::env_number("RAYLAB_FUZZ_SEED", 1);
    // A watchdog: a case that runs for a minute is a hang; say which and end the run.
    static CASE: AtomicU64 = AtomicU64::new(0);
    static CURRENT: Mutex<String> = Mutex::new(String::new());
    std::thread::spawn(|| {
        let mut last = (u64::MAX, Instant::now());
        loop {
            std::thread::sleep(Duration::from_secs(1));
            let case = CASE.load(Ordering::Relaxed);
            if case != last.0 {
                last = (case, Instant::now());
            } else if last.1.elapsed() > Duration::from_secs(60) {
                let input = CURRENT.lock().map(|s| s.clone()).unwrap_or_default();
                eprintln!("fuzz case {case} hangs:\n{input}");
                std::process::abort();
            }
        }
    });
    let dir = tempfile::tempdir().unwrap();
    let seeds: Vec<(Target, Vec<String>)> = TARGETS.iter().map(|&t| (t, seeds(t))).collect();
    let mut rng = Rng(seed);
    // Per target: inputs accepted, inputs refused.
    let mut counts = [[0u64; 2]; TARGETS.len()];
    let start = Instant::now();
    for case in 0..cases {
        let (target, inputs) = &seeds[case as usize % seeds.len()];
        let input = mutate(&inputs[rng.below(inputs.len())], &mut rng);
        if let Ok(mut current) = CURRENT.lock() {
            current.clone_from(&input);
        }
        CASE.store(case, Ordering::Relaxed);
        let result = outcome(*target, &input, dir.path());
        if let Err(e) = result {
            let small = shrink(*target, &input, dir.path());
            let name = format!(
                "{:?}-{:016x}.{}",
                target,
                raylab::math::rng::mix64(case ^ seed << 32),
                target.extension()
            )
            .to_lowercase();
            let kept = regressions().join(name);
            let _ = std::fs::write(&kept, &small);
            panic!(
                "case {case} ({target:?}): {e}\nshrunk input kept in {}:\n{small}",
                kept.display()
            );
        }
        counts[case as usize % TARGETS.len()][usize::from(result == Ok(false))] += 1;
    }
    let per_target: Vec<String> = TARGETS
        .iter()
        .zip(counts)
        .map(|(t, [ok, refused])| format!("{t:?} {ok} accepted, {refused} refused"))
        .collect();
    eprintln!(
        "fuzz: {cases} cases (seed {seed}) in {:.1} s, none failed: {}",
        start.elapsed().as_secs_f64(),
        per_target.join("; ")
    );
    // Mutations that never get past the parsers would test little.
    for (t, [ok, refused]) in TARGETS.iter().zip(counts) {
        assert!(
            ok > 0 && refused > 0,
            "{t:?}: {ok} accepted, {refused} refused"
        );
    }
}

/// The command line, through the binary: every run ends with status 0, 1 or 2, and any
/// error is one line.
#[test]
fn mutated_command_lines_exit_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let base = "render\nglass\n-o\nx.png\n--size\n8x6\n--spp\n1\n--set\nmax_depth=3\n--seed\n5";
    let mut rng = Rng(99);
    for case in 0..150 {
        let line = mutate(base, &mut rng);
        // An argument cannot hold a NUL byte: no shell can pass one.
        let args: Vec<&str> = line.lines().filter(|a| !a.contains('\0')).collect();
        let o = common::raylab(&args, dir.path());
        let err = common::stderr(&o);
        let code = o.status.code();
        assert!(
            matches!(code, Some(0..=2)),
            "case {case} {args:?}: {code:?} {err}"
        );
        assert!(!err.contains("panicked"), "case {case} {args:?}: {err}");
        if code == Some(1) {
            assert_eq!(err.lines().count(), 1, "case {case} {args:?}: {err}");
        }
    }
}

/// Kills during writes: the CLI killed (SIGKILL or Ctrl-C) at moments drawn at random
/// across a render and its write. After each, the image's own parameters and its sidecar's
/// (if one is there) are the same render's, and after the last a write leaves no
/// temporary file. `RAYLAB_FUZZ_KILLS` sets how many (12 by default).
#[cfg(unix)]
#[test]
fn kills_at_random_moments_never_pair_an_image_with_another_render() {
    let kills: u64 = common::env_number("RAYLAB_FUZZ_KILLS", 12);
    let dir = tempfile::tempdir().unwrap();
    let args = |seed: u64| -> Vec<String> {
        let fixed = [
            "render", "glass", "-o", "k.png", "--size", "320x180", "--spp", "1", "-q",
        ];
        let mut args: Vec<String> = fixed.iter().map(|s| s.to_string()).collect();
        args.extend(["--seed".to_string(), seed.to_string()]);
        args
    };
    let start = Instant::now();
    let first = std::process::Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(args(0))
        .current_dir(dir.path())
        .status()
        .unwrap();
    assert!(first.success());
    let whole = start.elapsed();
    let mut rng = Rng(0x6b696c6c);
    for n in 1..=kills {
        let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_raylab"))
            .args(args(n))
            .current_dir(dir.path())
            .spawn()
            .unwrap();
        std::thread::sleep(whole.mul_f64(rng.below(1000) as f64 / 700.0));
        let signal = *rng.pick(&["-KILL", "-INT"]);
        let _ = std::process::Command::new("kill")
            .args([signal, &child.id().to_string()])
            .status();
        let _ = child.wait();
        let image = Sidecar::read(&dir.path().join("k.png")).unwrap();
        if let Ok(sidecar) = Sidecar::read(&dir.path().join("k.png.json")) {
            assert_eq!(
                image.params.seed, sidecar.params.seed,
                "kill {n} ({signal})"
            );
        }
    }
    let last = std::process::Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(args(kills + 1))
        .current_dir(dir.path())
        .status()
        .unwrap();
    assert!(last.success());
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(left.is_empty(), "{left:?}");
}
