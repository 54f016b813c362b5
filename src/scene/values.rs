//! The checked values of the scene format: numbers, vectors and colours that deserialize
//! only when finite and in range, so that serde's error carries the offending value's span.

use crate::geometry::{MAX_COORDINATE, within_limits};
use crate::math::{Color, Vec3};
use crate::params::{ABBE_RANGE, IOR_RANGE, ROUGHNESS_RANGE};
use serde::Deserialize;

/// A finite number.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(try_from = "f64")]
pub(super) struct Num(pub(super) f32);

impl TryFrom<f64> for Num {
    type Error = String;
    fn try_from(v: f64) -> Result<Self, String> {
        let f = v as f32;
        if f.is_finite() {
            Ok(Num(f))
        } else {
            Err(format!("{} is not a finite number", Shown(v)))
        }
    }
}

/// A number as an error message shows it: plainly, or in exponent form when very large
/// or small (`1e20`, not twenty-one digits).
struct Shown(f64);

impl std::fmt::Display for Shown {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let a = self.0.abs();
        if a == 0.0 || (1e-4..1e7).contains(&a) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

/// Declares a number type that deserializes only from a finite value meeting `$ok`,
/// else fails with `$message`: `|v, f|` names the value read and its f32.
macro_rules! checked_number {
    ($(#[$doc:meta])* $name:ident, |$v:ident, $f:ident| $ok:expr, $($message:tt)+) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, Deserialize)]
        #[serde(try_from = "f64")]
        pub(super) struct $name(pub(super) f32);

        impl TryFrom<f64> for $name {
            type Error = String;
            fn try_from($v: f64) -> Result<Self, String> {
                let Num($f) = Num::try_from($v)?;
                if $ok {
                    Ok($name($f))
                } else {
                    let $v = Shown($v);
                    Err(format!($($message)+))
                }
            }
        }
    };
}

checked_number!(
    /// A finite number > 0.
    Positive, |v, f| f > 0.0, "must be greater than 0, got {v}"
);
checked_number!(
    /// A finite number ≥ 0.
    NonNegative, |v, f| f >= 0.0, "must not be negative, got {v}"
);
checked_number!(
    /// An index of refraction, 1 to 3.
    Ior, |v, f| (IOR_RANGE.0..=IOR_RANGE.1).contains(&f),
    "an index of refraction must be between {} and {}, got {v}", IOR_RANGE.0, IOR_RANGE.1
);
checked_number!(
    /// An Abbe number, 0 (no dispersion) to 100.
    Abbe, |v, f| (ABBE_RANGE.0..=ABBE_RANGE.1).contains(&f),
    "an Abbe number must be between {} (no dispersion) and {}, got {v}", ABBE_RANGE.0, ABBE_RANGE.1
);
checked_number!(
    /// A GGX roughness α, 0 (smooth) to 1.
    Roughness, |v, f| (ROUGHNESS_RANGE.0..=ROUGHNESS_RANGE.1).contains(&f),
    "a roughness must be between {} (smooth) and {}, got {v}", ROUGHNESS_RANGE.0, ROUGHNESS_RANGE.1
);
checked_number!(
    /// A Phong exponent, 1 to 100,000.
    Exponent, |v, f| (1.0..=crate::params::MAX_PHONG_EXPONENT).contains(&f),
    "a Phong exponent must be between 1 and {}, got {v}", crate::params::MAX_PHONG_EXPONENT
);
checked_number!(
    /// A fraction, 0 to 1.
    Unit, |v, f| (0.0..=1.0).contains(&f), "must be between 0 and 1, got {v}"
);

checked_number!(
    /// A length: a finite number > 0, at most the largest coordinate.
    Length, |v, f| f > 0.0 && f <= MAX_COORDINATE,
    "must be greater than 0 and at most {MAX_COORDINATE:e}, got {v}"
);

/// A vector of three finite numbers, each within ±[`MAX_COORDINATE`] (points, edges,
/// velocities, colours).
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(try_from = "[f64; 3]")]
pub(super) struct V3(pub(super) Vec3);

impl TryFrom<[f64; 3]> for V3 {
    type Error = String;
    fn try_from(v: [f64; 3]) -> Result<Self, String> {
        let f = Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32);
        if !f.is_finite() {
            Err(format!("{v:?} has a non-finite component"))
        } else if !within_limits(f) {
            Err(format!(
                "{v:?} is beyond ±{MAX_COORDINATE:e}, the largest coordinate raylab handles"
            ))
        } else {
            Ok(V3(f))
        }
    }
}

