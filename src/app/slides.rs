//! The lecture's slides, in its order: each a scene, parameters, the comparison and the
//! control sections it opens, and a caption that follows the parameters.

use super::compare::CompareKind;
use crate::params::{ParamError, Params};

/// One slide of the lecture: a scene, parameters, and what to look at.
pub(crate) struct Slide {
    /// Menu entry.
    pub title: &'static str,
    /// The built-in scene.
    pub scene: &'static str,
    /// Parameters set on top of the scene's, as `--set` would. The slide's `spp` is its
    /// target: enough for the status bar's noise under 2 % (tests/slides.rs), except where
    /// the slide is about the noise of few samples.
    pub params: &'static [(&'static str, &'static str)],
    /// The caption shown under or over the image, from the parameters as they are now:
    /// it follows what the lecturer changes.
    pub caption: fn(&Params) -> String,
    /// The sections of the controls the slide opens (where the controls it names are).
    pub open: &'static [&'static str],
    /// The A/B comparison the slide opens, if it compares two things.
    pub compare: Option<CompareKind>,
    /// The Fresnel plot, if the slide shows it: `Some(None)` for the dielectric's curves,
    /// `Some(Some(metal))` compared with a measured metal's.
    pub plot: Option<Option<&'static str>>,
    /// The pixel whose ray tree the inspector shows, as a fraction of the image's width
    /// and height, if the slide is about the tree.
    pub inspect: Option<(f32, f32)>,
}

