//! Real rays through a prescription, from the film out to the scene: at each surface the
//! ray meets its sphere (or plane), is blocked outside the clear aperture, and refracts by
//! Snell's law ([`crate::optics::refract`], the scene's own), or is lost to total internal
//! reflection.
//!
//! Lens space: millimetres, the axis along +z towards the scene, the last surface's vertex
//! at z = 0 and the others in front of it, the film behind it at negative z.

use super::Prescription;
use crate::math::Vec3;
use crate::math::lanes::{Real, Vector, is_finite};
use crate::optics::refract_of;

/// A prescription laid out on the axis, with its stop's radius as set.
#[derive(Clone, Debug)]
pub(super) struct Layout {
    /// Per surface: its vertex's z, its radius, its clear radius, and n_d and the Abbe
    /// number of the medium behind it, front to back.
    surfaces: Vec<Placed>,
}

#[derive(Clone, Copy, Debug)]
struct Placed {
    z: f32,
    radius: f32,
    clear_radius: f32,
    ior: f32,
    abbe: f32,
}

impl Placed {
    fn ior_at(&self, wavelength: Option<f32>) -> f32 {
        match wavelength {
            Some(lambda) => crate::optics::dispersion::ior_at(self.ior, self.abbe, lambda),
            None => self.ior,
        }
    }
}

impl Layout {
    /// `lens` on the axis with its stop's diameter scaled by `stop_scale`.
    pub(super) fn new(lens: &Prescription, stop_scale: f32) -> Layout {
        let n = lens.surfaces.len();
        let surfaces = (0..n)
            .map(|i| {
                let s = &lens.surfaces[i];
                let scale = if s.stop { stop_scale } else { 1.0 };
                Placed {
                    // z_i = the thicknesses from surface i to the last (whose own
                    // thickness is no gap: focusing sets the film's distance).
                    z: lens.surfaces[i..n - 1].iter().map(|s| s.thickness).sum(),
                    radius: s.radius,
                    clear_radius: 0.5 * s.aperture * scale,
                    ior: s.ior,
                    abbe: s.abbe,
                }
            })
            .collect();
        Layout { surfaces }
    }

    /// Each surface as drawn on a lens bench, front to back, its vertex at `z` less
    /// `shift`.
    pub(super) fn profile(&self, shift: f32, stop: usize) -> Vec<super::SurfaceProfile> {
        self.surfaces
            .iter()
            .enumerate()
            .map(|(i, s)| super::SurfaceProfile {
                z: s.z - shift,
                radius: s.radius,
                clear_radius: s.clear_radius,
                ior: s.ior,
                stop: i == stop,
            })
            .collect()
    }

    /// The clear radius of the last surface (the rear element), mm.
    pub(super) fn rear_radius(&self) -> f32 {
        self.surfaces.last().map_or(0.0, |s| s.clear_radius)
    }

    /// The z of the first surface's vertex (the front of the lens), mm.
    pub(super) fn front_z(&self) -> f32 {
        self.surfaces.first().map_or(0.0, |s| s.z)
    }

    /// Traces the ray from `origin` (behind the lens) along `dir` out through every
    /// surface, back to front, carrying `wavelength` (nm; `None`: n_d). `visit` sees each
    /// point the ray reaches, the origin first. `Some` ray leaving the front surface, or
    /// `None` where the ray is blocked by an aperture, misses a surface, or is totally
    /// internally reflected.
    pub(super) fn trace(
        &self,
        origin: Vec3,
        dir: Vec3,
        wavelength: Option<f32>,
        visit: impl FnMut(Vec3),
    ) -> Option<(Vec3, Vec3)> {
        let (p, d, through) = self.trace_of::<f32>(origin, dir, true, wavelength, visit);
        through.then_some((p, d))
    }

    /// [`Layout::trace`] for one ray or one per lane, those where `alive` holds: where
    /// each leaves the front surface and its direction, and whether it got through. A
    /// ray's lane does what [`Layout::trace`] does for it alone, bit for bit (the lanes
    /// stop together, once none is left).
    #[inline(always)]
    pub(super) fn trace_of<R: Real>(
        &self,
        origin: R::V3,
        dir: R::V3,
        alive: R::Mask,
        wavelength: Option<f32>,
        mut visit: impl FnMut(R::V3),
    ) -> (R::V3, R::V3, R::Mask) {
        let (mut p, mut d, mut alive) = (origin, dir, alive);
        visit(p);
        for (i, s) in self.surfaces.iter().enumerate().rev() {
            if !R::any(alive) {
                break;
            }
            let (t, normal, hit) = intersect_of::<R>(s, p, d);
            alive = alive & hit;
            p = R::V3::select(alive, p + d.scale(t), p);
            visit(p);
            let [x, y, _] = p.coords();
            let clear = R::splat(s.clear_radius * s.clear_radius);
            alive = alive & (x * x + y * y).less_eq(clear);
            // From the medium behind this surface into the one in front of it (air
            // before the first).
            let n1 = s.ior_at(wavelength);
            let n2 = if i == 0 {
                1.0
            } else {
                self.surfaces[i - 1].ior_at(wavelength)
            };
            if n1 != n2 {
                let (bent, ok) = refract_of::<R>(d, normal, R::splat(n1), R::splat(n2));
                alive = alive & ok;
                d = R::V3::select(alive, bent, d);
            }
        }
        (p, d, alive)
    }
}

