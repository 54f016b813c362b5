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

use super::pace::Pace;
use super::{Film, Frame, PassObserver, Progress, render_pass, render_preview};
use crate::camera::Camera;
use crate::math::Color;
use crate::params::Params;
use crate::scene::Scene;
use crate::tracer::Stats;
use crossbeam_channel::{Receiver, RecvTimeoutError, Sender, TryRecvError, TrySendError};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// The resolution pyramid that opens every generation: previews with one sample per block
/// of these sides, each upsampled smoothly, before the full passes. The first costs 1/64
/// of a pass, so it shows within a frame; a change cancels the rest.
pub const PREVIEW_LEVELS: [u32; 3] = [8, 4, 2];
/// The most samples per pixel one pass adds.
pub const MAX_PASS_SPP: u32 = 16;
/// Passes are kept about this long, so that frames keep coming.
pub const PASS_BUDGET: Duration = Duration::from_millis(250);
/// Frames the channel holds before the newest waits in the engine for room.
const FRAME_CAPACITY: usize = 4;

/// How many worker threads render.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EngineConfig {
    /// Worker threads (at least 1).
    pub threads: usize,
}

impl EngineConfig {
    /// Every core: for headless rendering.
    pub fn headless() -> Self {
        EngineConfig { threads: cores() }
    }

    /// Every core but one, which the window keeps for itself (at least one worker).
    pub fn with_ui() -> Self {
        EngineConfig {
            threads: cores().saturating_sub(1).max(1),
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

enum Command {
    Params(Params),
    Scene(Arc<Scene>),
    Camera(Camera),
    Resize(u32, u32),
    Unlimited(bool),
    Pause(bool),
    Shutdown,
}

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
                        .spawn(|| thread.run())?;
                    workers
                        .lock()
                        .map_err(|_| std::io::Error::other("worker list poisoned"))?
                        .push(handle);
                    Ok(())
                })
                .build()
                .map_err(std::io::Error::other)?
        };
        let camera = scene.camera.clone();
        let controller = Controller {
            film: Film::new(width.max(1), height.max(1)),
            scene,
            camera,
            params: params.clone(),
            unlimited: false,
            paused: false,
            generation: 1,
            preview_level: 0,
            started: Instant::now(),
            finished: None,
            pass_time: Duration::ZERO,
            passes: 0,
            pass_rays: 0,
            pace: Pace::default(),
            stats: Stats::default(),
            requested: Arc::clone(&requested),
            outbox: Outbox {
                tx: frame_tx,
                pending: None,
            },
            wake: Box::new(wake),
            failure: None,
        };
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

/// The frame channel, and the newest frame that found it full.
struct Outbox {
    tx: Sender<Frame>,
    pending: Option<Frame>,
}

impl Outbox {
    /// Sends what waits; false if it still waits.
    fn flush(&mut self) -> bool {
        if let Some(frame) = self.pending.take() {
            match self.tx.try_send(frame) {
                Ok(()) => {}
                Err(TrySendError::Full(frame)) => self.pending = Some(frame),
                Err(TrySendError::Disconnected(_)) => {}
            }
        }
        self.pending.is_none()
    }

    /// Sends `frame`, or keeps it (replacing an older one) until there is room.
    fn send(&mut self, frame: Frame) {
        if self.flush() {
            if let Err(TrySendError::Full(frame)) = self.tx.try_send(frame) {
                self.pending = Some(frame);
            }
        } else {
            self.pending = Some(frame);
        }
    }
}

/// Stops a pass as soon as a newer generation is requested.
struct Watch<'a> {
    requested: &'a AtomicU64,
    generation: u64,
}

impl PassObserver for Watch<'_> {
    fn keep_going(&self) -> bool {
        self.requested.load(Ordering::Relaxed) == self.generation
    }
}

