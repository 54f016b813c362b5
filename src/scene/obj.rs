//! Wavefront OBJ meshes, read with tobj, with errors that name the line.

use super::{Location, SceneError};
use crate::camera::Camera;
use crate::geometry::Mesh;
use crate::light::Light;
use crate::material::{Conductor, Diffuse, Emissive, Material, Mirror, Texture};
use crate::math::{Color, Vec3};
use glam::Vec2;
use std::cell::RefCell;
use std::io::{BufRead, Read};
use std::path::Path;

/// One object of a model file (an OBJ object, a glTF primitive): its triangles and, if
/// the file gave one, its material.
#[derive(Clone, Debug)]
pub struct ObjPart {
    /// The object's name in the file.
    pub name: String,
    /// Its triangles.
    pub mesh: Mesh,
    /// Its material from the file (the .mtl, the glTF material), mapped to a raylab
    /// material, and its name there.
    pub material: Option<(String, Material)>,
    /// Where the model places it, in the model's coordinates: once, as it stands (an OBJ
    /// object, a glTF mesh one node places, its triangles already moved there), or once
    /// per node that places it (a glTF mesh several nodes place: built once, instanced).
    pub at: Vec<glam::Affine3A>,
}

/// A model file's objects, and what the user should know of how it was read.
#[derive(Clone, Debug)]
pub struct Model {
    /// Its objects.
    pub parts: Vec<ObjPart>,
    /// Its camera, in the model's own coordinates (a glTF file's; OBJ has none).
    pub camera: Option<ModelCamera>,
    /// Its lights, in the model's own coordinates (a glTF file's KHR_lights_punctual).
    pub lights: Vec<Light>,
    /// What was missing but not fatal (a material library that is not there), one line
    /// each, naming the file.
    pub warnings: Vec<String>,
}

/// A camera a model file defines.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelCamera {
    /// Where it stands and looks, with its vertical field of view.
    pub camera: Camera,
    /// Width over height of the image it was made for, if the file says.
    pub aspect: Option<f32>,
}

