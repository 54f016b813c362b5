//! Lanes: one instruction for 4, 8 or 16 rays.
//!
//! The formulas the scalar tracer and the wavefront share (the shapes' intersections first)
//! are written once over [`Real`], a number that is either one `f32` or a row of them,
//! [`Lanes<N>`], with comparisons giving masks and `select` in place of branches. For `f32`
//! the code is the scalar tracer's; for `Lanes<N>` each operation is a loop over the lanes
//! that the compiler turns into vector instructions inside a function compiled for the
//! processor's vector extension ([`Width::dispatch`]). Every lane does exactly the scalar
//! operations in the scalar order (Rust never fuses a multiply and an add on its own), so a
//! lane's result is the scalar result bit for bit.
//!
//! The width is chosen at run time ([`Width::best`]): 16 lanes with AVX-512, 8 with AVX2, 4
//! with SSE2 or NEON (the baselines of x86-64 and AArch64), one elsewhere. `RAYLAB_LANES`
//! (1, 4, 8 or 16) asks for a narrower one, to test and compare each ([`asked_lanes`]).

mod columns;
mod vector;
mod width;

pub use columns::{Columns, RayColumns};
pub use vector::{V3, Vector, Wide};
pub use width::{LaneKernel, Width, asked_lanes};

use super::Vec3;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// A number the shared formulas are written over: `f32`, or [`Lanes<N>`].
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// The result of a comparison: `bool`, or one per lane.
    type Mask: Copy
        + BitAnd<Output = Self::Mask>
        + BitOr<Output = Self::Mask>
        + Not<Output = Self::Mask>;
    /// A point or direction of these: [`Vec3`] for one ray, [`V3`] for lanes.
    type V3: Vector<Self>;
    /// `x` in every lane.
    fn splat(x: f32) -> Self;
    /// The square root (correctly rounded, as `f32::sqrt`).
    fn sqrt(self) -> Self;
    /// |self|.
    fn abs(self) -> Self;
    /// |self| with the sign of `sign`.
    fn copysign(self, sign: Self) -> Self;
    /// self < other (false where either is NaN).
    fn less(self, other: Self) -> Self::Mask;
    /// self ≤ other (false where either is NaN).
    fn less_eq(self, other: Self) -> Self::Mask;
    /// self = other (false where either is NaN).
    fn equal(self, other: Self) -> Self::Mask;
    /// `a` where `m` holds, `b` elsewhere.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// Whether `m` holds in any lane: lets a formula stop early when no lane goes on, as the
    /// scalar code returns early.
    fn any(m: Self::Mask) -> bool;
    /// Whether `m` holds in every lane: lets a formula skip what no lane needs.
    fn all(m: Self::Mask) -> bool;
}

