//! Dispersion: an index of refraction that depends on the wavelength, and the wavelengths
//! a sample carries once it meets a dispersive dielectric.
//!
//! Spectra are the three boxes of the RGB channels: blue is 400–500 nm, green 500–600 nm,
//! red 600–700 nm, each flat inside its box. An RGB colour is the spectrum that is its
//! channel's value across each box, and a spectrum's RGB is its mean over each box, so the
//! round trip is exact and white stays white (a white furnace stays uniform). At a
//! sample's first dispersive surface the ray tree splits into three wavelengths, one
//! uniform in each box from one random number ([`wavelength_in`]), each carrying its
//! box's channel: no colour noise. A single path (stochastic tree, path tracing, photons)
//! picks one wavelength uniform over 400–700 nm instead and carries only its box's
//! channel, times 3 (the probability of that box is 1/3). Either way the expected value
//! of every channel is unchanged.

use crate::math::Color;

/// The d line of helium, where an Abbe number's `ior` is measured (nm).
pub const LAMBDA_D: f32 = 587.56;
/// The F line of hydrogen (nm).
pub const LAMBDA_F: f32 = 486.13;
/// The C line of hydrogen (nm).
pub const LAMBDA_C: f32 = 656.27;

/// The shortest wavelength sampled (nm).
pub const LAMBDA_MIN: f32 = 400.0;
/// The longest wavelength sampled (nm).
pub const LAMBDA_MAX: f32 = 700.0;

/// The index of refraction at `lambda_nm` of a glass with `ior` = n_d at the d line and
/// Abbe number `abbe` = V_d = (n_d − 1)/(n_F − n_C), by Cauchy's two-term equation
/// n(λ) = A + B/λ², fitted to both: B = (n_d − 1) / (V_d (1/λ_F² − 1/λ_C²)),
/// A = n_d − B/λ_d². `abbe` 0 means no dispersion. Never below 1 (a very low Abbe number
/// would otherwise take the red end of a weak glass under vacuum's index).
// Out of line: the tracer's hot path only branches to it when a glass disperses.
#[inline(never)]
pub fn ior_at(ior: f32, abbe: f32, lambda_nm: f32) -> f32 {
    if abbe <= 0.0 {
        return ior;
    }
    let inv_sq = |l: f32| 1.0 / (l as f64 * l as f64);
    let b = (ior as f64 - 1.0) / (abbe as f64 * (inv_sq(LAMBDA_F) - inv_sq(LAMBDA_C)));
    let a = ior as f64 - b * inv_sq(LAMBDA_D);
    ((a + b * inv_sq(lambda_nm)) as f32).max(1.0)
}

/// The wavelength (nm) for a uniform number `u` in [0, 1): uniform over 400–700 nm.
pub fn wavelength(u: f32) -> f32 {
    LAMBDA_MIN + (LAMBDA_MAX - LAMBDA_MIN) * u
}

/// The wavelength (nm) in the box of `channel` (0 red, 1 green, 2 blue) for a uniform
/// number `u` in [0, 1): uniform over that box, so that one `u` gives a sample one
/// wavelength in each of the three (stratified).
pub fn wavelength_in(channel: usize, u: f32) -> f32 {
    let width = (LAMBDA_MAX - LAMBDA_MIN) / 3.0;
    LAMBDA_MAX - width * (channel as f32 + 1.0 - u)
}

/// The RGB channel whose box holds `lambda_nm`: 0 (red), 1 (green) or 2 (blue).
pub fn channel(lambda_nm: f32) -> usize {
    if lambda_nm >= 600.0 {
        0
    } else if lambda_nm >= 500.0 {
        1
    } else {
        2
    }
}

/// What a sample that carries `lambda_nm` multiplies its radiance by: 3 in the channel of
/// its box (1 over the probability of that box), 0 in the others.
pub fn channel_weight(lambda_nm: f32) -> Color {
    let mut w = Color::ZERO;
    w[channel(lambda_nm)] = 3.0;
    w
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cauchy_fit_meets_the_index_and_the_abbe_number() {
        for (ior, abbe) in [
            (1.5168f32, 64.17f32),
            (1.62, 36.4),
            (2.417, 55.3),
            (1.333, 55.8),
        ] {
            assert!((ior_at(ior, abbe, LAMBDA_D) - ior).abs() < 1e-6);
            let v = (ior - 1.0) / (ior_at(ior, abbe, LAMBDA_F) - ior_at(ior, abbe, LAMBDA_C));
            assert!((v - abbe).abs() < 1e-3 * abbe, "{ior}, {abbe}: V = {v}");
            // Normal dispersion: blue bends more than red.
            assert!(ior_at(ior, abbe, 450.0) > ior_at(ior, abbe, 650.0));
        }
        // N-BK7 (n_d 1.5168, V_d 64.17): Schott's Sellmeier equation gives n = 1.52532 at
        // 450 nm and 1.51452 at 650 nm; the two-term fit is within 1e-3 of both.
        assert!((ior_at(1.5168, 64.17, 450.0) - 1.5253).abs() < 1e-3);
        assert!((ior_at(1.5168, 64.17, 650.0) - 1.5145).abs() < 1e-3);
        assert_eq!(ior_at(1.5, 0.0, 450.0), 1.5);
        assert_eq!(ior_at(1.01, 0.2, 700.0), 1.0);
    }

    #[test]
    fn boxes_split_the_visible_range_in_thirds_and_weigh_three() {
        assert_eq!(wavelength(0.0), 400.0);
        for (u, c) in [
            (0.0, 2),
            (0.33, 2),
            (0.34, 1),
            (0.66, 1),
            (0.67, 0),
            (0.999, 0),
        ] {
            assert_eq!(channel(wavelength(u)), c, "u = {u}");
        }
        // Uniform u: each channel a third of the time, times 3: white stays white.
        let n = 3000;
        let mean = (0..n)
            .map(|i| channel_weight(wavelength((i as f32 + 0.5) / n as f32)))
            .fold(Color::ZERO, |a, b| a + b)
            / n as f32;
        assert!((mean - Color::ONE).abs().max_element() < 1e-6, "{mean}");
    }

    #[test]
    fn one_number_puts_a_wavelength_in_each_box() {
        for u in [0.0, 0.25, 0.5, 0.999] {
            for c in 0..3 {
                assert_eq!(channel(wavelength_in(c, u)), c, "u = {u}, channel {c}");
            }
        }
        assert_eq!(wavelength_in(0, 0.0), 600.0);
        assert_eq!(wavelength_in(1, 0.5), 550.0);
        assert_eq!(wavelength_in(2, 0.0), 400.0);
        // At the top of a box, within rounding of the next one's bottom.
        assert!((wavelength_in(2, 1.0 - f32::EPSILON) - 500.0).abs() < 1e-3);
    }
}
