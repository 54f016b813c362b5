//! The tracer's side of polarisation: how a camera's analyzer follows a child ray through
//! an interface, and how unpolarised light at the end of a branch is seen through it.
//!
//! The tree walk is generic over [`Polarization`]: without a polariser it runs with
//! [`Unpolarized`], which compiles to nothing (as fast as before polarisation existed);
//! with one, with an [`Analyzer`].

use crate::material::{Interaction, Lobe, Material, Side};
use crate::math::{Color, Vec3};
use crate::optics::polarization::{Analyzer, Mueller};

/// What a branch carries of the camera's polariser.
pub(super) trait Polarization: Sized {
    /// How unpolarised radiance `c` arriving along the branch is seen.
    fn seen(&self, c: Color) -> Color;
    /// This branch meeting a surface of normal `n` (facing the ray) along `dir`: itself in
    /// the interface's s/p frame.
    fn at_interface(&self, dir: Vec3, n: Vec3) -> Self;
    /// The child ray `lobe` of `material` at `at`, from the branch at the interface.
    fn child(&self, material: &Material, at: &Interaction, lobe: &Lobe) -> Self;
    /// How the light `lit` a material's direct shading sends back is seen, from the branch
    /// at the interface: unpolarised off a diffuse surface, polarised coming out through a
    /// glaze.
    fn direct(&self, material: &Material, at: &Interaction, lit: Color) -> Color;
    /// For the inspector: the weights per Stokes component, green channel.
    fn weights(&self) -> Option<[f32; 4]>;
}

/// No polariser: radiance is seen as it is.
#[derive(Clone, Copy)]
pub(super) struct Unpolarized;

impl Polarization for Unpolarized {
    #[inline(always)]
    fn seen(&self, c: Color) -> Color {
        c
    }
    #[inline(always)]
    fn at_interface(&self, _: Vec3, _: Vec3) -> Self {
        Unpolarized
    }
    #[inline(always)]
    fn child(&self, _: &Material, _: &Interaction, _: &Lobe) -> Self {
        Unpolarized
    }
    #[inline(always)]
    fn direct(&self, _: &Material, _: &Interaction, lit: Color) -> Color {
        lit
    }
    fn weights(&self) -> Option<[f32; 4]> {
        None
    }
}

impl Polarization for Analyzer {
    fn seen(&self, c: Color) -> Color {
        c * self.unpolarized()
    }

    /// In the s/p frame: x = s, perpendicular to the plane of incidence. Head-on, where
    /// every s will do, it keeps its own.
    fn at_interface(&self, dir: Vec3, n: Vec3) -> Self {
        let s = dir.cross(n);
        let len = s.length();
        if len > 1e-6 {
            self.in_frame(dir, s / len)
        } else {
            *self
        }
    }

    /// Through the lobe's Mueller matrix (a lobe the material does not polarise passes as
    /// it is), its x axis kept perpendicular to the child's direction.
    fn child(&self, material: &Material, at: &Interaction, lobe: &Lobe) -> Self {
        // A rough interface's child: in its facet's s/p frame.
        let a = match material.facet_mueller(at, lobe) {
            Some((facet, m)) => self.at_interface(at.dir, facet).through(&m),
            None => self.through(
                &material
                    .mueller(at, Some(lobe), lobe.side)
                    .unwrap_or_else(|| Mueller::neutral_transmission(lobe.weight)),
            ),
        };
        // A jittered glossy ray leaves the plane of incidence a little: square s up to it.
        let x = a.x - a.x.dot(lobe.dir) * lobe.dir;
        let len = x.length();
        Analyzer {
            x: if len > 1e-6 { x / len } else { a.x },
            ..a
        }
    }

    fn direct(&self, material: &Material, at: &Interaction, lit: Color) -> Color {
        match material.mueller(at, None, Side::Transmit) {
            Some(coat) => lit * self.through(&coat).unpolarized(),
            None => lit * self.unpolarized(),
        }
    }

    fn weights(&self) -> Option<[f32; 4]> {
        Some(self.w.map(|c| c.y))
    }
}
