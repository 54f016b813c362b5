//! Output paths: the default name when `-o` is not given, and the checks made before
//! any time is spent rendering.

use anyhow::{Result, bail};
use raylab::render::output::{
    Target, folder_of, image_bytes_at_most, image_format, safe_file_stem, unused_png,
};
use raylab::render::sidecar_path;
use std::path::{Path, PathBuf};

/// Where an image goes when `-o` is not given: `<stem>.png` in `dir` (the current folder
/// for the commands), or `<stem>-2.png`, `<stem>-3.png`, ... when that name or its sidecar
/// is taken, so that a default never replaces a file.
pub fn default_output(dir: &Path, stem: &str) -> PathBuf {
    unused_png(dir, &safe_file_stem(stem))
}

/// Refuses, before any time is spent rendering, an output the film cannot write (a
/// format it does not write, a caption where the file cannot carry one) or that cannot
/// take a `size` image in its format (see [`check_writable`]); `sidecar` if a sidecar
/// goes beside it. Says how the image will be written (a FIFO or pipe gets no sidecar).
pub fn check_output(
    path: &Path,
    caption: bool,
    sidecar: bool,
    (width, height): (u32, u32),
) -> Result<Target> {
    let format = image_format(path).unwrap_or_default();
    if !matches!(format.as_str(), "png" | "exr") {
        bail!("{}: the output must end in .png or .exr", path.display());
    }
    if caption && format != "png" {
        bail!(
            "{}: --caption draws text into the picture, so it needs a .png output",
            path.display()
        );
    }
    check_writable(path, sidecar, image_bytes_at_most(&format, width, height))
}

/// Refuses an output whose folder does not exist, before any time is spent.
fn check_folder(path: &Path) -> Result<()> {
    let dir = folder_of(path);
    if !dir.is_dir() {
        bail!(
            "{}: the folder {} does not exist",
            path.display(),
            dir.display()
        );
    }
    Ok(())
}

/// Refuses an output that cannot be written whole, before any time is spent: a folder
/// that is not there or takes no new file (read-only), a file system without room for
/// `bytes`, a name too long (with its sidecar's `.json`, if `sidecar`), a file that may
/// not be replaced (read-only, immutable), or what is not a file (a device such as
/// /dev/null, a folder, a link to one); and the same of the sidecar beside it.
pub fn check_writable(path: &Path, sidecar: bool, bytes: u64) -> Result<Target> {
    check_folder(path)?;
    let extra = if sidecar { ".json".len() } else { 0 };
    let target = match raylab::render::output::check_writable(path, extra, bytes) {
        Ok(target) => target,
        Err(e) => bail!("{}: cannot be written: {e}", path.display()),
    };
    if sidecar && !target.is_stream() {
        let json = sidecar_path(path);
        if let Err(e) = raylab::render::output::check_sidecar(&json) {
            bail!("{}: cannot be written: {e}", json.display());
        }
    }
    Ok(target)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_default_name_never_replaces_a_file() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        assert_eq!(default_output(d, "glass"), d.join("glass.png"));
        std::fs::write(d.join("glass.png"), b"mine").unwrap();
        assert_eq!(default_output(d, "glass"), d.join("glass-2.png"));
        // A sidecar alone takes the name too (its image may have been moved).
        std::fs::write(d.join("glass-2.png.json"), b"{}").unwrap();
        assert_eq!(default_output(d, "glass"), d.join("glass-3.png"));
        assert_eq!(default_output(d, "my scene/v2"), d.join("my_scene_v2.png"));
        assert_eq!(default_output(d, ".."), d.join("image.png"));
        assert_eq!(default_output(Path::new(""), "x"), Path::new("x.png"));
    }
}
