//! The scene file format (TOML), documented in `scenes/README.md`.
//!
//! Numbers are checked as they are read (finite, in range), so that serde's error carries
//! the span of the offending value and the message can name its line and column.

use super::gltf::load_gltf;
use super::materials::{MaterialDef, MaterialTable, default_material, material};
use super::obj::load_obj;
use super::values::{Dir, Ior, Length, NonNegative, Pixels, Positive, Rgb, V3};
use super::{Location, Object, Scene, SceneDesc, SceneError, SceneSource};
use crate::camera::Camera;
use crate::geometry::{Mesh, Plane, Quad, Shape, Sphere};
use crate::light::{Background, Light, LightShape};
use crate::math::{Color, Vec3};
use crate::params::{ParamError, Params};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// Where a scene's model files (OBJ and MTL, glTF and its buffers) come from.
pub(crate) trait Assets {
    /// The bytes of the file at `rel`, relative to the scene.
    fn read(&self, rel: &str) -> Result<Vec<u8>, String>;
    /// How to name `rel` in messages.
    fn label(&self, rel: &str) -> String;
}

/// Files beside the scene file.
pub(crate) struct FsAssets(pub PathBuf);

impl Assets for FsAssets {
    fn read(&self, rel: &str) -> Result<Vec<u8>, String> {
        let path = self.0.join(rel);
        // Models and their binary buffers may be large; text beside them may not.
        let is_mesh =
            super::input::extension(&path).is_some_and(|e| super::is_model(&e) || e == "bin");
        let limit = if is_mesh {
            crate::scene::input::MAX_MESH_BYTES
        } else {
            crate::scene::input::MAX_TEXT_BYTES
        };
        crate::scene::input::read_limited(&path, limit).map_err(|e| e.to_string())
    }
    fn label(&self, rel: &str) -> String {
        self.0.join(rel).display().to_string()
    }
}

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
    material: BTreeMap<String, MaterialDef>,
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
struct SphereDef {
    name: Option<String>,
    center: V3,
    radius: Length,
    velocity: Option<V3>,
    material: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PlaneDef {
    name: Option<String>,
    point: V3,
    normal: Dir,
    material: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct QuadDef {
    name: Option<String>,
    corner: V3,
    edge_u: V3,
    edge_v: V3,
    material: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BoxDef {
    name: Option<String>,
    min: V3,
    max: V3,
    rotate: Option<V3>,
    velocity: Option<V3>,
    material: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MeshDef {
    name: Option<String>,
    file: Spanned<String>,
    material: Option<Spanned<String>>,
    scale: Option<Length>,
    rotate: Option<V3>,
    translate: Option<V3>,
    velocity: Option<V3>,
    #[serde(default = "yes")]
    smooth: bool,
}

fn yes() -> bool {
    true
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
struct SphereLightDef {
    center: V3,
    radius: Length,
    color: Option<Rgb>,
    intensity: NonNegative,
}

/// The refusal of geometry that reaches beyond what the renderer handles.
fn beyond_limits(what: &str) -> String {
    format!(
        "{what} reaches beyond ±{:e} scene units, the largest coordinate raylab handles",
        crate::geometry::MAX_COORDINATE
    )
}

/// The material objects get when they name none: a mid-grey diffuse.
const DEFAULT_MATERIAL: &str = "default";

/// Parses scene text into a description; `file` names it in errors.
pub(crate) fn parse(text: &str, file: &str, assets: &dyn Assets) -> Result<SceneDesc, SceneError> {
    let at = |span: std::ops::Range<usize>| Location::at_offset(file, text, span.start);
    let f: SceneFile = toml::from_str(text).map_err(|e| {
        let loc = e.span().map_or_else(|| Location::file(file), at);
        SceneError::new(loc, e.message())
    })?;

    let mut materials = MaterialTable::default();
    for (name, def) in f.material {
        materials.add(name, material(def));
    }
    let resolve = |name: &Option<Spanned<String>>, materials: &mut MaterialTable| match name {
        None => Ok(materials.add(DEFAULT_MATERIAL.to_string(), default_material())),
        Some(s) => materials.get(s.get_ref()).ok_or_else(|| {
            SceneError::new(
                at(s.span()),
                format!(
                    "unknown material `{}` (defined: {})",
                    s.get_ref(),
                    materials.names()
                ),
            )
        }),
    };

    let mut objects = Vec::new();
    let name_or = |name: Option<String>, kind: &str, n: usize| {
        name.unwrap_or_else(|| format!("{kind} {}", n + 1))
    };
    // Where each object is written, for the check of its extent below.
    let mut spans = Vec::new();
    for (n, s) in f.sphere.into_iter().enumerate() {
        spans.push(s.span());
        let s = s.into_inner();
        let material = resolve(&s.material, &mut materials)?;
        objects.push(Object {
            name: name_or(s.name, "sphere", n),
            shape: Shape::Sphere(Sphere {
                velocity: s.velocity.map_or(Vec3::ZERO, |v| v.0),
                ..Sphere::new(s.center.0, s.radius.0)
            }),
            material,
        });
    }
    for (n, p) in f.plane.into_iter().enumerate() {
        spans.push(p.span());
        let p = p.into_inner();
        let material = resolve(&p.material, &mut materials)?;
        objects.push(Object {
            name: name_or(p.name, "plane", n),
            shape: Shape::Plane(Plane::new(p.point.0, p.normal.0)),
            material,
        });
    }
    for (n, q) in f.quad.into_iter().enumerate() {
        let span = q.span();
        let q = q.into_inner();
        let area = q.edge_u.0.cross(q.edge_v.0).length();
        if !(area > 0.0 && area.is_finite()) {
            return Err(SceneError::new(
                at(span),
                "quad edges `edge_u` and `edge_v` must not be parallel or zero",
            ));
        }
        let material = resolve(&q.material, &mut materials)?;
        spans.push(span.clone());
        objects.push(Object {
            name: name_or(q.name, "quad", n),
            shape: Shape::Quad(Quad::new(q.corner.0, q.edge_u.0, q.edge_v.0)),
            material,
        });
    }
    for (n, b) in f.r#box.into_iter().enumerate() {
        let span = b.span();
        let b = b.into_inner();
        let (lo, hi) = (b.min.0, b.max.0);
        if !lo.cmplt(hi).all() {
            return Err(SceneError::new(
                at(span),
                "box `min` must be below `max` on every axis",
            ));
        }
        let center = 0.5 * (lo + hi);
        let rotate = glam::Affine3A::from_translation(center.into())
            * glam::Affine3A::from_quat(rotation(b.rotate))
            * glam::Affine3A::from_translation((-center).into());
        let mut mesh = Mesh::cuboid(lo, hi)
            .and_then(|m| m.transformed(&rotate, false))
            .map_err(|e| SceneError::new(at(span.clone()), e.to_string()))?;
        mesh.velocity = b.velocity.map_or(Vec3::ZERO, |v| v.0);
        let material = resolve(&b.material, &mut materials)?;
        spans.push(span);
        objects.push(Object {
            name: name_or(b.name, "box", n),
            shape: Shape::Mesh(mesh),
            material,
        });
    }
    for (n, m) in f.mesh.into_iter().enumerate() {
        let rel = m.file.get_ref().as_str();
        let gltf = match super::input::extension(Path::new(rel)).as_deref() {
            Some("gltf" | "glb") => true,
            // A file without an extension is read as OBJ, as it always was.
            None | Some("obj") => false,
            Some(other) => {
                return Err(SceneError::new(
                    at(m.file.span()),
                    format!(
                        "unsupported model format `.{other}`: a mesh is an OBJ (.obj) or glTF 2.0 (.gltf, .glb) file"
                    ),
                ));
            }
        };
        let kind = if gltf { "glTF" } else { "OBJ" };
        let bytes = assets.read(rel).map_err(|e| {
            SceneError::new(
                at(m.file.span()),
                format!("cannot read {kind} file `{}`: {e}", assets.label(rel)),
            )
        })?;
        let label = assets.label(rel);
        let dir = Path::new(rel).parent().unwrap_or(Path::new(""));
        let beside = |name: &str| assets.read(&dir.join(name).to_string_lossy());
        let parts = if gltf {
            load_gltf(&bytes, &label, &beside)?
        } else {
            load_obj(&bytes, &label, &|name| beside(name).ok())?
        };
        let transform = glam::Affine3A::from_scale_rotation_translation(
            glam::Vec3::splat(m.scale.map_or(1.0, |s| s.0)),
            rotation(m.rotate),
            m.translate.map_or(glam::Vec3::ZERO, |t| t.0.into()),
        );
        let base = name_or(m.name, "mesh", n);
        let single = parts.len() == 1;
        for part in parts {
            let material = match (&m.material, part.material) {
                (Some(_), _) | (None, None) => resolve(&m.material, &mut materials)?,
                (None, Some((mtl_name, mat))) => materials.add(format!("{rel}:{mtl_name}"), mat),
            };
            let mut mesh = part.mesh.transformed(&transform, m.smooth).map_err(|e| {
                SceneError::new(at(m.file.span()), format!("after its transform: {e}"))
            })?;
            mesh.velocity = m.velocity.map_or(Vec3::ZERO, |v| v.0);
            let mesh = Shape::Mesh(mesh);
            if !mesh.within_limits() {
                return Err(SceneError::new(
                    at(m.file.span()),
                    beyond_limits("the mesh"),
                ));
            }
            spans.push(m.file.span());
            objects.push(Object {
                name: if single {
                    base.clone()
                } else {
                    format!("{base}/{}", part.name)
                },
                shape: mesh,
                material,
            });
        }
    }
    // Points and lengths were checked as they were read; what they make may still reach out.
    if let Some((o, span)) = objects
        .iter()
        .zip(spans)
        .find(|(o, _)| !o.shape.within_limits())
    {
        return Err(SceneError::new(
            at(span),
            beyond_limits(&format!("object `{}`", o.name)),
        ));
    }

    let mut params = Params::default();
    for (key, value) in &f.params {
        let json = serde_json::to_value(value.get_ref())
            .map_err(|e| SceneError::new(at(value.span()), e.to_string()))?;
        params.set_value(key.get_ref(), json).map_err(|e| {
            let span = if matches!(e, ParamError::Unknown { .. }) {
                key.span()
            } else {
                value.span()
            };
            SceneError::new(at(span), format!("in [params]: {e}"))
        })?;
    }

    let background = match f.background {
        None => Background::Gradient {
            horizon: Color::new(0.8, 0.85, 0.9),
            zenith: Color::new(0.35, 0.5, 0.8),
        },
        Some(b) => {
            let span = b.span();
            match b.into_inner() {
                BackgroundDef {
                    color: Some(c),
                    horizon: None,
                    zenith: None,
                } => Background::Constant(c.0),
                BackgroundDef {
                    color: None,
                    horizon: Some(h),
                    zenith: Some(z),
                } => Background::Gradient {
                    horizon: h.0,
                    zenith: z.0,
                },
                _ => {
                    return Err(SceneError::new(
                        at(span),
                        "[background] takes either `color`, or both `horizon` and `zenith`",
                    ));
                }
            }
        }
    };

    let camera_span = f.camera.span();
    let c = f.camera.into_inner();
    let fov = match c.fov {
        Some(fov) if fov.get_ref().0 >= 180.0 => {
            return Err(SceneError::new(
                at(fov.span()),
                "[camera] `fov` must be below 180 degrees",
            ));
        }
        Some(fov) => fov.into_inner().0,
        None => 45.0,
    };
    let up = c.up.map_or(Vec3::Y, |u| u.0);
    let camera = Camera::looking_at(c.position.0, c.look_at.0, up, fov);
    camera
        .check()
        .map_err(|e| SceneError::new(at(camera_span), format!("[camera] {e}")))?;

    let intensity = |color: Option<Rgb>, i: NonNegative| color.map_or(Color::ONE, |c| c.0) * i.0;
    let light = |shape, intensity| Light {
        shape,
        intensity,
        scale: 1.0,
    };
    let mut lights: Vec<Light> = f
        .point_light
        .into_iter()
        .map(|l| Light::point(l.position.0, intensity(l.color, l.intensity)))
        .collect();
    for r in f.rect_light {
        let span = r.span();
        let r = r.into_inner();
        if r.edge_u.0.cross(r.edge_v.0).length_squared() == 0.0 {
            return Err(SceneError::new(
                at(span),
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
    for d in f.disk_light {
        let shape = LightShape::Disk {
            center: d.center.0,
            normal: d.normal.0,
            radius: d.radius.0,
        };
        lights.push(light(shape, intensity(d.color, d.intensity)));
    }
    for s in f.sphere_light {
        let shape = LightShape::Sphere {
            center: s.center.0,
            radius: s.radius.0,
        };
        lights.push(light(shape, intensity(s.color, s.intensity)));
    }

    let (width, height) = match f.image {
        None => (640, 360),
        Some(i) => {
            let span = i.span();
            let i = i.into_inner();
            super::check_size(i.width.0, i.height.0)
                .map_err(|e| SceneError::new(at(span), format!("[image]: {e}")))?;
            (i.width.0, i.height.0)
        }
    };
    Ok(SceneDesc {
        name: String::new(),
        description: f.description,
        camera,
        width,
        height,
        params,
        materials: materials.list,
        objects,
        lights,
        ambient: f.ambient.map_or(Color::ZERO, |a| a.0),
        background,
        medium_ior: f.medium_ior.map_or(1.0, |m| m.0),
    })
}

/// The rotation of `rotate = [x, y, z]` degrees: about x, then y, then z.
fn rotation(rotate: Option<V3>) -> glam::Quat {
    rotate.map_or(glam::Quat::IDENTITY, |r| {
        let r = r.0 * (std::f32::consts::PI / 180.0);
        glam::Quat::from_euler(glam::EulerRot::ZYX, r.z, r.y, r.x)
    })
}
