//! The one parameter model: every knob of the renderer, under the names the CLI's
//! `--set name=value`, scene files' `[params]` and snapshot sidecars all use. Each
//! parameter's range, unit and documentation are in `table`.

mod spec;
mod table;

pub use crate::math::Pattern;
use crate::optics::FresnelMode;
pub use crate::optics::lens::{LensDispersion, LensModel};
use serde::{Deserialize, Serialize};
pub use spec::{Choice, Kind, SliderRange, Spec};
pub use table::{
    ABBE_RANGE, IOR_RANGE, MAX_DEPTH, MAX_PHONG_EXPONENT, MAX_SPP, ROUGHNESS_RANGE, TABLE, spec,
};

/// How the ray tree branches at a dielectric.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TreeMode {
    /// Trace both children, weighted R and 1 − R: the lecture's ray tree.
    Split,
    /// Follow one child, reflected with probability R, else refracted: one path per
    /// sample, as distribution and path tracers do. Same mean, more noise, fewer rays.
    Stochastic,
}

/// How light reaches a surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Transport {
    /// The lecture's tracer: shadow rays stop at the first surface, glass included.
    Whitted,
    /// Shadow rays pass straight through dielectrics, attenuated by 1 − R at each interface
    /// and by Beer–Lambert inside: tinted, see-through shadows, though not where real glass
    /// would focus the light.
    TransmissiveShadows,
    /// Unidirectional path tracing: light sampled at every diffuse or glossy vertex and
    /// found by the path itself, the two weighed by multiple importance sampling; diffuse
    /// interreflection, and caustics from area lights and emitting surfaces. The reference
    /// the lecture's tracer is compared with.
    Path,
    /// Path tracing, plus the caustics of point lights (which no path can find) by
    /// progressive photon mapping: photons shot from each point light through mirrors and
    /// glass are gathered where the path meets a diffuse surface, within a radius that
    /// shrinks pass by pass.
    Photons,
}

impl Transport {
    /// Whether each sample follows one path (path tracing, with or without photons)
    /// rather than the ray tree.
    pub fn traces_paths(self) -> bool {
        matches!(self, Transport::Path | Transport::Photons)
    }
}

