//! The cost heat map: rays traced per sample in each pixel, black to pale yellow.

/// An "inferno"-like ramp from black through purple, red and orange to pale yellow, for
/// t in [0, 1].
pub(crate) fn heat_color(t: f32) -> [u8; 3] {
    const STOPS: [[f32; 3]; 6] = [
        [0.0, 0.0, 0.02],
        [0.34, 0.06, 0.43],
        [0.73, 0.21, 0.33],
        [0.96, 0.48, 0.10],
        [0.98, 0.80, 0.25],
        [0.99, 1.0, 0.64],
    ];
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    } * (STOPS.len() - 1) as f32;
    let i = (t.floor() as usize).min(STOPS.len() - 2);
    let f = t - i as f32;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    [0, 1, 2].map(|k| ((a[k] + (b[k] - a[k]) * f) * 255.0 + 0.5) as u8)
}

/// The cost heat map as RGBA: rays per sample from `lo` (black) to `hi` (pale yellow).
pub(crate) fn heat_map_rgba(cost: &[f32], lo: f32, hi: f32) -> Vec<u8> {
    let span = (hi - lo).max(1e-6);
    cost.iter()
        .flat_map(|&c| {
            let [r, g, b] = heat_color((c - lo) / span);
            [r, g, b, 255]
        })
        .collect()
}

/// The smallest and largest values of `cost`.
pub(crate) fn cost_range(cost: &[f32]) -> (f32, f32) {
    cost.iter().fold((f32::INFINITY, 0.0f32), |(lo, hi), &c| {
        (lo.min(c), hi.max(c))
    })
}
