//! Snapshot sidecars: the JSON beside an image that holds all it takes to render it again.

use crate::camera::Camera;
use crate::params::Params;
use crate::tracer::Stats;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// What a sidecar holds: the scene, the size and every parameter (the seed among them),
/// which reproduce the image bit for bit; and, for the record, the version and what the
/// render cost.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sidecar {
    /// The raylab version that wrote it.
    pub raylab_version: String,
    /// The scene: `builtin:NAME` or an absolute file path.
    pub scene: String,
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// Every parameter.
    pub params: Params,
    /// Samples per pixel in the image, when fewer than `params.spp` (a snapshot of a render
    /// still refining); the regular and jittered patterns lay out `params.spp` samples.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub samples: Option<u32>,
    /// The camera, when it was moved from the scene's (orbited, dollied, zoomed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera: Option<Camera>,
    /// The image file it describes.
    #[serde(default)]
    pub image: Option<String>,
    /// Wall-clock render time, seconds.
    #[serde(default)]
    pub seconds: Option<f64>,
    /// Rays and pruning counters of the render.
    #[serde(default)]
    pub stats: Option<Stats>,
}

/// A sidecar that cannot be read or written.
#[derive(Debug, thiserror::Error)]
pub enum SidecarError {
    /// Reading or writing the file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// Why.
        source: std::io::Error,
    },
    /// The JSON is malformed or does not match.
    #[error("{path}:{line}:{column}: {message}")]
    Parse {
        /// The file.
        path: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// Its size, sample count or camera cannot be rendered.
    #[error("{path}: {message}")]
    Invalid {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// A parameter in it is out of range.
    #[error("{path}: {source}")]
    Param {
        /// The file.
        path: String,
        /// Which and why.
        source: crate::params::ParamError,
    },
}

/// The sidecar of an image: the same name with `.json`.
pub fn sidecar_path(image: &Path) -> PathBuf {
    image.with_extension("json")
}

impl Sidecar {
    /// Reads and checks a sidecar.
    pub fn read(path: &Path) -> Result<Sidecar, SidecarError> {
        let name = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|source| SidecarError::Io {
            path: name.clone(),
            source,
        })?;
        let sidecar: Sidecar = serde_json::from_str(&text).map_err(|e| SidecarError::Parse {
            path: name.clone(),
            line: e.line(),
            column: e.column(),
            message: e
                .to_string()
                .split(" at line")
                .next()
                .unwrap_or_default()
                .to_string(),
        })?;
        sidecar
            .params
            .validate()
            .map_err(|source| SidecarError::Param {
                path: name.clone(),
                source,
            })?;
        sidecar.check().map_err(|message| SidecarError::Invalid {
            path: name,
            message,
        })?;
        Ok(sidecar)
    }

    /// Checks the fields besides the parameters, as the scene loader checks its own: the
    /// size within the film's limits, a sample count the renderer takes, a camera that
    /// makes a view.
    fn check(&self) -> Result<(), String> {
        super::check_size(self.width, self.height)?;
        if let Some(n) = self.samples {
            let max = crate::params::MAX_SPP;
            if !(1..=max).contains(&n) {
                return Err(format!("`samples` must be between 1 and {max}, got {n}"));
            }
        }
        if let Some(camera) = &self.camera {
            camera.check().map_err(|e| format!("camera: {e}"))?;
        }
        Ok(())
    }

    /// Writes the sidecar as pretty JSON.
    pub fn write(&self, path: &Path) -> Result<(), SidecarError> {
        let io = |source| SidecarError::Io {
            path: path.display().to_string(),
            source,
        };
        let json = serde_json::to_string_pretty(self).map_err(|e| io(std::io::Error::other(e)))?;
        std::fs::write(path, json + "\n").map_err(io)
    }
}
