//! Snapshots: the newest full frame written as PNG or EXR with its JSON sidecar, which
//! `raylab render --params` turns back into the same image. The files are written on a
//! thread of their own (a 1920×1080 PNG takes a good part of a second to encode): the
//! window goes on drawing, and says how it went when the thread is done.

use super::RaylabApp;
use super::files::snapshot_path;
use crate::params::Params;
use crate::render::{Frame, Rendered, Sidecar, sidecar_path, write_image};
use crossbeam_channel::{Receiver, TryRecvError};
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

/// A snapshot being written.
pub(super) struct Saving {
    /// Where it goes, the image's path.
    path: PathBuf,
    /// Whether the user chose the folder (Save as…): snapshots go there from now on, once
    /// this one is written.
    chosen: bool,
    /// The thread's answer: whether it wrote both files.
    done: Receiver<Result<(), String>>,
}

impl Drop for Saving {
    /// Waits for the thread to finish writing: a window closed a moment after Ctrl+S must
    /// not cut its snapshot off half written.
    fn drop(&mut self) {
        let _ = self.done.recv_timeout(WAIT_AT_EXIT);
    }
}

/// The longest a closing window waits for a snapshot being written (a 4K EXR over a slow
/// network share takes seconds; a thread stuck for longer is left).
const WAIT_AT_EXIT: Duration = Duration::from_secs(30);

/// Writes `frame` to `path` (PNG or EXR) with `sidecar`, inside it and beside it, making
/// the folder where there is none; never over a sidecar raylab did not write.
fn write_snapshot(
    path: &Path,
    frame: &Frame,
    exposure: f32,
    sidecar: &Sidecar,
) -> Result<(), String> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    Sidecar::check_target(&sidecar_path(path), None).map_err(|e| e.to_string())?;
    write_image(
        path,
        frame.width,
        frame.height,
        &frame.pixels,
        exposure,
        Some(sidecar),
    )
    .map_err(|e| e.to_string())
}

impl RaylabApp {
    /// Starts writing the newest full frame to `path` with its sidecar; `chosen` where the
    /// user chose the place. Says at once when there is nothing to save.
    pub(super) fn save_to(&mut self, ctx: &egui::Context, path: &Path, chosen: bool) {
        let Some(frame) = self.main.frame().filter(|f| !f.is_preview()).cloned() else {
            self.toasts
                .error("Not saved: nothing to save yet, wait for the first pass");
            return;
        };
        // The frame's own parameters: those the engine rendered it with.
        let exposure = self.settings.params.exposure;
        let params = Params {
            exposure,
            ..self.main.engine().params().clone()
        };
        let sidecar = Sidecar::new(
            path,
            &Rendered {
                scene: &self.scene,
                camera: self.main.camera(),
                params: &params,
                width: frame.width,
                height: frame.height,
                samples: frame.progress.spp,
                seconds: frame.progress.elapsed.as_secs_f64(),
                stats: frame.progress.stats,
            },
        );
        let (tell, done) = crossbeam_channel::bounded(1);
        let ctx = ctx.clone();
        let to = path.to_path_buf();
        let spawned = std::thread::Builder::new()
            .name("raylab-snapshot".into())
            .spawn(move || {
                // The window may be gone when the files are: nobody to tell then.
                let _ = tell.send(write_snapshot(&to, &frame, exposure, &sidecar));
                ctx.request_repaint();
            });
        match spawned {
            Ok(_) => self.saving.push(Saving {
                path: path.to_path_buf(),
                chosen,
                done,
            }),
            Err(e) => self.toasts.error(format!("Not saved: {e}")),
        }
    }

    /// Ctrl+S: `<snapshot folder>/<scene>-<timestamp>.png` and its sidecar.
    pub(super) fn save_snapshot(&mut self, ctx: &egui::Context) {
        let path = snapshot_path(
            &self.options.snapshot_dir,
            &self.scene.name,
            SystemTime::now(),
        );
        self.save_to(ctx, &path, false);
    }

    /// Says how each snapshot written since the last frame went, naming the files in
    /// full.
    pub(super) fn receive_saves(&mut self) {
        let mut i = 0;
        while i < self.saving.len() {
            let result = match self.saving[i].done.try_recv() {
                Err(TryRecvError::Empty) => {
                    i += 1;
                    continue;
                }
                Ok(result) => result,
                Err(TryRecvError::Disconnected) => Err("the writing thread stopped".into()),
            };
            let saving = self.saving.swap_remove(i);
            match result {
                Ok(()) => {
                    let full =
                        std::path::absolute(&saving.path).unwrap_or_else(|_| saving.path.clone());
                    let json = sidecar_path(&full);
                    self.toasts
                        .info(format!("Saved {} and {}", full.display(), json.display()));
                    if saving.chosen
                        && let Some(dir) = full.parent().filter(|d| d.is_dir())
                    {
                        self.options.snapshot_dir = dir.to_path_buf();
                    }
                }
                Err(e) => self.toasts.error(format!("Not saved: {e}")),
            }
        }
    }

    /// Whether a snapshot is still being written.
    pub fn saving(&self) -> bool {
        !self.saving.is_empty()
    }
}
