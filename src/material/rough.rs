//! Rough glass: a dielectric whose interface is a field of GGX microfacets of roughness α
//! (Walter et al. 2007; the formulas are in [`crate::optics::microfacet`]). Where the lecture
//! jitters the mirror ray for glossy reflection, the rough interface jitters the facet the
//! ray meets, and with it both children: at each hit one facet normal m is drawn among
//! those the ray sees, and the ray splits there as at a smooth interface, its reflected
//! child of weight F(m) · G1(o) and its refracted child of weight (1 − F(m)) · G1(o), F at
//! the facet's own angle by the material's Fresnel mode. A child that would leave on the
//! wrong side of the surface is shadowed (G1 = 0): that light is lost, as single scattering
//! on a rough surface loses it. α → 0 is the smooth dielectric.

use super::{Dielectric, Interaction, Interface, Lobe, LobeKind, Scatter, Side};
use crate::math::{Color, Uniform, Vec3, orthonormal_basis};
use crate::optics::microfacet::{
    reflection_normal, refraction_jacobian, refraction_normal, sample_visible_normal, smith_g1,
    visible_normal_pdf,
};
use crate::optics::polarization::Mueller;
use crate::optics::{FresnelMode, reflect, refract};

/// A rough interface as one hit sees it: what its lobes need to say how much light they
/// pass towards any direction, and with what density they draw it (path tracing weighs
/// its light samples by that).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microfacet {
    /// The GGX roughness α.
    pub alpha: f32,
    /// The index on the side the ray comes from.
    pub n1: f32,
    /// The index on the other side.
    pub n2: f32,
    /// How each facet's reflectance is computed.
    pub fresnel: FresnelMode,
    /// The reflectance of the constant model.
    pub constant_reflectance: f32,
}

/// The macro surface's frame at a hit: the shading normal, or the geometric one where the
/// ray would meet the shading normal from behind (no facet of it would be visible).
struct Frame {
    t: Vec3,
    b: Vec3,
    n: Vec3,
}

impl Frame {
    fn at(hit: &Interaction) -> Frame {
        let n = if -hit.dir.dot(hit.n_shade) > 0.0 {
            hit.n_shade
        } else {
            hit.n_geom
        };
        let (t, b) = orthonormal_basis(n);
        Frame { t, b, n }
    }

    fn local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.t), v.dot(self.b), v.dot(self.n))
    }

    fn world(&self, v: Vec3) -> Vec3 {
        v.x * self.t + v.y * self.b + v.z * self.n
    }
}

/// The two children of a hit at one facet: each one's direction and weight, `None` where
/// it does not exist (the refraction under total internal reflection at the facet) or is
/// masked (it would leave on the wrong side of the macro surface, either normal).
struct Children {
    reflected: Option<(Vec3, f32)>,
    refracted: Option<(Vec3, f32)>,
    // cos θ at the facet, its reflectance, and whether it reflects totally.
    cos_m: f32,
    r: f32,
    total: bool,
}

impl Microfacet {
    /// The reflectance of the facet seen at cos θ = `cos_m` (1 under total internal
    /// reflection).
    fn reflectance(&self, cos_m: f32) -> f32 {
        self.fresnel
            .reflectance(cos_m, self.n1, self.n2, self.constant_reflectance)
    }

