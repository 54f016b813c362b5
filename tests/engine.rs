//! The progressive engine: fresh generations, the same pixels as the CLI's kernel, and
//! clean shutdown.
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

use raylab::math::Color;
use raylab::params::Params;
use raylab::render::{Engine, EngineConfig, Film, Frame, render_pass, render_preview};
use raylab::scene::Scene;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

const W: u32 = 96;
const H: u32 = 54;

fn engine(scene: &Arc<Scene>, params: Params) -> Engine {
    Engine::new(
        Arc::clone(scene),
        params,
        W,
        H,
        EngineConfig::with_threads(2),
        || {},
    )
    .unwrap()
}

/// Frames until one satisfies `stop` (which is included), failing after `limit`.
fn frames_until(e: &Engine, limit: Duration, mut stop: impl FnMut(&Frame) -> bool) -> Vec<Frame> {
    let deadline = Instant::now() + limit;
    let mut frames = Vec::new();
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        let f = e
            .frames()
            .recv_timeout(left)
            .expect("a frame before the deadline");
        let last = stop(&f);
        frames.push(f);
        if last {
            return frames;
        }
    }
}

fn bits(pixels: &[Color]) -> Vec<[u32; 3]> {
    pixels
        .iter()
        .map(|c| c.to_array().map(f32::to_bits))
        .collect()
}

/// The film the kernel makes for `params` at `spp` samples, as the engine renders it.
fn reference(scene: &Scene, params: &Params, spp: u32) -> Vec<Color> {
    let mut film = Film::new(W, H);
    render_pass(scene, &scene.camera, params, &mut film, spp, &()).unwrap();
    film.pixels().collect()
}

#[test]
fn every_frame_of_a_new_generation_shows_the_new_parameters() {
    let scene = Arc::new(Scene::load("default").unwrap());
    let a = Params {
        spp: 6,
        ..scene.params.clone()
    };
    let mut e = engine(&scene, a.clone());
    let first = frames_until(&e, Duration::from_secs(20), |f| f.progress.done());
    assert_eq!(
        first.iter().take(3).map(|f| f.block).collect::<Vec<_>>(),
        raylab::render::PREVIEW_LEVELS,
        "a generation opens with its pyramid of previews, coarse to fine"
    );
    assert!(first.iter().all(|f| f.generation == 1));

    // (A new seed reaches every sample: the whole image starts again. A change that
    // reaches part of it keeps the rest: tests/reuse.rs.)
    let b = Params {
        ior: Some(1.33),
        max_depth: 3,
        seed: 3,
        ..a.clone()
    };
    e.set_params(b.clone());
    let generation = e.generation();
    assert_eq!(generation, 2);
    let frames = frames_until(&e, Duration::from_secs(20), |f| {
        f.generation == generation && f.progress.done()
    });
    let mut spps = Vec::new();
    for f in frames.iter().filter(|f| f.generation == generation) {
        let expected = if f.is_preview() {
            render_preview(&scene, &scene.camera, &b, W, H, f.block, &())
                .unwrap()
                .0
        } else {
            reference(&scene, &b, f.progress.spp)
        };
        assert_eq!(
            bits(&f.pixels),
            bits(&expected),
            "frame at {} spp (block {})",
            f.progress.spp,
            f.block
        );
        spps.push(f.progress.spp);
    }
    assert_eq!(spps[..3], [0, 0, 0], "the previews come first");
    assert!(
        spps[3..].windows(2).all(|w| w[0] < w[1]),
        "passes only add samples: {spps:?}"
    );
    assert_eq!(*spps.last().unwrap(), 6);
    // The final image is the CLI's, bit for bit.
    let cli = raylab::render::render(&scene, &b, W, H, &()).unwrap().0;
    assert_eq!(
        bits(&frames.last().unwrap().pixels),
        bits(&cli.pixels().collect::<Vec<_>>())
    );
}

#[test]
fn a_thousand_changes_end_in_the_right_image() {
    let scene = Arc::new(Scene::load("glass").unwrap());
    let base = Params {
        spp: 4,
        ..scene.params.clone()
    };
    let mut e = engine(&scene, base.clone());
    let mut last = base.clone();
    for i in 0..1000 {
        last = Params {
            ior: Some(1.0 + (i % 200) as f32 / 100.0),
            seed: i as u64,
            ..base.clone()
        };
        e.set_params(last.clone());
    }
    // Every change was taken at once, each a generation of its own.
    let generation = e.generation();
    assert_eq!(generation, 1001);
    let frames = frames_until(&e, Duration::from_secs(30), |f| {
        f.generation == generation && f.progress.done()
    });
    let f = frames.last().unwrap();
    assert_eq!(bits(&f.pixels), bits(&reference(&scene, &last, 4)));
    e.shutdown();
}

