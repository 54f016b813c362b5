//! Text drawn into images (slide captions for handouts, contact sheets' labels) in egui's
//! own typeface, Ubuntu Light, rasterised with ab_glyph: anti-aliased at any size and
//! clipped to its place.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont, point};
use image::{Rgb, RgbImage};

/// The typeface, from the bytes egui ships. `None` only if those bytes were not a font.
fn typeface() -> Option<FontRef<'static>> {
    FontRef::try_from_slice(epaint_default_fonts::UBUNTU_LIGHT).ok()
}

/// The width of `line` in pixels at `px` pixels per em, with kerning.
fn line_width(font: &impl ScaleFont<FontRef<'static>>, line: &str) -> f32 {
    let mut width = 0.0;
    let mut last = None;
    for c in line.chars() {
        let id = font.glyph_id(c);
        if let Some(prev) = last {
            width += font.kern(prev, id);
        }
        width += font.h_advance(id);
        last = Some(id);
    }
    width
}

/// `text` broken at spaces into lines no wider than `max_width` pixels (a word wider
/// than that has a line of its own).
fn wrap(font: &impl ScaleFont<FontRef<'static>>, text: &str, max_width: f32) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        let candidate = if line.is_empty() {
            word.to_string()
        } else {
            format!("{line} {word}")
        };
        if line_width(font, &candidate) <= max_width || line.is_empty() {
            line = candidate;
        } else {
            lines.push(std::mem::replace(&mut line, word.to_string()));
        }
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

/// A rectangle of an image in pixels: left, top, width, height.
#[derive(Clone, Copy)]
struct Clip {
    x: u32,
    y: u32,
    w: u32,
    h: u32,
}

impl Clip {
    fn whole(img: &RgbImage) -> Clip {
        Clip {
            x: 0,
            y: 0,
            w: img.width(),
            h: img.height(),
        }
    }

    fn contains(&self, px: i64, py: i64) -> bool {
        px >= self.x as i64
            && py >= self.y as i64
            && px < (self.x + self.w) as i64
            && py < (self.y + self.h) as i64
    }
}

/// Draws `line` in `colour` on `img` with its baseline at `baseline` and its left edge at
/// `x`, blending by each pixel's coverage; what falls outside `clip` (and the image) is
/// clipped.
fn draw_line(
    img: &mut RgbImage,
    font: &impl ScaleFont<FontRef<'static>>,
    line: &str,
    (x, baseline): (f32, f32),
    clip: Clip,
    colour: [u8; 3],
) {
    let mut caret = x;
    let mut last = None;
    for c in line.chars() {
        let id = font.glyph_id(c);
        if let Some(prev) = last {
            caret += font.kern(prev, id);
        }
        let glyph = id.with_scale_and_position(font.scale(), point(caret, baseline));
        caret += font.h_advance(id);
        last = Some(id);
        let Some(outline) = font.outline_glyph(glyph) else {
            continue; // a space
        };
        let bounds = outline.px_bounds();
        outline.draw(|gx, gy, coverage| {
            let (px, py) = (
                bounds.min.x as i64 + gx as i64,
                bounds.min.y as i64 + gy as i64,
            );
            if !clip.contains(px, py) || !Clip::whole(img).contains(px, py) {
                return;
            }
            let p = img.get_pixel_mut(px as u32, py as u32);
            let a = coverage.clamp(0.0, 1.0);
            let mut c = colour.into_iter();
            *p = Rgb(p.0.map(|v| {
                let to = c.next().unwrap_or(255) as f32;
                (v as f32 + (to - v as f32) * a).round() as u8
            }));
        });
    }
}

/// `image` with `caption` under it in a black strip: white text at 1/30 of the image's
/// height (never under 12 px), wrapped to the image's width.
pub fn with_caption(image: &RgbImage, caption: &str) -> RgbImage {
    let Some(face) = typeface() else {
        return image.clone();
    };
    let px = (image.height() as f32 / 30.0).max(12.0);
    let font = face.into_scaled(PxScale::from(px));
    let margin = px * 0.6;
    let lines = wrap(&font, caption, image.width() as f32 - 2.0 * margin);
    let line_height = font.height() + font.line_gap();
    let strip = (lines.len() as f32 * line_height + 2.0 * margin).ceil() as u32;
    let mut out = RgbImage::new(image.width(), image.height() + strip);
    image::imageops::replace(&mut out, image, 0, 0);
    let whole = Clip::whole(&out);
    for (i, line) in lines.iter().enumerate() {
        let baseline = image.height() as f32 + margin + font.ascent() + i as f32 * line_height;
        draw_line(&mut out, &font, line, (margin, baseline), whole, WHITE);
    }
    out
}

