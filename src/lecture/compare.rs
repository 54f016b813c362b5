//! What the sides of an A/B view differ in: one setting of the lecture, changed (two
//! sides, or three for regular, random and jittered samples).

use crate::optics::FresnelMode;
use crate::params::{LensModel, Params, Pattern, Transport, TreeMode};

/// Two (or three) images of one scene that differ in one thing the lecture compares.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Comparison {
    /// Schlick's approximation against the exact Fresnel equations.
    SchlickExact,
    /// Regular, random and jittered samples, at the same samples per pixel: three sides.
    RegularRandomJittered,
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
    /// The lecture's thin lens against a real one of glass (the double Gauss), of the same
    /// entrance pupil and focused at the same distance.
    ThinReal,
}

impl Comparison {
    /// The comparisons the window's A/B menu offers, with their menu entries: those that
    /// change one setting and keep the rest.
    pub const PRESETS: [(&'static str, Comparison); 8] = [
        ("Schlick | exact", Comparison::SchlickExact),
        (
            "regular | random | jittered",
            Comparison::RegularRandomJittered,
        ),
        ("constant | Fresnel", Comparison::ConstantFresnel),
        ("split | stochastic tree", Comparison::SplitStochastic),
        (
            "whitted | transmissive shadows",
            Comparison::WhittedTransmissive,
        ),
        ("whitted | path", Comparison::WhittedPath),
        ("whitted | path + photons", Comparison::WhittedPhotons),
        ("thin lens | double Gauss", Comparison::ThinReal),
    ];

    /// The labels of its sides, A first, left to right.
    pub fn labels(self) -> &'static [&'static str] {
        match self {
            Comparison::SchlickExact => &["A: Schlick", "B: exact Fresnel"],
            Comparison::RegularRandomJittered => &["A: regular", "B: random", "C: jittered"],
            Comparison::ConstantFresnel => &["A: constant k", "B: exact Fresnel"],
            Comparison::SplitStochastic => &["A: split tree", "B: stochastic tree"],
            Comparison::WhittedTransmissive => &["A: Whitted", "B: transmissive shadows"],
            Comparison::WhittedPath => &["A: Whitted", "B: path tracing"],
            Comparison::WhittedPhotons => &["A: Whitted", "B: path tracing + photons"],
            Comparison::Supersampling => &["A: 1 sample, centre", "B: 4 jittered"],
            Comparison::Blurring => &["A: 1 ray, point light", "B: 256 rays, area light"],
            Comparison::Polariser => &["A: no polariser", "B: vertical polariser"],
            Comparison::ThinReal => &["A: thin lens", "B: double Gauss 50 mm"],
        }
    }

    /// Where the dividers between its sides start, across the image (0 to 1, left to
    /// right): at `divider` between two sides, evenly spaced between three.
    pub fn dividers(self, divider: f32) -> Vec<f32> {
        match self.labels().len() {
            2 => vec![divider],
            n => (1..n).map(|i| i as f32 / n as f32).collect(),
        }
    }

    /// Side A's parameters when the comparison starts.
    pub fn side_a(self, p: &Params) -> Params {
        let mut p = p.clone();
        match self {
            Comparison::SchlickExact => p.fresnel = Some(FresnelMode::Schlick),
            Comparison::RegularRandomJittered => p.pattern = Pattern::Regular,
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
            Comparison::ThinReal => p.lens = LensModel::Thin,
        }
        p
    }

    /// The sides after A, left to right, given A's parameters: B (and C).
    pub fn others(self, a: &Params) -> Vec<Params> {
        let mut sides = vec![self.side_b(a)];
        if self == Comparison::RegularRandomJittered {
            sides.push(Params {
                pattern: Pattern::Jittered,
                ..a.clone()
            });
        }
        sides
    }

    /// Side B's parameters, given side A's: A's with the compared setting changed (the
    /// middle one of three).
    fn side_b(self, a: &Params) -> Params {
        let mut p = a.clone();
        match self {
            Comparison::SchlickExact | Comparison::ConstantFresnel => {
                p.fresnel = Some(FresnelMode::Exact)
            }
            Comparison::RegularRandomJittered => p.pattern = Pattern::Random,
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
            Comparison::ThinReal => p.lens = LensModel::DoubleGauss50,
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
            let sides: Vec<Params> = std::iter::once(a.clone()).chain(kind.others(&a)).collect();
            assert_eq!(sides.len(), kind.labels().len(), "{label}: a label a side");
            assert_eq!(kind.dividers(0.5).len(), sides.len() - 1, "{label}");
            for (i, s) in sides.iter().enumerate() {
                assert_eq!(
                    (s.max_depth, s.spp),
                    (3, 7),
                    "{label}: side {i} keeps the rest"
                );
                for t in &sides[..i] {
                    assert_ne!(s, t, "{label}: the sides differ");
                }
            }
        }
        let three = Comparison::RegularRandomJittered;
        let a = three.side_a(&p);
        let patterns: Vec<Pattern> = std::iter::once(&a)
            .chain(&three.others(&a))
            .map(|s| s.pattern)
            .collect();
        assert_eq!(
            patterns,
            [Pattern::Regular, Pattern::Random, Pattern::Jittered]
        );
        assert_eq!(three.dividers(0.2), [1.0 / 3.0, 2.0 / 3.0]);
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
            assert_eq!(k.others(&a)[0].transport, b);
        }
    }
}
