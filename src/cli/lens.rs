//! `raylab lens`: a lens prescription's paraxial description, from its ray-transfer
//! matrices: effective, back and front focal lengths, f-number and field of view.

use anyhow::{Context, Result, bail};
use raylab::optics::lens::{LensModel, Paraxial, Prescription};
use std::path::Path;

/// The film the field of view is given on: 35 mm, 36 × 24 mm.
const FILM_MM: (f64, f64) = (36.0, 24.0);

#[derive(clap::Args)]
pub struct LensArgs {
    /// Built-in designs (double-gauss-50, wide-22, telephoto-250, singlet-50) or
    /// prescription files (see docs/scenes.md, "Real lenses"); every built-in design
    /// without one.
    #[arg(value_name = "NAME|FILE")]
    lenses: Vec<String>,
}

pub fn lens_command(args: &LensArgs) -> Result<()> {
    let all: Vec<String>;
    let lenses = if args.lenses.is_empty() {
        all = LensModel::DESIGNS
            .iter()
            .filter_map(|m| m.table().map(|(name, _)| name.to_string()))
            .collect();
        &all
    } else {
        &args.lenses
    };
    for (i, name) in lenses.iter().enumerate() {
        let (lens, origin) = read(name)?;
        if i > 0 {
            say!("");
        }
        for line in describe(&lens, origin)? {
            say!("{line}");
        }
    }
    Ok(())
}

/// The prescription `name` stands for: a built-in design, or the file at that path.
fn read(name: &str) -> Result<(Prescription, &'static str)> {
    if let Some(model) = LensModel::named(name) {
        let (_, text) = model.table().context("a design has a table")?;
        return Ok((Prescription::parse(text, name)?, "built in"));
    }
    let path = Path::new(name);
    let text = raylab::scene::input::read_text(path).with_context(|| {
        let names: Vec<&str> = LensModel::DESIGNS
            .iter()
            .filter_map(|m| m.table().map(|(n, _)| n))
            .collect();
        format!(
            "{name}: neither a built-in design ({}) nor a readable file",
            names.join(", ")
        )
    })?;
    Ok((Prescription::parse(&text, name)?, "file"))
}

/// `lens`'s description, line by line.
fn describe(lens: &Prescription, origin: &str) -> Result<Vec<String>> {
    let Some(p) = Paraxial::of(lens) else {
        bail!(
            "{}: no paraxial focus (the lens has no power, or no ray from the front reaches its stop)",
            lens.name
        );
    };
    // An element is a piece of glass: a surface with glass behind it begins one.
    let elements = lens.surfaces.iter().filter(|s| s.ior > 1.0).count();
    let (w, h) = FILM_MM;
    let diagonal = w.hypot(h);
    let dispersion = if lens.disperses() {
        "Abbe numbers given for its glass"
    } else {
        "no Abbe numbers"
    };
    let rows = [
        ("effective focal length", format!("{:.3} mm", p.efl)),
        (
            "back focal length",
            format!("{:.3} mm (last surface to the focus)", p.bfl),
        ),
        (
            "front focal length",
            format!("{:.3} mm (first surface to the front focus)", p.ffl),
        ),
        (
            "length",
            format!("{:.3} mm (first surface to last)", p.length),
        ),
        (
            "entrance pupil",
            format!("{:.3} mm across, the stop open", p.entrance_pupil),
        ),
        ("f-number", format!("f/{:.2}", p.f_number())),
        (
            "field of view",
            format!(
                "{:.1}° × {:.1}° ({:.1}° diagonal) on {w} × {h} mm film, focused at infinity",
                p.field_of_view(w),
                p.field_of_view(h),
                p.field_of_view(diagonal)
            ),
        ),
        ("dispersion", dispersion.to_string()),
    ];
    let plural = if elements == 1 { "" } else { "s" };
    let mut lines = vec![format!(
        "{} ({origin}): {elements} element{plural}, {} surfaces, the stop at surface {}",
        lens.name,
        lens.surfaces.len(),
        lens.stop() + 1
    )];
    lines.extend(
        rows.iter()
            .map(|(label, value)| format!("  {label:<24}{value}")),
    );
    Ok(lines)
}