/// Every parameter that shapes the image (and the display exposure).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Params {
    /// Target samples per pixel.
    pub spp: u32,
    /// How the samples of a pixel are spread over the image, the lens, the shutter, the
    /// lights and glossy lobes.
    pub pattern: Pattern,
    /// Seed of every random number: the same seed gives the same image, bit for bit.
    pub seed: u64,
    /// Adaptive sampling's noise target, in percent of the image's mean displayed
    /// brightness: pixels stop receiving samples once they have had their share of an
    /// image with that noise (see `render::adaptive`). `None`: off, every pixel gets
    /// every sample.
    #[serde(with = "noise_target_value")]
    pub noise_target: Option<f32>,
    /// Index of refraction of every dielectric and glazed material (except those with
    /// `ior_fixed`); `None` keeps each material's own. 1.0 to 3.0.
    #[serde(deserialize_with = "real::optional")]
    pub ior: Option<f32>,
    /// Abbe number V_d of every dielectric (except those with `ior_fixed`): 0 is no
    /// dispersion; `None` keeps each material's own. 0 to 100.
    #[serde(deserialize_with = "real::optional")]
    pub abbe: Option<f32>,
    /// GGX roughness α of every dielectric's interface (except those with `ior_fixed`):
    /// 0 is smooth, above 0 the reflected and refracted rays are jittered over facets
    /// (frosted glass); `None` keeps each material's own. 0 to 1.
    #[serde(deserialize_with = "real::optional")]
    pub roughness: Option<f32>,
    /// Reflectance model of every dielectric and glazed material; `None` keeps each
    /// material's own.
    pub fresnel: Option<FresnelMode>,
    /// The constant reflectance k of the `constant` Fresnel mode; `None` keeps each
    /// material's own.
    #[serde(deserialize_with = "real::optional")]
    pub constant_reflectance: Option<f32>,
    /// Multiplies the absorption coefficient σ of every dielectric (0: all clear).
    #[serde(deserialize_with = "real::required")]
    pub absorption_scale: f32,
    /// Split (the full ray tree) or stochastic (one branch per hit).
    pub tree: TreeMode,
    /// How light reaches a surface: the lecture's tracer, transmissive shadows, or path
    /// tracing.
    pub transport: Transport,
    /// Pruning by depth: the deepest ray-tree level traced (camera rays are level 0).
    pub max_depth: u32,
    /// Pruning by attenuation: a branch whose path weight (the product of the
    /// reflectances above it, largest channel) falls below this is not traced.
    #[serde(deserialize_with = "real::required")]
    pub min_weight: f32,
    /// Scale of every area light (1: as in the scene; 0: a point light, hard shadows).
    /// Each light keeps its power: a larger light is dimmer per unit area.
    #[serde(deserialize_with = "real::required")]
    pub light_size: f32,
    /// Phong exponent of every glossy material: higher is sharper; `None` keeps each
    /// material's own.
    #[serde(deserialize_with = "real::optional")]
    pub phong_exponent: Option<f32>,
    /// The camera's lens: the thin lens, or a real design traced through its glass.
    pub lens: LensModel,
    /// Whether a real lens's glass disperses (chromatic aberration); the thin lens never
    /// does.
    pub lens_dispersion: LensDispersion,
    /// Lens radius of the thin-lens camera, in scene units; 0 is a pinhole. A real lens is
    /// stopped down to an entrance pupil of this radius.
    #[serde(deserialize_with = "real::required")]
    pub aperture: f32,
    /// Distance from the lens to the plane in focus; `None` focuses on the camera's
    /// `look_at` point.
    #[serde(deserialize_with = "real::optional")]
    pub focus_distance: Option<f32>,
    /// When the shutter opens, in frame time (objects move over the frame, time 0 to 1).
    #[serde(deserialize_with = "real::required")]
    pub shutter_open: f32,
    /// How long the shutter stays open, in frame time; 0 freezes motion.
    #[serde(deserialize_with = "real::required")]
    pub shutter: f32,
    /// A linear polariser in front of the lens, its transmission axis at this angle
    /// (degrees) from the image's horizontal; `None`: no polariser. 0 to 180.
    #[serde(with = "polarizer_value")]
    pub polarizer: Option<f32>,
    /// Display exposure in stops: pixel values are scaled by 2^exposure before display.
    #[serde(deserialize_with = "real::required")]
    pub exposure: f32,
}

/// Real parameters as read from any file or option: a number an f32 holds. A number
/// beyond f32's range (`1e39`) would otherwise become infinity silently, pass the range
/// checks (which see it written back as `null`) and render something else than was asked.
mod real {
    use serde::{Deserialize, Deserializer};

    /// `x` as an f32, if it is finite there.
    pub fn narrow<E: serde::de::Error>(x: f64) -> Result<f32, E> {
        let narrow = x as f32;
        if narrow.is_finite() {
            Ok(narrow)
        } else {
            Err(E::custom(format!(
                "must be a finite number of at most {:e} in size, got {x:e}",
                f32::MAX
            )))
        }
    }

    pub fn required<'de, D: Deserializer<'de>>(d: D) -> Result<f32, D::Error> {
        narrow(f64::deserialize(d)?)
    }

    pub fn optional<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f32>, D::Error> {
        Option::<f64>::deserialize(d)?.map(narrow).transpose()
    }
}

/// A parameter that is a word meaning "off" or a number, as JSON: written as the f32 (its
/// shortest form) or the word, read as f64 (checked as every real is) or the word.
mod word_or_real {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    #[derive(Serialize)]
    #[serde(untagged)]
    enum Value<'w> {
        Number(f32),
        Word(&'w str),
    }

    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Read {
        Number(f64),
        Word(String),
    }

    pub fn serialize<S: Serializer>(v: &Option<f32>, word: &str, s: S) -> Result<S::Ok, S::Error> {
        match v {
            Some(x) => Value::Number(*x),
            None => Value::Word(word),
        }
        .serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(
        d: D,
        word: &str,
        what: &str,
    ) -> Result<Option<f32>, D::Error> {
        match Option::<Read>::deserialize(d)? {
            Some(Read::Number(x)) => super::real::narrow(x).map(Some),
            Some(Read::Word(w)) if w == word => Ok(None),
            None => Ok(None),
            Some(Read::Word(w)) => Err(serde::de::Error::custom(format!(
                "must be {word} or {what}, got \"{w}\""
            ))),
        }
    }
}

/// `polarizer`: `"none"` or an angle.
mod polarizer_value {
    use serde::{Deserializer, Serializer};