impl Real for f32 {
    type Mask = bool;
    type V3 = Vec3;
    #[inline(always)]
    fn splat(x: f32) -> f32 {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> f32 {
        f32::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> f32 {
        f32::abs(self)
    }
    #[inline(always)]
    fn copysign(self, sign: f32) -> f32 {
        f32::copysign(self, sign)
    }
    #[inline(always)]
    fn less(self, other: f32) -> bool {
        self < other
    }
    #[inline(always)]
    fn less_eq(self, other: f32) -> bool {
        self <= other
    }
    #[inline(always)]
    fn equal(self, other: f32) -> bool {
        self == other
    }
    #[inline(always)]
    fn select(m: bool, a: f32, b: f32) -> f32 {
        if m { a } else { b }
    }
    #[inline(always)]
    fn any(m: bool) -> bool {
        m
    }
    #[inline(always)]
    fn all(m: bool) -> bool {
        m
    }
}

/// A ray in the numbers `R`: one ray for `f32`, `N` rays coordinate by coordinate for
/// [`Lanes<N>`] (the lanes form of [`crate::math::Ray`]).
pub struct RayOf<R: Real> {
    /// Where each ray starts.
    pub origin: R::V3,
    /// Each ray's unit direction.
    pub dir: R::V3,
    /// Each ray's time in the shutter interval.
    pub time: R,
}

// By hand: a derive would ask `R: Clone` and not see that `R::V3` is `Copy`.
impl<R: Real> Clone for RayOf<R> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<R: Real> Copy for RayOf<R> {}

impl<const N: usize> RayOf<Lanes<N>> {
    /// Lane `i`'s ray.
    #[inline(always)]
    pub fn get(&self, i: usize) -> super::Ray {
        super::Ray {
            origin: self.origin.get(i),
            dir: self.dir.get(i),
            time: self.time.0[i],
        }
    }
}

/// `N` numbers operated on together, one per lane.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(transparent)]
pub struct Lanes<const N: usize>(pub [f32; N]);

/// A comparison's result in each of `N` lanes: all ones where it holds, zeros elsewhere, as
/// the processor's vector comparisons give it (a `bool` per lane would be narrowed to bytes
/// and widened again at every use).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(transparent)]
pub struct Mask<const N: usize>(pub [u32; N]);

impl<const N: usize> Lanes<N> {
    /// Lane i is `f(i)`.
    #[inline(always)]
    pub fn from_fn(f: impl FnMut(usize) -> f32) -> Self {
        Lanes(std::array::from_fn(f))
    }

    #[inline(always)]
    fn map(self, f: impl Fn(f32) -> f32) -> Self {
        let mut out = self.0;
        for x in &mut out {
            *x = f(*x);
        }
        Lanes(out)
    }

    #[inline(always)]
    fn zip(self, other: Self, f: impl Fn(f32, f32) -> f32) -> Self {
        let mut out = self.0;
        for (x, y) in out.iter_mut().zip(other.0) {
            *x = f(*x, y);
        }
        Lanes(out)
    }

    #[inline(always)]
    fn compare(self, other: Self, f: impl Fn(f32, f32) -> bool) -> Mask<N> {
        let mut out = [0; N];
        for ((m, x), y) in out.iter_mut().zip(self.0).zip(other.0) {
            *m = if f(x, y) { u32::MAX } else { 0 };
        }
        Mask(out)
    }
}

impl<const N: usize> Mask<N> {
    #[inline(always)]
    fn zip(self, other: Self, f: impl Fn(u32, u32) -> u32) -> Self {
        let mut out = self.0;
        for (x, y) in out.iter_mut().zip(other.0) {
            *x = f(*x, y);
        }
        Mask(out)
    }
}

macro_rules! lane_op {
    ($trait:ident, $method:ident, $op:tt) => {
        impl<const N: usize> $trait for Lanes<N> {
            type Output = Self;
            #[inline(always)]
            fn $method(self, other: Self) -> Self {
                self.zip(other, |x, y| x $op y)
            }
        }
    };
}
lane_op!(Add, add, +);
lane_op!(Sub, sub, -);
lane_op!(Mul, mul, *);
lane_op!(Div, div, /);

impl<const N: usize> Neg for Lanes<N> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        self.map(|x| -x)
    }
}

impl<const N: usize> BitAnd for Mask<N> {
    type Output = Self;
    #[inline(always)]
    fn bitand(self, other: Self) -> Self {
        self.zip(other, |x, y| x & y)
    }
}

impl<const N: usize> BitOr for Mask<N> {
    type Output = Self;
    #[inline(always)]
    fn bitor(self, other: Self) -> Self {
        self.zip(other, |x, y| x | y)
    }
}

impl<const N: usize> Not for Mask<N> {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        let mut out = self.0;
        for x in &mut out {
            *x = !*x;
        }
        Mask(out)
    }
}

