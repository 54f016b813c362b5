//! The scene file format (TOML), documented in `docs/scenes.md`.
//!
//! Numbers are checked as they are read (finite, in range), so that serde's error carries
//! the span of the offending value and the message can name its line and column.

use super::materials::RawMaterial;
use super::obj::ModelCamera;
use super::objects::{BoxDef, MeshDef, Objects, PlaneDef, QuadDef, SphereDef};
use super::source::{Assets, FsAssets, Source};
use super::values::{Dir, Ior, Length, NonNegative, Pixels, Positive, Rgb, V3};
use super::{Location, Scene, SceneDesc, SceneError, SceneSource};
use crate::camera::Camera;
use crate::light::{Background, Cone, Light, LightShape};
use crate::math::{Color, Vec3};
use crate::params::{ParamError, Params};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// Reads and parses a scene file; OBJ paths resolve against its folder.
pub(crate) fn load_file(path: &Path) -> Result<Scene, SceneError> {
    let label = path.display().to_string();
    let text = crate::scene::input::read_text(path).map_err(|e| {
        SceneError::new(
            Location::file(&label),
            format!("cannot read the scene file: {e}"),
        )
    })?;
    let dir = path
        .parent()
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
    let mut desc = parse(&text, &label, &FsAssets(dir))?;
    desc.name = path
        .file_stem()
        .map_or_else(|| label.clone(), |s| s.to_string_lossy().into_owned());
    let full = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
    Ok(Scene::new(desc, SceneSource::File(full)))
}

/// The `description` of a scene text, without building the scene.
pub fn describe(text: &str) -> Option<String> {
    #[derive(Deserialize)]
    struct Head {
        description: Option<String>,
    }
    toml::from_str::<Head>(text).ok()?.description
}

