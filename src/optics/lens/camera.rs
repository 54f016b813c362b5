//! A camera whose lens is a prescription: film behind the glass, focused by moving the
//! lens, its rays aimed at the exit pupil so that few are wasted on the lens's barrel.
//!
//! Each film point's rays are drawn uniformly over a rectangle on the plane of the rear
//! vertex that bounds where rays from that film distance get through the lens (found once
//! by tracing a grid, per ring of the film, as pbrt's realistic camera does). A ray that
//! is blocked after all brings black. One that passes is weighted by the rectangle's area
//! over the on-axis pupil's, so the film's centre is exactly as bright as the thin lens's
//! and the corners darken where the lens's barrel cuts the pupil (mechanical vignetting;
//! the cos⁴ fall-off is left out, as it is for the thin lens).

use super::trace::Layout;
use super::{Paraxial, Prescription};
use crate::math::Vec3;
use crate::math::lanes::{Lanes, Mask, V3};
use crate::math::sampling::concentric_disk;
use glam::Vec2;
use rayon::prelude::*;
use std::sync::{Arc, Mutex};

/// The smallest stop, as a share of the open stop's diameter: the lens's pinhole (f/40
/// on the f/2 double Gauss), still wide enough for the grids to find.
const MIN_STOP: f64 = 0.05;
/// Rings of the film whose exit pupils are bounded separately.
const RINGS: usize = 32;
/// Grid of rays that finds a ring's pupil, per side: once across the rear element, once
/// across what that found.
const GRID: usize = 64;
/// Film points per ring the grid is traced from (its edges and middle).
const RING_POINTS: usize = 3;

/// How far a lens's stop is closed for an entrance pupil `pupil` mm across: the share of
/// its open diameter, at least [`MIN_STOP`], at most 1 (the pupil is the stop's image, so
/// it scales with the stop).
fn stop_scale(paraxial: &Paraxial, pupil: f32) -> f64 {
    (f64::from(pupil) / paraxial.entrance_pupil).clamp(MIN_STOP, 1.0)
}

/// The f-number of `lens` stopped to an entrance pupil `pupil` mm across (as
/// [`RealLens::new`] stops it): N = f / pupil diameter. `None` for a lens with no
/// paraxial focus.
pub fn stopped_f_number(lens: &Prescription, pupil: f32) -> Option<f64> {
    let paraxial = Paraxial::of(lens)?;
    Some(paraxial.f_number() / stop_scale(&paraxial, pupil))
}

/// The real lens of one render: laid out, focused, stopped down, its pupils found.
#[derive(Clone, Debug)]
pub struct RealLens {
    layout: Layout,
    paraxial: Paraxial,
    /// The front principal plane's z, where the camera's position (the thin lens's
    /// centre) is: rays are given from there.
    z_principal: f32,
    /// The film's z, behind the rear vertex.
    film_z: f32,
    /// Half the film's width and height, mm.
    half_film: Vec2,
    pupils: Arc<Pupils>,
    disperses: bool,
    /// The stop's surface.
    stop: usize,
    /// How far the stop is closed (its share of the open diameter).
    stop_scale: f32,
}

/// The exit pupils of a focused, stopped lens: per film ring, the rectangle on the rear
/// vertex's plane that rays from that ring get through, and the on-axis pupil's area.
#[derive(Debug)]
struct Pupils {
    /// Film radius the rings span, mm.
    film_radius: f32,
    /// Per ring: (min, max) corners; min > max where no ray gets through.
    bounds: Vec<(Vec2, Vec2)>,
    /// The area of the pupil seen from the film's centre, mm².
    on_axis: f32,
}

/// One surface of a laid-out lens, as a lens bench draws it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceProfile {
    /// Its vertex's z in the camera's frame (mm).
    pub z: f32,
    /// Its radius of curvature (mm; positive: its centre towards the film; 0: flat).
    pub radius: f32,
    /// Half its clear aperture (mm), the stop's as stopped down.
    pub clear_radius: f32,
    /// n_d of the medium behind it (1: air).
    pub ior: f32,
    /// Whether it is the stop.
    pub stop: bool,
}

impl SurfaceProfile {
    /// The z of the surface at `h` mm from the axis (its sag from the vertex), clamped to
    /// the sphere's rim.
    pub fn z_at(&self, h: f32) -> f32 {
        if self.radius == 0.0 {
            return self.z;
        }
        let r = self.radius;
        let h = h.abs().min(r.abs());
        // The sphere's centre is at z − r: the surface point at height h is
        // z − r + sign(r)·√(r² − h²).
        self.z - r + r.signum() * (r * r - h * h).sqrt()
    }

