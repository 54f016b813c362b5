//! Polarisation: the complex Fresnel amplitudes r_s and r_p, the Mueller matrix of a
//! reflection or a refraction in its s/p frame, and the rotation of Stokes frames.
//!
//! A Stokes vector (I, Q, U, V) describes light along a ray in a frame (x, y = d × x)
//! perpendicular to its direction d: Q > 0 is light polarised along x, U along the
//! diagonal, V circular. At an interface the natural frame has x = s, the direction
//! perpendicular to the plane of incidence, shared by the incident, reflected and
//! refracted rays. There a reflection's Mueller matrix is
//!
//! ```text
//!       | A  B  0  0 |     A = (R_s + R_p)/2,  B = (R_s − R_p)/2,
//!   M = | B  A  0  0 |     C + iS = r_s conj(r_p)
//!       | 0  0  C  S |     (R_s = |r_s|², R_p = |r_p|²)
//!       | 0  0 −S  C |
//! ```
//!
//! and a refraction's the same with T_s = 1 − R_s, T_p = 1 − R_p, C = √(T_s T_p), S = 0
//! (radiance is not scaled by (n2/n1)², as everywhere in the tracer). Light from the
//! lights, the sky and diffuse surfaces is unpolarised: (I, 0, 0, 0).

use crate::math::Color;

/// A complex number, for the amplitudes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Complex {
    /// Real part.
    pub re: f64,
    /// Imaginary part.
    pub im: f64,
}

impl Complex {
    /// re + i·im.
    pub const fn new(re: f64, im: f64) -> Complex {
        Complex { re, im }
    }

    fn add(self, o: Complex) -> Complex {
        Complex::new(self.re + o.re, self.im + o.im)
    }

    fn sub(self, o: Complex) -> Complex {
        Complex::new(self.re - o.re, self.im - o.im)
    }

    fn mul(self, o: Complex) -> Complex {
        Complex::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }

    fn div(self, o: Complex) -> Complex {
        let d = o.norm2();
        Complex::new(
            (self.re * o.re + self.im * o.im) / d,
            (self.im * o.re - self.re * o.im) / d,
        )
    }

    /// The complex conjugate.
    pub fn conj(self) -> Complex {
        Complex::new(self.re, -self.im)
    }

    /// |z|².
    pub fn norm2(self) -> f64 {
        self.re * self.re + self.im * self.im
    }

    /// The square root with a non-negative imaginary part.
    fn sqrt_upper(self) -> Complex {
        let r = self.norm2().sqrt();
        let re = (0.5 * (r + self.re)).max(0.0).sqrt();
        let im = (0.5 * (r - self.re)).max(0.0).sqrt();
        // Pick the root in the upper half plane: Im ≥ 0 (a wave that decays beyond).
        if self.im >= 0.0 {
            Complex::new(re, im)
        } else {
            Complex::new(-re, im)
        }
    }
}

/// The Fresnel amplitude ratios (r_s, r_p) of light arriving at cos θi from a dielectric of
/// index `n1` onto a medium of complex index `eta` + i`k` (k = 0: a dielectric; beyond its
/// critical angle the amplitudes are complex of modulus 1, total internal reflection):
///
/// r_s = (n1 cos θi − n cos θt)/(n1 cos θi + n cos θt),
/// r_p = (n cos θi − n1 cos θt)/(n cos θi + n1 cos θt),  n sin θt = n1 sin θi,
///
/// the same signs as [`super::fresnel_exact`]'s F_s and F_p.
pub fn fresnel_amplitudes(cos_i: f32, n1: f32, eta: f32, k: f32) -> (Complex, Complex) {
    let cos_i = (cos_i as f64).clamp(0.0, 1.0);
    let n1 = n1 as f64;
    let n = Complex::new(eta as f64, k as f64);
    let sin2_i = 1.0 - cos_i * cos_i;
    // cos θt = √(1 − (n1/n)² sin²θi), the root whose wave decays into the medium.
    let ratio = Complex::new(n1, 0.0).div(n);
    let cos_t = Complex::new(1.0, 0.0)
        .sub(ratio.mul(ratio).mul(Complex::new(sin2_i, 0.0)))
        .sqrt_upper();
    let n1_cos_i = Complex::new(n1 * cos_i, 0.0);
    let n_cos_t = n.mul(cos_t);
    let r_s = n1_cos_i.sub(n_cos_t).div(n1_cos_i.add(n_cos_t));
    let n_cos_i = n.mul(Complex::new(cos_i, 0.0));
    let n1_cos_t = Complex::new(n1, 0.0).mul(cos_t);
    let r_p = n_cos_i.sub(n1_cos_t).div(n_cos_i.add(n1_cos_t));
    if r_s.re.is_finite() && r_s.im.is_finite() && r_p.re.is_finite() && r_p.im.is_finite() {
        (r_s, r_p)
    } else {
        // Exactly grazing: everything reflected.
        (Complex::new(-1.0, 0.0), Complex::new(-1.0, 0.0))
    }
}

