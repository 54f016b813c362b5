//! Scenes: the immutable description the tracer reads, loaded from TOML files or built in.

mod builtin;
mod error;
mod file;
mod gltf;
pub mod input;
mod materials;
pub mod memory;
mod obj;
mod objects;
mod source;
mod values;

pub use builtin::{BUILTIN_SCENES, BuiltinScene, builtin};
pub(crate) use error::one_line;
pub use error::{Location, SceneError, line_col};
pub use file::describe;
pub use gltf::load_gltf;
pub use obj::{Model, ObjPart, load_obj};
pub use values::{MAX_IMAGE_SIDE, MAX_PIXELS, check_size};

use crate::camera::Camera;
use crate::geometry::{Accel, PrimRef, Shape, SurfaceHit, SurfaceLanes};
use crate::light::{Background, Light};
use crate::material::{Diffuse, Material};
use crate::math::lanes::{Lanes, Mask, RayColumns, RayOf, Width};
use crate::math::{Color, Ray, Vec3};
use crate::params::Params;
use std::path::{Path, PathBuf};

/// Where a scene came from, so that a snapshot can name it and it can be loaded again.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SceneSource {
    /// A scene embedded in the binary, by name.
    Builtin(String),
    /// A scene file.
    File(PathBuf),
    /// Built in code (tests, benchmarks).
    Code,
}

impl SceneSource {
    /// How the source is written in a snapshot sidecar and on the command line: the
    /// built-in name, or the file path.
    pub fn reference(&self) -> String {
        match self {
            SceneSource::Builtin(name) => format!("builtin:{name}"),
            SceneSource::File(path) => path.display().to_string(),
            SceneSource::Code => "code".to_string(),
        }
    }
}

/// One object: a shape with a material and a name.
#[derive(Clone, Debug)]
pub struct Object {
    /// Name for listings and the inspector.
    pub name: String,
    /// Geometry.
    pub shape: Shape,
    /// Index into the scene's materials.
    pub material: u32,
}

/// Everything a scene holds, before its BVH is built. Fields are public so that tests and
/// benchmarks can build scenes in code.
#[derive(Clone, Debug)]
pub struct SceneDesc {
    /// Short name.
    pub name: String,
    /// One-line description.
    pub description: String,
    /// The camera.
    pub camera: Camera,
    /// Default image width.
    pub width: u32,
    /// Default image height.
    pub height: u32,
    /// The scene's default parameters.
    pub params: Params,
    /// Named materials.
    pub materials: Vec<(String, Material)>,
    /// Objects.
    pub objects: Vec<Object>,
    /// Lights.
    pub lights: Vec<Light>,
    /// Ambient radiance: light arriving from every direction, unshadowed.
    pub ambient: Color,
    /// What rays that leave the scene see.
    pub background: Background,
    /// Index of refraction of the medium around everything (air 1.0, water 1.33).
    pub medium_ior: f32,
    /// What was missing from its files but not fatal (a material library that is not
    /// there), one line each: the CLI and the window say them.
    pub warnings: Vec<String>,
}

impl SceneDesc {
    /// A scene holding nothing but `camera`: no objects, no lights, black background and
    /// ambient, air around, default parameters, 64 × 64 pixels. For scenes built in code.
    pub fn empty(camera: Camera) -> Self {
        SceneDesc {
            name: "code".into(),
            description: String::new(),
            camera,
            width: 64,
            height: 64,
            params: Params::default(),
            materials: Vec::new(),
            objects: Vec::new(),
            lights: Vec::new(),
            ambient: Color::ZERO,
            background: crate::light::Background::Constant(Color::ZERO),
            medium_ior: 1.0,
            warnings: Vec::new(),
        }
    }

    /// Adds an object with a material of its own; returns the object's index.
    pub fn add(&mut self, name: impl Into<String>, shape: Shape, material: Material) -> u32 {
        let name = name.into();
        self.materials.push((name.clone(), material));
        self.objects.push(Object {
            name,
            shape,
            material: self.materials.len() as u32 - 1,
        });
        self.objects.len() as u32 - 1
    }

    /// The scene, with its BVH built.
    pub fn build(self) -> Scene {
        Scene::new(self, SceneSource::Code)
    }
}

/// A ray's nearest hit in a scene.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    /// The surface hit.
    pub surface: SurfaceHit,
    /// The object hit.
    pub object: u32,
    /// Its material.
    pub material: u32,
}