/// Parses OBJ text. `read_mtl` fetches a material library named by `mtllib`;
/// `file` names the OBJ in error messages.
pub fn load_obj(
    data: &[u8],
    file: &str,
    read_mtl: &dyn Fn(&str) -> Option<Vec<u8>>,
) -> Result<Model, SceneError> {
    let data = super::input::without_bom(data);
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let mut reader = LineCounter {
        data,
        pos: 0,
        newlines: 0,
    };
    let failed_mtl = RefCell::new(None::<String>);
    let bad_mtl = RefCell::new(None::<SceneError>);
    let read_mtl_label = RefCell::new(None::<String>);
    let mtl_label = |name: &str| Path::new(file).with_file_name(name).display().to_string();
    // tobj panics on some malformed input: it is given only text checked here, and any
    // panic left is caught and reported as an error in the file.
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        tobj::load_obj_buf(&mut reader, &options, |p: &Path| {
            let name = p.to_string_lossy().into_owned();
            match read_mtl(&name) {
                Some(bytes) => {
                    let text = super::input::without_bom(&bytes);
                    match check_mtl(text, &mtl_label(&name)) {
                        Ok(()) => {
                            // The library a parse error that tobj reports alone is in.
                            *read_mtl_label.borrow_mut() = Some(mtl_label(&name));
                            tobj::load_mtl_buf(&mut &text[..])
                        }
                        Err(e) => {
                            bad_mtl.borrow_mut().get_or_insert(e);
                            Err(tobj::LoadError::MaterialParseError)
                        }
                    }
                }
                None => {
                    failed_mtl.borrow_mut().get_or_insert(name);
                    Err(tobj::LoadError::OpenFileFailed)
                }
            }
        })
    }))
    .map_err(|_| {
        SceneError::new(
            Location::file(file),
            "the OBJ reader (tobj) failed on this file or its material library",
        )
    })?;
    if let Some(e) = bad_mtl.into_inner() {
        return Err(e);
    }
    let (models, materials) = match result {
        Ok(ok) => ok,
        Err(e) => return Err(obj_error(data, file, e, reader.current_line())),
    };
    // A missing or broken .mtl is not fatal: the scene may give the material, and
    // otherwise the default one is used; but a .mtl that exists and is broken is an error.
    let mut warnings = Vec::new();
    let materials = match (materials, failed_mtl.into_inner()) {
        (Ok(m), _) => m,
        (Err(_), Some(missing)) => {
            warnings.push(format!(
                "{file}: its material library `{missing}` cannot be read (looked for {}); its objects get the scene's or the default material",
                mtl_label(&missing)
            ));
            Vec::new()
        }
        (Err(e), None) => {
            return Err(match read_mtl_label.into_inner() {
                Some(mtl) => SceneError::new(
                    Location::file(mtl),
                    format!("malformed material library ({e})"),
                ),
                None => SceneError::new(
                    Location::file(file),
                    format!("its material library is malformed ({e})"),
                ),
            });
        }
    };
    let mut parts = Vec::new();
    for model in models {
        let m = model.mesh;
        let positions = triples(&m.positions);
        if m.indices.is_empty() {
            continue;
        }
        if !positions.iter().all(|&p| crate::geometry::within_limits(p)) {
            let (line, col, message) = find_bad_vertex(&String::from_utf8_lossy(data)).unwrap_or((
                0,
                0,
                "a vertex is not a finite point within the limits".into(),
            ));
            return Err(SceneError::new(
                Location {
                    file: file.to_string(),
                    line_col: (line > 0).then_some((line, Some(col))),
                },
                message,
            ));
        }
        let indices: Vec<[u32; 3]> = m
            .indices
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect();
        let normals = (!m.normals.is_empty()).then(|| triples(&m.normals));
        let uvs = (!m.texcoords.is_empty()).then(|| {
            m.texcoords
                .chunks_exact(2)
                .map(|c| Vec2::new(c[0], c[1]))
                .collect::<Vec<_>>()
        });
        let mesh = Mesh::new(positions, indices, normals, uvs).map_err(|e| {
            SceneError::new(
                Location::file(file),
                format!("object `{}`: {e}", model.name),
            )
        })?;
        let material = m
            .material_id
            .and_then(|i| materials.get(i))
            .map(|mtl| (mtl.name.clone(), map_material(mtl)));
        parts.push(ObjPart {
            name: model.name,
            mesh,
            material,
            at: vec![glam::Affine3A::IDENTITY],
        });
    }
    if parts.is_empty() {
        return Err(SceneError::new(
            Location::file(file),
            "the OBJ file has no faces",
        ));
    }
    Ok(Model {
        parts,
        camera: None,
        lights: Vec::new(),
        warnings,
    })
}

fn triples(v: &[f32]) -> Vec<Vec3> {
    v.chunks_exact(3)
        .map(|c| Vec3::new(c[0], c[1], c[2]))
        .collect()
}

/// Maps a .mtl material to raylab's: where `Ke` is set, a light of `Ke` if it has no `Kd`,
/// else its diffuse `Kd` (with its `Ks` highlight) glowing with `Ke`, as MTL adds `Ke` to
/// the surface's own shading (raylab's glowing surfaces are diffuse, whatever its `Pm`);
/// a metal if the PBR extension's metallic `Pm` (which Blender writes) is at least 0.5:
/// the measured conductor its name
/// contains (`Gold`, `brushed_copper`), else a mirror of its base colour `Kd`; a mirror
/// for the ray-traced reflection models (illum 3 and 5); otherwise diffuse with a Phong
/// highlight.
fn map_material(m: &tobj::Material) -> Material {
    let rgb = |c: Option<[f32; 3]>, default: f32| {
        let c = c.map_or(Color::splat(default), Color::from);
        if c.is_finite() {
            c.clamp(Color::ZERO, Color::ONE)
        } else {
            Color::splat(default)
        }
    };
    let diffuse = |emission| {
        Material::Diffuse(Diffuse {
            albedo: Texture::Solid(rgb(m.diffuse, 0.7)),
            specular: rgb(m.specular, 0.0),
            exponent: m
                .shininess
                .filter(|s| s.is_finite() && *s > 0.0)
                .unwrap_or(1.0),
            emission,
        })
    };
    let emissive = rgb(m.emissive, 0.0);
    if emissive.max_element() > 0.0 {
        return match m.diffuse {
            None => Material::Emissive(Emissive::solid(emissive)),
            Some(_) => diffuse(Some(Texture::Solid(emissive))),
        };
    }
    let metallic = m
        .unknown_param
        .get("Pm")
        .and_then(|v| v.trim().parse::<f32>().ok())
        .is_some_and(|pm| pm >= 0.5);
    if metallic {
        return match metal_named_in(&m.name) {
            Some(metal) => Material::Conductor(Conductor {
                eta: metal.eta(),
                k: metal.k(),
                exponent: None,
            }),
            None => Material::Mirror(Mirror {
                reflectance: rgb(m.diffuse, 0.9),
            }),
        };
    }
    match m.illumination_model {
        Some(3) | Some(5) => Material::Mirror(Mirror {
            reflectance: rgb(m.specular, 0.9),
        }),
        _ => diffuse(None),
    }
}

