//! The camera: a pinhole, or a thin lens with a plane of focus, open over a shutter interval.

use crate::math::lanes::{RayOf, Real, Vector};
use crate::math::rng::SobolLanes;
use crate::math::{Ray, Uniform, Vec3, sampling::concentric_disk_of};
use crate::optics::lens::{LensDispersion, LensModel, LensRay, RealLens, stopped_f_number};
use crate::params::Params;
use glam::Vec2;

/// Millimetres per scene unit: a scene unit is a metre, a lens prescription is in mm.
const MM: f32 = 1000.0;

/// Where the camera is and what it sees.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Camera {
    /// Eye position (the lens centre).
    pub position: Vec3,
    /// The point looked at.
    pub look_at: Vec3,
    /// Which way is up (need not be perpendicular to the view direction).
    pub up: Vec3,
    /// Vertical field of view, degrees.
    pub fov_deg: f32,
}

/// The lens and shutter settings of one render (from [`Params`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exposure {
    /// The thin lens, or a real design.
    pub lens: LensModel,
    /// Whether a real lens's glass disperses.
    pub lens_dispersion: LensDispersion,
    /// Lens radius (a real lens's entrance pupil radius); 0 is a pinhole (everything
    /// sharp).
    pub aperture: f32,
    /// Distance from the lens to the plane in focus, along the view direction.
    pub focus_distance: f32,
    /// The shutter opens at this time and closes at the second; equal times freeze motion.
    pub shutter: (f32, f32),
}

/// The uniform numbers of one camera sample, drawn first from every sample's stream and
/// always in this order: the position in the pixel, the point on the lens, the time in the
/// shutter. The tracer and the sample-pattern view both draw them here.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraSample {
    /// Position in the pixel, unit square.
    pub pixel: Vec2,
    /// Lens sample, unit square (mapped onto the lens disk by the frame).
    pub lens: Vec2,
    /// Time sample, unit interval (mapped onto the shutter by the frame).
    pub time: f32,
}

impl CameraSample {
    /// Draws the camera's dimensions from `u`. Without a `lens` (a pinhole) or a `shutter`
    /// interval their numbers cannot change the ray: their dimensions are skipped, not
    /// computed, and read as 0.
    pub fn draw(u: &mut impl Uniform, lens: bool, shutter: bool) -> CameraSample {
        let pixel = u.next_2d();
        let lens = if lens {
            u.next_2d()
        } else {
            u.skip(1);
            Vec2::ZERO
        };
        let time = if shutter {
            u.next_1d()
        } else {
            u.skip(1);
            0.0
        };
        CameraSample { pixel, lens, time }
    }

    /// [`CameraSample::draw`] for `N` Sobol streams at once, in the same order: lane i's
    /// sample is what `draw` gives from lane i's stream.
    #[inline(always)]
    pub(crate) fn draw_lanes<const N: usize>(
        u: &mut SobolLanes<N>,
        lens: bool,
        shutter: bool,
    ) -> [CameraSample; N] {
        let pixel = u.next_2d();
        let lens = if lens {
            u.next_2d()
        } else {
            u.skip(1);
            [Vec2::ZERO; N]
        };
        let time = if shutter {
            u.next_1d()
        } else {
            u.skip(1);
            [0.0; N]
        };
        std::array::from_fn(|i| CameraSample {
            pixel: pixel[i],
            lens: lens[i],
            time: time[i],
        })
    }
}

/// The camera's frame, computed once per render.
#[derive(Clone, Debug)]
pub struct CameraFrame {
    origin: Vec3,
    forward: Vec3,
    // Image-plane axes at distance 1, scaled by the half-extent of the view.
    right: Vec3,
    up: Vec3,
    lens_u: Vec3,
    lens_v: Vec3,
    aperture: f32,
    focus_distance: f32,
    shutter: (f32, f32),
    /// A real lens, traced through its glass; `None`: the thin lens (or pinhole).
    real: Option<RealLens>,
}

