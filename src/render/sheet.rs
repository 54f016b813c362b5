//! Sweeps: one image per value of a parameter, labelled, laid out side by side in a contact
//! sheet like the lecture's comparison figures, or played one after another as an
//! animation for a slide deck.

use super::text::draw_label;
use super::{Cancelled, Film, PassObserver, render_pass};
use crate::camera::Camera;
use crate::params::{ParamError, Params};
use crate::scene::Scene;
use image::{Rgb, RgbImage};

/// A sheet that cannot be made.
#[derive(Debug, thiserror::Error)]
pub enum SheetError {
    /// A value does not suit the parameter.
    #[error(transparent)]
    Param(#[from] ParamError),
    /// No values.
    #[error("a sweep needs at least one value")]
    Empty,
    /// Stopped.
    #[error(transparent)]
    Cancelled(#[from] Cancelled),
    /// A frame could not be added to what is being made of them (an animation's encoder).
    #[error("{0}")]
    Frame(String),
}

/// A parameter and the values a sweep gives it, as `--set` takes them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Sweep {
    /// The parameter.
    pub name: String,
    /// Its values, one image each.
    pub values: Vec<String>,
}

impl Sweep {
    /// Parameter `name` at the comma-separated `values` (`1,4,16`; blanks dropped).
    pub fn of(name: &str, values: &str) -> Sweep {
        Sweep {
            name: name.trim().to_string(),
            values: values
                .split(',')
                .map(|v| v.trim().to_string())
                .filter(|v| !v.is_empty())
                .collect(),
        }
    }
}

/// Parses `name=v1,v2,...` into the parameter and its values.
pub fn parse_sweep(spec: &str) -> Result<Sweep, ParamError> {
    let (name, values) = spec
        .split_once('=')
        .ok_or_else(|| ParamError::Syntax(spec.to_string()))?;
    Ok(Sweep::of(name, values))
}

/// Columns of a sheet of `n` images: at most four across.
fn columns(n: usize) -> usize {
    n.clamp(1, 4)
}

const GAP: u32 = 8;
/// The sheet's background and the label strips'.
const BACKDROP: Rgb<u8> = Rgb([24, 24, 24]);

/// The height of the label strip under a tile `height` pixels tall: a tenth of it, between
/// 16 and 40 pixels.
fn label_height(height: u32) -> u32 {
    (height / 10).clamp(16, 40)
}

/// The size of a sweep's frame for images of `size`: the image and its label strip.
pub fn frame_size((width, height): (u32, u32)) -> (u32, u32) {
    (width, height + label_height(height))
}

/// Renders one image of `scene` through `camera`, `size` (width, height) pixels, for each
/// value of the sweep's parameter (set as `--set name=value` would, on top of `base`), each
/// with a strip under it labelled `name = value`: the frames of a sweep, handed to `each`
/// as each is made, so that a sweep of thousands of values holds one frame at a time.
pub fn sweep_each(
    scene: &Scene,
    camera: &Camera,
    base: &Params,
    size: (u32, u32),
    sweep: &Sweep,
    observer: &dyn PassObserver,
    each: &mut dyn FnMut(RgbImage) -> Result<(), SheetError>,
) -> Result<(), SheetError> {
    let ((width, height), name, values) = (size, sweep.name.as_str(), &sweep.values);
    if values.is_empty() {
        return Err(SheetError::Empty);
    }
    // Check every value before rendering any.
    let params: Vec<Params> = values
        .iter()
        .map(|v| {
            let mut p = base.clone();
            p.set(name, v).map(|_| p)
        })
        .collect::<Result<_, _>>()?;
    let (_, framed) = frame_size(size);
    for (p, value) in params.iter().zip(values) {
        let mut film = Film::new(width, height);
        render_pass(scene, camera, p, &mut film, p.spp, observer)?;
        let mut frame = RgbImage::from_pixel(width, framed, BACKDROP);
        image::imageops::replace(&mut frame, &film.to_srgb8(p.exposure), 0, 0);
        draw_label(
            &mut frame,
            (0, height, width, framed - height),
            &format!("{name} = {value}"),
        );
        each(frame)?;
    }
    Ok(())
}

/// A contact sheet filled frame by frame: rows of up to four, `GAP` apart.
pub struct ContactSheet {
    sheet: RgbImage,
    columns: u32,
    tile: (u32, u32),
    next: u32,
}

impl ContactSheet {
    /// The sheet's size for `n` frames of `tile` pixels.
    pub fn size(n: usize, (w, h): (u32, u32)) -> (u32, u32) {
        let cols = columns(n) as u32;
        let rows = n.max(1).div_ceil(cols as usize) as u32;
        (cols * w + (cols + 1) * GAP, rows * h + (rows + 1) * GAP)
    }