/// The measured metal whose full name a material's name contains, ignoring case
/// ("aluminum" too); chemical symbols are not matched ("Cu" is in "Cube").
pub(super) fn metal_named_in(name: &str) -> Option<&'static crate::material::Metal> {
    let name = name.to_ascii_lowercase().replace("aluminum", "aluminium");
    crate::material::METALS
        .iter()
        .find(|m| name.contains(m.name))
}

/// Turns a tobj error into one that names the line. tobj reads one line at a time and
/// stops at the first bad one, except for face indices out of range, which it finds only
/// when an object ends: those are located by scanning the faces here.
fn obj_error(data: &[u8], file: &str, e: tobj::LoadError, line: usize) -> SceneError {
    use tobj::LoadError::*;
    let text = String::from_utf8_lossy(data);
    match e {
        FaceVertexOutOfBounds | FaceTexCoordOutOfBounds | FaceNormalOutOfBounds => {
            match find_bad_face_index(&text) {
                Some((line, col, message)) => SceneError::new(
                    Location {
                        file: file.to_string(),
                        line_col: Some((line, Some(col))),
                    },
                    message,
                ),
                None => SceneError::new(Location::file(file), e.to_string()),
            }
        }
        _ => SceneError::new(Location::at_line(file, line), format!("{e} in OBJ")),
    }
}

/// The first face index that refers to a vertex, texture coordinate or normal that does
/// not exist: (line, column, message).
fn find_bad_face_index(text: &str) -> Option<(usize, usize, String)> {
    let count = |tag: &str| {
        text.lines()
            .filter(|l| l.split_whitespace().next() == Some(tag))
            .count()
    };
    let totals = [count("v"), count("vt"), count("vn")];
    let mut seen = [0usize; 3];
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => seen[0] += 1,
            Some("vt") => seen[1] += 1,
            Some("vn") => seen[2] += 1,
            Some("f") => {
                for word in words {
                    for (k, idx) in word.split('/').enumerate().take(3) {
                        if idx.is_empty() {
                            continue;
                        }
                        let Ok(i) = idx.parse::<i64>() else { continue };
                        // Positive indices count from the file's start, negative ones back
                        // from the latest element.
                        let ok = if i > 0 {
                            i as usize <= totals[k]
                        } else {
                            i < 0 && i.unsigned_abs() as usize <= seen[k]
                        };
                        if !ok {
                            let what = ["vertex", "texture coordinate", "normal"][k];
                            let col = line.find(word).map_or(1, |c| c + 1);
                            let have = if i > 0 { totals[k] } else { seen[k] };
                            return Some((
                                n + 1,
                                col,
                                format!("face refers to {what} {i}, but there are {have}"),
                            ));
                        }
                    }
                }
            }
            _ => {}
        }
    }
    None
}

/// The first vertex (`v` line) with a coordinate that is not finite or lies beyond
/// ±[`crate::geometry::MAX_COORDINATE`]: (line, column, message).
fn find_bad_vertex(text: &str) -> Option<(usize, usize, String)> {
    let limit = crate::geometry::MAX_COORDINATE;
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        if words.next() != Some("v") {
            continue;
        }
        for word in words.take(3) {
            let Ok(x) = word.parse::<f32>() else { continue };
            if !x.is_finite() || x.abs() > limit {
                let col = line.find(word).map_or(1, |c| c + 1);
                let what = if x.is_finite() {
                    format!("is beyond ±{limit:e}, the largest coordinate raylab handles")
                } else {
                    "is not a finite number".to_string()
                };
                return Some((n + 1, col, format!("vertex coordinate {word} {what}")));
            }
        }
    }
    None
}

