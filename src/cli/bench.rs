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
    // A drag: a change every 16 ms for 2 s, as a slider moved at 60 Hz.
    let drag = raylab::render::simulate_drag(
        &mut engine,
        Duration::from_millis(16),
        Duration::from_secs(2),
        |i| Params {
            ior: Some(1.2 + 0.02 * (i % 40) as f32),
            ..params.clone()
        },
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
    say!(
        "1-spp pass: {:.1} ms (median of 5), {:.2} M samples/s, {:.2} M rays, {:.2} M rays/s",
        pass * 1e3,
        f64::from(width) * f64::from(height) / pass / 1e6,
        rays as f64 / 1e6,
        rays as f64 / pass / 1e6
    );
    Ok(())
}
