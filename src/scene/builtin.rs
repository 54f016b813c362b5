//! Scenes embedded in the binary, so that raylab works with no files at all. They are the
//! files of `scenes/`, compiled in: one source for both.

use super::file::parse;
use super::source::Assets;
use super::{Scene, SceneError, SceneSource};

/// A scene compiled into the binary.
#[derive(Clone, Copy, Debug)]
pub struct BuiltinScene {
    /// Its name, as given on the command line.
    pub name: &'static str,
    /// Its TOML text.
    pub text: &'static str,
}

/// Every built-in scene; the first is the default.
pub static BUILTIN_SCENES: &[BuiltinScene] = &[
    BuiltinScene {
        name: "default",
        text: include_str!("../../scenes/default.toml"),
    },
    BuiltinScene {
        name: "glazed",
        text: include_str!("../../scenes/glazed.toml"),
    },
    BuiltinScene {
        name: "metals",
        text: include_str!("../../scenes/metals.toml"),
    },
    BuiltinScene {
        name: "glass",
        text: include_str!("../../scenes/glass.toml"),
    },
    BuiltinScene {
        name: "tir",
        text: include_str!("../../scenes/tir.toml"),
    },
    BuiltinScene {
        name: "ray-tree",
        text: include_str!("../../scenes/ray-tree.toml"),
    },
    BuiltinScene {
        name: "antialiasing",
        text: include_str!("../../scenes/antialiasing.toml"),
    },
    BuiltinScene {
        name: "soft-shadows",
        text: include_str!("../../scenes/soft-shadows.toml"),
    },
    BuiltinScene {
        name: "glossy",
        text: include_str!("../../scenes/glossy.toml"),
    },
    BuiltinScene {
        name: "frosted",
        text: include_str!("../../scenes/frosted.toml"),
    },
    BuiltinScene {
        name: "depth-of-field",
        text: include_str!("../../scenes/depth-of-field.toml"),
    },
    BuiltinScene {
        name: "real-lens",
        text: include_str!("../../scenes/real-lens.toml"),
    },
    BuiltinScene {
        name: "motion-blur",
        text: include_str!("../../scenes/motion-blur.toml"),
    },
    BuiltinScene {
        name: "polarization",
        text: include_str!("../../scenes/polarization.toml"),
    },
    BuiltinScene {
        name: "dispersion",
        text: include_str!("../../scenes/dispersion.toml"),
    },
    BuiltinScene {
        name: "bunny",
        text: include_str!("../../scenes/bunny.toml"),
    },
];

/// Files the built-in scenes refer to, by their path relative to `scenes/`.
static ASSETS: &[(&str, &[u8])] = &[
    (
        "models/bunny.obj",
        include_bytes!("../../scenes/models/bunny.obj"),
    ),
    (
        "models/prism.obj",
        include_bytes!("../../scenes/models/prism.obj"),
    ),
    (
        "models/prism-60.obj",
        include_bytes!("../../scenes/models/prism-60.obj"),
    ),
];

/// The built-in scene called `name`.
pub fn builtin(name: &str) -> Option<&'static BuiltinScene> {
    BUILTIN_SCENES.iter().find(|b| b.name == name)
}

struct Embedded;

impl Assets for Embedded {
    fn read(&self, rel: &str) -> Result<Vec<u8>, String> {
        let rel = rel.trim_start_matches("./");
        ASSETS
            .iter()
            .find(|(p, _)| *p == rel)
            .map(|(_, bytes)| bytes.to_vec())
            .ok_or_else(|| "not embedded in the binary".to_string())
    }
    fn label(&self, rel: &str) -> String {
        format!("builtin:{rel}")
    }
}

impl BuiltinScene {
    /// The one-line description from the scene text.
    pub fn description(&self) -> String {
        super::describe(self.text).unwrap_or_default()
    }

    /// Parses the scene and builds its BVH.
    pub fn load(&self) -> Result<Scene, SceneError> {
        let mut desc = parse(self.text, &format!("builtin:{}", self.name), &Embedded)?;
        desc.name = self.name.to_string();
        Ok(Scene::new(
            desc,
            SceneSource::Builtin(self.name.to_string()),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_scene_loads_and_has_a_description() {
        for b in BUILTIN_SCENES {
            let scene = b.load().unwrap_or_else(|e| panic!("{}: {e}", b.name));
            assert!(!b.description().is_empty(), "{} has no description", b.name);
            assert!(!scene.shapes.is_empty());
        }
    }

    #[test]
    fn every_scene_file_is_built_in_and_every_built_in_scene_is_its_file() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
        let mut files: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .flatten()
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|e| e == "toml"))
            .filter_map(|p| Some(p.file_stem()?.to_string_lossy().into_owned()))
            .collect();
        files.sort();
        let mut built_in: Vec<String> = BUILTIN_SCENES.iter().map(|b| b.name.into()).collect();
        built_in.sort();
        assert_eq!(files, built_in, "scenes/*.toml and the built-in scenes");
        for b in BUILTIN_SCENES {
            let text = std::fs::read_to_string(dir.join(format!("{}.toml", b.name))).unwrap();
            assert_eq!(text, b.text, "builtin:{} is scenes/{0}.toml", b.name);
        }
        // And every model file beside them is embedded for them.
        let models: Vec<String> = std::fs::read_dir(dir.join("models"))
            .unwrap()
            .flatten()
            .map(|e| format!("models/{}", e.file_name().to_string_lossy()))
            .collect();
        for m in &models {
            assert!(ASSETS.iter().any(|(p, _)| p == m), "{m} is not embedded");
        }
    }
}