    /// The children of a ray along `dir` meeting the facet `m` (world space), the macro
    /// surface's frame `frame` and geometric normal `n_geom` facing the ray: reflected of
    /// weight F(m) G1(o), refracted of weight (1 − F(m)) G1(o).
    fn children(&self, dir: Vec3, m: Vec3, frame: &Frame, n_geom: Vec3) -> Children {
        let cos_m = (-dir).dot(m).clamp(0.0, 1.0);
        let r = self.reflectance(cos_m);
        let child = |side, o: Vec3, share: f32| {
            let (cos_o, cos_geom) = (o.dot(frame.n), o.dot(n_geom));
            let right_side = match side {
                Side::Reflect => cos_o > 0.0 && cos_geom > 0.0,
                Side::Transmit => cos_o < 0.0 && cos_geom < 0.0,
            };
            let weight = share * smith_g1(cos_o, self.alpha);
            (right_side && weight > 0.0).then_some((o, weight))
        };
        let refracted = refract(dir, m, self.n1, self.n2);
        Children {
            reflected: child(Side::Reflect, reflect(dir, m), r),
            refracted: refracted.and_then(|t| child(Side::Transmit, t, 1.0 - r)),
            cos_m,
            r,
            total: refracted.is_none(),
        }
    }

    /// What the lobe on `side` passes from direction `dir` towards the viewer of `at`
    /// (f cos θo), the density with which it draws `dir`, and the facet that sends the
    /// view there (world space): [`Microfacet::lobe`] in the hit's frame, where `dir`
    /// leaves on `side` of the geometric surface too.
    fn lobe_eval(
        &self,
        at: &Interaction,
        frame: &Frame,
        side: Side,
        dir: Vec3,
    ) -> Option<(f32, f32, Vec3)> {
        let leaves_here = dir.dot(at.n_geom) > 0.0;
        if leaves_here != (side == Side::Reflect) {
            return None;
        }
        let (f_cos, pdf, m) = self.lobe(frame.local(-at.dir), frame.local(dir), side)?;
        Some((f_cos, pdf, frame.world(m)))
    }

    /// What the lobe on `side` passes from `v` (towards the viewer) to `o` in the macro
    /// surface's frame (n = +z): f cos θo, the density with which the lobe draws `o`, and
    /// the facet m that sends the view there: the half vector, D_v(m) times the Jacobian
    /// of reflection (1/(4|o·m|)) or refraction, and f cos θo = that density times the
    /// weight the lobe would carry, F(m) G1(o) or (1 − F(m)) G1(o). `None` where `o` is on
    /// the other side or no facet sends the view there. The interface workbench draws
    /// the lobes with it.
    pub fn lobe(&self, v: Vec3, o: Vec3, side: Side) -> Option<(f32, f32, Vec3)> {
        let (m, jacobian, share) = match side {
            Side::Reflect if o.z > 0.0 => {
                let m = reflection_normal(v, o)?;
                let f = self.reflectance(v.dot(m).clamp(0.0, 1.0));
                (m, 1.0 / (4.0 * o.dot(m).abs()), f)
            }
            Side::Transmit if o.z < 0.0 => {
                let m = refraction_normal(v, o, self.n1, self.n2)?;
                let f = self.reflectance(v.dot(m).clamp(0.0, 1.0));
                (m, refraction_jacobian(v, o, m, self.n1, self.n2), 1.0 - f)
            }
            _ => return None,
        };
        let pdf = visible_normal_pdf(v, m, self.alpha) * jacobian;
        (pdf > 0.0 && pdf.is_finite()).then(|| (share * smith_g1(o.z, self.alpha) * pdf, pdf, m))
    }

    /// What the lobe on `side` passes from `dir` towards the viewer of `at` (f cos θo),
    /// and the density with which it draws `dir`, as the split tree draws it at every hit:
    /// D_v(m) of the facet m that sends the view there (the half vector) times the
    /// Jacobian of reflection (1/(4|o·m|)) or refraction, and f cos θo = that density times
    /// the lobe's weight there, F(m) G1(o) or (1 − F(m)) G1(o). (0, 0) where no facet
    /// sends the view to `dir`.
    pub fn eval(&self, at: &Interaction, side: Side, dir: Vec3) -> (f32, f32) {
        self.lobe_eval(at, &Frame::at(at), side, dir)
            .map_or((0.0, 0.0), |(f_cos, pdf, _)| (f_cos, pdf))
    }

