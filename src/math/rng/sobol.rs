//! Owen-scrambled Sobol points: the first three Sobol dimensions, the hash-based Owen
//! scramble, the pair a [`SampleStream`] draws per dimension, the image position's third
//! coordinate ([`SampleStream::with_image_position`]), and the same pairs drawn for
//! several samples at once in SIMD lanes ([`SobolLanes`]).

use super::{Pattern, SampleStream, dimension_key, mix64, pixel_key};
use crate::math::lanes::Lanes;
use glam::Vec2;

/// The Laine–Karras permutation of the bits of `x` (least significant first): flipping
/// each bit by a hash of the bits below it. Applied to bit-reversed numbers it is a nested
/// uniform (Owen) scramble (Burley, "Practical Hash-based Owen Scrambling", JCGT 2020,
/// with Vegdahl's constants).
#[inline]
pub(super) fn laine_karras(mut x: u32, seed: u32) -> u32 {
    x = x.wrapping_add(seed);
    x ^= x.wrapping_mul(0x6c50_b47c);
    x ^= x.wrapping_mul(0xb82f_1e52);
    x ^= x.wrapping_mul(0xc7af_e638);
    x ^= x.wrapping_mul(0x8d22_f6e6);
    x
}

/// Owen scrambling of the 32-bit fraction `x` (most significant bit first).
#[inline]
pub fn owen_scramble(x: u32, seed: u32) -> u32 {
    laine_karras(x.reverse_bits(), seed).reverse_bits()
}

/// The first two dimensions of the Sobol sequence at `index`, as 32-bit fractions.
///
/// Dimension 0 is the van der Corput sequence: the bits of the index reversed. Dimension
/// 1's generator matrix is Pascal's triangle mod 2: output bit r is the XOR of the index
/// bits c with binom(c, r) odd, which by Lucas's theorem means r ⊆ c (as bit sets of the
/// positions). That superset sum runs over the 5 bits of a position in 5 shift-xor steps.
#[inline]
pub fn sobol_2d(index: u32) -> (u32, u32) {
    (index.reverse_bits(), pascal(index).reverse_bits())
}

/// The second Sobol dimension before its bit reversal: the Pascal matrix mod 2 applied to
/// `index` (Lucas's theorem), in five steps.
#[inline]
pub(super) fn pascal(index: u32) -> u32 {
    let mut y = index;
    y ^= (y >> 1) & 0x5555_5555;
    y ^= (y >> 2) & 0x3333_3333;
    y ^= (y >> 4) & 0x0f0f_0f0f;
    y ^= (y >> 8) & 0x00ff_00ff;
    y ^= (y >> 16) & 0x0000_ffff;
    y
}

/// The third Sobol dimension's direction numbers v_k = m_k / 2^k as 32-bit fractions, for
/// index bits k = 1..32. Its primitive polynomial is x² + x + 1 (degree s = 2, a₁ = 1), with
/// m₁ = 1, m₂ = 3 (Joe and Kuo's table) and the recurrence
/// m_k = 2a₁·m_{k−1} ⊕ 2²·m_{k−2} ⊕ m_{k−2}.
const SOBOL_3: [u32; 32] = {
    let mut v = [0u32; 32];
    let mut m = [0u64; 33];
    m[1] = 1;
    m[2] = 3;
    let mut k = 3;
    while k <= 32 {
        m[k] = (2 * m[k - 1]) ^ (4 * m[k - 2]) ^ m[k - 2];
        k += 1;
    }
    let mut k = 1;
    while k <= 32 {
        v[k - 1] = (m[k] << (32 - k)) as u32;
        k += 1;
    }
    v
};

/// The third Sobol dimension at `index`, as a 32-bit fraction: the XOR of the direction
/// numbers of the index's set bits.
#[inline]
fn sobol_third(index: u32) -> u32 {
    let mut x = 0;
    let mut bits = index;
    while bits != 0 {
        x ^= SOBOL_3[bits.trailing_zeros() as usize];
        bits &= bits - 1;
    }
    x
}

