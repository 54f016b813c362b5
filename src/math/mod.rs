//! Vectors, rays, robust ray offsets, and deterministic random numbers.
//!
//! `Vec3` and `Color` are glam's 16-byte aligned `Vec3A`: SIMD arithmetic, and the type
//! the BVH traversal (obvhs) takes without conversion.

pub mod rng;
pub mod sampling;

pub use rng::{Pattern, SampleStream, Uniform};

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

impl Ray {
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
pub fn offset_ray_origin(p: Vec3, n: Vec3) -> Vec3 {
    const ORIGIN: f32 = 1.0 / 32.0;
    const FLOAT_SCALE: f32 = 1.0 / 65536.0;
    const INT_SCALE: f32 = 256.0;
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

/// The largest component: the weight of a colour for pruning by attenuation.
pub fn max_component(c: Color) -> f32 {
    c.max_element()
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
