//! PNG files that carry how they were made: 8-bit sRGB, with the sidecar in an iTXt chunk
//! (`raylab:sidecar`, UTF-8 JSON) and the program in a `Software` text chunk, so that an
//! image can be reproduced from itself and can never be paired with the wrong description.
//! `exiftool` and `pngcheck -t` list them.

use std::path::Path;

/// The key of the sidecar's JSON in a PNG's iTXt chunk and an EXR's header.
pub const SIDECAR_KEY: &str = "raylab:sidecar";

/// The PNG file of 8-bit `data` (`width` × `height`, rows of RGB, or RGBA if `alpha`),
/// with `sidecar` (its JSON) inside.
pub(crate) fn png_bytes(
    width: u32,
    height: u32,
    alpha: bool,
    data: &[u8],
    sidecar: Option<&str>,
) -> Result<Vec<u8>, png::EncodingError> {
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, width, height);
    encoder.set_color(if alpha {
        png::ColorType::Rgba
    } else {
        png::ColorType::Rgb
    });
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
    encoder.add_text_chunk("Software".into(), format!("raylab {}", crate::VERSION_LINE))?;
    if let Some(json) = sidecar {
        encoder.add_itxt_chunk(SIDECAR_KEY.into(), json.into())?;
    }
    let mut writer = encoder.write_header()?;
    writer.write_image_data(data)?;
    writer.finish()?;
    Ok(bytes)
}

/// The sidecar JSON an image written by raylab carries (a PNG's iTXt chunk, an EXR's
/// header attribute); `None` when it carries none. Only the header is read.
pub fn embedded_sidecar(path: &Path) -> Result<Option<String>, String> {
    let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if !meta.is_file() {
        return Err("not a regular file (a folder, device or pipe); not read".into());
    }
    match crate::scene::input::extension(path).as_deref() {
        Some("png") => {
            let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
            let reader = png::Decoder::new(std::io::BufReader::new(file))
                .read_info()
                .map_err(|e| format!("not a readable PNG: {e}"))?;
            let chunk = reader
                .info()
                .utf8_text
                .iter()
                .find(|c| c.keyword == SIDECAR_KEY);
            chunk
                .map(|c| c.get_text().map_err(|e| format!("its {SIDECAR_KEY}: {e}")))
                .transpose()
        }
        Some("exr") => {
            let meta = exr::meta::MetaData::read_from_file(path, false)
                .map_err(|e| format!("not a readable EXR: {e}"))?;
            let key = exr::prelude::Text::from(SIDECAR_KEY);
            Ok(meta
                .headers
                .iter()
                .find_map(|h| match h.own_attributes.other.get(&key) {
                    Some(exr::prelude::AttributeValue::Text(t)) => Some(t.to_string()),
                    _ => None,
                }))
        }
        _ => Ok(None),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sidecar_rides_in_the_png_and_the_pixels_are_untouched() {
        let dir = tempfile::tempdir().unwrap();
        let data: Vec<u8> = (0..2 * 3 * 3).map(|i| (i * 13) as u8).collect();
        let json = r#"{"scene": "scènes/verre.toml"}"#;
        let bytes = png_bytes(2, 3, false, &data, Some(json)).unwrap();
        let path = dir.path().join("a.png");
        std::fs::write(&path, &bytes).unwrap();
        assert_eq!(embedded_sidecar(&path).unwrap().as_deref(), Some(json));
        let back = image::load_from_memory(&bytes).unwrap().into_rgb8();
        assert_eq!(back.into_raw(), data);
        let bare = png_bytes(2, 3, false, &data, None).unwrap();
        std::fs::write(&path, bare).unwrap();
        assert_eq!(embedded_sidecar(&path).unwrap(), None);
    }
}
