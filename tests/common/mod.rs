//! Helpers shared by the tests: running the `raylab` binary as a user runs it, and
//! rendering on a given number of threads.

#![allow(dead_code)] // Each test file uses its own share of these.

use std::path::Path;
use std::process::{Command, Output};

/// Runs `raylab` with `args` in `cwd`.
pub fn raylab(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("the binary runs")
}

/// What the run wrote to stderr.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Runs and expects exit code 2 with one error line containing `words`.
pub fn fails(args: &[&str], cwd: &Path, words: &str) -> String {
    let o = raylab(args, cwd);
    let err = stderr(&o);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{args:?} should exit 2; stderr: {err}"
    );
    assert!(
        err.contains(words),
        "{args:?}: expected `{words}` in: {err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    err
}

/// A JSON file (a sidecar) as a value.
pub fn read_json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("the file exists"))
        .expect("the file is JSON")
}

/// The one-line error of scene `text` read as `t.toml`, its OBJ paths relative to `dir`.
pub fn scene_error(text: &str, dir: &Path) -> String {
    match raylab::scene::Scene::from_toml_str(text, "t.toml", dir) {
        Ok(_) => panic!("expected an error for:\n{text}"),
        Err(e) => {
            let s = e.to_string();
            assert!(!s.contains('\n'), "error is not one line: {s}");
            s
        }
    }
}

/// The pinhole eye ray through the centre of pixel (x, y) of a `width` × `height` image:
/// where a one-sample render with the regular pattern samples it, so a closed form can be
/// evaluated there.
pub fn pixel_centre_ray(
    frame: &raylab::camera::CameraFrame,
    (x, y): (u32, u32),
    (width, height): (u32, u32),
) -> raylab::math::Ray {
    let film = glam::Vec2::new(
        (x as f32 + 0.5) / width as f32,
        (y as f32 + 0.5) / height as f32,
    );
    frame.ray(film, glam::Vec2::ZERO, 0.0)
}

/// Runs `f` on a pool of `threads` worker threads.
pub fn in_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
        .install(f)
}

/// `params`' samples of `scene` at `size`, traced by `traversal`, in one pass.
pub fn render_by(
    traversal: raylab::tracer::Traversal,
    scene: &raylab::scene::Scene,
    params: &raylab::params::Params,
    size: (u32, u32),
) -> raylab::render::Film {
    let mut film = raylab::render::Film::new(size.0, size.1);
    raylab::render::render_pass_by(
        traversal,
        scene,
        &scene.camera,
        params,
        &mut film,
        params.spp,
        &(),
    )
    .expect("a render of a valid scene");
    film
}

/// A film's pixels as bits, for comparisons that must be exact.
pub fn bits(film: &raylab::render::Film) -> Vec<[u32; 3]> {
    film.pixels()
        .map(|c| c.to_array().map(f32::to_bits))
        .collect()
}

/// A binary glTF container: the JSON chunk (padded with spaces) and the binary chunk
/// (padded with zeros), each to 4 bytes.
pub fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut j = json.as_bytes().to_vec();
    while !j.len().is_multiple_of(4) {
        j.push(b' ');
    }
    let mut b = bin.to_vec();
    while !b.len().is_multiple_of(4) {
        b.push(0);
    }
    let total = 12 + 8 + j.len() + 8 + b.len();
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    out.extend_from_slice(&(b.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&b);
    out
}

/// SplitMix64: the fuzzers' own deterministic stream.
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        raylab::math::rng::mix64(self.0)
    }
    /// A number below `n` (0 for `n` = 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    /// One of `items`.
    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// A number from the environment variable `name`, else `default`: a fuzzer's case count
/// or seed.
pub fn env_number(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// Runs `raylab` with the words of `job` (and `-q`) in `dir` under an address space of
/// 2 GB (`ulimit -v`; the memory limit is then 1 GB), the environment's limit unset.
pub fn under_two_gigabytes(job: &str, dir: &Path) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v 2000000 && exec \"$0\" {job} -q"))
        .arg(env!("CARGO_BIN_EXE_raylab"))
        .env_remove("RAYLAB_MEMORY_LIMIT")
        .current_dir(dir)
        .output()
        .expect("sh runs")
}
