//! `raylab bench`: the engine's latency, drag behaviour, shutdown and pass speed.

use crate::parse_size;
use anyhow::Result;
use raylab::params::Params;
use raylab::scene::Scene;
use std::time::Instant;

#[derive(clap::Args)]
pub struct BenchArgs {
    /// A scene file or built-in name.
    #[arg(default_value = "default")]
    scene: std::ffi::OsString,
    /// Image size.
    #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "960x540")]
    size: (u32, u32),
    /// Parameter changes to time.
    #[arg(long, default_value_t = 200, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    changes: u32,
    /// Worker threads [default: every core, below normal priority, as with the window].
    #[arg(long, value_name = "T", value_parser = clap::value_parser!(u32).range(1..=1024))]
    threads: Option<u32>,
    /// The parameter the simulated drag moves, over the middle half of its slider (light
    /// size on the soft-shadow scene, aperture on depth of field).
    #[arg(long, value_name = "NAME", default_value = "ior")]
    drag: String,
    /// Frames shown raw, not calmed (View > Calm noise while refining off).
    #[arg(long)]
    no_calm: bool,
    /// Instead: the time each lecture slide takes to reach its target (all its sides),
    /// every pixel sampled against adaptive sampling (the scene argument is not used).
    #[arg(long)]
    slides: bool,
}

pub fn bench_command(args: &BenchArgs) -> Result<()> {
    use raylab::render::{Engine, EngineConfig, Film, render_pass};
    use std::sync::Arc;
    use std::time::Duration;
    let config = match args.threads {
        Some(t) => EngineConfig::with_threads(t as usize),
        None => EngineConfig::with_ui(),
    };
    if args.slides {
        return super::bench_slides::bench_slides(args.size, config.threads);
    }
    let scene = Arc::new(Scene::load(&args.scene)?);
    crate::cli::streams::warn(&scene);
    let (width, height) = args.size;
    let params = Params {
        spp: 1 << 16,
        ..scene.params.clone()
    };
    say!(
        "raylab bench: {} at {width}x{height}, {} worker thread{}, {} cores",
        scene.name,
        config.threads,
        if config.threads == 1 { "" } else { "s" },
        std::thread::available_parallelism().map_or(1, |n| n.get())
    );

    let traversal = raylab::tracer::Traversal::best()
        .for_tracer(&raylab::tracer::Tracer::new(&scene, &params, width, height));
    say!(
        "ray trees walked {traversal} (RAYLAB_LANES=1, 4, 8 or 16 narrows the lanes; 0 walks \
         them recursively)"
    );

    // Latency: change a parameter at a random moment of a pass, time the first frame of the
    // new generation (the coarse preview).
    let mut engine = Engine::new(
        Arc::clone(&scene),
        params.clone(),
        width,
        height,
        config,
        || {},
    )?;
    engine.set_calm(!args.no_calm);
    let wait_for = |engine: &Engine, generation: u64| -> Result<()> {
        loop {
            let frame = engine.frames().recv_timeout(Duration::from_secs(60))?;
            if frame.generation == generation {
                return Ok(());
            }
        }
    };
    wait_for(&engine, 1)?;
    let mut latencies = Vec::with_capacity(args.changes as usize);
    let mut rng = raylab::math::SampleStream::new(7, 0, 0);
    for i in 0..args.changes {
        std::thread::sleep(Duration::from_secs_f32(0.05 * rng.next_1d()));
        let start = Instant::now();
        engine.set_params(Params {
            ior: Some(1.2 + 0.5 * (i % 2) as f32),
            ..params.clone()
        });
        wait_for(&engine, engine.generation())?;
        latencies.push(start.elapsed().as_secs_f64() * 1e3);
    }
    // A drag: a change every 16 ms for 2 s, as a slider moved at 60 Hz, to and fro over
    // the middle half of the slider in 40 steps.
    let slider = raylab::params::spec(&args.drag)
        .and_then(|s| s.slider)
        .ok_or_else(|| anyhow::anyhow!("--drag {}: no parameter with a slider", args.drag))?;
    let dragged = |i: u32| -> Result<Params> {
        let along = 0.25 + 0.5 * (i % 40) as f64 / 40.0;
        let value = slider.min + (slider.max - slider.min) * along;
        let mut p = params.clone();
        p.set(&args.drag, &value.to_string())?;
        Ok(p)
    };
    // A drag starts from an image refined a while (its noise what calms the drag's frames).
    engine.set_params(dragged(0)?);
    loop {
        let frame = engine.frames().recv_timeout(Duration::from_secs(60))?;
        if frame.generation == engine.generation() && frame.progress.spp >= 16 {
            break;
        }
    }
    let drag = raylab::render::simulate_drag(
        &mut engine,
        Duration::from_millis(16),
        Duration::from_secs(2),
        |i| dragged(i).unwrap_or_else(|_| params.clone()),
    );
    // Shutdown in the middle of a pass: the workers stop at their next pixel.
    let start = Instant::now();
    engine.shutdown();
    let shutdown_ms = start.elapsed().as_secs_f64() * 1e3;
    latencies.sort_by(f64::total_cmp);
    let at = |q: f64| latencies[((latencies.len() - 1) as f64 * q).round() as usize];
    say!(
        "change -> first frame: median {:.2} ms, p95 {:.2} ms, max {:.2} ms ({} changes)",
        at(0.5),
        at(0.95),
        at(1.0),
        latencies.len()
    );
    say!("{}", drag.summary());
    say!("shutdown mid-pass: {shutdown_ms:.1} ms");

    // A full-resolution pass of one sample per pixel, on the same number of threads.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(config.threads)
        .build()?;
    let mut times = Vec::new();
    let mut rays = 0;
    for _ in 0..5 {
        let mut film = Film::new(width, height);
        let start = Instant::now();
        let stats =
            pool.install(|| render_pass(&scene, &scene.camera, &params, &mut film, 1, &()))?;
        times.push(start.elapsed().as_secs_f64());
        rays = stats.total_rays();
    }
    times.sort_by(f64::total_cmp);
    let pass = times[times.len() / 2];
    let calm_ms = calm_cost(&pool, &scene, &params, (width, height))?;
    say!(
        "1-spp pass: {:.1} ms (median of 5), {:.2} M samples/s, {:.2} M rays, {:.2} M rays/s",
        pass * 1e3,
        f64::from(width) * f64::from(height) / pass / 1e6,
        rays as f64 / 1e6,
        rays as f64 / pass / 1e6
    );
    let (guides_ms, calm_ms) = calm_ms;
    say!(
        "calm a 1-spp frame for the window: {calm_ms:.1} ms (median of 5), {:.2}x the pass; \
         the guides, once per view: {guides_ms:.1} ms",
        calm_ms / (pass * 1e3)
    );
    Ok(())
}

