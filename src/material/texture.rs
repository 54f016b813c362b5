//! Textures: colours that vary over a surface.

use crate::math::Color;
use glam::Vec2;

/// A colour that may vary over a surface.
#[derive(Clone, Debug, PartialEq)]
pub enum Texture {
    /// One colour everywhere.
    Solid(Color),
    /// Squares of two colours, `scale` squares per unit of the surface coordinates
    /// (world units on planes; the whole surface is 0..1 on spheres, quads and meshes).
    Checker {
        /// Colour of the squares where floor(u s) + floor(v s) is even.
        even: Color,
        /// Colour of the others.
        odd: Color,
        /// Squares per unit.
        scale: f32,
    },
}

impl Texture {
    /// The colour at surface coordinates `uv`.
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Color {
        match self {
            Texture::Solid(c) => *c,
            Texture::Checker { even, odd, scale } => {
                let k = (uv.x * scale).floor() as i64 + (uv.y * scale).floor() as i64;
                if k.rem_euclid(2) == 0 { *even } else { *odd }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checker_alternates_in_both_directions() {
        let t = Texture::Checker {
            even: Color::ONE,
            odd: Color::ZERO,
            scale: 2.0,
        };
        assert_eq!(t.eval(Vec2::new(0.1, 0.1)), Color::ONE);
        assert_eq!(t.eval(Vec2::new(0.6, 0.1)), Color::ZERO);
        assert_eq!(t.eval(Vec2::new(0.6, 0.6)), Color::ONE);
        // Across zero the pattern continues instead of mirroring.
        assert_eq!(t.eval(Vec2::new(-0.1, 0.1)), Color::ZERO);
    }
}