    /// Its unit normal at the point `p` on it (camera frame), facing the scene (+z).
    pub fn normal_at(&self, p: Vec3) -> Vec3 {
        if self.radius == 0.0 {
            return Vec3::Z;
        }
        let centre = Vec3::new(0.0, 0.0, self.z - self.radius);
        let n = (p - centre).normalize_or(Vec3::Z);
        if n.z < 0.0 { -n } else { n }
    }
}

/// A ray the lens lets out, in the camera's frame (mm, +z along the view, the front
/// principal plane at z = 0), with its weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LensRay {
    /// Where it leaves the front surface.
    pub origin: Vec3,
    /// Its unit direction.
    pub dir: Vec3,
    /// What its radiance counts for (see the module's doc).
    pub weight: f32,
}

impl RealLens {
    /// `lens` focused on a plane `focus` mm in front of its front principal plane (no
    /// nearer than twice its focal length), its stop closed so that its entrance pupil is
    /// `pupil` mm across (at least a twentieth of its open stop, at most open), behind film
    /// of aspect ratio `aspect` sized to see `fov_deg` vertically at the focus distance, as the
    /// thin lens does. `disperse`: its glass's Abbe numbers apply. `None` for a lens with
    /// no paraxial focus.
    pub fn new(
        lens: &Prescription,
        focus: f32,
        pupil: f32,
        fov_deg: f32,
        aspect: f32,
        disperse: bool,
    ) -> Option<RealLens> {
        let paraxial = Paraxial::of(lens)?;
        let stop_scale = stop_scale(&paraxial, pupil) as f32;
        let layout = Layout::new(lens, stop_scale);
        let object = f64::from(focus).max(2.0 * paraxial.efl);
        let image = paraxial.image_distance(object)?;
        let z_rear_principal = paraxial.rear_principal();
        let film_z = (z_rear_principal - image) as f32;
        let half_h = (image * (0.5 * f64::from(fov_deg)).to_radians().tan()) as f32;
        let half_film = Vec2::new(half_h * aspect, half_h);
        let z_principal = layout.front_z() - paraxial.front_principal() as f32;
        let key = PupilKey {
            surfaces: lens.surfaces.clone(),
            bits: [stop_scale, film_z, half_film.length()].map(f32::to_bits),
        };
        let pupils = cached(key, || Pupils::find(&layout, film_z, half_film.length()))?;
        Some(RealLens {
            layout,
            paraxial,
            z_principal,
            film_z,
            half_film,
            pupils,
            disperses: disperse && lens.disperses(),
            stop: lens.stop(),
            stop_scale,
        })
    }

    /// Whether its rays depend on the wavelength.
    pub fn disperses(&self) -> bool {
        self.disperses
    }

    /// Its surfaces in the camera's frame (mm, +z towards the scene, the front principal
    /// plane at z = 0), front to back, as stopped down: for the lens bench.
    pub fn profile(&self) -> Vec<SurfaceProfile> {
        self.layout.profile(self.z_principal, self.stop)
    }

    /// The film's z in the camera's frame (mm).
    pub fn film_z(&self) -> f32 {
        self.film_z - self.z_principal
    }

    /// Its f-number as stopped down: f over the entrance pupil's diameter.
    pub fn f_number(&self) -> f64 {
        self.paraxial.f_number() / f64::from(self.stop_scale)
    }

    /// Its paraxial description.
    pub fn paraxial(&self) -> &Paraxial {
        &self.paraxial
    }

    /// The ray through image position `film` ((0, 0) top left, (1, 1) bottom right) from
    /// lens sample `lens` (unit square), carrying `wavelength` (nm; `None`: n_d, or a lens
    /// that does not disperse); `None` where the lens blocks it.
    pub fn ray(&self, film: Vec2, lens: Vec2, wavelength: Option<f32>) -> Option<LensRay> {
        self.traced(film, lens, wavelength, |_| {})
    }

    /// [`RealLens::ray`], with `visit` seeing each point the ray reaches on its way out:
    /// the film point, then each surface (in the camera's frame, as the ray's origin).
    pub fn traced(
        &self,
        film: Vec2,
        lens: Vec2,
        wavelength: Option<f32>,
        mut visit: impl FnMut(Vec3),
    ) -> Option<LensRay> {
        let wavelength = wavelength.filter(|_| self.disperses);
        let (from, dir, weight) = self.aim(film, lens)?;
        let shift = Vec3::new(0.0, 0.0, self.z_principal);
        let (origin, dir) = self
            .layout
            .trace(from, dir, wavelength, |v| visit(v - shift))?;
        Some(LensRay {
            origin: origin - shift,
            dir,
            weight,
        })
    }

