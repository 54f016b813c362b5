//! `raylab render`: a scene or a lecture slide to a PNG or EXR, with its sidecar.

use crate::cli::output::{check_output, default_output};
use crate::cli::progress::{Progress, progress_bar};
use crate::cli::reference::Reference;
use crate::{parse_size, runtime};
use anyhow::{Context, Result};
use indicatif::ProgressBar;
use raylab::lecture::Slide;
use raylab::params::Params;
use raylab::render::output::Target;
use raylab::render::{Crop, Film, Rendered, Sidecar, render_crop_pass, render_pass, sidecar_path};
use raylab::scene::{BUILTIN_SCENES, Scene};
use raylab::tracer::Stats;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(clap::Args)]
pub struct RenderArgs {
    /// A scene file (.toml), a model shown on a floor under a light (.obj, .gltf, .glb)
    /// or the name of a built-in scene [default: the default scene, or the scene of
    /// --params].
    scene: Option<std::ffi::OsString>,
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
    #[command(flatten)]
    threads: crate::cli::threads::Threads,
    /// Set any parameter by name, e.g. --set max_depth=3 --set min_weight=0.01 (repeatable).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// Start from a snapshot's sidecar JSON, or from an image raylab wrote (its PNG or EXR
    /// carries the same): its scene, size and every parameter, to reproduce the image bit
    /// for bit. Other options override it.
    #[arg(long, value_name = "SIDECAR.json|IMAGE")]
    params: Option<PathBuf>,
    /// Render slide N of the lecture (`raylab lecture` lists them) as the window shows it:
    /// its scene and parameters; a slide that compares things as its split image, side
    /// A left, B (and C) right of it (no sidecar: no one set of parameters makes it).
    #[arg(long, value_name = "N", conflicts_with_all = ["scene", "params"])]
    slide: Option<usize>,
    /// With --slide: the slide's caption under the image, in a strip of its own (PNG only).
    #[arg(long, requires = "slide")]
    caption: bool,
    /// Measure the render against a reference image of the same size (an EXR of linear
    /// radiance, as `-o REF.exr` writes one) after each pass, the passes doubling (1, 2,
    /// 4, … samples): MSE, relative MSE, the RMS error as shown and the noise estimate,
    /// printed and written to the sidecar.
    #[arg(long, value_name = "REF.exr")]
    reference: Option<PathBuf>,
    /// Render only the rectangle from pixel (x0, y0) up to (x1, y1) of the image, its
    /// pixels bit for bit the whole render's (the sidecar keeps it, for --params).
    #[arg(long, value_name = "x0,y0,x1,y1", value_parser = crate::cli::crop::parse_crop)]
    crop: Option<[u32; 4]>,
    /// Stream each pass into a running tev (its default address 127.0.0.1:14158, or
    /// --tev=HOST:PORT): the image named as the output file, refining as the passes double
    /// (1, 1, 2, 4, ... samples).
    #[arg(long, value_name = "HOST:PORT", num_args = 0..=1, require_equals = true,
          default_missing_value = raylab::render::tev::TEV_ADDRESS)]
    tev: Option<String>,
    /// No progress bar and no summary.
    #[arg(short, long, conflicts_with = "verbose")]
    quiet: bool,
    /// The summary's details too: samples and rays, total internal reflections, the
    /// branches pruned, the samples dropped and what adaptive sampling did.
    #[arg(short, long)]
    verbose: bool,
}

/// What is done with the film after each pass of a render.
type AfterPass<'a> = dyn FnMut(&Film) + Send + 'a;

/// What a render is of: the scene, the camera, the parameters, the size and the samples to
/// take, from the options (a scene, a sidecar or a slide, then the overrides).
struct Job {
    scene: Scene,
    camera: raylab::camera::Camera,
    params: Params,
    // The parameters of the sides after A (B, and C), for a slide that compares things.
    others: Vec<Params>,
    slide: Option<&'static Slide>,
    width: u32,
    height: u32,
    // Samples per pixel to take (a snapshot still refining holds fewer than its target).
    samples: u32,
    // The rectangle rendered (x0, y0, x1, y1), where not the whole image.
    crop: Option<[u32; 4]>,
}

