//! Loading scenes off the UI thread, and watching the scene file: saved in an editor, it
//! reloads; a file that failed to open opens once it is fixed.

use super::RaylabApp;
use crate::params::Params;
use crate::scene::{Scene, SceneError, SceneSource};
use crossbeam_channel::{Receiver, Sender};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::{Duration, SystemTime};

/// Why a scene is being loaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LoadPurpose {
    /// Opened by the user: the scene's defaults replace the parameters.
    Open,
    /// Its file changed on disk: parameters the user changed are kept.
    Reload,
}

/// A finished load.
pub(crate) struct Loaded {
    purpose: LoadPurpose,
    // The number of Opens asked for when this load was: a later Open overtakes it.
    opens: u64,
    result: Result<Scene, SceneError>,
}

/// The watched file: its path, when it was last seen to change, and whether it is the scene
/// shown (reload) or one that failed to open (open again).
type Watched = Option<(PathBuf, Option<SystemTime>, LoadPurpose)>;

/// Scenes loading on threads of their own, and the file watched for changes. A watcher
/// thread reads the file's time stamp twice a second and wakes the window only when it
/// changed, so an idle window does not repaint to poll.
pub(crate) struct Loader {
    tx: Sender<Loaded>,
    rx: Receiver<Loaded>,
    loading: usize,
    // Opens asked for so far. Loads run on threads of their own and can finish out of
    // order: the scene of an older Open (two slides asked for quickly) must not arrive
    // after the newer one and replace it.
    opens: u64,
    watched: Arc<Mutex<Watched>>,
    changed: Receiver<(PathBuf, LoadPurpose)>,
    // The file of the last Open, to watch if it fails.
    opening: Option<PathBuf>,
    // Woken when a load finishes or the watched file changes.
    ctx: egui::Context,
}

/// How often the watched file's time stamp is read.
const POLL: Duration = Duration::from_millis(500);

impl Loader {
    pub(crate) fn new(ctx: &egui::Context) -> Loader {
        let (tx, rx) = crossbeam_channel::unbounded();
        let (changed_tx, changed) = crossbeam_channel::unbounded();
        let watched: Arc<Mutex<Watched>> = Arc::new(Mutex::new(None));
        let shared = Arc::clone(&watched);
        let wake = ctx.clone();
        // Ends once the loader is dropped (it holds the other reference).
        std::thread::spawn(move || {
            while Arc::strong_count(&shared) > 1 {
                std::thread::sleep(POLL);
                let mut guard = shared.lock().unwrap_or_else(|e| e.into_inner());
                if let Some((path, seen, purpose)) = guard.as_mut() {
                    let now = modified(path);
                    if now != *seen {
                        *seen = now;
                        let _ = changed_tx.send((path.clone(), *purpose));
                        wake.request_repaint();
                    }
                }
            }
        });
        Loader {
            tx,
            rx,
            loading: 0,
            opens: 0,
            watched,
            changed,
            opening: None,
            ctx: ctx.clone(),
        }
    }

    /// Loads a scene file, built-in name or model file on a thread of its own.
    pub(crate) fn load(&mut self, reference: std::ffi::OsString, purpose: LoadPurpose) {
        if purpose == LoadPurpose::Open {
            self.opening = Some(PathBuf::from(&reference)).filter(|p| p.is_file());
            self.opens += 1;
        }
        let opens = self.opens;
        let tx = self.tx.clone();
        let wake = self.ctx.clone();
        self.loading += 1;
        std::thread::spawn(move || {
            let result = crate::guard::caught(|| Scene::load(&reference)).unwrap_or_else(|e| {
                Err(crate::scene::SceneError::new(
                    crate::scene::Location::file(reference.to_string_lossy()),
                    e,
                ))
            });
            let _ = tx.send(Loaded {
                purpose,
                opens,
                result,
            });
            wake.request_repaint();
        });
    }

    /// Whether a scene is loading.
    pub(crate) fn is_loading(&self) -> bool {
        self.loading > 0
    }

    /// Whether an Open was asked after Open number `opens` (whose scene is then stale).
    pub(crate) fn overtaken(&self, opens: u64) -> bool {
        self.opens != opens
    }

    fn set_watched(&self, watched: Watched) {
        *self.watched.lock().unwrap_or_else(|e| e.into_inner()) = watched;
    }

    /// Watches `scene`'s file, if it has one, to reload it when it changes.
    pub(crate) fn watch(&mut self, scene: &Scene) {
        self.set_watched(match &scene.source {
            SceneSource::File(path) => Some((path.clone(), modified(path), LoadPurpose::Reload)),
            _ => None,
        });
    }

