//! Output paths: the default name when `-o` is not given, and the checks made before
//! any time is spent rendering.

use anyhow::{Result, bail};
use raylab::render::output::{folder_of, safe_file_stem, unused_png};
use std::path::{Path, PathBuf};

/// Where an image goes when `-o` is not given: `<stem>.png` in `dir` (the current folder
/// for the commands), or `<stem>-2.png`, `<stem>-3.png`, ... when that name or its sidecar
/// is taken, so that a default never replaces a file.
pub fn default_output(dir: &Path, stem: &str) -> PathBuf {
    unused_png(dir, &safe_file_stem(stem))
}

/// Refuses, before any time is spent rendering, an output the film cannot write (a
/// format it does not write, a caption where the file cannot carry one) or that the file
/// system will not take (see [`check_writable`]); `sidecar` if a sidecar goes beside it.
pub fn check_output(path: &Path, caption: bool, sidecar: bool) -> Result<()> {
    let ext = raylab::scene::input::extension(path);
    if !matches!(ext.as_deref(), Some("png") | Some("exr")) {
        bail!("{}: the output must end in .png or .exr", path.display());
    }
    if caption && ext.as_deref() != Some("png") {
        bail!(
            "{}: --caption draws text into the picture, so it needs a .png output",
            path.display()
        );
    }
    check_writable(path, sidecar)
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

/// Refuses an output that cannot be written, before any time is spent: a folder that is
/// not there or takes no new file (read-only, full), a folder in the file's place, or a
/// name too long for the file system (with its sidecar's `.json`, if `sidecar`).
pub fn check_writable(path: &Path, sidecar: bool) -> Result<()> {
    check_folder(path)?;
    let extra = if sidecar { ".json".len() } else { 0 };
    if let Err(e) = raylab::render::output::check_writable(path, extra) {
        bail!("{}: cannot be written: {e}", path.display());
    }
    Ok(())
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
