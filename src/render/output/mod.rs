//! Writing files so that nothing the user has is lost and nothing else is touched: a
//! file is written whole to a temporary file beside it and renamed into place, so a
//! crash, a kill or a full disk leaves either the old file or the new one, never a
//! truncated mix; a link's file is rewritten in place and a FIFO streamed into, and a
//! device is refused ([`Target`]); an image and its sidecar are replaced as a pair, one
//! writer at a time per folder; whether a write can finish is checked before any work
//! ([`check_writable`]); and a temporary file left by a killed run is removed by the next
//! write to its folder.

mod lock;
mod pair;
mod target;

use lock::FolderLock;
pub use pair::write_pair;
pub use target::Target;

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

/// A new hidden temporary name in `dir` for the file `name`: `.NAME.raylab-PID-N.tmp`.
fn temp_name(dir: &Path, name: &str) -> PathBuf {
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
    dir.join(format!(".{}{tail}", &name[..keep]))
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
        let path = temp_name(dir, name);
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

/// `dir`'s lock ([`FolderLock`]), taken before anything in the folder is made, and the
/// folder swept once under it of what killed runs left.
fn hold_folder(dir: &Path) -> std::io::Result<FolderLock> {
    let lock = FolderLock::take(dir)?;
    sweep_stale(dir);
    Ok(lock)
}

/// A temporary file for `path`, with `bytes` written and flushed. The caller holds the
/// folder ([`hold_folder`]), so that no other raylab sweeps the file between its making
/// and its lock.
fn staged(path: &Path, bytes: &[u8]) -> std::io::Result<TempFile> {
    let name = path
        .file_name()
        .ok_or_else(|| std::io::Error::other("not a file name"))?;
    let mut temp = TempFile::create(folder_of(path), &name.to_string_lossy())?;
    temp.write_all(bytes)?;
    Ok(temp)
}

/// Writes `bytes` at `path` as its [`Target`] says: a new name or a file replaced whole (a
/// crash, a kill or a full disk leaves the old file or the new, never a mix), the file a
/// link leads to rewritten in place (the link and the target's folder otherwise left
/// alone), or a FIFO or pipe streamed into. A device, a socket or a folder is refused.
pub fn write_file(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let target = Target::of(path)?;
    target.may_change()?;
    match target {
        Target::Replace(p) => {
            let _held = hold_folder(folder_of(&p))?;
            staged(&p, bytes)?.persist(&p)
        }
        Target::Through(p) => write_in_place(&p, bytes),
        Target::Stream(p) => write_stream(&p, bytes),
    }
}

/// Rewrites the file a link leads to (or makes it, for a link to a name not there yet),
/// its room reserved first where the system can, so that a full disk is found before
/// any old byte is touched.
fn write_in_place(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut file = File::options()
        .write(true)
        .create(true)
        .truncate(false)
        .open(path)?;
    let len = bytes.len() as u64;
    #[cfg(target_os = "linux")]
    match rustix::fs::fallocate(&file, rustix::fs::FallocateFlags::empty(), 0, len) {
        Err(e) if matches!(e, rustix::io::Errno::NOSPC | rustix::io::Errno::DQUOT) => {
            return Err(e.into());
        }
        // Reserved, or a file system that cannot reserve: written as it comes.
        _ => {}
    }
    file.write_all(bytes)?;
    file.set_len(len)?;
    file.sync_all()
}

/// How long a FIFO is waited on for a program to read from it.
const STREAM_WAIT: std::time::Duration = std::time::Duration::from_secs(30);

/// Writes `bytes` into a FIFO or a pipe, as a program writing to standard output does.
fn write_stream(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut file = open_stream(path)?;
    file.write_all(bytes)?;
    file.flush()
}

/// Opens a FIFO for writing once a program reads from it (within [`STREAM_WAIT`]: a plain
/// open would wait for ever for a reader that never comes).
#[cfg(unix)]
fn open_stream(path: &Path) -> std::io::Result<File> {
    use rustix::fs::OFlags;
    use std::os::unix::fs::OpenOptionsExt;
    let deadline = std::time::Instant::now() + STREAM_WAIT;
    let no_reader = Some(rustix::io::Errno::NXIO.raw_os_error());
    loop {
        let opened = File::options()
            .write(true)
            .custom_flags(OFlags::NONBLOCK.bits() as i32)
            .open(path);
        match opened {
            Ok(file) => {
                // From here writes wait for the reader, as any pipe's writer does.
                rustix::fs::fcntl_setfl(&file, OFlags::empty())?;
                return Ok(file);
            }
            Err(e) if e.raw_os_error() == no_reader => {
                if std::time::Instant::now() >= deadline {
                    return Err(std::io::Error::new(
                        std::io::ErrorKind::TimedOut,
                        format!(
                            "is a FIFO no program read from within {} s",
                            STREAM_WAIT.as_secs()
                        ),
                    ));
                }
                std::thread::sleep(std::time::Duration::from_millis(50));
            }
            Err(e) => return Err(e),
        }
    }
}

#[cfg(not(unix))]
fn open_stream(path: &Path) -> std::io::Result<File> {
    File::options().write(true).open(path)
}

/// Checks, before any work, that `path` can be written with up to `bytes`: its name (and
/// its sidecar's, `extra` bytes longer) fits the file system, and what it names takes the
/// write without anything else touched (see `target.rs`). Says how it will be
/// written.
pub fn check_writable(path: &Path, extra: usize, bytes: u64) -> std::io::Result<Target> {
    let name = path
        .file_name()
        .ok_or_else(|| std::io::Error::other("not a file name"))?;
    let len = name.len() + extra;
    if len > MAX_NAME_BYTES {
        return Err(std::io::Error::other(format!(
            "the name is {len} bytes long{}; file systems take at most {MAX_NAME_BYTES}",
            if extra > 0 {
                " with its sidecar's .json"
            } else {
                ""
            }
        )));
    }
    target::preflight(path, bytes)
}

/// The most bytes a sidecar takes, for the check of its file system's room.
const SIDECAR_BYTES: u64 = 64 * 1024;

/// Checks, before any work, that a sidecar can be written at `path` ([`check_writable`]):
/// and it is a file, not a FIFO.
pub fn check_sidecar(path: &Path) -> std::io::Result<()> {
    match check_writable(path, 0, SIDECAR_BYTES)? {
        t if t.is_stream() => Err(target::sidecar_not_a_file()),
        _ => Ok(()),
    }
}

/// The format an image at `path` is written in: its extension's (lower case), or PNG
/// for a FIFO or pipe named without one (`-o /dev/stdout`).
pub fn image_format(path: &Path) -> Option<String> {
    crate::scene::input::extension(path).or_else(|| {
        Target::of(path)
            .is_ok_and(|t| t.is_stream())
            .then(|| "png".to_string())
    })
}

/// The most bytes an image of `width` × `height` pixels takes as a file in `format`
/// (`png`: 8-bit RGB rows, stored uncompressed at worst; `exr`: 32-bit float RGB), with
/// room for its header and the parameters it carries.
pub fn image_bytes_at_most(format: &str, width: u32, height: u32) -> u64 {
    const HEADER: u64 = 64 * 1024;
    let (w, h) = (width as u64, height as u64);
    let raw = match format {
        "exr" => 12 * w * h,
        // A filter byte a row; deflate's stored blocks add 5 bytes in 65,535.
        _ => h * (1 + 3 * w),
    };
    raw + raw / 10_000 + HEADER
}

/// Encodes `img` as `format` in memory and writes it with [`write_file`].
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
    write_file(path, bytes.get_ref()).map_err(image::ImageError::IoError)
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
mod tests;
