//! The real lens in whole renders: the waves trace its rays as the recursion does, bit for
//! bit; focused where the thin lens is, it makes the thin lens's picture in the band that
//! is in focus; out of focus it does not.
#![allow(clippy::unwrap_used)]

mod common;
#[path = "common/mutate.rs"]
mod mutate;

use glam::Vec2;
use raylab::math::Color;
use raylab::math::lanes::Width;
use raylab::optics::lens::{Paraxial, Prescription, RealLens};
use raylab::params::{LensDispersion, LensModel, Params, TreeMode};
use raylab::render::Film;
use raylab::scene::Scene;
use raylab::tracer::{Traversal, pick};

#[test]
fn every_width_traces_every_design_as_the_recursion_does() {
    let scene = Scene::load("depth-of-field").unwrap();
    let designs = LensModel::DESIGNS.map(|lens| (lens, LensDispersion::Off, TreeMode::Split));
    // And through the singlet's dispersing glass: three camera rays a sample in the split
    // tree, one at a wavelength of its own in the stochastic tree.
    let dispersed = [TreeMode::Split, TreeMode::Stochastic]
        .map(|tree| (LensModel::Singlet50, LensDispersion::On, tree));
    for (lens, lens_dispersion, tree) in designs.into_iter().chain(dispersed) {
        let params = Params {
            spp: 4,
            lens,
            lens_dispersion,
            tree,
            ..scene.params.clone()
        };
        let reference = common::render_by(Traversal::Recursive, &scene, &params, (40, 30));
        // The lens blocks some rays (black) and lets most through.
        let lit = reference.pixels().filter(|p| p.max_element() > 0.0).count();
        assert!(lit > 40 * 30 / 3, "{lens:?}: {lit} pixels lit");
        for w in Width::ALL.into_iter().filter(|w| w.runs_here()) {
            let film = common::render_by(Traversal::Waves(w), &scene, &params, (40, 30));
            assert_eq!(
                common::bits(&film),
                common::bits(&reference),
                "{lens:?} {lens_dispersion:?} {tree:?}: {w:?} lanes"
            );
            assert_eq!(film.cost(), reference.cost(), "{lens:?}: {w:?}: rays");
        }
    }
}

/// The depth-of-field scene through `lens` at radius `aperture`, focused at `focus`,
/// with `seed`.
fn dof(lens: LensModel, aperture: f32, focus: f32, seed: u64) -> Film {
    let scene = Scene::load("depth-of-field").unwrap();
    let params = Params {
        spp: 64,
        lens,
        aperture,
        focus_distance: Some(focus),
        seed,
        ..scene.params.clone()
    };
    common::render_by(Traversal::Recursive, &scene, &params, SIZE)
}

const SIZE: (u32, u32) = (384, 216);

/// The band of the floor in focus: the pixels near the middle of the picture (within a
/// quarter of its half-diagonal, where the double Gauss's distortion moves the image by
/// under a tenth of a pixel) whose pinhole ray meets the floor within 4 % of the focus
/// distance. (The spheres' highlights are left out: where a highlight is depends on
/// where it is seen from, and the real lens sees from its entrance pupil, centimetres
/// from the thin lens's centre.)
fn in_focus_band(focus: f32) -> Vec<usize> {
    let scene = Scene::load("depth-of-field").unwrap();
    let aspect = SIZE.0 as f32 / SIZE.1 as f32;
    let hit = |film: Vec2| pick(&scene, &scene.camera, aspect, film);
    // The middle of the picture's bottom edge is the floor.
    let floor = hit(Vec2::new(0.5, 0.99)).unwrap().object;
    let mut band = Vec::new();
    for y in 0..SIZE.1 {
        for x in 0..SIZE.0 {
            let film = Vec2::new(
                (x as f32 + 0.5) / SIZE.0 as f32,
                (y as f32 + 0.5) / SIZE.1 as f32,
            );
            let off = (film - Vec2::splat(0.5)) * Vec2::new(aspect, 1.0);
            let near_middle = off.length() < Vec2::new(aspect, 1.0).length() / 8.0;
            let sharp = hit(film)
                .is_some_and(|p| p.object == floor && (p.depth / focus - 1.0).abs() < 0.04);
            if near_middle && sharp {
                band.push((y * SIZE.0 + x) as usize);
            }
        }
    }
    band
}

