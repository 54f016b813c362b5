//! Textures: colours that vary over a surface.

use super::image::ImageMap;
use crate::math::Color;
use crate::math::lanes::Lanes;
use glam::Vec2;

/// A colour that may vary over a surface.
#[derive(Clone, Debug, PartialEq)]
pub enum Texture {
    /// One colour everywhere.
    Solid(Color),
    /// Cells of two colours, `scale.x` per unit of u and `scale.y` per unit of v (world
    /// units on planes; the whole surface is 0..1 on spheres, quads and meshes, so a
    /// 16 × 9 quad has square cells at a scale of 16 × 9 times any factor).
    Checker {
        /// Colour of the cells where floor(u s_u) + floor(v s_v) is even.
        even: Color,
        /// Colour of the others.
        odd: Color,
        /// Cells per unit along u and along v.
        scale: Vec2,
    },
    /// A picture (a glTF model's base-colour or emissive texture).
    Image(ImageMap),
}

impl Texture {
    /// The colour at surface coordinates `uv`.
    // Always inlined: it runs at every shaded hit, where a call costs more than the checker
    // (docs/performance.md, "Shaped by measurement"); a picture's lookup stays a call.
    #[inline(always)]
    pub fn eval(&self, uv: Vec2) -> Color {
        match self {
            Texture::Solid(c) => *c,
            Texture::Checker { even, odd, scale } => [*even, *odd][cell_parity(uv, *scale)],
            Texture::Image(image) => image.eval(uv),
        }
    }

    /// [`Texture::eval`] at `N` points at once, given coordinate by coordinate: one
    /// loop over the lanes, which the compiler makes vector instructions.
    #[inline(always)]
    pub(crate) fn eval_lanes<const N: usize>(&self, u: Lanes<N>, v: Lanes<N>) -> [Color; N] {
        match self {
            Texture::Solid(c) => [*c; N],
            Texture::Checker { even, odd, scale } => {
                let x: [f32; N] = std::array::from_fn(|i| u.0[i] * scale.x);
                let y: [f32; N] = std::array::from_fn(|i| v.0[i] * scale.y);
                // Where every cell index fits 32 bits (as on any surface seen), the floors
                // in 32-bit lanes, which every vector unit converts; floor_i64 elsewhere.
                let small = |a: &[f32; N]| a.iter().fold(true, |all, x| all & (x.abs() < SMALL));
                let parity: [usize; N] = if small(&x) & small(&y) {
                    std::array::from_fn(|i| {
                        (floor_i32(x[i]).wrapping_add(floor_i32(y[i])) & 1) as usize
                    })
                } else {
                    std::array::from_fn(|i| cell_parity(Vec2::new(u.0[i], v.0[i]), *scale))
                };
                parity.map(|k| [*even, *odd][k])
            }
            // Four texel reads at each point: gathers, which vector units do not speed up.
            Texture::Image(image) => std::array::from_fn(|i| image.eval(Vec2::new(u.0[i], v.0[i]))),
        }
    }
}

/// 0 for the checker's cells where floor(u s_u) + floor(v s_v) is even, 1 for the others:
/// the colour is picked by this index, not by a branch, which on a checker seen at random
/// is mispredicted half the time.
#[inline(always)]
fn cell_parity(uv: Vec2, scale: Vec2) -> usize {
    let k = floor_i64(uv.x * scale.x) + floor_i64(uv.y * scale.y);
    (k & 1) as usize
}

/// Below this magnitude `floor_i32` is `floor_i64`: its cell index fits 32 bits.
const SMALL: f32 = (1u32 << 30) as f32;

/// `floor_i64(x)` for |x| < [`SMALL`], in 32 bits: truncation, one less for a negative
/// non-integer. (The parity of a sum wrapped to 32 bits is the parity of the sum.)
#[inline(always)]
fn floor_i32(x: f32) -> i32 {
    let i = x as i32;
    i - ((i as f32) > x) as i32
}

