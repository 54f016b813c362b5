//! Writing files so that nothing the user has is lost: every file is written whole beside
//! its destination and renamed into place, so a crash or a full disk leaves either the old
//! file or the new one, never a truncated mix.

use std::io::Write;
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicU32, Ordering};

/// Writes `bytes` to `path` atomically: to a temporary file in the same folder (so the
/// rename stays on one file system), flushed to disk, then renamed over `path`.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    static COUNTER: AtomicU32 = AtomicU32::new(0);
    let name = path
        .file_name()
        .ok_or_else(|| std::io::Error::other("not a file name"))?;
    let temp = path.with_file_name(format!(
        ".{}.{}-{}.tmp",
        name.to_string_lossy(),
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    let written = std::fs::File::create(&temp).and_then(|mut f| {
        f.write_all(bytes)?;
        f.sync_all()
    });
    let renamed = written.and_then(|()| std::fs::rename(&temp, path));
    if renamed.is_err() {
        // Nothing half-written is left behind.
        let _ = std::fs::remove_file(&temp);
    }
    renamed
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
