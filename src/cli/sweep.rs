//! `raylab sweep`: one image per value of a parameter, as a labelled contact sheet.

use crate::{parse_size, runtime};
use anyhow::{Context, Result, bail};
use raylab::scene::Scene;
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args)]
pub struct SweepArgs {
    /// A scene file or built-in name.
    scene: String,
    /// The parameter and its values, e.g. spp=1,4,16 or fresnel=schlick,exact.
    #[arg(long, value_name = "NAME=V1,V2,...")]
    param: String,
    /// The sheet to write (.png).
    #[arg(short, long, value_name = "SHEET.png")]
    output: PathBuf,
    /// Size of each image [default: the scene's, halved].
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Set other parameters for every image (repeatable).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
}

pub fn sweep_command(args: &SweepArgs) -> Result<()> {
    let (name, values) = raylab::render::parse_sweep(&args.param).context("--param")?;
    let scene = Scene::load(&args.scene)?;
    let mut params = scene.params.clone();
    params.set_all(&args.set).context("--set")?;
    let ext = args
        .output
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    if ext.as_deref() != Some("png") {
        bail!("{}: a contact sheet is a .png", args.output.display());
    }
    let (w, h) = args
        .size
        .unwrap_or(((scene.width / 2).max(1), (scene.height / 2).max(1)));
    let start = Instant::now();
    let sheet =
        raylab::render::contact_sheet(&scene, &scene.camera, &params, w, h, &name, &values, &())?;
    raylab::render::output::save_image(&sheet, &args.output, image::ImageFormat::Png)
        .with_context(|| format!("{}: cannot write the sheet", args.output.display()))
        .map_err(runtime)?;
    eprintln!(
        "{}: {} images of {w}x{h} across {name} in {:.2} s; wrote {}",
        scene.name,
        values.len(),
        start.elapsed().as_secs_f64(),
        args.output.display()
    );
    Ok(())
}
