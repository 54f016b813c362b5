//! Counter-based sample streams: a sample's numbers depend only on (seed, pixel, sample
//! index, dimension) and the pattern, never on which thread or pass drew them.
//!
//! Each draw is one "dimension" (a 1D number or a 2D pair): the image position, the lens
//! point, the time, a point on a light, a glossy direction, a branch choice. Every
//! dimension of a pixel gets its own permutation or scramble, so dimensions are
//! decorrelated: the lens point of a sample says nothing about its image position.

mod sobol;

pub(crate) use sobol::{Pair, SobolDraw, SobolLanes, sobol_pairs};
pub use sobol::{owen_scramble, sobol_2d};
use sobol::{sobol_first, sobol_pair};

use glam::Vec2;
use serde::{Deserialize, Serialize};

/// How the samples of a pixel are spread over each dimension.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Pattern {
    /// The centres of a grid of ⌈√n⌉ × ⌈n/⌈√n⌉⌉ cells (n = samples per pixel): the
    /// lecture's baseline, which aliases.
    Regular,
    /// Independent uniform random numbers.
    Random,
    /// One uniform random point in each cell of the same grid (stratified sampling).
    Jittered,
    /// Owen-scrambled Sobol points: stratified at every power-of-two prefix, so each
    /// progressive pass adds to a well-spread set.
    Sobol,
}

impl Pattern {
    /// Every pattern, in menu order.
    pub const ALL: [Pattern; 4] = [
        Pattern::Regular,
        Pattern::Random,
        Pattern::Jittered,
        Pattern::Sobol,
    ];

    /// The name used in files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Pattern::Regular => "regular",
            Pattern::Random => "random",
            Pattern::Jittered => "jittered",
            Pattern::Sobol => "sobol",
        }
    }
}

/// The SplitMix64 finalizer: a bijective 64-bit mixer with full avalanche.
#[inline]
pub fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Maps 64 random bits to a uniform float in [0, 1) (24 bits: every value exact in f32).
#[inline]
pub fn to_unit_f32(bits: u64) -> f32 {
    (bits >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
}

/// Element `i` of a pseudo-random permutation of 0..len chosen by `seed`, for any `len`
/// (Kensler, "Correlated Multi-Jittered Sampling", 2013).
pub fn permute(mut i: u32, len: u32, seed: u32) -> u32 {
    let p = seed;
    let mut w = len.wrapping_sub(1);
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    loop {
        i ^= p;
        i = i.wrapping_mul(0xe170_893d);
        i ^= p >> 16;
        i ^= (i & w) >> 4;
        i ^= p >> 8;
        i = i.wrapping_mul(0x0929_eb3f);
        i ^= p >> 23;
        i ^= (i & w) >> 1;
        i = i.wrapping_mul(1 | p >> 27);
        i = i.wrapping_mul(0x6935_fa69);
        i ^= (i & w) >> 11;
        i = i.wrapping_mul(0x74dc_b303);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0x9e50_1cc3);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0xc860_a3df);
        i &= w;
        i ^= i >> 5;
        if i < len {
            break;
        }
    }
    (i.wrapping_add(p)) % len
}

/// The grid the regular and jittered patterns use for `n` samples: ⌈√n⌉ columns and
/// enough rows for n cells.
pub fn grid(n: u32) -> (u32, u32) {
    let nx = (n.max(1) as f64).sqrt().ceil() as u32;
    (nx, n.max(1).div_ceil(nx))
}

/// The random numbers of one camera sample, dimension after dimension, in the order the
/// tracer asks for them.
#[derive(Clone, Debug)]
pub struct SampleStream {
    pattern: Pattern,
    // Samples per pixel the pattern is laid out for (regular, jittered).
    count: u32,
    sample: u32,
    // The sample number's bits reversed, for the Owen scrambling of Sobol indices.
    sample_reversed: u32,
    // Mixes seed and pixel: every dimension's permutation and scramble derive from it.
    pixel_key: u64,
    // Mixes seed, pixel and sample: the random numbers derive from it.
    sample_key: u64,
    dim: u32,
}