/// The four distinct elements of a Mueller matrix in its interface's s/p frame (see the
/// module's documentation), per colour channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mueller {
    /// (M_s + M_p)/2: what unpolarised light keeps.
    pub a: Color,
    /// (M_s − M_p)/2: how much it polarises along s.
    pub b: Color,
    /// The diagonal's U and V elements.
    pub c: Color,
    /// The retardance's U–V coupling.
    pub s: Color,
}

impl Mueller {
    /// A reflection of amplitudes `r_s`, `r_p` per channel.
    pub fn reflection(amplitudes: [(Complex, Complex); 3]) -> Mueller {
        let per = |f: &dyn Fn(Complex, Complex) -> f64| {
            Color::from_array(amplitudes.map(|(s, p)| f(s, p) as f32))
        };
        Mueller {
            a: per(&|s, p| 0.5 * (s.norm2() + p.norm2())),
            b: per(&|s, p| 0.5 * (s.norm2() - p.norm2())),
            c: per(&|s, p| s.mul(p.conj()).re),
            s: per(&|s, p| s.mul(p.conj()).im),
        }
    }

    /// A refraction with reflectances `r_s`, `r_p` (all channels alike): T = 1 − R.
    pub fn transmission(r_s: f32, r_p: f32) -> Mueller {
        let (t_s, t_p) = ((1.0 - r_s).max(0.0), (1.0 - r_p).max(0.0));
        Mueller {
            a: Color::splat(0.5 * (t_s + t_p)),
            b: Color::splat(0.5 * (t_s - t_p)),
            c: Color::splat((t_s * t_p).sqrt()),
            s: Color::ZERO,
        }
    }

    /// A reflection that does not polarise (a constant reflectance, Schlick): r_s = −r_p,
    /// as at normal incidence.
    pub fn neutral_reflection(r: Color) -> Mueller {
        Mueller {
            a: r,
            b: Color::ZERO,
            c: -r,
            s: Color::ZERO,
        }
    }

    /// A refraction that does not polarise.
    pub fn neutral_transmission(t: Color) -> Mueller {
        Mueller {
            a: t,
            b: Color::ZERO,
            c: t,
            s: Color::ZERO,
        }
    }
}

/// A polarisation-sensitive measurement along a ray: the row vector w (per channel) such
/// that a Stokes vector S arriving along the ray is seen as w · S. The camera's polariser
/// starts it; each interface, walked from the camera towards the lights, multiplies it by
/// its Mueller matrix. It is kept divided by the unpolarised weights the tracer already
/// applies, so that unpolarised light L at the end of a path is seen as w₀ L.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Analyzer {
    /// w per Stokes component, per channel, in the frame (x, d × x) of the ray.
    pub w: [Color; 4],
    /// The frame's x axis.
    pub x: crate::math::Vec3,
}

impl Analyzer {
    /// A linear polariser whose transmission axis is `axis` (unit, perpendicular to the
    /// ray): w = ½ (1, 1, 0, 0) in the frame whose x axis is the polariser's. Unpolarised
    /// light passes half.
    pub fn linear_polarizer(axis: crate::math::Vec3) -> Analyzer {
        Analyzer {
            w: [
                Color::splat(0.5),
                Color::splat(0.5),
                Color::ZERO,
                Color::ZERO,
            ],
            x: axis,
        }
    }

    /// The same measurement in the frame whose x axis is `x` (unit, perpendicular to the
    /// ray `dir`): turning the frame by θ turns (w₁, w₂) by 2θ, as it does (Q, U).
    pub fn in_frame(&self, dir: crate::math::Vec3, x: crate::math::Vec3) -> Analyzer {
        let y = dir.cross(self.x);
        let (cos, sin) = (x.dot(self.x), x.dot(y));
        // cos 2θ and sin 2θ of the angle θ from the old x axis to the new one.
        let norm = cos * cos + sin * sin;
        let (cos2, sin2) = if norm > 0.0 {
            ((cos * cos - sin * sin) / norm, 2.0 * cos * sin / norm)
        } else {
            (1.0, 0.0)
        };
        let [w0, w1, w2, w3] = self.w;
        Analyzer {
            w: [w0, w1 * cos2 + w2 * sin2, -w1 * sin2 + w2 * cos2, w3],
            x,
        }
    }

