//! glTF 2.0 models (`.gltf` with its buffers, or one `.glb`), read with the gltf crate:
//! the triangles of every mesh the default scene places, in world space, each
//! primitive's metallic-roughness material mapped to the closest raylab material (with
//! its base-colour and emissive textures), the scene's camera and its
//! KHR_lights_punctual lights.

mod materials;
mod nodes;

use super::obj::Model;
use super::{Location, SceneError};
use base64::Engine as _;
use std::borrow::Cow;

/// The extensions a file may require: those whose data raylab reads (the rest are refused
/// by name).
const READ_EXTENSIONS: [&str; 4] = [
    "KHR_materials_ior",
    "KHR_materials_transmission",
    "KHR_materials_emissive_strength",
    "KHR_lights_punctual",
];

/// Reads a file the glTF names by a relative URI (a buffer, an image): its bytes, or why
/// not.
type ReadFile<'a> = &'a dyn Fn(&str) -> Result<Vec<u8>, String>;

/// Parses a glTF file: `data` is the `.gltf` JSON or the `.glb` container; `read_file`
/// fetches a buffer or an image the file names by a relative URI; `file` names it in
/// messages. The model's parts, camera and lights are in its own coordinates.
pub fn load_gltf(data: &[u8], file: &str, read_file: ReadFile) -> Result<Model, SceneError> {
    let error = |message: String| SceneError::new(Location::file(file), message);
    // A .gltf saved by a Windows editor may start with a byte-order mark.
    let data = super::input::without_bom(data);
    let mut warnings = Vec::new();
    let unchecked = read_unchecked(data, file, &mut warnings)?;
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
    nodes::check_tree(json).map_err(|m| error(format!("invalid glTF: {m}")))?;
    // gltf 1.4 unwraps an image's source and a buffer view's MIME type without checking.
    for (i, image) in json.images.iter().enumerate() {
        match (&image.uri, &image.buffer_view, &image.mime_type) {
            (None, None, _) => {
                return Err(error(format!(
                    "invalid glTF: images[{i}] has neither a uri nor a bufferView"
                )));
            }
            (None, Some(_), None) => {
                return Err(error(format!(
                    "invalid glTF: images[{i}] is in a bufferView but has no mimeType"
                )));
            }
            _ => {}
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
            gltf::buffer::Source::Uri(uri) => Cow::Owned(
                read_uri(uri, read_file)
                    .map_err(|e| error(format!("buffer {}: {e}", buffer.index())))?,
            ),
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
    let model = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        nodes::collect(&gltf, &buffers, file, read_file)
    }))
    .map_err(|_| error("the glTF reader failed on this file".into()))??;
    if model.parts.is_empty() {
        return Err(error("the glTF file has no triangles".into()));
    }
    warnings.extend(model.warnings);
    Ok(Model { warnings, ..model })
}

