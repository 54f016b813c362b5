//! Materials in scene files: the `[material.NAME]` tables, and the material each becomes.

use super::SceneError;
use super::source::Source;
use super::values::{
    Abbe, CheckerScale, Exponent, Ior, NonNegative, Positive, Reflectance, Rgb, Roughness, Unit,
};
use crate::material::{
    Conductor, Dielectric, Diffuse, Emissive, Glazed, Glossy, Material, Mirror, Texture,
};
use crate::math::Color;
use crate::optics::FresnelMode;
use serde::Deserialize;
use std::collections::{BTreeMap, HashMap};
use toml::Spanned;

/// A `[material.NAME]` table as written: each key and value with its place in the file.
pub(super) type RawMaterial = Spanned<BTreeMap<Spanned<String>, Spanned<toml::Value>>>;

/// The material a table defines, an error at the value (or key) it is about. serde reads
/// a table tagged by `type` only after buffering it, which forgets where each value was
/// written; so the table is read whole, and an error is then placed at the `type` when it
/// is unknown, at the one key whose value alone (with the `type`) gives the same error,
/// or at the table's header (a missing key, or keys that clash).
pub(super) fn material_def(src: &Source, raw: RawMaterial) -> Result<MaterialDef, SceneError> {
    type Entry<'a> = (&'a Spanned<String>, &'a Spanned<toml::Value>);
    let read = |entries: &mut dyn Iterator<Item = Entry>| {
        let table: toml::Table = entries
            .map(|(k, v)| (k.get_ref().clone(), v.get_ref().clone()))
            .collect();
        MaterialDef::deserialize(toml::Value::Table(table)).map_err(|e| e.message().to_string())
    };
    let message = match read(&mut raw.get_ref().iter()) {
        Ok(def) => return Ok(def),
        Err(message) => message,
    };
    let is_type = |k: &Spanned<String>| k.get_ref() == "type";
    let same = |keep: &dyn Fn(&Spanned<String>) -> bool| {
        read(&mut raw.get_ref().iter().filter(|(k, _)| keep(k)))
            .err()
            .as_ref()
            == Some(&message)
    };
    let kind = raw.get_ref().iter().find(|(k, _)| is_type(k));
    let span = if same(&is_type) {
        // The `type` alone is wrong (unknown), or the table lacks what it needs.
        match kind {
            Some((_, kind)) if message.starts_with("unknown variant") => kind.span(),
            _ => raw.span(),
        }
    } else {
        let culprit = raw
            .get_ref()
            .iter()
            .filter(|(k, _)| !is_type(k))
            .find(|(key, _)| same(&|k| is_type(k) || k == *key));
        match culprit {
            Some((key, _)) if message.starts_with("unknown field") => key.span(),
            Some((_, value)) => value.span(),
            None => raw.span(),
        }
    };
    Err(src.error(span, message))
}

#[derive(Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub(super) enum MaterialDef {
    Diffuse {
        color: Reflectance,
        checker: Option<CheckerDef>,
        specular: Option<Reflectance>,
        exponent: Option<Positive>,
        emission: Option<Rgb>,
    },
    Mirror {
        reflectance: Reflectance,
    },
    Glossy {
        reflectance: Reflectance,
        exponent: Exponent,
    },
    Conductor(ConductorDef),
    Emissive {
        color: Rgb,
        checker: Option<EmissiveCheckerDef>,
        strength: Option<NonNegative>,
    },
    Dielectric {
        ior: Ior,
        #[serde(default)]
        ior_fixed: bool,
        fresnel: Option<FresnelMode>,
        constant_reflectance: Option<Unit>,
        absorption: Option<Rgb>,
        abbe: Option<Abbe>,
        roughness: Option<Roughness>,
    },
    Glazed {
        color: Reflectance,
        checker: Option<CheckerDef>,
        ior: Option<Ior>,
        #[serde(default)]
        ior_fixed: bool,
        fresnel: Option<FresnelMode>,
        constant_reflectance: Option<Unit>,
    },
}

/// A conductor's keys as written: a measured `metal`, or its own `eta` and `k`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ConductorKeys {
    metal: Option<String>,
    eta: Option<Rgb>,
    k: Option<Rgb>,
    exponent: Option<Exponent>,
}

/// A conductor's optical constants, from a measured metal or given.
#[derive(Deserialize)]
#[serde(try_from = "ConductorKeys")]
pub(super) struct ConductorDef(Conductor);

impl TryFrom<ConductorKeys> for ConductorDef {
    type Error = String;
    fn try_from(c: ConductorKeys) -> Result<Self, String> {
        let (eta, k) = match (c.metal, c.eta, c.k) {
            (Some(name), None, None) => {
                let m = crate::material::find_metal(&name)?;
                (m.eta(), m.k())
            }
            (None, Some(eta), Some(k)) => (eta.0, k.0),
            (Some(_), _, _) => {
                return Err("give either `metal` or `eta` and `k`, not both".into());
            }
            (None, _, _) => {
                return Err(format!(
                    "a conductor needs `metal` ({}) or both `eta` and `k`",
                    crate::material::metal_names()
                ));
            }
        };
        Ok(ConductorDef(Conductor {
            eta,
            k,
            exponent: c.exponent.map(|e| e.0),
        }))
    }
}

