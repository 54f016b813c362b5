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

use super::{Ray, Vec3};
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
    /// Whether `m` holds in every lane: lets a formula stop early when every lane is done.
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

/// `N` numbers operated on together, one per lane.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(transparent)]
pub struct Lanes<const N: usize>(pub [f32; N]);

/// A comparison's result in each of `N` lanes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(transparent)]
pub struct Mask<const N: usize>(pub [bool; N]);

impl<const N: usize> Lanes<N> {
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
        let mut out = [false; N];
        for ((m, x), y) in out.iter_mut().zip(self.0).zip(other.0) {
            *m = f(x, y);
        }
        Mask(out)
    }
}

impl<const N: usize> Mask<N> {
    #[inline(always)]
    fn zip(self, other: Self, f: impl Fn(bool, bool) -> bool) -> Self {
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
            if m {
                *o = a;
            }
        }
        Lanes(out)
    }
    #[inline(always)]
    fn any(m: Mask<N>) -> bool {
        // Or-reduced without a branch per lane, so that it vectorises.
        m.0.iter().fold(false, |a, &b| a | b)
    }
    #[inline(always)]
    fn all(m: Mask<N>) -> bool {
        m.0.iter().fold(true, |a, &b| a & b)
    }
}

/// A point or direction over a [`Real`]: the operations the shared formulas use, each
/// coordinate computed as glam's `Vec3A` computes it (on SSE2, NEON and without either),
/// so that one vector per lane gives `Vec3A`'s results bit for bit.
pub trait Vector<R>: Copy + Add<Output = Self> + Sub<Output = Self> {
    /// `v` in every lane.
    fn splat(v: Vec3) -> Self;
    /// The dot product, (x x′ + y y′) + z z′.
    fn dot(self, o: Self) -> R;
    /// The cross product, (y z′ − z y′, z x′ − x z′, x y′ − y x′).
    fn cross(self, o: Self) -> Self;
    /// Each coordinate times `s`.
    fn scale(self, s: R) -> Self;
    /// |self|².
    #[inline(always)]
    fn length_squared(self) -> R {
        self.dot(self)
    }
}

/// One ray's vectors are glam's, in SIMD registers as everywhere else in the tracer.
impl Vector<f32> for Vec3 {
    #[inline(always)]
    fn splat(v: Vec3) -> Vec3 {
        v
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
}

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

/// The most lanes any width has.
const MAX_LANES: usize = 16;

/// Rays kept as columns, one per coordinate, in blocks of [`MAX_LANES`], so that `N` rays'
/// x (or y, ...) load as one row of lanes and adding a ray checks for room once a block.
#[derive(Clone, Debug, Default)]
pub struct RayColumns {
    // Origin x, y, z, direction x, y, z, time.
    blocks: Vec<[[f32; MAX_LANES]; 7]>,
    len: usize,
}

impl RayColumns {
    /// No rays.
    pub fn clear(&mut self) {
        self.blocks.clear();
        self.len = 0;
    }

    /// The number of rays.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Adds `ray` at the end.
    #[inline]
    pub fn push(&mut self, ray: &Ray) {
        let j = self.len % MAX_LANES;
        if j == 0 {
            // The lanes past the last ray are zeros: a ray of no direction, hitting nothing.
            self.blocks.push([[0.0; MAX_LANES]; 7]);
        }
        if let Some(block) = self.blocks.last_mut() {
            let values = [
                ray.origin.x,
                ray.origin.y,
                ray.origin.z,
                ray.dir.x,
                ray.dir.y,
                ray.dir.z,
                ray.time,
            ];
            for (c, v) in block.iter_mut().zip(values) {
                c[j] = v;
            }
        }
        self.len += 1;
    }

    /// Ray `i`.
    #[inline]
    pub fn get(&self, i: usize) -> Ray {
        let block = &self.blocks[i / MAX_LANES];
        let c = |k: usize| block[k][i % MAX_LANES];
        Ray {
            origin: Vec3::new(c(0), c(1), c(2)),
            dir: Vec3::new(c(3), c(4), c(5)),
            time: c(6),
        }
    }