// ---- The file's shape ----

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    #[serde(default)]
    description: String,
    ambient: Option<Rgb>,
    medium_ior: Option<Ior>,
    image: Option<Spanned<ImageDef>>,
    #[serde(default)]
    params: BTreeMap<Spanned<String>, Spanned<toml::Value>>,
    camera: Spanned<CameraDef>,
    background: Option<Spanned<BackgroundDef>>,
    #[serde(default)]
    material: BTreeMap<String, RawMaterial>,
    #[serde(default)]
    sphere: Vec<Spanned<SphereDef>>,
    #[serde(default)]
    plane: Vec<Spanned<PlaneDef>>,
    #[serde(default)]
    quad: Vec<Spanned<QuadDef>>,
    #[serde(default)]
    r#box: Vec<Spanned<BoxDef>>,
    #[serde(default)]
    mesh: Vec<MeshDef>,
    #[serde(default)]
    point_light: Vec<PointLightDef>,
    #[serde(default)]
    rect_light: Vec<Spanned<RectLightDef>>,
    #[serde(default)]
    disk_light: Vec<DiskLightDef>,
    #[serde(default)]
    sphere_light: Vec<SphereLightDef>,
    #[serde(default)]
    spot_light: Vec<Spanned<SpotLightDef>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ImageDef {
    width: Pixels,
    height: Pixels,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraDef {
    position: V3,
    look_at: V3,
    up: Option<Dir>,
    fov: Option<Spanned<Positive>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BackgroundDef {
    color: Option<Rgb>,
    horizon: Option<Rgb>,
    zenith: Option<Rgb>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PointLightDef {
    position: V3,
    color: Option<Rgb>,
    intensity: NonNegative,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RectLightDef {
    center: V3,
    edge_u: V3,
    edge_v: V3,
    color: Option<Rgb>,
    intensity: NonNegative,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct DiskLightDef {
    center: V3,
    normal: Dir,
    radius: Length,
    color: Option<Rgb>,
    intensity: NonNegative,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SpotLightDef {
    position: V3,
    direction: Dir,
    /// Degrees from the direction beyond which it is dark.
    outer_angle: Positive,
    /// Degrees within which it shines at full intensity (default 0).
    inner_angle: Option<NonNegative>,
    color: Option<Rgb>,
    intensity: NonNegative,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SphereLightDef {
    center: V3,
    radius: Length,
    color: Option<Rgb>,
    intensity: NonNegative,
}

/// A camera's vertical field of view where the file gives none, degrees.
const DEFAULT_FOV: f32 = 45.0;
/// The image size where the file gives none, pixels.
const DEFAULT_SIZE: (u32, u32) = (640, 360);
/// The background where the file gives none: a pale sky gradient.
const DEFAULT_BACKGROUND: Background = Background::Gradient {
    horizon: Color::new(0.8, 0.85, 0.9),
    zenith: Color::new(0.35, 0.5, 0.8),
};

/// Parses scene text into a description; `file` names it in errors.
pub(crate) fn parse(text: &str, file: &str, assets: &dyn Assets) -> Result<SceneDesc, SceneError> {
    parse_with_camera(text, file, assets).map(|(desc, _)| desc)
}

/// [`parse`], and the camera of the first model (a glTF file's) that brings one, placed
/// as its mesh is.
pub(crate) fn parse_with_camera(
    text: &str,
    file: &str,
    assets: &dyn Assets,
) -> Result<(SceneDesc, Option<ModelCamera>), SceneError> {
    let src = Source { file, text };
    let f: SceneFile = toml::from_str(text).map_err(|e| match e.span() {
        Some(span) => src.error(span, e.message()),
        None => SceneError::new(Location::file(file), e.message()),
    })?;
    let mut objects = Objects::new(&src, f.material)?;
    objects.spheres(f.sphere)?;
    objects.planes(f.plane)?;
    objects.quads(f.quad)?;
    objects.boxes(f.r#box)?;
    objects.meshes(f.mesh, assets)?;
    let built = objects.finish()?;
    let lights = LightDefs {
        point: f.point_light,
        rect: f.rect_light,
        disk: f.disk_light,
        sphere: f.sphere_light,
        spot: f.spot_light,
    };
    let (width, height) = match f.image {
        None => DEFAULT_SIZE,
        Some(i) => {
            let span = i.span();
            let i = i.into_inner();
            super::check_size(i.width.0, i.height.0)
                .map_err(|e| src.error(span, format!("[image]: {e}")))?;
            (i.width.0, i.height.0)
        }
    };
    // Checked in the order they are written in a file's table of keys.
    let camera = camera(&src, f.camera)?;
    let params = scene_params(&src, &f.params)?;
    // The file's own lights, then those its models bring.
    let mut all_lights = lights.build(&src)?;
    all_lights.extend(built.lights);
    let desc = SceneDesc {
        name: String::new(),
        description: f.description,
        camera,
        width,
        height,
        params,
        materials: built.materials,
        objects: built.objects,
        lights: all_lights,
        ambient: f.ambient.map_or(Color::ZERO, |a| a.0),
        background: background(&src, f.background)?,
        medium_ior: f.medium_ior.map_or(1.0, |m| m.0),
        warnings: built.warnings,
    };
    Ok((desc, built.camera))
}

/// The `[params]` table: each set as `--set` would, the error at the key (unknown) or at
/// the value (refused).
fn scene_params(
    src: &Source,
    params: &BTreeMap<Spanned<String>, Spanned<toml::Value>>,
) -> Result<Params, SceneError> {
    let mut p = Params::default();
    for (key, value) in params {
        let json = match value.get_ref() {
            // JSON has no NaN or infinity (serde_json would write null, which means
            // "unset"): the word, as `--set ior=nan` gives it, for the table to refuse.
            toml::Value::Float(x) if !x.is_finite() => {
                serde_json::Value::String(x.to_string().to_lowercase())
            }
            v => serde_json::to_value(v).map_err(|e| src.error(value.span(), e.to_string()))?,
        };
        p.set_value(key.get_ref(), json).map_err(|e| {
            let span = if matches!(e, ParamError::Unknown { .. }) {
                key.span()
            } else {
                value.span()
            };
            src.error(span, format!("in [params]: {e}"))
        })?;
    }
    Ok(p)
}

fn background(src: &Source, b: Option<Spanned<BackgroundDef>>) -> Result<Background, SceneError> {
    let Some(b) = b else {
        return Ok(DEFAULT_BACKGROUND);
    };
    let span = b.span();
    match b.into_inner() {
        BackgroundDef {
            color: Some(c),
            horizon: None,
            zenith: None,
        } => Ok(Background::Constant(c.0)),
        BackgroundDef {
            color: None,
            horizon: Some(h),
            zenith: Some(z),
        } => Ok(Background::Gradient {
            horizon: h.0,
            zenith: z.0,
        }),
        _ => Err(src.error(
            span,
            "[background] takes either `color`, or both `horizon` and `zenith`",
        )),
    }
}

fn camera(src: &Source, c: Spanned<CameraDef>) -> Result<Camera, SceneError> {
    let span = c.span();
    let c = c.into_inner();
    let fov = match c.fov {
        Some(fov) if fov.get_ref().0 >= 180.0 => {
            return Err(src.error(fov.span(), "[camera] `fov` must be below 180 degrees"));
        }
        Some(fov) => fov.into_inner().0,
        None => DEFAULT_FOV,
    };
    let up = c.up.map_or(Vec3::Y, |u| u.0);
    let camera = Camera::looking_at(c.position.0, c.look_at.0, up, fov);
    camera
        .check()
        .map_err(|e| src.error(span, format!("[camera] {e}")))?;
    Ok(camera)
}

/// The file's lights, of each shape.
struct LightDefs {
    point: Vec<PointLightDef>,
    rect: Vec<Spanned<RectLightDef>>,
    disk: Vec<DiskLightDef>,
    sphere: Vec<SphereLightDef>,
    spot: Vec<Spanned<SpotLightDef>>,
}

impl LightDefs {
    fn build(self, src: &Source) -> Result<Vec<Light>, SceneError> {
        let intensity =
            |color: Option<Rgb>, i: NonNegative| color.map_or(Color::ONE, |c| c.0) * i.0;
        let light = |shape, intensity| Light {
            shape,
            intensity,
            scale: 1.0,
        };
        let mut lights: Vec<Light> = self
            .point
            .into_iter()
            .map(|l| Light::point(l.position.0, intensity(l.color, l.intensity)))
            .collect();
        for r in self.rect {
            let span = r.span();
            let r = r.into_inner();
            if r.edge_u.0.cross(r.edge_v.0).length_squared() == 0.0 {
                return Err(src.error(
                    span,
                    "rect_light edges `edge_u` and `edge_v` must not be parallel or zero",
                ));
            }
            let shape = LightShape::Rect {
                center: r.center.0,
                edge_u: r.edge_u.0,
                edge_v: r.edge_v.0,
            };
            lights.push(light(shape, intensity(r.color, r.intensity)));
        }
        for d in self.disk {
            let shape = LightShape::Disk {
                center: d.center.0,
                normal: d.normal.0,
                radius: d.radius.0,
            };
            lights.push(light(shape, intensity(d.color, d.intensity)));
        }
        for s in self.sphere {
            let shape = LightShape::Sphere {
                center: s.center.0,
                radius: s.radius.0,
            };
            lights.push(light(shape, intensity(s.color, s.intensity)));
        }
        for spot in self.spot {
            let span = spot.span();
            let s = spot.into_inner();
            let (outer, inner) = (s.outer_angle.0, s.inner_angle.map_or(0.0, |a| a.0));
            if outer > 90.0 || inner >= outer {
                return Err(src.error(
                    span,
                    format!(
                        "spot_light needs 0 ≤ inner_angle < outer_angle ≤ 90 (degrees), not {inner} and {outer}"
                    ),
                ));
            }
            let cone = Cone {
                axis: s.direction.0,
                cos_inner: inner.to_radians().cos(),
                cos_outer: outer.to_radians().cos(),
            };
            lights.push(Light::spot(
                s.position.0,
                cone,
                intensity(s.color, s.intensity),
            ));
        }
        Ok(lights)
    }
}