/// The checker of an emitter: its second colour is a radiance (any value ≥ 0).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct EmissiveCheckerDef {
    color: Rgb,
    scale: CheckerScale,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CheckerDef {
    color: Reflectance,
    scale: CheckerScale,
}

/// Materials by name, in the order they were added.
#[derive(Default)]
pub(super) struct MaterialTable {
    pub(super) list: Vec<(String, Material)>,
    index: HashMap<String, u32>,
}

impl MaterialTable {
    /// The index of `name`, adding `material` under it if it is new.
    pub(super) fn add(&mut self, name: String, material: Material) -> u32 {
        if let Some(&i) = self.index.get(&name) {
            return i;
        }
        self.list.push((name.clone(), material));
        let i = self.list.len() as u32 - 1;
        self.index.insert(name, i);
        i
    }

    pub(super) fn get(&self, name: &str) -> Option<u32> {
        self.index.get(name).copied()
    }

    /// The defined names, sorted, comma separated.
    pub(super) fn names(&self) -> String {
        let mut names: Vec<_> = self.list.iter().map(|(n, _)| n.as_str()).collect();
        names.sort();
        names.join(", ")
    }
}

pub(super) fn default_material() -> Material {
    Material::Diffuse(Diffuse::solid(Color::splat(0.6)))
}

pub(super) fn material(def: MaterialDef) -> Material {
    match def {
        MaterialDef::Diffuse {
            color,
            checker,
            specular,
            exponent,
            emission,
        } => Material::Diffuse(Diffuse {
            albedo: texture(color, checker),
            specular: specular.map_or(Color::ZERO, |s| s.0),
            exponent: exponent.map_or(20.0, |e| e.0),
            // A glow of 0 is none: path tracing does not aim light samples at it.
            emission: emission
                .filter(|e| e.0.max_element() > 0.0)
                .map(|e| Texture::Solid(e.0)),
        }),
        MaterialDef::Mirror { reflectance } => Material::Mirror(Mirror {
            reflectance: reflectance.0,
        }),
        MaterialDef::Glossy {
            reflectance,
            exponent,
        } => Material::Glossy(Glossy {
            reflectance: reflectance.0,
            exponent: exponent.0,
        }),
        MaterialDef::Conductor(c) => Material::Conductor(c.0),
        MaterialDef::Emissive {
            color,
            checker,
            strength,
        } => {
            let k = strength.map_or(1.0, |s| s.0);
            Material::Emissive(Emissive {
                radiance: match checker {
                    None => Texture::Solid(color.0 * k),
                    Some(c) => Texture::Checker {
                        even: color.0 * k,
                        odd: c.color.0 * k,
                        scale: c.scale.0,
                    },
                },
            })
        }
        MaterialDef::Dielectric {
            ior,
            ior_fixed,
            fresnel,
            constant_reflectance,
            absorption,
            abbe,
            roughness,
        } => {
            let clear = interface(ior.0, ior_fixed, fresnel, constant_reflectance);
            Material::Dielectric(Dielectric {
                absorption: absorption.map_or(clear.absorption, |a| a.0),
                abbe: abbe.map_or(clear.abbe, |a| a.0),
                roughness: roughness.map_or(clear.roughness, |a| a.0),
                ..clear
            })
        }
        MaterialDef::Glazed {
            color,
            checker,
            ior,
            ior_fixed,
            fresnel,
            constant_reflectance,
        } => Material::Glazed(Glazed {
            coat: interface(
                ior.map_or(1.5, |i| i.0),
                ior_fixed,
                fresnel,
                constant_reflectance,
            ),
            base: texture(color, checker),
        }),
    }
}

/// A clear interface of index `ior` with the keys a dielectric and a glaze share.
fn interface(
    ior: f32,
    ior_fixed: bool,
    fresnel: Option<FresnelMode>,
    constant_reflectance: Option<Unit>,
) -> Dielectric {
    let clear = Dielectric::clear(ior);
    Dielectric {
        ior_fixed,
        fresnel: fresnel.unwrap_or(clear.fresnel),
        constant_reflectance: constant_reflectance.map_or(clear.constant_reflectance, |k| k.0),
        ..clear
    }
}

fn texture(color: Reflectance, checker: Option<CheckerDef>) -> Texture {
    match checker {
        None => Texture::Solid(color.0),
        Some(c) => Texture::Checker {
            even: color.0,
            odd: c.color.0,
            scale: c.scale.0,
        },
    }
}