/// Checks what tobj does not, so that a bad line is named by its line and column rather
/// than as "malformed": a colour (`Ka`, `Kd`, `Ks`, `Ke`, `Tf`) needs three numbers (tobj 4
/// panics on fewer), and every number tobj reads must be a finite f32 (`Ni 1e39` would
/// otherwise become an infinite index). `file` names the library in the error.
fn check_mtl(bytes: &[u8], file: &str) -> Result<(), SceneError> {
    let text = String::from_utf8_lossy(bytes);
    for (n, line) in text.lines().enumerate() {
        let at = |col: usize, message: String| {
            SceneError::new(
                Location {
                    file: file.to_string(),
                    line_col: Some((n + 1, Some(col))),
                },
                message,
            )
        };
        let mut words = line.split_whitespace();
        let Some(key) = words.next() else { continue };
        let count = match key {
            "Ka" | "Kd" | "Ks" | "Ke" | "Tf" => 3,
            "Ns" | "Ni" | "d" | "Tr" | "Pm" | "Pr" => 1,
            _ => continue,
        };
        // Each word is a slice of `line`: its column is where it starts.
        let col_of = |word: &str| {
            let offset = word.as_ptr() as usize - line.as_ptr() as usize;
            offset + 1
        };
        let numbers: Vec<&str> = words.take(count).collect();
        if numbers.len() < count {
            let what = if count == 3 {
                "three numbers (r g b)"
            } else {
                "a number"
            };
            return Err(at(
                col_of(key),
                format!("`{key}` needs {what}, got {}", numbers.len()),
            ));
        }
        for word in numbers {
            if !word.parse::<f32>().is_ok_and(f32::is_finite) {
                return Err(at(
                    col_of(word),
                    format!("`{key}`: `{word}` is not a finite number"),
                ));
            }
        }
    }
    Ok(())
}

/// A reader over bytes that counts the newlines consumed, so that when tobj stops at a bad
/// line, we know which one.
struct LineCounter<'a> {
    data: &'a [u8],
    pos: usize,
    newlines: usize,
}

impl LineCounter<'_> {
    /// The 1-based number of the line read last.
    fn current_line(&self) -> usize {
        let ended_on_newline = self.pos > 0 && self.data[self.pos - 1] == b'\n';
        self.newlines + usize::from(!ended_on_newline)
    }
}

impl Read for LineCounter<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.fill_buf()?.read(buf)?;
        self.consume(n);
        Ok(n)
    }
}

