//! Nothing outside the output is touched (issue 52): what `-o` names is written as what
//! it is (a file replaced, a link's file rewritten, a FIFO or pipe streamed into) or
//! refused (a device, a link to one) by every command that writes; two renders to one
//! output leave one render's pair; a file that may not be replaced and a disk without
//! room are found before the render, with the old pair left as it was.

// Its helpers unwrap as its tests do: a failure there fails the test.
#![allow(clippy::unwrap_used)]
// FIFOs, devices, links, chattr and mount are tested where the system has them.
#![cfg_attr(not(target_os = "linux"), allow(dead_code, unused_imports))]

mod common;

use common::{fails, raylab, stderr};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The commands that write a file named by `-o` (their words but the output), each with
/// the extension of a file it writes; `compare`'s input made in `dir`.
#[cfg(unix)]
fn writers(dir: &Path) -> Vec<(Vec<&'static str>, &'static str)> {
    let made = raylab(
        &["render", "-o", "a.png", "--size", "8x8", "--spp", "1", "-q"],
        dir,
    );
    assert!(made.status.success(), "{}", stderr(&made));
    let words = |w: &'static str| w.split_whitespace().collect::<Vec<_>>();
    vec![
        (words("render --size 8x8 --spp 1 -q -o"), "png"),
        (words("render --size 8x8 --spp 1 -q -o"), "exr"),
        (
            words("sweep default --param ior=1.0,1.5 --size 8x8 --spp 1 -q -o"),
            "gif",
        ),
        (words("section --angle 30 -o"), "svg"),
        (words("compare a.png a.png -o"), "png"),
    ]
}

/// Whether this process may make device nodes (root, outside a restricted container).
#[cfg(unix)]
fn device_node(path: &Path) -> bool {
    // /dev/null's numbers: a node of one's own, so that a failure replaces only it.
    Command::new("mknod")
        .arg(path)
        .args(["c", "1", "3"])
        .status()
        .is_ok_and(|s| s.success())
}

#[cfg(unix)]
fn is_char_device(path: &Path) -> bool {
    use std::os::unix::fs::FileTypeExt;
    path.symlink_metadata()
        .is_ok_and(|m| m.file_type().is_char_device())
}

#[cfg(unix)]
fn is_link(path: &Path) -> bool {
    path.symlink_metadata()
        .is_ok_and(|m| m.file_type().is_symlink())
}

#[cfg(unix)]
#[test]
fn a_device_or_a_link_to_one_is_refused_by_every_command_and_left_as_it_was() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    if !device_node(&dir.join("probe")) {
        eprintln!("skipped: mknod is not permitted here (not root)");
        return;
    }
    for (words, ext) in writers(dir) {
        // A device node of its own (on 10fbafe the system's /dev/null was replaced through
        // a link), and a link to it.
        let (node, link) = (format!("dev.{ext}"), format!("link.{ext}"));
        if !dir.join(&node).exists() {
            assert!(device_node(&dir.join(&node)));
            std::os::unix::fs::symlink(&node, dir.join(&link)).unwrap();
        }
        for (out, what) in [
            (&node, "is a character device"),
            (&link, "is a link to a character device"),
        ] {
            let args: Vec<&str> = words.iter().copied().chain([out.as_str()]).collect();
            fails(&args, dir, &format!("{out}: cannot be written: {what}"));
            assert!(is_char_device(&dir.join(&node)), "{args:?}: still a node");
            assert!(is_link(&dir.join(&link)), "{args:?}: still a link");
            assert!(!dir.join(format!("{out}.json")).exists(), "{args:?}");
        }
    }
}

/// Makes a FIFO at `path`.
#[cfg(unix)]
fn mkfifo(path: &Path) {
    let made = Command::new("mkfifo").arg(path).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo {}", path.display());
}

/// Runs `args` while another thread reads the FIFO `fifo` to the end of a PNG (within
/// 30 s: on 10fbafe the FIFO was replaced and nothing came); what it read.
#[cfg(target_os = "linux")]
fn read_while(fifo: &Path, dir: &Path, args: &[&str]) -> (std::process::Output, Vec<u8>) {
    use std::io::Read;
    use std::os::unix::fs::OpenOptionsExt;
    // Read and write: a writer finds a reader at once, and no read waits for ever.
    let mut f = std::fs::File::options()
        .read(true)
        .write(true)
        .custom_flags(rustix::fs::OFlags::NONBLOCK.bits() as i32)
        .open(fifo)
        .unwrap();
    let reader = std::thread::spawn(move || {
        let (mut bytes, start) = (Vec::new(), std::time::Instant::now());
        let mut chunk = [0u8; 65536];
        while !bytes.ends_with(b"IEND\xaeB`\x82") && start.elapsed().as_secs() < 30 {
            match f.read(&mut chunk) {
                Ok(n) => bytes.extend_from_slice(&chunk[..n]),
                Err(_) => std::thread::sleep(std::time::Duration::from_millis(5)),
            }
        }
        bytes
    });
    let o = raylab(args, dir);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    (o, reader.join().unwrap())
}