    /// [`RealLens::ray`] for `N` rays at once, traced through the glass in lanes: each
    /// lane's ray is the one [`RealLens::ray`] gives it, bit for bit.
    #[inline(always)]
    pub(crate) fn rays<const N: usize>(
        &self,
        film: [Vec2; N],
        lens: [Vec2; N],
    ) -> [Option<LensRay>; N] {
        let aimed: [Option<(Vec3, Vec3, f32)>; N] =
            std::array::from_fn(|i| self.aim(film[i], lens[i]));
        // A lane with nothing to trace follows the axis, masked off.
        let or_axis = |i: usize| aimed[i].unwrap_or((Vec3::ZERO, Vec3::Z, 0.0));
        let from = V3::from_fn(|i| or_axis(i).0);
        let dir = V3::from_fn(|i| or_axis(i).1);
        let alive = Mask(std::array::from_fn(|i| {
            if aimed[i].is_some() { u32::MAX } else { 0 }
        }));
        let (origin, dir, through) =
            self.layout
                .trace_of::<Lanes<N>>(from, dir, alive, None, |_| {});
        let shift = Vec3::new(0.0, 0.0, self.z_principal);
        std::array::from_fn(|i| {
            (through.0[i] != 0).then(|| LensRay {
                origin: origin.get(i) - shift,
                dir: dir.get(i),
                weight: or_axis(i).2,
            })
        })
    }

    /// Where the ray through image position `film` from lens sample `lens` starts (on the
    /// film), where it is aimed (unit), and its weight; `None` where its ring of the film
    /// gets no light through.
    #[inline(always)]
    fn aim(&self, film: Vec2, lens: Vec2) -> Option<(Vec3, Vec3, f32)> {
        // The image is upside down on the film: the top left of the picture is at the
        // film's bottom right.
        let x = (2.0 * film.x - 1.0) * self.half_film.x;
        let y = (1.0 - 2.0 * film.y) * self.half_film.y;
        let from = Vec3::new(-x, -y, self.film_z);
        let p = &self.pupils;
        let r = from.x.hypot(from.y);
        let ring = ((r / p.film_radius * RINGS as f32) as usize).min(RINGS - 1);
        let (lo, hi) = p.bounds[ring];
        if lo.x > hi.x {
            return None;
        }
        // Over the ellipse the bounds frame: the pupil is a disk on the axis, two disks'
        // overlap (a cat's eye) off it, and either fills the ellipse of its bounding box
        // more than the box (tests: no light is lost).
        let q = 0.5 * (lo + hi) + 0.5 * (hi - lo) * concentric_disk(lens);
        // The ring's bounds are for a film point on the +x axis: turn them to this one.
        let (cos, sin) = if r > 0.0 {
            (from.x / r, from.y / r)
        } else {
            (1.0, 0.0)
        };
        let aim = Vec3::new(q.x * cos - q.y * sin, q.x * sin + q.y * cos, 0.0);
        let area = std::f32::consts::FRAC_PI_4 * (hi.x - lo.x) * (hi.y - lo.y);
        Some((from, (aim - from).normalize(), area / p.on_axis))
    }
}

impl Pupils {
    /// Finds the pupils of `layout` seen from film at `film_z`, out to `film_radius`.
    /// `None` where no light passes along the axis.
    fn find(layout: &Layout, film_z: f32, film_radius: f32) -> Option<Pupils> {
        let search = 1.5 * layout.rear_radius();
        let through = |from: Vec3, x: f32, y: f32| {
            let dir = (Vec3::new(x, y, 0.0) - from).normalize();
            layout.trace(from, dir, None, |_| {}).is_some()
        };
        // The on-axis pupil is a disk: its radius by bisection along x.
        let centre = Vec3::new(0.0, 0.0, film_z);
        if !through(centre, 0.0, 0.0) {
            return None;
        }
        let (mut inside, mut outside) = (0.0f32, search);
        for _ in 0..32 {
            let mid = 0.5 * (inside + outside);
            if through(centre, mid, 0.0) {
                inside = mid;
            } else {
                outside = mid;
            }
        }
        let whole = (Vec2::splat(-search), Vec2::splat(search));
        let bounds = (0..RINGS)
            .into_par_iter()
            .map(|ring| {
                let froms: [Vec3; RING_POINTS] = std::array::from_fn(|k| {
                    let t = (ring as f32 + k as f32 / (RING_POINTS - 1) as f32) / RINGS as f32;
                    Vec3::new(t * film_radius, 0.0, film_z)
                });
                // Coarse over the whole rear element, then fine over what the coarse
                // grid found: a stopped-down pupil is a few of the coarse cells.
                let coarse = bound(&froms, whole, &through);
                if coarse.0.x > coarse.1.x {
                    coarse
                } else {
                    bound(&froms, coarse, &through)
                }
            })
            .collect();
        Some(Pupils {
            film_radius,
            bounds,
            on_axis: std::f32::consts::PI * inside * inside,
        })
    }
}

