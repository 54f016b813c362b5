//! A real lens: spherical glass surfaces and a stop, read from a prescription table, traced
//! with the same Snell's law as the scene's glass.
//!
//! A prescription lists the surfaces from the front (the scene's side) to the back (the
//! film's), one row each, in millimetres, as lens designers and pbrt's lens files do:
//!
//! ```text
//! # radius  thickness  ior    aperture  abbe
//!   29.265  3.733      1.67   25.02     47.1
//!   0       4.468      0      16.98           # radius 0 and ior 0: the stop
//! ```
//!
//! - `radius`: of the surface's sphere; positive when its centre is behind the surface
//!   (towards the film), so the surface bulges towards the scene; 0 is flat.
//! - `thickness`: the distance along the axis to the next surface (the last row's is
//!   ignored: focusing sets the film's distance).
//! - `ior`: n_d of the medium behind the surface, up to the next one; 1 (or 0) is air.
//! - `aperture`: the surface's clear diameter; a ray outside it is blocked.
//! - `abbe` (optional): the Abbe number of that medium, for dispersion (0 or absent: none).
//!
//! The stop is the row with radius 0 and ior 0 (exactly one); stopping the lens down
//! shrinks it. [`LensModel`] names the shipped designs, [`paraxial`] gives the focal
//! lengths and f-number from ray-transfer matrices, [`RealLens`] traces rays through the
//! glass. docs/scenes.md ("Real lenses") is the user's page for all of it.

mod camera;
pub mod paraxial;
mod trace;

pub use camera::{LensRay, RealLens, SurfaceProfile, stopped_f_number};
pub use paraxial::Paraxial;

use crate::optics::dispersion;

/// The camera's lens: the thin lens of the lecture, or one of the real designs raylab
/// ships (the `lens` parameter).
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
pub enum LensModel {
    /// The lecture's thin lens: an ideal disk of radius `aperture`.
    #[default]
    #[serde(rename = "thin")]
    Thin,
    /// A 50 mm f/2 double Gauss (Tronnier), the classic normal lens.
    #[serde(rename = "double-gauss-50")]
    DoubleGauss50,
    /// A 22 mm wide angle (Nakamura).
    #[serde(rename = "wide-22")]
    Wide22,
    /// A 250 mm f/5.6 telephoto (Sigler).
    #[serde(rename = "telephoto-250")]
    Telephoto250,
    /// A single biconvex lens of N-BK7, f ≈ 50.7 mm, behind a stop.
    #[serde(rename = "singlet-50")]
    Singlet50,
}

impl LensModel {
    /// The real designs, in the order the parameter lists them.
    pub const DESIGNS: [LensModel; 4] = [
        LensModel::DoubleGauss50,
        LensModel::Wide22,
        LensModel::Telephoto250,
        LensModel::Singlet50,
    ];

    /// A real design's name (the parameter's word for it) and prescription table;
    /// `None` for the thin lens.
    pub fn table(self) -> Option<(&'static str, &'static str)> {
        Some(match self {
            LensModel::Thin => return None,
            LensModel::DoubleGauss50 => (
                "double-gauss-50",
                include_str!("designs/double-gauss-50.lens"),
            ),
            LensModel::Wide22 => ("wide-22", include_str!("designs/wide-22.lens")),
            LensModel::Telephoto250 => {
                ("telephoto-250", include_str!("designs/telephoto-250.lens"))
            }
            LensModel::Singlet50 => ("singlet-50", include_str!("designs/singlet-50.lens")),
        })
    }

    /// A real design's prescription; `None` for the thin lens.
    pub fn prescription(self) -> Option<Prescription> {
        let (name, text) = self.table()?;
        // The shipped designs are tested to parse.
        Prescription::parse(text, name).ok()
    }

    /// The design named `name` (as the parameter spells it).
    pub fn named(name: &str) -> Option<LensModel> {
        LensModel::DESIGNS
            .into_iter()
            .find(|m| m.table().is_some_and(|(n, _)| n == name))
    }
}

/// Whether a real lens's glass disperses (the `lens_dispersion` parameter): off, every
/// element refracts at its n_d; on, at n(λ) from its Abbe number, so each wavelength is
/// focused and magnified a little differently (chromatic aberration).
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "snake_case")]
pub enum LensDispersion {
    /// Every element at n_d: one image for all wavelengths.
    #[default]
    Off,
    /// Each element at n(λ) (Cauchy, through n_d and its Abbe number).
    On,
}

