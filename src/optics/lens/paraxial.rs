//! Paraxial optics of a prescription: ray-transfer matrices for rays close to the axis,
//! which give the focal lengths, the principal planes, the entrance pupil and the f-number.
//!
//! A paraxial ray is its height y and its reduced angle n u. Crossing a surface of
//! curvature c = 1/R from index n into n′ bends it, (y, n′u′) = (y, n u − y (n′ − n) c),
//! and travelling a thickness t in index n moves it, (y + t (n u)/n, n u). The product of
//! these 2×2 matrices from the first surface to the last is the system matrix [A B; C D],
//! from which the effective focal length is f = −1/C and the back focal length (from the
//! last surface to the focus of light from infinity) is −A/C.

use super::Prescription;

/// A 2×2 ray-transfer matrix acting on (y, n u), in f64: a long lens's product of many
/// matrices loses digits in f32.
#[derive(Clone, Copy, Debug)]
struct Matrix([[f64; 2]; 2]);

impl Matrix {
    const IDENTITY: Matrix = Matrix([[1.0, 0.0], [0.0, 1.0]]);

    /// Refraction at a surface of radius `radius` (0: flat) from index `n` into `n_after`.
    fn refraction(radius: f64, n: f64, n_after: f64) -> Matrix {
        let power = if radius == 0.0 {
            0.0
        } else {
            (n_after - n) / radius
        };
        Matrix([[1.0, 0.0], [-power, 1.0]])
    }

    /// Travel over `thickness` in index `n`.
    fn transfer(thickness: f64, n: f64) -> Matrix {
        Matrix([[1.0, thickness / n], [0.0, 1.0]])
    }

    /// `self` after `first`: the matrix of `first` then `self`.
    fn after(self, first: Matrix) -> Matrix {
        let (a, b) = (self.0, first.0);
        Matrix(std::array::from_fn(|i| {
            std::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j])
        }))
    }

    fn apply(self, (y, nu): (f64, f64)) -> (f64, f64) {
        let m = self.0;
        (m[0][0] * y + m[0][1] * nu, m[1][0] * y + m[1][1] * nu)
    }
}

/// What the paraxial matrices say about a lens (lengths in mm, at n_d).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Paraxial {
    /// Effective focal length f = −1/C.
    pub efl: f64,
    /// Back focal length: from the last surface to the focus of parallel light, −A/C.
    pub bfl: f64,
    /// Front focal length: from the first surface forward to the front focus, −D/C.
    pub ffl: f64,
    /// From the first surface to the last, along the axis.
    pub length: f64,
    /// Diameter of the entrance pupil (the stop as seen from the front) with the stop
    /// open: the stop's diameter over the height at the stop of a ray that enters parallel
    /// to the axis at height 1.
    pub entrance_pupil: f64,
}

impl Paraxial {
    /// The paraxial description of `lens`, or `None` for one without power (C = 0: it
    /// focuses nothing) or whose stop no paraxial ray from the front reaches.
    pub fn of(lens: &Prescription) -> Option<Paraxial> {
        let mut m = Matrix::IDENTITY;
        let mut n = 1.0;
        let mut at_stop = None;
        let last = lens.surfaces.len() - 1;
        for (i, s) in lens.surfaces.iter().enumerate() {
            let n_after = f64::from(s.ior);
            m = Matrix::refraction(f64::from(s.radius), n, n_after).after(m);
            if s.stop {
                at_stop = Some(m.apply((1.0, 0.0)).0);
            }
            if i < last {
                m = Matrix::transfer(f64::from(s.thickness), n_after).after(m);
            }
            n = n_after;
        }
        let [[a, _], [c, d]] = m.0;
        let height_at_stop = at_stop?.abs();
        if c == 0.0 || !c.is_finite() || height_at_stop < 1e-9 {
            return None;
        }
        let stop_diameter = f64::from(lens.surfaces[lens.stop()].aperture);
        Some(Paraxial {
            efl: -1.0 / c,
            bfl: -a / c,
            ffl: -d / c,
            length: lens.surfaces[..last]
                .iter()
                .map(|s| f64::from(s.thickness))
                .sum(),
            entrance_pupil: stop_diameter / height_at_stop,
        })
    }

