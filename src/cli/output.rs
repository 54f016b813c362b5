//! Output paths: the default name when `-o` is not given, and the checks made before
//! any time is spent rendering.

use anyhow::{Result, bail};
use raylab::render::output::{safe_file_stem, unused_png};
use std::path::{Path, PathBuf};

/// Where an image goes when `-o` is not given: `<stem>.png` in `dir` (the current folder
/// for the commands), or `<stem>-2.png`, `<stem>-3.png`, ... when that name or its sidecar
/// is taken, so that a default never replaces a file.
pub fn default_output(dir: &Path, stem: &str) -> PathBuf {
    unused_png(dir, &safe_file_stem(stem))
}

/// Refuses an output the film cannot write before spending time on the render (and a
/// caption where the file cannot carry one).
pub fn check_output(path: &Path, caption: bool) -> Result<()> {
    let ext = raylab::scene::input::extension(path);
    if !matches!(ext.as_deref(), Some("png") | Some("exr")) {
        bail!("{}: the output must end in .png or .exr", path.display());
    }
    check_folder(path)?;
    if caption && ext.as_deref() != Some("png") {
        bail!(
            "{}: --caption draws text into the picture, so it needs a .png output",
            path.display()
        );
    }
    Ok(())
}

/// Refuses an output whose folder does not exist, before any time is spent.
pub fn check_folder(path: &Path) -> Result<()> {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !dir.is_dir() {
        bail!(
            "{}: the folder {} does not exist",
            path.display(),
            dir.display()
        );
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