/// Most surfaces a prescription may have: real designs have a few dozen.
pub const MAX_SURFACES: usize = 64;
/// Largest radius, thickness or aperture a prescription may give (mm): 100 m.
const MAX_LENGTH: f32 = 1e5;

/// One surface of a lens, and the medium behind it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// Radius of curvature (mm): positive with the centre behind the surface (towards the
    /// film), 0 for a flat surface.
    pub radius: f32,
    /// Distance along the axis to the next surface (mm).
    pub thickness: f32,
    /// n_d of the medium behind the surface (1 for air).
    pub ior: f32,
    /// Abbe number of that medium (0: it does not disperse).
    pub abbe: f32,
    /// Clear diameter (mm).
    pub aperture: f32,
    /// Whether this is the aperture stop.
    pub stop: bool,
}

impl Surface {
    /// The index of refraction behind the surface at `wavelength` (nm; `None`: n_d).
    pub fn ior_at(&self, wavelength: Option<f32>) -> f32 {
        match wavelength {
            Some(lambda) => dispersion::ior_at(self.ior, self.abbe, lambda),
            None => self.ior,
        }
    }
}

/// A lens: its surfaces, front to back.
#[derive(Clone, Debug, PartialEq)]
pub struct Prescription {
    /// Where it came from: a design's name or a file's path.
    pub name: String,
    /// The surfaces, from the scene's side to the film's.
    pub surfaces: Vec<Surface>,
}

/// A prescription that cannot be read, with the file and line:column.
#[derive(Debug, thiserror::Error, PartialEq)]
#[error("{file}:{line}:{column}: {message}")]
pub struct LensError {
    /// The file (or design name).
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column, in characters.
    pub column: usize,
    /// What is wrong.
    pub message: String,
}

impl Prescription {
    /// Whether any of its glass disperses (has an Abbe number).
    pub fn disperses(&self) -> bool {
        self.surfaces.iter().any(|s| s.abbe > 0.0)
    }

    /// The index of its stop.
    pub fn stop(&self) -> usize {
        // `parse` checks there is exactly one.
        self.surfaces.iter().position(|s| s.stop).unwrap_or(0)
    }

    /// Reads a prescription table (see the module's doc) from `text`; `file` names it in
    /// errors.
    pub fn parse(text: &str, file: &str) -> Result<Prescription, LensError> {
        let err = |line: usize, column: usize, message: String| LensError {
            file: file.to_string(),
            line,
            column,
            message,
        };
        let mut surfaces = Vec::new();
        let mut last_line = 1;
        for (i, raw) in text.lines().enumerate() {
            let line = i + 1;
            last_line = line;
            let body = raw.split('#').next().unwrap_or("");
            let fields = columns(body);
            if fields.is_empty() {
                continue;
            }
            if !(4..=5).contains(&fields.len()) {
                let msg = format!(
                    "a surface has 4 or 5 numbers (radius, thickness, ior, aperture, abbe), found {}",
                    fields.len()
                );
                return Err(err(line, fields[0].0, msg));
            }
            let mut values = [0.0f32; 5];
            for (k, &(column, word)) in fields.iter().enumerate() {
                values[k] = match word.parse::<f32>() {
                    Ok(v) if v.is_finite() && v.abs() <= MAX_LENGTH => v,
                    _ => {
                        let msg = format!(
                            "`{word}` is not a number within ±{MAX_LENGTH:e} ({})",
                            COLUMNS[k]
                        );
                        return Err(err(line, column, msg));
                    }
                };
            }
            let [radius, thickness, ior, aperture, abbe] = values;
            let at = |k: usize| fields[k].0;
            let stop = radius == 0.0 && ior == 0.0;
            if thickness < 0.0 {
                return Err(err(
                    line,
                    at(1),
                    "the thickness must not be negative".into(),
                ));
            }
            if !(ior == 0.0 || ior >= 1.0) {
                let msg = format!("the ior must be at least 1 (or 0 for air), got {ior}");
                return Err(err(line, at(2), msg));
            }
            if aperture <= 0.0 {
                return Err(err(line, at(3), "the aperture must be positive".into()));
            }
            if radius != 0.0 && aperture > 2.0 * radius.abs() {
                let msg = format!(
                    "an aperture of {aperture} mm does not fit on a sphere of radius {radius} mm"
                );
                return Err(err(line, at(3), msg));
            }
            if abbe < 0.0 {
                return Err(err(
                    line,
                    at(4),
                    "the Abbe number must not be negative".into(),
                ));
            }
            if surfaces.len() == MAX_SURFACES {
                let msg = format!("a lens has at most {MAX_SURFACES} surfaces");
                return Err(err(line, at(0), msg));
            }
            if stop && surfaces.iter().any(|s: &Surface| s.stop) {
                return Err(err(line, at(0), "a lens has one stop".into()));
            }
            surfaces.push(Surface {
                radius,
                thickness,
                ior: ior.max(1.0),
                abbe,
                aperture,
                stop,
            });
        }
        let whole = |message: &str| err(last_line, 1, message.to_string());
        if surfaces.len() < 2 {
            return Err(whole("a lens has at least two surfaces"));
        }
        if !surfaces.iter().any(|s| s.stop) {
            return Err(whole("a lens has a stop: a row with radius 0 and ior 0"));
        }
        if surfaces.last().is_some_and(|s| s.ior != 1.0) {
            return Err(whole(
                "the last surface must leave the light in air (ior 1)",
            ));
        }
        Ok(Prescription {
            name: file.to_string(),
            surfaces,
        })
    }
}