/// A scene ready to trace: immutable, shared between render threads behind an `Arc`.
#[derive(Debug)]
pub struct Scene {
    /// Short name.
    pub name: String,
    /// One-line description.
    pub description: String,
    /// Where it was loaded from.
    pub source: SceneSource,
    /// The camera.
    pub camera: Camera,
    /// Default image width.
    pub width: u32,
    /// Default image height.
    pub height: u32,
    /// The scene's default parameters.
    pub params: Params,
    /// Materials.
    pub materials: Vec<Material>,
    /// Material names, parallel to `materials`.
    pub material_names: Vec<String>,
    /// Object names, parallel to `shapes`.
    pub object_names: Vec<String>,
    /// Object materials, parallel to `shapes`.
    pub object_materials: Vec<u32>,
    /// Object geometry.
    pub shapes: Vec<Shape>,
    /// Lights.
    pub lights: Vec<Light>,
    /// Ambient radiance.
    pub ambient: Color,
    /// Background.
    pub background: Background,
    /// Index of refraction of the surrounding medium.
    pub medium_ior: f32,
    /// What was missing from its files but not fatal, one line each (see
    /// [`SceneDesc::warnings`]).
    pub warnings: Vec<String>,
    accel: Accel,
    // Whether each object's material reads surface coordinates (a texture).
    object_uses_uv: Vec<bool>,
}

impl Scene {
    /// Builds the BVH and freezes the scene.
    pub fn new(desc: SceneDesc, source: SceneSource) -> Self {
        let mut object_names = Vec::with_capacity(desc.objects.len());
        let mut object_materials = Vec::with_capacity(desc.objects.len());
        let mut shapes = Vec::with_capacity(desc.objects.len());
        for o in desc.objects {
            object_names.push(o.name);
            object_materials.push(o.material);
            shapes.push(o.shape);
        }
        let accel = Accel::build(&shapes);
        let (material_names, materials): (Vec<String>, Vec<Material>) =
            desc.materials.into_iter().unzip();
        let object_uses_uv = object_materials
            .iter()
            .map(|&m| materials.get(m as usize).is_some_and(Material::uses_uv))
            .collect();
        Scene {
            name: desc.name,
            description: desc.description,
            source,
            camera: desc.camera,
            width: desc.width,
            height: desc.height,
            params: desc.params,
            materials,
            material_names,
            object_names,
            object_materials,
            object_uses_uv,
            shapes,
            lights: desc.lights,
            ambient: desc.ambient,
            background: desc.background,
            medium_ior: desc.medium_ior,
            warnings: desc.warnings,
            accel,
        }
    }

    /// Loads a built-in scene by name (`default` or `builtin:default`), or a scene file by
    /// path (any path the system allows, UTF-8 or not). A bare name that is both a
    /// built-in and an existing file means the file.
    pub fn load(name_or_path: impl AsRef<std::ffi::OsStr>) -> Result<Scene, SceneError> {
        let start = std::time::Instant::now();
        let scene = Scene::find_and_load(name_or_path.as_ref())?;
        log::debug!(
            "{}: loaded in {:.1} ms, {} objects, {} primitives",
            scene.source.reference(),
            start.elapsed().as_secs_f64() * 1e3,
            scene.shapes.len(),
            scene.primitive_count()
        );
        Ok(scene)
    }

    /// [`Scene::load`], untimed.
    fn find_and_load(given: &std::ffi::OsStr) -> Result<Scene, SceneError> {
        let text = given.to_str();
        if let Some(name) = text.and_then(|t| t.strip_prefix("builtin:")) {
            return match builtin(name) {
                Some(b) => b.load(),
                None => Err(unknown_scene(name)),
            };
        }
        let path = Path::new(given);
        let named = text.and_then(builtin);
        // Anything there but a built-in's name is read as a file, which refuses what is
        // not a regular file (a folder, a device, a pipe) with a message.
        if path.is_file() || (path.exists() && named.is_none()) {
            return Scene::load_file(path);
        }
        match named {
            Some(b) => b.load(),
            None => Err(unknown_scene(&given.to_string_lossy())),
        }
    }

