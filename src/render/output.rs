//! Writing files so that nothing the user has is lost: every file is written whole to a
//! temporary file beside its destination and renamed into place, so a crash, a kill or a
//! full disk leaves either the old file or the new one, never a truncated mix; an image
//! and its sidecar are replaced as a pair; and a temporary file left by a killed run is
//! removed by the next write to its folder.

use std::fs::File;
use std::io::Write;
use std::path::{Component, Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicU32, Ordering};

/// The longest file name most file systems take, in bytes.
pub const MAX_NAME_BYTES: usize = 255;

/// What marks raylab's temporary files: `.NAME.raylab-PID-N.tmp`.
const TEMP_MARK: &str = ".raylab-";

/// The temporary files being written now, for [`remove_temporaries`].
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Removes every temporary file this process is writing, and keeps the list locked, so
/// that no other can be made after: for a Ctrl-C handler, just before it ends the process.
pub fn remove_temporaries() {
    if let Ok(live) = LIVE.lock() {
        for path in live.iter() {
            let _ = std::fs::remove_file(path);
        }
        // Held until the process ends: a writer waits at its next file.
        std::mem::forget(live);
    }
}

/// A file being written beside its destination, under a hidden name, locked while it is
/// written (so that another process's sweep can tell it from one left by a killed run),
/// and removed unless it is renamed into place.
struct TempFile {
    path: PathBuf,
    file: Option<File>,
}

impl TempFile {
    /// A new temporary file in `dir` for the file `name`.
    fn create(dir: &Path, name: &str) -> std::io::Result<TempFile> {
        static COUNTER: AtomicU32 = AtomicU32::new(0);
        let tail = format!(
            "{TEMP_MARK}{}-{}.tmp",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        );
        // A name near the limit would not fit with the tail: its start is enough.
        let mut keep = name.len().min(MAX_NAME_BYTES - 1 - tail.len());
        while !name.is_char_boundary(keep) {
            keep -= 1;
        }
        let path = dir.join(format!(".{}{tail}", &name[..keep]));
        // Made and listed under the list's lock, so that Ctrl-C finds every file made.
        let mut live = LIVE.lock().ok();
        let file = File::options().write(true).create_new(true).open(&path)?;
        // Unlocked only on platforms without file locks; the sweep then leaves it alone.
        let _ = file.try_lock();
        if let Some(live) = live.as_mut() {
            live.push(path.clone());
        }
        drop(live);
        Ok(TempFile {
            path,
            file: Some(file),
        })
    }

    /// Writes `bytes` and flushes them to the disk.
    fn write_all(&mut self, bytes: &[u8]) -> std::io::Result<()> {
        let file = self
            .file
            .as_mut()
            .ok_or_else(|| std::io::Error::other("already closed"))?;
        file.write_all(bytes)?;
        file.sync_all()
    }

    /// Renames it over `path`, still locked, so that no sweep takes it before.
    fn persist(mut self, path: &Path) -> std::io::Result<()> {
        std::fs::rename(&self.path, path)?;
        self.forget();
        Ok(())
    }

    /// Leaves the file on disk, unlocked, as a killed process leaves it.
    fn abandon(mut self) {
        self.forget();
    }

    fn forget(&mut self) {
        if let Ok(mut live) = LIVE.lock() {
            live.retain(|p| p != &self.path);
        }
        self.file = None;
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        if self.file.is_some() {
            self.file = None;
            let _ = std::fs::remove_file(&self.path);
            self.forget();
        }
    }
}

/// Where writing `path` goes: through a symbolic link to its target (a link the user
/// made stays a link), else `path` itself.
fn destination(path: &Path) -> PathBuf {
    let is_link = path
        .symlink_metadata()
        .is_ok_and(|m| m.file_type().is_symlink());
    if !is_link {
        return path.to_path_buf();
    }
    match std::fs::canonicalize(path) {
        Ok(target) => target,
        // A link to a file not there yet: its target, relative to the link's folder.
        Err(_) => match std::fs::read_link(path) {
            Ok(target) => folder_of(path).join(target),
            Err(_) => path.to_path_buf(),
        },
    }
}

