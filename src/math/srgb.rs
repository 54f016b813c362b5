//! The sRGB curve (IEC 61966-2-1) between linear radiance and what a display shows: exact,
//! as tables for whole frames, and back (textures are decoded by it).

/// Linear to sRGB transfer function (IEC 61966-2-1), for values in [0, 1].
#[inline]
pub fn srgb_encode(linear: f32) -> f32 {
    if linear <= 0.003_130_8 {
        12.92 * linear
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    }
}

/// sRGB encoding of a linear value clamped to [0, 1], from a table of 4096 steps with
/// linear interpolation (within 2e-5 of [`srgb_encode`]): the noise estimate runs it nine
/// times a pixel for every frame, where `powf` is too slow (docs/performance.md, "Shaped
/// by measurement").
#[inline]
pub(crate) fn srgb_encode_table(linear: f32) -> f32 {
    static TABLE: std::sync::OnceLock<Vec<f32>> = std::sync::OnceLock::new();
    const N: usize = 4096;
    let table = TABLE.get_or_init(|| {
        (0..=N + 1)
            .map(|i| srgb_encode((i as f32 / N as f32).min(1.0)))
            .collect()
    });
    let x = linear.clamp(0.0, 1.0) * N as f32;
    let i = x as usize;
    let t = x - i as f32;
    table[i] + (table[i + 1] - table[i]) * t
}

/// 8-bit sRGB of a linear value, clamped to [0, 1] (NaN is black), exactly rounded.
#[inline]
pub fn srgb8_exact(linear: f32) -> u8 {
    let v = if linear.is_finite() {
        linear.clamp(0.0, 1.0)
    } else {
        0.0
    };
    (srgb_encode(v) * 255.0 + 0.5) as u8
}

/// 8-bit sRGB of a linear value, clamped to [0, 1]: a 4096-entry table, exact to within
/// one code value, for converting whole frames quickly on the display thread.
#[inline]
pub fn srgb8(linear: f32) -> u8 {
    static TABLE: std::sync::OnceLock<Vec<u8>> = std::sync::OnceLock::new();
    const N: usize = 4096;
    let table = TABLE.get_or_init(|| (0..=N).map(|i| srgb8_exact(i as f32 / N as f32)).collect());
    let v = if linear.is_finite() {
        linear.clamp(0.0, 1.0)
    } else {
        0.0
    };
    table[(v * N as f32 + 0.5) as usize]
}

/// sRGB to linear (IEC 61966-2-1), the inverse of [`srgb_encode`].
pub fn srgb_decode(encoded: f32) -> f32 {
    if encoded <= 0.040_45 {
        encoded / 12.92
    } else {
        ((encoded + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_curve_endpoints_and_midtone() {
        assert_eq!(srgb_encode(0.0), 0.0);
        assert!((srgb_encode(1.0) - 1.0).abs() < 1e-6);
        // Linear 0.2140 is the sRGB mid-grey 0.5.
        assert!((srgb_encode(0.214_041) - 0.5).abs() < 1e-4);
    }

    #[test]
    fn the_srgb_table_matches_the_curve() {
        for i in 0..=1000 {
            let v = i as f32 / 1000.0;
            assert!((srgb8(v) as i32 - srgb8_exact(v) as i32).abs() <= 1, "{v}");
        }
        assert_eq!((srgb8(-1.0), srgb8(2.0), srgb8(f32::NAN)), (0, 255, 0));
    }

    #[test]
    fn the_srgb_table_follows_the_curve() {
        for i in 0..=100_000 {
            let v = i as f32 / 100_000.0;
            let err = (srgb_encode_table(v) - srgb_encode(v)).abs();
            assert!(err < 2e-5, "at {v}: {err}");
        }
        assert_eq!(srgb_encode_table(7.0), srgb_encode(1.0));
        assert_eq!(srgb_encode_table(-1.0), 0.0);
    }

    #[test]
    fn srgb_decoding_inverts_the_encoding() {
        for v in [0.0, 0.001, 0.003, 0.2, 0.5, 1.0] {
            assert!((srgb_decode(srgb_encode(v)) - v).abs() < 1e-6, "{v}");
        }
    }
}