    /// An empty sheet for `n` frames of `tile` pixels.
    pub fn new(n: usize, tile: (u32, u32)) -> ContactSheet {
        let (w, h) = ContactSheet::size(n, tile);
        ContactSheet {
            sheet: RgbImage::from_pixel(w, h, BACKDROP),
            columns: columns(n) as u32,
            tile,
            next: 0,
        }
    }

    /// Places the next frame.
    pub fn add(&mut self, frame: &RgbImage) {
        let (w, h) = self.tile;
        let (col, row) = (self.next % self.columns, self.next / self.columns);
        let (x0, y0) = (GAP + col * (w + GAP), GAP + row * (h + GAP));
        image::imageops::replace(&mut self.sheet, frame, x0 as i64, y0 as i64);
        self.next += 1;
    }

    /// The sheet.
    pub fn finish(self) -> RgbImage {
        self.sheet
    }
}

/// An animated GIF that loops, encoded frame by frame into `bytes`, each frame shown for
/// `delay_ms` milliseconds (GIF keeps 256 colours a frame, chosen per frame).
pub struct Animation<'a> {
    encoder: image::codecs::gif::GifEncoder<&'a mut Vec<u8>>,
    delay: image::Delay,
}

impl<'a> Animation<'a> {
    /// An animation written into `bytes`.
    pub fn new(bytes: &'a mut Vec<u8>, delay_ms: u32) -> image::ImageResult<Animation<'a>> {
        use image::codecs::gif::{GifEncoder, Repeat};
        let mut encoder = GifEncoder::new_with_speed(bytes, 10);
        encoder.set_repeat(Repeat::Infinite)?;
        Ok(Animation {
            encoder,
            delay: image::Delay::from_numer_denom_ms(delay_ms, 1),
        })
    }

    /// Adds the next frame.
    pub fn add(&mut self, frame: &RgbImage) -> image::ImageResult<()> {
        let rgba = image::DynamicImage::ImageRgb8(frame.clone()).into_rgba8();
        self.encoder
            .encode_frame(image::Frame::from_parts(rgba, 0, 0, self.delay))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every frame of a sweep of `scene` seen by its camera (see [`sweep_each`]), in the
    /// order of its values.
    fn sweep_frames(
        scene: &Scene,
        base: &Params,
        size: (u32, u32),
        sweep: &Sweep,
    ) -> Result<Vec<RgbImage>, SheetError> {
        let mut frames = Vec::with_capacity(sweep.values.len());
        sweep_each(scene, &scene.camera, base, size, sweep, &(), &mut |f| {
            frames.push(f);
            Ok(())
        })?;
        Ok(frames)
    }

    /// Lays out `frames` (all of one size) in rows of up to four, `GAP` apart: a contact
    /// sheet. Empty for no frames.
    fn contact_sheet(frames: &[RgbImage]) -> RgbImage {
        let Some(first) = frames.first() else {
            return RgbImage::new(0, 0);
        };
        let mut sheet = ContactSheet::new(frames.len(), first.dimensions());
        for frame in frames {
            sheet.add(frame);
        }
        sheet.finish()
    }

    /// `frames` as an animated GIF that loops, each shown for `delay_ms` milliseconds.
    fn animation(frames: &[RgbImage], delay_ms: u32) -> image::ImageResult<Vec<u8>> {
        let mut bytes = Vec::new();
        {
            let mut animation = Animation::new(&mut bytes, delay_ms)?;
            for frame in frames {
                animation.add(frame)?;
            }
        }
        Ok(bytes)
    }

    #[test]
    fn sweep_specs_parse() {
        assert_eq!(
            parse_sweep("spp=1, 4,16").unwrap(),
            Sweep {
                name: "spp".into(),
                values: vec!["1".into(), "4".into(), "16".into()]
            }
        );
        assert!(parse_sweep("spp").is_err());
    }

    #[test]
    fn a_sheet_lays_out_labelled_tiles_in_rows_of_four() {
        let scene = Scene::load("default").unwrap();
        let base = Params {
            spp: 1,
            ..scene.params.clone()
        };
        let five = parse_sweep("max_depth=1,2,3,4,5").unwrap();
        let frames = sweep_frames(&scene, &base, (40, 30), &five).unwrap();
        let sheet = contact_sheet(&frames);
        assert_eq!(sheet.width(), 4 * 40 + 5 * GAP);
        let label = label_height(30);
        assert_eq!(sheet.height(), 2 * (30 + label) + 3 * GAP);
        // The fifth tile is the image with max_depth 5, in the second row's first place.
        let mut film = Film::new(40, 30);
        let p = Params {
            max_depth: 5,
            ..base.clone()
        };
        render_pass(&scene, &scene.camera, &p, &mut film, 1, &()).unwrap();
        let tile = film.to_srgb8(0.0);
        let y0 = GAP + 30 + label + GAP;
        assert_eq!(sheet.get_pixel(GAP + 7, y0 + 11), tile.get_pixel(7, 11));
        // Its label has text: bright pixels in the strip under it.
        let bright = (0..40)
            .flat_map(|x| (0..label).map(move |y| (x, y)))
            .filter(|&(x, y)| sheet.get_pixel(GAP + x, y0 + 30 + y).0[0] > 128)
            .count();
        assert!(bright > 10, "{bright} bright pixels in the label");
        // "max_depth = 5" is wider than a 40-pixel tile at any legible size: it is cut at
        // the tile's edge, and the gap beside it stays the sheet's grey.
        for y in y0 + 30..y0 + 30 + label {
            for x in GAP + 40..2 * GAP + 40 {
                assert_eq!(sheet.get_pixel(x, y).0, [24, 24, 24], "({x}, {y})");
            }
        }
        // A bad value is an error before any rendering.
        let sweep = |spec: &str| {
            let sweep = parse_sweep(spec).unwrap();
            sweep_frames(&scene, &base, (8, 8), &sweep)
        };
        assert!(sweep("spp=0").is_err());
        assert!(sweep("spp=").is_err());

        // As an animation: a GIF of the five frames that loops, each as rendered (GIF's
        // palette of 256 colours per frame keeps a flat label strip exact).
        let gif = animation(&frames, 800).unwrap();
        let decoder = image::codecs::gif::GifDecoder::new(std::io::Cursor::new(&gif)).unwrap();
        use image::AnimationDecoder;
        let decoded = decoder.into_frames().collect_frames().unwrap();
        assert_eq!(decoded.len(), 5);
        for (frame, original) in decoded.iter().zip(&frames) {
            assert_eq!(frame.buffer().dimensions(), original.dimensions());
            assert_eq!(frame.delay().numer_denom_ms(), (800, 1));
            assert_eq!(
                frame.buffer().get_pixel(1, 30 + label - 1).0,
                [24, 24, 24, 255]
            );
        }
    }
}
