//! The parameter table: each parameter's name, label, kind and range, unit, slider and
//! documentation, written once. Validation, the window's sliders and tooltips, `--set`,
//! `raylab params` and README's table all read it.

/// What values a parameter takes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// A whole number from `min` to `max`.
    Count {
        /// Smallest value.
        min: u64,
        /// Largest value.
        max: u64,
    },
    /// A real number from `min` to `max` (above `min`, if `open_min`).
    Number {
        /// Smallest value.
        min: f64,
        /// Largest value.
        max: f64,
        /// The value must exceed `min`.
        open_min: bool,
    },
    /// One of these words.
    Choice(&'static [&'static str]),
    /// A word meaning "off", or a real number from `min` to `max`.
    WordOrNumber {
        /// The word.
        word: &'static str,
        /// Smallest value.
        min: f64,
        /// Largest value.
        max: f64,
    },
}

/// The range a slider offers, within the valid range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliderRange {
    /// Left end.
    pub min: f64,
    /// Right end.
    pub max: f64,
    /// Logarithmic spacing.
    pub log: bool,
}

/// One parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spec {
    /// Its name in `--set`, scene files' `[params]` and sidecars.
    pub name: &'static str,
    /// Its label in the window.
    pub label: &'static str,
    /// Its values.
    pub kind: Kind,
    /// Its unit, if it has one.
    pub unit: &'static str,
    /// What it does, in one line.
    pub doc: &'static str,
    /// The lecture's explanation, for the window's tooltip.
    pub explain: &'static str,
    /// The window's slider, if it has one.
    pub slider: Option<SliderRange>,
    /// It changes only how the image is shown, not the render.
    pub display_only: bool,
}

const fn slider(min: f64, max: f64) -> Option<SliderRange> {
    Some(SliderRange {
        min,
        max,
        log: false,
    })
}

const fn log_slider(min: f64, max: f64) -> Option<SliderRange> {
    Some(SliderRange {
        min,
        max,
        log: true,
    })
}

