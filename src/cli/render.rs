//! `raylab render`: a scene or a lecture slide to a PNG or EXR, with its sidecar.

use crate::cli::output::{check_output, default_output};
use crate::cli::progress::{Progress, progress_bar};
use crate::{parse_size, runtime};
use anyhow::{Context, Result};
use raylab::render::{Film, Sidecar, render_pass, sidecar_path};
use raylab::scene::{BUILTIN_SCENES, Scene};
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(clap::Args)]
pub struct RenderArgs {
    /// A scene file (.toml), a model shown on a floor under a light (.obj, .gltf, .glb)
    /// or the name of a built-in scene [default: the default scene, or the scene of
    /// --params].
    scene: Option<String>,
    /// The image to write: .png (8-bit sRGB) or .exr (linear radiance) [default:
    /// SCENE.png, or slide-N.png, in the current folder; SCENE-2.png and so on if taken:
    /// a default never replaces a file].
    #[arg(short, long, value_name = "OUT.png|OUT.exr")]
    output: Option<PathBuf>,
    /// Samples per pixel (same as --set spp=N).
    #[arg(long, value_name = "N")]
    spp: Option<u32>,
    /// Image size in pixels.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Random seed (same as --set seed=S).
    #[arg(long, value_name = "S")]
    seed: Option<u64>,
    /// Worker threads [default: all cores].
    #[arg(long, value_name = "T", value_parser = clap::value_parser!(u32).range(1..=1024))]
    threads: Option<u32>,
    /// Set any parameter by name, e.g. --set max_depth=3 --set min_weight=0.01 (repeatable).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// Start from a snapshot's sidecar JSON: its scene, size and every parameter, to
    /// reproduce its image bit for bit. Other options override it.
    #[arg(long, value_name = "SIDECAR.json")]
    params: Option<PathBuf>,
    /// Render slide N of the lecture (`raylab lecture` lists them) as the window shows it:
    /// its scene and parameters; a slide that compares two things as its split image, side
    /// A left and B right (no sidecar: no one set of parameters makes it).
    #[arg(long, value_name = "N", conflicts_with_all = ["scene", "params"])]
    slide: Option<usize>,
    /// With --slide: the slide's caption under the image, in a strip of its own (PNG only).
    #[arg(long, requires = "slide")]
    caption: bool,
    /// No progress bar and no summary line.
    #[arg(short, long)]
    quiet: bool,
}

