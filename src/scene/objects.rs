//! A scene file's objects: spheres, planes, quads, boxes and meshes (OBJ or glTF), each
//! with its material, built and checked where they are written.

use super::gltf::load_gltf;
use super::materials::{MaterialTable, RawMaterial, default_material, material, material_def};
use super::obj::{Model, ModelCamera, load_obj};
use super::source::{Assets, Source};
use super::values::{Dir, Length, V3};
use super::{Material, Object, SceneError};
use crate::geometry::{Instance, Mesh, Plane, Quad, SMALL_MESH, Shape, SharedMesh, Sphere};
use crate::light::Light;
use crate::math::Vec3;
use serde::Deserialize;
use std::collections::{BTreeMap, HashMap};
use std::ops::Range;
use std::path::Path;
use std::rc::Rc;
use std::sync::Arc;
use toml::Spanned;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SphereDef {
    name: Option<String>,
    center: V3,
    radius: Length,
    velocity: Option<V3>,
    material: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PlaneDef {
    name: Option<String>,
    point: V3,
    normal: Dir,
    material: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct QuadDef {
    name: Option<String>,
    corner: V3,
    edge_u: V3,
    edge_v: V3,
    material: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BoxDef {
    name: Option<String>,
    min: V3,
    max: V3,
    rotate: Option<V3>,
    velocity: Option<V3>,
    material: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MeshDef {
    name: Option<String>,
    file: Spanned<String>,
    material: Option<Spanned<String>>,
    scale: Option<Length>,
    rotate: Option<V3>,
    translate: Option<V3>,
    velocity: Option<V3>,
    #[serde(default = "yes")]
    smooth: bool,
    /// The model's up axis: `y` (glTF's, and most OBJ files'), or `z` (CAD and many
    /// scans), turned to stand on raylab's floor before `rotate`.
    #[serde(default)]
    up: UpAxis,
}

/// Which of the model file's axes points up.
#[derive(Clone, Copy, Debug, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
enum UpAxis {
    #[default]
    Y,
    Z,
}

impl UpAxis {
    /// `rotation` after the turn that makes this axis raylab's +y: for z up, −90° about x,
    /// so (x, y, z) ↦ (x, z, −y). For y up, `rotation` itself, not a product with the
    /// identity (which could turn a −0 into +0 and change an image by a bit).
    fn then(self, rotation: glam::Quat) -> glam::Quat {
        match self {
            UpAxis::Y => rotation,
            UpAxis::Z => rotation * glam::Quat::from_rotation_x(-std::f32::consts::FRAC_PI_2),
        }
    }
}

fn yes() -> bool {
    true
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

/// The rotation of `rotate = [x, y, z]` degrees: about x, then y, then z.
fn rotation(rotate: Option<V3>) -> glam::Quat {
    rotate.map_or(glam::Quat::IDENTITY, |r| {
        let r = r.0 * (std::f32::consts::PI / 180.0);
        glam::Quat::from_euler(glam::EulerRot::ZYX, r.z, r.y, r.x)
    })
}

/// The objects of a file as they are built: their materials, and where each is written
/// (for the check of its extent once all are in).
pub(super) struct Objects<'s> {
    src: &'s Source<'s>,
    materials: MaterialTable,
    objects: Vec<Object>,
    spans: Vec<Range<usize>>,
    warnings: Vec<String>,
    // Each model file read once, however often it is placed.
    models: HashMap<String, Rc<Loaded>>,
    // The lights and the first camera the placed models bring.
    lights: Vec<Light>,
    camera: Option<ModelCamera>,
    // Triangles built so far and shared placements, for the memory estimate.
    triangles: u64,
    instances: u64,
}

/// A model file as its placements use it: its parts, and the lights and camera it
/// brings, in its own coordinates.
struct Loaded {
    parts: Vec<Part>,
    lights: Vec<Light>,
    camera: Option<ModelCamera>,
}

/// A part of a model file, as its placements use it.
struct Part {
    name: String,
    material: Option<(String, Material)>,
    mesh: PartMesh,
    /// Where the model places it (see [`super::obj::ObjPart::at`]).
    at: Vec<glam::Affine3A>,
}

/// A part's triangles: copied into each placement, or built once and shared.
enum PartMesh {
    Copied(Mesh),
    Shared(Arc<SharedMesh>),
}

/// Whether a part of `triangles` placed `placements` times is shared by its placements
/// (an instance each): when there are several and it is more than a small mesh. A small
/// mesh is copied: it costs little, and copies are tested directly, several rays at once,
/// where an instance is a trip into its own frame and tree.
fn shares(placements: usize, triangles: usize) -> bool {
    placements > 1 && triangles > SMALL_MESH
}

/// What one placement of a model adds to the memory estimate, per part.
struct PartSize {
    /// The part's triangles.
    triangles: usize,
    /// How many times the model places it ([`super::obj::ObjPart::at`]).
    times: usize,
    /// Whether its placements share one mesh ([`shares`]).
    shared: bool,
}

impl PartSize {
    /// `part`'s, of a model the scene places `placements` times.
    fn of(part: &super::obj::ObjPart, placements: usize) -> PartSize {
        let (triangles, times) = (part.mesh.triangle_count(), part.at.len());
        PartSize {
            triangles,
            times,
            shared: shares(placements.saturating_mul(times), triangles),
        }
    }
}

impl Part {
    /// `part` of a model placed `placements` times, shared as [`PartSize::of`] says.
    fn new(part: super::obj::ObjPart, placements: usize) -> Part {
        let mesh = if PartSize::of(&part, placements).shared {
            PartMesh::Shared(SharedMesh::new(part.mesh))
        } else {
            PartMesh::Copied(part.mesh)
        };
        Part {
            name: part.name,
            material: part.material,
            mesh,
            at: part.at,
        }
    }

    /// What another placement of its model adds.
    fn size(&self) -> PartSize {
        let (triangles, shared) = match &self.mesh {
            PartMesh::Copied(m) => (m.triangle_count(), false),
            PartMesh::Shared(s) => (s.mesh().triangle_count(), true),
        };
        PartSize {
            triangles,
            times: self.at.len(),
            shared,
        }
    }
}

/// The memory a shared placement takes beside its mesh: the instance and its leaf of
/// the scene's BVH, with margin.
const BYTES_PER_INSTANCE: u64 = 512;

/// A file's materials (by name) and objects, built, with the lights and camera its
/// models brought (placed).
pub(super) struct Built {
    pub(super) materials: Vec<(String, Material)>,
    pub(super) objects: Vec<Object>,
    pub(super) lights: Vec<Light>,
    pub(super) camera: Option<ModelCamera>,
    pub(super) warnings: Vec<String>,
}

/// `name`, or the kind and number of the `n`-th (from 0) object of its kind.
fn name_or(name: Option<String>, kind: &str, n: usize) -> String {
    name.unwrap_or_else(|| format!("{kind} {}", n + 1))
}

impl<'s> Objects<'s> {
    /// No objects yet, the file's materials defined.
    pub(super) fn new(
        src: &'s Source<'s>,
        defs: BTreeMap<String, RawMaterial>,
    ) -> Result<Objects<'s>, SceneError> {
        let mut materials = MaterialTable::default();
        for (name, raw) in defs {
            materials.add(name, material(material_def(src, raw)?));
        }
        Ok(Objects {
            src,
            materials,
            objects: Vec::new(),
            spans: Vec::new(),
            warnings: Vec::new(),
            models: HashMap::new(),
            lights: Vec::new(),
            camera: None,
            triangles: 0,
            instances: 0,
        })
    }

    /// The material an object names (the default one, if none).
    fn resolve(&mut self, name: &Option<Spanned<String>>) -> Result<u32, SceneError> {
        match name {
            None => Ok(self
                .materials
                .add(DEFAULT_MATERIAL.to_string(), default_material())),
            Some(s) => self.materials.get(s.get_ref()).ok_or_else(|| {
                self.src.error(
                    s.span(),
                    format!(
                        "unknown material `{}` (defined: {})",
                        s.get_ref(),
                        self.materials.names()
                    ),
                )
            }),
        }
    }

    /// Adds an object written at `span`.
    fn push(&mut self, span: Range<usize>, name: String, shape: Shape, material: u32) {
        self.spans.push(span);
        self.objects.push(Object {
            name,
            shape,
            material,
        });
    }

    pub(super) fn spheres(&mut self, defs: Vec<Spanned<SphereDef>>) -> Result<(), SceneError> {
        for (n, s) in defs.into_iter().enumerate() {
            let span = s.span();
            let s = s.into_inner();
            let material = self.resolve(&s.material)?;
            let shape = Shape::Sphere(Sphere {
                velocity: s.velocity.map_or(Vec3::ZERO, |v| v.0),
                ..Sphere::new(s.center.0, s.radius.0)
            });
            self.push(span, name_or(s.name, "sphere", n), shape, material);
        }
        Ok(())
    }

    pub(super) fn planes(&mut self, defs: Vec<Spanned<PlaneDef>>) -> Result<(), SceneError> {
        for (n, p) in defs.into_iter().enumerate() {
            let span = p.span();
            let p = p.into_inner();
            let material = self.resolve(&p.material)?;
            let shape = Shape::Plane(Plane::new(p.point.0, p.normal.0));
            self.push(span, name_or(p.name, "plane", n), shape, material);
        }
        Ok(())
    }

    pub(super) fn quads(&mut self, defs: Vec<Spanned<QuadDef>>) -> Result<(), SceneError> {
        for (n, q) in defs.into_iter().enumerate() {
            let span = q.span();
            let q = q.into_inner();
            let area = q.edge_u.0.cross(q.edge_v.0).length();
            if !(area > 0.0 && area.is_finite()) {
                return Err(self.src.error(
                    span,
                    "quad edges `edge_u` and `edge_v` must not be parallel or zero",
                ));
            }
            let material = self.resolve(&q.material)?;
            let shape = Shape::Quad(Quad::new(q.corner.0, q.edge_u.0, q.edge_v.0));
            self.push(span, name_or(q.name, "quad", n), shape, material);
        }
        Ok(())
    }

    pub(super) fn boxes(&mut self, defs: Vec<Spanned<BoxDef>>) -> Result<(), SceneError> {
        for (n, b) in defs.into_iter().enumerate() {
            let span = b.span();
            let b = b.into_inner();
            let (lo, hi) = (b.min.0, b.max.0);
            if !lo.cmplt(hi).all() {
                return Err(self
                    .src
                    .error(span, "box `min` must be below `max` on every axis"));
            }
            let center = 0.5 * (lo + hi);
            let rotate = glam::Affine3A::from_translation(center.into())
                * glam::Affine3A::from_quat(rotation(b.rotate))
                * glam::Affine3A::from_translation((-center).into());
            let mut mesh = Mesh::cuboid(lo, hi)
                .and_then(|m| m.transformed(&rotate, false))
                .map_err(|e| self.src.error(span.clone(), e.to_string()))?;
            mesh.velocity = b.velocity.map_or(Vec3::ZERO, |v| v.0);
            let material = self.resolve(&b.material)?;
            self.push(span, name_or(b.name, "box", n), Shape::Mesh(mesh), material);
        }
        Ok(())
    }

    /// Meshes from model files beside the scene (`assets`): one object per part of a
    /// model, each with its own material unless the scene names one. A file placed more
    /// than once is read and built once, and placed by transforms (see [`Part::new`]).
    pub(super) fn meshes(
        &mut self,
        defs: Vec<MeshDef>,
        assets: &dyn Assets,
    ) -> Result<(), SceneError> {
        let mut placements: HashMap<String, usize> = HashMap::new();
        for m in &defs {
            *placements.entry(m.file.get_ref().clone()).or_default() += 1;
        }
        for (n, m) in defs.into_iter().enumerate() {
            let span = m.file.span();
            let rel = m.file.get_ref();
            // Each placement is counted before it is built (the first before its model's
            // shared trees are), and refused while it is only a count.
            let loaded = match self.models.get(rel) {
                Some(loaded) => {
                    let loaded = Rc::clone(loaded);
                    self.account(loaded.parts.iter().map(Part::size), false, &span)?;
                    loaded
                }
                None => {
                    let placed = placements.get(rel).copied().unwrap_or(1);
                    let raw = self.model(&m, assets)?;
                    let sizes = raw.parts.iter().map(|p| PartSize::of(p, placed));
                    self.account(sizes, true, &span)?;
                    let loaded = Rc::new(Loaded {
                        parts: raw
                            .parts
                            .into_iter()
                            .map(|p| Part::new(p, placed))
                            .collect(),
                        lights: raw.lights,
                        camera: raw.camera,
                    });
                    self.models.insert(rel.clone(), Rc::clone(&loaded));
                    loaded
                }
            };
            let parts = &loaded.parts;
            let transform = glam::Affine3A::from_scale_rotation_translation(
                glam::Vec3::splat(m.scale.map_or(1.0, |s| s.0)),
                m.up.then(rotation(m.rotate)),
                m.translate.map_or(glam::Vec3::ZERO, |t| t.0.into()),
            );
            self.lights
                .extend(loaded.lights.iter().map(|l| l.transformed(&transform)));
            if self.camera.is_none() {
                self.camera = loaded.camera.as_ref().map(|c| ModelCamera {
                    camera: c.camera.transformed(&transform),
                    ..c.clone()
                });
            }
            let velocity = m.velocity.map_or(Vec3::ZERO, |v| v.0);
            let base = name_or(m.name, "mesh", n);
            let single = parts.len() == 1;
            for part in parts.iter() {
                let material = match (&m.material, &part.material) {
                    (Some(_), _) | (None, None) => self.resolve(&m.material)?,
                    (None, Some((mtl_name, mat))) => {
                        self.materials.add(format!("{rel}:{mtl_name}"), mat.clone())
                    }
                };
                let after = |e: crate::geometry::MeshError| {
                    self.src
                        .error(span.clone(), format!("after its transform: {e}"))
                };
                let name = if single {
                    base.clone()
                } else {
                    format!("{base}/{}", part.name)
                };
                for (k, at) in part.at.iter().enumerate() {
                    // As it stands: the placement's transform alone, bit for bit.
                    let transform = if *at == glam::Affine3A::IDENTITY {
                        transform
                    } else {
                        transform * *at
                    };
                    let shape = match &part.mesh {
                        PartMesh::Copied(mesh) => {
                            let mut mesh = mesh.transformed(&transform, m.smooth).map_err(after)?;
                            mesh.velocity = velocity;
                            Shape::Mesh(mesh)
                        }
                        PartMesh::Shared(shared) => Shape::Instance(
                            Instance::new(Arc::clone(shared), transform, m.smooth, velocity)
                                .map_err(after)?,
                        ),
                    };
                    if !shape.within_limits() {
                        return Err(self.src.error(span, beyond_limits("the mesh")));
                    }
                    let name = match part.at.len() {
                        1 => name.clone(),
                        _ => format!("{name}#{}", k + 1),
                    };
                    self.push(span.clone(), name, shape, material);
                }
            }
        }
        Ok(())
    }

    /// Adds one placement of a model's parts to the memory estimate, and refuses it beyond
    /// the limit. A shared part's triangles count once, at the `first` placement, and each
    /// time it is placed as an instance; a copied part's triangles each time.
    fn account(
        &mut self,
        parts: impl Iterator<Item = PartSize>,
        first: bool,
        span: &Range<usize>,
    ) -> Result<(), SceneError> {
        for p in parts {
            let (triangles, times) = (p.triangles as u64, p.times as u64);
            let built = match (p.shared, first) {
                (true, true) => triangles,
                (true, false) => 0,
                (false, _) => triangles.saturating_mul(times),
            };
            self.triangles = self.triangles.saturating_add(built);
            if p.shared {
                self.instances = self.instances.saturating_add(times);
            }
        }
        let bytes = self.triangles * super::memory::BYTES_PER_TRIANGLE
            + self.instances * BYTES_PER_INSTANCE;
        super::memory::check(
            bytes,
            &format!("with this mesh, the scene's {} triangles", self.triangles),
        )
        .map_err(|e| self.src.error(span.clone(), e))
    }

    /// The model file a mesh names: OBJ, or glTF by its extension.
    fn model(&mut self, m: &MeshDef, assets: &dyn Assets) -> Result<Model, SceneError> {
        let rel = m.file.get_ref().as_str();
        let gltf = match super::input::extension(Path::new(rel)).as_deref() {
            Some("gltf" | "glb") => true,
            // A file without an extension is read as OBJ, as it always was.
            None | Some("obj") => false,
            Some(other) => {
                return Err(self.src.error(
                    m.file.span(),
                    format!(
                        "unsupported model format `.{other}`: a mesh is an OBJ (.obj) or glTF 2.0 (.gltf, .glb) file"
                    ),
                ));
            }
        };
        let kind = if gltf { "glTF" } else { "OBJ" };
        let bytes = assets.read(rel).map_err(|e| {
            self.src.error(
                m.file.span(),
                format!("cannot read {kind} file `{}`: {e}", assets.label(rel)),
            )
        })?;
        let label = assets.label(rel);
        let dir = Path::new(rel).parent().unwrap_or(Path::new(""));
        let beside = |name: &str| assets.read(&dir.join(name).to_string_lossy());
        let mut model = if gltf {
            load_gltf(&bytes, &label, &beside)?
        } else {
            load_obj(&bytes, &label, &|name| beside(name).ok())?
        };
        self.warnings.append(&mut model.warnings);
        Ok(model)
    }

    /// The materials and the objects, once every object is checked to lie within the
    /// coordinates the renderer handles (points and lengths were checked as they were
    /// read; what they make may still reach out).
    pub(super) fn finish(self) -> Result<Built, SceneError> {
        if let Some((o, span)) = self
            .objects
            .iter()
            .zip(&self.spans)
            .find(|(o, _)| !o.shape.within_limits())
        {
            return Err(self
                .src
                .error(span.clone(), beyond_limits(&format!("object `{}`", o.name))));
        }
        Ok(Built {
            materials: self.materials.list,
            objects: self.objects,
            lights: self.lights,
            camera: self.camera,
            warnings: self.warnings,
        })
    }
}