struct Controller {
    scene: Arc<Scene>,
    camera: Camera,
    params: Params,
    film: Film,
    unlimited: bool,
    paused: bool,
    generation: u64,
    // The next level of PREVIEW_LEVELS to render; past the end once they are done.
    preview_level: usize,
    started: Instant,
    // How long the generation took to reach its target, once it has.
    finished: Option<Duration>,
    // Time, count and rays of the full passes of this generation (not the preview's).
    pass_time: Duration,
    passes: u32,
    pass_rays: u64,
    // How fast the newest passes went: the time left.
    pace: Pace,
    // Everything traced in this generation, the preview included.
    stats: Stats,
    requested: Arc<AtomicU64>,
    outbox: Outbox,
    wake: Box<dyn Fn() + Send + Sync>,
    // Why this generation stopped, if a pass panicked.
    failure: Option<String>,
}

impl Controller {
    fn run(
        mut self,
        commands: Receiver<(u64, Command)>,
        pool: rayon::ThreadPool,
        workers: Arc<Mutex<Vec<JoinHandle<()>>>>,
    ) {
        'outer: loop {
            // Take every command that waits; wait for one when there is nothing to do.
            loop {
                let idle = self.failure.is_some()
                    || (!self.needs_preview() && (self.paused || self.target_reached()));
                let next = if idle {
                    if self.outbox.pending.is_some() {
                        match commands.recv_timeout(Duration::from_millis(10)) {
                            Ok(c) => Some(c),
                            Err(RecvTimeoutError::Timeout) => None,
                            Err(RecvTimeoutError::Disconnected) => break 'outer,
                        }
                    } else {
                        match commands.recv() {
                            Ok(c) => Some(c),
                            Err(_) => break 'outer,
                        }
                    }
                } else {
                    match commands.try_recv() {
                        Ok(c) => Some(c),
                        Err(TryRecvError::Empty) => None,
                        Err(TryRecvError::Disconnected) => break 'outer,
                    }
                };
                self.outbox.flush();
                let Some((generation, command)) = next else {
                    break;
                };
                if !self.apply(generation, command) {
                    break 'outer;
                }
            }
            if self.failure.is_some() {
                continue;
            } else if self.needs_preview() {
                self.preview(&pool);
            } else if !self.paused && !self.target_reached() {
                self.pass(&pool);
            }
        }
        drop(pool);
        if let Ok(mut workers) = workers.lock() {
            for handle in workers.drain(..) {
                let _ = handle.join();
            }
        }
    }

    /// Applies a command; false to shut down.
    fn apply(&mut self, generation: u64, command: Command) -> bool {
        let restart = match command {
            Command::Shutdown => return false,
            Command::Params(p) => {
                self.params = p;
                true
            }
            Command::Scene(scene) => {
                self.camera = scene.camera.clone();
                self.scene = scene;
                true
            }
            Command::Camera(camera) => {
                self.camera = camera;
                true
            }
            Command::Resize(w, h) => {
                self.film.resize(w, h);
                true
            }
            Command::Unlimited(u) => {
                self.unlimited = u;
                self.finished = self.target_reached().then(|| self.started.elapsed());
                self.send_frame();
                false
            }
            Command::Pause(p) => {
                self.paused = p;
                self.pace.pause();
                self.send_frame();
                false
            }
        };
        if restart {
            self.generation = self.generation.max(generation);
            self.film.clear();
            self.preview_level = 0;
            self.started = Instant::now();
            self.finished = None;
            self.pass_time = Duration::ZERO;
            self.passes = 0;
            self.pass_rays = 0;
            self.pace = Pace::default();
            self.stats = Stats::default();
            self.failure = None;
        }
        true
    }

    fn target(&self) -> Option<u32> {
        (!self.unlimited).then_some(self.params.spp)
    }

    /// The target reached, or every pixel stopped by adaptive sampling.
    fn target_reached(&self) -> bool {
        self.target().is_some_and(|t| self.film.spp() >= t) || self.film.all_done()
    }

    fn needs_preview(&self) -> bool {
        self.preview_level < PREVIEW_LEVELS.len()
    }

    /// The next level of the pyramid, unless a newer generation cancels it.
    fn preview(&mut self, pool: &rayon::ThreadPool) {
        let (w, h) = (self.film.width(), self.film.height());
        let block = PREVIEW_LEVELS[self.preview_level];
        let result = crate::guard::caught(|| {
            pool.install(|| {
                render_preview(
                    &self.scene,
                    &self.camera,
                    &self.params,
                    w,
                    h,
                    block,
                    &Watch {
                        requested: &self.requested,
                        generation: self.generation,
                    },
                )
            })
        });
        let result = match result {
            Ok(result) => result,
            Err(failure) => return self.fail(failure),
        };
        if let Ok((pixels, stats)) = result {
            self.preview_level += 1;
            self.stats += stats;
            self.emit(Arc::new(pixels), Arc::new(Vec::new()), block);
        }
    }

    /// Samples per pixel for the next pass: 1, 1, 2, 4, ... up to the cap, kept within the
    /// time budget, and never past the target.
    fn next_pass_spp(&self) -> u32 {
        let grow = if self.passes < 2 {
            1
        } else {
            1 << (self.passes - 1).min(4)
        };
        let mut n = grow.min(MAX_PASS_SPP);
        if self.film.spp() > 0 {
            let per_spp = self.pass_time.as_secs_f64() / self.film.spp() as f64;
            if per_spp > 0.0 {
                n = n.min(((PASS_BUDGET.as_secs_f64() / per_spp) as u32).max(1));
            }
        }
        match self.target() {
            Some(t) => n.min(t.saturating_sub(self.film.spp())).max(1),
            None => n,
        }
    }

    fn pass(&mut self, pool: &rayon::ThreadPool) {
        let n = self.next_pass_spp();
        let start = Instant::now();
        let watch = Watch {
            requested: &self.requested,
            generation: self.generation,
        };
        let result = crate::guard::caught(|| {
            pool.install(|| {
                render_pass(
                    &self.scene,
                    &self.camera,
                    &self.params,
                    &mut self.film,
                    n,
                    &watch,
                )
            })
        });
        let result = match result {
            Ok(result) => result,
            Err(failure) => return self.fail(failure),
        };
        // Cancelled means a newer generation was requested: its command waits, and restarts.
        if let Ok(stats) = result {
            self.pass_time += start.elapsed();
            self.passes += 1;
            self.pass_rays += stats.total_rays();
            self.pace.pass(start, Instant::now(), n);
            self.stats += stats;
            if self.target_reached() {
                self.finished = Some(self.started.elapsed());
            }
            self.send_frame();
        }
    }

    fn progress(&self) -> Progress {
        let spp = self.film.spp();
        let target = self.target();
        let secs = self.pass_time.as_secs_f64();
        let eta = target.and_then(|t| self.pace.time_left(t.saturating_sub(spp)));
        Progress {
            spp,
            target,
            elapsed: self.finished.unwrap_or_else(|| self.started.elapsed()),
            rays_per_second: if secs > 0.0 {
                self.pass_rays as f64 / secs
            } else {
                0.0
            },
            eta,
            noise: self.film.noise(self.params.exposure),
            pixels_done: self
                .params
                .noise_target
                .map(|_| self.film.done_pixels() as f32 / self.film.pixels.len().max(1) as f32),
            stats: self.stats,
            paused: self.paused,
            failure: self.failure.clone(),
        }
    }

    /// Sends the film as it is (or, before any pass, nothing new: progress only).
    /// Stops the generation after a pass panicked, and says why in a frame of what the
    /// film holds (cleared: a pass may have stopped half-way).
    fn fail(&mut self, failure: String) {
        self.failure = Some(failure);
        self.film.clear();
        let pixels = Arc::new(vec![
            Color::ZERO;
            self.film.width() as usize * self.film.height() as usize
        ]);
        self.emit(pixels, Arc::new(Vec::new()), 1);
    }

    fn send_frame(&mut self) {
        if self.film.spp() == 0 {
            return;
        }
        let pixels = Arc::new(self.film.pixels().collect());
        let cost = Arc::new(self.film.cost());
        self.emit(pixels, cost, 1);
    }

    fn emit(&mut self, pixels: Arc<Vec<Color>>, cost: Arc<Vec<f32>>, block: u32) {
        let frame = Frame {
            generation: self.generation,
            width: self.film.width(),
            height: self.film.height(),
            pixels,
            cost,
            block,
            progress: self.progress(),
        };
        self.outbox.send(frame);
        (self.wake)();
    }
}