impl Camera {
    /// A camera at `position` looking at `look_at`.
    pub fn looking_at(position: Vec3, look_at: Vec3, up: Vec3, fov_deg: f32) -> Self {
        Camera {
            position,
            look_at,
            up,
            fov_deg,
        }
    }

    /// This camera moved and turned by `t`, a transform that scales uniformly (a placed
    /// model's): the view's angles, so its field of view, are unchanged.
    pub(crate) fn transformed(&self, t: &glam::Affine3A) -> Camera {
        Camera {
            position: t.transform_point3(self.position.into()).into(),
            look_at: t.transform_point3(self.look_at.into()).into(),
            up: t.transform_vector3(self.up.into()).into(),
            fov_deg: self.fov_deg,
        }
    }

    /// Checks what makes a view: `position` and `look_at` apart and within the scene's
    /// limits, `up` not parallel to the view direction, a field of view between 0 and 180
    /// degrees. Scene files and sidecars alike pass through here.
    pub fn check(&self) -> Result<(), String> {
        use crate::geometry::{MAX_COORDINATE, within_limits};
        if !within_limits(self.position) || !within_limits(self.look_at) {
            return Err(format!(
                "`position` and `look_at` must be finite and within ±{MAX_COORDINATE:e}"
            ));
        }
        let view = self.look_at - self.position;
        if view.length_squared() == 0.0 {
            return Err("`look_at` must differ from `position`".into());
        }
        let cross = self.up.cross(view).length_squared();
        if !(cross > 0.0 && cross.is_finite()) {
            return Err("`up` must not be parallel to the view direction".into());
        }
        if !(self.fov_deg > 0.0 && self.fov_deg < 180.0) {
            return Err(format!(
                "`fov` must be between 0 and 180 degrees (exclusive), got {}",
                self.fov_deg
            ));
        }
        Ok(())
    }

    /// The distance from the eye to the `look_at` point: the default focus distance.
    pub fn look_distance(&self) -> f32 {
        (self.look_at - self.position).length()
    }

    /// The lens and shutter of `params`: aperture, focus distance (default: the `look_at`
    /// distance) and shutter interval.
    pub fn exposure(&self, params: &Params) -> Exposure {
        Exposure {
            lens: params.lens,
            lens_dispersion: params.lens_dispersion,
            aperture: params.aperture,
            focus_distance: params
                .focus_distance
                .unwrap_or_else(|| self.look_distance()),
            shutter: (params.shutter_open, params.shutter_open + params.shutter),
        }
    }

    /// The f-number of `lens` at radius `aperture`. The thin lens's is that of a lens on a
    /// 35 mm camera (24 mm film height) with this vertical field of view, taking one scene
    /// unit as a metre: N = focal length / diameter, focal length = 12 mm / tan(fov/2);
    /// `None` for a pinhole. A real lens's is its own focal length over the entrance pupil
    /// it is stopped to (it has no pinhole: its stop closes no further than
    /// [`RealLens::new`] allows).
    pub fn f_number(&self, lens: LensModel, aperture: f32) -> Option<f32> {
        let pupil_mm = 2.0 * aperture * MM;
        if let Some(real) = lens.prescription() {
            return stopped_f_number(&real, pupil_mm).map(|n| n as f32);
        }
        let focal_mm = 12.0 / (self.fov_deg.to_radians() * 0.5).tan();
        (aperture > 0.0).then(|| focal_mm / pupil_mm)
    }

    /// A pinhole's frame for an image of the given aspect ratio (width / height).
    pub fn pinhole(&self, aspect: f32) -> CameraFrame {
        self.frame(
            aspect,
            Exposure {
                lens: LensModel::Thin,
                lens_dispersion: LensDispersion::Off,
                aperture: 0.0,
                focus_distance: self.look_distance(),
                shutter: (0.0, 0.0),
            },
        )
    }