const GOLDEN: u64 = 0x9e37_79b9_7f4a_7c15;

/// The key of pixel `pixel` (row-major index) under the seed whose key is `seed_key`.
#[inline(always)]
pub(super) fn pixel_key(seed_key: u64, pixel: u32) -> u64 {
    mix64(seed_key ^ (pixel as u64).wrapping_mul(GOLDEN))
}

/// The key of dimension `dim` of the pixel whose key is `pixel_key`, shared by all its
/// samples.
#[inline(always)]
pub(super) fn dimension_key(pixel_key: u64, dim: u32) -> u64 {
    mix64(pixel_key ^ (dim as u64 + 1).wrapping_mul(0x9e6c_63d0_676a_9a99))
}

/// The key every pixel's numbers under `seed` derive from.
#[inline]
pub(crate) fn seed_key(seed: u64) -> u64 {
    mix64(seed.wrapping_add(GOLDEN))
}

impl SampleStream {
    /// The stream of sample `sample` of pixel `pixel` (row-major index) under `seed`,
    /// with independent uniform random numbers.
    pub fn new(seed: u64, pixel: u32, sample: u32) -> Self {
        Self::with_pattern(Pattern::Random, 1, seed, pixel, sample)
    }

    /// The stream of sample `sample` of `spp` samples of pixel `pixel` under `seed`, laid
    /// out by `pattern`.
    pub fn with_pattern(pattern: Pattern, spp: u32, seed: u64, pixel: u32, sample: u32) -> Self {
        Self::with_seed_key(pattern, spp, seed_key(seed), pixel, sample)
    }

    /// [`SampleStream::with_pattern`] with the seed's key, [`seed_key`], computed once by
    /// the caller rather than once per sample.
    #[inline]
    pub(crate) fn with_seed_key(
        pattern: Pattern,
        spp: u32,
        seed_key: u64,
        pixel: u32,
        sample: u32,
    ) -> Self {
        Self::of_pixel_key(pattern, spp, pixel_key(seed_key, pixel), sample)
    }

    /// [`SampleStream::with_seed_key`] with the pixel's key, [`pixel_key`].
    #[inline(always)]
    fn of_pixel_key(pattern: Pattern, spp: u32, pixel_key: u64, sample: u32) -> Self {
        SampleStream {
            pattern,
            count: spp.max(1),
            sample,
            sample_reversed: sample.reverse_bits(),
            pixel_key,
            // Sobol points need no per-sample key (their sample number is scrambled).
            sample_key: match pattern {
                Pattern::Sobol => 0,
                _ => mix64(pixel_key ^ (sample as u64 + 1).wrapping_mul(0xd1b5_4a32_d192_ed03)),
            },
            dim: 0,
        }
    }

    /// 64 random bits for draw `k` of this dimension, unique to the sample.
    #[inline]
    fn random_bits(&self, k: u64) -> u64 {
        mix64(
            self.sample_key
                ^ ((self.dim as u64) << 2 | k)
                    .wrapping_add(1)
                    .wrapping_mul(GOLDEN),
        )
    }

    /// A key for this dimension of this pixel, shared by all its samples.
    #[inline]
    fn dimension_key(&self) -> u64 {
        dimension_key(self.pixel_key, self.dim)
    }

    /// This dimension's Owen-scrambled Sobol pair ([`sobol_pair`]).
    #[inline]
    fn sobol_pair(&self) -> Vec2 {
        sobol_pair(self.pixel_key, self.sample_reversed, self.dim)
    }

    /// The next dimension, uniform in [0, 1).
    #[inline]
    pub fn next_1d(&mut self) -> f32 {
        // Sobol, the default, in line at every call; the other patterns behind a call.
        if self.pattern == Pattern::Sobol {
            let u = sobol_first(self.pixel_key, self.sample_reversed, self.dim);
            self.dim += 1;
            return u;
        }
        self.next_1d_other()
    }

