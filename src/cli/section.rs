//! `raylab section`: the section view of one pixel's ray tree, or the interface
//! workbench at one angle, as an SVG (for slides) or a PNG.

use super::inspect::{SampleArgs, Traced, parse_pixel, trace_pixel};
use super::output::check_writable;
use crate::{parse_ior, parse_size};
use anyhow::{Context, Result, bail};
use raylab::section::{Bench, Room, Theme, Workbench, section, text_size, to_png, to_svg};
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct SectionArgs {
    /// A scene file (.toml), a model (.obj, .gltf, .glb) or a built-in name.
    #[arg(default_value = "default")]
    scene: std::ffi::OsString,
    /// The pixel whose ray tree to draw, X,Y from the top left of the image.
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel, required_unless_present = "angle")]
    pixel: Option<(u32, u32)>,
    #[command(flatten)]
    sample: SampleArgs,
    /// The interface workbench instead of a pixel: the angle of incidence, degrees from
    /// the normal (0 to 89.9), between --n1 and --n2.
    #[arg(long, value_name = "DEG", value_parser = parse_angle, conflicts_with_all = ["pixel", "set", "size"])]
    angle: Option<f32>,
    /// The workbench's index of refraction on the side the light comes from.
    #[arg(long, default_value_t = 1.0, value_parser = parse_ior, requires = "angle")]
    n1: f32,
    /// The workbench's index of refraction on the other side.
    #[arg(long, default_value_t = 1.5, value_parser = parse_ior, requires = "angle")]
    n2: f32,
    /// The workbench's GGX roughness α (0 to 1): above 0 it draws the rough interface's
    /// reflection and transmission lobes.
    #[arg(long, value_name = "ALPHA", default_value_t = 0.0, value_parser = parse_roughness, requires = "angle")]
    roughness: f32,
    /// The file to write: .svg (text stays text, for slides) or .png.
    #[arg(short, long, value_name = "FILE")]
    output: PathBuf,
    /// The picture's size in points (SVG) or pixels (PNG).
    #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "960x720")]
    figure: (u32, u32),
    /// Light marks on near-black, as the window draws them, instead of dark on white.
    #[arg(long)]
    dark: bool,
    /// Zoom in on where the pixel's camera ray first meets a surface: 1 shows the whole
    /// tree, up to 50.
    #[arg(long, value_name = "F", default_value_t = 1.0, value_parser = parse_zoom, conflicts_with = "angle")]
    zoom: f32,
    /// The lens bench instead of the pixel's section: the camera's real lens (the `lens`
    /// parameter) cut through its axis and the pixel's film point, and the pixel's rays
    /// through its glass with their angles at each surface.
    #[arg(long, conflicts_with_all = ["angle", "zoom"])]
    lens_bench: bool,
}

/// A zoom factor, 1 to the section's deepest.
fn parse_zoom(s: &str) -> Result<f32, String> {
    number_in(s, 1.0, raylab::section::MAX_ZOOM, "")
}

/// A roughness α, 0 (smooth) to the largest a material takes.
fn parse_roughness(s: &str) -> Result<f32, String> {
    let (lo, hi) = raylab::params::ROUGHNESS_RANGE;
    number_in(s, lo, hi, "")
}

/// An angle of incidence in degrees, 0 to the workbench's largest.
fn parse_angle(s: &str) -> Result<f32, String> {
    number_in(s, 0.0, raylab::section::MAX_ANGLE, " degrees")
}

/// `s` as a number from `lo` to `hi` (in `unit`), or why not.
fn number_in(s: &str, lo: f32, hi: f32, unit: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if (lo..=hi).contains(&v) => Ok(v),
        Ok(v) => Err(format!("{v} is out of range ({lo} to {hi}{unit})")),
        Err(_) => Err(format!("`{s}` is not a number")),
    }
}

pub fn section_command(args: &SectionArgs) -> Result<()> {
    let path = &args.output;
    let svg = match raylab::scene::input::extension(path).as_deref() {
        Some("svg") => true,
        Some("png") => false,
        _ => bail!("{}: the output must end in .svg or .png", path.display()),
    };
    let (fw, fh) = args.figure;
    // An SVG is a few kB; a PNG at most its RGBA pixels.
    check_writable(path, false, 4 * fw as u64 * fh as u64 + 64 * 1024)?;
    let diagram = match (args.angle, args.pixel) {
        (Some(theta_i), _) => Workbench {
            n1: args.n1,
            n2: args.n2,
            theta_i,
            roughness: args.roughness,
        }
        .diagram(),
        (None, Some(pixel)) if args.lens_bench => {
            let Traced {
                scene,
                frame,
                camera_point: (film, sample),
                ..
            } = trace_pixel(&args.scene, &args.sample, pixel)?;
            let lens = frame.real_lens().with_context(|| {
                format!(
                    "{}: the camera has the thin lens, which has no glass to draw; add --set lens=double-gauss-50 (or another design)",
                    scene.name
                )
            })?;
            let bench = Bench { lens, film, sample };
            let mut d = bench
                .diagram()
                .context("no ray from the pixel's film point gets through the lens")?;
            d.title = format!(
                "{}: lens bench at pixel ({}, {}), sample {}",
                scene.name, pixel.0, pixel.1, args.sample.sample
            );
            d
        }
        (None, Some(pixel)) => {
            let Traced {
                scene, tree, frame, ..
            } = trace_pixel(&args.scene, &args.sample, pixel)?;
            let (w, h) = args.figure;
            let room = Room {
                size: glam::Vec2::new(w as f32, h as f32),
                text: text_size(w, h),
                zoom: args.zoom,
                titled: true,
            };
            let mut d = section(&scene, &frame, &tree, pixel, room)
                .context("the pixel's sample traced no ray")?;
            d.title = format!(
                "{}: section through pixel ({}, {}), sample {}",
                scene.name, pixel.0, pixel.1, args.sample.sample
            );
            d
        }
        (None, None) => {
            bail!("give --pixel X,Y (a pixel's ray tree) or --angle DEG (the workbench)")
        }
    };
    let theme = if args.dark { Theme::Dark } else { Theme::Light };
    let (w, h) = args.figure;
    let written = if svg {
        raylab::render::output::write_file(path, to_svg(&diagram, w, h, theme).as_bytes())
            .map_err(anyhow::Error::from)
    } else {
        let img = to_png(&diagram, w, h, theme).context("an empty picture")?;
        raylab::render::output::save_image(&img, path, image::ImageFormat::Png)
            .map_err(anyhow::Error::from)
    };
    written
        .with_context(|| format!("cannot write {}", path.display()))
        .map_err(crate::runtime)?;
    say!("{}", path.display());
    Ok(())
}