    /// The f-number with the stop open: N = f / entrance pupil diameter.
    pub fn f_number(&self) -> f64 {
        self.efl / self.entrance_pupil
    }

    /// The field of view (degrees) across `film` mm of film with the lens focused at
    /// infinity: 2 atan(film / 2f).
    pub fn field_of_view(&self, film: f64) -> f64 {
        2.0 * (0.5 * film / self.efl).atan().to_degrees()
    }

    /// The front principal plane's distance behind the first surface (negative: in front
    /// of it): the front focus is f beyond it.
    pub fn front_principal(&self) -> f64 {
        self.efl - self.ffl
    }

    /// The rear principal plane's distance in front of the last surface (negative: behind
    /// it): the back focus is f behind it.
    pub fn rear_principal(&self) -> f64 {
        self.efl - self.bfl
    }

    /// The image distance behind the rear principal plane of a point `object` mm in front
    /// of the front principal plane, by Gauss's lens equation 1/s + 1/s′ = 1/f:
    /// s′ = s f / (s − f). `None` for an object at or inside the front focus (no real
    /// image).
    pub fn image_distance(&self, object: f64) -> Option<f64> {
        let f = self.efl;
        (object > f).then(|| object * f / (object - f))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optics::lens::{LensModel, Prescription};

    fn design(model: LensModel) -> Paraxial {
        Paraxial::of(&model.prescription().unwrap()).unwrap()
    }

    #[test]
    fn a_thick_singlets_focal_length_is_the_lensmakers() {
        // 1/f = (n − 1) (1/R1 − 1/R2 + (n − 1) d / (n R1 R2)).
        let (n, r1, r2, d): (f64, f64, f64, f64) = (1.5168, 51.5, -51.5, 5.0);
        let f = 1.0 / ((n - 1.0) * (1.0 / r1 - 1.0 / r2 + (n - 1.0) * d / (n * r1 * r2)));
        let p = design(LensModel::Singlet50);
        // (To the f32 the table's numbers are held in.)
        assert!((p.efl - f).abs() < 1e-6 * f, "{} against {f}", p.efl);
        // Its principal planes: h′ = −f (n − 1) d / (n R1) from the back surface.
        let rear = f * (n - 1.0) * d / (n * r1);
        assert!(
            (p.rear_principal() - rear).abs() < 1e-6,
            "{}",
            p.rear_principal()
        );
        // The stop, 12 mm across in air in front of it, is its own entrance pupil.
        assert!((p.entrance_pupil - 12.0).abs() < 1e-12);
    }

    #[test]
    fn the_shipped_designs_have_their_published_focal_lengths() {
        for (model, published) in [
            (LensModel::DoubleGauss50, 50.0),
            (LensModel::Wide22, 22.0),
            (LensModel::Telephoto250, 250.0),
        ] {
            let efl = design(model).efl;
            assert!(
                (efl / published - 1.0).abs() < 0.005,
                "{model:?}: {efl} mm against {published}"
            );
        }
        // The double Gauss is an f/2 (its stop, seen through the front group).
        let n = design(LensModel::DoubleGauss50).f_number();
        assert!((n - 2.0).abs() < 0.1, "f/{n}");
        // The telephoto is an f/5.6.
        let n = design(LensModel::Telephoto250).f_number();
        assert!((n - 5.6).abs() < 0.3, "f/{n}");
    }

    #[test]
    fn gauss_equation_images_infinity_at_the_back_focus() {
        let p = design(LensModel::DoubleGauss50);
        let far = p.image_distance(1e12).unwrap();
        assert!((far - p.efl).abs() < 1e-6);
        // Unit magnification at 2f: s = s′.
        let s = p.image_distance(2.0 * p.efl).unwrap();
        assert!((s - 2.0 * p.efl).abs() < 1e-9);
        assert_eq!(p.image_distance(p.efl), None);
    }

    #[test]
    fn a_lens_without_power_has_no_paraxial_description() {
        let flat = Prescription::parse("0 1 0 4\n0 2 1.5 8\n0 0 1 8\n", "window").unwrap();
        assert_eq!(Paraxial::of(&flat), None);
    }
}
