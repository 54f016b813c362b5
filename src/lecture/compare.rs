//! What the two sides of an A/B view differ in: one setting of the lecture, changed.

use crate::optics::FresnelMode;
use crate::params::{Params, Pattern, Transport, TreeMode};

/// Two images of one scene that differ in one thing the lecture compares.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Comparison {
    /// Schlick's approximation against the exact Fresnel equations.
    SchlickExact,
    /// Random against jittered samples, at the same samples per pixel.
    RandomJittered,
    /// Constant reflectance against Fresnel.
    ConstantFresnel,
    /// The split ray tree against the stochastic one.
    SplitStochastic,
    /// The lecture's black shadows behind glass against transmissive shadows.
    WhittedTransmissive,
    /// The lecture's tracer against path tracing, the reference.
    WhittedPath,
    /// The lecture's tracer against path tracing with photons (point lights' caustics).
    WhittedPhotons,
    /// One sample at each pixel's centre against four jittered samples: supersampling
    /// (a slide's, not a preset: the sides differ in their sample counts).
    Supersampling,
    /// One ray per pixel to a point light against 256 averaged over the pixel and the
    /// area light: distribution ray tracing's blurs (a slide's, not a preset).
    Blurring,
    /// No polariser against a vertical one in front of the lens.
    Polariser,
}

impl Comparison {
    /// The comparisons the window's A/B menu offers, with their menu entries: those that
    /// change one setting and keep the rest.
    pub const PRESETS: [(&'static str, Comparison); 7] = [
        ("Schlick | exact", Comparison::SchlickExact),
        ("random | jittered", Comparison::RandomJittered),
        ("constant | Fresnel", Comparison::ConstantFresnel),
        ("split | stochastic tree", Comparison::SplitStochastic),
        (
            "whitted | transmissive shadows",
            Comparison::WhittedTransmissive,
        ),
        ("whitted | path", Comparison::WhittedPath),
        ("whitted | path + photons", Comparison::WhittedPhotons),
    ];

    /// The labels of side A and side B.
    pub fn labels(self) -> (&'static str, &'static str) {
        match self {
            Comparison::SchlickExact => ("A: Schlick", "B: exact Fresnel"),
            Comparison::RandomJittered => ("A: random", "B: jittered"),
            Comparison::ConstantFresnel => ("A: constant k", "B: exact Fresnel"),
            Comparison::SplitStochastic => ("A: split tree", "B: stochastic tree"),
            Comparison::WhittedTransmissive => ("A: Whitted", "B: transmissive shadows"),
            Comparison::WhittedPath => ("A: Whitted", "B: path tracing"),
            Comparison::WhittedPhotons => ("A: Whitted", "B: path tracing + photons"),
            Comparison::Supersampling => ("A: 1 sample, centre", "B: 4 jittered"),
            Comparison::Blurring => ("A: 1 ray, point light", "B: 256 rays, area light"),
            Comparison::Polariser => ("A: no polariser", "B: vertical polariser"),
        }
    }

    /// Side A's parameters when the comparison starts.
    pub fn side_a(self, p: &Params) -> Params {
        let mut p = p.clone();
        match self {
            Comparison::SchlickExact => p.fresnel = Some(FresnelMode::Schlick),
            Comparison::RandomJittered => p.pattern = Pattern::Random,
            Comparison::ConstantFresnel => p.fresnel = Some(FresnelMode::Constant),
            Comparison::SplitStochastic => p.tree = TreeMode::Split,
            Comparison::WhittedTransmissive
            | Comparison::WhittedPath
            | Comparison::WhittedPhotons => p.transport = Transport::Whitted,
            // The lecture's basic tracer: one ray through each pixel's centre (and, to show
            // what blurring adds, a point light).
            Comparison::Supersampling | Comparison::Blurring => {
                p.spp = 1;
                p.pattern = Pattern::Regular;
                if self == Comparison::Blurring {
                    p.light_size = 0.0;
                }
            }
            Comparison::Polariser => p.polarizer = None,
        }
        p
    }

    /// Side B's parameters, given side A's: A's with the compared setting changed.
    pub fn side_b(self, a: &Params) -> Params {
        let mut p = a.clone();
        match self {
            Comparison::SchlickExact | Comparison::ConstantFresnel => {
                p.fresnel = Some(FresnelMode::Exact)
            }
            Comparison::RandomJittered => p.pattern = Pattern::Jittered,
            Comparison::SplitStochastic => p.tree = TreeMode::Stochastic,
            Comparison::WhittedTransmissive => p.transport = Transport::TransmissiveShadows,
            Comparison::WhittedPath => p.transport = Transport::Path,
            Comparison::WhittedPhotons => p.transport = Transport::Photons,
            Comparison::Supersampling => {
                p.spp = 4;
                p.pattern = Pattern::Jittered;
            }
            Comparison::Blurring => {
                p.spp = 256;
                p.pattern = Pattern::Sobol;
                p.light_size = 1.0;
            }
            Comparison::Polariser => p.polarizer = Some(90.0),
        }
        p
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_differs_in_one_setting_and_keeps_the_rest() {
        let p = Params {
            max_depth: 3,
            spp: 7,
            ..Params::default()
        };
        for (label, kind) in Comparison::PRESETS {
            let a = kind.side_a(&p);
            let b = kind.side_b(&a);
            assert_ne!(a, b, "{label}: the sides differ");
            assert_eq!((a.max_depth, a.spp), (3, 7), "{label}: A keeps the rest");
            assert_eq!((b.max_depth, b.spp), (3, 7), "{label}: B keeps the rest");
        }
        for (k, b) in [
            (
                Comparison::WhittedTransmissive,
                Transport::TransmissiveShadows,
            ),
            (Comparison::WhittedPath, Transport::Path),
            (Comparison::WhittedPhotons, Transport::Photons),
        ] {
            let a = k.side_a(&p);
            assert_eq!(a.transport, Transport::Whitted);
            assert_eq!(k.side_b(&a).transport, b);
        }
    }
}