/// A 32-bit fraction to a float in [0, 1) (its top 24 bits, exact in f32).
#[inline]
pub(super) fn fraction_to_f32(x: u32) -> f32 {
    (x >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
}

/// Dimension `dim`'s key in the pixel whose key is `pixel_key`, and the Owen-scrambled
/// index of the sample whose number, bits reversed, is `sample_reversed` (a nested uniform
/// scramble of the sample number, which keeps every power-of-two prefix a net).
#[inline(always)]
fn scrambled_index(pixel_key: u64, sample_reversed: u32, dim: u32) -> (u64, u32) {
    let key = dimension_key(pixel_key, dim);
    (
        key,
        laine_karras(sample_reversed, key as u32).reverse_bits(),
    )
}

/// The first number of [`sobol_pair`], bit for bit, without the second's work (its hash,
/// Pascal matrix and scramble): rev32(x) is the low half of the pair's 64-bit reversal.
#[inline(always)]
pub(super) fn sobol_first(pixel_key: u64, sample_reversed: u32, dim: u32) -> f32 {
    let (key, index) = scrambled_index(pixel_key, sample_reversed, dim);
    fraction_to_f32(laine_karras(index, (key >> 32) as u32).reverse_bits())
}

/// Dimension `dim`'s Owen-scrambled Sobol pair of the sample whose number, bits reversed, is
/// `sample_reversed`, in the pixel whose key is `pixel_key`: the sample index shuffled by a
/// nested uniform scramble (which keeps every power-of-two prefix a (0,m,2)-net), then each
/// coordinate scrambled, all seeded per pixel and dimension ("padded" Sobol).
#[inline(always)]
pub(super) fn sobol_pair(pixel_key: u64, sample_reversed: u32, dim: u32) -> Vec2 {
    let (key, index) = scrambled_index(pixel_key, sample_reversed, dim);
    let (sx, sy) = ((key >> 32) as u32, mix64(key) as u32);
    // In full: index = owen_scramble(sample, key), (x, y) = sobol_2d(index), then each
    // Owen-scrambled. With owen_scramble(v, s) = rev(LK(rev(v), s)) and sobol_2d(i) =
    // (rev(i), rev(pascal(i))), the bit reversals cancel in pairs: 3 instead of 8,
    // the same bits. The last two are one 64-bit reversal of the pair side by side
    // (rev64(a·2³² + b) = rev32(b)·2³² + rev32(a)): a reversal costs some twenty
    // instructions where the processor has no instruction for it, as x86 has not.
    let x = laine_karras(index, sx);
    let y = laine_karras(pascal(index), sy);
    let both = ((x as u64) << 32 | y as u64).reverse_bits();
    Vec2::new(
        fraction_to_f32(both as u32),
        fraction_to_f32((both >> 32) as u32),
    )
}

/// A Sobol pair a stream has passed over, to be drawn later with others of its kind `N` at
/// a time in SIMD lanes ([`sobol_pairs`]): the inputs of [`sobol_pair`].
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct SobolDraw {
    pixel_key: u64,
    sample_reversed: u32,
    dim: u32,
}

/// A stream's next pair ([`SampleStream::next_2d_or_later`]): drawn, or, with the Sobol
/// pattern, left to be drawn in lanes.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Pair {
    /// The pair, drawn.
    Drawn(Vec2),
    /// What draws it: [`sobol_pairs`].
    Later(SobolDraw),
}

/// The pairs of `draws` (up to `N`; lanes past the last repeat it) in lanes, x and y: each
/// [`sobol_pair`]'s bit for bit. Only for use inside a
/// [`crate::math::lanes::LaneKernel`], as [`SobolLanes`].
#[inline(always)]
pub(crate) fn sobol_pairs<const N: usize>(draws: &[SobolDraw]) -> (Lanes<N>, Lanes<N>) {
    let last = draws.last().copied().unwrap_or_default();
    let draw = |k: usize| draws.get(k).copied().unwrap_or(last);
    let keys: [u64; N] = std::array::from_fn(|k| draw(k).pixel_key);
    let revs: [u32; N] = std::array::from_fn(|k| draw(k).sample_reversed);
    let dims: [u32; N] = std::array::from_fn(|k| draw(k).dim);
    let (mut x, mut y) = ([0.0; N], [0.0; N]);
    for k in 0..N {
        let v = sobol_pair(keys[k], revs[k], dims[k]);
        (x[k], y[k]) = (v.x, v.y);
    }
    (Lanes(x), Lanes(y))
}

impl SampleStream {
    /// [`SampleStream::next_2d`], but with the Sobol pattern the pair is left to be drawn
    /// later, `N` at a time ([`sobol_pairs`]); either way the stream moves past it.
    #[inline(always)]
    pub(crate) fn next_2d_or_later(&mut self) -> Pair {
        if self.pattern != Pattern::Sobol {
            return Pair::Drawn(self.next_2d());
        }
        let later = SobolDraw {
            pixel_key: self.pixel_key,
            sample_reversed: self.sample_reversed,
            dim: self.dim,
        };
        self.dim += 1;
        Pair::Later(later)
    }

