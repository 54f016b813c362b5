//! Snapshot sidecars: the JSON beside an image that holds all it takes to render it again.

use crate::camera::Camera;
use crate::params::ParamError;
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
    /// The commit that raylab was built from, where it was known ([`crate::COMMIT`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub raylab_commit: Option<String>,
    /// The scene: `builtin:NAME`, or the file's path relative to the sidecar's folder
    /// (absolute where no relative path leads there), so that a folder of scenes and
    /// renders can move as a whole. [`Sidecar::read`] resolves it.
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
    /// Its error against a reference image, pass by pass (`raylab render --reference`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference: Option<ReferenceErrors>,
    /// The rectangle of the `width` × `height` image the file holds, x0, y0, x1, y1
    /// (`raylab render --crop`): the whole image where absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crop: Option<[u32; 4]>,
}

/// A render's error against a reference image after each of its passes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ReferenceErrors {
    /// The reference, as it was named.
    pub image: String,
    /// After each pass, in order.
    pub passes: Vec<PassError>,
}

/// The error after one pass (see [`crate::render::compare::Metrics`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PassError {
    /// Samples per pixel so far.
    pub samples: u32,
    /// Mean squared error, linear RGB.
    pub mse: f64,
    /// Relative mean squared error, linear RGB.
    pub rel_mse: f64,
    /// RMS error of the brightness as shown, over its mean.
    pub rms_shown: f64,
    /// The noise the render estimated of itself then (as the status bar shows it).
    pub noise: Option<f32>,
}

/// A sidecar that cannot be read or written.
#[derive(Debug, thiserror::Error)]
pub enum SidecarError {
    /// Reading or writing the file failed.
    // `error`, not `source`: the message already says it, and a source would be said twice.
    #[error("{path}: {error}")]
    Io {
        /// The file.
        path: String,
        /// Why.
        error: std::io::Error,
    },
    /// The JSON is malformed or does not match, or a value in it is out of range.
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
}

/// The sidecar of an image: its whole name with `.json` added (`a.png.json`), so that two
/// images, `a.png` and `a.exr`, never share one.
pub fn sidecar_path(image: &Path) -> PathBuf {
    let mut name = image.as_os_str().to_owned();
    name.push(".json");
    PathBuf::from(name)
}

/// A finished render, as its sidecar records it.
pub struct Rendered<'a> {
    /// The scene.
    pub scene: &'a crate::scene::Scene,
    /// The camera it was seen through (the scene's, or one the user moved).
    pub camera: &'a Camera,
    /// Every parameter.
    pub params: &'a Params,
    /// Its size in pixels.
    pub width: u32,
    /// Its height in pixels.
    pub height: u32,
    /// Samples per pixel done (fewer than `params.spp` in a snapshot still refining).
    pub samples: u32,
    /// How long it took.
    pub seconds: f64,
    /// Its rays and pruning counters.
    pub stats: Stats,
}

impl Sidecar {
    /// The sidecar of `image`, written at `sidecar_path(image)`, describing `r`.
    pub fn new(image: &Path, r: &Rendered) -> Sidecar {
        Sidecar {
            raylab_version: crate::VERSION.to_string(),
            raylab_commit: crate::COMMIT.map(str::to_string),
            scene: Sidecar::scene_reference(&r.scene.source, &sidecar_path(image)),
            width: r.width,
            height: r.height,
            params: r.params.clone(),
            samples: (r.samples != r.params.spp).then_some(r.samples),
            camera: (*r.camera != r.scene.camera).then(|| r.camera.clone()),
            image: image.file_name().map(|n| n.to_string_lossy().into_owned()),
            seconds: Some(r.seconds),
            stats: Some(r.stats),
            reference: None,
            crop: None,
        }
    }

    /// How a sidecar at `sidecar` names the scene `source`: relative to its own folder
    /// where a relative path leads there, with `/` between folders on every system.
    pub fn scene_reference(source: &crate::scene::SceneSource, sidecar: &Path) -> String {
        let crate::scene::SceneSource::File(scene) = source else {
            return source.reference();
        };
        let folder = sidecar
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        let relative = std::fs::canonicalize(folder)
            .ok()
            .and_then(|folder| crate::render::output::relative_path(scene, &folder));
        match relative {
            Some(rel) => rel
                .components()
                .map(|c| c.as_os_str().to_string_lossy())
                .collect::<Vec<_>>()
                .join("/"),
            None => source.reference(),
        }
    }

