//! `raylab bench --slides`: how long each lecture slide takes to be clean, every pixel
//! getting every sample against adaptive sampling.

use anyhow::Result;
use raylab::lecture::{LECTURE, slide_setup};
use raylab::params::Params;
use raylab::render::{Film, render_pass};
use raylab::scene::Scene;
use std::time::Instant;

/// One way of rendering a slide's sides: the seconds for all of them, the worst noise
/// among them (as the status bar estimates it) and the samples a pixel on average.
struct Run {
    seconds: f64,
    noise: Option<f32>,
    samples_per_pixel: f64,
}

/// Renders every side of a slide (`sides`, the window renders them all) to its target at
/// `size` in `pool`.
fn run(
    pool: &rayon::ThreadPool,
    scene: &Scene,
    sides: &[Params],
    (width, height): (u32, u32),
) -> Result<Run> {
    let (mut seconds, mut noise, mut samples) = (0.0, None::<f32>, 0u64);
    for params in sides {
        let mut film = Film::new(width, height);
        let start = Instant::now();
        let stats =
            pool.install(|| render_pass(scene, &scene.camera, params, &mut film, params.spp, &()))?;
        seconds += start.elapsed().as_secs_f64();
        samples += stats.samples;
        if let Some(n) = film.noise(params.exposure) {
            noise = Some(noise.map_or(n, |m| m.max(n)));
        }
    }
    let pixels = (width as u64 * height as u64 * sides.len() as u64).max(1);
    Ok(Run {
        seconds,
        noise,
        samples_per_pixel: samples as f64 / pixels as f64,
    })
}

/// The table: per slide, its sides' most samples, then each way's time, noise and
/// samples a pixel, and how much faster adaptive sampling made it.
pub fn bench_slides(size: (u32, u32), threads: usize) -> Result<()> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    say!(
        "raylab bench --slides: each slide's sides to their targets at {}x{}, {threads} thread{}",
        size.0,
        size.1,
        if threads == 1 { "" } else { "s" }
    );
    say!(
        "{:<48} {:>5} | {:>8} {:>6} | {:>8} {:>6} {:>7} | {:>6}",
        "slide",
        "spp",
        "every px",
        "noise",
        "adaptive",
        "noise",
        "spp avg",
        "faster"
    );
    let noise = |n: Option<f32>| n.map_or("-".to_string(), |n| format!("{:.2}%", n * 100.0));
    let (mut total_uniform, mut total_adaptive) = (0.0, 0.0);
    for number in 1..=LECTURE.len() {
        let setup = slide_setup(number)?;
        let mut sides = vec![setup.params.clone()];
        sides.extend(setup.slide.others(&setup.params));
        let uniform: Vec<Params> = sides
            .iter()
            .map(|p| Params {
                noise_target: None,
                ..p.clone()
            })
            .collect();
        let spp = sides.iter().map(|p| p.spp).max().unwrap_or(0);
        let every = run(&pool, &setup.scene, &uniform, size)?;
        total_uniform += every.seconds;
        let title = format!("{number:>2} {}", setup.slide.title);
        let title: String = title.chars().take(48).collect();
        let head = format!(
            "{title:<48} {spp:>5} | {:>7.2}s {:>6}",
            every.seconds,
            noise(every.noise)
        );
        if sides.iter().all(|p| p.noise_target.is_none()) {
            total_adaptive += every.seconds;
            say!("{head} | {:>8} {:>6} {:>7} |", "off", "", "");
            continue;
        }
        let adaptive = run(&pool, &setup.scene, &sides, size)?;
        total_adaptive += adaptive.seconds;
        say!(
            "{head} | {:>7.2}s {:>6} {:>7.1} | {:>5.1}x",
            adaptive.seconds,
            noise(adaptive.noise),
            adaptive.samples_per_pixel,
            every.seconds / adaptive.seconds.max(1e-9)
        );
    }
    say!(
        "the whole lecture: {total_uniform:.1} s with every pixel sampled, {total_adaptive:.1} s with adaptive sampling"
    );
    Ok(())
}