    /// The frame for an image of the given aspect ratio (width / height).
    pub fn frame(&self, aspect: f32, exposure: Exposure) -> CameraFrame {
        let forward = (self.look_at - self.position).normalize();
        let right = forward.cross(self.up).normalize();
        let up = right.cross(forward);
        let half_h = (self.fov_deg.to_radians() * 0.5).tan();
        let real = exposure.lens.prescription().and_then(|lens| {
            let (focus, pupil) = (exposure.focus_distance * MM, 2.0 * exposure.aperture * MM);
            let disperse = exposure.lens_dispersion == LensDispersion::On;
            RealLens::new(&lens, focus, pupil, self.fov_deg, aspect, disperse)
        });
        CameraFrame {
            origin: self.position,
            forward,
            right: right * half_h * aspect,
            up: up * half_h,
            lens_u: right,
            lens_v: up,
            aperture: exposure.aperture,
            focus_distance: exposure.focus_distance,
            shutter: exposure.shutter,
            real,
        }
    }
}

impl CameraFrame {
    /// The camera sample for a ray of this frame: the lens and time drawn only where the
    /// frame has a lens and an open shutter.
    pub fn draw_sample(&self, u: &mut impl Uniform) -> CameraSample {
        let (lens, shutter) = self.draws();
        CameraSample::draw(u, lens, shutter)
    }

    /// [`CameraFrame::draw_sample`] for `N` Sobol streams at once.
    #[inline(always)]
    pub(crate) fn draw_samples<const N: usize>(&self, u: &mut SobolLanes<N>) -> [CameraSample; N] {
        let (lens, shutter) = self.draws();
        CameraSample::draw_lanes(u, lens, shutter)
    }

    /// Whether its samples draw a lens point and a time: where it has a lens (a real one
    /// always has), and an open shutter.
    fn draws(&self) -> (bool, bool) {
        (
            self.aperture > 0.0 || self.real.is_some(),
            self.shutter.1 > self.shutter.0,
        )
    }

    /// The real lens, if the camera has one.
    pub fn real_lens(&self) -> Option<&RealLens> {
        self.real.as_ref()
    }

    /// The eye ray through `film`, the image position with (0, 0) at the top-left corner and
    /// (1, 1) at the bottom-right, from lens sample `lens` (unit square), at time sample
    /// `time_u` (unit interval, mapped onto the shutter).
    ///
    /// Thin lens: every ray through one film point meets the plane of focus at the point the
    /// pinhole ray meets it, so that plane is sharp and everything else blurs.
    ///
    /// A real lens: the ray leaves its front surface, NaN where the lens blocks it.
    #[inline]
    pub fn ray(&self, film: Vec2, lens: Vec2, time_u: f32) -> Ray {
        self.weighed_ray(film, lens, time_u).0
    }

    /// [`CameraFrame::ray`], with what its radiance counts for: 1 through the thin lens;
    /// through a real one, the share of the pupil it stands for ([`RealLens::ray`]), 0
    /// where the lens blocks it.
    #[inline(always)]
    pub fn weighed_ray(&self, film: Vec2, lens: Vec2, time_u: f32) -> (Ray, f32) {
        self.weighed_ray_at(film, lens, time_u, None)
    }

    /// [`CameraFrame::weighed_ray`] carrying `wavelength` (nm) through a real lens that
    /// [`CameraFrame::disperses`]; `None`, or any other lens: at n_d.
    #[inline(always)]
    pub fn weighed_ray_at(
        &self,
        film: Vec2,
        lens: Vec2,
        time_u: f32,
        wavelength: Option<f32>,
    ) -> (Ray, f32) {
        let Some(real) = &self.real else {
            return (
                self.ray_of(film.x, film.y, lens.x, lens.y, time_u).into(),
                1.0,
            );
        };
        self.out_of_lens(real.ray(film, lens, wavelength), time_u)
    }

    /// Whether its rays depend on their wavelength: through a real lens whose glass
    /// disperses (`lens_dispersion`).
    pub fn disperses(&self) -> bool {
        self.real.as_ref().is_some_and(RealLens::disperses)
    }

