//! The engine's controller: the thread that owns the film and the state, takes commands,
//! runs previews and passes on the worker pool, renders ahead when idle, and sends frames.

use super::calm::{self, Guides};

mod calming;
mod reuse;
use super::generation::{MAX_PASS_SPP, PASS_BUDGET, PREVIEW_LEVELS};
use super::pace::Pace;
use super::prerender::{Ahead, FilmCache, Key, Prerender};
use super::{Calm, Film, Frame, PassObserver, Progress, render_pass, render_preview};
use crate::camera::Camera;
use crate::math::Color;
use crate::params::Params;
use crate::scene::Scene;
use crate::tracer::Stats;
use crossbeam_channel::{Receiver, RecvTimeoutError, Sender, TryRecvError, TrySendError};
use reuse::Kept;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// What the engine tells its controller: new parameters, scene, camera or size (each
/// starts a new generation), unlimited samples, pause, slides to render ahead, stop.
pub(super) enum Command {
    Params(Params),
    Scene(Arc<Scene>),
    Camera(Camera),
    Resize(u32, u32),
    Unlimited(bool),
    Calm(bool),
    Pause(bool),
    Prerender(FilmCache, Vec<Prerender>),
    Shutdown,
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

pub(super) struct Controller {
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
    // Images rendered ahead, and those still to render once idle.
    cache: Option<FilmCache>,
    ahead: Ahead,
    // Whether frames on their way carry a calmed picture; what calms them: the guides of
    // the image's geometry, the last image's spread and its noise at one sample per pixel
    // (kept across changes of parameters, dropped with the scene, camera or size).
    calm: bool,
    guides: Vec<Arc<Guides>>,
    spread: Option<Arc<Vec<f32>>>,
    // The spread at each preview level's blocks, made as they are needed.
    coarse_spread: Vec<(u32, Arc<Vec<f32>>)>,
    one_sample_noise: f32,
    // The workers, while `run` runs: frames are calmed on them.
    pool: Option<Arc<rayon::ThreadPool>>,
    // What is known of an image a change kept in part.
    kept: Kept,
}

impl Controller {
    /// A controller of a new engine, its first generation `scene` with `params` on
    /// `film`.
    pub(super) fn new(
        film: Film,
        scene: Arc<Scene>,
        params: Params,
        requested: Arc<AtomicU64>,
        frames: Sender<Frame>,
        wake: Box<dyn Fn() + Send + Sync>,
        cache: Option<FilmCache>,
    ) -> Controller {
        Controller {
            film,
            camera: scene.camera.clone(),
            scene,
            params,
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
            requested,
            outbox: Outbox {
                tx: frames,
                pending: None,
            },
            wake,
            failure: None,
            cache,
            ahead: Ahead::default(),
            calm: true,
            guides: Vec::new(),
            spread: None,
            coarse_spread: Vec::new(),
            one_sample_noise: 0.0,
            pool: None,
            kept: Kept::default(),
        }
    }

    pub(super) fn run(
        mut self,
        commands: Receiver<(u64, Command)>,
        pool: rayon::ThreadPool,
        workers: Arc<Mutex<Vec<JoinHandle<()>>>>,
    ) {
        let pool = Arc::new(pool);
        self.pool = Some(Arc::clone(&pool));
        'outer: loop {
            // Take every command that waits; wait for one when there is nothing to do.
            loop {
                let idle = self.failure.is_some()
                    || (!self.needs_preview()
                        && (self.paused || (self.target_reached() && !self.has_jobs())));
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
                if !self.adopt() {
                    self.preview(&pool);
                }
            } else if !self.paused && !self.target_reached() {
                self.pass(&pool);
            } else if !self.paused
                && let Some(cache) = &self.cache
            {
                let watch = Watch {
                    requested: &self.requested,
                    generation: self.generation,
                };
                self.ahead.step(cache, &pool, &watch);
            }
        }
        self.pool = None;
        drop(pool);
        if let Ok(mut workers) = workers.lock() {
            for handle in workers.drain(..) {
                let _ = handle.join();
            }
        }
    }

    /// Whether there are images to render ahead.
    fn has_jobs(&self) -> bool {
        self.cache.is_some() && !self.ahead.is_empty()
    }

    /// The key of the image being made.
    fn key(&self) -> Option<Key> {
        let size = (self.film.width(), self.film.height());
        Key::of(&self.scene, &self.camera, &self.params, size)
    }

    /// Starts the generation from the cache's film of the new image, if it has one: no
    /// preview, the film's samples shown at once. Whether it did.
    fn adopt(&mut self) -> bool {
        if self.preview_level > 0 || self.film.spp() > 0 {
            return false;
        }
        let Some(film) = self.key().and_then(|k| self.cache.as_ref()?.take(&k)) else {
            return false;
        };
        log::debug!(
            "{}: {} samples per pixel taken from the images rendered ahead",
            self.scene.source.reference(),
            film.spp()
        );
        self.kept.ceiling = film.taken.iter().map(|t| t.count).max().unwrap_or(0);
        self.film = film;
        self.preview_level = PREVIEW_LEVELS.len();
        self.finished = self.target_reached().then(|| self.started.elapsed());
        self.send_frame();
        true
    }