/// The root mean square over `band` of the difference of `a` and `b`'s luminance.
fn rms_difference(a: &Film, b: &Film, band: &[usize]) -> f32 {
    let luminance = |c: Color| c.dot(Color::new(0.2126, 0.7152, 0.0722));
    let (a, b): (Vec<Color>, Vec<Color>) = (a.pixels().collect(), b.pixels().collect());
    let sum: f32 = band
        .iter()
        .map(|&i| (luminance(a[i]) - luminance(b[i])).powi(2))
        .sum();
    (sum / band.len() as f32).sqrt()
}

#[test]
fn focused_alike_the_real_and_thin_lens_agree_in_the_band_in_focus() {
    // The double Gauss at f/4 (a 6.25 mm pupil radius: wide open at f/2 its front and
    // rear elements cut the pupil off the axis, vignetting the band) and a thin lens of
    // the same radius, both focused on the third sphere.
    let (focus, aperture) = (6.0, 0.00625);
    let band = in_focus_band(focus);
    assert!(band.len() > 200, "{} pixels in focus", band.len());
    let (thin, real) = (LensModel::Thin, LensModel::DoubleGauss50);
    let agree = rms_difference(
        &dof(thin, aperture, focus, 0),
        &dof(real, aperture, focus, 0),
        &band,
    );
    // Two images of one lens with other seeds differ by their noise alone, √2 σ; a thin
    // and a real one by √(σ_thin² + σ_real²) where they agree (the real lens adds noise:
    // some of its rays are blocked in the pupil's bounds), and by what its distortion
    // moves: the checker's edges, by under a tenth of a pixel here (0.2 % barrel distortion 30
    // pixels from the middle), a pixel on an edge of contrast 0.7 by under 0.07, an rms
    // over the band of 0.01.
    let noise = |lens| {
        let a = dof(lens, aperture, focus, 0);
        rms_difference(&a, &dof(lens, aperture, focus, 1), &band)
    };
    let (thin_noise, real_noise) = (noise(thin), noise(real));
    let expected = ((thin_noise.powi(2) + real_noise.powi(2)) / 2.0).sqrt();
    let tolerance = 1.2 * expected.hypot(0.01);
    assert!(
        agree < tolerance,
        "real against thin {agree}, noise {thin_noise} thin, {real_noise} real"
    );
    // Focused at 1 m, the band blurs (by 62 mm at 6 m, over three pixels) and the test
    // sees it.
    let blurred = rms_difference(
        &dof(thin, aperture, focus, 0),
        &dof(real, aperture, 1.0, 0),
        &band,
    );
    assert!(
        blurred > 2.0 * tolerance,
        "misfocused {blurred}, {tolerance}"
    );
}

#[test]
fn lens_prints_the_paraxial_description_of_a_design_or_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = |args: &[&str]| {
        let o = common::raylab(args, d);
        assert!(o.status.success(), "{}", common::stderr(&o));
        String::from_utf8(o.stdout).unwrap()
    };
    // Every built-in design, the double Gauss at its published 50 mm and f/2.
    let all = out(&["lens"]);
    for name in ["double-gauss-50", "wide-22", "telephoto-250", "singlet-50"] {
        assert!(all.contains(&format!("{name} (built in)")), "{all}");
    }
    let dgauss = out(&["lens", "double-gauss-50"]);
    assert!(
        dgauss.contains("effective focal length  49.999 mm"),
        "{dgauss}"
    );
    assert!(dgauss.contains("f/2.03"), "{dgauss}");
    // A biconvex lens in air, R = ±100 mm, 10 mm of n = 1.5, stop at its front: the thick
    // lensmaker's equation 1/f = (n − 1)(2/R − (n − 1) d / (n R²)) gives f = 101.695 mm,
    // its back focal length f (1 − (n − 1) d / (n R)) = 98.305 mm; a 20 mm stop in air is
    // its own entrance pupil (f/5.08); on 24 mm film height it sees 2 atan(12 / f).
    std::fs::write(
        d.join("biconvex.lens"),
        "# a test lens\n0 0 0 20\n100 10 1.5 40\n-100 0 1 40\n",
    )
    .unwrap();
    let file = out(&["lens", "biconvex.lens"]);
    for expected in [
        "biconvex.lens (file): 1 element, 3 surfaces, the stop at surface 1",
        "effective focal length  101.695 mm",
        "back focal length       98.305 mm",
        "entrance pupil          20.000 mm",
        "f-number                f/5.08",
        "× 13.5°",
        "no Abbe numbers",
    ] {
        assert!(
            file.contains(expected),
            "`{expected}` missing from:\n{file}"
        );
    }
    // Bad input: one line, with the file, line and column.
    std::fs::write(d.join("bad.lens"), "0 0 0 20\n100 10 1.5 4O\n").unwrap();
    let err = common::fails(
        &["lens", "bad.lens"],
        d,
        "bad.lens:2:12: `4O` is not a number",
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    common::fails(&["lens", "no-such.lens"], d, "neither a built-in design");
    std::fs::write(d.join("flat.lens"), "0 0 0 20\n0 10 1.5 40\n0 0 1 40\n").unwrap();
    common::fails(&["lens", "flat.lens"], d, "flat.lens: no paraxial focus");
}