    /// A number in [0, 1) that is the third coordinate of the image position's point: with
    /// the Sobol pattern, the same Owen-scrambled index as the first draw's pair (dimension
    /// 0, the image position), taken through the third Sobol dimension and scrambled with
    /// a seed of its own. The pixel's samples in (x, y, u) are then a scrambled 3D Sobol
    /// net, not three independently shuffled strata: where the value depends on the image
    /// position and u together (a wavelength seen through a prism: the colour changes
    /// across the pixel), the error falls faster than with a padded draw. Other patterns
    /// draw the next dimension. Either way the stream moves past one dimension, so the
    /// draws after it are where [`SampleStream::next_1d`] would leave them.
    pub fn with_image_position(&mut self) -> f32 {
        if self.pattern != Pattern::Sobol {
            return self.next_1d();
        }
        let (key, index) = scrambled_index(self.pixel_key, self.sample_reversed, 0);
        self.dim += 1;
        fraction_to_f32(owen_scramble(sobol_third(index), (mix64(key) >> 32) as u32))
    }
}

/// The Sobol streams of `N` samples begun together, their first draws made in SIMD lanes
/// (the camera's, which every sample makes at the same dimensions): each lane's numbers are
/// its [`SampleStream`]'s bit for bit. Only for use inside a [`crate::math::lanes::LaneKernel`]
/// (everything here is inlined into it, to be compiled for its vector extension).
pub(crate) struct SobolLanes<const N: usize> {
    spp: u32,
    pixel_key: [u64; N],
    sample: [u32; N],
    sample_reversed: [u32; N],
    dim: u32,
}

impl<const N: usize> SobolLanes<N> {
    /// Sample `samples[i]` of pixel `pixels[i]` in lane i, of `spp` per pixel, under the seed
    /// whose key is `seed_key` ([`seed_key`]): [`SampleStream::with_seed_key`] with the
    /// Sobol pattern, in lanes.
    #[inline(always)]
    pub(crate) fn new(spp: u32, seed_key: u64, pixels: [u32; N], samples: [u32; N]) -> Self {
        SobolLanes {
            spp,
            pixel_key: pixels.map(|p| pixel_key(seed_key, p)),
            sample: samples,
            sample_reversed: samples.map(u32::reverse_bits),
            dim: 0,
        }
    }

    /// [`SampleStream::next_2d`] in every lane.
    #[inline(always)]
    pub(crate) fn next_2d(&mut self) -> [Vec2; N] {
        let mut out = [Vec2::ZERO; N];
        for ((o, &key), &rev) in out
            .iter_mut()
            .zip(&self.pixel_key)
            .zip(&self.sample_reversed)
        {
            *o = sobol_pair(key, rev, self.dim);
        }
        self.dim += 1;
        out
    }

    /// [`SampleStream::next_1d`] in every lane.
    #[inline(always)]
    pub(crate) fn next_1d(&mut self) -> [f32; N] {
        let mut out = [0.0; N];
        for ((o, &key), &rev) in out
            .iter_mut()
            .zip(&self.pixel_key)
            .zip(&self.sample_reversed)
        {
            *o = sobol_first(key, rev, self.dim);
        }
        self.dim += 1;
        out
    }

    /// Skips `n` dimensions, as [`Uniform::skip`].
    #[inline(always)]
    pub(crate) fn skip(&mut self, n: u32) {
        self.dim += n;
    }

