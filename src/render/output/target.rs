//! What a path names before anything is written to it, and the checks that prove, before
//! any time is spent, that writing there can finish without touching anything else.
//!
//! A path is one of three targets. A new name or a regular file is replaced whole: the
//! new bytes go to a temporary file in its folder, renamed into place. A symbolic link to
//! a regular file (or to a name not there yet) is written through: the file it points to
//! is rewritten in place, so the link stays a link and nothing is made, renamed or swept
//! in the target's folder. A FIFO or a pipe (`/dev/stdout` into a pipe) is a stream: the
//! bytes are written into it and nothing is put beside it. Anything else (a device such
//! as `/dev/null` or a terminal, a socket, a folder, or a link to one) is refused.

use crate::scene::memory::shown;
use std::fs::{File, Metadata};
use std::io::{Error, ErrorKind, Result};
use std::path::{Path, PathBuf};

/// How a file is written at a path (see the module's doc).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Target {
    /// A new name or a regular file: written whole beside it and renamed into place.
    Replace(PathBuf),
    /// A symbolic link to a regular file, or to a name not there yet: the file it points
    /// to is written in place through the link.
    Through(PathBuf),
    /// A FIFO or a pipe: the bytes are written into it as a stream; a stream gets no
    /// sidecar beside it (the image carries its parameters inside it).
    Stream(PathBuf),
}

impl Target {
    /// What `path` names now; an error naming what it is if raylab does not write there.
    pub fn of(path: &Path) -> Result<Target> {
        let own = match path.symlink_metadata() {
            Err(e) if e.kind() == ErrorKind::NotFound => {
                return Ok(Target::Replace(path.to_path_buf()));
            }
            other => other?,
        };
        if !own.file_type().is_symlink() {
            return match Kind::of(&own) {
                Kind::File => Ok(Target::Replace(path.to_path_buf())),
                Kind::Fifo => Ok(Target::Stream(path.to_path_buf())),
                other => Err(refused(other.what())),
            };
        }
        // A link: what it leads to, followed to the end.
        match path.metadata() {
            Err(e) if e.kind() == ErrorKind::NotFound => Ok(Target::Through(path.to_path_buf())),
            Err(e) => Err(e),
            Ok(end) => match Kind::of(&end) {
                Kind::File => Ok(Target::Through(path.to_path_buf())),
                Kind::Fifo => Ok(Target::Stream(path.to_path_buf())),
                other => {
                    let to = std::fs::canonicalize(path)
                        .map(|t| format!(" ({})", t.display()))
                        .unwrap_or_default();
                    Err(refused(&format!("a link to {}{to}", other.what())))
                }
            },
        }
    }

    /// The path as given.
    pub fn path(&self) -> &Path {
        match self {
            Target::Replace(p) | Target::Through(p) | Target::Stream(p) => p,
        }
    }

    /// Refuses a file there that its owner has marked as not to be changed (read-only,
    /// immutable, append-only, another's in a sticky folder), or that a link leads to
    /// and cannot be written: checked before any work and again at the write.
    pub(super) fn may_change(&self) -> Result<()> {
        match self {
            Target::Replace(p) => match p.symlink_metadata() {
                Ok(m) => replaceable(p, &m),
                Err(_) => Ok(()),
            },
            // Opened for writing and closed unchanged: it proves the file takes writes
            // without touching its bytes.
            Target::Through(p) => match p.metadata() {
                Ok(m) => writable_in_place(p, &m),
                Err(_) => Ok(()),
            },
            Target::Stream(_) => Ok(()),
        }
    }

    /// Whether the bytes go into a FIFO or a pipe, with nothing beside them.
    pub fn is_stream(&self) -> bool {
        matches!(self, Target::Stream(_))
    }
}

/// What kind of file a path is, as far as writing to it goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    File,
    Fifo,
    Folder,
    CharDevice,
    BlockDevice,
    Socket,
    Other,
}

impl Kind {
    fn of(m: &Metadata) -> Kind {
        let t = m.file_type();
        if t.is_file() {
            return Kind::File;
        }
        if t.is_dir() {
            return Kind::Folder;
        }
        #[cfg(unix)]
        {
            use std::os::unix::fs::FileTypeExt;
            if t.is_fifo() {
                return Kind::Fifo;
            }
            if t.is_char_device() {
                return Kind::CharDevice;
            }
            if t.is_block_device() {
                return Kind::BlockDevice;
            }
            if t.is_socket() {
                return Kind::Socket;
            }
        }
        Kind::Other
    }