#[cfg(target_os = "linux")]
#[test]
fn a_fifo_or_a_pipe_is_written_through_with_its_parameters_and_nothing_beside_it() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    let fifo = dir.join("pipe.png");
    mkfifo(&fifo);
    let args = [
        "render", "glass", "--size", "8x8", "--spp", "2", "-o", "pipe.png",
    ];
    let (o, png) = read_while(&fifo, dir, &args);
    assert!(png.starts_with(b"\x89PNG"), "a PNG came through");
    assert!(
        stderr(&o).contains("a stream: no sidecar"),
        "{}",
        stderr(&o)
    );
    // The image carries its parameters: it renders again, bit for bit.
    std::fs::write(dir.join("got.png"), &png).unwrap();
    let again = raylab(&["render", "--params", "got.png", "-o", "again.png"], dir);
    assert!(again.status.success(), "{}", stderr(&again));
    let pixels = |p: &str| image::open(dir.join(p)).unwrap().to_rgb8().into_raw();
    assert_eq!(pixels("got.png"), pixels("again.png"));
    let fifo_kind = std::fs::symlink_metadata(&fifo).unwrap().file_type();
    assert!(std::os::unix::fs::FileTypeExt::is_fifo(&fifo_kind));
    assert!(
        !dir.join("pipe.png.json").exists(),
        "nothing beside a stream"
    );
    // A FIFO in a sidecar's place: refused before the render, not after.
    let side = dir.join("s.png.json");
    mkfifo(&side);
    fails(
        &["render", "--size", "8x8", "--spp", "1", "-o", "s.png"],
        dir,
        "s.png.json: cannot be written: is a FIFO, and a sidecar is a file",
    );
    assert!(!dir.join("s.png").exists());
    // A section and a sweep through a link to the FIFO.
    std::os::unix::fs::symlink("pipe.png", dir.join("to-pipe.png")).unwrap();
    let (_, section) = read_while(
        &fifo,
        dir,
        &["section", "--angle", "40", "-o", "to-pipe.png"],
    );
    assert!(section.starts_with(b"\x89PNG"));
    assert!(is_link(&dir.join("to-pipe.png")));

    // Standard output into a pipe: the image on stdout, nothing made in /dev.
    let o = raylab(
        &["render", "--size", "8x8", "--spp", "1", "-o", "/dev/stdout"],
        dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(o.stdout.starts_with(b"\x89PNG"), "the PNG is on stdout");
    assert!(!Path::new("/dev/stdout.json").exists());
}

#[cfg(unix)]
#[test]
fn a_link_to_a_file_rewrites_that_file_and_stays_a_link() {
    let d = tempfile::tempdir().unwrap();
    let elsewhere = tempfile::tempdir().unwrap();
    let dir = d.path();
    let real = elsewhere.path().join("kept.png");
    std::fs::write(&real, "an older image").unwrap();
    let link = dir.join("latest.png");
    std::os::unix::fs::symlink(&real, &link).unwrap();
    let o = raylab(
        &["render", "--size", "8x8", "--spp", "1", "-o", "latest.png"],
        dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(is_link(&link));
    assert!(std::fs::read(&real).unwrap().starts_with(b"\x89PNG"));
    assert!(
        dir.join("latest.png.json").is_file(),
        "the sidecar beside the link"
    );
    // The target's folder holds the target alone: nothing made or swept there.
    assert_eq!(std::fs::read_dir(elsewhere.path()).unwrap().count(), 1);
}

/// The seed an image carries inside it, and the one its sidecar names (if it has one).
fn seeds(image: &Path) -> (u64, Option<u64>) {
    let inside = raylab::render::Sidecar::read(image).unwrap().params.seed;
    let beside = raylab::render::Sidecar::read(&raylab::render::sidecar_path(image))
        .ok()
        .map(|s| s.params.seed);
    (inside, beside)
}

#[test]
fn two_renders_to_one_output_leave_one_renders_pair() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path().to_path_buf();
    let start = |seed: u64| {
        Command::new(env!("CARGO_BIN_EXE_raylab"))
            .args([
                "render", "--size", "16x16", "--spp", "1", "-q", "-o", "p.png",
            ])
            .args(["--seed", &seed.to_string()])
            .current_dir(&dir)
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap()
    };
    let finish = |child: std::process::Child| {
        let o = child.wait_with_output().unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
    };
    // Three hundred rounds of two writers started together (on 10fbafe, 9 mixed pairs
    // were seen in 400).
    let rounds = 300u64;
    let mut mixed = Vec::new();
    for round in 0..rounds {
        let (a, b) = (2 * round + 1, 2 * round + 2);
        let (first, second) = (start(a), start(b));
        finish(first);
        finish(second);
        let (inside, beside) = seeds(&dir.join("p.png"));
        if beside != Some(inside) || ![a, b].contains(&inside) {
            mixed.push((round, inside, beside));
        }
    }
    assert!(mixed.is_empty(), "mixed pairs: {mixed:?}");
    let left: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        // Where a folder cannot be locked itself (Windows), its lock file stays.
        .filter(|p| !p.ends_with(".raylab.lock"))
        .collect();
    assert_eq!(left.len(), 2, "the pair alone: {left:?}");
}

