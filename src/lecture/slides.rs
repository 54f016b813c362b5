//! The lecture's slides, in its order: each a few lines (see [`slide`]).

use super::captions::{inspected_object, sharp_sphere};
use super::{Comparison, Instrument, Slide, slide};

/// The lecture, slide by slide.
pub const LECTURE: &[Slide] = &[
    slide("Metals vs dielectrics", "metals")
        .set(&[("spp", "32")])
        .says(
            "Left: dielectrics. The black glaze and the glass reflect 4% head-on and 100% only at grazing. Right: silver, gold and copper (measured η + iκ) reflect 80–97% at every angle, coloured: it depends on angle, but not much. The next slide plots both against the angle.",
        ),
    // A pixel whose ray meets the sphere at 42°: the bend in and out is plain to see,
    // zoomed in on the sphere (the floor and the camera are far).
    slide("Snell's law", "glass")
        .set(&[("spp", "128")])
        .open(&[Instrument::Section {
            x: 0.334,
            y: 0.482,
            zoom: 3.0,
        }])
        .asks(&["ior"])
        .says(
            "n1 sin θi = n2 sin θt. Beside the image, the marked pixel's section: its ray bends towards the normal going into the glass and away coming out, θ written at both surfaces. So the sphere is a lens: the floor upside down. Drag the IOR.",
        ),
    slide("The ray tree", "ray-tree")
        .set(&[("spp", "32")])
        .open(&[Instrument::Section {
            x: 0.42,
            y: 0.5,
            zoom: 1.5,
        }])
        .follows(|s| {
            let tree = "Each hit on glass spawns a reflected ray (R) and a refracted one (1 − R): a tree per pixel, its section beside the image.";
            match inspected_object(s) {
                Some(Some("front sphere")) => format!(
                    "{tree} Drawn: the marked pixel's, off and through the front sphere. Click another pixel."
                ),
                Some(Some(object)) => format!(
                    "{tree} Drawn and listed: the tree of the marked pixel, on the {object}. Click another pixel."
                ),
                Some(None) => format!(
                    "{tree} The marked pixel's ray meets nothing: click a pixel on the glass."
                ),
                None => format!("{tree} Click a pixel to see its tree."),
            }
        }),
    slide("Total internal reflection", "tir")
        .set(&[("spp", "32")])
        .open(&[Instrument::Workbench {
            angle: 45.0,
            out: true,
        }])
        .asks(&["ior"])
        .says(
            "Inside the prism light meets the back faces at 45°, past the critical angle asin(1/n) for n > 1.41: no refracted ray (the workbench), a perfect mirror. Set the IOR below 1.41: the red wall appears. The air bubble in water has the same silver rim, beyond 48.8°.",
        ),
    slide("Pruning the ray tree", "ray-tree")
        .set(&[("max_depth", "2"), ("spp", "64")])
        .open(&[Instrument::Section {
            x: 0.42,
            y: 0.5,
            zoom: 1.5,
        }])
        .asks(&["max_depth", "min_weight"])
        .follows(|s| {
            let p = s.params;
            let d = p.max_depth;
            if d <= 3 {
                format!(
                    "Every hit on glass spawns a reflected and a refracted ray. Cut at depth {d}: through the front glass the spheres behind turn dark, and the section crosses out each cut branch. Raise Max depth, or prune by Min weight instead."
                )
            } else {
                format!(
                    "At depth {d} the tree reaches through the glass: the spheres behind the front one show in it. Lower Max depth to 2 and they go dark; raise Min weight (now {}) and the faint internal reflections go first.",
                    p.min_weight
                )
            }
        }),
    slide("Reflectance against angle: metal and glass", "metals")
        .set(&[("spp", "32")])
        .open(&[
            Instrument::FresnelPlot {
                metal: Some("gold"),
            },
            Instrument::Workbench {
                angle: 60.0,
                out: false,
            },
        ])
        .says(
            "Gold reflects 97% of red and 32% of blue head-on, more as the angle grows. Glass (the white curve) reflects 4%, rising to 100% only at grazing: on the workbench its reflected ray is as wide as R; drag the angle towards 90°.",
        ),
    slide("Fresnel reflection on the black glazed sphere", "glazed")
        .set(&[("spp", "32"), ("constant_reflectance", "0.1")])
        .compare(Comparison::ConstantFresnel)
        .says(
            "Left of the divider (A): constant reflectance, 10% at every angle. Right (B): Fresnel, 4% head-on rising to 100% at grazing angles: the bright rim that makes it look glazed. Drag the divider across a sphere to see it change.",
        ),
    slide("Fresnel's formulas and Schlick's approximation", "glazed")
        .compare(Comparison::SchlickExact)
        .open(&[
            Instrument::FresnelPlot { metal: None },
            Instrument::Workbench {
                angle: 80.0,
                out: false,
            },
        ])
        .says(
            "Left: Schlick's R0 + (1 − R0)(1 − cos θ)^5. Right: exact (Fs² + Fp²)/2. For n = 1.5 they differ by under 0.01 up to 47°, 0.036 at most (85°), on the bright rims. The workbench writes both at its angle.",
        ),
    slide("The basic ray tracer", "default")
        .uniform()
        .set(&[("spp", "1"), ("pattern", "regular")])
        .follows(|s| {
            let p = s.params;
            format!(
                "One ray through each pixel's centre ({} sample{} per pixel), a shadow ray to the point light: hard shadows, jagged edges. Everything after this slide adds rays: more per pixel, per light, per reflection.",
                p.spp,
                if p.spp == 1 { "" } else { "s" }
            )
        }),
    slide("Antialiasing: 1 against 4 samples", "antialiasing")
        .uniform()
        .compare(Comparison::Supersampling)
        .says(
            "Left: one sample at each pixel's centre: the far checks turn to moiré and the thin rods break into stair steps (aliasing). Right: 4 jittered samples per pixel, averaged (a box filter): smooth edges, and grey where the checks are finer than a pixel.",
        ),
    slide("Regular, random and jittered samples", "antialiasing")
        .uniform()
        .set(&[("spp", "4")])
        .compare(Comparison::RegularRandomJittered)
        .asks(&["spp"])
        .follows(|s| {
            let n = s.params.spp;
            let (nx, ny) = crate::math::rng::grid(n);
            format!(
                "{n} sample{} per pixel each. Left: regular, each cell's centre, alike in every pixel: the far checks alias. Middle: random: clumps and gaps, noisy edges. Right: jittered, one anywhere in each cell of a {nx} × {ny} grid: the least noise. Raise Samples per pixel: regular still aliases.",
                if n == 1 { "" } else { "s" }
            )
        }),
    // The divider through the sphere: each side shows half of it and of its shadow.
    slide("Blurring to improve images", "soft-shadows")
        .compare(Comparison::Blurring)
        .divider(0.39)
        .says(
            "Left: one ray through each pixel's centre, one shadow ray to a point light: jagged edges, a hard shadow. Right: 256 rays per pixel, each to its own point of the pixel and of the area light, averaged: smooth edges, a penumbra. Distribution ray tracing blurs on purpose.",
        ),
    slide("Soft shadows", "soft-shadows")
        .set(&[("spp", "256")])
        .asks(&["light_size"])
        .says(
            "Each sample's shadow ray goes to a different point of the area light: the penumbra. Drag Light size; at 0 the light is a point and shadows are hard.",
        ),
    slide("Glossy reflection", "glossy")
        .set(&[("spp", "512")])
        .says(
            "Reflected rays jittered over a Phong lobe cos^n around the mirror direction: n = 10 to 10,000 from left to right.",
        ),
    slide("Glossy transmission: jitter the refracted ray", "frosted")
        .set(&[("spp", "256")])
        .says(
            "Rough glass: tiny facets spread by roughness α = 0 to 0.6, left to right. Each hit jitters its facet, so the refracted ray is jittered as glossy reflection jitters the reflected one.",
        ),
    slide("Depth of field", "depth-of-field")
        .set(&[("spp", "256")])
        .asks(&["focus_distance", "aperture"])
        .follows(|s| {
            if s.params.aperture <= 0.0 {
                return "A pinhole (aperture 0): every eye ray starts at one point, and everything is sharp. Drag the Aperture to open the lens.".into();
            }
            match sharp_sphere(s) {
                Some((Some(colour), focus)) => format!(
                    "Eye rays from random points on the lens meet on the plane of focus, {focus:.1} units away: the {colour} sphere is sharp, the others blur by their circle of confusion. Try Click to focus, or drag the Aperture."
                ),
                Some((None, focus)) => format!(
                    "Eye rays from random points on the lens meet on the plane of focus, {focus:.1} units away: no sphere lies there, so every sphere blurs by its circle of confusion. Try Click to focus on one."
                ),
                None => "Eye rays from random points on the lens meet on the plane of focus: what lies there is sharp, the rest blurs. Try Click to focus.".into(),
            }
        }),
    // The real lens of `real-lens` wide open at f/2, where its barrel cuts the pupil.
    slide("Thin lens against a real lens", "real-lens")
        .set(&[("spp", "128")])
        .compare(Comparison::ThinReal)
        .asks(&["aperture"])
        .says(
            "Left: the lecture's thin lens, an ideal disk. Right: a 50 mm f/2 double Gauss of the same pupil, six glass elements traced by Snell's law, focused as far: the same framing and focus, but off the axis its barrel cuts the pupil and the corners darken. Drag the Aperture down: they brighten.",
        ),
    // A fifth of the frame: the spheres smear over a fifth of their travel and stay
    // solid enough to see (over the whole frame they were faint ghosts).
    slide("Motion blur", "motion-blur")
        .set(&[("shutter", "0.2")])
        .asks(&["shutter"])
        .follows(|s| {
            let p = s.params;
            format!(
                "Each sample has a time in the shutter interval, open for {:.2} of the frame: the moving spheres smear over their travel in that time, the still one stays sharp. Drag the Shutter interval: 0 freezes them, 1 smears them over the whole frame.",
                p.shutter
            )
        }),
    // The scene's own polariser is vertical.
    // The divider through the glazed sphere: its dark band shows against its glare.
    slide("F_s and F_p: polarisation at Brewster's angle", "polarization")
        .compare(Comparison::Polariser)
        .divider(0.37)
        .says(
            "Reflection polarises: R_s > R_p, and at Brewster's angle (53° on water, 56° on glaze) R_p = 0: the reflected light is all s-polarised. Left: no polariser, glare on the pond. Right: a vertical one cuts it: the tiles show, a dark band crosses the sphere.",
        ),
    slide("Dispersion", "dispersion")
        .asks(&["abbe"])
        .says(
            "n depends on the wavelength: n(λ) = A + B/λ² through n_d and the Abbe number. Through the flint prism a white slit (out of view, left) spreads into its spectrum, blue bent most; reflected in the left face it stays white. Drag the Abbe number (0: none).",
        ),
    slide("What the ray tree misses", "default")
        .set(&[("spp", "64")])
        .compare(Comparison::WhittedPhotons)
        .asks(&["transport"])
        .says(
            "Left, the lecture's tracer: light only along shadow rays and mirror directions, a flat ambient in the shadows. Right, path tracing with photons: sky light in the shadows, the lamp's light through the glass in a caustic at its foot. Light transport > transmissive shadows: tinted, not focused.",
        ),
];