pub fn render_command(args: RenderArgs) -> Result<()> {
    let sidecar = args.params.as_deref().map(Sidecar::read).transpose()?;
    let (scene, mut params, slide) = match args.slide.map(raylab::lecture::slide_setup) {
        Some(setup) => {
            let s = setup?;
            (s.scene, s.params, Some(s.slide))
        }
        None => {
            let scene_ref = match (&args.scene, &sidecar) {
                (Some(s), _) => s.clone(),
                (None, Some(sc)) => sc.scene.clone(),
                (None, None) => BUILTIN_SCENES[0].name.to_string(),
            };
            let scene = Scene::load(&scene_ref)?;
            let params = match &sidecar {
                Some(sc) => sc.params.clone(),
                None => scene.params.clone(),
            };
            (scene, params, None)
        }
    };
    let (mut width, mut height) = match &sidecar {
        Some(sc) => (sc.width, sc.height),
        None => (scene.width, scene.height),
    };
    if let Some((w, h)) = args.size {
        (width, height) = (w, h);
    }
    // A snapshot from the window may have moved the camera.
    let camera = sidecar
        .as_ref()
        .and_then(|sc| sc.camera.clone())
        .unwrap_or_else(|| scene.camera.clone());
    // A snapshot of a render still refining holds fewer samples than its target.
    let mut samples = sidecar.as_ref().and_then(|sc| sc.samples);
    if let Some(spp) = args.spp {
        params.set("spp", &spp.to_string()).context("--spp")?;
        samples = None;
    }
    if let Some(seed) = args.seed {
        params.seed = seed;
    }
    params.set_all(&args.set).context("--set")?;
    let params_b = slide.and_then(|s| s.side_b(&params));
    let output = match (&args.output, args.slide) {
        (Some(o), _) => o.clone(),
        (None, Some(n)) => default_output(Path::new(""), &format!("slide-{n}")),
        (None, None) => default_output(Path::new(""), &scene.name),
    };
    check_output(&output, args.caption)?;
    let json = sidecar_path(&output);
    if params_b.is_none() {
        Sidecar::check_target(&json, args.params.as_deref())?;
    }

    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0) as usize)
        .build()
        .context("cannot start the worker threads")
        .map_err(runtime)?;
    let bar = progress_bar(
        args.quiet,
        height as u64 * (1 + params_b.is_some() as u64),
        "rendering",
    );
    let start = Instant::now();
    let (film, stats) = pool
        .install(|| {
            let mut film = Film::new(width, height);
            let n = samples.unwrap_or(params.spp);
            let observer = Progress(bar.clone());
            let mut stats = render_pass(&scene, &camera, &params, &mut film, n, &observer)?;
            if let Some(b) = &params_b {
                // The A/B view's split, at the window's starting divider: the middle.
                let mut right = Film::new(width, height);
                stats += render_pass(&scene, &camera, b, &mut right, b.spp, &observer)?;
                film.split_with(&right, width / 2);
            }
            Ok::<_, raylab::render::Cancelled>((film, stats))
        })
        .map_err(runtime)?;
    let seconds = start.elapsed().as_secs_f64();
    bar.finish_and_clear();

    // Replacing the file named by -o is what was asked; the summary still says so.
    let replaced = if output.exists() {
        " (replacing the file there)"
    } else {
        ""
    };
    // No one set of parameters makes an A/B split: it gets no sidecar.
    let sidecar = params_b.is_none().then(|| Sidecar {
        raylab_version: raylab::VERSION.to_string(),
        scene: Sidecar::scene_reference(&scene.source, &json),
        width,
        height,
        params: params.clone(),
        samples,
        camera: (camera != scene.camera).then(|| camera.clone()),
        image: output.file_name().map(|n| n.to_string_lossy().into_owned()),
        seconds: Some(seconds),
        stats: Some(stats),
    });
    match slide.filter(|_| args.caption) {
        // The caption as it reads for the parameters rendered (after any --set).
        Some(slide) => {
            let image = raylab::render::with_caption(
                &film.to_srgb8(params.exposure),
                &slide.caption(&params),
            );
            raylab::render::output::save_image(&image, &output, image::ImageFormat::Png)
                .with_context(|| format!("cannot write {}", output.display()))
                .map_err(runtime)?;
        }
        None => film
            .save(&output, params.exposure, sidecar.as_ref())
            .map_err(runtime)?,
    }
    let Some(sidecar) = sidecar else {
        if !args.quiet {
            eprintln!(
                "slide {}: A/B split written to {}{replaced} (no sidecar: no one set of parameters makes it)",
                args.slide.unwrap_or(0),
                output.display()
            );
        }
        return Ok(());
    };
    sidecar.write(&json).map_err(runtime)?;

    if !args.quiet {
        let pixels = (width as u64 * height as u64) as f64;
        // The status bar's estimate, so a render's noise can be judged without a window.
        let noise = film
            .noise(params.exposure)
            .map_or(String::new(), |n| format!(" noise {:.2}%;", n * 100.0));
        let rays = stats.total_rays();
        eprintln!(
            "{} {}x{} at {} spp: {:.2} s, {:.2} M samples, {:.2} M rays ({:.2} M rays/s, {:.1} rays/pixel); {} total internal reflections; pruned {} by depth, {} by weight, {} by the ray budget; {} non-finite samples dropped;{noise} wrote {}{replaced} and {}",
            scene.name,
            width,
            height,
            samples.unwrap_or(params.spp),
            seconds,
            stats.samples as f64 / 1e6,
            rays as f64 / 1e6,
            rays as f64 / seconds.max(1e-9) / 1e6,
            rays as f64 / pixels,
            stats.tir_events,
            stats.pruned_by_depth,
            stats.pruned_by_weight,
            stats.pruned_by_budget,
            stats.non_finite,
            output.display(),
            json.display()
        );
    }
    Ok(())
}
