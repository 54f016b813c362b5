//! Image textures: a picture mapped over a surface by its (u, v), as glTF maps its
//! base-colour and emissive textures.

use crate::math::Color;
use glam::Vec2;
use std::sync::{Arc, LazyLock};

/// The texels of an 8-bit sRGB picture (glTF's colour textures are sRGB-encoded), shared
/// by every material that maps it.
#[derive(Clone, PartialEq)]
pub struct Texels {
    width: u32,
    height: u32,
    // Row by row from the top, three bytes per texel.
    rgb: Vec<u8>,
}

impl Texels {
    /// A picture of `width` × `height` texels, row by row from the top, three sRGB bytes
    /// each; `None` if `rgb` is not that long or the picture is empty.
    pub fn new(width: u32, height: u32, rgb: Vec<u8>) -> Option<Texels> {
        let texels = width as usize * height as usize;
        (texels > 0 && rgb.len() == 3 * texels).then_some(Texels { width, height, rgb })
    }

    /// The texel at column `x`, row `y` (both within the picture), in linear RGB by `lut`.
    #[inline]
    fn linear(&self, lut: &[f32; 256], x: usize, y: usize) -> Color {
        let i = 3 * (y * self.width as usize + x);
        Color::new(
            lut[self.rgb[i] as usize],
            lut[self.rgb[i + 1] as usize],
            lut[self.rgb[i + 2] as usize],
        )
    }
}

impl std::fmt::Debug for Texels {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Texels({} × {})", self.width, self.height)
    }
}

/// The sRGB transfer function undone for each byte (`srgb_decode` of byte/255).
static SRGB_TO_LINEAR: LazyLock<[f32; 256]> =
    LazyLock::new(|| std::array::from_fn(|b| crate::math::srgb_decode(b as f32 / 255.0)));

/// What a texture does beyond its edges along one direction (glTF's sampler wrap modes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Wrap {
    /// The picture tiles the plane.
    #[default]
    Repeat,
    /// The edge texels stretch on.
    Clamp,
    /// The picture tiles, every other copy mirrored.
    Mirror,
}

impl Wrap {
    /// Texel index `i` of a row or column of `n` brought within 0..n.
    #[inline]
    fn index(self, i: i64, n: usize) -> usize {
        let n = n as i64;
        let k = match self {
            Wrap::Repeat => i.rem_euclid(n),
            Wrap::Clamp => i.clamp(0, n - 1),
            Wrap::Mirror => {
                let m = i.rem_euclid(2 * n);
                if m < n { m } else { 2 * n - 1 - m }
            }
        };
        k as usize
    }
}

/// A picture mapped over a surface: (u, v) = (0, 0) is its top-left corner and (1, 1) its
/// bottom-right (glTF's convention), filtered bilinearly, each colour scaled by `factor`.
#[derive(Clone, Debug, PartialEq)]
pub struct ImageMap {
    /// The picture.
    pub texels: Arc<Texels>,
    /// What every texel's linear colour is multiplied by (glTF's `baseColorFactor`, or
    /// `emissiveFactor` times its strength).
    pub factor: Color,
    /// Beyond the picture's edges along u, and along v.
    pub wrap: [Wrap; 2],
}

