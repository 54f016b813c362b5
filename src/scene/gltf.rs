//! glTF 2.0 models (`.gltf` with its buffers, or one `.glb`), read with the gltf crate:
//! the triangles of every mesh the default scene places, in world space, and each
//! primitive's metallic-roughness material mapped to the closest raylab material.

use super::obj::{ObjPart, metal_named_in};
use super::{Location, SceneError};
use crate::geometry::Mesh;
use crate::material::{
    Conductor, Dielectric, Diffuse, Emissive, Glossy, Material, Mirror, Texture,
};
use crate::math::{Color, Vec3};
use base64::Engine as _;
use glam::{Mat4, Vec2};
use std::borrow::Cow;

/// The extensions a file may require: those whose data raylab reads (the rest are refused
/// by name).
const READ_EXTENSIONS: [&str; 3] = [
    "KHR_materials_ior",
    "KHR_materials_transmission",
    "KHR_materials_emissive_strength",
];

/// Parses a glTF file: `data` is the `.gltf` JSON or the `.glb` container; `read_buffer`
/// fetches a buffer the file names by a relative URI; `file` names it in messages.
pub fn load_gltf(
    data: &[u8],
    file: &str,
    read_buffer: &dyn Fn(&str) -> Result<Vec<u8>, String>,
) -> Result<Vec<ObjPart>, SceneError> {
    let error = |message: String| SceneError::new(Location::file(file), message);
    // A .gltf saved by a Windows editor may start with a byte-order mark.
    let data = super::input::without_bom(data);
    let unchecked =
        gltf::Gltf::from_slice_without_validation(data).map_err(|e| gltf_error(file, e))?;
    // Before validating: a compressed mesh has no plain data, and validation would call
    // it missing rather than say why.
    if let Some(extension) = unchecked
        .extensions_required()
        .find(|e| !READ_EXTENSIONS.contains(e))
    {
        let what = match extension {
            "KHR_draco_mesh_compression" => " (Draco-compressed meshes)",
            "EXT_meshopt_compression" => " (meshoptimizer-compressed buffers)",
            "KHR_mesh_quantization" => " (quantized vertex attributes)",
            _ => "",
        };
        return Err(error(format!(
            "needs the glTF extension {extension}{what}, which raylab does not read; export the model without it"
        )));
    }
    // gltf-json 1.4's validator indexes the accessors by each POSITION without checking
    // it: checked here first, so that it says what is wrong rather than panicking.
    let json = unchecked.as_json();
    for (m, mesh) in json.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let position = gltf::json::validation::Checked::Valid(gltf::Semantic::Positions);
            if let Some(index) = primitive.attributes.get(&position)
                && index.value() >= json.accessors.len()
            {
                return Err(error(format!(
                    "invalid glTF: meshes[{m}].primitives[{p}].attributes.POSITION is accessor {}, but the file has {}",
                    index.value(),
                    json.accessors.len()
                )));
            }
        }
    }
    let gltf::Gltf { document, blob } = unchecked;
    let document =
        gltf::Document::from_json(document.into_json()).map_err(|e| gltf_error(file, e))?;
    let gltf = gltf::Gltf { document, blob };
    // The .glb's own chunk is borrowed, not copied: it may be most of a large file.
    let mut buffers: Vec<Cow<[u8]>> = Vec::new();
    for buffer in gltf.buffers() {
        let bytes = match buffer.source() {
            gltf::buffer::Source::Bin => Cow::Borrowed(gltf.blob.as_deref().ok_or_else(|| {
                error("a buffer refers to the .glb's binary chunk, which is missing".into())
            })?),
            gltf::buffer::Source::Uri(uri) => Cow::Owned(match uri.strip_prefix("data:") {
                Some(data_uri) => decode_data_uri(data_uri).ok_or_else(|| {
                    error(format!("buffer {}: not a base64 data URI", buffer.index()))
                })?,
                None => read_buffer(uri)
                    .map_err(|e| error(format!("cannot read buffer `{uri}`: {e}")))?,
            }),
        };
        if bytes.len() < buffer.length() {
            return Err(error(format!(
                "buffer {} holds {} bytes, fewer than the {} it declares",
                buffer.index(),
                bytes.len(),
                buffer.length()
            )));
        }
        buffers.push(bytes);
    }
    // The gltf crate checks indices and slices its buffers with bounds checks; a panic
    // left in it on malformed input is reported as an error in the file.
    let parts = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        collect_parts(&gltf, &buffers, file)
    }))
    .map_err(|_| error("the glTF reader failed on this file".into()))??;
    if parts.is_empty() {
        return Err(error("the glTF file has no triangles".into()));
    }
    Ok(parts)
}