impl Job {
    fn from_args(args: &RenderArgs) -> Result<Job> {
        let sidecar = args.params.as_deref().map(Sidecar::read).transpose()?;
        let (scene, mut params, slide) = match args.slide.map(raylab::lecture::slide_setup) {
            Some(setup) => {
                let s = setup?;
                (s.scene, s.params, Some(s.slide))
            }
            None => {
                let scene_ref = match (&args.scene, &sidecar) {
                    (Some(s), _) => s.clone(),
                    (None, Some(sc)) => sc.scene.clone().into(),
                    (None, None) => BUILTIN_SCENES[0].name.into(),
                };
                let scene = Scene::load(&scene_ref)?;
                if !args.quiet {
                    crate::cli::streams::warn(&scene);
                }
                let params = match &sidecar {
                    Some(sc) => sc.params.clone(),
                    None => scene.params.clone(),
                };
                (scene, params, None)
            }
        };
        let (width, height) = match (args.size, &sidecar) {
            (Some(size), _) => size,
            (None, Some(sc)) => (sc.width, sc.height),
            (None, None) => (scene.width, scene.height),
        };
        // A snapshot from the window may have moved the camera.
        let camera = sidecar
            .as_ref()
            .and_then(|sc| sc.camera.clone())
            .unwrap_or_else(|| scene.camera.clone());
        let mut samples = sidecar.as_ref().and_then(|sc| sc.samples);
        if let Some(spp) = args.spp {
            params.set("spp", &spp.to_string()).context("--spp")?;
            samples = None;
        }
        if let Some(seed) = args.seed {
            params.seed = seed;
        }
        params.set_all(&args.set).context("--set")?;
        let crop = args
            .crop
            .or_else(|| sidecar.as_ref().and_then(|sc| sc.crop));
        if let Some(c) = crop {
            crate::cli::crop::check(c, (width, height), &params)?;
        }
        Ok(Job {
            crop,
            others: slide.map_or_else(Vec::new, |s| s.others(&params)),
            samples: samples.unwrap_or(params.spp),
            scene,
            camera,
            params,
            slide,
            width,
            height,
        })
    }

    /// The size of the image written: the crop's, or the whole.
    fn image_size(&self) -> (u32, u32) {
        match self.crop {
            Some([x0, y0, x1, y1]) => (x1 - x0, y1 - y0),
            None => (self.width, self.height),
        }
    }

    /// Renders it on `pool` in `passes` (the samples each adds), `after` called on the
    /// film after each; a slide that compares things as its split image: side A left of
    /// the first divider, B (and C) after it.
    fn render(
        &self,
        pool: &rayon::ThreadPool,
        bar: &ProgressBar,
        passes: &[u32],
        after: &mut AfterPass,
    ) -> Result<(Film, Stats)> {
        let (scene, camera, w, h) = (&self.scene, &self.camera, self.width, self.height);
        let [x0, y0, ..] = self.crop.unwrap_or_default();
        let crop = Crop {
            size: (w, h),
            origin: (x0, y0),
        };
        pool.install(|| {
            let (cw, ch) = self.image_size();
            let mut film = Film::new(cw, ch);
            let observer = Progress(bar.clone());
            let mut stats = Stats::default();
            for &n in passes {
                let params = &self.params;
                stats += render_crop_pass(scene, camera, params, &mut film, crop, n, &observer)?;
                after(&film);
            }
            // The A/B view's panes, at the window's starting dividers.
            let dividers = self.slide.map_or_else(Vec::new, |s| s.dividers());
            let column = |d: &f32| (w as f32 * d).round() as u32;
            let starts = dividers.iter().map(column);
            let ends = dividers.iter().skip(1).map(column).chain([w]);
            for (side, (x0, x1)) in self.others.iter().zip(starts.zip(ends)) {
                let mut pane = Film::new(w, h);
                stats += render_pass(scene, camera, side, &mut pane, side.spp, &observer)?;
                film.paste_columns(&pane, x0, x1);
            }
            Ok::<_, raylab::render::Cancelled>((film, stats))
        })
        .map_err(runtime)
    }
}

