//! The lecture's formulas of ideal specular reflection.

use crate::math::Vec3;

/// Ideal mirror reflection of the incoming direction `d` about the unit normal `n`:
/// r = d − 2 (d·n) n. Works for `n` on either side of the surface.
#[inline]
pub fn reflect(d: Vec3, n: Vec3) -> Vec3 {
    d - 2.0 * d.dot(n) * n
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reflection_keeps_the_tangent_and_flips_the_normal_part() {
        let d = Vec3::new(1.0, -1.0, 0.0).normalize();
        let r = reflect(d, Vec3::Y);
        assert!((r - Vec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-6);
        // Angle of incidence equals angle of reflection, whichever side n faces.
        assert!((reflect(d, -Vec3::Y) - r).length() < 1e-6);
        assert!((r.length() - 1.0).abs() < 1e-6);
    }
}
