//! Vectors, rays, robust ray offsets, and deterministic random numbers.
//!
//! `Vec3` and `Color` are glam's 16-byte aligned `Vec3A`: SIMD arithmetic, and the type
//! obvhs's boxes (which the BVH is built from) are made of.

pub mod lanes;
pub mod rng;
pub mod sampling;
pub mod srgb;

pub use rng::{Pattern, SampleStream, Uniform};
pub use srgb::{srgb_decode, srgb_encode, srgb8};

/// A point or direction in world space.
pub type Vec3 = glam::Vec3A;
/// Linear RGB radiance or reflectance.
pub type Color = glam::Vec3A;

/// A ray `origin + t * dir` at one instant `time` (the motion-blur time of its camera sample).
///
/// `dir` is kept normalized: the intersection routines and `t` as a distance rely on it.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Ray {
    /// Where the ray starts.
    pub origin: Vec3,
    /// Unit direction.
    pub dir: Vec3,
    /// The time of the sample, in the shutter interval.
    pub time: f32,
}

impl From<lanes::RayOf<f32>> for Ray {
    fn from(r: lanes::RayOf<f32>) -> Ray {
        Ray {
            origin: r.origin,
            dir: r.dir,
            time: r.time,
        }
    }
}

impl Ray {
    /// The same ray, as the formulas written for one ray or lanes take it.
    #[inline(always)]
    pub fn of(&self) -> lanes::RayOf<f32> {
        lanes::RayOf {
            origin: self.origin,
            dir: self.dir,
            time: self.time,
        }
    }

    /// A ray from `origin` along `dir` (normalized here) at `time`.
    pub fn new(origin: Vec3, dir: Vec3, time: f32) -> Self {
        Ray {
            origin,
            dir: dir.normalize(),
            time,
        }
    }

    /// The point at distance `t` along the ray.
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + t * self.dir
    }
}

/// Moves a surface point `p` off the surface along `n`, far enough that a ray starting
/// there cannot hit the same surface again (no acne), and no further (no leaking through
/// thin or touching geometry).
///
/// `n` is the geometric normal flipped to the side the new ray leaves towards. The offset
/// is a fixed number of units in the last place of each coordinate, so it scales with the
/// floating-point error of `p` wherever the scene sits ("A Fast and Robust Method for
/// Avoiding Self-Intersection", Wächter and Binder, Ray Tracing Gems ch. 6). Near the
/// origin, where ulps are tiny, a small absolute offset takes over.
#[inline]
pub fn offset_ray_origin(p: Vec3, n: Vec3) -> Vec3 {
    // x86-64: the three coordinates at once in SSE2 (every x86-64 has it), the same bits
    // as the scalar form: it runs for every child and shadow ray, and the scalar form's
    // branches and saturating casts were 4 % of a render's instructions (callgrind).
    #[cfg(target_arch = "x86_64")]
    #[allow(unsafe_code)]
    // SAFETY: the one requirement of `offset_sse2` is SSE2, which every x86-64 processor
    // has (it is the target's baseline).
    return unsafe { offset_sse2(p, n) };
    #[cfg(not(target_arch = "x86_64"))]
    return offset_scalar(p, n);
}

/// Below |p| = ORIGIN the offset is FLOAT_SCALE·n; above, INT_SCALE·n units in the last
/// place of p.
const ORIGIN: f32 = 1.0 / 32.0;
const FLOAT_SCALE: f32 = 1.0 / 65536.0;
const INT_SCALE: f32 = 256.0;

/// [`offset_ray_origin`] one coordinate at a time: the definition.
#[cfg_attr(target_arch = "x86_64", allow(dead_code))]
fn offset_scalar(p: Vec3, n: Vec3) -> Vec3 {
    let nudge = |p: f32, n: f32| -> f32 {
        if p.abs() < ORIGIN {
            p + FLOAT_SCALE * n
        } else {
            let of_i = (INT_SCALE * n) as i32;
            let bits = p.to_bits() as i32;
            // Moving the bit pattern away from zero grows |p|; towards zero shrinks it.
            f32::from_bits(bits.wrapping_add(if p < 0.0 { -of_i } else { of_i }) as u32)
        }
    };
    Vec3::new(nudge(p.x, n.x), nudge(p.y, n.y), nudge(p.z, n.z))
}