    /// Rays `i..i + N` (`i` a multiple of `N`, which divides [`MAX_LANES`]), coordinate by
    /// coordinate: (origin, direction, time). Lanes past the last ray hold zeros.
    #[inline(always)]
    pub fn lanes<const N: usize>(&self, i: usize) -> (V3<Lanes<N>>, V3<Lanes<N>>, Lanes<N>) {
        let block = &self.blocks[i / MAX_LANES];
        let j = i % MAX_LANES;
        let load = |k: usize| {
            let mut a = [0.0; N];
            a.copy_from_slice(&block[k][j..j + N]);
            Lanes(a)
        };
        (
            V3 {
                x: load(0),
                y: load(1),
                z: load(2),
            },
            V3 {
                x: load(3),
                y: load(4),
                z: load(5),
            },
            load(6),
        )
    }
}

/// How many rays one instruction serves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Width {
    /// One: no vector extension (or asked for).
    One,
    /// Four: SSE2 (every x86-64) or NEON (every AArch64).
    Four,
    /// Eight: AVX2.
    Eight,
    /// Sixteen: AVX-512.
    Sixteen,
}

impl Width {
    /// Every width, narrowest first.
    pub const ALL: [Width; 4] = [Width::One, Width::Four, Width::Eight, Width::Sixteen];

    /// The number of lanes.
    pub fn lanes(self) -> usize {
        match self {
            Width::One => 1,
            Width::Four => 4,
            Width::Eight => 8,
            Width::Sixteen => 16,
        }
    }

    /// The width of `lanes` lanes (1, 4, 8 or 16).
    pub fn of_lanes(lanes: usize) -> Option<Width> {
        Width::ALL.into_iter().find(|w| w.lanes() == lanes)
    }

    /// The vector extension it runs on, for messages.
    pub fn extension(self) -> &'static str {
        match self {
            Width::One => "scalar",
            Width::Four if cfg!(target_arch = "aarch64") => "NEON",
            Width::Four => "SSE2",
            Width::Eight => "AVX2",
            Width::Sixteen => "AVX-512",
        }
    }

    /// Whether this processor runs it.
    pub fn runs_here(self) -> bool {
        match self {
            Width::One => true,
            Width::Four => cfg!(any(target_arch = "x86_64", target_arch = "aarch64")),
            #[cfg(target_arch = "x86_64")]
            Width::Eight => std::arch::is_x86_feature_detected!("avx2"),
            #[cfg(target_arch = "x86_64")]
            Width::Sixteen => std::arch::is_x86_feature_detected!("avx512f"),
            #[cfg(not(target_arch = "x86_64"))]
            Width::Eight | Width::Sixteen => false,
        }
    }

    /// The widest this processor runs.
    pub fn widest() -> Width {
        Width::ALL
            .into_iter()
            .rev()
            .find(|w| w.runs_here())
            .unwrap_or(Width::One)
    }

    /// The widest this processor runs, at most [`asked_lanes`] if that is 1, 4, 8 or 16.
    pub fn best() -> Width {
        let asked = asked_lanes().and_then(Width::of_lanes);
        Width::widest().min(asked.unwrap_or(Width::Sixteen))
    }

    /// Runs `kernel` at this width: compiled for the width's vector extension, when this
    /// processor has it, else at the widest narrower one that it has.
    #[inline]
    pub fn dispatch<K: LaneKernel>(self, kernel: K) -> K::Output {
        let width = if self.runs_here() {
            self
        } else {
            Width::widest().min(self)
        };
        match width {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: `run_avx512` needs AVX-512F, which `runs_here` has just detected.
            #[allow(unsafe_code)]
            Width::Sixteen => unsafe { run_avx512(kernel) },
            #[cfg(target_arch = "x86_64")]
            // SAFETY: `run_avx2` needs AVX2, which `runs_here` has just detected.
            #[allow(unsafe_code)]
            Width::Eight => unsafe { run_avx2(kernel) },
            #[cfg(not(target_arch = "x86_64"))]
            Width::Sixteen | Width::Eight => kernel.run::<4>(),
            Width::Four => kernel.run::<4>(),
            Width::One => kernel.run::<1>(),
        }
    }
}