/// The cells of a grid over `region` through which a ray from any of `froms` gets
/// (`through`), bounded, with a cell's margin (the grid sees the pupil's edge only to a
/// cell) inside `region`; min > max where none does.
fn bound(
    froms: &[Vec3],
    (lo, hi): (Vec2, Vec2),
    through: &(impl Fn(Vec3, f32, f32) -> bool + Sync),
) -> (Vec2, Vec2) {
    let cell = (hi - lo) / GRID as f32;
    let (mut found_lo, mut found_hi) = (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN));
    for &from in froms {
        for gx in 0..GRID {
            for gy in 0..GRID {
                let at = lo + cell * Vec2::new(gx as f32 + 0.5, gy as f32 + 0.5);
                if through(from, at.x, at.y) {
                    found_lo = found_lo.min(at);
                    found_hi = found_hi.max(at);
                }
            }
        }
    }
    if found_lo.x > found_hi.x {
        return (found_lo, found_hi);
    }
    ((found_lo - cell).max(lo), (found_hi + cell).min(hi))
}

/// What a lens's pupils depend on: the prescription, the stop, the film's distance and
/// size (as f32 bits).
#[derive(Clone, Debug, PartialEq)]
struct PupilKey {
    surfaces: Vec<super::Surface>,
    bits: [u32; 3],
}

/// The last few pupils found: finding them takes tens of milliseconds, and every pass of
/// a render (and every change that leaves the camera alone) asks for the same ones.
static CACHE: Mutex<Vec<(PupilKey, Arc<Pupils>)>> = Mutex::new(Vec::new());
const CACHED: usize = 4;