/// Whether `a` and `b` name one existing file (through links, `..` and the like).
pub fn same_file(a: &Path, b: &Path) -> bool {
    matches!((std::fs::canonicalize(a), std::fs::canonicalize(b)), (Ok(a), Ok(b)) if a == b)
}

/// The folder `path` is in (`.` for a bare name).
pub fn folder_of(path: &Path) -> &Path {
    path.parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

/// Whether `name` is a temporary file raylab writes (or wrote before this version:
/// `.NAME.PID-N.tmp`).
fn is_temporary(name: &str) -> bool {
    let Some(inner) = name.strip_prefix('.').and_then(|n| n.strip_suffix(".tmp")) else {
        return false;
    };
    if inner.contains(TEMP_MARK) {
        return true;
    }
    // 0.1's names carry no mark: only those of a file raylab writes are taken, so that
    // another program's `.notes.txt.12-3.tmp` is never removed.
    let Some((name, tail)) = inner.rsplit_once('.') else {
        return false;
    };
    let ours = [".png", ".exr", ".json", ".gif", ".svg"];
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    ours.iter().any(|ext| name.ends_with(ext))
        && tail
            .split_once('-')
            .is_some_and(|(pid, n)| digits(pid) && digits(n))
}

/// Removes the temporary files a killed run left in `dir`: those no running writer holds
/// locked. Every write sweeps its folder (a listing; only temporary names are opened).
pub fn sweep_stale(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        if !entry.file_name().to_str().is_some_and(is_temporary) {
            continue;
        }
        let path = entry.path();
        let unheld = File::options()
            .write(true)
            .open(&path)
            .is_ok_and(|f| f.try_lock().is_ok());
        if unheld {
            let _ = std::fs::remove_file(&path);
        }
    }
}

/// A temporary file for `path`, with `bytes` written and flushed.
fn staged(path: &Path, bytes: &[u8]) -> std::io::Result<TempFile> {
    let name = path
        .file_name()
        .ok_or_else(|| std::io::Error::other("not a file name"))?;
    let dir = folder_of(path);
    sweep_stale(dir);
    let mut temp = TempFile::create(dir, &name.to_string_lossy())?;
    temp.write_all(bytes)?;
    Ok(temp)
}

/// Writes `bytes` to `path` atomically: to a temporary file in the same folder (so the
/// rename stays on one file system), flushed to disk, then renamed over `path` (or over
/// the file a link at `path` points to).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let path = destination(path);
    staged(&path, bytes)?.persist(&path)
}

/// Writes an image and its sidecar as a pair. Both are written whole first; then the old
/// sidecar is removed, the new image renamed into place and the new sidecar beside it. A
/// kill at any moment leaves the old image with its old sidecar, an image alone (which
/// carries its own parameters), or the new pair: never an image beside another's sidecar.
pub fn write_pair(
    image: &Path,
    image_bytes: &[u8],
    sidecar: &Path,
    sidecar_bytes: &[u8],
) -> std::io::Result<()> {
    write_pair_until(image, image_bytes, sidecar, sidecar_bytes, PAIR_STEPS)
}

/// The steps of [`write_pair`].
const PAIR_STEPS: usize = 5;

/// [`write_pair`]'s first `steps` steps, the temporary files of a step not reached left
/// where they are, as a kill would leave them (for the test of every point).
fn write_pair_until(
    image: &Path,
    image_bytes: &[u8],
    sidecar: &Path,
    sidecar_bytes: &[u8],
    steps: usize,
) -> std::io::Result<()> {
    let (image, sidecar) = (destination(image), destination(sidecar));
    let new_image = staged(&image, image_bytes)?;
    if steps < 2 {
        new_image.abandon();
        return Ok(());
    }
    let new_sidecar = staged(&sidecar, sidecar_bytes)?;
    if steps < 3 {
        new_image.abandon();
        new_sidecar.abandon();
        return Ok(());
    }
    match std::fs::remove_file(&sidecar) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => return Err(e),
        _ => {}
    }
    if steps < 4 {
        new_image.abandon();
        new_sidecar.abandon();
        return Ok(());
    }
    new_image.persist(&image)?;
    if steps < 5 {
        new_sidecar.abandon();
        return Ok(());
    }
    new_sidecar.persist(&sidecar)
}