/// Draws `label` in white inside the `w` × `h` box at (`x`, `y`) of `img`, one line,
/// vertically centred: as tall as the box allows (60 % of it), smaller if that would not
/// fit the width, never under 8 px; whatever still does not fit is clipped to the box.
pub(crate) fn draw_label(img: &mut RgbImage, (x, y, w, h): (u32, u32, u32, u32), label: &str) {
    let Some(face) = typeface() else {
        return;
    };
    let pad = (h as f32 * 0.2).max(2.0);
    let tall = h as f32 * 0.6;
    let natural = line_width(&face.clone().into_scaled(PxScale::from(tall)), label);
    let room = (w as f32 - 2.0 * pad).max(1.0);
    let px = if natural > room {
        (tall * room / natural).max(8.0)
    } else {
        tall
    };
    let font = face.into_scaled(PxScale::from(px));
    let baseline = y as f32 + (h as f32 + font.ascent() + font.descent()) / 2.0;
    draw_line(
        img,
        &font,
        label,
        (x as f32 + pad, baseline),
        Clip { x, y, w, h },
        WHITE,
    );
}

const WHITE: [u8; 3] = [255, 255, 255];

/// Draws one line of `text` on `img` in `colour`, `px` pixels per em, centred vertically on
/// `y`; `align` places it across: 0 starts it at `x`, 0.5 centres it there, 1 ends it there.
pub(crate) fn draw_text(
    img: &mut RgbImage,
    text: &str,
    (x, y): (f32, f32),
    px: f32,
    colour: [u8; 3],
    align: f32,
) {
    let Some(face) = typeface() else {
        return;
    };
    let font = face.into_scaled(PxScale::from(px));
    let left = x - align * line_width(&font, text);
    let baseline = y + (font.ascent() + font.descent()) / 2.0;
    let whole = Clip::whole(img);
    draw_line(img, &font, text, (left, baseline), whole, colour);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_caption_is_wrapped_to_the_width_and_drawn_in_the_strip_only() {
        let image = RgbImage::from_pixel(320, 180, Rgb([10, 20, 30]));
        let caption =
            "Left: one sample at each pixel's centre. Right: four jittered samples, averaged.";
        let out = with_caption(&image, caption);
        assert_eq!(out.width(), 320);
        assert!(
            out.height() > 180 + 2 * 12,
            "at least two lines: {}",
            out.height()
        );
        // The image is untouched; the strip has white text on black.
        assert!((0..180).all(|y| (0..320).all(|x| out.get_pixel(x, y).0 == [10, 20, 30])));
        let strip: Vec<u8> = (180..out.height())
            .flat_map(|y| (0..320).map(move |x| (x, y)))
            .map(|(x, y)| out.get_pixel(x, y).0[0])
            .collect();
        let lit = strip.iter().filter(|&&v| v > 128).count();
        assert!(lit > 200, "text drawn: {lit} bright pixels");
        assert!(
            lit < strip.len() / 4,
            "mostly black: {lit} of {}",
            strip.len()
        );
        // Wrapped: no text in the right-hand margin.
        let margin = (320.0 - 0.6 * 12.0) as u32;
        assert!((180..out.height()).all(|y| out.get_pixel(margin + 2, y).0[0] == 0));
    }

    #[test]
    fn a_tiny_image_gets_a_legible_size_and_nothing_is_drawn_outside() {
        // Words wider than the image are clipped at its edge (a write outside it would
        // panic), and the text is 12 px however small the image: one line per word here.
        let image = RgbImage::new(40, 20);
        let out = with_caption(&image, "Snell's law: n1 sin θi = n2 sin θt");
        assert_eq!(out.width(), 40);
        let lines = 8.0;
        assert!(
            out.height() as f32 >= 20.0 + lines * 12.0,
            "{}",
            out.height()
        );
        let lit = (20..out.height())
            .flat_map(|y| (0..40).map(move |x| (x, y)))
            .filter(|&(x, y)| out.get_pixel(x, y).0[0] > 128)
            .count();
        assert!(lit > 50, "text drawn: {lit}");
    }
}