/// The names of a row's columns, for errors.
const COLUMNS: [&str; 5] = ["radius", "thickness", "ior", "aperture", "abbe"];

/// The whitespace-separated words of `line`, each with its 1-based column (in characters).
fn columns(line: &str) -> Vec<(usize, &str)> {
    let mut words = Vec::new();
    let mut start = None;
    for (column, (offset, c)) in line.char_indices().enumerate() {
        match (c.is_whitespace(), start) {
            (false, None) => start = Some((column + 1, offset)),
            (true, Some((col, from))) => {
                words.push((col, &line[from..offset]));
                start = None;
            }
            _ => {}
        }
    }
    if let Some((col, from)) = start {
        words.push((col, &line[from..]));
    }
    words
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_shipped_design_parses_under_its_parameters_word() {
        assert_eq!(LensModel::Thin.table(), None);
        for model in LensModel::DESIGNS {
            let (name, text) = model.table().unwrap();
            let p = Prescription::parse(text, name).unwrap();
            assert_eq!(p.surfaces.iter().filter(|s| s.stop).count(), 1, "{name}");
            assert_eq!(LensModel::named(name), Some(model));
            let word = serde_json::to_value(model).unwrap();
            assert_eq!(word.as_str(), Some(name));
        }
    }

    #[test]
    fn errors_name_the_line_and_column() {
        let e = Prescription::parse("# a lens\n 10  2 1.5 8\n 0 1 0 x7\n", "my.lens").unwrap_err();
        assert_eq!(
            e.to_string(),
            "my.lens:3:8: `x7` is not a number within ±1e5 (aperture)"
        );
        let e = Prescription::parse("10 2 1.5 30\n0 1 0 4\n-10 0 1 8\n", "a").unwrap_err();
        assert_eq!(e.line, 1);
        assert_eq!(e.column, 10);
        assert!(e.message.contains("does not fit"), "{e}");
        let e = Prescription::parse("10 2 1.5 8\n-10 0 1 8\n", "a").unwrap_err();
        assert!(e.message.contains("stop"), "{e}");
        let e = Prescription::parse("0 1 0 4\n10 2 0.5 8\n-10 0 1 8\n", "a").unwrap_err();
        assert_eq!((e.line, e.column), (2, 6));
        let e = Prescription::parse("0 1 0 4\n10 2 1.5 8\n-10 0 1.5 8\n", "a").unwrap_err();
        assert!(e.message.contains("air"), "{e}");
        let e = Prescription::parse("0 1 0 4 1 9\n", "a").unwrap_err();
        assert!(e.message.contains("found 6"), "{e}");
        let e = Prescription::parse("0 1 0 4\n0 1 0 4\n-10 0 1 8\n", "a").unwrap_err();
        assert!(e.message.contains("one stop"), "{e}");
        let e = Prescription::parse("0 1 0 4\n10 NaN 1.5 8\n-10 0 1 8\n", "a").unwrap_err();
        assert_eq!((e.line, e.column), (2, 4));
    }
}