/// Where the ray from `p` along unit `d` meets surface `s`: the distance, the unit normal
/// there (the axis, for a flat surface), and whether it does. On a sphere, the cap around
/// the vertex is taken, not the far side of the sphere.
#[inline(always)]
fn intersect_of<R: Real>(s: &Placed, p: R::V3, d: R::V3) -> (R, R::V3, R::Mask) {
    let [_, _, pz] = p.coords();
    let [_, _, dz] = d.coords();
    let zero = R::splat(0.0);
    if s.radius == 0.0 {
        let t = (R::splat(s.z) - pz) / dz;
        let hit = zero.less(t) & is_finite(t);
        return (t, R::V3::splat(Vec3::Z), hit);
    }
    // The centre is `radius` behind the vertex (towards the film) for a positive radius.
    let centre = Vec3::new(0.0, 0.0, s.z - s.radius);
    let oc = p - R::V3::splat(centre);
    // |oc + t d|² = r²: t² + 2 b t + c = 0 with b = oc·d, c = |oc|² − r².
    let b = oc.dot(d);
    let c = oc.length_squared() - R::splat(s.radius * s.radius);
    let disc = b * b - c;
    let meets = zero.less_eq(disc);
    let root = R::select(meets, disc, zero).sqrt();
    // The vertex's cap is where (z − centre z) has the sign of the radius.
    let on_cap =
        |t: R| zero.less(t) & zero.less((pz + t * dz - R::splat(centre.z)) * R::splat(s.radius));
    let (near, far) = (-b - root, -b + root);
    let near_on_cap = on_cap(near);
    let t = R::select(near_on_cap, near, far);
    let hit = meets & (near_on_cap | on_cap(far));
    let normal = (p + d.scale(t) - R::V3::splat(centre)).div(R::splat(s.radius.abs()));
    (t, normal, hit)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optics::lens::{LensModel, Paraxial};

    #[test]
    fn a_ray_near_the_axis_from_the_back_focus_leaves_parallel() {
        // Light from infinity focuses at the back focus; reversed, a ray from there leaves
        // parallel to the axis, as the paraxial matrices say, within their own
        // approximation (a ray 0.5 mm from the axis).
        for model in LensModel::DESIGNS {
            let lens = model.prescription().unwrap();
            let p = Paraxial::of(&lens).unwrap();
            let layout = Layout::new(&lens, 1.0);
            let focus = Vec3::new(0.0, 0.0, -p.bfl as f32);
            // Aim at the height that comes out 0.5 mm off the axis: the slope is small.
            let dir = (Vec3::new(0.0, 0.02, 0.0) - focus).normalize();
            let (out, d) = layout.trace(focus, dir, None, |_| {}).unwrap();
            assert!(out.y.abs() > 1e-3, "{model:?}");
            assert!(
                d.y.abs() / d.z < 1e-4 * 50.0 / p.efl as f32,
                "{model:?}: {d}"
            );
        }
    }

    #[test]
    fn rays_outside_an_aperture_are_blocked_and_the_stop_shrinks() {
        let lens = LensModel::Singlet50.prescription().unwrap();
        let open = Layout::new(&lens, 1.0);
        let half = Layout::new(&lens, 0.5);
        let from = Vec3::new(0.0, 0.0, -50.0);
        // The stop is 12 mm across, 15 mm in front of the back: aim inside 6 mm, and
        // between 3 and 6 mm.
        let through = |l: &Layout, y: f32| {
            let dir = (Vec3::new(0.0, y, 0.0) - from).normalize();
            l.trace(from, dir, None, |_| {}).is_some()
        };
        assert!(through(&open, 1.0) && through(&half, 1.0));
        assert!(through(&open, 4.5) && !through(&half, 4.5));
        assert!(!through(&open, 11.0));
        assert_eq!(open.front_z(), 15.0);
        assert_eq!(open.rear_radius(), 12.0);
    }
}