    pub fn serialize<S: Serializer>(v: &Option<f32>, s: S) -> Result<S::Ok, S::Error> {
        super::word_or_real::serialize(v, "none", s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f32>, D::Error> {
        super::word_or_real::deserialize(d, "none", "an angle in degrees")
    }
}

/// `noise_target`: `"off"` or a percentage.
mod noise_target_value {
    use serde::{Deserializer, Serializer};

    pub fn serialize<S: Serializer>(v: &Option<f32>, s: S) -> Result<S::Ok, S::Error> {
        super::word_or_real::serialize(v, "off", s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f32>, D::Error> {
        super::word_or_real::deserialize(d, "off", "a percentage")
    }
}

impl Default for Params {
    fn default() -> Self {
        Params {
            spp: 16,
            pattern: Pattern::Sobol,
            seed: 0,
            noise_target: None,
            ior: None,
            abbe: None,
            roughness: None,
            fresnel: None,
            constant_reflectance: None,
            absorption_scale: 1.0,
            tree: TreeMode::Split,
            transport: Transport::Whitted,
            max_depth: 8,
            min_weight: 0.001,
            light_size: 1.0,
            phong_exponent: None,
            lens: LensModel::Thin,
            lens_dispersion: LensDispersion::Off,
            aperture: 0.0,
            focus_distance: None,
            shutter_open: 0.0,
            shutter: 0.0,
            polarizer: None,
            exposure: 0.0,
        }
    }
}

/// A parameter that cannot be set.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ParamError {
    /// No parameter has this name.
    #[error("unknown parameter `{name}` (known: {known})")]
    Unknown {
        /// The name given.
        name: String,
        /// The known names, comma separated.
        known: String,
    },
    /// The value has the wrong type or is out of range.
    #[error("bad value for `{name}`: {message}")]
    Invalid {
        /// The parameter.
        name: String,
        /// What is wrong.
        message: String,
    },
    /// Not of the form name=value.
    #[error("expected NAME=VALUE, got `{0}`")]
    Syntax(String),
}

/// A `--set` value as JSON: `scene` is null (left to the scene), numbers are numbers,
/// anything else a string.
fn value_json(value: &str) -> serde_json::Value {
    let value = value.trim();
    if value == "scene" {
        serde_json::Value::Null
    } else {
        serde_json::from_str(value).unwrap_or_else(|_| serde_json::Value::String(value.to_string()))
    }
}

impl Params {
    /// The names of all parameters, in the table's order.
    pub fn names() -> Vec<String> {
        TABLE.iter().map(|s| s.name.to_string()).collect()
    }

    /// Sets parameter `name` from the text `value`, as typed after `--set name=`.
    /// Numbers, `true`/`false` and bare words (for choices) are accepted; `scene` (or
    /// `null`) returns an override such as `ior` to the scene's own values.
    pub fn set(&mut self, name: &str, value: &str) -> Result<(), ParamError> {
        self.set_value(name, value_json(value))
    }

    /// Parses `name=value` and sets it.
    pub fn set_assignment(&mut self, assignment: &str) -> Result<(), ParamError> {
        self.set_all(&[assignment])
    }

    /// Parses every `name=value` and sets them together, then checks the result: so
    /// `shutter_open=0.5 shutter=0.5` is valid in either order, whatever the shutter was
    /// before. On error nothing changes.
    pub fn set_all(&mut self, assignments: &[impl AsRef<str>]) -> Result<(), ParamError> {
        let values = assignments
            .iter()
            .map(|a| {
                let a = a.as_ref();
                let (name, value) = a
                    .split_once('=')
                    .ok_or_else(|| ParamError::Syntax(a.to_string()))?;
                Ok((name.trim(), value_json(value)))
            })
            .collect::<Result<Vec<_>, ParamError>>()?;
        *self = self.with_values(values)?;
        Ok(())
    }

    /// Sets parameter `name` to a JSON value, checking its type and range. On error
    /// nothing changes.
    pub fn set_value(&mut self, name: &str, value: serde_json::Value) -> Result<(), ParamError> {
        *self = self.with_values([(name, value)])?;
        Ok(())
    }

    /// The defaults with every parameter of `given` (a sidecar's `params` object) set, each
    /// checked as `--set` checks it: a value out of range or beyond f32 is named by its
    /// parameter, with the table's range.
    pub fn from_json(
        given: &serde_json::Map<String, serde_json::Value>,
    ) -> Result<Params, ParamError> {
        Params::default().with_values(given.iter().map(|(k, v)| (k.as_str(), v.clone())))
    }

    /// These parameters with `values` set, checked once all are in place. Each value is
    /// checked against its own entry in the table first, so an error names the parameter
    /// whose value it is, whatever else is set with it.
    fn with_values<'n>(
        &self,
        values: impl IntoIterator<Item = (&'n str, serde_json::Value)>,
    ) -> Result<Params, ParamError> {
        let mut map = self.to_map();
        for (name, value) in values {
            let (Some(slot), Some(spec)) = (map.get_mut(name), spec(name)) else {
                return Err(ParamError::Unknown {
                    name: name.to_string(),
                    known: Params::names().join(", "),
                });
            };
            let invalid = |message| ParamError::Invalid {
                name: name.to_string(),
                message,
            };
            spec.check(&value).map_err(invalid)?;
            // Through the field's own type: a value the table allows but the field cannot
            // hold (`null` for a parameter the scene has no value of) is refused here.
            let mut alone = serde_json::Map::new();
            alone.insert(name.to_string(), value.clone());
            serde_json::from_value::<Params>(serde_json::Value::Object(alone))
                .map_err(|e| invalid(e.to_string()))?;
            *slot = value;
        }
        let updated: Params =
            serde_json::from_value(serde_json::Value::Object(map)).map_err(|e| {
                ParamError::Invalid {
                    name: "params".into(),
                    message: e.to_string(),
                }
            })?;
        updated.validate()?;
        Ok(updated)
    }

    /// Whether `other` renders the same image: every parameter equal but the display
    /// exposure, which only changes how the image is shown.
    pub fn same_image(&self, other: &Params) -> bool {
        let display_only = |p: &Params| Params {
            exposure: 0.0,
            ..p.clone()
        };
        display_only(self) == display_only(other)
    }

    /// Checks every value against the table, and that the shutter closes within the
    /// frame; the first violation is the error.
    pub fn validate(&self) -> Result<(), ParamError> {
        let map = self.to_map();
        for spec in TABLE {
            let value = map.get(spec.name).unwrap_or(&serde_json::Value::Null);
            spec.check(value).map_err(|message| ParamError::Invalid {
                name: spec.name.to_string(),
                message,
            })?;
        }
        if self.shutter_open + self.shutter > 1.0 + 1e-6 {
            return Err(ParamError::Invalid {
                name: "shutter".into(),
                message: format!(
                    "must be at most 1 − shutter_open = {} (frame time), got {}",
                    1.0 - self.shutter_open,
                    self.shutter
                ),
            });
        }
        Ok(())
    }

    /// Every parameter by name, as JSON values (null: left to the scene).
    fn to_map(&self) -> serde_json::Map<String, serde_json::Value> {
        match serde_json::to_value(self) {
            Ok(serde_json::Value::Object(map)) => map,
            _ => serde_json::Map::new(),
        }
    }

    /// Parameter `name`'s value as `--set` would take it (`scene` for an override left to
    /// the scene).
    pub fn value_text(&self, name: &str) -> Option<String> {
        self.to_map().get(name).map(|v| match v {
            serde_json::Value::Null => "scene".to_string(),
            serde_json::Value::String(s) => s.clone(),
            serde_json::Value::Number(n) if n.is_f64() => {
                // Real parameters are f32: their shortest form, not the widened f64's.
                n.as_f64()
                    .map_or_else(|| n.to_string(), |x| (x as f32).to_string())
            }
            other => other.to_string(),
        })
    }
}

/// The choices of parameter `name` as values of `T`, its field's type in [`Params`], each
/// with its entry, in the table's order (none if `name` is no choice of `T`).
pub fn choices<T: serde::de::DeserializeOwned>(name: &str) -> Vec<(T, &'static Choice)> {
    let Some(Kind::Choice(all)) = spec(name).map(|s| s.kind) else {
        return Vec::new();
    };
    all.iter()
        .filter_map(|c| {
            let value = serde_json::from_value(serde_json::Value::String(c.word.into()));
            value.ok().map(|v| (v, c))
        })
        .collect()
}

/// The entry of `value`, a value of the choice parameter `name`.
pub fn choice_of<T: Serialize>(name: &str, value: &T) -> Option<&'static Choice> {
    let word = serde_json::to_value(value).ok()?;
    match spec(name)?.kind {
        Kind::Choice(all) => all.iter().find(|c| word.as_str() == Some(c.word)),
        _ => None,
    }
}

/// The table as Markdown, as the documentation shows it: name, default, valid values,
/// meaning (with what each choice does).
pub fn markdown_table() -> String {
    let defaults = Params::default();
    let mut out = String::from("| name | default | values | meaning |\n|---|---|---|---|\n");
    for s in TABLE {
        let default = defaults.value_text(s.name).unwrap_or_default();
        let mut meaning = s.doc.to_string();
        if let Kind::Choice(choices) = s.kind {
            let each: Vec<String> = choices
                .iter()
                .map(|c| format!("`{}`: {}", c.word, c.explain))
                .collect();
            meaning = format!("{meaning}. {}", each.join(" "));
        }
        out += &format!(
            "| `{}` | `{default}` | {} | {meaning} |\n",
            s.name,
            s.range_text(),
        );
    }
    out
}

/// The table as aligned plain text, for `raylab params`.
pub fn text_table() -> String {
    let defaults = Params::default();
    let rows: Vec<[String; 4]> =
        std::iter::once(["name", "default", "values", "meaning"].map(String::from))
            .chain(TABLE.iter().map(|s| {
                [
                    s.name.to_string(),
                    defaults.value_text(s.name).unwrap_or_default(),
                    s.range_text(),
                    s.doc.to_string(),
                ]
            }))
            .collect();
    let width = |k: usize| rows.iter().map(|r| r[k].chars().count()).max().unwrap_or(0);
    let (w0, w1, w2) = (width(0), width(1), width(2));
    rows.iter()
        .map(|[a, b, c, d]| format!("{a:w0$}  {b:w1$}  {c:w2$}  {d}\n"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_by_name_parses_and_validates() {
        let mut p = Params::default();
        p.set("max_depth", "3").unwrap();
        p.set_assignment("min_weight=0.01").unwrap();
        p.set("seed", "42").unwrap();
        assert_eq!((p.max_depth, p.min_weight, p.seed), (3, 0.01, 42));
        let before = p.clone();
        assert!(matches!(p.set("spp", "0"), Err(ParamError::Invalid { .. })));
        assert!(matches!(
            p.set("spp", "many"),
            Err(ParamError::Invalid { .. })
        ));
        assert!(matches!(
            p.set("min_weight", "2"),
            Err(ParamError::Invalid { .. })
        ));
        assert!(matches!(
            p.set("exposure", "NaN"),
            Err(ParamError::Invalid { .. })
        ));
        assert!(matches!(
            p.set("nope", "1"),
            Err(ParamError::Unknown { .. })
        ));
        assert!(matches!(
            p.set_assignment("spp"),
            Err(ParamError::Syntax(_))
        ));
        assert_eq!(p, before, "a failed set changes nothing");
    }

    #[test]
    fn the_table_names_every_field_in_order() {
        // Serialised, the fields come in their declaration order.
        let text = serde_json::to_string(&Params::default()).unwrap();
        let declared: Vec<&str> = text
            .trim_matches(|c| c == '{' || c == '}')
            .split(',')
            .filter_map(|kv| kv.split_once(':'))
            .map(|(k, _)| k.trim_matches('"'))
            .collect();
        assert_eq!(
            declared,
            Params::names(),
            "the table lists Params's fields, in their order"
        );
    }
}