#[test]
fn exposure_does_not_restart_but_everything_else_does() {
    let scene = Arc::new(Scene::load("default").unwrap());
    let p = Params {
        spp: 2,
        ..scene.params.clone()
    };
    let mut e = engine(&scene, p.clone());
    e.set_params(Params {
        exposure: 1.5,
        ..p.clone()
    });
    assert_eq!(e.generation(), 1);
    e.set_params(Params {
        light_size: 0.5,
        exposure: 1.5,
        ..p.clone()
    });
    assert_eq!(e.generation(), 2);
    e.resize(40, 30);
    let mut camera = scene.camera.clone();
    camera.fov_deg = 20.0;
    e.set_camera(camera.clone());
    e.set_scene(Arc::new(Scene::load("glass").unwrap()));
    assert_eq!(e.generation(), 5);
    let frames = frames_until(&e, Duration::from_secs(20), |f| {
        f.generation == 5 && f.progress.done()
    });
    let f = frames.last().unwrap();
    assert_eq!(
        (f.width, f.height),
        (40, 30),
        "the size survives a scene change"
    );
}

#[test]
fn pause_holds_and_resume_finishes_and_unlimited_runs_on() {
    let scene = Arc::new(Scene::load("default").unwrap());
    let p = Params {
        spp: 64,
        ..scene.params.clone()
    };
    let e = engine(&scene, p);
    frames_until(&e, Duration::from_secs(20), |f| !f.is_preview());
    e.pause();
    let paused = frames_until(&e, Duration::from_secs(20), |f| f.progress.paused);
    let held = paused.last().unwrap().progress.spp;
    // Nothing more comes while paused.
    assert!(e.frames().recv_timeout(Duration::from_millis(300)).is_err());
    e.resume();
    let rest = frames_until(&e, Duration::from_secs(60), |f| f.progress.done());
    let done = rest.last().unwrap();
    assert!(done.progress.spp == 64 && held < 64);
    assert!(done.progress.noise.is_some() && done.progress.rays_per_second > 0.0);
    assert_eq!(done.progress.eta, Some(Duration::ZERO));
    let mut e = e;
    e.set_unlimited(true);
    let more = frames_until(&e, Duration::from_secs(20), |f| f.progress.spp > 64);
    assert_eq!(more.last().unwrap().progress.target, None);
}

/// Names of this process's threads (Linux only: read from /proc).
#[cfg(target_os = "linux")]
fn thread_names() -> Vec<String> {
    threads().into_iter().map(|(name, _)| name).collect()
}

/// This process's threads: each one's name and nice value (Linux only: read from /proc).
#[cfg(target_os = "linux")]
fn threads() -> Vec<(String, i64)> {
    let read = |task: std::path::PathBuf| {
        let name = std::fs::read_to_string(task.join("comm")).ok()?;
        // stat: "pid (comm) state ppid ...": nice is the 19th field, the 17th after comm.
        let stat = std::fs::read_to_string(task.join("stat")).ok()?;
        let after_comm = &stat[stat.rfind(')')? + 1..];
        let nice = after_comm.split_whitespace().nth(16)?.parse().ok()?;
        Some((name.trim().to_string(), nice))
    };
    std::fs::read_dir("/proc/self/task")
        .map(|d| d.filter_map(|t| read(t.ok()?.path())).collect())
        .unwrap_or_default()
}