/// What calming costs at `size` on `pool`: the guides (once per scene, camera and size),
/// and a 1-spp film calmed with the spread of a 16-spp one (as a drag's first frames are),
/// median of 5; in milliseconds.
fn calm_cost(
    pool: &rayon::ThreadPool,
    scene: &Scene,
    params: &Params,
    (width, height): (u32, u32),
) -> Result<(f64, f64)> {
    use raylab::render::{CALM_BLOCK, Film, Guides, calm_film, render_pass, spread};
    let start = Instant::now();
    let (gw, gh) = (width.div_ceil(CALM_BLOCK), height.div_ceil(CALM_BLOCK));
    let guides = pool.install(|| Guides::of(scene, &scene.camera, gw, gh));
    let guides_ms = start.elapsed().as_secs_f64() * 1e3;
    let mut before = Film::new(width, height);
    pool.install(|| render_pass(scene, &scene.camera, params, &mut before, 16, &()))?;
    let spread = pool.install(|| spread(&before));
    let mut film = Film::new(width, height);
    pool.install(|| render_pass(scene, &scene.camera, params, &mut film, 1, &()))?;
    let mut times: Vec<f64> = (0..5)
        .map(|_| {
            let start = Instant::now();
            pool.install(|| calm_film(&film, &guides, spread.as_deref(), &()));
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    times.sort_by(f64::total_cmp);
    Ok((guides_ms, times[times.len() / 2]))
}