fn cached(key: PupilKey, find: impl FnOnce() -> Option<Pupils>) -> Option<Arc<Pupils>> {
    let hit = |cache: &Vec<(PupilKey, Arc<Pupils>)>| {
        cache
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, p)| p.clone())
    };
    if let Some(p) = CACHE.lock().ok().and_then(|c| hit(&c)) {
        return Some(p);
    }
    let pupils = Arc::new(find()?);
    if let Ok(mut cache) = CACHE.lock() {
        if cache.len() == CACHED {
            cache.remove(0);
        }
        cache.push((key, pupils.clone()));
    }
    Some(pupils)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optics::lens::LensModel;

    /// `model` focused at 2 m with an entrance pupil `pupil` mm across, seeing 40°
    /// vertically on 4:3 film.
    fn lens(model: LensModel, pupil: f32) -> RealLens {
        let p = model.prescription().unwrap();
        RealLens::new(&p, 2000.0, pupil, 40.0, 4.0 / 3.0, false).unwrap()
    }

    /// The lens samples of an n × n grid, cell centres.
    fn grid(n: usize) -> impl Iterator<Item = Vec2> {
        (0..n * n).map(move |i| Vec2::new((i % n) as f32 + 0.5, (i / n) as f32 + 0.5) / n as f32)
    }

    #[test]
    fn the_films_centre_is_as_bright_as_the_thin_lens() {
        // E[weight] over the lens samples is the pupil's area over the on-axis pupil's:
        // 1 at the centre, whatever the stop.
        for (model, pupil) in [
            (LensModel::DoubleGauss50, 100.0),
            (LensModel::DoubleGauss50, 6.25),
            (LensModel::Singlet50, 8.0),
            (LensModel::Wide22, 100.0),
        ] {
            let l = lens(model, pupil);
            let n = 128;
            let sum: f32 = grid(n)
                .filter_map(|u| l.ray(Vec2::splat(0.5), u, None))
                .map(|r| r.weight)
                .sum();
            let mean = sum / (n * n) as f32;
            assert!((mean - 1.0).abs() < 0.01, "{model:?} at {pupil} mm: {mean}");
        }
    }

    #[test]
    fn a_point_in_focus_at_f8_images_smaller_than_a_pixel() {
        // At f/8 (an entrance pupil of f/8 across) every ray from one film point meets the
        // plane of focus within a pixel of a 640 × 480 image: the lens is focused there
        // and its aberrations are small stopped down.
        let l = lens(LensModel::DoubleGauss50, 50.0 / 8.0);
        let pixel = 2.0 * 2000.0 * 20f32.to_radians().tan() / 480.0;
        for film in [Vec2::splat(0.5), Vec2::new(0.3, 0.6), Vec2::new(0.5, 0.2)] {
            let hits: Vec<Vec3> = grid(16)
                .filter_map(|u| l.ray(film, u, None))
                .map(|r| r.origin + r.dir * ((2000.0 - r.origin.z) / r.dir.z))
                .collect();
            // A disk fills π/4 of the square that bounds it: most draws get through.
            assert!(hits.len() > 128, "{film}: {} rays through", hits.len());
            let mean = hits.iter().copied().sum::<Vec3>() / hits.len() as f32;
            let spread = hits
                .iter()
                .map(|h| (*h - mean).length())
                .fold(0.0, f32::max);
            assert!(spread < 0.5 * pixel, "{film}: {spread} mm against {pixel}");
            // And the spot is where the thin lens (a pinhole through the principal
            // plane) puts that film point, within a pixel (the lens's distortion).
            let x = (2.0 * film.x - 1.0) * 4.0 / 3.0 * 20f32.to_radians().tan() * 2000.0;
            let y = (1.0 - 2.0 * film.y) * 20f32.to_radians().tan() * 2000.0;
            let off = Vec2::new(mean.x - x, mean.y - y).length();
            assert!(off < pixel, "{film}: {off} mm from the thin lens's point");
        }
    }

    #[test]
    fn the_corners_of_a_wide_field_darken() {
        // The telephoto cannot cover 40°: its barrel cuts the pupil towards the corners.
        let l = lens(LensModel::Telephoto250, 100.0);
        let brightness = |film: Vec2| {
            let n = 64;
            let sum: f32 = grid(n)
                .filter_map(|u| l.ray(film, u, None))
                .map(|r| r.weight)
                .sum();
            sum / (n * n) as f32
        };
        let (centre, corner) = (brightness(Vec2::splat(0.5)), brightness(Vec2::splat(0.02)));
        assert!((centre - 1.0).abs() < 0.01, "{centre}");
        assert!(corner < 0.5 * centre, "{corner}");
    }

    #[test]
    fn the_pupil_bounds_hold_all_the_light_that_gets_through() {
        // E[weight] at a film point is the area of its pupil inside its ring's bounds over
        // the on-axis pupil's; brute force over the whole rear element gives the pupil's
        // whole area. They agree where the bounds miss nothing.
        for (model, pupil) in [
            (LensModel::DoubleGauss50, 100.0),
            (LensModel::Wide22, 100.0),
            (LensModel::Telephoto250, 100.0),
            (LensModel::Singlet50, 8.0),
        ] {
            let l = lens(model, pupil);
            for film in [
                Vec2::new(0.3, 0.5),
                Vec2::new(0.5, 0.05),
                Vec2::new(0.1, 0.1),
            ] {
                let n = 128;
                let weighed: f32 = grid(n)
                    .filter_map(|u| l.ray(film, u, None))
                    .map(|r| r.weight)
                    .sum::<f32>()
                    / (n * n) as f32;
                let x = (2.0 * film.x - 1.0) * l.half_film.x;
                let y = (1.0 - 2.0 * film.y) * l.half_film.y;
                let from = Vec3::new(-x, -y, l.film_z);
                let side = 1.5 * l.layout.rear_radius();
                let m = 400;
                let through = grid(m)
                    .filter(|u| {
                        let q = (2.0 * *u - Vec2::ONE) * side;
                        let aim = Vec3::new(q.x, q.y, 0.0);
                        let dir = (aim - from).normalize();
                        l.layout.trace(from, dir, None, |_| {}).is_some()
                    })
                    .count();
                let area = through as f32 / (m * m) as f32 * (2.0 * side).powi(2);
                let brute = area / l.pupils.on_axis;
                assert!(
                    (weighed - brute).abs() < 0.005 + 0.015 * brute,
                    "{model:?} at {film}: {weighed} weighed, {brute} by brute force"
                );
            }
        }
    }
}