    /// Starts a load for each change the watcher saw.
    pub(crate) fn poll(&mut self) {
        while let Ok((path, purpose)) = self.changed.try_recv() {
            self.load(path.into_os_string(), purpose);
        }
    }

    /// The next finished load that no later Open has overtaken (those are dropped). A
    /// file that failed to open is watched from now on.
    fn receive(&mut self) -> Option<Loaded> {
        let loaded = loop {
            let loaded = self.rx.try_recv().ok()?;
            self.loading = self.loading.saturating_sub(1);
            if loaded.opens == self.opens {
                break loaded;
            }
        };
        if loaded.purpose == LoadPurpose::Open
            && loaded.result.is_err()
            && let Some(path) = self.opening.take()
        {
            self.set_watched(Some((path.clone(), modified(&path), LoadPurpose::Open)));
        }
        Some(loaded)
    }
}

impl RaylabApp {
    /// Loads a scene file, built-in name or model file; it replaces the scene when loaded.
    pub fn open_scene(&mut self, reference: impl AsRef<std::ffi::OsStr>) {
        self.loader
            .load(reference.as_ref().to_os_string(), LoadPurpose::Open);
    }

    /// Takes the scenes that finished loading: a good one opened starts arriving
    /// (`arrival.rs`), a good one reloaded replaces the scene shown at once, a bad one
    /// leaves it and shows what is wrong and where.
    pub(super) fn receive_scenes(&mut self, ctx: &egui::Context) {
        while let Some(loaded) = self.loader.receive() {
            let scene = match loaded.result {
                Ok(scene) => Arc::new(scene),
                Err(e) => {
                    self.error = Some(e.to_string());
                    self.toasts
                        .error("The scene has an error: see above the image");
                    continue;
                }
            };
            match loaded.purpose {
                LoadPurpose::Open => self.stage(ctx, scene, loaded.opens),
                LoadPurpose::Reload => {
                    let s = &mut self.settings;
                    s.params = merge_defaults(&s.params, &self.scene.params, &scene.params);
                    // A camera the user moved stays.
                    if s.camera == self.scene.camera {
                        s.camera = scene.camera.clone();
                    }
                    self.keep_side_a();
                    self.instruments.section.zoom_to(1.0);
                    self.replace_scene(scene, Some("Reloaded"));
                }
            }
        }
    }
}

/// The parameters after the scene's defaults change from `old` to `new`: a parameter the
/// user left at the old default takes the new one; one the user changed stays.
fn merge_defaults(current: &Params, old: &Params, new: &Params) -> Params {
    let json = |p: &Params| {
        serde_json::to_value(p)
            .ok()
            .and_then(|v| v.as_object().cloned())
            .unwrap_or_default()
    };
    let (cur, old, new) = (json(current), json(old), json(new));
    let merged: serde_json::Map<String, serde_json::Value> = cur
        .iter()
        .map(|(k, v)| {
            let v = if old.get(k) == Some(v) {
                new.get(k).unwrap_or(v)
            } else {
                v
            };
            (k.clone(), v.clone())
        })
        .collect();
    serde_json::from_value(serde_json::Value::Object(merged)).unwrap_or_else(|_| current.clone())
}

fn modified(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_open_overtaken_by_a_later_one_is_dropped() {
        let mut loader = Loader::new(&egui::Context::default());
        // The first is the slowest to load (a 100k-triangle mesh), the second quick.
        loader.load("bunny".into(), LoadPurpose::Open);
        loader.load("glass".into(), LoadPurpose::Open);
        let deadline = std::time::Instant::now() + Duration::from_secs(60);
        let mut arrived = Vec::new();
        while loader.is_loading() {
            assert!(std::time::Instant::now() < deadline, "loads never ended");
            match loader.receive() {
                Some(l) => arrived.push(l.result.map(|s| s.name).unwrap_or_default()),
                None => std::thread::sleep(Duration::from_millis(5)),
            }
        }
        assert_eq!(arrived, ["glass"]);
    }

    #[test]
    fn reload_keeps_what_the_user_changed_and_takes_new_defaults() {
        let old = Params::default();
        let new = Params {
            spp: 64,
            max_depth: 3,
            ..Params::default()
        };
        let current = Params {
            max_depth: 12,
            ..Params::default()
        };
        let merged = merge_defaults(&current, &old, &new);
        assert_eq!(merged.spp, 64, "left at the old default: takes the new one");
        assert_eq!(merged.max_depth, 12, "changed by the user: kept");
    }
}