/// One glTF error as one line, at the line and column of a JSON error.
fn gltf_error(file: &str, e: gltf::Error) -> SceneError {
    match e {
        gltf::Error::Deserialize(json) => SceneError::new(
            Location {
                file: file.to_string(),
                line_col: (json.line() > 0).then_some((json.line(), Some(json.column()))),
            },
            format!("not valid glTF JSON: {json}"),
        ),
        gltf::Error::Validation(errors) => {
            let (path, what) = errors
                .first()
                .map_or((String::new(), String::new()), |(p, e)| {
                    (p.to_string(), e.to_string())
                });
            SceneError::new(
                Location::file(file),
                format!("invalid glTF: {path}: {what}"),
            )
        }
        other => SceneError::new(Location::file(file), format!("not a glTF file: {other}")),
    }
}

/// The bytes of a `data:` URI's payload (after `data:`), if it is base64.
fn decode_data_uri(uri: &str) -> Option<Vec<u8>> {
    let (_, payload) = uri.split_once(";base64,")?;
    base64::engine::general_purpose::STANDARD
        .decode(payload)
        .ok()
}

/// Every triangle primitive placed by the default scene (or the first; or, with no
/// scenes, every mesh where it stands), transformed to world space.
fn collect_parts(
    gltf: &gltf::Gltf,
    buffers: &[Cow<[u8]>],
    file: &str,
) -> Result<Vec<ObjPart>, SceneError> {
    let mut parts = Vec::new();
    let scene = gltf.default_scene().or_else(|| gltf.scenes().next());
    match scene {
        Some(scene) => {
            // Depth-first, with each node's transform composed onto its parent's; glTF
            // node graphs are trees (the validator refuses cycles), capped at 64 levels.
            let mut stack: Vec<(gltf::Node, Mat4, u32)> =
                scene.nodes().map(|n| (n, Mat4::IDENTITY, 0)).collect();
            while let Some((node, parent, depth)) = stack.pop() {
                let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
                if let Some(mesh) = node.mesh() {
                    add_mesh(&mut parts, &mesh, &world, buffers, file)?;
                }
                if depth < 64 {
                    stack.extend(node.children().map(|c| (c, world, depth + 1)));
                }
            }
        }
        None => {
            for mesh in gltf.meshes() {
                add_mesh(&mut parts, &mesh, &Mat4::IDENTITY, buffers, file)?;
            }
        }
    }
    Ok(parts)
}