    /// [`CameraFrame::weighed_ray`] for `N` samples through a real lens, its glass traced
    /// in lanes: each the same bits as alone.
    #[inline(always)]
    pub(crate) fn weighed_rays<const N: usize>(
        &self,
        real: &RealLens,
        film: [Vec2; N],
        lens: [Vec2; N],
        time_u: [f32; N],
    ) -> [(Ray, f32); N] {
        let rays = real.rays(film, lens);
        std::array::from_fn(|i| self.out_of_lens(rays[i], time_u[i]))
    }

    /// The scene's ray (and weight) of a ray out of the real lens at time sample `time_u`;
    /// a NaN ray of weight 0 where the lens blocked it.
    #[inline(always)]
    fn out_of_lens(&self, ray: Option<LensRay>, time_u: f32) -> (Ray, f32) {
        let time = self.shutter.0 + time_u * (self.shutter.1 - self.shutter.0);
        match ray {
            Some(r) => {
                // Lens space to the scene: x right, y up, z along the view, mm to units.
                let world = |v: Vec3| v.x * self.lens_u + v.y * self.lens_v + v.z * self.forward;
                let ray = Ray::new(self.origin + world(r.origin) / MM, world(r.dir), time);
                (ray, r.weight)
            }
            None => (
                Ray::new(Vec3::splat(f32::NAN), Vec3::splat(f32::NAN), time),
                0.0,
            ),
        }
    }

    /// [`CameraFrame::ray`] for one ray or one per lane, the film position (`film_x`,
    /// `film_y`), the lens sample (`lens_x`, `lens_y`) and the time sample given
    /// coordinate by coordinate: the thin lens (or pinhole) only (a real lens's rays come
    /// from [`CameraFrame::weighed_rays`]).
    #[inline(always)]
    pub(crate) fn ray_of<R: Real>(
        &self,
        film_x: R,
        film_y: R,
        lens_x: R,
        lens_y: R,
        time_u: R,
    ) -> RayOf<R> {
        let (one, two) = (R::splat(1.0), R::splat(2.0));
        let (x, y) = (two * film_x - one, one - two * film_y);
        let at = R::V3::splat;
        // The pinhole direction, with unit length along `forward`.
        let d = at(self.forward) + at(self.right).scale(x) + at(self.up).scale(y);
        let (open, close) = (R::splat(self.shutter.0), R::splat(self.shutter.1));
        let time = open + time_u * (close - open);
        if self.aperture <= 0.0 {
            return RayOf {
                origin: at(self.origin),
                dir: d.normalize(),
                time,
            };
        }
        let focus_point = at(self.origin) + d.scale(R::splat(self.focus_distance));
        let (disk_x, disk_y) = concentric_disk_of(lens_x, lens_y);
        let aperture = R::splat(self.aperture);
        let (l_x, l_y) = (aperture * disk_x, aperture * disk_y);
        let origin = at(self.origin) + at(self.lens_u).scale(l_x) + at(self.lens_v).scale(l_y);
        RayOf {
            origin,
            dir: (focus_point - origin).normalize(),
            time,
        }
    }

    /// The transmission axis of a linear polariser in front of the lens at `angle_deg`
    /// from the image's horizontal (towards its up), for the ray along `dir`: the angle is
    /// taken in the plane across the ray, from the image's horizontal squared up to the ray,
    /// so that polarisers 90° apart are crossed for every ray, as ideal ones are.
    pub fn polarizer_axis(&self, angle_deg: f32, dir: Vec3) -> Vec3 {
        let (sin, cos) = angle_deg.to_radians().sin_cos();
        let x = (self.lens_u - self.lens_u.dot(dir) * dir).normalize_or(self.lens_u);
        let y = dir.cross(x);
        // Up in the image is −(dir × right): the axis turns from right towards up.
        (cos * x - sin * y).normalize_or(x)
    }

