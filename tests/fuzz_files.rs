//! Generated glTF node graphs and output paths (issue 52), beside the mutation fuzzer of
//! `fuzz.rs`.
//!
//! Node graphs: random trees, some broken on purpose (a child listed twice or by two
//! parents, a cycle, a node its own child, a scene listing a child or a root twice, an
//! index past the end), chains thousands deep. A graph is accepted exactly when it is a
//! set of trees (judged here independently, by in-degrees and reachability), and then
//! every node that names the mesh places it once; no case panics or hangs.
//!
//! Output paths: an image and its sidecar written (the library's `write_png`) where the
//! image and the sidecar are each one of a new name, a file, a read-only file, a folder,
//! a FIFO, a device node, or a link to a file, to nothing, to a folder, to a FIFO, to a
//! device, or to itself. Nothing but the two outputs and the files their links point to
//! may change, no temporary file is left, a device stays a device, and a write either
//! succeeds (the image readable where it went) or leaves the old pair (or, if the sidecar
//! alone failed, the new image without a sidecar).
//!
//! `cargo test --release --test fuzz_files` runs 2,000 cases of each; longer:
//! `RAYLAB_FUZZ_CASES=100000 RAYLAB_FUZZ_SEED=7 cargo test --release --test fuzz_files`.
#![allow(clippy::unwrap_used)]
// The output paths are generated where the system has FIFOs, devices and links.
#![cfg_attr(not(target_os = "linux"), allow(dead_code, unused_imports))]

mod common;

use common::{Rng, env_number};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// A watchdog over a test's case counter: a case running a minute is a hang; it says
/// which and ends the run. It stops watching when dropped, with its test.
struct Watchdog {
    case: std::sync::Arc<std::sync::atomic::AtomicU64>,
    done: std::sync::Arc<std::sync::atomic::AtomicBool>,
}

impl Watchdog {
    fn start(what: &'static str) -> Watchdog {
        use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
        let case = std::sync::Arc::new(AtomicU64::new(0));
        let done = std::sync::Arc::new(AtomicBool::new(false));
        let (c, d) = (case.clone(), done.clone());
        std::thread::spawn(move || {
            let mut last = (u64::MAX, Instant::now());
            while !d.load(Ordering::Relaxed) {
                std::thread::sleep(Duration::from_secs(1));
                let now = c.load(Ordering::Relaxed);
                if now != last.0 {
                    last = (now, Instant::now());
                } else if last.1.elapsed() > Duration::from_secs(60) && !d.load(Ordering::Relaxed) {
                    eprintln!("{what}: fuzz case {now} hangs");
                    std::process::abort();
                }
            }
        });
        Watchdog { case, done }
    }

    fn at(&self, case: u64) {
        self.case.store(case, std::sync::atomic::Ordering::Relaxed);
    }
}

impl Drop for Watchdog {
    fn drop(&mut self) {
        self.done.store(true, std::sync::atomic::Ordering::Relaxed);
    }
}

/// A node graph: each node's children and whether it names the mesh; the scene's roots.
struct Graph {
    children: Vec<Vec<usize>>,
    mesh: Vec<bool>,
    roots: Vec<usize>,
}

impl Graph {
    /// A random tree (or forest), then 0 to 2 breaks drawn from every way to break one.
    fn generate(rng: &mut Rng) -> Graph {
        let n = match rng.below(10) {
            0 => 500 + rng.below(3000), // a deep chain or a wide tree
            _ => 1 + rng.below(40),
        };
        let chain = rng.below(2) == 0;
        let mut children = vec![Vec::new(); n];
        let mut roots = vec![0];
        for i in 1..n {
            match (chain, rng.below(8)) {
                (_, 0) => roots.push(i),
                (true, _) => children[i - 1].push(i),
                (false, _) => children[rng.below(i)].push(i),
            }
        }
        let mesh = (0..n).map(|_| rng.below(3) != 0).collect();
        let mut g = Graph {
            children,
            mesh,
            roots,
        };
        for _ in 0..rng.below(3) {
            let (a, b) = (rng.below(n), rng.below(n));
            match rng.below(7) {
                0 => g.children[a].push(b), // a second parent, a cycle or a self-loop
                1 => g.children[a].push(a), // a node its own child
                2 if !g.children[a].is_empty() => {
                    let c = g.children[a][0];
                    g.children[a].push(c); // listed twice
                }
                3 => g.roots.push(b), // a root listed twice, or a child
                4 => g.children[a].push(n + rng.below(3)), // past the end
                5 => g.children[b].push(0), // back to the first root
                _ => {}
            }
        }
        g
    }