    /// Whether a sidecar may be written at `path`: refused where that would replace the
    /// sidecar being read (`input`) or a file that is not a raylab sidecar.
    pub fn check_target(path: &Path, input: Option<&Path>) -> Result<(), SidecarError> {
        if !path.exists() {
            return Ok(());
        }
        let refuse = |message: &str| {
            Err(SidecarError::Invalid {
                path: path.display().to_string(),
                message: message.to_string(),
            })
        };
        if input.is_some_and(|input| super::output::same_file(path, input)) {
            return refuse(
                "is the sidecar this render reads; not replaced (write the image under another name)",
            );
        }
        let ours = crate::scene::input::read_text(path)
            .ok()
            .is_some_and(|text| serde_json::from_str::<Sidecar>(&text).is_ok());
        if !ours {
            return refuse("exists and is not a raylab sidecar; not replaced");
        }
        Ok(())
    }

    /// Reads and checks a sidecar: a `.json` file, or the copy a PNG or EXR written by
    /// raylab carries inside it.
    pub fn read(path: &Path) -> Result<Sidecar, SidecarError> {
        let name = path.display().to_string();
        let text = match crate::scene::input::extension(path).as_deref() {
            Some("png" | "exr") => super::embedded_sidecar(path)
                .map_err(|message| SidecarError::Invalid {
                    path: name.clone(),
                    message,
                })?
                .ok_or_else(|| SidecarError::Invalid {
                    path: name.clone(),
                    message: "carries no raylab parameters (written by another program or an older raylab, or its metadata was stripped); give its .json sidecar".into(),
                })?,
            _ => crate::scene::input::read_text(path).map_err(|error| SidecarError::Io {
                path: name.clone(),
                error,
            })?,
        };
        let parse = |e: serde_json::Error| SidecarError::Parse {
            path: name.clone(),
            line: e.line(),
            column: e.column(),
            message: crate::scene::one_line(
                e.to_string().split(" at line").next().unwrap_or_default(),
            ),
        };
        // Where a field is written, for a message that names its line and column.
        let at = |key: &str, message: String| match text.find(&format!("\"{key}\"")) {
            Some(offset) => {
                let (line, column) = crate::scene::line_col(&text, offset);
                SidecarError::Parse {
                    path: name.clone(),
                    line,
                    column,
                    message,
                }
            }
            None => SidecarError::Invalid {
                path: name.clone(),
                message,
            },
        };
        // The parameters first, each as `--set` checks it, so that an error names the
        // parameter and its range (a typed read would only say where it stopped).
        let raw: serde_json::Value = serde_json::from_str(&text).map_err(parse)?;
        if let Some(serde_json::Value::Object(given)) = raw.get("params") {
            Params::from_json(given).map_err(|error| {
                let key = match &error {
                    ParamError::Invalid { name, .. } | ParamError::Unknown { name, .. } => name,
                    ParamError::Syntax(_) => "params",
                };
                at(key, error.to_string())
            })?;
        }
        let mut sidecar: Sidecar = serde_json::from_str(&text).map_err(parse)?;
        sidecar.check().map_err(|(key, message)| at(key, message))?;
        // A scene path relative to the sidecar's folder (a bare built-in name stays).
        if let Some(folder) = path.parent() {
            let beside = folder.join(&sidecar.scene);
            if Path::new(&sidecar.scene).is_relative() && beside.is_file() {
                sidecar.scene = beside.display().to_string();
            }
        }
        Ok(sidecar)
    }

    /// Checks the fields besides the parameters, as the scene loader checks its own: the
    /// size within the film's limits, a sample count the renderer takes, a camera that
    /// makes a view.
    /// An error names the field it is about.
    fn check(&self) -> Result<(), (&'static str, String)> {
        let size = |w, h, key| crate::scene::check_size(w, h).map_err(|e| (key, e));
        size(self.width, 1, "width")?;
        size(1, self.height, "height")?;
        size(self.width, self.height, "height")?;
        if let Some(n) = self.samples {
            let max = crate::params::MAX_SPP;
            if !(1..=max).contains(&n) {
                return Err((
                    "samples",
                    format!("`samples` must be between 1 and {max}, got {n}"),
                ));
            }
        }
        if let Some(camera) = &self.camera {
            camera
                .check()
                .map_err(|e| ("camera", format!("camera: {e}")))?;
        }
        Ok(())
    }

    /// The sidecar file's text: pretty JSON.
    pub fn file_json(&self) -> std::io::Result<String> {
        let json = serde_json::to_string_pretty(self).map_err(std::io::Error::other)?;
        Ok(json + "\n")
    }

    /// The copy an image carries of it: what reproduces the image (the file's own name and
    /// the render's time left out), so that a render repeated from it, under any name, is
    /// the same file byte for byte.
    pub fn embedded_json(&self) -> String {
        let reproducible = Sidecar {
            image: None,
            seconds: None,
            reference: None,
            ..self.clone()
        };
        serde_json::to_string(&reproducible).unwrap_or_default()
    }
}