impl ImageMap {
    /// The colour at surface coordinates `uv`: the four texels around it weighed by
    /// bilinear interpolation, texel centres at half-integers. Coordinates that are not
    /// finite read as 0.
    #[inline(never)]
    pub fn eval(&self, uv: Vec2) -> Color {
        let t = &*self.texels;
        let (w, h) = (t.width as usize, t.height as usize);
        let finite = |x: f32| if x.is_finite() { x } else { 0.0 };
        let x = finite(uv.x) * w as f32 - 0.5;
        let y = finite(uv.y) * h as f32 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let [wrap_u, wrap_v] = self.wrap;
        let (xa, xb) = (wrap_u.index(x0, w), wrap_u.index(x0.saturating_add(1), w));
        let (ya, yb) = (wrap_v.index(y0, h), wrap_v.index(y0.saturating_add(1), h));
        let lut = &*SRGB_TO_LINEAR;
        let top = t.linear(lut, xa, ya) * (1.0 - fx) + t.linear(lut, xb, ya) * fx;
        let bottom = t.linear(lut, xa, yb) * (1.0 - fx) + t.linear(lut, xb, yb) * fx;
        (top * (1.0 - fy) + bottom * fy) * self.factor
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 2 × 2: black, white / red, a mid sRGB grey (128).
    fn picture() -> Arc<Texels> {
        let rgb = vec![0, 0, 0, 255, 255, 255, 255, 0, 0, 128, 128, 128];
        Arc::new(Texels::new(2, 2, rgb).expect("2 × 2"))
    }

    fn map(wrap: Wrap) -> ImageMap {
        ImageMap {
            texels: picture(),
            factor: Color::ONE,
            wrap: [wrap; 2],
        }
    }

    #[test]
    fn texel_centres_give_their_own_linear_colour_and_between_them_the_mean() {
        let m = map(Wrap::Repeat);
        assert_eq!(m.eval(Vec2::new(0.25, 0.25)), Color::ZERO);
        assert_eq!(m.eval(Vec2::new(0.75, 0.25)), Color::ONE);
        assert_eq!(m.eval(Vec2::new(0.25, 0.75)), Color::new(1.0, 0.0, 0.0));
        // sRGB 128 is linear 0.2158605 (the sRGB curve, by hand).
        let grey = m.eval(Vec2::new(0.75, 0.75)).x;
        assert!((grey - 0.215_860_5).abs() < 1e-6, "{grey}");
        // Halfway between black and white along the top row.
        let mid = m.eval(Vec2::new(0.5, 0.25));
        assert!(
            (mid - Color::splat(0.5)).abs().max_element() < 1e-6,
            "{mid}"
        );
        // The factor scales everything.
        let tinted = ImageMap {
            factor: Color::new(0.5, 0.25, 2.0),
            ..map(Wrap::Repeat)
        };
        assert_eq!(
            tinted.eval(Vec2::new(0.75, 0.25)),
            Color::new(0.5, 0.25, 2.0)
        );
    }

    #[test]
    fn each_wrap_mode_continues_the_picture_as_gltf_says() {
        // Just past the right edge, on the top row's centre line.
        let past = Vec2::new(1.25, 0.25);
        // Repeat: the first column again (black). Clamp: the last column (white).
        // Mirror: the last column, mirrored back (white).
        assert_eq!(map(Wrap::Repeat).eval(past), Color::ZERO);
        assert_eq!(map(Wrap::Clamp).eval(past), Color::ONE);
        assert_eq!(map(Wrap::Mirror).eval(past), Color::ONE);
        // Two pictures to the left, repeat and mirror are where they started.
        let far = Vec2::new(-1.75, 0.25);
        assert_eq!(map(Wrap::Repeat).eval(far), Color::ZERO);
        assert_eq!(map(Wrap::Mirror).eval(far), Color::ZERO);
        assert_eq!(map(Wrap::Clamp).eval(far), Color::ZERO);
    }

    #[test]
    fn coordinates_out_of_every_range_give_a_colour_of_the_picture() {
        for wrap in [Wrap::Repeat, Wrap::Clamp, Wrap::Mirror] {
            for u in [f32::NAN, f32::INFINITY, -1e30, 1e30, -0.0, 3e9] {
                let c = map(wrap).eval(Vec2::new(u, u));
                assert!(
                    c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= 1.0,
                    "{wrap:?} at {u}: {c}"
                );
            }
        }
        assert!(Texels::new(2, 2, vec![0; 11]).is_none());
        assert!(Texels::new(0, 5, Vec::new()).is_none());
    }
}
