//! The false-colour ramp of raylab's maps (the window's cost heat map, `raylab compare`'s
//! difference): black through purple, red and orange to pale yellow, after matplotlib's
//! inferno, so that brightness rises with the value and the dark end stays dark.

/// The ramp's colour for t in [0, 1] (clamped; a value that is not finite is black).
pub fn inferno(t: f32) -> [u8; 3] {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ramp_runs_dark_to_light() {
        let y = |t: f32| {
            let [r, g, b] = inferno(t);
            0.2126 * r as f32 + 0.7152 * g as f32 + 0.0722 * b as f32
        };
        let steps: Vec<f32> = (0..=50).map(|i| y(i as f32 / 50.0)).collect();
        assert!(steps.windows(2).all(|w| w[1] >= w[0]), "{steps:?}");
        assert_eq!(inferno(-1.0), inferno(0.0));
        assert_eq!(inferno(7.0), inferno(1.0));
        assert_eq!(inferno(f32::NAN), inferno(0.0));
    }
}