    fn what(self) -> &'static str {
        match self {
            Kind::File => "a file",
            Kind::Fifo => "a FIFO",
            Kind::Folder => "a folder",
            Kind::CharDevice => "a character device (such as /dev/null or a terminal)",
            Kind::BlockDevice => "a block device (a disk)",
            Kind::Socket => "a socket",
            Kind::Other => "neither a file nor a folder",
        }
    }
}

/// The refusal of a FIFO in a sidecar's place.
pub(super) fn sidecar_not_a_file() -> Error {
    Error::new(
        ErrorKind::InvalidInput,
        "is a FIFO, and a sidecar is a file (remove it, or write the image under another name)",
    )
}

/// The refusal of a path that is `what`, left as it is.
fn refused(what: &str) -> Error {
    Error::new(
        ErrorKind::InvalidInput,
        format!(
            "is {what}; raylab writes only to files, new names, FIFOs and pipes, and left it untouched"
        ),
    )
}

/// Checks, before any work, that writing up to `bytes` at `path` will finish without
/// touching anything but the output: what it names (see [`Target::of`]), that a file
/// there may be replaced (not read-only, not immutable or append-only, not another's in a
/// sticky folder), that its folder takes a new file, and that the file system has room.
pub(super) fn preflight(path: &Path, bytes: u64) -> Result<Target> {
    let target = Target::of(path)?;
    target.may_change()?;
    match &target {
        Target::Replace(p) => {
            let dir = super::folder_of(p);
            let name = p
                .file_name()
                .ok_or_else(|| Error::other("not a file name"))?;
            super::TempFile::create(dir, &name.to_string_lossy())
                .map(drop)
                .map_err(|e| {
                    Error::new(
                        e.kind(),
                        format!("no new file can be made in {}: {e}", dir.display()),
                    )
                })?;
            room(dir, bytes)?;
        }
        Target::Through(p) => match p.metadata() {
            Ok(_) => room(p, bytes)?,
            Err(_) => {
                let end = link_end(p);
                let dir = super::folder_of(&end);
                if !dir.is_dir() {
                    return Err(Error::new(
                        ErrorKind::NotFound,
                        format!(
                            "is a link to {}, whose folder does not exist",
                            end.display()
                        ),
                    ));
                }
                room(dir, bytes)?;
            }
        },
        Target::Stream(_) => {}
    }
    Ok(target)
}

/// Where a link that leads to nothing yet points, relative to the link's folder.
fn link_end(link: &Path) -> PathBuf {
    let mut end = link.to_path_buf();
    // Bounded: a loop of links ends here as the system's own limit would.
    for _ in 0..40 {
        match std::fs::read_link(&end) {
            Ok(to) => end = super::folder_of(&end).join(to),
            Err(_) => break,
        }
    }
    end
}

/// Refuses a file that renaming over would fail on, or that its owner has marked as not
/// to be changed.
fn replaceable(path: &Path, m: &Metadata) -> Result<()> {
    unchangeable(path, m, "is read-only (its permissions); not replaced")?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        // In a sticky folder (/tmp), only the file's owner, the folder's or root may
        // replace it.
        let dir = super::folder_of(path);
        if let Ok(d) = dir.metadata() {
            let me = rustix::process::geteuid().as_raw();
            let sticky = d.mode() & 0o1000 != 0;
            if sticky && me != 0 && m.uid() != me && d.uid() != me {
                return Err(Error::new(
                    ErrorKind::PermissionDenied,
                    "belongs to another user in a folder where only its owner may replace it",
                ));
            }
        }
    }
    Ok(())
}