    /// Through an interface, in its s/p frame (the analyzer's x axis must be s): w · M,
    /// divided by the unpolarised weight A where it is not 0.
    pub fn through(&self, m: &Mueller) -> Analyzer {
        let [w0, w1, w2, w3] = self.w;
        let scale = Color::from_array(m.a.to_array().map(|a| if a > 0.0 { 1.0 / a } else { 0.0 }));
        Analyzer {
            w: [
                (w0 * m.a + w1 * m.b) * scale,
                (w0 * m.b + w1 * m.a) * scale,
                (w2 * m.c - w3 * m.s) * scale,
                (w2 * m.s + w3 * m.c) * scale,
            ],
            x: self.x,
        }
    }

    /// How unpolarised light is seen: w₀ per channel.
    pub fn unpolarized(&self) -> Color {
        self.w[0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Vec3;

    #[test]
    fn amplitudes_match_the_real_fresnel_equations_and_total_reflection_has_modulus_one() {
        for (n1, n2) in [(1.0f32, 1.5f32), (1.5, 1.0), (1.0, 2.42), (1.33, 1.0)] {
            for i in 0..=89 {
                let cos_i = (i as f32).to_radians().cos();
                let (r_s, r_p) = fresnel_amplitudes(cos_i, n1, n2, 0.0);
                match super::super::cos_transmitted(cos_i, n1, n2) {
                    Some(_) => {
                        let (f_s, f_p, _) = super::super::fresnel_exact(cos_i, n1, n2);
                        assert!((r_s.re as f32 - f_s).abs() < 1e-5, "{n1}->{n2} at {i}°");
                        assert!((r_p.re as f32 - f_p).abs() < 1e-5, "{n1}->{n2} at {i}°");
                        assert!(r_s.im.abs() < 1e-9 && r_p.im.abs() < 1e-9);
                    }
                    None => {
                        assert!((r_s.norm2() - 1.0).abs() < 1e-9, "{n1}->{n2} at {i}°");
                        assert!((r_p.norm2() - 1.0).abs() < 1e-9, "{n1}->{n2} at {i}°");
                    }
                }
            }
        }
    }

    #[test]
    fn a_polarizer_follows_malus_and_an_interface_polarizes_at_brewster() {
        // Light polarised along x seen through a polariser at θ: cos²θ of it (Malus).
        let d = Vec3::NEG_Z;
        for deg in [0.0f32, 30.0, 45.0, 90.0, 120.0] {
            let t = deg.to_radians();
            let pol = Analyzer::linear_polarizer(Vec3::new(t.cos(), t.sin(), 0.0));
            let w = pol.in_frame(d, Vec3::X).w;
            // Fully polarised along x: S = (1, 1, 0, 0).
            let seen = w[0].x + w[1].x;
            assert!((seen - t.cos().powi(2)).abs() < 1e-6, "{deg}°: {seen}");
        }
        // At Brewster's angle r_p = 0: the reflected light is all s. A polariser along s
        // sees it all, one crossed with s sees none.
        let (n1, n2) = (1.0f32, 1.5f32);
        let brewster = super::super::brewster_angle(n1, n2);
        let amps = fresnel_amplitudes(brewster.cos(), n1, n2, 0.0);
        let m = Mueller::reflection([amps; 3]);
        // Unpolarised light in, reflected: (A, B, 0, 0) with A = B = R_s/2. Seen through
        // a polariser along s: (A + B)/2 = R_s/2; crossed: (A − B)/2 = 0.
        let r_s = amps.0.norm2() as f32;
        for (axis, expected) in [(Vec3::X, r_s / 2.0), (Vec3::Y, 0.0)] {
            let a = Analyzer::linear_polarizer(axis)
                .in_frame(d, Vec3::X)
                .through(&m);
            // The tracer multiplies by A itself; the analyzer keeps the rest.
            let seen = a.unpolarized().x * m.a.x;
            assert!(
                (seen - expected).abs() < 1e-6,
                "{axis}: {seen} against {expected}"
            );
        }
    }
}