/// The lecture, slide by slide.
pub(crate) const LECTURE: &[Slide] = &[
    Slide {
        title: "Metals vs dielectrics",
        scene: "metals",
        params: &[("spp", "32")],
        caption: |_| {
            "Left: dielectrics. The black glaze and the glass reflect 4% head-on and 100% only at grazing. Right: silver, gold and copper (measured η + iκ) reflect 80–97% at every angle, coloured: it depends on angle, but not much. Instruments > Fresnel plot > Compare with a metal.".into()
        },
        compare: None,
        open: &[],
        plot: None,
        inspect: None,
    },
    Slide {
        title: "Snell's law",
        scene: "glass",
        params: &[("spp", "128")],
        caption: |_| {
            "n1 sin θi = n2 sin θt: the refracted rays bend towards the normal going in and away coming out, so the sphere is a lens and shows the floor upside down. Drag the IOR.".into()
        },
        compare: None,
        open: &[],
        plot: None,
        inspect: None,
    },
    Slide {
        title: "The ray tree",
        scene: "ray-tree",
        params: &[("spp", "32")],
        caption: |_| {
            "Every hit on glass spawns two rays, reflected (weight R) and refracted (weight 1 − R), and each of those spawns two more: a tree per pixel. The inspector (right) lists the tree of the pixel marked through the front sphere, and draws it over the image: the reflections off its front and back, the rays through it to the amber sphere and beyond. Click another pixel to see its tree.".into()
        },
        compare: None,
        open: &[],
        plot: None,
        inspect: Some((0.42, 0.5)),
    },
    Slide {
        title: "Total internal reflection",
        scene: "tir",
        params: &[("spp", "32")],
        caption: |_| {
            "Inside the prism light meets the back faces at 45°, beyond the critical angle asin(1/n) for n > 1.41: a perfect mirror. Set the IOR below 1.41 and the red wall appears.".into()
        },
        compare: None,
        open: &[],
        plot: None,
        inspect: None,
    },
    Slide {
        title: "Pruning the ray tree",
        scene: "ray-tree",
        params: &[("max_depth", "2"), ("spp", "64")],
        caption: |p| {
            let d = p.max_depth;
            if d <= 3 {
                format!(
                    "Every hit on glass spawns a reflected and a refracted ray. Cut at depth {d}: through the front glass the spheres behind turn dark where the tree stops. Raise Max depth, or prune by Min weight instead."
                )
            } else {
                format!(
                    "At depth {d} the tree reaches through the glass: the spheres behind the front one show in it. Lower Max depth to 2 and they go dark; raise Min weight (now {}) and the faint internal reflections go first.",
                    p.min_weight
                )
            }
        },
        compare: None,
        open: &[],
        plot: None,
        inspect: None,
    },
    Slide {
        title: "Reflectance against angle: metal and glass",
        scene: "metals",
        params: &[("spp", "32")],
        caption: |_| {
            "The Fresnel plot: gold (top, per colour channel) reflects 97% of red and 32% of blue head-on, and more as the angle grows; glass (below) 4% head-on, rising to 100% only at grazing. Dielectrics' reflection is mostly Fresnel's rise; metals' is mostly there from the start.".into()
        },
        compare: None,
        open: &[],
        plot: Some(Some("gold")),
        inspect: None,
    },
    Slide {
        title: "Fresnel reflection on the black glazed sphere",
        scene: "glazed",
        params: &[("spp", "32"), ("constant_reflectance", "0.1")],
        caption: |_| {
            "Left of the divider (A): constant reflectance, 10% at every angle. Right (B): Fresnel, 4% head-on rising to 100% at grazing angles: the bright rim that makes it look glazed. Drag the divider across a sphere to see it change.".into()
        },
        compare: Some(CompareKind::ConstantFresnel),
        open: &[],
        plot: None,
        inspect: None,
    },
    Slide {
        title: "Fresnel's formulas and Schlick's approximation",
        scene: "glazed",
        params: &[],
        caption: |_| {
            "Left: Schlick's R0 + (1 − R0)(1 − cos θ)^5. Right: the exact (Fs² + Fp²)/2. The plot's Schlick − exact curve shows the error for n = 1.5: under 0.01 up to 47°, at most 0.036 (at 85°), on the rims, where both are bright: the images barely differ.".into()
        },
        compare: Some(CompareKind::SchlickExact),
        open: &[],
        plot: Some(None),
        inspect: None,
    },
    Slide {
        title: "The basic ray tracer",
        scene: "default",
        params: &[("spp", "1"), ("pattern", "regular")],
        caption: |p| {
            format!(
                "One ray through each pixel's centre ({} sample{} per pixel), a shadow ray to the point light: hard shadows, jagged edges. Everything after this slide adds rays: more per pixel, per light, per reflection.",
                p.spp,
                if p.spp == 1 { "" } else { "s" }
            )
        },
        compare: None,
        open: &[],
        plot: None,
        inspect: None,
    },
    Slide {
        title: "Antialiasing: 1 against 4 samples",
        scene: "antialiasing",
        params: &[],
        caption: |_| {
            "Left: one sample at each pixel's centre: the far checks turn to moiré and the thin rods break into stair steps (aliasing). Right: 4 jittered samples per pixel, averaged (a box filter): smooth edges, and grey where the checks are finer than a pixel.".into()
        },
        compare: Some(CompareKind::Supersampling),
        open: &[],
        plot: None,
        inspect: None,
    },
    Slide {
        title: "Regular, random and jittered samples",
        scene: "antialiasing",
        params: &[("spp", "4")],
        caption: |p| {
            format!(
                "{} samples per pixel. Left: random, independent in each pixel: clumps and gaps, noisier edges. Right: jittered, one in each cell of a 2 × 2 grid: the same cost, less noise. Regular (each cell's centre) would alias again: the Pattern menu has it.",
                p.spp
            )
        },
        compare: Some(CompareKind::RandomJittered),
        open: &[],
        plot: None,
        inspect: None,
    },
    Slide {
        title: "Blurring to improve images",
        scene: "soft-shadows",
        params: &[],
        caption: |_| {
            "Left (A): one ray through each pixel's centre, one shadow ray to a point light: jagged edges, hard shadows. Right (B): 256 rays per pixel, each through its own point of the pixel and to its own point of the area light, averaged: edges blur into smooth lines, shadows into penumbrae. Distribution ray tracing blurs on purpose, averaging rays spread over the pixel, the light, the lens and the shutter.".into()
        },
        compare: Some(CompareKind::Blurring),
        open: &[],
        plot: None,
        inspect: None,
    },
    Slide {
        title: "Soft shadows",
        scene: "soft-shadows",
        params: &[("spp", "256")],
        caption: |_| {
            "Each sample's shadow ray goes to a different point of the area light: the penumbra. Drag Light size; at 0 the light is a point and shadows are hard.".into()
        },
        compare: None,
        open: &["Soft shadows"],
        plot: None,
        inspect: None,
    },
    Slide {
        title: "Glossy reflection",
        scene: "glossy",
        params: &[("spp", "512")],
        caption: |_| {
            "Reflected rays jittered over a Phong lobe cos^n around the mirror direction: n = 10 to 10,000 from left to right.".into()
        },
        compare: None,
        open: &[],
        plot: None,
        inspect: None,
    },
    Slide {
        title: "Depth of field",
        scene: "depth-of-field",
        params: &[("spp", "256")],
        caption: |_| {
            "Eye rays from random points on the lens meet on the plane of focus: the blue sphere is sharp, the others blur by their circle of confusion. Try Click to focus.".into()
        },
        compare: None,
        open: &[],
        plot: None,
        inspect: None,
    },
    Slide {
        title: "Motion blur",
        scene: "motion-blur",
        // A fifth of the frame: the spheres smear over a fifth of their travel and stay
        // solid enough to see (over the whole frame they were faint ghosts).
        params: &[("shutter", "0.2")],
        caption: |p| {
            format!(
                "Each sample has a time in the shutter interval, open for {:.2} of the frame: the moving spheres smear over their travel in that time, the still one stays sharp. Drag the Shutter interval: 0 freezes them, 1 smears them over the whole frame.",
                p.shutter
            )
        },
        compare: None,
        open: &["Motion blur"],
        plot: None,
        inspect: None,
    },
    Slide {
        title: "F_s and F_p: polarisation at Brewster's angle",
        scene: "polarization",
        // The scene's own polariser is vertical.
        params: &[],
        caption: |_| {
            "Reflection polarises: R_s > R_p, and at Brewster's angle (53° on water, 56° on glaze) R_p = 0, so the reflection is s only, along the surface. A vertical polariser cuts it: the glare on the pond fades and the tiles show; a dark band crosses the sphere. Polariser > Horizontal brings it back.".into()
        },
        compare: None,
        open: &["Polariser"],
        plot: None,
        inspect: None,
    },
    Slide {
        title: "Dispersion",
        scene: "dispersion",
        params: &[],
        caption: |_| {
            "n depends on the wavelength: n(λ) = A + B/λ² through n_d and the Abbe number. Through the flint prism the white slit spreads into its spectrum, blue bent most; the lamps seen in the diamond fringe with colour. Drag the Abbe number (0: none).".into()
        },
        compare: None,
        open: &[],
        plot: None,
        inspect: None,
    },
    Slide {
        title: "What the ray tree misses",
        scene: "default",
        params: &[("spp", "64")],
        caption: |_| {
            "Left, the lecture's tracer: light comes only along shadow rays and mirror directions, so shadows get a flat ambient. Right, path tracing with photons (the reference): the blue sky lights the shadows, the glass focuses it into its own shadow, and the lamp's light through the glass lands in a bright caustic at its right foot. Drag the divider right: the lecture's tracer leaves that shadow black. Light transport > transmissive shadows is the common fix: tinted, but not focused.".into()
        },
        compare: Some(CompareKind::WhittedPhotons),
        open: &[],
        plot: None,
        inspect: None,
    },
];

impl Slide {
    /// The built-in scene's reference.
    pub(crate) fn reference(&self) -> String {
        format!("builtin:{}", self.scene)
    }

    /// `base` with the slide's parameters set on top, through the checked path: a name or
    /// value that `--set` would refuse is an error here too.
    pub(crate) fn apply(&self, base: &Params) -> Result<Params, ParamError> {
        let mut p = base.clone();
        for (name, value) in self.params {
            p.set(name, value)?;
        }
        Ok(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pruning_caption_follows_max_depth() {
        let slide = LECTURE
            .iter()
            .find(|s| s.title == "Pruning the ray tree")
            .unwrap();
        let at = |max_depth| {
            (slide.caption)(&Params {
                max_depth,
                ..Params::default()
            })
        };
        assert!(at(2).contains("Cut at depth 2"), "{}", at(2));
        // Raised past the cut, it no longer says the tree is cut.
        assert!(
            at(8).contains("At depth 8") && !at(8).contains("Cut at"),
            "{}",
            at(8)
        );
    }
}