#[test]
fn mutated_prescriptions_are_read_or_refused_at_a_line_and_column() {
    // The shipped designs, mutated as the fuzzers mutate scene files: each is read, or
    // refused with its file, line and column; a lens read is described, and the first
    // few with a focus are laid out and traced, without a panic.
    let designs: Vec<(&str, &str)> = LensModel::DESIGNS
        .iter()
        .filter_map(|m| m.table())
        .collect();
    let mut rng = common::Rng(56);
    let (mut read, mut refused, mut traced) = (0, 0, 0);
    for case in 0..2000 {
        let (name, text) = designs[rng.below(designs.len())];
        let text = mutate::mutate(text, &mut rng);
        match Prescription::parse(&text, name) {
            Ok(lens) => {
                read += 1;
                assert!(lens.surfaces.len() <= 64, "case {case}");
                let Some(p) = Paraxial::of(&lens) else {
                    continue;
                };
                assert!(p.efl.is_finite() && p.efl != 0.0, "case {case}: {p:?}");
                if traced < 30 {
                    traced += 1;
                    if let Some(camera) = RealLens::new(&lens, 2000.0, 10.0, 40.0, 1.5, false) {
                        for u in [0.1, 0.5, 0.9] {
                            let ray = camera.ray(Vec2::splat(u), Vec2::splat(u), None);
                            assert!(
                                ray.is_none_or(|r| r.dir.is_finite() && r.weight >= 0.0),
                                "case {case}: {ray:?}"
                            );
                        }
                    }
                }
            }
            Err(e) => {
                refused += 1;
                let message = e.to_string();
                let lines = text.lines().count().max(1);
                assert!(
                    message.starts_with(&format!("{name}:")) && e.line <= lines + 1,
                    "case {case}: {message}"
                );
                assert_eq!(message.lines().count(), 1, "case {case}: {message}");
            }
        }
    }
    assert!(
        read > 100 && refused > 100,
        "{read} read, {refused} refused"
    );
}

/// A small white sphere 2 m away, off the axis to the right, on black, through the singlet
/// focused on it: the scene of [`lateral_colour_of_a_singlet`].
fn white_point(dispersion: &str) -> (Scene, Params) {
    let text = format!(
        "[image]\nwidth = {W}\nheight = {H}\n\
         [params]\nlens = \"singlet-50\"\nlens_dispersion = \"{dispersion}\"\n\
         aperture = {APERTURE}\nfocus_distance = 2\nspp = 64\n\
         [camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -2]\nfov = {FOV}\n\
         [background]\ncolor = [0, 0, 0]\n\
         [material.white]\ntype = \"emissive\"\ncolor = [1, 1, 1]\n\
         [[sphere]]\ncenter = [{X}, 0, -2]\nradius = 0.004\nmaterial = \"white\"\n"
    );
    let scene = Scene::from_toml_str(&text, "white-point.toml", std::path::Path::new(".")).unwrap();
    let params = scene.params.clone();
    (scene, params)
}

const W: u32 = 480;
const H: u32 = 320;
const FOV: f32 = 27.0;
/// The sphere's distance right of the axis at 2 m: 80 % of the half-width.
const X: f32 = 0.8 * 2.0 * 1.5 * 0.240_079; // tan 13.5°
/// The entrance pupil's radius (m): the singlet at about f/8.
const APERTURE: f32 = 0.003;

/// Channel `c`'s centroid across the image, in pixels, within 20 pixels of the sphere.
fn centroid_x(film: &Film, c: usize) -> f32 {
    let (mut sum, mut weight) = (0.0f64, 0.0f64);
    let centre = ((0.5 + 0.4) * W as f32) as usize;
    for (i, p) in film.pixels().enumerate() {
        let (x, y) = (i % W as usize, i / W as usize);
        if x.abs_diff(centre) < 20 && y.abs_diff(H as usize / 2) < 20 {
            sum += f64::from(p[c]) * (x as f64 + 0.5);
            weight += f64::from(p[c]);
        }
    }
    assert!(weight > 0.0, "channel {c} sees nothing");
    (sum / weight) as f32
}