    /// Whether it is a set of disjoint trees with the scene listing distinct roots: no
    /// node with two parents, every node reached from one with none, indices in range.
    fn is_forest(&self) -> bool {
        let n = self.children.len();
        let mut parents = vec![0usize; n];
        for c in self.children.iter().flatten() {
            if *c >= n {
                return false;
            }
            parents[*c] += 1;
        }
        if parents.iter().any(|&p| p > 1) {
            return false;
        }
        let mut reached = vec![false; n];
        let mut stack: Vec<usize> = (0..n).filter(|&i| parents[i] == 0).collect();
        while let Some(i) = stack.pop() {
            reached[i] = true;
            stack.extend(&self.children[i]);
        }
        let mut roots = self.roots.clone();
        roots.sort_unstable();
        roots.dedup();
        reached.iter().all(|&r| r)
            && roots.len() == self.roots.len()
            && self.roots.iter().all(|&r| r < n && parents[r] == 0)
    }

    /// How many nodes under the scene's roots name the mesh (for a forest).
    fn placements(&self) -> usize {
        let mut stack = self.roots.clone();
        let mut count = 0;
        while let Some(i) = stack.pop() {
            count += usize::from(self.mesh[i]);
            stack.extend(&self.children[i]);
        }
        count
    }

    /// As a glTF file of one triangle, a node a line.
    fn gltf(&self) -> String {
        let nodes: Vec<String> = self
            .children
            .iter()
            .zip(&self.mesh)
            .map(|(c, &m)| {
                let mesh = if m { r#""mesh": 0, "# } else { "" };
                format!(r#"{{{mesh}"translation": [0, 0.001, 0], "children": {c:?}}}"#)
            })
            .collect();
        format!(
            r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": {:?}}}],
"meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
"buffers": [{{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}}],
"bufferViews": [{{"buffer": 0, "byteLength": 36}}],
"accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}}],
"nodes": [
{}
]}}"#,
            self.roots,
            nodes.join(",\n")
        )
    }
}

#[test]
fn generated_node_graphs_are_trees_or_refused_and_never_blow_up() {
    let cases = env_number("RAYLAB_FUZZ_CASES", 2000);
    let seed = env_number("RAYLAB_FUZZ_SEED", 1);
    let watchdog = Watchdog::start("node graphs");
    let mut rng = Rng(seed ^ 0x6a09_e667);
    let (mut trees, mut refused) = (0u64, 0u64);
    let start = Instant::now();
    for case in 0..cases {
        watchdog.at(case);
        let g = Graph::generate(&mut rng);
        let text = g.gltf();
        let no_files = |_: &str| Err("no files".to_string());
        let read = std::panic::catch_unwind(|| {
            raylab::scene::load_gltf(text.as_bytes(), "g.gltf", &no_files)
        });
        let Ok(read) = read else {
            panic!("case {case}: panicked on\n{text}");
        };
        let forest = g.is_forest();
        match read {
            Ok(model) => {
                assert!(
                    forest,
                    "case {case}: accepted a graph that is not a tree\n{text}"
                );
                let placed: usize = model.parts.iter().map(|p| p.at.len()).sum();
                assert_eq!(placed, g.placements(), "case {case}\n{text}");
                trees += 1;
            }
            Err(e) => {
                let e = e.to_string();
                let empty = e.contains("has no triangles") && g.placements() == 0;
                assert!(!forest || empty, "case {case}: refused a tree: {e}\n{text}");
                refused += 1;
            }
        }
    }
    eprintln!(
        "node graphs: {cases} cases (seed {seed}) in {:.1} s: {trees} read, {refused} refused",
        start.elapsed().as_secs_f64()
    );
    assert!(trees > 0 && refused > 0, "{trees} read, {refused} refused");
}

/// What an output path (or its sidecar's) is made as before the write.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    New,
    File,
    ReadOnly,
    Folder,
    Fifo,
    Device,
    LinkFile,
    LinkNothing,
    LinkFolder,
    LinkFifo,
    LinkDevice,
    LinkLoop,
}

const KINDS: [Kind; 12] = [
    Kind::New,
    Kind::File,
    Kind::ReadOnly,
    Kind::Folder,
    Kind::Fifo,
    Kind::Device,
    Kind::LinkFile,
    Kind::LinkNothing,
    Kind::LinkFolder,
    Kind::LinkFifo,
    Kind::LinkDevice,
    Kind::LinkLoop,
];