fn add_mesh(
    parts: &mut Vec<ObjPart>,
    mesh: &gltf::Mesh,
    world: &Mat4,
    buffers: &[Cow<[u8]>],
    file: &str,
) -> Result<(), SceneError> {
    let name = mesh
        .name()
        .map_or_else(|| format!("mesh{}", mesh.index()), str::to_string);
    let error = |message: String| {
        SceneError::new(Location::file(file), format!("mesh `{name}`: {message}"))
    };
    let normal_matrix = glam::Mat3::from_mat4(*world).inverse().transpose();
    for primitive in mesh.primitives() {
        if primitive.mode() != gltf::mesh::Mode::Triangles {
            continue; // points, lines and strips are not surfaces raylab renders
        }
        let reader = primitive.reader(|b| buffers.get(b.index()).map(|bytes| &bytes[..]));
        let Some(positions) = reader.read_positions() else {
            continue;
        };
        let positions: Vec<Vec3> = positions
            .map(|p| world.transform_point3(glam::Vec3::from(p)).into())
            .collect();
        if !positions.iter().all(|&p| crate::geometry::within_limits(p)) {
            return Err(error(
                "a vertex is not a finite point within the limits".into(),
            ));
        }
        let flat: Vec<u32> = match reader.read_indices() {
            Some(indices) => indices.into_u32().collect(),
            None => (0..positions.len() as u32).collect(),
        };
        // Mesh::new refuses an index past the last vertex.
        let indices: Vec<[u32; 3]> = flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        if indices.is_empty() {
            continue;
        }
        let normals = reader.read_normals().map(|n| {
            n.map(|n| (normal_matrix * glam::Vec3::from(n)).into())
                .collect::<Vec<Vec3>>()
        });
        let normals = normals.filter(|n| n.len() == positions.len());
        let uvs = reader
            .read_tex_coords(0)
            .map(|t| t.into_f32().map(Vec2::from).collect::<Vec<_>>())
            .filter(|t| t.len() == positions.len());
        let triangles =
            Mesh::new(positions, indices, normals, uvs).map_err(|e| error(e.to_string()))?;
        let material = primitive.material();
        parts.push(ObjPart {
            name: if mesh.primitives().len() > 1 {
                format!("{name}.{}", primitive.index())
            } else {
                name.clone()
            },
            mesh: triangles,
            // The glTF default material (no `material`) is left to the scene.
            material: material.index().map(|index| {
                let name = material
                    .name()
                    .map_or_else(|| format!("material{index}"), str::to_string);
                let mapped = map_material(&material, &name);
                (name, mapped)
            }),
        });
    }
    Ok(())
}

/// Maps a metallic-roughness material to raylab's closest: emissive if it emits; glass
/// (a dielectric of its KHR_materials_ior index, 1.5 without) if it transmits at least
/// half; a metal if metallic at least half, the measured conductor its name contains
/// (`Gold`, `copper`) or else a mirror of its base colour, glossy when rough; otherwise
/// diffuse in its base colour. Roughness r becomes a Phong exponent by the usual match of
/// lobe widths, n = 2/α² − 2 with α = r²; below r = 0.05 the surface is polished.
fn map_material(m: &gltf::Material, name: &str) -> Material {
    let pbr = m.pbr_metallic_roughness();
    let unit = |v: f32, default: f32| {
        if v.is_finite() {
            v.clamp(0.0, 1.0)
        } else {
            default
        }
    };
    let [r, g, b, _] = pbr.base_color_factor().map(|c| unit(c, 0.8));
    let base = Color::new(r, g, b);
    let strength = m
        .emissive_strength()
        .filter(|s| s.is_finite() && *s > 0.0)
        .unwrap_or(1.0);
    let emitted = Color::from(m.emissive_factor().map(|c| unit(c, 0.0))) * strength.min(1e4);
    if emitted.max_element() > 0.0 {
        return Material::Emissive(Emissive::solid(emitted));
    }
    let roughness = unit(pbr.roughness_factor(), 1.0);
    let exponent = (roughness >= 0.05).then(|| {
        let alpha = roughness * roughness;
        (2.0 / (alpha * alpha) - 2.0).clamp(1.0, crate::params::MAX_PHONG_EXPONENT)
    });
    let transmission = m
        .transmission()
        .map_or(0.0, |t| unit(t.transmission_factor(), 0.0));
    if transmission >= 0.5 {
        let ior = m.ior().filter(|n| (1.0..=3.0).contains(n)).unwrap_or(1.5);
        return Material::Dielectric(Dielectric::clear(ior));
    }
    if unit(pbr.metallic_factor(), 1.0) >= 0.5 {
        return match (metal_named_in(name), exponent) {
            (Some(metal), exponent) => Material::Conductor(Conductor {
                eta: metal.eta(),
                k: metal.k(),
                exponent,
            }),
            (None, Some(exponent)) => Material::Glossy(Glossy {
                reflectance: base,
                exponent,
            }),
            (None, None) => Material::Mirror(Mirror { reflectance: base }),
        };
    }
    Material::Diffuse(Diffuse {
        albedo: Texture::Solid(base),
        specular: Color::ZERO,
        exponent: 1.0,
    })
}