pub fn render_command(args: RenderArgs) -> Result<()> {
    let job = Job::from_args(&args)?;
    let output = match (&args.output, args.slide) {
        (Some(o), _) => o.clone(),
        (None, Some(n)) => default_output(Path::new(""), &format!("slide-{n}")),
        (None, None) => default_output(Path::new(""), &job.scene.name),
    };
    let json = sidecar_path(&output);
    let (w, h) = job.image_size();
    let split = !job.others.is_empty();
    // A FIFO or a pipe gets the image alone: it carries its parameters inside it.
    let target = check_output(&output, args.caption, !split, (w, h))?;
    let with_sidecar = !split && !target.is_stream();
    if with_sidecar {
        Sidecar::check_target(&json, args.params.as_deref())?;
    }
    // An image that carries the parameters being read is not replaced either.
    let read = args.params.as_deref();
    if read.is_some_and(|input| raylab::render::output::same_file(input, &output)) {
        anyhow::bail!(
            "{}: is the image this render reads its parameters from; not replaced (write the image under another name)",
            output.display()
        );
    }
    let pixels = w as u64 * h as u64;
    raylab::scene::memory::check(
        pixels * raylab::scene::memory::BYTES_PER_PIXEL,
        &format!("a {w}x{h} render's film and file"),
    )
    .map_err(anyhow::Error::msg)?;
    split_refuses(&args, &job)?;
    let mut reference = match &args.reference {
        Some(path) => Some(Reference::open(path, job.image_size())?),
        None => None,
    };
    let mut tev = match &args.tev {
        Some(address) => Some(connect_tev(address, &output, &job)?),
        None => None,
    };
    // Measured or watched, the samples come in passes that double, so that each is seen.
    let passes = match reference.is_some() || tev.is_some() {
        true => doubling(job.samples),
        false => vec![job.samples],
    };
    let rows = h as u64 * (passes.len() + job.others.len()) as u64;
    let bar = progress_bar(args.quiet, rows, "rendering");
    let start = Instant::now();
    let exposure = job.params.exposure;
    let quiet = args.quiet;
    let mut after = |film: &Film| {
        if let Some(r) = reference.as_mut() {
            r.after_pass(film, exposure, &bar);
        }
        if let Some(t) = tev.as_mut() {
            let pixels: Vec<_> = film.pixels().collect();
            if let Err(e) = t.update(&pixels) {
                // tev closed: the render goes on, to its file.
                if !quiet {
                    bar.suspend(|| tell!("warning: {e}; the render goes on without it"));
                }
                tev = None;
            }
        }
    };
    let (film, stats) = job.render(&args.threads.pool()?, &bar, &passes, &mut after)?;
    let seconds = start.elapsed().as_secs_f64();
    bar.finish_and_clear();

    // Replacing the file named by -o is what was asked; the summary still says so.
    let replaced = match &target {
        Target::Replace(p) if p.exists() => " (replacing the file there)".to_string(),
        Target::Through(p) => match std::fs::canonicalize(p) {
            Ok(file) => format!(" (through the link, into {})", file.display()),
            Err(_) => " (through the link)".to_string(),
        },
        _ => String::new(),
    };
    let params = &job.params;
    // No one set of parameters makes an A/B split: it gets no sidecar.
    let sidecar = job.others.is_empty().then(|| {
        let rendered = Rendered {
            scene: &job.scene,
            camera: &job.camera,
            params,
            width: job.width,
            height: job.height,
            samples: job.samples,
            seconds,
            stats,
        };
        Sidecar {
            reference: reference.map(Reference::errors),
            crop: job.crop,
            ..Sidecar::new(&output, &rendered)
        }
    });
    match job.slide.filter(|_| args.caption) {
        // The caption as it reads for the parameters rendered (after any --set).
        Some(slide) => {
            let (scene, camera) = (&job.scene, &job.camera);
            let shown = raylab::lecture::Shown {
                params,
                scene,
                camera,
                inspected: slide.inspected(scene, camera, (job.width, job.height)),
            };
            let image = raylab::render::with_caption(
                &film.to_srgb8(params.exposure),
                &slide.caption(&shown),
            );
            raylab::render::write_png(&output, &image, sidecar.as_ref()).map_err(runtime)?;
        }
        None => film
            .save(&output, params.exposure, sidecar.as_ref())
            .map_err(runtime)?,
    }
    if sidecar.is_none() {
        if !args.quiet {
            tell!(
                "slide {}: A/B split written to {}{replaced} (no sidecar: no one set of parameters makes it)",
                args.slide.unwrap_or(0),
                output.display()
            );
        }
        return Ok(());
    }
    if !args.quiet {
        tell!("{}", summary(&job, &film, &stats, seconds));
        if args.verbose {
            tell!("{}", details(&job, &film, &stats));
        }
        if with_sidecar {
            tell!(
                "wrote {}{replaced} and {}",
                output.display(),
                json.display()
            );
        } else {
            tell!(
                "wrote {} (a stream: no sidecar beside it; the image carries its parameters)",
                output.display()
            );
        }
    }
    Ok(())
}

