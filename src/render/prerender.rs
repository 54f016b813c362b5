//! Images rendered before they are asked for: the lecture's next and previous slides,
//! rendered by an engine's idle workers, kept in a cache of bounded size that every engine
//! of the window reads. An engine whose new generation matches a cached image (the same
//! built-in scene, camera, parameters and size) takes it as its film and goes on from its
//! samples: since a film after N samples is bit for bit the same however its passes were
//! split, the image is the one the engine would have made.

use super::Film;
use crate::camera::Camera;
use crate::params::Params;
use crate::scene::{Scene, SceneSource};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// The most memory the cache holds: about seven films of 960 × 540, or two of 1920 ×
/// 1080. The oldest go first.
pub const PRERENDER_MEMORY: usize = 256 << 20;

/// What an image is of: a built-in scene (by name), the camera, the parameters (the
/// display exposure aside) and the size.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Key {
    scene: String,
    camera: Camera,
    params: Params,
    size: (u32, u32),
}

impl Key {
    /// The key of an image; `None` for a scene that is not built in (a file may change
    /// on disk between the render and its use).
    pub(crate) fn of(
        scene: &Scene,
        camera: &Camera,
        params: &Params,
        size: (u32, u32),
    ) -> Option<Key> {
        let SceneSource::Builtin(name) = &scene.source else {
            return None;
        };
        Some(Key {
            scene: name.clone(),
            camera: camera.clone(),
            params: Params {
                exposure: 0.0,
                ..params.clone()
            },
            size,
        })
    }
}

/// One image to render ahead: its scene, camera, parameters and size.
#[derive(Clone)]
pub struct Prerender {
    /// The scene.
    pub scene: Arc<Scene>,
    /// The camera.
    pub camera: Camera,
    /// The parameters (its `spp` is the target).
    pub params: Params,
    /// The image size.
    pub size: (u32, u32),
}

impl Prerender {
    pub(crate) fn key(&self) -> Option<Key> {
        Key::of(&self.scene, &self.camera, &self.params, self.size)
    }
}

/// Films rendered ahead, oldest first, within [`PRERENDER_MEMORY`].
#[derive(Default)]
struct Films {
    films: Vec<(Key, Film)>,
}

/// The cache the engines of a window share.
#[derive(Clone, Default)]
pub struct FilmCache(Arc<Mutex<Films>>);

/// The memory a film takes.
fn bytes(film: &Film) -> usize {
    let pixel = std::mem::size_of::<super::Accum>() + std::mem::size_of::<super::film::Taken>();
    film.pixels.len() * (pixel + 1)
}

impl FilmCache {
    /// Takes out the film of `key`, if there is one with samples.
    pub(crate) fn take(&self, key: &Key) -> Option<Film> {
        let mut films = self.0.lock().ok()?;
        let i = films.films.iter().position(|(k, _)| k == key)?;
        let (_, film) = films.films.remove(i);
        (film.spp() > 0).then_some(film)
    }

    /// A copy of the film of `key`, if there is one, left in the cache.
    fn copy(&self, key: &Key) -> Option<Film> {
        let films = self.0.lock().ok()?;
        films
            .films
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, film)| film.clone())
    }

    /// Whether it holds a film of `key`.
    pub(crate) fn holds(&self, key: &Key) -> bool {
        self.0
            .lock()
            .is_ok_and(|f| f.films.iter().any(|(k, _)| k == key))
    }

    /// Samples per pixel of `job`'s image so far (0 when there is none).
    pub fn samples(&self, job: &Prerender) -> u32 {
        let Some(key) = job.key() else {
            return 0;
        };
        self.0.lock().map_or(0, |f| {
            f.films
                .iter()
                .find(|(k, _)| *k == key)
                .map_or(0, |(_, film)| film.spp())
        })
    }

    /// Puts `film` in as the newest, dropping the oldest beyond the memory bound.
    pub(crate) fn put(&self, key: Key, film: Film) {
        let Ok(mut films) = self.0.lock() else {
            return;
        };
        films.films.retain(|(k, _)| *k != key);
        films.films.push((key, film));
        let mut total: usize = films.films.iter().map(|(_, f)| bytes(f)).sum();
        while total > PRERENDER_MEMORY && !films.films.is_empty() {
            total -= bytes(&films.films[0].1);
            films.films.remove(0);
        }
    }

    /// How many films it holds, and their memory (for the tests: the window does not
    /// show it).
    #[cfg(test)]
    fn usage(&self) -> (usize, usize) {
        self.0
            .lock()
            .map(|f| (f.films.len(), f.films.iter().map(|(_, f)| bytes(f)).sum()))
            .unwrap_or((0, 0))
    }

    /// Whether `job`'s image is there, finished.
    pub fn ready(&self, job: &Prerender) -> bool {
        job.key()
            .is_some_and(|key| self.finished(&key, job.params.spp))
    }

    /// Whether the film of `key` is there and has reached its target (or, with adaptive
    /// sampling, stopped every pixel).
    pub(crate) fn finished(&self, key: &Key, target: u32) -> bool {
        self.0.lock().is_ok_and(|f| {
            f.films
                .iter()
                .any(|(k, film)| k == key && (film.spp() >= target || film.all_done()))
        })
    }
}

/// A pass rendered ahead is kept about this long: the image shown waits for none (a change
/// stops the pass at the next pixel), but a cancelled pass's samples are lost.
const AHEAD_PASS: Duration = Duration::from_millis(500);