/// The lanes `RAYLAB_LANES` asks for, read once: a number, or `None` where it is unset or
/// not a number. 1, 4, 8 or 16 cap the width ([`Width::best`]); 0 asks for no waves at all
/// (the tracer's recursive walk, [`crate::tracer::Traversal::best`]).
pub fn asked_lanes() -> Option<usize> {
    static ASKED: std::sync::OnceLock<Option<usize>> = std::sync::OnceLock::new();
    *ASKED.get_or_init(|| {
        std::env::var("RAYLAB_LANES")
            .ok()
            .and_then(|v| v.trim().parse().ok())
    })
}

/// Work written once for any number of lanes: [`Width::dispatch`] picks `N` and compiles
/// `run` for the vector extension of that width. `run` and what it calls must be inlined
/// (`#[inline(always)]`) to be compiled so.
pub trait LaneKernel {
    /// What the work gives.
    type Output;
    /// Does the work `N` lanes at a time.
    fn run<const N: usize>(self) -> Self::Output;
}

// `unsafe` for the one reason std::arch gives: a function compiled for an extension may only
// be called where the processor has it, which `Width::dispatch` checks first. Measured worth
// it: ray against 8 spheres, 4 lanes (SSE2) 1.23x the scalar loop, 8 (AVX2) 1.78x, 16
// (AVX-512) 2.6x, bit-identical (docs/performance.md).
#[cfg(target_arch = "x86_64")]
#[allow(unsafe_code)]
#[target_feature(enable = "avx512f")]
unsafe fn run_avx512<K: LaneKernel>(kernel: K) -> K::Output {
    kernel.run::<16>()
}

#[cfg(target_arch = "x86_64")]
#[allow(unsafe_code)]
#[target_feature(enable = "avx2")]
unsafe fn run_avx2<K: LaneKernel>(kernel: K) -> K::Output {
    kernel.run::<8>()
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
        assert!(!Lanes::any(a.less(Lanes::splat(f32::NEG_INFINITY))));
        // NaN in one lane: not all.
        assert!(!Lanes::all(a.less_eq(Lanes::splat(f32::INFINITY))));
        assert!(Lanes::all(Lanes::<8>::splat(1.0).less(Lanes::splat(2.0))));
    }

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
            let s = a.scale(Lanes::splat(1.5));
            let g = *v * 1.5;
            assert_eq!(
                [s.x.0[i], s.y.0[i], s.z.0[i]].map(bits),
                g.to_array().map(bits)
            );
        }
    }

    #[test]
    fn the_widest_width_runs_here_and_the_environment_can_only_narrow_it() {
        assert!(Width::widest().runs_here());
        assert!(Width::best() <= Width::widest());
        for w in Width::ALL {
            assert_eq!(Width::of_lanes(w.lanes()), Some(w));
        }
        assert_eq!(Width::of_lanes(3), None);
    }

    struct Sum<'a>(&'a [f32]);

    impl LaneKernel for Sum<'_> {
        type Output = (usize, f32);
        #[inline(always)]
        fn run<const N: usize>(self) -> (usize, f32) {
            let mut acc = Lanes::<N>::splat(0.0);
            let chunks = self.0.chunks_exact(N);
            let rest: f32 = chunks.remainder().iter().sum();
            for c in chunks {
                let mut l = [0.0; N];
                l.copy_from_slice(c);
                acc = acc + Lanes(l);
            }
            (N, acc.0.iter().sum::<f32>() + rest)
        }
    }

    #[test]
    fn dispatch_runs_the_asked_width_where_it_runs_and_a_narrower_one_elsewhere() {
        let data: Vec<f32> = (0..100).map(|i| i as f32).collect();
        for w in Width::ALL {
            let (lanes, sum) = w.dispatch(Sum(&data));
            assert_eq!(sum, 4950.0);
            if w.runs_here() {
                assert_eq!(lanes, w.lanes());
            } else {
                assert!(lanes < w.lanes());
            }
        }
    }
}