#[test]
#[cfg(target_os = "linux")]
fn the_windows_workers_run_on_every_core_below_its_priority_and_headless_ones_do_not() {
    let scene = Arc::new(Scene::load("default").unwrap());
    let start = |config| {
        Engine::new(
            Arc::clone(&scene),
            scene.params.clone(),
            W,
            H,
            config,
            || {},
        )
    };
    let window = start(EngineConfig::with_ui()).unwrap();
    let headless = start(EngineConfig::headless()).unwrap();
    let cores = std::thread::available_parallelism().unwrap().get();
    let nice_of = |e: &Engine, role: char| -> Vec<i64> {
        let prefix = e.thread_prefix();
        threads()
            .into_iter()
            .filter(|(n, _)| n.strip_prefix(&prefix).is_some_and(|r| r.starts_with(role)))
            .map(|(_, nice)| nice)
            .collect()
    };
    let own = threads()[0].1; // the process's first thread: what the others started from
    // Each worker lowers itself as it starts, and each thread takes its name as it starts
    // (until then it has its parent's): either may be a moment after the engine is.
    let lowered = vec![5.max(own); cores];
    let deadline = Instant::now() + Duration::from_secs(10);
    while (nice_of(&window, 'w') != lowered || nice_of(&window, 'c').is_empty())
        && Instant::now() < deadline
    {
        std::thread::sleep(Duration::from_millis(5));
    }
    assert_eq!(nice_of(&window, 'w'), lowered, "every core, at nice 5");
    assert_eq!(
        nice_of(&window, 'c'),
        vec![own],
        "the controller only waits"
    );
    // (Its workers too may start a moment after it.)
    while nice_of(&headless, 'w').len() < cores && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(5));
    }
    assert_eq!(
        nice_of(&headless, 'w'),
        vec![own; cores],
        "headless: normal priority"
    );
}

#[test]
#[cfg(target_os = "linux")]
fn shutdown_mid_pass_leaves_no_thread() {
    let scene = Arc::new(Scene::load("ray-tree").unwrap());
    let p = Params {
        spp: 1 << 16,
        ..scene.params.clone()
    };
    let wakes = Arc::new(AtomicUsize::new(0));
    let counter = Arc::clone(&wakes);
    let e = Engine::new(
        Arc::clone(&scene),
        p,
        480,
        270,
        EngineConfig::with_threads(2),
        move || {
            counter.fetch_add(1, Ordering::Relaxed);
        },
    )
    .unwrap();
    let prefix = e.thread_prefix();
    frames_until(&e, Duration::from_secs(20), |f| f.progress.spp >= 2);
    assert!(
        wakes.load(Ordering::Relaxed) >= 2,
        "every frame wakes the display"
    );
    let ours = |names: Vec<String>| {
        names
            .into_iter()
            .filter(|n| n.starts_with(&prefix) && n[prefix.len()..].starts_with(['w', 'c']))
            .count()
    };
    assert_eq!(ours(thread_names()), 3, "two workers and the controller");
    // Mid-pass on a deep ray tree: shutdown stops the workers at their next pixel and
    // joins them (how long that takes is measured by `raylab bench`).
    e.shutdown();
    // A joined thread can stay listed in /proc for a moment until the kernel reaps it.
    let mut left = ours(thread_names());
    for _ in 0..200 {
        if left == 0 {
            break;
        }
        std::thread::sleep(Duration::from_millis(10));
        left = ours(thread_names());
    }
    assert_eq!(left, 0, "threads left behind");
}

#[test]
fn a_pass_that_panics_stops_its_generation_with_a_message_and_the_engine_goes_on() {
    use raylab::camera::Camera;
    use raylab::geometry::{Shape, Sphere};
    use raylab::math::Vec3;
    use raylab::scene::{Object, SceneDesc};
    // Only code can build this broken scene (files are checked): an object whose material
    // does not exist, which the tracer indexes and panics on.
    let mut desc = SceneDesc::empty(Camera::looking_at(
        Vec3::new(0.0, 0.0, 5.0),
        Vec3::ZERO,
        Vec3::Y,
        40.0,
    ));
    desc.objects.push(Object {
        name: "broken".into(),
        shape: Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0)),
        material: 99,
    });
    let scene = Arc::new(desc.build());
    let mut e = engine(&scene, Params::default());
    let limit = Duration::from_secs(30);
    let failed = frames_until(&e, limit, |f| f.progress.failure.is_some());
    let failure = failed.last().unwrap().progress.failure.clone().unwrap();
    assert!(
        failure.contains("a bug in raylab") && failure.contains("index out of bounds"),
        "{failure}"
    );
    // The engine still takes commands: a new generation tries again (and fails again).
    e.set_params(Params {
        spp: 2,
        ..Params::default()
    });
    let again = frames_until(&e, limit, |f| {
        f.progress.failure.is_some() && f.generation == e.generation()
    });
    assert!(again.last().unwrap().progress.failure.is_some());
}