    /// Lane `lane`'s stream, to go on drawing from where the lanes are.
    #[inline(always)]
    pub(crate) fn stream(&self, lane: usize) -> SampleStream {
        let (key, sample) = (self.pixel_key[lane], self.sample[lane]);
        SampleStream {
            dim: self.dim,
            ..SampleStream::of_pixel_key(Pattern::Sobol, self.spp, key, sample)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_third_dimension_is_sobols() {
        // Joe and Kuo's third dimension, as pbrt tabulates its generator matrix.
        let expected = [
            0x8000_0000u32,
            0xc000_0000,
            0x6000_0000,
            0x9000_0000,
            0xe800_0000,
            0x5c00_0000,
            0x8e00_0000,
            0xc500_0000,
        ];
        assert_eq!(SOBOL_3[..8], expected);
        for (k, &v) in expected.iter().enumerate() {
            assert_eq!(sobol_third(1 << k), v);
        }
        // Index 3 is the XOR of indices 1 and 2: 1/2 ⊕ 3/4 = 1/4.
        assert_eq!(sobol_third(3), 0x4000_0000);
    }

    /// Whether `points` (2^m of them) put exactly 2^t in every elementary box of area
    /// 2^(t − m): a (t, m, 2)-net.
    fn is_net(points: &[(f32, f32)], t: u32) -> bool {
        let m = points.len().trailing_zeros();
        (0..=m - t).all(|a| {
            let b = m - t - a;
            let mut count = vec![0u32; 1 << (m - t)];
            for &(x, y) in points {
                let (i, j) = (
                    (x * (1u32 << a) as f32) as usize,
                    (y * (1u32 << b) as f32) as usize,
                );
                count[i << b | j] += 1;
            }
            count.iter().all(|&c| c == 1 << t)
        })
    }

    #[test]
    fn the_image_positions_third_coordinate_makes_a_net_with_it() {
        // Each pixel's first 2^m samples: (x, u) and (y, u) are (1, m, 2)-nets (t = 1 for
        // the pairs of Sobol's first three dimensions), which they would not be if u were
        // drawn on its own (padded).
        for pixel in [0, 7, 1234] {
            for m in [4u32, 6, 8] {
                let n = 1u32 << m;
                let (mut xu, mut yu, mut padded) = (Vec::new(), Vec::new(), Vec::new());
                for s in 0..n {
                    let mut stream = SampleStream::with_pattern(Pattern::Sobol, n, 9, pixel, s);
                    let p = stream.next_2d();
                    let mut other = stream.clone();
                    let u = stream.with_image_position();
                    xu.push((p.x, u));
                    yu.push((p.y, u));
                    padded.push((p.x, other.next_1d()));
                    // The stream moves past one dimension, as next_1d does.
                    assert_eq!(stream.dimension(), other.dimension());
                }
                assert!(is_net(&xu, 1) && is_net(&yu, 1), "pixel {pixel}, 2^{m}");
                // (16 padded points can be a net by chance; 64 and 256 are not.)
                assert!(m < 6 || !is_net(&padded, 1), "pixel {pixel}, 2^{m}: padded");
            }
        }
    }

    #[test]
    fn sobol_2d_matches_the_sequence() {
        // Dimension 1 of Sobol in index order: 0, 1/2, 3/4, 1/4, 5/8, 1/8, 3/8, 7/8.
        let expected = [0.0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875];
        for (i, e) in expected.iter().enumerate() {
            let (x, y) = sobol_2d(i as u32);
            assert_eq!(y as f64 / 2f64.powi(32), *e, "index {i}");
            assert_eq!(x, (i as u32).reverse_bits());
        }
    }

    #[test]
    fn pairs_left_for_later_are_the_pairs_drawn_now() {
        // Streams of several pixels and samples, each at its own dimension; a short last
        // group as well as a full one.
        let mut now = Vec::new();
        let mut later = Vec::new();
        for k in 0..11u32 {
            let mut st = SampleStream::with_pattern(Pattern::Sobol, 64, 5, k * 7, k * 13);
            for _ in 0..k % 4 {
                st.next_1d();
            }
            let mut twin = st.clone();
            now.push(st.next_2d());
            match twin.next_2d_or_later() {
                Pair::Later(draw) => later.push(draw),
                Pair::Drawn(_) => panic!("a Sobol pair is left for later"),
            }
            // The stream moves past the pair either way.
            assert_eq!(twin.next_1d().to_bits(), st.next_1d().to_bits());
        }
        for group in [&later[..8], &later[8..]] {
            let (x, y) = sobol_pairs::<8>(group);
            let first = if group.len() == 8 { 0 } else { 8 };
            for (k, v) in now[first..first + group.len()].iter().enumerate() {
                assert_eq!(
                    (x.0[k].to_bits(), y.0[k].to_bits()),
                    (v.x.to_bits(), v.y.to_bits())
                );
            }
            // Lanes past a short group's end repeat its last pair, as documented.
            let last = group.len() - 1;
            for k in group.len()..8 {
                assert_eq!((x.0[k], y.0[k]), (x.0[last], y.0[last]));
            }
        }
        // Other patterns draw at once, as next_2d.
        let mut st = SampleStream::with_pattern(Pattern::Jittered, 16, 5, 3, 2);
        let mut twin = st.clone();
        assert!(matches!(twin.next_2d_or_later(), Pair::Drawn(v) if v == st.next_2d()));
    }

    #[test]
    fn the_sobol_shortcut_equals_the_long_form() {
        for pixel in 0..4 {
            for sample in [0, 1, 2, 3, 7, 100, 1023, 65_537] {
                let mut st = SampleStream::with_pattern(Pattern::Sobol, 16, 3, pixel, sample);
                for _ in 0..6 {
                    let key = st.dimension_key();
                    let index = owen_scramble(sample, key as u32);
                    let (x, y) = sobol_2d(index);
                    let (sx, sy) = ((key >> 32) as u32, mix64(key) as u32);
                    let long = Vec2::new(
                        fraction_to_f32(owen_scramble(x, sx)),
                        fraction_to_f32(owen_scramble(y, sy)),
                    );
                    // One number alone is the pair's first, to the bit.
                    let (key, rev, dim) = (st.pixel_key, st.sample_reversed, st.dim);
                    let first = sobol_first(key, rev, dim);
                    assert_eq!(first.to_bits(), long.x.to_bits());
                    assert_eq!(st.next_2d(), long, "pixel {pixel}, sample {sample}");
                }
            }
        }
    }
}