/// [`offset_scalar`] in the four lanes of an SSE2 register, without branches: both
/// offsets computed, the one that applies selected per lane. Equal bit for bit for any
/// `p` and any `n` with |INT_SCALE·n| < 2³¹ (a unit normal): the scalar cast saturates
/// beyond that, the SSE2 one does not. A NaN in n gives no integer offset in either.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "sse2")]
#[inline]
fn offset_sse2(p: Vec3, n: Vec3) -> Vec3 {
    use std::arch::x86_64::*;
    let (p, n) = (__m128::from(p), __m128::from(n));
    let zero = _mm_setzero_ps();
    // p + FLOAT_SCALE·n, near the origin.
    let near = _mm_add_ps(p, _mm_mul_ps(_mm_set1_ps(FLOAT_SCALE), n));
    // INT_SCALE·n as integers, 0 where n is NaN (as Rust's cast gives).
    let ordered = _mm_castps_si128(_mm_cmpord_ps(n, n));
    let of_i = _mm_and_si128(
        _mm_cvttps_epi32(_mm_mul_ps(_mm_set1_ps(INT_SCALE), n)),
        ordered,
    );
    // Negated where p < 0: (x ^ m) - m with m all ones is -x, with m zero is x.
    let negative = _mm_castps_si128(_mm_cmplt_ps(p, zero));
    let of_i = _mm_sub_epi32(_mm_xor_si128(of_i, negative), negative);
    let far = _mm_castsi128_ps(_mm_add_epi32(_mm_castps_si128(p), of_i));
    // |p| < ORIGIN picks `near` (false for NaN, as in the scalar form).
    let abs = _mm_andnot_ps(_mm_set1_ps(-0.0), p);
    let small = _mm_cmplt_ps(abs, _mm_set1_ps(ORIGIN));
    Vec3::from(_mm_or_ps(
        _mm_and_ps(small, near),
        _mm_andnot_ps(small, far),
    ))
}

/// An orthonormal basis `(t, b)` completing the unit vector `n` (Duff et al. 2017, branchless).
pub fn orthonormal_basis(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offset_moves_to_the_requested_side_at_any_scale() {
        for scale in [1e-3f32, 0.5, 1.0, 37.0, 1e4] {
            let p = Vec3::new(scale, -scale, 0.25 * scale);
            let n = Vec3::new(0.3, 0.8, -0.52).normalize();
            let q = offset_ray_origin(p, n);
            let d = (q - p).dot(n);
            assert!(d > 0.0, "offset must leave along n at scale {scale}");
            // Far smaller than any feature of a scene at that scale.
            assert!(
                (q - p).length() < 1e-3 * scale.max(1.0),
                "offset too large at {scale}"
            );
        }
    }

    #[test]
    #[cfg(target_arch = "x86_64")]
    fn offset_in_sse2_is_the_scalar_offset_bit_for_bit() {
        // Unit normals and points spread over every exponent and sign, with the special
        // values: zeros of both signs, the ORIGIN threshold, subnormals, infinities, NaN.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state = crate::math::rng::mix64(state);
            state
        };
        let specials = [
            0.0,
            -0.0,
            ORIGIN,
            -ORIGIN,
            ORIGIN * (1.0 - f32::EPSILON),
            1e-40,
            -1e-40,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        let same =
            |a: Vec3, b: Vec3| a.to_array().map(f32::to_bits) == b.to_array().map(f32::to_bits);
        for i in 0..200_000u32 {
            let bits = next();
            let coordinate = |k: u32| {
                let b = (bits >> (k * 21)) as u32;
                if b.is_multiple_of(16) {
                    specials[(b >> 4) as usize % specials.len()]
                } else {
                    f32::from_bits(b.rotate_left(k * 7) ^ (i << 9))
                }
            };
            let p = Vec3::new(coordinate(0), coordinate(1), coordinate(2));
            let m = next();
            let n = Vec3::new(
                (m as u16) as f32 - 32768.0,
                ((m >> 16) as u16) as f32 - 32768.0,
                ((m >> 32) as u16) as f32 - 32768.0,
            )
            .normalize_or(Vec3::Y);
            let n = if i.is_multiple_of(1000) { Vec3::NAN } else { n };
            // SAFETY: x86-64 has SSE2 (see offset_ray_origin).
            #[allow(unsafe_code)]
            let simd = unsafe { offset_sse2(p, n) };
            let scalar = offset_scalar(p, n);
            assert!(
                same(simd, scalar),
                "p = {p:?}, n = {n:?}: {simd:?} vs {scalar:?}"
            );
        }
    }

    #[test]
    fn basis_is_orthonormal() {
        for n in [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.2, -0.9, 0.1).normalize(),
        ] {
            let (t, b) = orthonormal_basis(n);
            assert!((t.length() - 1.0).abs() < 1e-5 && (b.length() - 1.0).abs() < 1e-5);
            assert!(t.dot(n).abs() < 1e-5 && b.dot(n).abs() < 1e-5 && t.dot(b).abs() < 1e-5);
        }
    }
}