/// Checks, before any work, that `path` can be written: its folder exists and takes a new
/// file, and its name (and its sidecar's, `extra` bytes longer) fits the file system.
pub fn check_writable(path: &Path, extra: usize) -> std::io::Result<()> {
    let path = destination(path);
    let name = path
        .file_name()
        .ok_or_else(|| std::io::Error::other("not a file name"))?;
    let bytes = name.len() + extra;
    if bytes > MAX_NAME_BYTES {
        return Err(std::io::Error::other(format!(
            "the name is {bytes} bytes long{}; file systems take at most {MAX_NAME_BYTES}",
            if extra > 0 {
                " with its sidecar's .json"
            } else {
                ""
            }
        )));
    }
    if path.is_dir() {
        return Err(std::io::Error::other("is a folder"));
    }
    let dir = folder_of(&path);
    TempFile::create(dir, &name.to_string_lossy())
        .map(drop)
        .map_err(|e| {
            std::io::Error::new(
                e.kind(),
                format!("no new file can be made in {}: {e}", dir.display()),
            )
        })
}

/// Encodes `img` as `format` in memory and writes it with [`write_atomic`].
pub fn save_image<P, C>(
    img: &image::ImageBuffer<P, C>,
    path: &Path,
    format: image::ImageFormat,
) -> image::ImageResult<()>
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
    C: std::ops::Deref<Target = [P::Subpixel]>,
{
    let mut bytes = std::io::Cursor::new(Vec::new());
    img.write_to(&mut bytes, format)?;
    write_atomic(path, bytes.get_ref()).map_err(image::ImageError::IoError)
}

/// `name` as a file name's stem: every character but letters, digits, `-` and `_` becomes
/// `_` (`ray tree` gives `ray_tree`); `image` if nothing but `_` is left.
pub fn safe_file_stem(name: &str) -> String {
    let safe: String = name
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || matches!(c, '-' | '_') {
                c
            } else {
                '_'
            }
        })
        .collect();
    if safe.trim_matches('_').is_empty() {
        "image".to_string()
    } else {
        safe
    }
}

/// The first of `dir/<stem>.png`, `dir/<stem>-2.png`, `dir/<stem>-3.png`, ... of which
/// neither the image nor its sidecar exists (a dangling link counts as existing): a name
/// under which writing replaces nothing.
pub fn unused_png(dir: &Path, stem: &str) -> PathBuf {
    let taken = |p: &Path| {
        p.symlink_metadata().is_ok() || super::sidecar_path(p).symlink_metadata().is_ok()
    };
    let mut path = dir.join(format!("{stem}.png"));
    let mut n = 2u64;
    while taken(&path) {
        path = dir.join(format!("{stem}-{n}.png"));
        n += 1;
    }
    path
}

