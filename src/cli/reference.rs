//! `raylab render --reference REF`: the render measured against a reference image after
//! each pass, as pbrt's `--mse-reference-image` measures it at the end.

use anyhow::Result;
use indicatif::ProgressBar;
use raylab::render::compare::{LinearImage, compare};
use raylab::render::{Film, PassError, ReferenceErrors};
use std::path::Path;

/// A reference, and the render's error against it so far.
pub struct Reference {
    image: LinearImage,
    errors: ReferenceErrors,
}

impl Reference {
    /// The reference at `path`, for a render of `size`: one line and exit status 2 if it
    /// cannot be read or is another size.
    pub fn open(path: &Path, size: (u32, u32)) -> Result<Reference> {
        let image = LinearImage::read(path)?;
        image.check_size(&path.display().to_string(), ("the render", size))?;
        Ok(Reference {
            image,
            errors: ReferenceErrors {
                image: path.display().to_string(),
                passes: Vec::new(),
            },
        })
    }

    /// Measures `film` after a pass, shown at `exposure`, and prints the line (above the
    /// progress `bar`).
    pub fn after_pass(&mut self, film: &Film, exposure: f32, bar: &ProgressBar) {
        let image = LinearImage {
            width: film.width(),
            height: film.height(),
            pixels: film.pixels().collect(),
        };
        let m = compare(&image, &self.image, exposure);
        let pass = PassError {
            samples: film.spp(),
            mse: m.mse,
            rel_mse: m.rel_mse,
            rms_shown: m.rms_shown,
            noise: film.noise(exposure),
        };
        let noise = pass.noise.map_or(String::new(), |n| {
            format!("; noise estimate {:.3} %", n * 100.0)
        });
        bar.suspend(|| {
            say!(
                "{:>6} spp: MSE {:.4e}, relative MSE {:.4e}, RMS error {:.3} % as shown{noise}",
                pass.samples,
                pass.mse,
                pass.rel_mse,
                pass.rms_shown * 100.0
            )
        });
        self.errors.passes.push(pass);
    }

    /// What the sidecar records.
    pub fn errors(self) -> ReferenceErrors {
        self.errors
    }
}