/// `x.floor() as i64`, without the library call `floor` is on processors without a
/// rounding instruction (x86-64 before SSE4.1), for every f32 including infinities and
/// NaN: truncation, one less for a negative non-integer.
#[inline]
fn floor_i64(x: f32) -> i64 {
    let i = x as i64;
    i.saturating_sub(((i as f32) > x) as i64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checker_alternates_in_both_directions() {
        let t = Texture::Checker {
            even: Color::ONE,
            odd: Color::ZERO,
            scale: Vec2::splat(2.0),
        };
        assert_eq!(t.eval(Vec2::new(0.1, 0.1)), Color::ONE);
        assert_eq!(t.eval(Vec2::new(0.6, 0.1)), Color::ZERO);
        assert_eq!(t.eval(Vec2::new(0.6, 0.6)), Color::ONE);
        // Across zero the pattern continues instead of mirroring.
        assert_eq!(t.eval(Vec2::new(-0.1, 0.1)), Color::ZERO);
    }

    #[test]
    fn a_checker_evaluated_in_lanes_is_each_points_own() {
        let t = Texture::Checker {
            even: Color::new(1.0, 0.5, 0.25),
            odd: Color::new(0.1, 0.2, 0.3),
            scale: Vec2::new(16.0, 12.0),
        };
        let u = [0.01, 0.99, -0.3, 1e30, f32::NAN, -0.0, 0.5, 0.0625];
        let v = [0.5, -0.02, 0.33, 0.1, 0.2, f32::NEG_INFINITY, 0.5, 0.0];
        let lanes = t.eval_lanes(Lanes(u), Lanes(v));
        for i in 0..8 {
            assert_eq!(lanes[i], t.eval(Vec2::new(u[i], v[i])), "point {i}");
        }
        // Ordinary coordinates, all lanes below the 32-bit bound: cell edges, negative
        // cells, and cell indices near the 32-bit bound (6e7 × 16 is close to 2^30).
        let edge = [
            0.0625,
            -0.0625,
            1.0 / 12.0,
            -0.5,
            0.999_999_9,
            -1.0e-8,
            6.0e7,
            -6.0e7,
        ];
        let spread = (0..4096u32).map(|k| (k as f32 * 0.618_034).fract() * 4.0 - 2.0);
        let ordinary: Vec<f32> = edge.into_iter().chain(spread).collect();
        for (a, b) in ordinary
            .chunks_exact(8)
            .zip(ordinary.chunks_exact(8).skip(1))
        {
            let (u, v): ([f32; 8], [f32; 8]) = (a.try_into().unwrap(), b.try_into().unwrap());
            let lanes = t.eval_lanes(Lanes(u), Lanes(v));
            for i in 0..8 {
                assert_eq!(
                    lanes[i],
                    t.eval(Vec2::new(u[i], v[i])),
                    "({}, {})",
                    u[i],
                    v[i]
                );
            }
        }
        assert_eq!(
            Texture::Solid(Color::ONE).eval_lanes(Lanes(u), Lanes(v)),
            [Color::ONE; 8]
        );
    }

    #[test]
    fn a_checker_has_its_own_count_along_u_and_along_v() {
        // 4 cells along u, 2 along v: a cell is 0.25 wide and 0.5 tall.
        let t = Texture::Checker {
            even: Color::ONE,
            odd: Color::ZERO,
            scale: Vec2::new(4.0, 2.0),
        };
        let at = |u, v| t.eval(Vec2::new(u, v));
        assert_eq!(at(0.1, 0.1), Color::ONE);
        assert_eq!(at(0.3, 0.1), Color::ZERO, "the next cell along u");
        assert_eq!(at(0.1, 0.4), Color::ONE, "still the first cell along v");
        assert_eq!(at(0.1, 0.6), Color::ZERO, "the next cell along v");
        assert_eq!(at(0.3, 0.6), Color::ONE);
    }

    #[test]
    fn floor_i64_is_floor_for_every_kind_of_value() {
        let special = [
            0.0,
            -0.0,
            0.5,
            -0.5,
            -1.0,
            1.0 - f32::EPSILON,
            -8388607.5,
            16777217.0,
            -3.0e9,
            9.3e18,
            -9.3e18,
            1e30,
            -1e30,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
        ];
        let spread = (0..200_000u32).map(|k| f32::from_bits(k.wrapping_mul(0x9e37_79b9)));
        for x in special.into_iter().chain(spread) {
            assert_eq!(floor_i64(x), x.floor() as i64, "{x:e}");
            if x.abs() < SMALL {
                assert_eq!(floor_i32(x) as i64, floor_i64(x), "{x:e}");
            }
        }
        let bound = SMALL.next_down();
        assert_eq!(floor_i32(-bound) as i64, floor_i64(-bound));
    }
}