    /// [`SampleStream::next_1d`] for the patterns other than Sobol.
    #[inline(never)]
    fn next_1d_other(&mut self) -> f32 {
        let u = match self.pattern {
            Pattern::Random => to_unit_f32(self.random_bits(0)),
            Pattern::Sobol => self.sobol_pair().x,
            Pattern::Regular | Pattern::Jittered => {
                let n = self.count;
                let stratum = permute(self.sample % n, n, self.dimension_key() as u32);
                let offset = if self.pattern == Pattern::Regular {
                    0.5
                } else {
                    to_unit_f32(self.random_bits(0))
                };
                ((stratum as f32 + offset) / n as f32).min(ONE_MINUS_EPSILON)
            }
        };
        self.dim += 1;
        u
    }

    /// The next two dimensions, jointly stratified by the pattern, each in [0, 1).
    #[inline]
    pub fn next_2d(&mut self) -> Vec2 {
        // Sobol, the default, in line at every call; the other patterns behind a call.
        if self.pattern == Pattern::Sobol {
            let v = self.sobol_pair();
            self.dim += 1;
            return v;
        }
        self.next_2d_other()
    }

    /// [`SampleStream::next_2d`] for the patterns other than Sobol.
    #[inline(never)]
    fn next_2d_other(&mut self) -> Vec2 {
        let v = match self.pattern {
            Pattern::Random => Vec2::new(
                to_unit_f32(self.random_bits(0)),
                to_unit_f32(self.random_bits(1)),
            ),
            Pattern::Sobol => self.sobol_pair(),
            Pattern::Regular | Pattern::Jittered => {
                let (nx, ny) = grid(self.count);
                let cells = nx * ny;
                let cell = permute(self.sample % cells, cells, self.dimension_key() as u32);
                let offset = if self.pattern == Pattern::Regular {
                    Vec2::splat(0.5)
                } else {
                    Vec2::new(
                        to_unit_f32(self.random_bits(0)),
                        to_unit_f32(self.random_bits(1)),
                    )
                };
                let p = (Vec2::new((cell % nx) as f32, (cell / nx) as f32) + offset)
                    / Vec2::new(nx as f32, ny as f32);
                p.min(Vec2::splat(ONE_MINUS_EPSILON))
            }
        };
        self.dim += 1;
        v
    }

    /// How many dimensions have been drawn so far.
    pub fn dimension(&self) -> u32 {
        self.dim
    }
}

/// A source of uniform numbers in [0, 1): a sample's [`SampleStream`], or fixed numbers
/// in a test. Materials draw the numbers they need from it, in the caller's order.
pub trait Uniform {
    /// The next dimension.
    fn next_1d(&mut self) -> f32;
    /// The next two dimensions, jointly stratified where the source can.
    fn next_2d(&mut self) -> Vec2;
    /// Passes over `n` draws (of either kind) whose numbers would go unused, keeping the
    /// draws after them where they were.
    fn skip(&mut self, n: u32);
}

impl Uniform for SampleStream {
    #[inline]
    fn next_1d(&mut self) -> f32 {
        SampleStream::next_1d(self)
    }
    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        SampleStream::next_2d(self)
    }
    #[inline]
    fn skip(&mut self, n: u32) {
        self.dim += n;
    }
}

