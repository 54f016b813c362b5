//! Points and directions over a [`Real`]: glam's vectors for one ray, a row of lanes per
//! coordinate for many.

use super::{Lanes, Mask, Real};
use crate::math::Vec3;
use std::ops::{Add, Sub};

/// A point or direction over a [`Real`]: the operations the shared formulas use, each
/// coordinate computed as glam's `Vec3A` computes it (on SSE2, NEON and without either),
/// so that one vector per lane gives `Vec3A`'s results bit for bit.
pub trait Vector<R: Real>: Copy + Add<Output = Self> + Sub<Output = Self> {
    /// `v` in every lane.
    fn splat(v: Vec3) -> Self;
    /// The vector `wide` holds in every lane (lane 0's for one ray): a constant loaded
    /// row by row (see [`Wide`]).
    fn wide(wide: &Wide) -> Self;
    /// The dot product, (x x′ + y y′) + z z′.
    fn dot(self, o: Self) -> R;
    /// The cross product, (y z′ − z y′, z x′ − x z′, x y′ − y x′).
    fn cross(self, o: Self) -> Self;
    /// Each coordinate times `s`.
    fn scale(self, s: R) -> Self;
    /// Each coordinate divided by `s`.
    fn div(self, s: R) -> Self;
    /// |self|².
    #[inline(always)]
    fn length_squared(self) -> R {
        self.dot(self)
    }
    /// The unit vector along `self`: each coordinate divided by |self| where glam divides
    /// (SSE2), times 1 / |self| where it multiplies by the reciprocal (NEON, no SIMD).
    fn normalize(self) -> Self;
    /// −self.
    fn neg(self) -> Self;
    /// `a` where `m` holds, `b` elsewhere.
    fn select(m: R::Mask, a: Self, b: Self) -> Self;
    /// The coordinates (x, y, z).
    fn coords(self) -> [R; 3];
}

/// One ray's vectors are glam's, in SIMD registers as everywhere else in the tracer.
impl Vector<f32> for Vec3 {
    #[inline(always)]
    fn splat(v: Vec3) -> Vec3 {
        v
    }
    #[inline(always)]
    fn wide(wide: &Wide) -> Vec3 {
        wide.get(0)
    }
    #[inline(always)]
    fn dot(self, o: Vec3) -> f32 {
        Vec3::dot(self, o)
    }
    #[inline(always)]
    fn cross(self, o: Vec3) -> Vec3 {
        Vec3::cross(self, o)
    }
    #[inline(always)]
    fn scale(self, s: f32) -> Vec3 {
        s * self
    }
    #[inline(always)]
    fn div(self, s: f32) -> Vec3 {
        self / s
    }
    #[inline(always)]
    fn normalize(self) -> Vec3 {
        Vec3::normalize(self)
    }
    #[inline(always)]
    fn neg(self) -> Vec3 {
        -self
    }
    #[inline(always)]
    fn select(m: bool, a: Vec3, b: Vec3) -> Vec3 {
        if m { a } else { b }
    }
    #[inline(always)]
    fn coords(self) -> [f32; 3] {
        self.to_array()
    }
}

/// A constant vector in each of the widest width's 16 lanes, stored for the lanes to load
/// as whole rows: what the directly tested shapes keep their corners, normals and edges in.
/// Broadcast from a `Vec3` in its register, a constant lets the compiler's vectoriser pair
/// its coordinates across lanes and shuffle them back together: a quad's test took about
/// 200 instructions for 16 rays where about 110 do (docs/performance.md, "Shaped by
/// measurement").
pub type Wide = V3<Lanes<16>>;

/// A point or direction per lane: each coordinate a row of lanes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct V3<R> {
    /// x.
    pub x: R,
    /// y.
    pub y: R,
    /// z.
    pub z: R,
}

impl<const N: usize> V3<Lanes<N>> {
    /// Lane i is `f(i)`.
    #[inline(always)]
    pub fn from_fn(f: impl Fn(usize) -> Vec3) -> Self {
        V3 {
            x: Lanes::from_fn(|i| f(i).x),
            y: Lanes::from_fn(|i| f(i).y),
            z: Lanes::from_fn(|i| f(i).z),
        }
    }

    /// Lane `i`'s vector.
    #[inline(always)]
    pub fn get(&self, i: usize) -> Vec3 {
        Vec3::new(self.x.0[i], self.y.0[i], self.z.0[i])
    }
}

