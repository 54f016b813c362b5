//! A glTF material mapped to raylab's closest, with its base-colour and emissive
//! textures decoded (PNG or JPEG, from the file's buffers, a data URI or a file beside).

use super::{ReadFile, read_uri};
use crate::material::{
    Conductor, Dielectric, Diffuse, Glossy, ImageMap, Material, Mirror, Texels, Texture, Wrap,
};
use crate::math::Color;
use crate::scene::obj::metal_named_in;
use std::borrow::Cow;
use std::collections::HashMap;
use std::sync::Arc;

/// The largest texture side raylab decodes: 16384 texels, 768 MiB as 8-bit RGB at most.
const MAX_TEXTURE_SIDE: u32 = 16384;

/// A glTF file's materials as they are mapped: each picture decoded once, however many
/// materials use it, and what could not be read said once.
pub(super) struct Materials<'a> {
    buffers: &'a [Cow<'a, [u8]>],
    file: &'a str,
    read_file: ReadFile<'a>,
    // By image index: its texels, or `None` if it could not be read (and was warned of).
    pictures: HashMap<usize, Option<Arc<Texels>>>,
    warnings: Vec<String>,
}

impl<'a> Materials<'a> {
    /// None mapped yet, pictures read from `buffers` or through `read_file`.
    pub(super) fn new(
        buffers: &'a [Cow<'a, [u8]>],
        file: &'a str,
        read_file: ReadFile<'a>,
    ) -> Self {
        Materials {
            buffers,
            file,
            read_file,
            pictures: HashMap::new(),
            warnings: Vec::new(),
        }
    }

    /// What could not be read but was not fatal, one line each.
    pub(super) fn into_warnings(self) -> Vec<String> {
        self.warnings
    }

    /// The texture coordinate set (`TEXCOORD_n`) the material's textures are mapped by:
    /// its base-colour texture's, else its emissive texture's, else 0.
    pub(super) fn uv_set(m: &gltf::Material) -> u32 {
        let base = m.pbr_metallic_roughness().base_color_texture();
        base.or_else(|| m.emissive_texture())
            .map_or(0, |t| t.tex_coord())
    }

    /// `colour` as a texture: `info`'s picture scaled by it, or (without a texture, or if
    /// its picture cannot be read) the colour alone.
    fn textured(
        &mut self,
        info: Option<gltf::texture::Info>,
        colour: Color,
        material: &str,
    ) -> Texture {
        let Some(info) = info else {
            return Texture::Solid(colour);
        };
        let texture = info.texture();
        let image = texture.source();
        let texels = match self.pictures.get(&image.index()) {
            Some(texels) => texels.clone(),
            None => {
                let texels = match self.decode(&image) {
                    Ok(texels) => Some(Arc::new(texels)),
                    Err(why) => {
                        let name = image.name().map_or_else(String::new, |n| format!(" `{n}`"));
                        self.warnings.push(format!(
                            "{}: image {}{name}: {why}; material `{material}` and any other that maps it are drawn in their colour factors alone",
                            self.file,
                            image.index()
                        ));
                        None
                    }
                };
                self.pictures.insert(image.index(), texels.clone());
                texels
            }
        };
        let wrap = |mode: gltf::texture::WrappingMode| match mode {
            gltf::texture::WrappingMode::Repeat => Wrap::Repeat,
            gltf::texture::WrappingMode::ClampToEdge => Wrap::Clamp,
            gltf::texture::WrappingMode::MirroredRepeat => Wrap::Mirror,
        };
        let sampler = texture.sampler();
        match texels {
            Some(texels) => Texture::Image(ImageMap {
                texels,
                factor: colour,
                wrap: [wrap(sampler.wrap_s()), wrap(sampler.wrap_t())],
            }),
            None => Texture::Solid(colour),
        }
    }

    /// An image's texels: its encoded bytes (from a buffer view, a data URI or a file
    /// beside) decoded as PNG or JPEG, at most [`MAX_TEXTURE_SIDE`] a side.
    fn decode(&self, image: &gltf::Image) -> Result<Texels, String> {
        let bytes: Cow<[u8]> = match image.source() {
            gltf::image::Source::View { view, .. } => {
                let buffer = self
                    .buffers
                    .get(view.buffer().index())
                    .ok_or("its buffer view names a missing buffer")?;
                let range = view.offset()..view.offset().saturating_add(view.length());
                Cow::Borrowed(
                    buffer
                        .get(range)
                        .ok_or("its buffer view reaches past its buffer's end")?,
                )
            }
            gltf::image::Source::Uri { uri, .. } => Cow::Owned(read_uri(uri, self.read_file)?),
        };
        let mut limits = image::Limits::default();
        limits.max_image_width = Some(MAX_TEXTURE_SIDE);
        limits.max_image_height = Some(MAX_TEXTURE_SIDE);
        let mut reader = image::ImageReader::new(std::io::Cursor::new(&bytes[..]))
            .with_guessed_format()
            .map_err(|e| e.to_string())?;
        reader.limits(limits);
        let picture = reader
            .decode()
            .map_err(|e| format!("not a picture raylab reads (PNG or JPEG): {e}"))?
            .to_rgb8();
        let (width, height) = picture.dimensions();
        Texels::new(width, height, picture.into_raw()).ok_or_else(|| "an empty picture".into())
    }

    /// Maps a metallic-roughness material to raylab's closest: if it emits, its base colour
    /// (diffuse, as below) glowing with its emission (its `emissiveTexture` scaled by the
    /// factor and strength), as glTF adds emission to the base (raylab's glowing surfaces
    /// are diffuse: an emitting metal or glass keeps its base colour, not its metal or
    /// glass); glass (a dielectric of its
    /// KHR_materials_ior index, 1.5 without) if it transmits at least half; a metal if
    /// metallic at least half, the measured conductor its name contains (`Gold`,
    /// `copper`) or else a mirror of its base colour factor, glossy when rough; otherwise
    /// diffuse in its base colour (its `baseColorTexture` scaled by the factor). Roughness r becomes a Phong exponent by the usual match of
    /// lobe widths, n = 2/α² − 2 with α = r²; below r = 0.05 the surface is polished.
    pub(super) fn map(&mut self, m: &gltf::Material, name: &str) -> Material {
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
        let diffuse = |this: &mut Self, emission| {
            Material::Diffuse(Diffuse {
                albedo: this.textured(pbr.base_color_texture(), base, name),
                specular: Color::ZERO,
                exponent: 1.0,
                emission,
            })
        };
        if emitted.max_element() > 0.0 {
            let sets = (pbr.base_color_texture(), m.emissive_texture());
            if let (Some(b), Some(e)) = sets
                && b.tex_coord() != e.tex_coord()
            {
                self.warnings.push(format!(
                    "{}: material `{name}`: its emissive texture is mapped by TEXCOORD_{} as its base colour's is, not by its own TEXCOORD_{}",
                    self.file,
                    b.tex_coord(),
                    e.tex_coord()
                ));
            }
            let emission = self.textured(m.emissive_texture(), emitted, name);
            return diffuse(self, Some(emission));
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
            // glTF's roughness is perceptual: the GGX α is its square (polished below 0.05,
            // as for metals).
            let roughness = if roughness >= 0.05 {
                roughness * roughness
            } else {
                0.0
            };
            return Material::Dielectric(Dielectric {
                roughness,
                ..Dielectric::clear(ior)
            });
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
        diffuse(self, None)
    }
}