/// Refuses a file its owner has marked as not to be changed: read-only (`read_only` says
/// so), or immutable or append-only (Linux's `chattr +i`, `+a`), which no rename may
/// replace and no write may rewrite.
fn unchangeable(path: &Path, m: &Metadata, read_only: &str) -> Result<()> {
    if m.permissions().readonly() {
        return Err(Error::new(ErrorKind::PermissionDenied, read_only));
    }
    #[cfg(target_os = "linux")]
    {
        use rustix::fs::{AtFlags, CWD, StatxAttributes, StatxFlags, statx};
        if let Ok(x) = statx(CWD, path, AtFlags::empty(), StatxFlags::BASIC_STATS) {
            let set = x.stx_attributes & x.stx_attributes_mask;
            if set.contains(StatxAttributes::IMMUTABLE) {
                return Err(Error::new(
                    ErrorKind::PermissionDenied,
                    "is marked immutable (chattr +i); not replaced",
                ));
            }
            if set.contains(StatxAttributes::APPEND) {
                return Err(Error::new(
                    ErrorKind::PermissionDenied,
                    "is marked append-only (chattr +a); not replaced",
                ));
            }
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = path;
    Ok(())
}

/// Refuses a file a link leads to that cannot be rewritten in place.
fn writable_in_place(path: &Path, m: &Metadata) -> Result<()> {
    unchangeable(path, m, "is a link to a read-only file; not rewritten")?;
    File::options()
        .write(true)
        .open(path)
        .map(drop)
        .map_err(|e| Error::new(e.kind(), format!("its file cannot be written: {e}")))
}

/// The bytes free to an unprivileged writer on the file system holding `path`, where the
/// system says (Unix); `None` elsewhere.
fn free_bytes(path: &Path) -> Option<u64> {
    #[cfg(unix)]
    {
        rustix::fs::statvfs(path)
            .ok()
            .map(|s| s.f_bavail.saturating_mul(s.f_frsize))
    }
    #[cfg(not(unix))]
    {
        let _ = path;
        None
    }
}

/// Refuses a file system without room for `bytes` more.
fn room(path: &Path, bytes: u64) -> Result<()> {
    match free_bytes(path) {
        Some(free) if free < bytes => Err(Error::new(
            ErrorKind::StorageFull,
            format!(
                "needs up to {} and its file system has {} free",
                shown(bytes),
                shown(free)
            ),
        )),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_names_and_files_are_replaced_folders_refused() {
        let dir = tempfile::tempdir().unwrap();
        let new = dir.path().join("a.png");
        assert_eq!(Target::of(&new).unwrap(), Target::Replace(new.clone()));
        std::fs::write(&new, "x").unwrap();
        assert_eq!(Target::of(&new).unwrap(), Target::Replace(new.clone()));
        let e = Target::of(dir.path()).unwrap_err().to_string();
        assert!(e.starts_with("is a folder"), "{e}");
    }

    #[cfg(unix)]
    #[test]
    fn devices_and_links_to_them_are_refused_fifos_streamed_links_written_through() {
        let dir = tempfile::tempdir().unwrap();
        let e = Target::of(Path::new("/dev/null")).unwrap_err().to_string();
        assert!(e.contains("character device"), "{e}");
        let link = dir.path().join("null.png");
        std::os::unix::fs::symlink("/dev/null", &link).unwrap();
        let e = Target::of(&link).unwrap_err().to_string();
        assert!(e.starts_with("is a link to a character device"), "{e}");
        let fifo = dir.path().join("pipe.png");
        assert!(
            std::process::Command::new("mkfifo")
                .arg(&fifo)
                .status()
                .unwrap()
                .success()
        );
        assert!(Target::of(&fifo).unwrap().is_stream());
        let to_file = dir.path().join("latest.png");
        std::os::unix::fs::symlink("real.png", &to_file).unwrap();
        assert_eq!(
            Target::of(&to_file).unwrap(),
            Target::Through(to_file.clone())
        );
    }

    #[test]
    fn a_read_only_file_is_not_replaced_and_a_full_disk_is_found_before() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.png");
        std::fs::write(&path, "mine").unwrap();
        let mut p = std::fs::metadata(&path).unwrap().permissions();
        p.set_readonly(true);
        std::fs::set_permissions(&path, p).unwrap();
        let e = preflight(&path, 10).unwrap_err().to_string();
        assert!(e.contains("read-only"), "{e}");
        let other = dir.path().join("b.png");
        if free_bytes(dir.path()).is_some() {
            let e = preflight(&other, u64::MAX / 2).unwrap_err().to_string();
            assert!(e.starts_with("needs up to"), "{e}");
        }
        assert!(preflight(&other, 10).is_ok());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }
}
