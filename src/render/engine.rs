//! The progressive engine: background workers that refine the image pass after pass, and
//! drop their work the moment anything that shapes the image changes.
//!
//! A controller thread owns the state (scene, camera, parameters, size, film) and runs the
//! one render kernel on a pool of worker threads. The caller talks to it over a command
//! channel and receives whole frames over a bounded frame channel; nothing the caller does
//! waits on rendering. Each change that affects the image starts a new *generation*: the
//! caller bumps a shared counter before sending the command, the workers see it at their
//! next pixel and stop, and every frame is tagged with the generation it belongs to, so
//! no frame mixes samples of two.

use super::controller::{Command, Controller};
use super::prerender::{FilmCache, Prerender};
use super::{Film, Frame};
use crate::camera::Camera;
use crate::params::Params;
use crate::scene::Scene;
use crossbeam_channel::{Receiver, Sender};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

/// Frames the channel holds before the newest waits in the engine for room.
const FRAME_CAPACITY: usize = 4;

/// How many worker threads render, and whether they yield to a window.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EngineConfig {
    /// Worker threads (at least 1).
    pub threads: usize,
    /// The workers run below normal priority, so the window's thread never waits for them.
    pub below_window: bool,
}

impl EngineConfig {
    /// Every core at normal priority: for headless rendering.
    pub fn headless() -> Self {
        EngineConfig::with_threads(cores())
    }

    /// `threads` workers at normal priority.
    pub fn with_threads(threads: usize) -> Self {
        EngineConfig {
            threads,
            below_window: false,
        }
    }

    /// Every core, below the window's priority: a 2-core laptop renders on both cores and
    /// its interface still keeps its frames (measured in `priority.rs`).
    pub fn with_ui() -> Self {
        EngineConfig {
            threads: cores(),
            below_window: true,
        }
    }
}

fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// The engine cannot start.
#[derive(Debug, thiserror::Error)]
#[error("cannot start the render threads: {0}")]
pub struct EngineError(#[from] std::io::Error);

/// The progressive renderer, driven from the caller's thread.
pub struct Engine {
    commands: Sender<(u64, Command)>,
    frames: Receiver<Frame>,
    requested: Arc<AtomicU64>,
    params: Params,
    controller: Option<JoinHandle<()>>,
    id: u64,
}

/// Engines started so far, for thread names.
static ENGINES: AtomicU64 = AtomicU64::new(0);

impl Engine {
    /// Starts rendering `scene` through its camera at `width` × `height` with `params`.
    /// `wake` is called after every frame is sent (the window requests a repaint).
    pub fn new(
        scene: Arc<Scene>,
        params: Params,
        width: u32,
        height: u32,
        config: EngineConfig,
        wake: impl Fn() + Send + Sync + 'static,
    ) -> Result<Engine, EngineError> {
        Engine::sharing(scene, params, width, height, config, None, wake)
    }

    /// [`Engine::new`], sharing `cache` from the start (see [`Engine::prerender`]): its
    /// first image too is taken from the cache where it is there.
    pub fn sharing(
        scene: Arc<Scene>,
        params: Params,
        width: u32,
        height: u32,
        config: EngineConfig,
        cache: Option<FilmCache>,
        wake: impl Fn() + Send + Sync + 'static,
    ) -> Result<Engine, EngineError> {
        let id = ENGINES.fetch_add(1, Ordering::Relaxed);
        let (commands, command_rx) = crossbeam_channel::unbounded();
        let (frame_tx, frames) = crossbeam_channel::bounded(FRAME_CAPACITY);
        let requested = Arc::new(AtomicU64::new(1));
        let workers = Arc::new(Mutex::new(Vec::new()));
        let pool = {
            let workers = Arc::clone(&workers);
            rayon::ThreadPoolBuilder::new()
                .num_threads(config.threads.max(1))
                .spawn_handler(move |thread| {
                    let handle = std::thread::Builder::new()
                        .name(format!("rl{id}w{}", thread.index()))
                        .spawn(move || {
                            if config.below_window {
                                super::priority::below_window();
                            }
                            thread.run()
                        })?;
                    workers
                        .lock()
                        .map_err(|_| std::io::Error::other("worker list poisoned"))?
                        .push(handle);
                    Ok(())
                })
                .build()
                .map_err(std::io::Error::other)?
        };
        let controller = Controller::new(
            Film::new(width.max(1), height.max(1)),
            scene,
            params.clone(),
            Arc::clone(&requested),
            frame_tx,
            Box::new(wake),
            cache,
        );
        log::info!(
            "engine {id}: {} workers{}, {width}x{height}",
            config.threads.max(1),
            if config.below_window {
                ", below the window's priority"
            } else {
                ""
            }
        );
        let controller = std::thread::Builder::new()
            .name(format!("rl{id}c"))
            .spawn(move || controller.run(command_rx, pool, workers))?;
        Ok(Engine {
            commands,
            frames,
            requested,
            params,
            controller: Some(controller),
            id,
        })
    }

    /// The frames, oldest first. Only the newest matters to a display; older ones may be
    /// dropped by the engine when the caller falls behind.
    pub fn frames(&self) -> &Receiver<Frame> {
        &self.frames
    }

    /// The newest generation requested; frames of older ones are stale.
    pub fn generation(&self) -> u64 {
        self.requested.load(Ordering::SeqCst)
    }

    /// A prefix shared by the names of this engine's threads (`rl<id>`).
    pub fn thread_prefix(&self) -> String {
        format!("rl{}", self.id)
    }

    /// Sends a command that starts a new generation: bumping the counter first stops the
    /// workers at their next pixel.
    fn restart(&self, command: Command) {
        let generation = self.requested.fetch_add(1, Ordering::SeqCst) + 1;
        // If the engine is gone, there is nothing to restart.
        let _ = self.commands.send((generation, command));
    }

    fn send(&self, command: Command) {
        let _ = self.commands.send((self.generation(), command));
    }

    /// New parameters. A change of `exposure` alone does not restart: it is applied when
    /// a frame is displayed.
    pub fn set_params(&mut self, params: Params) {
        if !params.same_image(&self.params) {
            self.restart(Command::Params(params.clone()));
        }
        self.params = params;
    }

    /// Starts the current image again from its first sample.
    pub fn restart_now(&mut self) {
        self.restart(Command::Params(self.params.clone()));
    }

    /// The parameters last set.
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// A new scene, seen through its own camera.
    pub fn set_scene(&mut self, scene: Arc<Scene>) {
        self.restart(Command::Scene(scene));
    }

    /// A new camera.
    pub fn set_camera(&mut self, camera: Camera) {
        self.restart(Command::Camera(camera));
    }

    /// A new image size (each side at least 1).
    pub fn resize(&mut self, width: u32, height: u32) {
        self.restart(Command::Resize(width.max(1), height.max(1)));
    }

    /// Whether to run on past the target samples per pixel.
    pub fn set_unlimited(&mut self, unlimited: bool) {
        self.send(Command::Unlimited(unlimited));
    }

    /// Whether frames of an image on its way to its target (and not yet clean, see
    /// [`super::CLEAN_NOISE`]) carry a calmed picture for the screen ([`Frame::calm`]): its
    /// noise smoothed where the scene's geometry says the light is one surface's. On by
    /// default; the film is the same either way.
    pub fn set_calm(&mut self, calm: bool) {
        self.send(Command::Calm(calm));
    }

    /// Shares `cache` with the engine: a new image found there is taken from it, and an
    /// image finished when something changes is put there. Once the current image is
    /// finished, the idle workers render `jobs` into it (a change to the current image
    /// stops them at once). Replaces the jobs given before.
    pub fn prerender(&self, cache: &FilmCache, jobs: Vec<Prerender>) {
        self.send(Command::Prerender(cache.clone(), jobs));
    }

    /// Stops refining after the current pass.
    pub fn pause(&self) {
        self.send(Command::Pause(true));
    }

    /// Goes on refining.
    pub fn resume(&self) {
        self.send(Command::Pause(false));
    }

    /// Stops every thread and waits for them: within about one pixel's work of each worker.
    pub fn shutdown(mut self) {
        self.stop();
    }

    fn stop(&mut self) {
        if let Some(controller) = self.controller.take() {
            self.restart(Command::Shutdown);
            let _ = controller.join();
        }
    }
}

impl Drop for Engine {
    fn drop(&mut self) {
        self.stop();
    }
}
