//! Pure sampling functions: they take uniform numbers, not a random generator, so tests
//! can check them exactly.

use glam::Vec2;

/// Maps the unit square to the unit disk, keeping areas in proportion and strata compact
/// (Shirley and Chiu's concentric map): the lens sample of a thin-lens camera.
pub fn concentric_disk(u: Vec2) -> Vec2 {
    let o = 2.0 * u - Vec2::ONE;
    if o.x == 0.0 && o.y == 0.0 {
        return Vec2::ZERO;
    }
    let (r, theta) = if o.x.abs() > o.y.abs() {
        (o.x, std::f32::consts::FRAC_PI_4 * (o.y / o.x))
    } else {
        (
            o.y,
            std::f32::consts::FRAC_PI_2 - std::f32::consts::FRAC_PI_4 * (o.x / o.y),
        )
    };
    r * Vec2::new(theta.cos(), theta.sin())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn concentric_disk_stays_in_the_unit_disk_and_reaches_its_rim() {
        let mut max_r: f32 = 0.0;
        for i in 0..=64 {
            for j in 0..=64 {
                let p = concentric_disk(Vec2::new(i as f32 / 64.0, j as f32 / 64.0));
                assert!(p.length() <= 1.0 + 1e-6);
                max_r = max_r.max(p.length());
            }
        }
        assert!((max_r - 1.0).abs() < 1e-6);
        assert_eq!(concentric_disk(Vec2::splat(0.5)), Vec2::ZERO);
    }
}
