//! The parameter table: each parameter's name, label, kind and range, unit, slider and
//! documentation, written once. Validation, the window's sliders and tooltips, `--set`,
//! `raylab params` and docs/parameters.md's table all read it.

use super::spec::{Kind, Spec, choice, log_slider, number, slider};

/// The largest samples per pixel accepted.
pub const MAX_SPP: u32 = 1 << 20;
/// The deepest ray tree accepted.
pub const MAX_DEPTH: u32 = 64;
/// The largest Phong exponent accepted.
pub const MAX_PHONG_EXPONENT: f32 = 100_000.0;
/// The indices of refraction accepted, for the parameter and for scene files.
pub const IOR_RANGE: (f32, f32) = (1.0, 3.0);
/// The Abbe numbers accepted, for the parameter and for scene files (0: no dispersion).
pub const ABBE_RANGE: (f32, f32) = (0.0, 100.0);
/// The GGX roughnesses α accepted, for the parameter and for scene files (0: smooth).
pub const ROUGHNESS_RANGE: (f32, f32) = (0.0, 1.0);

/// Every parameter, in the order of [`super::Params`]'s fields.
pub const TABLE: &[Spec] = &[
    Spec {
        name: "spp",
        label: "Samples per pixel",
        kind: Kind::Count {
            min: 1,
            max: MAX_SPP as u64,
        },
        unit: "",
        doc: "samples per pixel",
        explain: "Supersampling: each pixel averages this many samples (a box filter). More samples, less aliasing and noise; the error falls like 1/√n for random samples.",
        slider: log_slider(1.0, 4096.0),
        display_only: false,
    },
    Spec {
        name: "pattern",
        label: "Pattern",
        kind: Kind::Choice(&[
            choice(
                "regular",
                "regular",
                "Sample positions on a fixed grid, each cell's centre: the same in every pixel, so regular structures alias.",
            ),
            choice(
                "random",
                "random",
                "Independent uniform random positions: no aliasing, but clumps and gaps make noise.",
            ),
            choice(
                "jittered",
                "jittered",
                "One random position in each cell of a grid (stratified): random, yet evenly spread.",
            ),
            choice(
                "sobol",
                "sobol",
                "Owen-scrambled Sobol points: evenly spread at every power-of-two count, so each progressive pass stays stratified.",
            ),
        ]),
        unit: "",
        doc: "how samples spread over the pixel, lens, shutter, lights and lobes",
        explain: "How the samples of each pixel are spread over the pixel, and over every other dimension a sample draws: the lens, the shutter, the lights and glossy lobes.",
        slider: None,
        display_only: false,
    },
    Spec {
        name: "seed",
        label: "Seed",
        kind: Kind::Count {
            min: 0,
            max: u64::MAX,
        },
        unit: "",
        doc: "seed of every random number: same seed, same image, bit for bit",
        explain: "The seed of every random number: same seed, same image, bit for bit.",
        slider: None,
        display_only: false,
    },
    Spec {
        name: "noise_target",
        label: "Adaptive: noise target %",
        kind: Kind::WordOrNumber {
            word: "off",
            min: 0.1,
            max: 20.0,
        },
        unit: "%",
        doc: "adaptive sampling: pixels stop receiving samples once they have had their share of an image whose noise is this share of its mean brightness (`off`: every pixel gets every sample)",
        explain: "Adaptive sampling: at 16, 32, 64, ... samples, each pixel's noise is estimated from the spread of its own samples. Samples go where the noise is, each pixel's in proportion to its spread (and its 8 neighbours'), the fewest that bring the image's noise to this share of its mean brightness; the rest of the pixels stop.",
        slider: log_slider(0.25, 10.0),
        display_only: false,
    },
    Spec {
        name: "ior",
        label: "IOR",
        kind: number(IOR_RANGE.0 as f64, IOR_RANGE.1 as f64),
        unit: "",
        doc: "index of refraction of the dielectric and glazed materials (not those with ior_fixed)",
        explain: "Index of refraction n of the glass, water or glaze. Snell's law bends the refracted ray: n1 sin θi = n2 sin θt. Higher n bends more and reflects more (R0 = ((n−1)/(n+1))²).",
        slider: slider(1.0, 2.5),
        display_only: false,
    },
    Spec {
        name: "abbe",
        label: "Abbe number",
        kind: number(ABBE_RANGE.0 as f64, ABBE_RANGE.1 as f64),
        unit: "",
        doc: "Abbe number V_d of the dielectric materials (not those with ior_fixed): dispersion, lower is stronger, 0 none",
        explain: "Dispersion: the index of refraction depends on the wavelength, n(λ) = A + B/λ² (Cauchy) with n_d = IOR at 587.6 nm and V_d = (n_d − 1)/(n_F − n_C). Lower V disperses more: crown glass 64, flint 36, diamond 55 (its fire is its high n). 0: no dispersion.",
        slider: slider(0.0, 100.0),
        display_only: false,
    },
    Spec {
        name: "roughness",
        label: "Roughness α",
        kind: number(ROUGHNESS_RANGE.0 as f64, ROUGHNESS_RANGE.1 as f64),
        unit: "",
        doc: "GGX roughness α of the dielectric materials (not those with ior_fixed): 0 smooth, above 0 frosted",
        explain: "Rough glass: the surface is a field of tiny facets whose normals spread by the GGX distribution of width α. Each hit jitters the facet the ray meets, so both the reflected and the refracted ray are jittered, as glossy reflection jitters the mirror ray: frosted glass. Each child carries its Fresnel share at the facet's angle times the share of facets not shadowed (Smith G1). 0: the smooth interface of the lecture.",
        slider: slider(0.0, 1.0),
        display_only: false,
    },
    Spec {
        name: "fresnel",
        label: "Fresnel",
        kind: Kind::Choice(&[
            choice(
                "exact",
                "exact (Fs, Fp)",
                "The Fresnel equations: R = (Fs² + Fp²)/2, Fs = (n1 cos θi − n2 cos θt)/(n1 cos θi + n2 cos θt), Fp = (n2 cos θi − n1 cos θt)/(n2 cos θi + n1 cos θt).",
            ),
            choice(
                "schlick",
                "Schlick",
                "Schlick's approximation R ≈ R0 + (1 − R0)(1 − cos θ)^5, with θ on the less dense side, so it reaches 1 at the critical angle.",
            ),
            choice(
                "schlick_naive",
                "naive Schlick",
                "Schlick with the incident angle always, as some textbooks write it: from inside it stays near R0 until it jumps to 1 at the critical angle.",
            ),
            choice(
                "constant",
                "constant k",
                "The same reflectance k at every angle: no brighter rim (the lecture's 'constant' black glazed sphere).",
            ),
        ]),
        unit: "",
        doc: "reflectance model of dielectrics and glazes",
        explain: "How the reflectance R of dielectrics and glazes depends on the angle. Every model gives R = 1 under total internal reflection.",
        slider: None,
        display_only: false,
    },
    Spec {
        name: "constant_reflectance",
        label: "k (constant)",
        kind: number(0.0, 1.0),
        unit: "",
        doc: "k of the `constant` Fresnel model",
        explain: "The reflectance of the constant model, at every angle (1 under total internal reflection).",
        slider: slider(0.0, 1.0),
        display_only: false,
    },
    Spec {
        name: "absorption_scale",
        label: "Absorption ×",
        kind: number(0.0, 100.0),
        unit: "",
        doc: "multiplies every dielectric's absorption coefficient σ (0: all clear)",
        explain: "Scales every dielectric's absorption σ. Beer–Lambert: light travelling a distance d inside keeps exp(−σ d).",
        slider: slider(0.0, 5.0),
        display_only: false,
    },
    Spec {
        name: "tree",
        label: "Tree",
        kind: Kind::Choice(&[
            choice(
                "split",
                "Split",
                "At a dielectric, trace both the reflected ray (weight R) and the refracted ray (weight 1 − R): the whole ray tree.",
            ),
            choice(
                "stochastic",
                "Stochastic",
                "Follow one branch, reflected with probability R: one path per sample. Same average, more noise, far fewer rays.",
            ),
        ]),
        unit: "",
        doc: "how the ray tree branches at a dielectric",
        explain: "How the ray tree branches at a dielectric (path tracing follows one path always).",
        slider: None,
        display_only: false,
    },
    Spec {
        name: "transport",
        label: "Light transport",
        kind: Kind::Choice(&[
            choice(
                "whitted",
                "Whitted (the lecture)",
                "The lecture's tracer: a shadow ray stops at the first surface, glass and water included, so they cast black shadows.",
            ),
            choice(
                "transmissive_shadows",
                "transmissive shadows",
                "Shadow rays pass straight through glass and water, keeping 1 − R at each interface and exp(−σ d) inside: tinted shadows. A common trick, and wrong about where the light lands: real glass bends it into caustics.",
            ),
            choice(
                "path",
                "path tracing (reference)",
                "Path tracing with light sampling and multiple importance sampling: each sample follows one path, gathering light at every diffuse or glossy surface and finding lights through glass. Colour bleeding, sky light in the shadows, caustics from area lights and emitters; not from point lights, which a path can never hit. `max_depth` bounds the path; `min_weight` and `tree` do not apply.",
            ),
            choice(
                "photons",
                "path tracing + photons",
                "Path tracing, plus photons shot from the point lights through glass and mirrors and gathered where they land (progressive photon mapping): the caustics a path cannot find, blurred at first, sharper with every pass.",
            ),
        ]),
        unit: "",
        doc: "how light reaches a surface",
        explain: "How light reaches a surface: the lecture's tracer, transmissive shadows, or path tracing (the reference), with or without photons.",
        slider: None,
        display_only: false,
    },
    Spec {
        name: "max_depth",
        label: "Max depth",
        kind: Kind::Count {
            min: 0,
            max: MAX_DEPTH as u64,
        },
        unit: "",
        doc: "pruning the ray tree by depth: the deepest level traced (camera rays are level 0)",
        explain: "Pruning by depth: camera rays are level 0, each reflection or refraction one level deeper. Branches below this level are not traced (black).",
        slider: slider(0.0, 32.0),
        display_only: false,
    },
    Spec {
        name: "min_weight",
        label: "Min weight",
        kind: number(0.0, 1.0),
        unit: "",
        doc: "pruning the ray tree by attenuation: branches whose path weight falls below this are not traced",
        explain: "Pruning by attenuation: a branch whose path weight (the product of the reflectances R or 1 − R above it) falls below this is not traced.",
        slider: log_slider(0.0, 1.0),
        display_only: false,
    },
    Spec {
        name: "light_size",
        label: "Light size",
        kind: number(0.0, 10.0),
        unit: "",
        doc: "scale of the area lights, keeping their power (0: point lights, hard shadows)",
        explain: "Scales every area light, keeping its power. Each sample sends its shadow ray to a different point of the light, so shadows get a penumbra as wide as similar triangles predict. 0: point lights, hard shadows.",
        slider: slider(0.0, 4.0),
        display_only: false,
    },
    Spec {
        name: "phong_exponent",
        label: "Phong exponent",
        kind: number(1.0, MAX_PHONG_EXPONENT as f64),
        unit: "",
        doc: "Phong exponent n of the glossy materials' lobe cos^n",
        explain: "Glossy reflection by jittering the reflected ray over the Phong lobe cos^n α around the mirror direction. Higher n: a tighter lobe, sharper reflections.",
        slider: log_slider(1.0, MAX_PHONG_EXPONENT as f64),
        display_only: false,
    },
    Spec {
        name: "lens",
        label: "Lens",
        kind: Kind::Choice(&[
            choice(
                "thin",
                "thin lens (the lecture)",
                "The lecture's thin lens: an ideal disk that sends every ray from a film point through one point of the plane of focus.",
            ),
            choice(
                "double-gauss-50",
                "double Gauss 50 mm f/2",
                "A real lens of six elements (Tronnier's double Gauss, the classic normal lens), traced surface by surface with Snell's law: its stop, its vignetting, its residual aberrations.",
            ),
            choice(
                "wide-22",
                "wide angle 22 mm",
                "A real wide-angle lens of seven elements (Nakamura): barrel distortion and darker corners.",
            ),
            choice(
                "telephoto-250",
                "telephoto 250 mm f/5.6",
                "A real telephoto of four elements (Sigler): a small image circle, so a wide view darkens towards the corners, and pincushion distortion.",
            ),
            choice(
                "singlet-50",
                "singlet 50 mm",
                "One biconvex lens of N-BK7 behind a stop: the simplest real lens, sharp only near the middle (field curvature, coma).",
            ),
        ]),
        unit: "",
        doc: "the camera's lens: the thin lens, or a real design traced through its glass",
        explain: "The camera's lens. A real design is traced through every glass surface; it is focused at the focus distance by moving it, stopped down to the aperture, and its film sized so it frames what the thin lens frames.",
        slider: None,
        display_only: false,
    },
    Spec {
        name: "lens_dispersion",
        label: "Lens dispersion",
        kind: Kind::Choice(&[
            choice(
                "off",
                "off: every element at n_d",
                "Every element refracts at its n_d: all wavelengths make one image.",
            ),
            choice(
                "on",
                "on: chromatic aberration",
                "Each element refracts at n(λ) from its glass's Abbe number: blue is bent more than red, so colours focus at different depths (axial colour) and image at different sizes (lateral colour: coloured fringes towards the corners).",
            ),
        ]),
        unit: "",
        doc: "whether a real lens's glass disperses (chromatic aberration); the thin lens never does",
        explain: "A real lens's glass bends each wavelength differently (its Abbe number): on, every sample's camera ray is traced through the lens at its own wavelengths, one in each colour channel, and the corners show coloured fringes. The thin lens is ideal: no colour.",
        slider: None,
        display_only: false,
    },
    Spec {
        name: "aperture",
        label: "Aperture",
        kind: number(0.0, 100.0),
        unit: "scene units",
        doc: "lens radius of the thin-lens camera (0: a pinhole); a real lens's entrance pupil radius (from 1/20 of its widest to its widest)",
        explain: "Thin lens: eye rays start at random points on a lens of this radius (scene units) and pass through the plane of focus. 0 is a pinhole: everything sharp. A real lens is stopped down until its entrance pupil has this radius (no wider than it opens, no narrower than 1/20 of that).",
        slider: slider(0.0, 0.5),
        display_only: false,
    },
    Spec {
        name: "focus_distance",
        label: "Focus distance",
        // Four times the largest coordinate: farther than anything a scene can hold.
        kind: Kind::Number {
            min: 0.0,
            max: 4.0 * crate::geometry::MAX_COORDINATE as f64,
            open_min: true,
        },
        unit: "scene units",
        doc: "distance from the lens to the plane in focus (`scene`: the camera's look-at point)",
        explain: "Distance to the plane in focus, along the view direction. Points off it blur into a circle of confusion of diameter 2a|z − s|/s at their depth.",
        slider: log_slider(0.05, 100.0),
        display_only: false,
    },
    Spec {
        name: "shutter_open",
        label: "Shutter opens",
        kind: number(0.0, 1.0),
        unit: "frame time",
        doc: "when the shutter opens (objects move over the frame, time 0 to 1)",
        explain: "When the shutter opens, in frame time (objects move over the frame, time 0 to 1).",
        slider: slider(0.0, 1.0),
        display_only: false,
    },
    Spec {
        name: "shutter",
        label: "Shutter interval",
        kind: number(0.0, 1.0),
        unit: "frame time",
        doc: "how long the shutter stays open, at most 1 − shutter_open (0 freezes motion)",
        explain: "How long the shutter stays open. Each sample's rays get a time in the interval, so moving objects smear over their travel. 0 freezes them.",
        slider: slider(0.0, 1.0),
        display_only: false,
    },
    Spec {
        name: "polarizer",
        label: "Polariser angle °",
        kind: Kind::WordOrNumber {
            word: "none",
            min: 0.0,
            max: 180.0,
        },
        unit: "degrees",
        doc: "a linear polariser in front of the lens, its axis at this angle from the image's horizontal (`none`: no polariser)",
        explain: "A linear polariser in front of the lens passes the light polarised along its axis. Reflection polarises: at Brewster's angle, tan θ = n2/n1, only s (perpendicular to the plane of incidence) is reflected, so the reflection vanishes where the polariser is crossed with s. Unpolarised light passes half.",
        slider: slider(0.0, 180.0),
        display_only: false,
    },
    Spec {
        name: "exposure",
        label: "Exposure (stops)",
        kind: number(-20.0, 20.0),
        unit: "stops",
        doc: "display exposure: pixels are scaled by 2^exposure before display (the render is unchanged)",
        explain: "Displayed brightness: pixels are radiance × 2^exposure, then sRGB. Changes the display only, not the render.",
        slider: slider(-5.0, 5.0),
        display_only: true,
    },
];

/// The entry of parameter `name`.
pub fn spec(name: &str) -> Option<&'static Spec> {
    TABLE.iter().find(|s| s.name == name)
}
