//! Where a scene comes from: its text and file name, for errors that say where, and the
//! model files it names (read beside it, or a model opened alone). What the scene file's
//! parser and its materials and objects share.

use super::{Location, SceneError};
use std::ops::Range;
use std::path::{Path, PathBuf};

/// The scene text and its file's name, for errors that say where.
pub(super) struct Source<'a> {
    pub(super) file: &'a str,
    pub(super) text: &'a str,
}

impl Source<'_> {
    /// The error `message` at the text `span`.
    pub(super) fn error(&self, span: Range<usize>, message: impl Into<String>) -> SceneError {
        SceneError::new(
            Location::at_offset(self.file, self.text, span.start),
            message,
        )
    }
}

/// Where a scene's model files (OBJ and MTL, glTF and its buffers) come from.
pub(crate) trait Assets {
    /// The bytes of the file at `rel`, relative to the scene.
    fn read(&self, rel: &str) -> Result<Vec<u8>, String>;
    /// How to name `rel` in messages.
    fn label(&self, rel: &str) -> String;
}

/// Files beside the scene file.
pub(crate) struct FsAssets(pub PathBuf);

impl Assets for FsAssets {
    fn read(&self, rel: &str) -> Result<Vec<u8>, String> {
        let path = self.0.join(rel);
        // Models and their binary buffers may be large; text beside them may not.
        let is_mesh =
            super::input::extension(&path).is_some_and(|e| super::is_model(&e) || e == "bin");
        let limit = if is_mesh {
            crate::scene::input::MAX_MESH_BYTES
        } else {
            crate::scene::input::MAX_TEXT_BYTES
        };
        crate::scene::input::read_limited(&path, limit).map_err(|e| e.to_string())
    }
    fn label(&self, rel: &str) -> String {
        self.0.join(rel).display().to_string()
    }
}

/// A model opened alone: `name` in the made-up scene around it is the file at `model`
/// (whatever characters its path holds), and the files it names lie beside it.
pub(crate) struct ModelAssets {
    pub model: PathBuf,
    pub name: String,
}

impl ModelAssets {
    fn beside(&self) -> FsAssets {
        FsAssets(
            self.model
                .parent()
                .map_or_else(PathBuf::new, Path::to_path_buf),
        )
    }
}

impl Assets for ModelAssets {
    fn read(&self, rel: &str) -> Result<Vec<u8>, String> {
        if rel == self.name {
            crate::scene::input::read_limited(&self.model, crate::scene::input::MAX_MESH_BYTES)
                .map_err(|e| e.to_string())
        } else {
            self.beside().read(rel)
        }
    }
    fn label(&self, rel: &str) -> String {
        if rel == self.name {
            self.model.display().to_string()
        } else {
            self.beside().label(rel)
        }
    }
}