    /// Loads a scene file (`.toml`, or a name without an extension), or shows a model
    /// (`.obj`, `.gltf`, `.glb`) on a floor under a light, framed by the camera. Any other
    /// extension is refused as a format raylab does not read, before the file is opened.
    pub fn load_file(path: &Path) -> Result<Scene, SceneError> {
        match input::extension(path).as_deref() {
            Some(m) if is_model(m) => Scene::for_model(path),
            None | Some("toml") => file::load_file(path),
            Some(other) => Err(SceneError::new(
                Location::file(path.display().to_string()),
                format!(
                    "unsupported format `.{other}`: raylab reads scene files (.toml), OBJ models (.obj) and glTF 2.0 models (.gltf, .glb)"
                ),
            )),
        }
    }

    /// A scene showing the meshes of a model file, OBJ or glTF (its materials, or grey),
    /// standing on a checkered floor. A glTF file's own camera and lights are used where
    /// it has them (the image shaped to the camera's aspect ratio); otherwise the camera
    /// looks at the model from the front and a little above, and one light shines from the
    /// upper left.
    pub fn for_model(path: &Path) -> Result<Scene, SceneError> {
        let full = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
        let label = path.display().to_string();
        // The mesh goes through the scene format, so that its errors and .mtl materials are
        // those of any scene; the rest is added around it.
        let assets = source::ModelAssets {
            name: format!("model.{}", input::extension(path).unwrap_or_default()),
            model: full.clone(),
        };
        let probe = format!(
            "[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\n[[mesh]]\nfile = \"{}\"\n",
            assets.name
        );
        // An error placed in that made-up text is about the model as a whole: it names
        // the model's file, with no line of a text the user never wrote.
        const PROBE: &str = "\0model";
        let (mut desc, model_camera) =
            file::parse_with_camera(&probe, PROBE, &assets).map_err(|mut e| {
                if e.location.file == PROBE {
                    e.location = Location::file(&label);
                }
                e
            })?;
        let (lo, hi) = desc
            .objects
            .iter()
            .filter_map(|o| match &o.shape {
                Shape::Mesh(m) => Some(m.positions()),
                _ => None,
            })
            .flatten()
            .fold(None, |b: Option<(Vec3, Vec3)>, &p| {
                Some(b.map_or((p, p), |(lo, hi)| (lo.min(p), hi.max(p))))
            })
            .ok_or_else(|| SceneError::new(Location::file(&label), "the model has no faces"))?;
        let c = 0.5 * (lo + hi);
        let r = (0.5 * (hi - lo).length()).max(1e-6);
        desc.name = path
            .file_stem()
            .map_or(label.clone(), |s| s.to_string_lossy().into_owned());
        desc.description = format!(
            "The mesh of {}",
            path.file_name()
                .map_or(label.clone(), |n| n.to_string_lossy().into_owned())
        );
        (desc.width, desc.height) = (960, 540);
        desc.ambient = Color::splat(0.05);
        // The model's own camera, or one from the front and a little above.
        match model_camera {
            Some(own) => {
                desc.camera = own.camera;
                if let Some(aspect) = own.aspect {
                    (desc.width, desc.height) = size_for_aspect(aspect);
                }
            }
            None => {
                desc.camera =
                    Camera::looking_at(c + Vec3::new(0.0, 0.6 * r, 3.2 * r), c, Vec3::Y, 35.0);
            }
        }
        let floor = Material::Diffuse(Diffuse {
            albedo: crate::material::Texture::Checker {
                even: Color::new(0.8, 0.8, 0.78),
                odd: Color::new(0.15, 0.15, 0.17),
                scale: glam::Vec2::splat(2.0 / r),
            },
            specular: Color::ZERO,
            exponent: 1.0,
            emission: None,
        });
        desc.add(
            "floor",
            Shape::Plane(crate::geometry::Plane::new(
                Vec3::new(c.x, lo.y - 1e-3 * r, c.z),
                Vec3::Y,
            )),
            floor,
        );
        // The model's own lights, or one from the upper left.
        if desc.lights.is_empty() {
            desc.lights.push(Light::point(
                c + Vec3::new(-2.0 * r, 4.0 * r, 3.0 * r),
                Color::splat(60.0 * r * r),
            ));
        }
        Ok(Scene::new(desc, SceneSource::File(full)))
    }

    /// Parses scene text; OBJ paths resolve against `base_dir`.
    pub fn from_toml_str(
        text: &str,
        file_label: &str,
        base_dir: &Path,
    ) -> Result<Scene, SceneError> {
        let desc = file::parse(text, file_label, &source::FsAssets(base_dir.to_path_buf()))?;
        Ok(Scene::new(desc, SceneSource::Code))
    }

