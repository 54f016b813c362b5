//! Snapshots: the newest full frame written as PNG or EXR with its JSON sidecar, which
//! `raylab render --params` turns back into the same image.

use super::RaylabApp;
use super::files::snapshot_path;
use crate::params::Params;
use crate::render::{Rendered, Sidecar, sidecar_path, write_image};
use std::path::{Path, PathBuf};
use std::time::SystemTime;

impl RaylabApp {
    /// Writes the newest full frame to `path` (PNG or EXR) with its sidecar, inside it and
    /// beside it.
    pub(super) fn save_to(&mut self, path: &Path) -> Result<PathBuf, String> {
        let Some(frame) = self.main.frame().filter(|f| !f.is_preview()) else {
            return Err("Nothing to save yet: wait for the first pass".into());
        };
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        }
        let json = sidecar_path(path);
        Sidecar::check_target(&json, None).map_err(|e| e.to_string())?;
        // The frame's own parameters: those the engine rendered it with.
        let params = self.main.engine().params().clone();
        let exposure = self.settings.params.exposure;
        let camera = self.main.camera();
        let params = Params { exposure, ..params };
        let sidecar = Sidecar::new(
            path,
            &Rendered {
                scene: &self.scene,
                camera,
                params: &params,
                width: frame.width,
                height: frame.height,
                samples: frame.progress.spp,
                seconds: frame.progress.elapsed.as_secs_f64(),
                stats: frame.progress.stats,
            },
        );
        write_image(
            path,
            frame.width,
            frame.height,
            &frame.pixels,
            exposure,
            Some(&sidecar),
        )
        .map_err(|e| e.to_string())?;
        Ok(path.to_path_buf())
    }

    /// Ctrl+S: `screenshots/<scene>-<timestamp>.png` and its sidecar.
    pub(super) fn save_snapshot(&mut self) {
        let path = snapshot_path(
            &self.options.snapshot_dir,
            &self.scene.name,
            SystemTime::now(),
        );
        self.report_save(&path);
    }

    /// Saves to `path` and says how it went, naming the files in full; whether it saved.
    pub(super) fn report_save(&mut self, path: &Path) -> bool {
        match self.save_to(path) {
            Ok(p) => {
                let full = std::path::absolute(&p).unwrap_or(p);
                let json = sidecar_path(&full);
                self.toasts
                    .info(format!("Saved {} and {}", full.display(), json.display()));
                true
            }
            Err(e) => {
                self.toasts.error(format!("Not saved: {e}"));
                false
            }
        }
    }
}
