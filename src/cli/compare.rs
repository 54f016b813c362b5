//! `raylab compare A B`: how far an image is from a reference, and where.

use crate::cli::output::check_writable;
use crate::runtime;
use anyhow::{Context, Result};
use raylab::render::compare::{LinearImage, compare, difference_image, percentile_99};
use raylab::render::output::save_image;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct CompareArgs {
    /// The image to measure (PNG, EXR, or another 8-bit, 16-bit or float format).
    image: PathBuf,
    /// The reference it is measured against, of the same size.
    reference: PathBuf,
    /// Also write where they differ, in false colour (|ΔY| as shown: black none, pale
    /// yellow at --scale or more), as a PNG.
    #[arg(short, long, value_name = "DIFF.png")]
    output: Option<PathBuf>,
    /// The difference the false colour's top stands for [default: the 99th percentile
    /// of the pixels' differences].
    #[arg(long, value_name = "DY", value_parser = parse_scale)]
    scale: Option<f64>,
}

fn parse_scale(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("`{s}`: a number above 0")),
    }
}

pub fn compare_command(args: &CompareArgs) -> Result<()> {
    let a = LinearImage::read(&args.image)?;
    let b = LinearImage::read(&args.reference)?;
    let b_name = args.reference.display().to_string();
    a.check_size(
        &args.image.display().to_string(),
        (&b_name, (b.width, b.height)),
    )?;
    if let Some(out) = &args.output {
        let bytes = raylab::render::output::image_bytes_at_most("png", a.width, a.height);
        check_writable(out, false, bytes)?;
    }
    let m = compare(&a, &b, 0.0);
    say!(
        "{} against {}: MSE {:.4e}, relative MSE {:.4e}, RMS error {:.3} % of the mean as shown; \
         largest difference {:.4} at ({}, {})",
        args.image.display(),
        args.reference.display(),
        m.mse,
        m.rel_mse,
        m.rms_shown * 100.0,
        m.largest.0,
        m.largest.1,
        m.largest.2
    );
    if let Some(out) = &args.output {
        let scale = args.scale.unwrap_or_else(|| percentile_99(&a, &b));
        // Images that do not differ: any scale shows black.
        let scale = if scale > 0.0 { scale } else { 1.0 };
        save_image(
            &difference_image(&a, &b, scale),
            out,
            image::ImageFormat::Png,
        )
        .with_context(|| format!("{}: cannot write the difference", out.display()))
        .map_err(runtime)?;
        say!(
            "wrote {} (pale yellow: a difference of {scale:.4} or more)",
            out.display()
        );
    }
    Ok(())
}