/// The images an engine renders ahead, in order, and the pace of the one in hand.
#[derive(Default)]
pub(crate) struct Ahead {
    jobs: Vec<Prerender>,
    // Seconds per sample per pixel of the first job's last pass, to size its next.
    per_spp: Option<f64>,
}

impl Ahead {
    pub(crate) fn new(jobs: Vec<Prerender>) -> Ahead {
        Ahead {
            jobs,
            per_spp: None,
        }
    }

    /// Whether nothing is left to render (as of the last step).
    pub(crate) fn is_empty(&self) -> bool {
        self.jobs.is_empty()
    }

    /// Renders one pass of the first job not yet finished in `cache`, on `pool`, stopped
    /// by `observer` (a newer generation of the engine: the image shown comes first).
    /// Finished jobs leave the list.
    ///
    /// The pass is rendered on a copy of the cached film, put back when the pass is
    /// whole: a cancelled pass loses its own samples (at most [`AHEAD_PASS`]), never the
    /// film's. Passes grow to fill [`AHEAD_PASS`] at the job's measured pace.
    pub(crate) fn step(
        &mut self,
        cache: &FilmCache,
        pool: &rayon::ThreadPool,
        observer: &dyn super::PassObserver,
    ) {
        let first = self.jobs.first().and_then(Prerender::key);
        self.jobs.retain(|job| {
            job.key()
                .is_some_and(|key| !cache.finished(&key, job.params.spp))
        });
        let Some(job) = self.jobs.first() else {
            return;
        };
        let Some(key) = job.key() else {
            return;
        };
        if Some(&key) != first.as_ref() {
            self.per_spp = None;
        }
        let (w, h) = job.size;
        let mut film = cache.copy(&key).unwrap_or_else(|| Film::new(w, h));
        let within = self
            .per_spp
            .map_or(1, |s| (AHEAD_PASS.as_secs_f64() / s) as u32);
        let n = super::generation::MAX_PASS_SPP
            .min(job.params.spp.saturating_sub(film.spp()))
            .min(within)
            .max(1);
        let start = Instant::now();
        let result = crate::guard::caught(|| {
            pool.install(|| {
                super::render_pass(&job.scene, &job.camera, &job.params, &mut film, n, observer)
            })
        });
        match result {
            Ok(Ok(_)) => {
                self.per_spp = Some(start.elapsed().as_secs_f64() / f64::from(n));
                log::trace!(
                    "ahead: {} at {} of {} samples per pixel",
                    job.scene.source.reference(),
                    film.spp(),
                    job.params.spp
                );
                cache.put(key, film);
            }
            Ok(Err(super::Cancelled)) => {
                log::trace!("ahead: a pass of {} stopped", job.scene.source.reference());
            }
            // A bug: not this job again.
            Err(_) => {
                self.jobs.remove(0);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cache_keeps_the_newest_films_within_its_memory() {
        let scene = Scene::load("default").unwrap();
        let key = |spp: u32| {
            let params = Params {
                spp,
                ..Params::default()
            };
            Key::of(&scene, &scene.camera, &params, (960, 540)).unwrap()
        };
        let cache = FilmCache::default();
        let film = || {
            let mut f = Film::new(960, 540);
            f.set_spp(4);
            f
        };
        for spp in 1..=10 {
            cache.put(key(spp), film());
        }
        let (count, memory) = cache.usage();
        assert!(memory <= PRERENDER_MEMORY, "{memory}");
        assert_eq!(count, PRERENDER_MEMORY / bytes(&film()));
        assert!(cache.take(&key(1)).is_none(), "the oldest went first");
        assert!(cache.take(&key(10)).is_some());
        assert!(cache.take(&key(10)).is_none(), "taken out");
        // The exposure is not part of what an image is.
        let shown = Params {
            spp: 9,
            exposure: 2.0,
            ..Params::default()
        };
        let brighter = Key::of(&scene, &scene.camera, &shown, (960, 540)).unwrap();
        assert!(cache.take(&brighter).is_some());
    }

    #[test]
    fn a_pass_cancelled_ahead_loses_its_own_samples_and_no_others() {
        /// Stops the pass at its first pixel, as a Page Down to another image does.
        struct Stop;
        impl crate::render::PassObserver for Stop {
            fn keep_going(&self) -> bool {
                false
            }
        }
        let scene = Arc::new(Scene::load("glass").unwrap());
        let job = Prerender {
            camera: scene.camera.clone(),
            params: Params {
                spp: 64,
                ..scene.params.clone()
            },
            scene,
            size: (48, 27),
        };
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let cache = FilmCache::default();
        let mut ahead = Ahead::new(vec![job.clone()]);
        // The first pass is 1 sample (nothing is measured yet); the next fill the budget.
        ahead.step(&cache, &pool, &());
        assert_eq!(cache.samples(&job), 1);
        ahead.step(&cache, &pool, &());
        let kept = cache.samples(&job);
        assert!(kept > 2, "the passes grow to the budget: {kept}");
        ahead.step(&cache, &pool, &Stop);
        assert_eq!(cache.samples(&job), kept, "the film's samples are kept");
        let film = cache.take(&job.key().unwrap()).unwrap();
        let mut whole = Film::new(48, 27);
        crate::render::render_pass(&job.scene, &job.camera, &job.params, &mut whole, kept, &())
            .unwrap();
        assert_eq!(film, whole, "a whole film, as if never stopped");
    }
}
