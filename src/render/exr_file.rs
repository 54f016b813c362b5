//! EXR files that carry how they were made: linear radiance (32-bit float RGB, lossless
//! compression), and in the header the software, the scene, every parameter and the whole
//! sidecar, as text attributes a viewer such as tev or `exrheader` lists.

use super::Sidecar;
use crate::math::Color;
use exr::prelude::{
    AttributeValue, Encoding, Image, Layer, LayerAttributes, SpecificChannels, Text, WritableImage,
};

/// The prefix of raylab's own header attributes: `raylab:ior`, `raylab:sidecar`, ...
pub const ATTRIBUTE_PREFIX: &str = "raylab:";

/// A header text: EXR's is Latin-1, so any other character is written as a JSON-style
/// `\uXXXX` escape (the sidecar's JSON stays valid JSON).
fn text(s: &str) -> Text {
    let escaped: String = s
        .chars()
        .map(|c| {
            if (c as u32) < 0x80 {
                c.to_string()
            } else {
                c.encode_utf16(&mut [0; 2])
                    .iter()
                    .map(|u| format!("\\u{u:04x}"))
                    .collect()
            }
        })
        .collect();
    // Only ASCII is left, which EXR text always holds.
    Text::new_or_none(&escaped).unwrap_or_default()
}

/// The EXR file of `pixels` (`width` × `height`, row-major, linear), with `sidecar`'s
/// facts in its header: `raylab:scene`, one `raylab:NAME` per parameter that is set (its
/// value as in `--set NAME=VALUE`), and `raylab:sidecar` (the sidecar's JSON, as
/// [`Sidecar::embedded_json`] gives it).
pub(crate) fn exr_bytes(
    width: u32,
    height: u32,
    pixels: &[Color],
    sidecar: Option<&Sidecar>,
) -> Result<Vec<u8>, exr::error::Error> {
    let mut attributes = LayerAttributes {
        software_name: Some(text(&format!("raylab {}", crate::VERSION_LINE))),
        ..LayerAttributes::default()
    };
    if let Some(sidecar) = sidecar {
        let mut add = |name: &str, value: &str| {
            attributes.other.insert(
                text(&format!("{ATTRIBUTE_PREFIX}{name}")),
                AttributeValue::Text(text(value)),
            );
        };
        add("scene", &sidecar.scene);
        // Through JSON text, so that an f32 reads as written (1.33, not 1.3300000429...).
        let params = serde_json::to_string(&sidecar.params)
            .ok()
            .and_then(|json| serde_json::from_str(&json).ok());
        if let Some(serde_json::Value::Object(params)) = params {
            for (name, value) in params {
                match value {
                    // Unset: each material keeps its own.
                    serde_json::Value::Null => {}
                    serde_json::Value::String(s) => add(&name, &s),
                    other => add(&name, &other.to_string()),
                }
            }
        }
        attributes.other.insert(
            text(super::SIDECAR_KEY),
            AttributeValue::Text(text(&sidecar.embedded_json())),
        );
    }
    let w = width as usize;
    let layer = Layer::new(
        (w, height as usize),
        attributes,
        Encoding::SMALL_LOSSLESS,
        SpecificChannels::rgb(|p: exr::math::Vec2<usize>| {
            let c = pixels
                .get(p.y() * w + p.x())
                .copied()
                .unwrap_or(Color::ZERO);
            (c.x, c.y, c.z)
        }),
    );
    let mut bytes = std::io::Cursor::new(Vec::new());
    Image::from_layer(layer).write().to_buffered(&mut bytes)?;
    Ok(bytes.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::Params;

    #[test]
    fn the_header_carries_every_parameter_and_the_sidecar() {
        let pixels: Vec<Color> = (0..6).map(|i| Color::splat(i as f32 * 0.25)).collect();
        let sidecar = Sidecar {
            raylab_version: crate::VERSION.into(),
            raylab_commit: Some("1a2b3c4d5e6f".into()),
            scene: "scènes/glass.toml".into(),
            width: 3,
            height: 2,
            params: Params {
                ior: Some(1.33),
                ..Params::default()
            },
            samples: None,
            camera: None,
            image: Some("a.exr".into()),
            seconds: None,
            stats: None,
            reference: None,
            crop: None,
        };
        let bytes = exr_bytes(3, 2, &pixels, Some(&sidecar)).unwrap();
        let meta =
            exr::meta::MetaData::read_from_buffered(std::io::Cursor::new(&bytes), false).unwrap();
        let header = &meta.headers[0];
        let get = |name: &str| match header.own_attributes.other.get(&text(name)) {
            Some(AttributeValue::Text(t)) => t.to_string(),
            other => panic!("{name}: {other:?}"),
        };
        assert_eq!(get("raylab:ior"), "1.33");
        assert_eq!(get("raylab:max_depth"), "8");
        assert_eq!(get("raylab:pattern"), "sobol");
        // Unset (each material its own): not written.
        assert!(
            !header
                .own_attributes
                .other
                .contains_key(&text("raylab:fresnel"))
        );
        assert_eq!(get("raylab:scene"), "sc\\u00e8nes/glass.toml");
        let back: Sidecar = serde_json::from_str(&get("raylab:sidecar")).unwrap();
        assert_eq!(back.scene, "scènes/glass.toml");
        assert_eq!(back.raylab_commit.as_deref(), Some("1a2b3c4d5e6f"));
        // The software: the version and, where known, the commit.
        let software = header.own_attributes.software_name.as_ref().unwrap();
        assert_eq!(
            software.to_string(),
            format!("raylab {}", crate::VERSION_LINE)
        );
        assert_eq!(back.params, sidecar.params);
        // And the pixels, as the image crate reads them back.
        let image = image::load_from_memory(&bytes).unwrap().into_rgb32f();
        assert_eq!(image.get_pixel(2, 1).0, [1.25; 3]);
    }
}
