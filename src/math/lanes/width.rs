//! The width the lanes run at, chosen at run time, and the dispatch that compiles work for
//! it.

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
            Width::Sixteen => {
                // F for the floats; BW, DQ and VL for the integer lanes of the random
                // numbers (64-bit products, byte shuffles): every AVX-512 processor but the
                // Xeon Phi has all four.
                std::arch::is_x86_feature_detected!("avx512f")
                    && std::arch::is_x86_feature_detected!("avx512bw")
                    && std::arch::is_x86_feature_detected!("avx512dq")
                    && std::arch::is_x86_feature_detected!("avx512vl")
            }
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
        let best = Width::widest().min(asked.unwrap_or(Width::Sixteen));
        static SAID: std::sync::Once = std::sync::Once::new();
        SAID.call_once(|| {
            let widest = Width::widest();
            log::info!(
                "SIMD: {} lanes, {} (this processor's widest: {}, {}; RAYLAB_LANES: {:?})",
                best.lanes(),
                best.extension(),
                widest.lanes(),
                widest.extension(),
                asked_lanes()
            );
        });
        best
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
            // SAFETY: `run_avx512` needs AVX-512 F, BW, DQ and VL, which `runs_here` has just
            // detected.
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
#[target_feature(enable = "avx512f,avx512bw,avx512dq,avx512vl")]
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
    use crate::math::lanes::{Lanes, Real};

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