    /// The whole interface towards `dir`, as a path meets it: f cos θo of the lobe on
    /// `dir`'s side, and the density with which a path draws `dir`: the lobe's density
    /// times the chance that the path follows that lobe at the facet that sends the view
    /// there, its weight over both children's (a path follows one child in proportion to
    /// its weight).
    pub fn eval_path(&self, at: &Interaction, dir: Vec3) -> (f32, f32) {
        let side = if dir.dot(at.n_geom) > 0.0 {
            Side::Reflect
        } else {
            Side::Transmit
        };
        let frame = Frame::at(at);
        let Some((f_cos, pdf, m)) = self.lobe_eval(at, &frame, side, dir) else {
            return (0.0, 0.0);
        };
        let c = self.children(at.dir, m, &frame, at.n_geom);
        let weight = |child: Option<(Vec3, f32)>| child.map_or(0.0, |(_, w)| w);
        let (w_r, w_t) = (weight(c.reflected), weight(c.refracted));
        let chosen = match side {
            Side::Reflect => w_r,
            Side::Transmit => w_t,
        };
        if chosen <= 0.0 {
            return (f_cos, 0.0);
        }
        (f_cos, pdf * chosen / (w_r + w_t))
    }
}

impl Dielectric {
    /// The facet a rough interface's child `lobe` of `hit` left from (world space, facing
    /// the incoming ray), and the Mueller matrix of that child in the facet's own s/p frame:
    /// the smooth interface's at the facet's angle, scaled by the masking G1 the lobe's
    /// weight carries (weight = F(m) G1 or (1 − F(m)) G1). Each facet polarises in its own
    /// plane of incidence, as the lecture's interface does in its one plane.
    pub(super) fn facet_mueller(&self, hit: &Interaction, lobe: &Lobe) -> Option<(Vec3, Mueller)> {
        let (n1, n2) = self.sides(hit);
        let v = -hit.dir;
        // The half vector of reflection, or Walter's generalized one of refraction.
        let h = match lobe.side {
            Side::Reflect => v + lobe.dir,
            Side::Transmit => -(n1 * v + n2 * lobe.dir),
        };
        let m = h.try_normalize()?;
        let m = if m.dot(v) < 0.0 { -m } else { m };
        let facet = self.mueller_at(v.dot(m).clamp(0.0, 1.0), n1, n2, lobe.side);
        // G1 per channel: the lobe's weight over the facet's Fresnel share.
        let g1 = (lobe.weight / facet.a.max(Color::splat(1e-12))).min(Color::ONE);
        let scaled = Mueller {
            a: facet.a * g1,
            b: facet.b * g1,
            c: facet.c * g1,
            s: facet.s * g1,
        };
        Some((m, scaled))
    }