impl<const N: usize> Vector<Lanes<N>> for V3<Lanes<N>> {
    #[inline(always)]
    fn splat(v: Vec3) -> Self {
        V3 {
            x: Lanes::splat(v.x),
            y: Lanes::splat(v.y),
            z: Lanes::splat(v.z),
        }
    }
    #[inline(always)]
    fn wide(wide: &Wide) -> Self {
        let first = |row: &Lanes<16>| Lanes::from_fn(|i| row.0[i]);
        V3 {
            x: first(&wide.x),
            y: first(&wide.y),
            z: first(&wide.z),
        }
    }
    #[inline(always)]
    fn dot(self, o: Self) -> Lanes<N> {
        (self.x * o.x + self.y * o.y) + self.z * o.z
    }
    #[inline(always)]
    fn cross(self, o: Self) -> Self {
        V3 {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }
    #[inline(always)]
    fn scale(self, s: Lanes<N>) -> Self {
        V3 {
            x: s * self.x,
            y: s * self.y,
            z: s * self.z,
        }
    }
    #[inline(always)]
    fn div(self, s: Lanes<N>) -> Self {
        V3 {
            x: self.x / s,
            y: self.y / s,
            z: self.z / s,
        }
    }
    #[inline(always)]
    fn normalize(self) -> Self {
        let length = self.length_squared().sqrt();
        if cfg!(target_feature = "sse2") {
            V3 {
                x: self.x / length,
                y: self.y / length,
                z: self.z / length,
            }
        } else {
            self.scale(Lanes::splat(1.0) / length)
        }
    }
    #[inline(always)]
    fn neg(self) -> Self {
        V3 {
            x: -self.x,
            y: -self.y,
            z: -self.z,
        }
    }
    #[inline(always)]
    fn select(m: Mask<N>, a: Self, b: Self) -> Self {
        V3 {
            x: Lanes::select(m, a.x, b.x),
            y: Lanes::select(m, a.y, b.y),
            z: Lanes::select(m, a.z, b.z),
        }
    }
    #[inline(always)]
    fn coords(self) -> [Lanes<N>; 3] {
        [self.x, self.y, self.z]
    }
}

impl<R: Real> Add for V3<R> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        V3 {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }
}

impl<R: Real> Sub for V3<R> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        V3 {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vectors_in_lanes_are_glams_bit_for_bit() {
        let vs = [
            Vec3::new(0.3, -1.7, 2.5e-3),
            Vec3::new(1e20, 3.0, -0.0),
            Vec3::new(-7.0, 0.1, 0.2),
            Vec3::new(f32::MIN_POSITIVE, 1.0, 1e-30),
        ];
        let lanes = |f: &dyn Fn(Vec3) -> f32| Lanes::<4>(std::array::from_fn(|i| f(vs[i])));
        let of = |v: Vec3| V3 {
            x: Lanes::splat(v.x),
            y: Lanes::splat(v.y),
            z: Lanes::splat(v.z),
        };
        let a = V3 {
            x: lanes(&|v| v.x),
            y: lanes(&|v| v.y),
            z: lanes(&|v| v.z),
        };
        let b = Vec3::new(0.7, 1.3, -2.9);
        let bits = |x: f32| x.to_bits();
        for (i, v) in vs.iter().enumerate() {
            assert_eq!(bits(a.dot(of(b)).0[i]), bits(v.dot(b)));
            assert_eq!(bits(a.length_squared().0[i]), bits(v.length_squared()));
            let c = a.cross(of(b));
            let g = v.cross(b);
            assert_eq!(
                [c.x.0[i], c.y.0[i], c.z.0[i]].map(bits),
                g.to_array().map(bits)
            );
            let n = a.normalize();
            assert_eq!(
                n.get(i).to_array().map(bits),
                v.normalize().to_array().map(bits)
            );
            let s = a.scale(Lanes::splat(1.5));
            let g = *v * 1.5;
            assert_eq!(
                [s.x.0[i], s.y.0[i], s.z.0[i]].map(bits),
                g.to_array().map(bits)
            );
            let q = a.div(Lanes::splat(0.7));
            assert_eq!(
                q.get(i).to_array().map(bits),
                (*v / 0.7).to_array().map(bits)
            );
            assert_eq!(a.coords().map(|c| bits(c.0[i])), v.to_array().map(bits));
        }
    }
}