/// A non-zero direction.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(try_from = "[f64; 3]")]
pub(super) struct Dir(pub(super) Vec3);

impl TryFrom<[f64; 3]> for Dir {
    type Error = String;
    fn try_from(v: [f64; 3]) -> Result<Self, String> {
        let V3(f) = V3::try_from(v)?;
        if f.length_squared() > 0.0 {
            Ok(Dir(f.normalize()))
        } else {
            Err("a direction must not be [0, 0, 0]".into())
        }
    }
}

/// A colour of radiance or intensity: three finite numbers ≥ 0.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(try_from = "[f64; 3]")]
pub(super) struct Rgb(pub(super) Color);

impl TryFrom<[f64; 3]> for Rgb {
    type Error = String;
    fn try_from(v: [f64; 3]) -> Result<Self, String> {
        let V3(f) = V3::try_from(v)?;
        if f.min_element() >= 0.0 {
            Ok(Rgb(f))
        } else {
            Err(format!("colour {v:?} has a negative component"))
        }
    }
}

/// A reflectance: three numbers in [0, 1] (more would create energy).
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(try_from = "[f64; 3]")]
pub(super) struct Reflectance(pub(super) Color);

impl TryFrom<[f64; 3]> for Reflectance {
    type Error = String;
    fn try_from(v: [f64; 3]) -> Result<Self, String> {
        let Rgb(f) = Rgb::try_from(v)?;
        if f.max_element() <= 1.0 {
            Ok(Reflectance(f))
        } else {
            Err(format!("reflectance {v:?} must be between 0 and 1"))
        }
    }
}

/// The longest image side accepted, in pixels.
pub const MAX_IMAGE_SIDE: u32 = 16384;

/// The most pixels an image may have (4096 × 4096): the film keeps 64 bytes a pixel
/// ([`crate::render::Accum`]: f64 sums, for refinement that stays exact over millions of
/// samples), so this caps it at 1 GiB.
pub const MAX_PIXELS: u64 = 1 << 24;

/// Checks an image size against [`MAX_IMAGE_SIDE`] and [`MAX_PIXELS`], before anything is
/// allocated.
pub fn check_size(width: u32, height: u32) -> Result<(), String> {
    for (name, side) in [("width", width), ("height", height)] {
        if !(1..=MAX_IMAGE_SIDE).contains(&side) {
            return Err(format!(
                "the {name} must be between 1 and {MAX_IMAGE_SIDE} pixels, got {side}"
            ));
        }
    }
    let pixels = width as u64 * height as u64;
    if pixels > MAX_PIXELS {
        return Err(format!(
            "{width}x{height} is {pixels} pixels, more than the {MAX_PIXELS} (4096x4096) the film holds in 1 GiB"
        ));
    }
    Ok(())
}

/// An image dimension in pixels.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(try_from = "i64")]
pub(super) struct Pixels(pub(super) u32);

impl TryFrom<i64> for Pixels {
    type Error = String;
    fn try_from(v: i64) -> Result<Self, String> {
        if (1..=MAX_IMAGE_SIDE as i64).contains(&v) {
            Ok(Pixels(v as u32))
        } else {
            Err(format!(
                "must be between 1 and {MAX_IMAGE_SIDE} pixels, got {v}"
            ))
        }
    }
}

/// A checker's cells per unit: one number for both directions, or [along u, along v], each
/// finite and > 0.
#[derive(Clone, Copy, Debug)]
pub(super) struct CheckerScale(pub(super) glam::Vec2);

impl<'de> Deserialize<'de> for CheckerScale {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = CheckerScale;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("cells per unit: a number, or [along u, along v]")
            }
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<CheckerScale, E> {
                let Positive(s) = Positive::try_from(v).map_err(E::custom)?;
                Ok(CheckerScale(glam::Vec2::splat(s)))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<CheckerScale, E> {
                self.visit_f64(v as f64)
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<CheckerScale, E> {
                self.visit_f64(v as f64)
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<CheckerScale, A::Error> {
                use serde::de::Error;
                let two = "[along u, along v]: two numbers";
                let u: Positive = seq.next_element()?.ok_or_else(|| A::Error::custom(two))?;
                let v: Positive = seq.next_element()?.ok_or_else(|| A::Error::custom(two))?;
                if seq.next_element::<serde::de::IgnoredAny>()?.is_some() {
                    return Err(A::Error::custom(two));
                }
                Ok(CheckerScale(glam::Vec2::new(u.0, v.0)))
            }
        }
        d.deserialize_any(Visitor)
    }
}
