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
    film.pixels.len() * (std::mem::size_of::<super::Accum>() + 1)
}

impl FilmCache {
    /// Takes out the film of `key`, if there is one with samples.
    pub(crate) fn take(&self, key: &Key) -> Option<Film> {
        let mut films = self.0.lock().ok()?;
        let i = films.films.iter().position(|(k, _)| k == key)?;
        let (_, film) = films.films.remove(i);
        (film.spp() > 0).then_some(film)
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

/// Renders one pass of the first of `jobs` not yet finished in `cache`, on `pool`,
/// stopped by `observer` (a newer generation of the engine: the current image comes
/// first). Finished jobs leave the list; a cancelled pass loses that film's samples.
pub(crate) fn step(
    jobs: &mut Vec<Prerender>,
    cache: &FilmCache,
    pool: &rayon::ThreadPool,
    observer: &dyn super::PassObserver,
) {
    jobs.retain(|job| {
        job.key()
            .is_some_and(|key| !cache.finished(&key, job.params.spp))
    });
    let Some(job) = jobs.first() else {
        return;
    };
    let Some(key) = job.key() else {
        return;
    };
    let (w, h) = job.size;
    let mut film = cache.take(&key).unwrap_or_else(|| Film::new(w, h));
    let n = super::engine::MAX_PASS_SPP.min(job.params.spp.saturating_sub(film.spp()).max(1));
    let result = crate::guard::caught(|| {
        pool.install(|| {
            super::render_pass(&job.scene, &job.camera, &job.params, &mut film, n, observer)
        })
    });
    match result {
        Ok(Ok(_)) => cache.put(key, film),
        Ok(Err(super::Cancelled)) => {}
        // A bug: not this job again.
        Err(_) => {
            jobs.remove(0);
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
}
