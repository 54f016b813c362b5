//! `raylab sweep`: one image per value of a parameter, as a labelled contact sheet or an
//! animation.

use crate::cli::output::{check_writable, default_output};
use crate::cli::progress::{Progress, progress_bar};
use crate::{parse_size, runtime};
use anyhow::{Context, Result, bail};
use raylab::render::SheetError;
use raylab::render::output::{save_image, write_file};
use raylab::scene::Scene;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(clap::Args)]
pub struct SweepArgs {
    /// A scene file (.toml), a model (.obj, .gltf, .glb) or a built-in name.
    scene: std::ffi::OsString,
    /// The parameter and its values, e.g. spp=1,4,16 or fresnel=schlick,exact.
    #[arg(long, value_name = "NAME=V1,V2,...")]
    param: String,
    /// The sheet to write: .png for a contact sheet, .gif for an animation with one
    /// labelled frame per value [default: SCENE-NAME.png in the current folder, numbered
    /// if taken].
    #[arg(short, long, value_name = "SHEET.png|ANIMATION.gif")]
    output: Option<PathBuf>,
    /// Size of each image [default: the scene's, halved].
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Samples per pixel of every image (same as --set spp=N), unless the sweep is of spp.
    #[arg(long, value_name = "N")]
    spp: Option<u32>,
    /// Random seed (same as --set seed=S).
    #[arg(long, value_name = "S")]
    seed: Option<u64>,
    /// Set other parameters for every image (repeatable).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    #[command(flatten)]
    threads: crate::cli::threads::Threads,
    /// How long an animation shows each frame, in milliseconds.
    #[arg(long, value_name = "MS", default_value_t = 1000, value_parser = clap::value_parser!(u32).range(20..=60_000))]
    frame_ms: u32,
    /// No progress bar and no summary line.
    #[arg(short, long)]
    quiet: bool,
}

pub fn sweep_command(args: &SweepArgs) -> Result<()> {
    let sweep = raylab::render::parse_sweep(&args.param).context("--param")?;
    let (name, values) = (&sweep.name, &sweep.values);
    let scene = Scene::load(&args.scene)?;
    crate::cli::streams::warn(&scene);
    let mut params = scene.params.clone();
    if let Some(spp) = args.spp {
        params.set("spp", &spp.to_string()).context("--spp")?;
    }
    if let Some(seed) = args.seed {
        params.seed = seed;
    }
    params.set_all(&args.set).context("--set")?;
    let output = match &args.output {
        Some(o) => o.clone(),
        None => default_output(Path::new(""), &format!("{}-{name}", scene.name)),
    };
    let gif = match raylab::scene::input::extension(&output).as_deref() {
        Some("png") => false,
        Some("gif") => true,
        _ => bail!(
            "{}: a sweep is a .png contact sheet or a .gif animation",
            output.display()
        ),
    };
    let (w, h) = args
        .size
        .unwrap_or(((scene.width / 2).max(1), (scene.height / 2).max(1)));
    // What the result holds, said before any frame is rendered: the sheet's pixels (twice,
    // while it is encoded), or an animation's frames at up to a byte a pixel.
    let tile = raylab::render::frame_size((w, h));
    let frames = values.len() as u64;
    let (needed, what) = if gif {
        (
            frames * tile.0 as u64 * tile.1 as u64 * 6 / 5,
            "the animation's frames",
        )
    } else {
        let (sw, sh) = raylab::render::ContactSheet::size(values.len(), tile);
        (2 * 3 * sw as u64 * sh as u64, "the contact sheet's pixels")
    };
    raylab::scene::memory::check(needed, &format!("{} values: {what}", values.len()))
        .map_err(anyhow::Error::msg)?;
    // The file holds what memory does, at most: a sheet stored uncompressed, or the frames.
    check_writable(&output, false, needed / if gif { 1 } else { 2 } + 64 * 1024)?;
    args.threads.install_global()?;
    let start = Instant::now();
    let bar = progress_bar(args.quiet, h as u64 * values.len() as u64, "sweeping");
    let progress = Progress(bar.clone());
    let sweep_each = |each: &mut dyn FnMut(image::RgbImage) -> Result<(), SheetError>| {
        raylab::render::sweep_each(
            &scene,
            &scene.camera,
            &params,
            (w, h),
            &sweep,
            &progress,
            each,
        )
    };
    // Each frame goes into the result as it is made, and is then dropped.
    let written = if gif {
        let mut bytes = Vec::new();
        let encoded = raylab::render::Animation::new(&mut bytes, args.frame_ms)
            .map_err(|e| SheetError::Frame(e.to_string()))
            .and_then(|mut animation| {
                sweep_each(&mut |frame| {
                    animation
                        .add(&frame)
                        .map_err(|e| SheetError::Frame(e.to_string()))
                })
            });
        encoded?;
        write_file(&output, &bytes).map_err(image::ImageError::IoError)
    } else {
        let mut sheet = raylab::render::ContactSheet::new(values.len(), tile);
        sweep_each(&mut |frame| {
            sheet.add(&frame);
            Ok(())
        })?;
        save_image(&sheet.finish(), &output, image::ImageFormat::Png)
    };
    bar.finish_and_clear();
    written
        .with_context(|| format!("{}: cannot write the sweep", output.display()))
        .map_err(runtime)?;
    if !args.quiet {
        tell!(
            "{}: {} images of {w}x{h} across {name} in {:.2} s; wrote {}",
            scene.name,
            values.len(),
            start.elapsed().as_secs_f64(),
            output.display()
        );
    }
    Ok(())
}