/// Renders a first pair `x.png` and `x.png.json` in `dir`; their bytes.
#[cfg(target_os = "linux")]
fn first_pair(dir: &Path) -> (Vec<u8>, Vec<u8>) {
    let o = raylab(
        &["render", "--size", "8x8", "--spp", "1", "-q", "-o", "x.png"],
        dir,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    (
        std::fs::read(dir.join("x.png")).unwrap(),
        std::fs::read(dir.join("x.png.json")).unwrap(),
    )
}

#[cfg(target_os = "linux")]
#[test]
fn an_immutable_image_or_sidecar_is_found_before_the_render_and_the_pair_kept() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    let old = first_pair(dir);
    for file in ["x.png", "x.png.json"] {
        let chattr = |flag: &str| {
            Command::new("chattr")
                .args([flag, file])
                .current_dir(dir)
                .status()
                .is_ok_and(|s| s.success())
        };
        if !chattr("+i") {
            eprintln!("skipped: chattr +i is not permitted here (root on ext4 or tmpfs)");
            return;
        }
        let o = raylab(
            &[
                "render", "--size", "8x8", "--spp", "1", "--seed", "7", "-o", "x.png",
            ],
            dir,
        );
        assert!(chattr("-i"), "the flag comes off again");
        let err = stderr(&o);
        // Exit 2 and this line are the preflight's, before the render: a write that
        // fails after it exits 1 with "cannot write".
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(
            err.contains(&format!("{file}: cannot be written: is marked immutable")),
            "{err}"
        );
        let now = (
            std::fs::read(dir.join("x.png")).unwrap(),
            std::fs::read(dir.join("x.png.json")).unwrap(),
        );
        assert!(now == old, "the old pair as it was");
    }
}

/// A tmpfs of `size` mounted on a new folder in `dir`, unmounted when dropped; `None`
/// where mounting is not permitted.
#[cfg(target_os = "linux")]
struct Tmpfs(PathBuf);

#[cfg(target_os = "linux")]
impl Tmpfs {
    fn mount(dir: &Path, size: &str) -> Option<Tmpfs> {
        let at = dir.join("small");
        std::fs::create_dir(&at).ok()?;
        let mounted = Command::new("mount")
            .args(["-t", "tmpfs", "-o", &format!("size={size}"), "tmpfs"])
            .arg(&at)
            .stderr(std::process::Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
        mounted.then_some(Tmpfs(at))
    }
}

#[cfg(target_os = "linux")]
impl Drop for Tmpfs {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(&self.0).status();
    }
}

#[cfg(target_os = "linux")]
#[test]
fn a_disk_without_room_is_found_before_the_render_and_the_pair_kept() {
    let d = tempfile::tempdir().unwrap();
    let Some(small) = Tmpfs::mount(d.path(), "256k") else {
        eprintln!("skipped: mounting a tmpfs is not permitted here (not root)");
        return;
    };
    let dir = small.0.as_path();
    let old = first_pair(dir);
    // 400 × 400 pixels: up to 480 kB as a PNG, more than the 256 kB there is.
    let err = fails(
        &["render", "--size", "400x400", "--spp", "1", "-o", "x.png"],
        dir,
        "x.png: cannot be written: needs up to",
    );
    assert!(err.contains("free"), "{err}");
    let now = (
        std::fs::read(dir.join("x.png")).unwrap(),
        std::fs::read(dir.join("x.png.json")).unwrap(),
    );
    assert!(now == old, "the old pair as it was");
    assert_eq!(std::fs::read_dir(dir).unwrap().count(), 2, "nothing left");
}