    /// The lens centre: where pinhole rays start.
    pub fn origin(&self) -> Vec3 {
        self.origin
    }

    /// The image's rectangle on the plane `distance` in front of the lens, corner by
    /// corner: top left, top right, bottom right, bottom left.
    pub fn film_corners(&self, distance: f32) -> [Vec3; 4] {
        let at =
            |x: f32, y: f32| self.origin + distance * (self.forward + x * self.right + y * self.up);
        [at(-1.0, 1.0), at(1.0, 1.0), at(1.0, -1.0), at(-1.0, -1.0)]
    }

    /// The unit view direction.
    pub fn forward(&self) -> Vec3 {
        self.forward
    }

    /// The film position (as in [`CameraFrame::ray`]) where the point `p` appears, if it
    /// is in front of the camera.
    pub fn project(&self, p: Vec3) -> Option<Vec2> {
        let rel = p - self.origin;
        let depth = rel.dot(self.forward);
        if depth <= 0.0 {
            return None;
        }
        let x = rel.dot(self.right) / (depth * self.right.length_squared());
        let y = rel.dot(self.up) / (depth * self.up.length_squared());
        Some(Vec2::new(0.5 * (x + 1.0), 0.5 * (1.0 - y)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam() -> Camera {
        Camera::looking_at(
            Vec3::new(0.0, 1.0, 5.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::Y,
            60.0,
        )
    }

    #[test]
    fn centre_ray_looks_at_the_target_and_corners_span_the_fov() {
        let f = cam().pinhole(2.0);
        let r = f.ray(Vec2::splat(0.5), Vec2::ZERO, 0.0);
        assert!((r.dir - -Vec3::Z).length() < 1e-6);
        let top = f.ray(Vec2::new(0.5, 0.0), Vec2::ZERO, 0.0);
        assert!((top.dir.angle_between(r.dir).to_degrees() - 30.0).abs() < 1e-3);
        assert!(top.dir.y > 0.0, "film y = 0 is the top of the image");
        let right = f.ray(Vec2::new(1.0, 0.5), Vec2::ZERO, 0.0);
        assert!(right.dir.x > 0.0);
        let expected = (2.0 * (30f32).to_radians().tan()).atan().to_degrees();
        assert!((right.dir.angle_between(r.dir).to_degrees() - expected).abs() < 1e-3);
    }

    #[test]
    fn f_number_of_a_normal_lens() {
        // 2 atan(12/28) vertical is a 28 mm lens on 35 mm film; a 1.75 mm radius is f/8.
        let fov = 2.0 * (12.0f32 / 28.0).atan().to_degrees();
        let c = Camera::looking_at(Vec3::ZERO, -Vec3::Z, Vec3::Y, fov);
        let n = c.f_number(LensModel::Thin, 0.00175).unwrap();
        assert!((n - 8.0).abs() < 1e-3, "{n}");
        assert_eq!(c.f_number(LensModel::Thin, 0.0), None);
        // The double Gauss is f/2 open: a 50 mm pupil would be wider than it opens.
        let n = c.f_number(LensModel::DoubleGauss50, 0.025).unwrap();
        assert!((n - 2.0).abs() < 0.1, "{n}");
        // Stopped to a 6.25 mm pupil (radius 3.125 mm) it is f/8.
        let n = c.f_number(LensModel::DoubleGauss50, 0.003125).unwrap();
        assert!((n - 8.0).abs() < 0.05, "{n}");
    }

    #[test]
    fn project_inverts_ray() {
        let f = cam().pinhole(1.5);
        let film = Vec2::new(0.3, 0.8);
        let p = f.ray(film, Vec2::ZERO, 0.0).at(7.0);
        assert!((f.project(p).unwrap() - film).length() < 1e-5);
    }

    #[test]
    fn thin_lens_rays_meet_on_the_focus_plane() {
        let c = cam();
        let f = c.frame(
            1.0,
            Exposure {
                lens: LensModel::Thin,
                lens_dispersion: LensDispersion::Off,
                aperture: 0.5,
                focus_distance: 3.0,
                shutter: (0.0, 0.0),
            },
        );
        let film = Vec2::new(0.7, 0.2);
        let pin = c.pinhole(1.0).ray(film, Vec2::ZERO, 0.0);
        // The pinhole ray reaches the focus plane (depth 3 along -z) at t = 3 / cos.
        let target = pin.at(3.0 / pin.dir.dot(-Vec3::Z));
        for lens in [
            Vec2::new(0.1, 0.9),
            Vec2::new(0.8, 0.3),
            Vec2::new(0.5, 0.5),
        ] {
            let r = f.ray(film, lens, 0.0);
            let t = (r.origin.z - target.z) / -r.dir.z;
            assert!((r.at(t) - target).length() < 1e-4);
        }
    }

    #[test]
    fn rays_made_in_lanes_are_each_pinhole_and_thin_lens_ray_bit_for_bit() {
        use crate::math::lanes::Lanes;
        let c = cam();
        let lens = Exposure {
            lens: LensModel::Thin,
            lens_dispersion: LensDispersion::Off,
            aperture: 0.3,
            focus_distance: 4.5,
            shutter: (0.25, 0.75),
        };
        // Film corners and centre, the lens's centre (0.5, 0.5, where the disk map takes
        // its own branch), its wedges and its edges.
        let film = [(0.0, 0.0), (1.0, 1.0), (0.5, 0.5), (0.13, 0.91)];
        let lens_u = [(0.5, 0.5), (0.9, 0.55), (0.45, 0.05), (0.0, 1.0)];
        let time_u = [0.0, 1.0, 0.37, 0.999];
        for frame in [c.pinhole(1.5), c.frame(1.5, lens)] {
            let rays = frame.ray_of(
                Lanes::<4>::from_fn(|i| film[i].0),
                Lanes::from_fn(|i| film[i].1),
                Lanes::from_fn(|i| lens_u[i].0),
                Lanes::from_fn(|i| lens_u[i].1),
                Lanes::from_fn(|i| time_u[i]),
            );
            for i in 0..4 {
                let r = frame.ray(
                    Vec2::new(film[i].0, film[i].1),
                    Vec2::new(lens_u[i].0, lens_u[i].1),
                    time_u[i],
                );
                let bits = |v: Vec3| v.to_array().map(f32::to_bits);
                assert_eq!(bits(rays.origin.get(i)), bits(r.origin));
                assert_eq!(bits(rays.dir.get(i)), bits(r.dir));
                assert_eq!(rays.time.0[i].to_bits(), r.time.to_bits());
            }
        }
    }

    #[test]
    fn camera_samples_drawn_in_lanes_are_each_streams_own() {
        use crate::math::{Pattern, SampleStream, rng::seed_key};
        let key = seed_key(11);
        let pixels: [u32; 8] = [0, 1, 2, 640, 641, 99_999, 5, 5];
        let samples: [u32; 8] = [0, 0, 7, 1, 1023, 65_537, 3, 4];
        for (lens, shutter) in [(false, false), (true, false), (false, true), (true, true)] {
            let mut lanes = SobolLanes::new(16, key, pixels, samples);
            let drawn = CameraSample::draw_lanes(&mut lanes, lens, shutter);
            for i in 0..8 {
                let mut one =
                    SampleStream::with_seed_key(Pattern::Sobol, 16, key, pixels[i], samples[i]);
                assert_eq!(drawn[i], CameraSample::draw(&mut one, lens, shutter));
                // And each lane's stream goes on where its own would.
                let mut rest = lanes.stream(i);
                assert_eq!(rest.dimension(), one.dimension());
                assert_eq!(rest.next_2d(), one.next_2d(), "lane {i}");
                assert_eq!(rest.next_1d(), one.next_1d(), "lane {i}");
            }
        }
    }
}