/// What a path holds: its kind and, for a file, its bytes; for a link, where it points.
#[derive(Debug, PartialEq, Clone)]
enum Held {
    File(Vec<u8>),
    Folder,
    Link(PathBuf),
    Other(String),
}

/// Everything below `root`, by path (links not followed).
fn snapshot(root: &Path) -> BTreeMap<PathBuf, Held> {
    let mut out = BTreeMap::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).unwrap().flatten() {
            let p = e.path();
            let m = p.symlink_metadata().unwrap();
            let t = m.file_type();
            let held = if t.is_symlink() {
                Held::Link(std::fs::read_link(&p).unwrap())
            } else if t.is_dir() {
                stack.push(p.clone());
                Held::Folder
            } else if t.is_file() {
                Held::File(std::fs::read(&p).unwrap())
            } else {
                Held::Other(format!("{t:?}"))
            };
            out.insert(p, held);
        }
    }
    out
}

/// The case's folder: `out` (the outputs) and `elsewhere` (what links point to, beside a
/// file that must never change). Makes `path` a `kind`; the files its link may rewrite.
#[cfg(unix)]
fn make(kind: Kind, path: &Path, elsewhere: &Path, device: bool) -> Vec<PathBuf> {
    use std::os::unix::fs::symlink;
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    let target = elsewhere.join(format!("{name}.target"));
    let fifo = |p: &Path| {
        let made = std::process::Command::new("mkfifo").arg(p).status();
        assert!(made.unwrap().success());
    };
    let node = |p: &Path| {
        std::process::Command::new("mknod")
            .arg(p)
            .args(["c", "1", "3"])
            .status()
            .is_ok_and(|s| s.success())
    };
    match kind {
        Kind::New => {}
        Kind::File => std::fs::write(path, "old bytes").unwrap(),
        Kind::ReadOnly => {
            std::fs::write(path, "kept").unwrap();
            let mut p = std::fs::metadata(path).unwrap().permissions();
            p.set_readonly(true);
            std::fs::set_permissions(path, p).unwrap();
        }
        Kind::Folder => std::fs::create_dir(path).unwrap(),
        Kind::Fifo => fifo(path),
        Kind::Device => {
            if !(device && node(path)) {
                std::fs::write(path, "no device here").unwrap();
            }
        }
        Kind::LinkFile => {
            std::fs::write(&target, "the link's old bytes").unwrap();
            symlink(&target, path).unwrap();
            return vec![target];
        }
        Kind::LinkNothing => {
            symlink(&target, path).unwrap();
            return vec![target];
        }
        Kind::LinkFolder => symlink(elsewhere, path).unwrap(),
        Kind::LinkFifo => {
            fifo(&target);
            symlink(&target, path).unwrap();
        }
        Kind::LinkDevice => {
            if !(device && node(&target)) {
                std::fs::create_dir(&target).unwrap();
            }
            symlink(&target, path).unwrap();
        }
        Kind::LinkLoop => symlink(path, path).unwrap(),
    }
    Vec::new()
}

/// Opens every FIFO in `dirs` for reading and writing (Linux), so that a writer finds a
/// reader at once; what each held is read back after.
#[cfg(target_os = "linux")]
fn hold_fifos(dirs: &[&Path]) -> Vec<(PathBuf, std::fs::File)> {
    use std::os::unix::fs::{FileTypeExt, OpenOptionsExt};
    let mut held = Vec::new();
    for dir in dirs {
        for e in std::fs::read_dir(dir).unwrap().flatten() {
            let is_fifo = e.path().symlink_metadata().unwrap().file_type().is_fifo();
            if is_fifo {
                let f = std::fs::File::options()
                    .read(true)
                    .write(true)
                    .custom_flags(rustix::fs::OFlags::NONBLOCK.bits() as i32)
                    .open(e.path())
                    .unwrap();
                held.push((e.path(), f));
            }
        }
    }
    held
}