/// The largest f32 below 1.
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_are_reproducible_and_distinct() {
        for pattern in Pattern::ALL {
            let draw = |seed, pixel, sample| {
                let mut s = SampleStream::with_pattern(pattern, 16, seed, pixel, sample);
                [s.next_2d().x, s.next_2d().y, s.next_1d()]
            };
            assert_eq!(draw(7, 10, 3), draw(7, 10, 3));
            if pattern != Pattern::Regular {
                assert_ne!(draw(7, 10, 3), draw(8, 10, 3), "{pattern:?}");
                assert_ne!(draw(7, 10, 3), draw(7, 11, 3), "{pattern:?}");
            }
            assert_ne!(draw(7, 10, 3), draw(7, 10, 4), "{pattern:?}");
        }
    }

    #[test]
    fn uniform_mean_and_range() {
        // 2^16 draws: the mean of U[0,1) has standard deviation 1/sqrt(12 n) ~ 0.0011.
        let n = 1 << 16;
        let mut sum = 0.0f64;
        for i in 0..n {
            let u = SampleStream::new(1, i, 0).next_1d();
            assert!((0.0..1.0).contains(&u));
            sum += u as f64;
        }
        assert!((sum / n as f64 - 0.5).abs() < 5.0 * 0.0011);
    }

    #[test]
    fn permute_is_a_permutation_for_any_length() {
        for len in [1u32, 2, 3, 7, 16, 100, 1000] {
            for seed in [0u32, 1, 0xdead_beef] {
                let mut seen = vec![false; len as usize];
                for i in 0..len {
                    let p = permute(i, len, seed) as usize;
                    assert!(!seen[p], "len {len}: {p} twice");
                    seen[p] = true;
                }
            }
        }
    }

    #[test]
    fn jittered_and_regular_fill_every_stratum_once() {
        for pattern in [Pattern::Regular, Pattern::Jittered] {
            for spp in [1u32, 4, 9, 16] {
                let (nx, ny) = grid(spp);
                // For every 2D dimension: one sample in each cell.
                for dim in 0..3 {
                    let mut hits = vec![0; (nx * ny) as usize];
                    for s in 0..spp {
                        let mut st = SampleStream::with_pattern(pattern, spp, 5, 42, s);
                        for _ in 0..dim {
                            st.next_2d();
                        }
                        let p = st.next_2d();
                        let cell = (p.x * nx as f32) as u32 + nx * (p.y * ny as f32) as u32;
                        hits[cell as usize] += 1;
                    }
                    assert!(
                        hits.iter().all(|&h| h == 1),
                        "{pattern:?} spp {spp} dim {dim}: {hits:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn sobol_prefixes_are_stratified() {
        // Every power-of-two prefix of every dimension pair is a (0,m,2)-net: one point in
        // each elementary interval of area 1/n, of every shape (n×1, n/2×2, ..., 1×n).
        for (pixel, dims) in [(9u32, 0u32), (1234, 3)] {
            let mut points = Vec::new();
            for s in 0..256u32 {
                let mut st = SampleStream::with_pattern(Pattern::Sobol, 1 << 10, 3, pixel, s);
                for _ in 0..dims {
                    st.next_2d();
                }
                points.push(st.next_2d());
            }
            for m in [2u32, 4, 6, 8] {
                let n = 1u32 << m;
                for k in 0..=m {
                    let (cols, rows) = (1u32 << k, 1u32 << (m - k));
                    let mut hits = vec![0; n as usize];
                    for p in &points[..n as usize] {
                        let cell = (p.x * cols as f32) as u32 + cols * (p.y * rows as f32) as u32;
                        hits[cell as usize] += 1;
                    }
                    let ok = hits.iter().all(|&h| h == 1);
                    assert!(ok, "pixel {pixel}, dim {dims}, n {n}, {cols}x{rows}");
                }
            }
        }
    }

    #[test]
    fn dimensions_are_decorrelated() {
        // The image position and the lens position of the same samples are uncorrelated.
        for pattern in Pattern::ALL {
            let n = 4096;
            let (mut sxy, mut sx, mut sy) = (0.0f64, 0.0f64, 0.0f64);
            for pixel in 0..64u32 {
                for s in 0..64u32 {
                    let mut st = SampleStream::with_pattern(pattern, 64, 1, pixel, s);
                    let a = st.next_2d().x as f64;
                    let b = st.next_2d().x as f64;
                    sxy += a * b;
                    sx += a;
                    sy += b;
                }
            }
            let cov = sxy / n as f64 - (sx / n as f64) * (sy / n as f64);
            // Independent U(0,1): covariance 0 with standard deviation 1/(12 sqrt n).
            assert!(
                cov.abs() < 4.0 / (12.0 * (n as f64).sqrt()),
                "{pattern:?}: covariance {cov}"
            );
        }
    }
}