    /// The total number of triangles, spheres and quads in the BVH.
    pub fn primitive_count(&self) -> usize {
        self.accel.primitive_count()
    }

    /// The nearest hit along `ray` closer than `t_max`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let (prim, t) = self.accel.intersect(&self.shapes, ray, t_max)?;
        Some(self.hit_at(prim, ray, t))
    }

    /// The nearest primitive and distance along every ray of a wave (each without a limit),
    /// into `out`, `width` rays at a time where the shapes allow (see
    /// [`Accel::intersect_wave`]); [`Scene::hit_at`] makes a hit of each.
    pub fn intersect_wave(
        &self,
        rays: &RayColumns,
        width: Width,
        out: &mut Vec<Option<(PrimRef, f32)>>,
    ) {
        self.accel.intersect_wave(&self.shapes, rays, width, out);
    }

    /// Whether anything lies on `ray` closer than `t_max`.
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.accel.occluded(&self.shapes, ray, t_max)
    }

    /// [`Scene::occluded`] for `N` rays (coordinate by coordinate, each up to its `t_max`)
    /// where `done` does not hold already: true where a ray is blocked or done.
    #[inline(always)]
    pub(crate) fn occluded_lanes<const N: usize>(
        &self,
        rays: RayOf<Lanes<N>>,
        t_max: Lanes<N>,
        done: Mask<N>,
    ) -> Mask<N> {
        self.accel.occluded_lanes(&self.shapes, rays, t_max, done)
    }

    /// The nearest hit found by testing every primitive (no BVH): the reference for tests.
    pub fn intersect_brute_force(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let (prim, t) = self.accel.intersect_brute_force(&self.shapes, ray, t_max)?;
        Some(self.hit_at(prim, ray, t))
    }

    /// The hit of primitive `prim` at distance `t` along `ray`, as [`Scene::intersect`]
    /// gives it.
    pub fn hit_at(&self, prim: PrimRef, ray: &Ray, t: f32) -> Hit {
        let o = prim.object as usize;
        Hit {
            surface: self.shapes[o].surface_hit(prim.index, ray, t, self.object_uses_uv[o]),
            object: prim.object,
            material: self.object_materials[o],
        }
    }

    /// The hits of `N` rays that all met `object`, at distances `t`, made in lanes as [`Shape::surface_lanes`] makes them:
    /// their records and material; `None` where they are made ray by ray. Lane i's record
    /// is [`Scene::hit_at`]'s of ray i bit for bit.
    #[inline(always)]
    pub(crate) fn hits_in_lanes<const N: usize>(
        &self,
        object: u32,
        rays: RayOf<Lanes<N>>,
        t: Lanes<N>,
    ) -> Option<(SurfaceLanes<N>, u32)> {
        let i = object as usize;
        let surfaces = self.shapes[i].surface_lanes(rays, t, self.object_uses_uv[i])?;
        Some((surfaces, self.object_materials[i]))
    }
}

/// The image size for a camera made for `aspect` (width over height): as many pixels
/// as 960 × 540, in that shape (an aspect beyond 1:8 or 8:1 is taken as that).
fn size_for_aspect(aspect: f32) -> (u32, u32) {
    let aspect = aspect.clamp(0.125, 8.0);
    let height = (960.0 * 540.0 / aspect).sqrt().round();
    ((height * aspect).round() as u32, height as u32)
}

fn unknown_scene(name: &str) -> SceneError {
    let names: Vec<_> = BUILTIN_SCENES.iter().map(|b| b.name).collect();
    SceneError::new(
        Location::file(name),
        format!(
            "no such scene file, and not a built-in scene (built-in: {})",
            names.join(", ")
        ),
    )
}

/// Whether a file extension (lower case, without the dot) is a model format raylab
/// reads: OBJ or glTF.
pub(crate) fn is_model(ext: &str) -> bool {
    matches!(ext, "obj" | "gltf" | "glb")
}

/// Whether raylab opens the file at `path`, by its extension: a scene (.toml) or a model
/// (.obj, .gltf, .glb).
pub fn opens(path: &Path) -> bool {
    input::extension(path).is_some_and(|e| e == "toml" || is_model(&e))
}