#[cfg(target_os = "linux")]
#[test]
fn generated_output_paths_touch_nothing_but_the_output() {
    use std::io::Read;
    let cases = env_number("RAYLAB_FUZZ_CASES", 2000);
    let seed = env_number("RAYLAB_FUZZ_SEED", 1);
    let watchdog = Watchdog::start("output paths");
    let root = tempfile::tempdir().unwrap();
    let device = {
        let probe = root.path().join("probe");
        let made = std::process::Command::new("mknod")
            .arg(&probe)
            .args(["c", "1", "3"])
            .stderr(std::process::Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
        let _ = std::fs::remove_file(&probe);
        if !made {
            eprintln!("device nodes left out: mknod is not permitted here (not root)");
        }
        made
    };
    let image = image::RgbImage::from_pixel(6, 4, image::Rgb([200, 100, 50]));
    let sidecar =
        raylab::render::Sidecar::read(&common_sidecar()).expect("a screenshot's sidecar reads");
    let mut rng = Rng(seed ^ 0xbb67_ae85);
    let mut outcomes = BTreeMap::new();
    let start = Instant::now();
    for case in 0..cases {
        watchdog.at(case);
        let dir = root.path().join(format!("case{case}"));
        let (out, elsewhere) = (dir.join("out"), dir.join("elsewhere"));
        std::fs::create_dir_all(&out).unwrap();
        std::fs::create_dir_all(&elsewhere).unwrap();
        std::fs::write(elsewhere.join("never.png"), "never changes").unwrap();
        let (image_kind, sidecar_kind) = (*rng.pick(&KINDS), *rng.pick(&KINDS));
        let path = out.join("x.png");
        let json = out.join("x.png.json");
        let mut may_change = vec![path.clone(), json.clone()];
        may_change.extend(make(image_kind, &path, &elsewhere, device));
        may_change.extend(make(sidecar_kind, &json, &elsewhere, device));
        let fifos = hold_fifos(&[&out, &elsewhere]);
        let before = snapshot(&dir);
        let written = raylab::render::write_png(&path, &image, Some(&sidecar));
        let after = snapshot(&dir);
        let what = format!("case {case}: image {image_kind:?}, sidecar {sidecar_kind:?}");
        // Nothing else changed, and no temporary file is left anywhere.
        for (p, held) in &before {
            if !may_change.contains(p) {
                assert_eq!(after.get(p), Some(held), "{what}: {} changed", p.display());
            }
        }
        for p in after.keys() {
            let name = p.file_name().unwrap().to_string_lossy();
            assert!(!name.ends_with(".tmp"), "{what}: {name} left");
            assert!(
                before.contains_key(p) || may_change.contains(p),
                "{what}: {} made",
                p.display()
            );
        }
        let streamed = matches!(image_kind, Kind::Fifo | Kind::LinkFifo);
        // What is neither a file, a new name, a link to one nor a FIFO is refused, and so
        // is a read-only file (a device made as a file where mknod is not permitted).
        let refused = |k: Kind| match k {
            Kind::Folder | Kind::LinkFolder | Kind::LinkLoop | Kind::ReadOnly => true,
            Kind::Device | Kind::LinkDevice => device,
            _ => false,
        };
        if refused(image_kind) || (!streamed && refused(sidecar_kind)) {
            assert!(written.is_err(), "{what}: written, not refused");
        }
        match &written {
            Ok(()) if streamed => {
                let mut bytes = Vec::new();
                for (_, mut f) in fifos {
                    let _ = f.read_to_end(&mut bytes);
                }
                assert!(
                    bytes.starts_with(b"\x89PNG"),
                    "{what}: nothing came through"
                );
                assert_eq!(
                    after.get(&json),
                    before.get(&json),
                    "{what}: beside a stream"
                );
            }
            Ok(()) => {
                let got = image::open(&path).map(|i| i.to_rgb8());
                assert!(
                    got.is_ok_and(|i| i == image),
                    "{what}: the image is not there"
                );
                let beside = raylab::render::Sidecar::read(&json);
                assert!(beside.is_ok(), "{what}: no sidecar beside it");
            }
            Err(_) => {
                // The old pair, or (the sidecar alone failing) the new image alone.
                let same = |p: &PathBuf| after.get(p) == before.get(p);
                let image_alone = image::open(&path).is_ok() && !after.contains_key(&json);
                assert!(
                    (same(&path) && same(&json)) || image_alone,
                    "{what}: failed ({written:?}) and changed the outputs"
                );
            }
        }
        *outcomes
            .entry(format!("{:?}", written.is_ok()))
            .or_insert(0u64) += 1;
        std::fs::remove_dir_all(&dir).unwrap();
    }
    eprintln!(
        "output paths: {cases} cases (seed {seed}) in {:.1} s: {outcomes:?}",
        start.elapsed().as_secs_f64()
    );
    assert_eq!(
        outcomes.len(),
        2,
        "some written, some refused: {outcomes:?}"
    );
}

/// A sidecar raylab wrote (a screenshot's).
fn common_sidecar() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("screenshots/antialiasing-1spp.png.json")
}
