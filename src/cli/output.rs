//! Checks on `render`'s output path, made before any time is spent rendering.

use anyhow::{Result, bail};
use std::path::Path;

/// Refuses an output the film cannot write before spending time on the render (and a
/// caption where the file cannot carry one).
pub fn check_output(path: &Path, caption: bool) -> Result<()> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    if !matches!(ext.as_deref(), Some("png") | Some("exr")) {
        bail!("{}: the output must end in .png or .exr", path.display());
    }
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