/// The file's JSON (from a `.gltf`, or a `.glb`'s JSON chunk) read without validation,
/// with what raylab does not render taken out so that it is ignored, as glTF says a
/// reader may: animations (said where KHR_animation_pointer drives them, as a reader
/// without it is told to fall back to the still scene) and application-specific vertex
/// attributes (`_TEMPERATURE`). glTF 1.0 is refused by name.
fn read_unchecked(
    data: &[u8],
    file: &str,
    warnings: &mut Vec<String>,
) -> Result<gltf::Gltf, SceneError> {
    let error = |message: String| SceneError::new(Location::file(file), message);
    let v1 = || {
        error(
        "is glTF 1.0, which raylab does not read; convert it to glTF 2.0 (Blender, or gltf-pipeline)".into(),
    )
    };
    let is_v1 = |version: &str| version == "1" || version.starts_with("1.");
    let (json, blob) = if data.starts_with(b"glTF") {
        if data.get(4..8) == Some(&1u32.to_le_bytes()[..]) {
            return Err(v1());
        }
        let mut glb = gltf::binary::Glb::from_slice(data).map_err(|e| gltf_error(file, e))?;
        let bin = glb.bin.take().map(Cow::into_owned);
        (glb.json, bin)
    } else {
        (Cow::Borrowed(data), None)
    };
    let positioned = |e: serde_json::Error| gltf_error(file, gltf::Error::Deserialize(e));
    // Read once as glTF 2.0, with errors at their line and column. Only a file that does
    // not read is read again as plain JSON: glTF 1.0, or animations this crate cannot
    // read (KHR_animation_pointer's targets name no node), taken out.
    let mut root = match gltf::json::Root::from_slice(&json) {
        Ok(root) => root,
        Err(first) => {
            let Ok(mut value) = serde_json::from_slice::<serde_json::Value>(&json) else {
                return Err(positioned(first));
            };
            let version = value.pointer("/asset/version").and_then(|v| v.as_str());
            if version.is_some_and(is_v1) {
                return Err(v1());
            }
            let animated = value
                .as_object_mut()
                .and_then(|root| root.remove("animations"))
                .is_some();
            match animated {
                true => serde_json::from_value(value)
                    .map_err(|e| error(format!("not valid glTF JSON: {e}")))?,
                false => return Err(positioned(first)),
            }
        }
    };
    if is_v1(&root.asset.version) {
        return Err(v1());
    }
    let pointer = "KHR_animation_pointer";
    if root
        .extensions_used
        .iter()
        .chain(&root.extensions_required)
        .any(|e| e == pointer)
    {
        warnings.push(format!(
            "{file}: its animations (KHR_animation_pointer) are left out: raylab renders the still scene"
        ));
    }
    root.extensions_required.retain(|e| e != pointer);
    root.animations.clear();
    // Attributes glTF does not define (an application's `_NAME`) are not read.
    for mesh in &mut root.meshes {
        for primitive in &mut mesh.primitives {
            primitive
                .attributes
                .retain(|k, _| matches!(k, gltf::json::validation::Checked::Valid(_)));
        }
    }
    Ok(gltf::Gltf {
        document: gltf::Document::from_json_without_validation(root),
        blob,
    })
}

/// The bytes a buffer's or image's URI names: a base64 `data:` URI's payload, or a file
/// beside the glTF (its URI percent-decoded, as `my%20texture.png` names
/// `my texture.png`).
fn read_uri(uri: &str, read_file: ReadFile) -> Result<Vec<u8>, String> {
    match uri.strip_prefix("data:") {
        Some(data_uri) => decode_data_uri(data_uri).ok_or_else(|| "not a base64 data URI".into()),
        None => {
            let name = percent_decoded(uri);
            read_file(&name).map_err(|e| format!("cannot read `{name}`: {e}"))
        }
    }
}

/// `uri` with each `%XX` escape replaced by its byte (an escape that is not two hex digits
/// is kept as written).
fn percent_decoded(uri: &str) -> String {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = bytes
            .get(i + 1..i + 3)
            .and_then(|h| std::str::from_utf8(h).ok())
            .and_then(|h| u8::from_str_radix(h, 16).ok());
        match (bytes[i], hex) {
            (b'%', Some(byte)) => {
                out.push(byte);
                i += 3;
            }
            (b, _) => {
                out.push(b);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
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

#[cfg(test)]
mod tests {
    use super::percent_decoded;

    #[test]
    fn uris_are_percent_decoded_as_exporters_encode_them() {
        assert_eq!(percent_decoded("my%20texture.png"), "my texture.png");
        assert_eq!(percent_decoded("caf%C3%A9/%41.jpg"), "café/A.jpg");
        // What is not an escape stays as written.
        assert_eq!(percent_decoded("100%.png"), "100%.png");
        assert_eq!(percent_decoded("a%zz%2"), "a%zz%2");
        assert_eq!(percent_decoded("plain.bin"), "plain.bin");
    }
}