/// Where, across the image (pixels), the singlet images the sphere's centre at
/// `wavelength`, traced through the prescription rather than rendered: for each point of
/// a grid over the pupil, the film point whose ray through it meets the sphere's centre,
/// averaged (as a small blur spot's centroid averages over the pupil).
fn traced_image_x(wavelength: f32) -> f32 {
    let prescription = LensModel::Singlet50.prescription().unwrap();
    let (w, h) = (W as f32, H as f32);
    let lens = RealLens::new(&prescription, 2000.0, 2000.0 * APERTURE, FOV, w / h, true).unwrap();
    // Across the sphere's plane, minus the sphere's centre: the miss of the ray from film
    // point `film_x` through pupil point `u` (None where the lens blocks it).
    let miss = |film_x: f32, u: Vec2| {
        let r = lens.ray(Vec2::new(film_x, 0.5), u, Some(wavelength))?;
        Some(r.origin.x + r.dir.x * (2000.0 - r.origin.z) / r.dir.z - X * 1000.0)
    };
    let n = 16;
    let (mut sum, mut count) = (0.0, 0);
    for i in 0..n * n {
        let u = Vec2::new((i % n) as f32 + 0.5, (i / n) as f32 + 0.5) / n as f32;
        let (mut lo, mut hi) = (0.8f32, 1.0f32);
        let (Some(a), Some(b)) = (miss(lo, u), miss(hi, u)) else {
            continue;
        };
        if a.signum() == b.signum() {
            continue;
        }
        for _ in 0..30 {
            let mid = 0.5 * (lo + hi);
            match miss(mid, u) {
                Some(m) if m.signum() == a.signum() => lo = mid,
                Some(_) => hi = mid,
                None => break,
            }
        }
        sum += 0.5 * (lo + hi);
        count += 1;
    }
    assert!(count > n * n / 2, "{count} pupil points image the sphere");
    sum / count as f32 * w
}

#[test]
fn lateral_colour_of_a_singlet() {
    // Through the singlet of N-BK7 (V_d = 64.2) with its glass dispersing, blue is bent
    // more than red, so the sphere's blue image lies nearer the middle than its red one
    // by what tracing the two wavelengths through the prescription predicts; with the
    // glass at n_d every channel images it in one place.
    let render = |dispersion| {
        let (scene, params) = white_point(dispersion);
        common::render_by(Traversal::Recursive, &scene, &params, (W, H))
    };
    let on = render("on");
    let (red, blue) = (centroid_x(&on, 0), centroid_x(&on, 2));
    let mid = |c| raylab::optics::dispersion::wavelength_in(c, 0.5);
    let predicted = traced_image_x(mid(0)) - traced_image_x(mid(2));
    assert!(predicted > 0.5, "predicted {predicted} px");
    let measured = red - blue;
    assert!(
        (measured - predicted).abs() < 0.1 * predicted,
        "red {red} px, blue {blue} px: {measured} apart, predicted {predicted}"
    );
    let off = render("off");
    let apart = centroid_x(&off, 0) - centroid_x(&off, 2);
    assert!(apart.abs() < 0.01, "without dispersion {apart} px apart");
}

#[test]
fn inspect_says_when_the_lens_blocks_a_sample_and_lists_each_wavelengths_ray() {
    let dir = tempfile::tempdir().unwrap();
    let inspect = |args: &[&str]| {
        let o = common::raylab(&[&["inspect", "real-lens"], args].concat(), dir.path());
        assert!(o.status.success(), "{}", common::stderr(&o));
        String::from_utf8(o.stdout).unwrap()
    };
    // The corner's fifth sample falls outside the pupil (the double Gauss wide open).
    let blocked = inspect(&["--pixel", "0,0", "--sample", "4"]);
    assert!(blocked.contains("0 rays"), "{blocked}");
    assert!(
        blocked.contains("The lens blocks this sample's ray"),
        "{blocked}"
    );
    // Through the dispersing singlet, one camera ray per colour channel's wavelength.
    let split = inspect(&[
        "--pixel",
        "147,545",
        "--set",
        "lens=singlet-50",
        "--set",
        "lens_dispersion=on",
    ]);
    let cameras: Vec<&str> = split
        .lines()
        .filter(|l| l.starts_with("Camera ray at"))
        .collect();
    assert_eq!(cameras.len(), 3, "{split}");
}