    /// This interface as rough ([`Dielectric::roughness`] above 0): one facet drawn among
    /// those the ray sees (two numbers from `u`), and the ray reflected and refracted there.
    pub(super) fn rough_scatter(&self, hit: &Interaction, u: &mut impl Uniform) -> Scatter {
        let (n1, n2) = self.sides(hit);
        let facets = Microfacet {
            alpha: self.roughness,
            n1,
            n2,
            fresnel: self.fresnel,
            constant_reflectance: self.constant_reflectance,
        };
        let frame = Frame::at(hit);
        let v = frame.local(-hit.dir);
        let m = frame.world(sample_visible_normal(v, facets.alpha, u.next_2d()));
        let c = facets.children(hit.dir, m, &frame, hit.n_geom);
        let lobe = |side, child: Option<(Vec3, f32)>| {
            child.map(|(dir, weight)| Lobe {
                side,
                kind: LobeKind::Microfacet(facets),
                dir,
                weight: crate::math::Color::splat(weight),
            })
        };
        Scatter {
            lobes: [
                lobe(Side::Reflect, c.reflected),
                lobe(Side::Transmit, c.refracted),
            ],
            interface: Some(Interface {
                cos_i: c.cos_m,
                n1,
                n2,
                r: c.r,
            }),
            total_internal_reflection: c.total,
            facets: Some(facets),
            ..Scatter::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::test_util::{Fixed, hit_at};
    use crate::material::{Material, Part};
    use glam::Vec2;

    fn frosted(alpha: f32) -> Dielectric {
        Dielectric {
            roughness: alpha,
            ..Dielectric::clear(1.5)
        }
    }

    /// A hit at `theta` degrees, entering the glass or leaving it (from inside, the
    /// normal facing the ray as the tracer gives it).
    fn hit(theta: f32, entering: bool) -> Interaction {
        Interaction {
            entering,
            ..hit_at(theta)
        }
    }

    /// The lobes a hit gets with the facet drawn from `u`.
    fn lobes(d: &Dielectric, at: &Interaction, u: Vec2) -> Scatter {
        d.rough_scatter(at, &mut Fixed(vec![u.x, u.y]))
    }

    /// E[W_r + W_t] over facets drawn at the points of a `k` × `k` grid (stratified, so
    /// close to the integral), each lobe's share apart: (reflected, refracted).
    fn sampled_albedo(d: &Dielectric, at: &Interaction, k: u32) -> (f64, f64) {
        let (mut r, mut t) = (0.0, 0.0);
        for i in 0..k {
            for j in 0..k {
                let u = Vec2::new((i as f32 + 0.5) / k as f32, (j as f32 + 0.5) / k as f32);
                for lobe in lobes(d, at, u).lobes() {
                    match lobe.side {
                        Side::Reflect => r += lobe.weight.x as f64,
                        Side::Transmit => t += lobe.weight.x as f64,
                    }
                }
            }
        }
        let n = (k * k) as f64;
        (r / n, t / n)
    }

    /// ∫ f(dir) dω over the whole sphere by the midpoint rule in (cos θ, φ) about +Z, `n`
    /// rows of cos θ: each side of the surface (+Y) separately, (upper, lower). The pole
    /// lies in the surface, where no lobe peaks: the rows are finest along its equator.
    fn sphere(f: impl Fn(Vec3) -> f64, n: usize) -> (f64, f64) {
        let (mut upper, mut lower) = (0.0, 0.0);
        let cell = 2.0 * std::f64::consts::PI * 2.0 / (n * 2 * n) as f64;
        for i in 0..n {
            let z = -1.0 + 2.0 * (i as f64 + 0.5) / n as f64;
            let s = (1.0 - z * z).sqrt();
            for j in 0..2 * n {
                let phi = std::f64::consts::PI * (j as f64 + 0.5) / n as f64;
                let d = Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, z as f32);
                let v = f(d) * cell;
                if d.y > 0.0 { upper += v } else { lower += v }
            }
        }
        (upper, lower)
    }

    /// The facets a hit's lobes are evaluated with.
    fn facets(d: &Dielectric, at: &Interaction) -> Microfacet {
        match lobes(d, at, Vec2::splat(0.5))
            .lobes()
            .next()
            .map(|l| l.kind)
        {
            Some(LobeKind::Microfacet(f)) => f,
            other => panic!("a rough lobe, not {other:?}"),
        }
    }

    #[test]
    fn the_jittered_rays_carry_what_the_lobes_pass_and_no_more() {
        // The white furnace, one bounce: what a hit's two children carry on average (their
        // weights, over facets drawn) is the integral of f cos θ of the two lobes over
        // every direction (quadrature, apart from the sampling code), to 1e-3; no energy is
        // created (at most 1), and what is lost is what single scattering loses: little at
        // low roughness, more at grazing angles and high roughness.
        for alpha in [0.1f32, 0.3, 0.7] {
            for (theta, entering) in [(0.0, true), (45.0, true), (80.0, true), (30.0, false)] {
                let d = frosted(alpha);
                let at = hit(theta, entering);
                let (r, t) = sampled_albedo(&d, &at, 400);
                let mf = facets(&d, &at);
                let f = |side| move |o: Vec3| mf.eval(&at, side, o).0 as f64;
                let (r_up, r_down) = sphere(f(Side::Reflect), 1500);
                let (t_up, t_down) = sphere(f(Side::Transmit), 1500);
                assert_eq!((r_down, t_up), (0.0, 0.0), "each lobe on its own side");
                let case = format!("α {alpha}, θ {theta}, entering {entering}");
                assert!(
                    (r - r_up).abs() < 1e-3,
                    "{case}: reflected {r} against {r_up}"
                );
                assert!(
                    (t - t_down).abs() < 1e-3,
                    "{case}: refracted {t} against {t_down}"
                );
                assert!(r + t <= 1.0 + 1e-6, "{case}: {}", r + t);
                if alpha <= 0.1 && entering && theta < 60.0 {
                    assert!(r + t > 0.99, "{case}: {}", r + t);
                }
            }
        }
    }

    #[test]
    fn each_lobe_draws_its_directions_with_the_density_it_reports() {
        // ∫ pdf dω over a lobe's side is the share of facets drawn that give it a ray (each
        // lobe is drawn at every hit, and is masked where its ray would leave on the wrong
        // side), both to 1e-3.
        for (alpha, theta) in [(0.2f32, 20.0), (0.5, 70.0)] {
            let d = frosted(alpha);
            let at = hit(theta, true);
            let mf = facets(&d, &at);
            let k = 300;
            let (mut reflected, mut refracted) = (0u32, 0u32);
            for i in 0..k {
                for j in 0..k {
                    let u = Vec2::new((i as f32 + 0.5) / k as f32, (j as f32 + 0.5) / k as f32);
                    for lobe in lobes(&d, &at, u).lobes() {
                        match lobe.side {
                            Side::Reflect => reflected += 1,
                            Side::Transmit => refracted += 1,
                        }
                    }
                }
            }
            let share = |c: u32| c as f64 / (k * k) as f64;
            let pdf = |side| move |o: Vec3| mf.eval(&at, side, o).1 as f64;
            let (r, _) = sphere(pdf(Side::Reflect), 1500);
            let (_, t) = sphere(pdf(Side::Transmit), 1500);
            assert!((r - share(reflected)).abs() < 1e-3, "α {alpha}: {r}");
            assert!((t - share(refracted)).abs() < 1e-3, "α {alpha}: {t}");
        }
    }

    #[test]
    fn a_paths_density_integrates_to_the_chance_that_it_goes_on() {
        // A path follows one child in proportion to its weight: the density with which it
        // draws a direction (`eval_path`), over every direction, is the share of facets
        // drawn that leave it a child; and what the interface passes whole is what the
        // two lobes pass, to 1e-3.
        for (alpha, theta, entering) in [(0.3f32, 35.0, true), (0.6, 25.0, false)] {
            let d = frosted(alpha);
            let at = hit(theta, entering);
            let mf = facets(&d, &at);
            let k = 300;
            let mut going_on = 0;
            for i in 0..k {
                for j in 0..k {
                    let u = Vec2::new((i as f32 + 0.5) / k as f32, (j as f32 + 0.5) / k as f32);
                    going_on += (lobes(&d, &at, u).lobes().count() > 0) as u32;
                }
            }
            let share = going_on as f64 / (k * k) as f64;
            let (up, down) = sphere(|o| mf.eval_path(&at, o).1 as f64, 1500);
            assert!(
                (up + down - share).abs() < 1e-3,
                "α {alpha}: {} against {share}",
                up + down
            );
            let (r, t) = sampled_albedo(&d, &at, 300);
            let (up, down) = sphere(|o| mf.eval_path(&at, o).0 as f64, 1500);
            assert!(
                (up + down - (r + t)).abs() < 1e-3,
                "α {alpha}: {} against {}",
                up + down,
                r + t
            );
        }
    }

    #[test]
    fn the_lobes_are_reciprocal() {
        // Reflection: f(i → o) = f(o → i). Refraction (Walter's generalized reciprocity):
        // f(i → o) / n_o² = f(o → i) / n_i², the index on each one's side.
        let d = frosted(0.35);
        let f = |from: Vec3, to: Vec3, entering: bool, side| {
            // `from` towards the viewer, the normal +Y on its side.
            let at = Interaction {
                dir: -from,
                n_geom: Vec3::Y * from.y.signum(),
                n_shade: Vec3::Y * from.y.signum(),
                entering,
                ..hit_at(0.0)
            };
            let mf = facets(&d, &at);
            let (f_cos, _) = mf.eval(&at, side, to);
            f_cos / to.y.abs()
        };
        let i = Vec3::new(0.4, 0.8, 0.2).normalize();
        for o in [Vec3::new(-0.3, 0.9, 0.1), Vec3::new(0.5, 0.3, -0.6)] {
            let o = o.normalize();
            let (a, b) = (f(i, o, true, Side::Reflect), f(o, i, true, Side::Reflect));
            assert!(a > 0.0 && (a / b - 1.0).abs() < 1e-4, "{a} {b}");
        }
        for o in [Vec3::new(-0.2, -0.9, 0.1), Vec3::new(-0.6, -0.5, 0.3)] {
            let o = o.normalize();
            // i outside (air, 1), o inside (glass, 1.5).
            let forward = f(i, o, true, Side::Transmit) / (1.5f32 * 1.5);
            let back = f(o, i, false, Side::Transmit) / 1.0;
            assert!(
                forward > 0.0 && (forward / back - 1.0).abs() < 1e-4,
                "{forward} {back}"
            );
        }
    }

    #[test]
    fn a_nearly_smooth_interface_splits_as_the_smooth_one() {
        let smooth = Dielectric::clear(1.5);
        for (theta, entering) in [(30.0, true), (60.0, false), (20.0, false)] {
            let at = hit(theta, entering);
            let a = lobes(&frosted(1e-4), &at, Vec2::new(0.37, 0.81));
            let b = smooth.scatter(&at);
            assert_eq!(a.total_internal_reflection, b.total_internal_reflection);
            for (x, y) in a.lobes().zip(b.lobes()) {
                assert_eq!(x.side, y.side);
                assert!((x.dir - y.dir).length() < 1e-3, "{theta}");
                assert!((x.weight - y.weight).abs().max_element() < 1e-3, "{theta}");
            }
            assert_eq!(a.lobes().count(), b.lobes().count());
        }
        // Roughness 0 is the smooth material, drawing nothing.
        let glass = Material::Dielectric(frosted(0.0));
        let mut none = Fixed(vec![]);
        assert_eq!(
            glass.scatter(&hit_at(30.0), &mut none),
            smooth.scatter(&hit_at(30.0))
        );
    }

    #[test]
    fn each_childs_weight_is_what_its_lobe_passes_over_its_density_there() {
        // What path tracing weighs its light samples by: f cos θ and the density at the
        // child's own direction, whose ratio is the weight the child carries.
        for (theta, entering) in [(40.0, true), (20.0, false)] {
            let at = hit(theta, entering);
            let s = lobes(&frosted(0.3), &at, Vec2::new(0.3, 0.6));
            assert_eq!(s.lobes().count(), 2, "both children");
            for lobe in s.lobes() {
                let (f_cos, pdf) = Part::Lobe(lobe).eval(&at, lobe.dir);
                assert!(pdf > 0.0 && (f_cos.x / pdf - lobe.weight.x).abs() < 1e-4);
                assert_eq!(lobe.pdf(&at, lobe.dir), Some(pdf));
            }
        }
    }
}
