//! What the window remembers between runs: the scene, and the controls' settings for it.

use super::Settings;
use crate::camera::Camera;
use crate::params::Params;
use crate::scene::Scene;
use serde::{Deserialize, Serialize};

/// What the window remembers between runs. Every field has a default, so what an older
/// raylab saved still loads when a field is added.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(default)]
pub(super) struct Persisted {
    pub(super) scene: String,
    pub(super) params: Params,
    pub(super) camera: Option<Camera>,
    pub(super) resolution: f32,
    pub(super) unlimited: bool,
    pub(super) calm: bool,
    pub(super) ui_scale: f32,
    /// The folder of the last Save as…, where snapshots go from then on.
    pub(super) snapshot_dir: Option<std::path::PathBuf>,
}

impl Default for Persisted {
    fn default() -> Self {
        Persisted {
            scene: String::new(),
            params: Params::default(),
            camera: None,
            resolution: 1.0,
            unlimited: false,
            calm: true,
            ui_scale: 1.0,
            snapshot_dir: None,
        }
    }
}

const STORAGE_KEY: &str = "raylab";

/// The state remembered by the last run, if any.
pub(super) fn load(cc: &eframe::CreationContext<'_>) -> Option<Persisted> {
    cc.storage.and_then(|s| eframe::get_value(s, STORAGE_KEY))
}

/// Remembers `scene`, `settings`, the UI scale and the snapshots' folder for the next run.
pub(super) fn save(
    storage: &mut dyn eframe::Storage,
    scene: &Scene,
    settings: &Settings,
    ui_scale: f32,
    snapshot_dir: &std::path::Path,
) {
    let state = Persisted {
        scene: scene.source.reference(),
        params: settings.params.clone(),
        camera: Some(settings.camera.clone()),
        resolution: settings.resolution,
        unlimited: settings.unlimited,
        calm: settings.calm,
        ui_scale,
        snapshot_dir: Some(snapshot_dir.to_path_buf()),
    };
    eframe::set_value(storage, STORAGE_KEY, &state);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn remembered_state_from_an_older_raylab_still_loads() {
        // Missing fields take their defaults instead of losing everything remembered.
        let old: Persisted =
            serde_json::from_str(r#"{"scene": "builtin:glass", "params": {"ior": 1.33}}"#).unwrap();
        assert_eq!(old.scene, "builtin:glass");
        assert_eq!(old.params.ior, Some(1.33));
        assert_eq!(
            (old.resolution, old.unlimited, old.calm, old.camera),
            (1.0, false, true, None)
        );
    }
}
