//! Output paths: the default name when `-o` is not given, and the checks made before
//! any time is spent rendering.

use anyhow::{Result, bail};
use raylab::render::sidecar_path;
use std::path::{Path, PathBuf};

/// Where an image goes when `-o` is not given: `<stem>.png` in `dir` (the current folder
/// for the commands), or
/// `<stem>-2.png`, `<stem>-3.png`, ... when that name or its sidecar is taken, so that a
/// default never replaces a file. Characters a file name cannot hold become `-`.
pub fn default_output(dir: &Path, stem: &str) -> Result<PathBuf> {
    let safe: String = stem
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || matches!(c, '-' | '_') {
                c
            } else {
                '-'
            }
        })
        .collect();
    let safe = if safe.trim_matches('-').is_empty() {
        "render".to_string()
    } else {
        safe
    };
    // symlink_metadata: a dangling link is taken too.
    let taken =
        |p: &Path| p.symlink_metadata().is_ok() || sidecar_path(p).symlink_metadata().is_ok();
    for n in 1..=9999 {
        let path = dir.join(if n == 1 {
            format!("{safe}.png")
        } else {
            format!("{safe}-{n}.png")
        });
        if !taken(&path) {
            return Ok(path);
        }
    }
    bail!("{safe}.png to {safe}-9999.png are all taken here: name the output with -o")
}

/// Refuses an output the film cannot write before spending time on the render (and a
/// caption where the file cannot carry one).
pub fn check_output(path: &Path, caption: bool) -> Result<()> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    if !matches!(ext.as_deref(), Some("png") | Some("exr")) {
        bail!("{}: the output must end in .png or .exr", path.display());
    }
    check_folder(path)?;
    let png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if caption && !png {
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
        assert_eq!(default_output(d, "glass").unwrap(), d.join("glass.png"));
        std::fs::write(d.join("glass.png"), b"mine").unwrap();
        assert_eq!(default_output(d, "glass").unwrap(), d.join("glass-2.png"));
        // A sidecar alone takes the name too (its image may have been moved).
        std::fs::write(d.join("glass-2.png.json"), b"{}").unwrap();
        assert_eq!(default_output(d, "glass").unwrap(), d.join("glass-3.png"));
        assert_eq!(
            default_output(d, "my scene/v2").unwrap(),
            d.join("my-scene-v2.png")
        );
        assert_eq!(default_output(d, "..").unwrap(), d.join("render.png"));
        assert_eq!(
            default_output(Path::new(""), "x").unwrap(),
            Path::new("x.png")
        );
    }
}