/// A split slide (its sides side by side) is one image of several renders: refused with
/// the options that need one render (`--crop`, `--reference`, `--tev`), naming it.
fn split_refuses(args: &RenderArgs, job: &Job) -> Result<()> {
    if job.others.is_empty() {
        return Ok(());
    }
    let refused = [
        (
            args.crop.is_some(),
            "--crop",
            "crop one of its sides' scenes instead",
        ),
        (
            args.reference.is_some(),
            "--reference",
            "not one to measure",
        ),
        (
            args.tev.is_some(),
            "--tev",
            "stream one of its sides' scenes instead",
        ),
    ];
    match refused.iter().find(|(given, ..)| *given) {
        Some((_, option, instead)) => anyhow::bail!(
            "{option}: slide {} is a split of {} images; {instead}",
            args.slide.unwrap_or(0),
            1 + job.others.len()
        ),
        None => Ok(()),
    }
}

/// tev at `address`, showing the image named as `output`'s file: one line if it is not
/// there.
fn connect_tev(address: &str, output: &Path, job: &Job) -> Result<raylab::render::tev::Tev> {
    let name = output.file_name().map_or_else(
        || output.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let (w, h) = job.image_size();
    raylab::render::tev::Tev::connect(address, &name, w, h).map_err(runtime)
}

/// The samples each pass adds to reach `samples`: 1, then doubling (1, 1, 2, 4, …), the
/// last pass what is left, so that the image is seen (and measured) at every power of two.
fn doubling(samples: u32) -> Vec<u32> {
    let mut passes = Vec::new();
    let mut done = 0u32;
    while done < samples {
        let add = done.max(1).min(samples - done);
        passes.push(add);
        done += add;
    }
    passes
}

/// What a render took and found, in a line that fits 80 columns for a scene name of up to
/// about 16 letters: the size, the samples, the time, the speed and the noise (the status
/// bar's), so a render can be judged without a window. Seconds to the millisecond: a
/// benchmark's render takes a fifth of a second (tests/mitsuba/speed.py reads them).
fn summary(job: &Job, film: &Film, stats: &Stats, seconds: f64) -> String {
    let noise = film
        .noise(job.params.exposure)
        .map_or(String::new(), |n| format!(", noise {:.2}%", n * 100.0));
    format!(
        "{} {}x{}{} at {} spp: {:.3} s, {:.2} M rays/s{noise}",
        job.scene.name,
        job.width,
        job.height,
        job.crop.map_or(String::new(), |[x0, y0, x1, y1]| format!(
            " (crop {x0},{y0} to {x1},{y1})"
        )),
        job.samples,
        seconds,
        stats.total_rays() as f64 / seconds.max(1e-9) / 1e6,
    )
}

/// The summary's details (`--verbose`), each line within 80 columns.
fn details(job: &Job, film: &Film, stats: &Stats) -> String {
    let (w, h) = job.image_size();
    let pixels = (w as u64 * h as u64) as f64;
    let rays = stats.total_rays();
    let mut lines = vec![
        format!(
            "  {:.2} M samples, {:.2} M rays, {:.1} rays/pixel",
            stats.samples as f64 / 1e6,
            rays as f64 / 1e6,
            rays as f64 / pixels,
        ),
        format!(
            "  {} total internal reflections, {} non-finite samples dropped",
            stats.tir_events, stats.non_finite
        ),
        format!(
            "  pruned {} by depth, {} by weight, {} by the ray budget",
            stats.pruned_by_depth, stats.pruned_by_weight, stats.pruned_by_budget
        ),
    ];
    if raylab::render::adaptive::acts(&job.params) {
        lines.push(format!(
            "  adaptive: {:.0}% of pixels done early, {:.1} samples/pixel on average",
            100.0 * film.done_pixels() as f64 / pixels,
            stats.samples as f64 / pixels
        ));
    }
    lines.join("\n")
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_passes_double_to_the_target() {
        assert_eq!(super::doubling(1), [1]);
        assert_eq!(super::doubling(8), [1, 1, 2, 4]);
        assert_eq!(super::doubling(10), [1, 1, 2, 4, 2]);
        assert_eq!(super::doubling(0), Vec::<u32>::new());
        assert_eq!(super::doubling(100).iter().sum::<u32>(), 100);
    }
}