/// An engine on `first` at `a`, asked to render `next` at `b` ahead into a cache of its
/// own: the engine, the cache and the job.
fn rendering_ahead(
    first: &Arc<Scene>,
    a: Params,
    next: &Arc<Scene>,
    b: &Params,
) -> (Engine, raylab::render::FilmCache, raylab::render::Prerender) {
    let e = engine(first, a);
    let cache = raylab::render::FilmCache::default();
    let job = raylab::render::Prerender {
        scene: Arc::clone(next),
        camera: next.camera.clone(),
        params: b.clone(),
        size: (W, H),
    };
    e.prerender(&cache, vec![job.clone()]);
    (e, cache, job)
}

#[test]
fn an_image_rendered_ahead_shows_at_once_finished_and_a_finished_one_comes_back() {
    let first = Arc::new(Scene::load("default").unwrap());
    let next = Arc::new(Scene::load("glass").unwrap());
    let a = Params {
        spp: 8,
        ..first.params.clone()
    };
    // Adaptive sampling too: its decisions ride along with the film.
    let b = Params {
        spp: 24,
        noise_target: Some(3.0),
        ..next.params.clone()
    };
    let (mut e, cache, job) = rendering_ahead(&first, a.clone(), &next, &b);
    frames_until(&e, Duration::from_secs(60), |f| f.progress.done());
    // The workers go on to the next image once this one is finished.
    let deadline = Instant::now() + Duration::from_secs(60);
    while !cache.ready(&job) {
        assert!(Instant::now() < deadline, "nothing rendered ahead");
        std::thread::sleep(Duration::from_millis(20));
    }
    // Switching to it: the first frame of the new generation is the finished image, no
    // preview, bit for bit the kernel's.
    let generation = e.generation() + 2;
    e.set_scene(Arc::clone(&next));
    e.set_params(b.clone());
    let frames = frames_until(&e, Duration::from_secs(60), |f| f.generation == generation);
    let shown = frames.last().unwrap();
    assert!(
        !shown.is_preview(),
        "a preview: nothing was taken from the cache"
    );
    assert!(shown.progress.done(), "{:?}", shown.progress);
    let mut film = Film::new(W, H);
    render_pass(&next, &next.camera, &b, &mut film, 24, &()).unwrap();
    assert_eq!(
        bits(&shown.pixels),
        bits(&film.pixels().collect::<Vec<_>>())
    );
    // And back: the first image, finished when it was left, comes back as it was.
    let generation = e.generation() + 2;
    e.set_scene(Arc::clone(&first));
    e.set_params(a.clone());
    let frames = frames_until(&e, Duration::from_secs(60), |f| f.generation == generation);
    let back = frames.last().unwrap();
    assert!(!back.is_preview() && back.progress.done());
    assert_eq!(bits(&back.pixels), bits(&reference(&first, &a, 8)));
}

#[test]
fn an_image_left_half_rendered_ahead_keeps_its_samples_when_it_is_asked_for() {
    let first = Arc::new(Scene::load("default").unwrap());
    let next = Arc::new(Scene::load("glass").unwrap());
    let a = Params {
        spp: 1,
        ..first.params.clone()
    };
    // A target far beyond what the test waits for: the pre-render is mid-way when asked.
    let b = Params {
        spp: 1 << 16,
        ..next.params.clone()
    };
    let (mut e, cache, job) = rendering_ahead(&first, a, &next, &b);
    frames_until(&e, Duration::from_secs(60), |f| f.progress.done());
    let deadline = Instant::now() + Duration::from_secs(60);
    while cache.samples(&job) < 8 {
        assert!(Instant::now() < deadline, "nothing rendered ahead");
        std::thread::sleep(Duration::from_millis(5));
    }
    // Asked for mid-pass: the pass in hand is cancelled, the samples before it are kept.
    let ahead = cache.samples(&job);
    let generation = e.generation() + 2;
    e.set_scene(Arc::clone(&next));
    e.set_params(b.clone());
    let frames = frames_until(&e, Duration::from_secs(60), |f| f.generation == generation);
    let shown = frames.last().unwrap();
    assert!(
        !shown.is_preview(),
        "a preview: the samples rendered ahead were lost"
    );
    assert!(
        shown.progress.spp >= ahead,
        "{} < {ahead}",
        shown.progress.spp
    );
    let mut film = Film::new(W, H);
    render_pass(&next, &next.camera, &b, &mut film, shown.progress.spp, &()).unwrap();
    assert_eq!(
        bits(&shown.pixels),
        bits(&film.pixels().collect::<Vec<_>>())
    );
}