impl BufRead for LineCounter<'_> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        Ok(&self.data[self.pos..])
    }

    fn consume(&mut self, amt: usize) {
        let end = (self.pos + amt).min(self.data.len());
        self.newlines += self.data[self.pos..end]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        self.pos = end;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn no_mtl(_: &str) -> Option<Vec<u8>> {
        None
    }

    #[test]
    fn metallic_mtl_materials_become_the_metal_they_name() {
        let mtl = b"newmtl Brushed_Gold\nKd 1 0.8 0.3\nPm 1.0\n\
                    newmtl chrome\nKd 0.6 0.6 0.6\nPm 0.9\n\
                    newmtl copper_paint\nKd 0.7 0.3 0.2\nPm 0.2\n";
        let obj = b"mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n\
                    usemtl Brushed_Gold\nf 1 2 3\nusemtl chrome\nf 1 2 3\n\
                    usemtl copper_paint\nf 1 2 3\n";
        let parts = load_obj(obj, "m.obj", &|_: &str| Some(mtl.to_vec()))
            .unwrap()
            .parts;
        let kinds: Vec<_> = parts
            .iter()
            .map(|p| p.material.as_ref().map(|(_, m)| m.kind()))
            .collect();
        assert_eq!(
            kinds,
            [Some("conductor"), Some("mirror"), Some("diffuse")],
            "gold by name; metallic with no metal's name a mirror of Kd; Pm < 0.5 not metal"
        );
        let gold = crate::material::metal("gold").unwrap();
        assert!(matches!(
            &parts[0].material.as_ref().unwrap().1,
            Material::Conductor(c) if c.eta == gold.eta() && c.k == gold.k()
        ));
    }

    #[test]
    fn ke_over_a_kd_glows_over_it_and_ke_alone_is_a_light() {
        let mtl = b"newmtl screen\nKd 0.2 0.3 0.4\nKe 1 0.5 0\nPm 1\n\
                    newmtl bulb\nKe 0.9 0.9 0.8\n";
        let obj = b"mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n\
                    usemtl screen\nf 1 2 3\nusemtl bulb\nf 1 2 3\n";
        let parts = load_obj(obj, "m.obj", &|_: &str| Some(mtl.to_vec()))
            .unwrap()
            .parts;
        let material = |i: usize| parts[i].material.as_ref().unwrap().1.clone();
        let Material::Diffuse(screen) = material(0) else {
            panic!("{:?}", material(0));
        };
        assert_eq!(screen.albedo, Texture::Solid(Color::new(0.2, 0.3, 0.4)));
        assert_eq!(
            screen.emission,
            Some(Texture::Solid(Color::new(1.0, 0.5, 0.0)))
        );
        assert_eq!(
            material(1),
            Material::Emissive(Emissive::solid(Color::new(0.9, 0.9, 0.8)))
        );
    }

    #[test]
    fn loads_a_quad_as_two_triangles() {
        let obj = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
        let parts = load_obj(obj, "q.obj", &no_mtl).unwrap().parts;
        assert_eq!(parts.len(), 1);
        assert_eq!(parts[0].mesh.triangle_count(), 2);
        assert!(parts[0].material.is_none());
    }

    #[test]
    fn parse_errors_name_the_line() {
        let obj = b"v 0 0 0\nv 1 0 0\nv 1 x 0\nf 1 2 3\n";
        let e = load_obj(obj, "bad.obj", &no_mtl).unwrap_err();
        assert_eq!(e.location.to_string(), "bad.obj:3", "{e}");
    }

    #[test]
    fn out_of_range_faces_name_line_and_column() {
        let obj = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\nf 1 2 9\n";
        let e = load_obj(obj, "bad.obj", &no_mtl).unwrap_err();
        assert_eq!(e.location.to_string(), "bad.obj:5:7", "{e}");
        assert!(e.message.contains("vertex 9"), "{e}");
    }

    #[test]
    fn mtl_materials_are_mapped() {
        let obj = b"mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl shiny\nf 1 2 3\n";
        let mtl = |name: &str| {
            (name == "m.mtl").then(|| b"newmtl shiny\nKs 0.8 0.7 0.6\nillum 3\n".to_vec())
        };
        let parts = load_obj(obj, "m.obj", &mtl).unwrap().parts;
        let (name, m) = parts[0].material.clone().unwrap();
        assert_eq!(name, "shiny");
        assert!(matches!(m, Material::Mirror(_)));
    }

    #[test]
    fn short_mtl_colours_are_refused_with_their_line() {
        let obj = b"mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl a\nf 1 2 3\n";
        for (mtl, col) in [("newmtl a\n  Kd 1\n", 3), ("newmtl a\nKd\n", 1)] {
            let read = |_: &str| Some(mtl.as_bytes().to_vec());
            let e = load_obj(obj, "dir/m.obj", &read).unwrap_err();
            assert_eq!(e.location.to_string(), format!("dir/m.mtl:2:{col}"), "{e}");
            assert!(e.message.contains("three numbers"), "{e}");
        }
    }

    #[test]
    fn far_or_infinite_vertices_name_line_and_column() {
        for (v, message) in [
            ("1e20", "beyond"),
            ("inf", "not a finite"),
            ("NaN", "not a finite"),
        ] {
            let obj = format!("v 0 0 0\nv 1 0 0\nv 0  {v} 0\nf 1 2 3\n");
            let e = load_obj(obj.as_bytes(), "far.obj", &no_mtl).unwrap_err();
            assert_eq!(e.location.to_string(), "far.obj:3:6", "{e}");
            assert!(e.message.contains(message), "{e}");
        }
    }

    #[test]
    fn empty_obj_is_an_error() {
        let e = load_obj(b"# nothing\n", "e.obj", &no_mtl).unwrap_err();
        assert!(e.message.contains("no faces"), "{e}");
    }
}