    /// Before a change of image: a finished image goes to the cache (the lecturer may come
    /// back to it); a copy, where the film is to be `kept` in part.
    fn stash(&mut self, kept: bool) {
        if !(self.film.spp() > 0 && self.target_reached()) {
            return;
        }
        if let (Some(cache), Some(key)) = (&self.cache, self.key()) {
            let film = match kept {
                true => self.film.clone(),
                false => {
                    let fresh = Film::new(self.film.width(), self.film.height());
                    std::mem::replace(&mut self.film, fresh)
                }
            };
            cache.put(key, film);
        }
    }

    /// Applies a command; false to shut down.
    fn apply(&mut self, generation: u64, command: Command) -> bool {
        // What a change of parameters reaches, where the film can keep the pixels it
        // cannot alter (a finished image is then stashed as a copy).
        let reach = match &command {
            Command::Params(p) => self.reach(p),
            _ => None,
        };
        if matches!(
            command,
            Command::Params(_) | Command::Scene(_) | Command::Camera(_) | Command::Resize(..)
        ) {
            self.stash(reach.is_some());
        }
        let mut kept = false;
        let restart = match command {
            Command::Shutdown => return false,
            Command::Params(p) => {
                kept = reach.is_some_and(|r| self.keep_unreached(&r));
                self.params = p;
                true
            }
            Command::Scene(scene) => {
                self.camera = scene.camera.clone();
                self.scene = scene;
                self.forget_geometry();
                true
            }
            Command::Camera(camera) => {
                self.camera = camera;
                self.forget_geometry();
                true
            }
            Command::Resize(w, h) => {
                self.film.resize(w, h);
                self.forget_geometry();
                true
            }
            Command::Calm(calm) => {
                self.calm = calm;
                self.send_frame();
                false
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
            Command::Prerender(cache, jobs) => {
                self.cache = Some(cache);
                self.ahead = Ahead::new(jobs);
                false
            }
        };
        if restart {
            if let Some(spread) = calm::spread(&self.film) {
                self.spread = Some(Arc::new(spread));
                self.coarse_spread.clear();
                // Noise falls as one over the square root of the samples (or faster, with
                // Sobol's: this errs towards not calming).
                let noise = self.film.noise(self.params.exposure).unwrap_or(0.0);
                self.one_sample_noise = noise * (self.film.spp() as f32).sqrt();
            }
            self.generation = self.generation.max(generation);
            let few = self.restart_kept(kept);
            self.preview_level = if few { PREVIEW_LEVELS.len() } else { 0 };
            self.started = Instant::now();
            self.finished = None;
            self.pass_time = Duration::ZERO;
            self.passes = 0;
            self.pass_rays = 0;
            self.pace = Pace::default();
            self.stats = Stats::default();
            self.failure = None;
            if kept && self.film.spp() > 0 {
                // Nothing to render again: the image as it is, at once.
                self.finished = self.target_reached().then(|| self.started.elapsed());
                self.send_frame();
            }
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
        if self.kept.reached() < 1.0 {
            return self.preview_reached(pool, block);
        }
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
            let calm = self.calm_preview(&pixels, block);
            if self.superseded() {
                return;
            }
            self.emit(Arc::new(pixels), Arc::new(Vec::new()), (block, block), calm);
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
        let catching_up = self.pass_to(self.film.spp() + n);
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
        if result.is_err() && !catching_up {
            self.stopped_ahead();
        }
        // Cancelled means a newer generation was requested: its command waits, and restarts.
        if let Ok(stats) = result {
            self.pass_time += start.elapsed();
            self.passes += 1;
            self.pass_rays += stats.total_rays();
            self.pace.pass(start, Instant::now(), n);
            self.stats += stats;
            if self.target_reached() {
                let took = self.started.elapsed();
                log::debug!(
                    "{}: finished at {} samples per pixel in {:.2} s",
                    self.scene.source.reference(),
                    self.film.spp(),
                    took.as_secs_f64()
                );
                self.finished = Some(took);
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
            pixels_done: super::adaptive::acts(&self.params)
                .then(|| self.film.done_pixels() as f32 / self.film.pixels.len().max(1) as f32),
            stats: self.stats,
            paused: self.paused,
            reached: self.kept.reached(),
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
        self.emit(pixels, Arc::new(Vec::new()), (1, 1), None);
    }

    fn send_frame(&mut self) {
        if self.film.spp() == 0 {
            return;
        }
        let pixels = self.frame_pixels();
        let cost = Arc::new(self.film.cost());
        let calm = self.calm_film();
        if self.superseded() {
            return;
        }
        let coarsest = calm.as_ref().map_or(1, |c| c.block);
        self.emit(pixels, cost, (1, coarsest), calm);
    }

    /// Sends a frame of `pixels` in blocks of `block`, the coarsest shown `coarsest`
    /// ([`Frame::coarsest`]).
    fn emit(
        &mut self,
        pixels: Arc<Vec<Color>>,
        cost: Arc<Vec<f32>>,
        (block, coarsest): (u32, u32),
        calm: Option<Calm>,
    ) {
        let frame = Frame {
            generation: self.generation,
            width: self.film.width(),
            height: self.film.height(),
            pixels,
            cost,
            block,
            coarsest,
            progress: self.progress(),
            calm,
        };
        self.outbox.send(frame);
        (self.wake)();
    }
}