/// `target` written relative to the folder `base` (`../scenes/glass.toml`), when both are
/// absolute paths on the same root; `None` otherwise (then the absolute path is kept).
pub(crate) fn relative_path(target: &Path, base: &Path) -> Option<PathBuf> {
    let (t, b): (Vec<Component>, Vec<Component>) =
        (target.components().collect(), base.components().collect());
    let rooted =
        |c: &[Component]| matches!(c.first(), Some(Component::Prefix(_) | Component::RootDir));
    if !rooted(&t) || !rooted(&b) || t.first() != b.first() {
        return None;
    }
    let common = t.iter().zip(&b).take_while(|(x, y)| x == y).count();
    let mut rel = PathBuf::new();
    for _ in common..b.len() {
        rel.push("..");
    }
    for c in &t[common..] {
        rel.push(c);
    }
    Some(rel)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_atomic_write_replaces_the_file_and_leaves_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.json");
        std::fs::write(&path, "old").unwrap();
        write_atomic(&path, b"new").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
        let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(names.len(), 1, "{names:?}");
        // A folder in the way: an error, and the folder untouched.
        std::fs::create_dir(dir.path().join("d")).unwrap();
        assert!(write_atomic(&dir.path().join("d"), b"x").is_err());
        assert!(dir.path().join("d").is_dir());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
    }

    #[test]
    fn a_pair_cut_at_any_step_is_never_mixed_and_the_next_write_sweeps() {
        for steps in 0..=PAIR_STEPS {
            let dir = tempfile::tempdir().unwrap();
            let (image, sidecar) = (dir.path().join("a.png"), dir.path().join("a.png.json"));
            std::fs::write(&image, "old image").unwrap();
            std::fs::write(&sidecar, "old sidecar").unwrap();
            write_pair_until(&image, b"new image", &sidecar, b"new sidecar", steps).unwrap();
            let read = |p: &Path| std::fs::read_to_string(p).ok();
            let state = (read(&image), read(&sidecar));
            let allowed = [
                (Some("old image"), Some("old sidecar")),
                (Some("old image"), None),
                (Some("new image"), None),
                (Some("new image"), Some("new sidecar")),
            ];
            assert!(
                allowed
                    .iter()
                    .any(|(i, s)| state.0.as_deref() == *i && state.1.as_deref() == *s),
                "after {steps} steps: {state:?}"
            );
            if steps == PAIR_STEPS {
                assert_eq!(state.0.as_deref(), Some("new image"));
                assert_eq!(state.1.as_deref(), Some("new sidecar"));
            }
            // What a kill left is gone after the next write to the folder.
            write_atomic(&dir.path().join("b.txt"), b"b").unwrap();
            let temporary: Vec<_> = std::fs::read_dir(dir.path())
                .unwrap()
                .flatten()
                .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
                .collect();
            assert!(temporary.is_empty(), "after {steps} steps: {temporary:?}");
        }
    }

    #[test]
    fn a_temporary_file_held_by_a_writer_is_not_swept() {
        let dir = tempfile::tempdir().unwrap();
        let held = TempFile::create(dir.path(), "a.png").unwrap();
        let old = dir.path().join(".b.png.12345-0.tmp");
        std::fs::write(&old, "left by raylab 0.1").unwrap();
        let mine = dir.path().join(".notes.tmp");
        std::fs::write(&mine, "not ours").unwrap();
        let theirs = dir.path().join(".notes.txt.12-3.tmp");
        std::fs::write(&theirs, "another program's").unwrap();
        sweep_stale(dir.path());
        assert!(held.path.exists(), "a live writer's file stays");
        assert!(!old.exists(), "an old version's leftover goes");
        assert!(mine.exists(), "a name raylab never writes stays");
        assert!(theirs.exists(), "another program's temporary file stays");
        assert!(is_temporary(".x.raylab-1-2.tmp") && !is_temporary(".x.1.tmp"));
    }

    #[test]
    fn names_near_the_limit_get_a_temporary_name_that_fits() {
        let dir = tempfile::tempdir().unwrap();
        let name = format!("{}.png", "é".repeat(125));
        assert_eq!(name.len(), 254);
        let path = dir.path().join(&name);
        write_atomic(&path, b"x").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"x");
        assert!(check_writable(&path, 0).is_ok());
        let e = check_writable(&path, ".json".len())
            .unwrap_err()
            .to_string();
        assert!(e.contains("259 bytes"), "{e}");
    }

    #[cfg(unix)]
    #[test]
    fn a_link_stays_a_link_and_its_target_is_written() {
        let dir = tempfile::tempdir().unwrap();
        let (link, target) = (dir.path().join("link.png"), dir.path().join("real.png"));
        std::os::unix::fs::symlink("real.png", &link).unwrap();
        write_atomic(&link, b"first").unwrap();
        write_atomic(&link, b"second").unwrap();
        assert!(link.symlink_metadata().unwrap().file_type().is_symlink());
        assert_eq!(std::fs::read(&target).unwrap(), b"second");
    }

    #[test]
    fn relative_paths_climb_to_the_common_folder() {
        let rel = |t: &str, b: &str| relative_path(Path::new(t), Path::new(b));
        assert_eq!(rel("/a/b/s.toml", "/a/b"), Some(PathBuf::from("s.toml")));
        assert_eq!(
            rel("/a/scenes/s.toml", "/a/renders/today"),
            Some(PathBuf::from("../../scenes/s.toml"))
        );
        assert_eq!(rel("/s.toml", "/a"), Some(PathBuf::from("../s.toml")));
        assert_eq!(rel("s.toml", "/a"), None);
    }
}