const fn number(min: f64, max: f64) -> Kind {
    Kind::Number {
        min,
        max,
        open_min: false,
    }
}

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
        kind: Kind::Choice(&["regular", "random", "jittered", "sobol"]),
        unit: "",
        doc: "how samples spread over the pixel, lens, shutter, lights and lobes",
        explain: "Regular: a fixed grid (aliases). Random: independent (clumps and gaps). Jittered: one random sample per grid cell. Sobol: evenly spread at every power-of-two count.",
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
        name: "fresnel",
        label: "Fresnel",
        kind: Kind::Choice(&["exact", "schlick", "schlick_naive", "constant"]),
        unit: "",
        doc: "reflectance model of dielectrics and glazes: exact (F_s, F_p), Schlick, naive Schlick or constant k",
        explain: "How the reflectance R of dielectrics and glazes depends on the angle.",
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
        kind: Kind::Choice(&["split", "stochastic"]),
        unit: "",
        doc: "`split` traces reflected and refracted rays weighted R and 1 − R (the ray tree); `stochastic` follows one, chosen with probability R",
        explain: "Split: trace both children of a dielectric hit, weighted R and 1 − R. Stochastic: follow one, reflected with probability R: same average, more noise, far fewer rays.",
        slider: None,
        display_only: false,
    },
    Spec {
        name: "transport",
        label: "Light transport",
        kind: Kind::Choice(&["whitted", "transmissive_shadows", "path", "photons"]),
        unit: "",
        doc: "how light reaches a surface: `whitted`, the lecture's tracer (shadow rays stop at glass); `transmissive_shadows`, shadow rays pass straight through dielectrics, attenuated by 1 − R per interface and by absorption; `path`, path tracing with light sampling and multiple importance sampling (interreflection, caustics from area lights and emitters; `max_depth` bounds the path, `min_weight` and `tree` do not apply); `photons`, path tracing plus the caustics of point lights by progressive photon mapping",
        explain: "Whitted: a shadow ray stops at the first surface, glass included, so glass and water cast black shadows. Transmissive shadows: the shadow ray passes straight through dielectrics, keeping 1 − R at each interface and exp(−σ d) inside: tinted shadows. A common trick, and wrong about where the light lands: real glass bends it into caustics. Path: each sample follows one path, gathering light at every diffuse or glossy surface and finding lights through glass: colour bleeding, sky light in the shadows, caustics from area lights (not from point lights, which a path can never hit). Photons: path tracing, plus photons shot from the point lights through glass and mirrors, gathered where they land: the point light's caustic, blurred at first, sharpening pass by pass.",
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
        name: "aperture",
        label: "Aperture",
        kind: number(0.0, 100.0),
        unit: "scene units",
        doc: "lens radius of the thin-lens camera (0: a pinhole)",
        explain: "Thin lens: eye rays start at random points on a lens of this radius (scene units) and pass through the plane of focus. 0 is a pinhole: everything sharp.",
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

impl Spec {
    /// The valid values, as words: "1 to 1048576", "0 to 1 frame time", "> 0 scene units",
    /// "split, stochastic".
    pub fn range_text(&self) -> String {
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        match self.kind {
            Kind::Count { min, max } if max == u64::MAX => format!("{min} or more{unit}"),
            Kind::Count { min, max } => format!("{min} to {max}{unit}"),
            Kind::Number {
                min,
                open_min: true,
                max,
                ..
            } if max.is_infinite() => format!("> {min}{unit}"),
            Kind::Number {
                min,
                open_min: true,
                max,
            } => format!("> {min}, ≤ {max}{unit}"),
            Kind::Number { min, max, .. } => format!("{min} to {max}{unit}"),
            Kind::Choice(words) => words.join(", "),
            Kind::WordOrNumber { word, min, max } => format!("{word}, or {min} to {max}{unit}"),
        }
    }

    /// The window's tooltip: the explanation, then the valid values.
    pub fn tooltip(&self) -> String {
        format!(
            "{}\n\nParameter {}: {}.",
            self.explain,
            self.name,
            self.range_text()
        )
    }

    /// Checks `value` (a JSON number or string; null is an override left to the scene).
    pub(super) fn check(&self, value: &serde_json::Value) -> Result<(), String> {
        let out_of_range = || format!("must be {}, got {value}", self.range_words());
        match (self.kind, value) {
            (_, serde_json::Value::Null) => Ok(()),
            (Kind::Count { min, max }, v) => match v.as_u64() {
                Some(n) if (min..=max).contains(&n) => Ok(()),
                _ => Err(out_of_range()),
            },
            (Kind::Number { min, max, open_min }, v) => match v.as_f64() {
                Some(x) if x.is_finite() && x <= max && (x > min || (!open_min && x == min)) => {
                    Ok(())
                }
                _ => Err(out_of_range()),
            },
            (Kind::Choice(words), v) => match v.as_str() {
                Some(w) if words.contains(&w) => Ok(()),
                _ => Err(format!("must be one of {}, got {value}", words.join(", "))),
            },
            (Kind::WordOrNumber { word, min, max }, v) => match (v.as_str(), v.as_f64()) {
                (Some(w), _) if w == word => Ok(()),
                (_, Some(x)) if x.is_finite() && (min..=max).contains(&x) => Ok(()),
                _ => Err(format!(
                    "must be {word} or a number from {min} to {max}, got {value}"
                )),
            },
        }
    }

    fn range_words(&self) -> String {
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" ({})", self.unit)
        };
        match self.kind {
            Kind::Number {
                min,
                max,
                open_min: true,
            } if max.is_infinite() => format!("greater than {min}{unit}"),
            Kind::Number {
                min,
                max,
                open_min: true,
            } => format!("greater than {min} and at most {max}{unit}"),
            Kind::Count { max, min } if max == u64::MAX => format!("at least {min}"),
            Kind::Count { min, max } => format!("between {min} and {max}{unit}"),
            Kind::Number { min, max, .. } => format!("between {min} and {max}{unit}"),
            Kind::Choice(words) => words.join(", "),
            Kind::WordOrNumber { word, min, max } => {
                format!("{word} or between {min} and {max}{unit}")
            }
        }
    }
}
