//! Reading the user's files within bounds: only regular files (a folder, a device such as
//! `/dev/zero` or a pipe is refused before it is opened, so nothing blocks or reads for
//! ever), and only up to a size.

use std::io::Read;
use std::path::Path;

/// The largest scene file, sidecar or material library read: far beyond any written by hand.
pub const MAX_TEXT_BYTES: u64 = 16 << 20;

/// The largest mesh (OBJ) file read: a few million triangles.
pub const MAX_MESH_BYTES: u64 = 1 << 30;

/// The extension of `path` in lower case (`Bunny.GLB` gives `glb`), if it has one: what
/// raylab decides a file's format by.
pub fn extension(path: &Path) -> Option<String> {
    path.extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
}

/// The bytes of the regular file at `path`, if it holds at most `limit` of them.
pub fn read_limited(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(std::io::Error::other(
            "not a regular file (a folder, device or pipe); not read",
        ));
    }
    let too_big = || {
        std::io::Error::other(format!(
            "larger than the {} MiB raylab reads from such a file",
            limit >> 20
        ))
    };
    if meta.len() > limit {
        return Err(too_big());
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    // Read one byte past the limit: a file that grows while it is read is caught too.
    std::fs::File::open(path)?
        .take(limit + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(too_big());
    }
    Ok(bytes)
}

/// The text of the regular file at `path`, at most [`MAX_TEXT_BYTES`] of UTF-8, without a
/// byte-order mark (which Windows editors write and which no format here allows).
pub fn read_text(path: &Path) -> std::io::Result<String> {
    let text = String::from_utf8(read_limited(path, MAX_TEXT_BYTES)?)
        .map_err(|_| std::io::Error::new(std::io::ErrorKind::InvalidData, "not UTF-8 text"))?;
    Ok(match text.strip_prefix(BYTE_ORDER_MARK) {
        Some(rest) => rest.to_string(),
        None => text,
    })
}

/// UTF-8's byte-order mark, as text.
const BYTE_ORDER_MARK: &str = "\u{feff}";

/// `bytes` without a leading UTF-8 byte-order mark (for the text formats read as bytes:
/// OBJ, MTL, glTF JSON).
pub fn without_bom(bytes: &[u8]) -> &[u8] {
    bytes
        .strip_prefix(BYTE_ORDER_MARK.as_bytes())
        .unwrap_or(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_regular_files_within_the_limit_are_read() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("a.toml");
        std::fs::write(&file, "0123456789").unwrap();
        assert_eq!(read_limited(&file, 10).unwrap().len(), 10);
        let e = read_limited(&file, 9).unwrap_err().to_string();
        assert!(e.contains("larger than"), "{e}");
        let e = read_limited(dir.path(), 10).unwrap_err().to_string();
        assert!(e.contains("not a regular file"), "{e}");
        std::fs::write(&file, [0xff, 0xfe]).unwrap();
        assert!(read_text(&file).unwrap_err().to_string().contains("UTF-8"));
    }

    #[cfg(unix)]
    #[test]
    fn devices_are_refused_without_reading() {
        let e = read_limited(Path::new("/dev/zero"), 10)
            .unwrap_err()
            .to_string();
        assert!(e.contains("not a regular file"), "{e}");
    }
}
