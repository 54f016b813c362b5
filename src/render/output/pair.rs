//! An image and its sidecar replaced as a pair, one writer at a time per folder, so that a
//! reader never finds an image beside another render's sidecar.

use super::{
    Target, TempFile, folder_of, hold_folder, staged, target, temp_name, write_in_place,
    write_stream,
};
use std::fs::File;
use std::path::{Path, PathBuf};

/// A file's new bytes made ready, before anything the user has is touched.
enum Staged<'a> {
    /// Written whole to a temporary file beside it, to be renamed into place.
    Temp(TempFile, &'a Path),
    /// To be written in place through a link.
    InPlace(&'a Path, &'a [u8]),
}

impl<'a> Staged<'a> {
    fn new(target: &'a Target, bytes: &'a [u8]) -> std::io::Result<Staged<'a>> {
        match target {
            Target::Through(p) => Ok(Staged::InPlace(p, bytes)),
            other => Ok(Staged::Temp(staged(other.path(), bytes)?, other.path())),
        }
    }

    fn persist(self) -> std::io::Result<()> {
        match self {
            Staged::Temp(temp, path) => temp.persist(path),
            Staged::InPlace(path, bytes) => write_in_place(path, bytes),
        }
    }

    /// Left as a kill leaves it.
    fn abandon(self) {
        if let Staged::Temp(temp, _) = self {
            temp.abandon();
        }
    }
}

/// An old sidecar taken out of its place while the new image goes in, so that no moment
/// shows the new image beside the old sidecar, and put back if the image cannot be.
enum Aside {
    /// There was none.
    Nothing,
    /// Renamed to a hidden temporary name in its folder (swept if a kill leaves it).
    Moved { from: PathBuf, to: PathBuf },
    /// A link's file, emptied, its old bytes kept here.
    Emptied { path: PathBuf, bytes: Vec<u8> },
}

impl Aside {
    /// Takes the sidecar at `target` out of its place. An error here (a sidecar that may
    /// not be renamed) leaves everything as it was.
    fn take(target: &Target) -> std::io::Result<Aside> {
        match target {
            Target::Through(p) => match std::fs::read(p) {
                Ok(bytes) => {
                    File::options().write(true).open(p)?.set_len(0)?;
                    Ok(Aside::Emptied {
                        path: p.clone(),
                        bytes,
                    })
                }
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(Aside::Nothing),
                Err(e) => Err(e),
            },
            other => {
                let from = other.path();
                if from.symlink_metadata().is_err() {
                    return Ok(Aside::Nothing);
                }
                let name = from.file_name().unwrap_or_default().to_string_lossy();
                let to = temp_name(folder_of(from), &name);
                std::fs::rename(from, &to)?;
                Ok(Aside::Moved {
                    from: from.to_path_buf(),
                    to,
                })
            }
        }
    }

    /// Puts the old sidecar back.
    fn restore(self) -> std::io::Result<()> {
        match self {
            Aside::Nothing => Ok(()),
            Aside::Moved { from, to } => std::fs::rename(to, from),
            Aside::Emptied { path, bytes } => write_in_place(&path, &bytes),
        }
    }

    /// The new pair is in place (or the new image alone): the old sidecar goes.
    fn discard(self) {
        if let Aside::Moved { to, .. } = self {
            let _ = std::fs::remove_file(to);
        }
    }
}

/// Writes an image and its sidecar as a pair, holding the folder's lock, so that two
/// writers replace it one after the other. Both are written whole first (a full disk
/// stops there, with nothing touched); then the old sidecar is set aside (a sidecar that
/// may not be moved stops there), the new image goes into place (if it cannot, the old
/// sidecar is put back) and the new sidecar beside it. A kill at any moment leaves the
/// old image with its old sidecar, an image alone (which carries its own parameters), or
/// the new pair: never an image beside another's sidecar. A FIFO or a pipe gets the image
/// alone.
pub fn write_pair(
    image: &Path,
    image_bytes: &[u8],
    sidecar: &Path,
    sidecar_bytes: &[u8],
) -> std::io::Result<()> {
    write_pair_cut(image, image_bytes, sidecar, sidecar_bytes, Cut::None)
}

/// Where the tests cut [`write_pair`] short (of its six steps).
#[derive(Clone, Copy, PartialEq)]
#[cfg_attr(not(test), allow(dead_code))]
pub(super) enum Cut {
    /// Not cut.
    None,
    /// Killed after this many steps: the temporary files of a step not reached left
    /// where they are, as a kill would leave them.
    Kill(usize),
    /// The new image cannot go into place (as over an immutable file).
    ImageFails,
}

pub(super) fn write_pair_cut(
    image: &Path,
    image_bytes: &[u8],
    sidecar: &Path,
    sidecar_bytes: &[u8],
    cut: Cut,
) -> std::io::Result<()> {
    let image = Target::of(image)?;
    if let Target::Stream(p) = &image {
        return write_stream(p, image_bytes);
    }
    let sidecar = Target::of(sidecar)?;
    if sidecar.is_stream() {
        let e = target::sidecar_not_a_file();
        let named = format!("{} {e}", sidecar.path().display());
        return Err(std::io::Error::new(e.kind(), named));
    }
    image.may_change()?;
    sidecar.may_change()?;
    let killed = |step: usize| matches!(cut, Cut::Kill(n) if n < step);
    let _held = hold_folder(folder_of(image.path()))?;
    let new_image = Staged::new(&image, image_bytes)?;
    if killed(2) {
        new_image.abandon();
        return Ok(());
    }
    let new_sidecar = Staged::new(&sidecar, sidecar_bytes)?;
    if killed(3) {
        new_image.abandon();
        new_sidecar.abandon();
        return Ok(());
    }
    let aside = Aside::take(&sidecar)?;
    if killed(4) {
        new_image.abandon();
        new_sidecar.abandon();
        return Ok(());
    }
    let placed = match cut {
        Cut::ImageFails => Err(std::io::Error::from(std::io::ErrorKind::PermissionDenied)),
        _ => new_image.persist(),
    };
    if let Err(e) = placed {
        // The old pair as it was.
        aside.restore()?;
        return Err(e);
    }
    if killed(5) {
        new_sidecar.abandon();
        return Ok(());
    }
    let beside = new_sidecar.persist();
    if killed(6) {
        return beside;
    }
    aside.discard();
    beside
}
