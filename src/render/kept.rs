//! A film a change of parameters re-rendered in part, previewed at full resolution: the
//! pixels it kept as they are, those it started again from a preview of them.

use crate::math::Color;

/// Fills the pixels `behind` (indices into `pixels`, a `width`-wide image) from a preview
/// of them, `cells` one value per `block` × `block` block of which only those `wanted`
/// marks hold values: stretched bilinearly as the window stretches a preview, weighing
/// the wanted blocks alone.
pub(crate) fn fill_behind(
    pixels: &mut [Color],
    behind: &[u32],
    width: u32,
    (cells, wanted): (&[Color], &[bool]),
    block: u32,
) {
    let block = block.max(1);
    let height = pixels.len() as u32 / width.max(1);
    let (gw, gh) = (width.div_ceil(block), height.div_ceil(block));
    let fits = |n: usize| n == (gw * gh) as usize;
    if !fits(cells.len()) || !fits(wanted.len()) {
        return;
    }
    // A pixel's place among the blocks' centres: the two blocks either side and how far
    // towards the second.
    let place = |p: u32, n: u32| {
        let u = ((p as f32 + 0.5) / block as f32 - 0.5).clamp(0.0, (n - 1) as f32);
        let i = u as u32;
        (i, (i + 1).min(n - 1), u - i as f32)
    };
    for &p in behind {
        let (x, y) = (p % width, p / width);
        let ((x0, x1, fx), (y0, y1, fy)) = (place(x, gw), place(y, gh));
        let (mut sum, mut weight) = (Color::ZERO, 0.0);
        for (cx, cy, k) in [
            (x0, y0, (1.0 - fx) * (1.0 - fy)),
            (x1, y0, fx * (1.0 - fy)),
            (x0, y1, (1.0 - fx) * fy),
            (x1, y1, fx * fy),
        ] {
            let c = (cy * gw + cx) as usize;
            if wanted[c] {
                sum += cells[c] * k;
                weight += k;
            }
        }
        pixels[p as usize] = match weight > 0.0 {
            true => sum / weight,
            // (Its own block is wanted, but may lie at a corner of weight 0.)
            false => cells[((y / block) * gw + x / block) as usize],
        };
    }
}