impl<const N: usize> Real for Lanes<N> {
    type Mask = Mask<N>;
    type V3 = V3<Lanes<N>>;
    #[inline(always)]
    fn splat(x: f32) -> Self {
        Lanes([x; N])
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        self.map(f32::sqrt)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        self.map(f32::abs)
    }
    #[inline(always)]
    fn copysign(self, sign: Self) -> Self {
        self.zip(sign, f32::copysign)
    }
    #[inline(always)]
    fn less(self, other: Self) -> Mask<N> {
        self.compare(other, |x, y| x < y)
    }
    #[inline(always)]
    fn less_eq(self, other: Self) -> Mask<N> {
        self.compare(other, |x, y| x <= y)
    }
    #[inline(always)]
    fn equal(self, other: Self) -> Mask<N> {
        self.compare(other, |x, y| x == y)
    }
    #[inline(always)]
    fn select(m: Mask<N>, a: Self, b: Self) -> Self {
        let mut out = b.0;
        for ((o, m), a) in out.iter_mut().zip(m.0).zip(a.0) {
            if m != 0 {
                *o = a;
            }
        }
        Lanes(out)
    }
    #[inline(always)]
    fn any(m: Mask<N>) -> bool {
        // Or-reduced without a branch per lane, so that it vectorises.
        m.0.iter().fold(0, |a, &b| a | b) != 0
    }
    #[inline(always)]
    fn all(m: Mask<N>) -> bool {
        m.0.iter().fold(u32::MAX, |a, &b| a & b) == u32::MAX
    }
}

/// `x` clamped to [lo, hi] as `f32::clamp` does it (NaN stays NaN), for one number or
/// one per lane.
#[inline(always)]
pub fn clamp<R: Real>(x: R, lo: R, hi: R) -> R {
    let x = R::select(x.less(lo), lo, x);
    R::select(hi.less(x), hi, x)
}

/// The smaller of `a` and `b`; `a` where they do not compare (a NaN), so that a NaN in
/// `b` leaves `a` as it was.
#[inline(always)]
pub fn min<R: Real>(a: R, b: R) -> R {
    R::select(b.less(a), b, a)
}

/// The larger of `a` and `b`; `a` where they do not compare (a NaN), so that a NaN in
/// `b` leaves `a` as it was.
#[inline(always)]
pub fn max<R: Real>(a: R, b: R) -> R {
    R::select(a.less(b), b, a)
}

/// Where `x` is finite (neither infinite nor NaN), as `f32::is_finite`: x − x is 0 there
/// and NaN elsewhere.
#[inline(always)]
#[allow(clippy::eq_op)] // x − x is the test, not a slip.
pub fn is_finite<R: Real>(x: R) -> R::Mask {
    (x - x).equal(R::splat(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_compute_what_each_scalar_computes_bit_for_bit() {
        let xs = [
            1.5f32,
            -0.0,
            0.0,
            3e-39,
            f32::MAX,
            f32::INFINITY,
            f32::NAN,
            -7.25,
        ];
        let ys = [0.1f32, 2.0, -0.0, 1e-30, 2.0, f32::NEG_INFINITY, 1.0, -7.25];
        let (a, b) = (Lanes(xs), Lanes(ys));
        let same = |l: Lanes<8>, f: &dyn Fn(f32, f32) -> f32| {
            for i in 0..8 {
                assert_eq!(l.0[i].to_bits(), f(xs[i], ys[i]).to_bits(), "lane {i}");
            }
        };
        same(a + b, &|x, y| x + y);
        same(a - b, &|x, y| x - y);
        same(a * b, &|x, y| x * y);
        same(a / b, &|x, y| x / y);
        same(-a, &|x, _| -x);
        same(a.sqrt(), &|x, _| x.sqrt());
        same(a.abs(), &|x, _| x.abs());
        same(a.copysign(b), &|x, y| x.copysign(y));
        same(Lanes::select(a.less(b), a, b), &|x, y| {
            if x < y { x } else { y }
        });
        same(Lanes::select(a.less_eq(b), a, b), &|x, y| {
            if x <= y { x } else { y }
        });
        same(Lanes::select(a.equal(b), a, b), &|x, y| {
            if x == y { x } else { y }
        });
        assert!(Lanes::any(a.equal(b)));
        assert!(!Lanes::all(a.equal(b)));
        let (finite, clamped) = (is_finite(a), clamp(a, Lanes::splat(0.0), Lanes::splat(1.0)));
        for (i, x) in xs.iter().enumerate() {
            assert_eq!(finite.0[i] != 0, x.is_finite(), "lane {i}");
            assert_eq!(
                clamped.0[i].to_bits(),
                x.clamp(0.0, 1.0).to_bits(),
                "lane {i}"
            );
        }
        assert!(Lanes::all(a.equal(a) | !a.equal(a)));
        assert!(!Lanes::any(a.less(Lanes::splat(f32::NEG_INFINITY))));
    }
}
