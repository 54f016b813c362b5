//! Dispersion in images: a dispersive clear sphere keeps a white furnace white, and a
//! prism spreads a white slit where Snell's law with Cauchy's n(λ) puts each wavelength.
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

use raylab::camera::Camera;
use raylab::geometry::{Shape, Sphere};
use raylab::light::Background;
use raylab::material::{Dielectric, Material};
use raylab::math::rng::Pattern;
use raylab::math::{Color, Vec3};
use raylab::optics::dispersion::{channel, ior_at};
use raylab::params::{MAX_DEPTH, Params, TreeMode};
use raylab::render::{Film, render};
use raylab::scene::{Scene, SceneDesc};

#[test]
fn white_furnace_a_dispersive_clear_sphere_in_a_uniform_environment_vanishes() {
    let camera = Camera::looking_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y, 32.0);
    let mut desc = SceneDesc::empty(camera);
    let flint = Dielectric {
        abbe: 20.0,
        ..Dielectric::clear(1.62)
    };
    desc.add(
        "sphere",
        Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0)),
        Material::Dielectric(flint),
    );
    desc.background = Background::Constant(Color::ONE);
    let scene = desc.build();
    // The ray tree splits into three wavelengths at the first hit, one per channel: one
    // sample already brings back white.
    let split = Params {
        spp: 1,
        max_depth: MAX_DEPTH,
        min_weight: 0.0,
        ..Params::default()
    };
    let (film, _) = render(&scene, &split, 8, 8, &()).unwrap();
    let centre = film.pixel(4, 4);
    assert!((centre - Color::ONE).abs().max_element() < 1e-3, "{centre}");
    // One path (stochastic tree) carries one wavelength from its first hit on: one
    // channel, times 3.
    let one = Params {
        tree: TreeMode::Stochastic,
        ..split
    };
    let (film, _) = render(&scene, &one, 8, 8, &()).unwrap();
    let centre = film.pixel(4, 4);
    let lit: Vec<f32> = centre.to_array().into_iter().filter(|&c| c > 0.0).collect();
    assert_eq!(lit.len(), 1, "one channel per sample: {centre}");
    assert!((lit[0] - 3.0).abs() < 1e-3, "{centre}");
    // Each sample keeps its energy, only its colour is chosen: every pixel's mean over the
    // channels is 1. Over 4096 samples the wavelengths (one Sobol dimension, stratified)
    // fall a third in each channel's box to within a sample where every sample meets the
    // sphere: each channel within 3/4096 of 1 there, and in the image's mean. (At the rim,
    // where some samples miss, a pixel's colour keeps some noise.)
    let many = Params { spp: 4096, ..one };
    let (film, _) = render(&scene, &many, 8, 8, &()).unwrap();
    for (i, c) in film.pixels().enumerate() {
        let energy = c.element_sum() / 3.0;
        assert!((energy - 1.0).abs() < 1e-3, "pixel {i}: {c}");
    }
    for (x, y) in [(3, 3), (3, 4), (4, 3), (4, 4)] {
        let c = film.pixel(x, y);
        assert!(
            (c - Color::ONE).abs().max_element() < 1e-3,
            "pixel ({x}, {y}): {c}"
        );
    }
    let mean = film.pixels().fold(Color::ZERO, |a, b| a + b) / 64.0;
    assert!(
        (mean - Color::ONE).abs().max_element() < 1e-3,
        "mean {mean}"
    );
}

/// A vertical equilateral prism, 4 on a side, its centroid at (0, y, -5), turned 33.2°
/// about y so that a ray along -z meets its first face at 63.2° (minimum deviation for
/// n_d 1.785): the triangle's corners in the xz plane, apex first.
fn prism_corners() -> [[f64; 2]; 3] {
    let (s, c) = 33.2f64.to_radians().sin_cos();
    let r = 4.0 / 3f64.sqrt();
    [[r, 0.0], [-r / 2.0, 2.0], [-r / 2.0, -2.0]]
        .map(|[x, z]| [x * c + z * s, -x * s + z * c - 5.0])
}

/// The 2D ray from the origin at `angle` (radians from -z towards +x) through the prism's
/// face from corner 0 to 1 and out of the face from corner 2 to 0, by Snell's law in vector
/// form with index `n`: the exit point and direction, or None if it misses or reflects.
fn through_prism(angle: f64, n: f64) -> Option<([f64; 2], [f64; 2])> {
    let p = prism_corners();
    let sub = |a: [f64; 2], b: [f64; 2]| [a[0] - b[0], a[1] - b[1]];
    let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
    // Where the ray o + t d crosses the segment a-b, and the segment's outward normal.
    let cross = |o: [f64; 2], d: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        let e = sub(b, a);
        let den = d[0] * e[1] - d[1] * e[0];
        let ao = sub(a, o);
        let t = (ao[0] * e[1] - ao[1] * e[0]) / den;
        let u = (ao[0] * d[1] - ao[1] * d[0]) / den;
        let centroid = [
            (p[0][0] + p[1][0] + p[2][0]) / 3.0,
            (p[0][1] + p[1][1] + p[2][1]) / 3.0,
        ];
        let mut normal = [e[1], -e[0]];
        if dot(normal, sub(a, centroid)) < 0.0 {
            normal = [-normal[0], -normal[1]];
        }
        let len = dot(normal, normal).sqrt();
        (
            (t > 0.0 && (0.0..=1.0).contains(&u)).then_some(t),
            [normal[0] / len, normal[1] / len],
        )
    };
    // Snell: t = η d + (η cos_i − cos_t) n̂, n̂ facing the incoming ray.
    let refract = |d: [f64; 2], nrm: [f64; 2], eta: f64| {
        let cos_i = -dot(d, nrm);
        let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
        (sin2_t <= 1.0).then(|| {
            let k = eta * cos_i - (1.0 - sin2_t).sqrt();
            [eta * d[0] + k * nrm[0], eta * d[1] + k * nrm[1]]
        })
    };
    let d = [angle.sin(), -angle.cos()];
    let (t, outward) = cross([0.0, 0.0], d, p[0], p[1]);
    let o = [t? * d[0], t? * d[1]];
    let inside = refract(d, outward, 1.0 / n)?;
    let (t, outward) = cross(o, inside, p[2], p[0]);
    let exit = [o[0] + t? * inside[0], o[1] + t? * inside[1]];
    let out = refract(inside, [-outward[0], -outward[1]], n)?;
    Some((exit, out))
}

/// A white slit 30 units beyond the prism, seen through it by a camera at the origin
/// looking down -z over a 400×2 image, 30° across.
struct SlitThroughPrism {
    ior: f32,
    abbe: f32,
    width: u32,
    height: u32,
    // tan of half the horizontal field of view.
    half_h: f64,
    centre: [f64; 2],
    // The exit direction of the ray at 10°, and across it (along the slit's width).
    dir: [f64; 2],
    across: [f64; 2],
    slit_width: f64,
    scene: Scene,
    _models: tempfile::TempDir,
}

impl SlitThroughPrism {
    fn new() -> Self {
        // A weakly dispersive glass of high index, so that the whole spectrum fits in the
        // prism's face as the camera sees it.
        let (ior, abbe) = (1.785f32, 90.0f32);
        let (width, height) = (400u32, 2u32);
        // 30° across the image; the vertical field of view follows from the aspect ratio.
        let half_h = 15f64.to_radians().tan();
        let fov = 2.0 * (half_h * height as f64 / width as f64).atan().to_degrees();
        // The slit: 30 units beyond the prism along the exit ray of a camera ray at 10° for
        // n_d, square to it, 0.25 wide (about half a degree seen through the prism).
        let (exit, dir) = through_prism(10f64.to_radians(), ior as f64).unwrap();
        let centre = [exit[0] + 30.0 * dir[0], exit[1] + 30.0 * dir[1]];
        let across = [-dir[1], dir[0]];
        let slit_width = 0.25;
        let corner = [
            centre[0] - across[0] * slit_width / 2.0,
            centre[1] - across[1] * slit_width / 2.0,
        ];
        let p = prism_corners();
        let models = tempfile::tempdir().unwrap();
        let mut obj = String::new();
        for y in [-3.0, 3.0] {
            for [x, z] in p {
                obj += &format!("v {x} {y} {z}\n");
            }
        }
        obj += "f 1 2 3\nf 4 6 5\nf 1 4 5 2\nf 2 5 6 3\nf 3 6 4 1\n";
        std::fs::write(models.path().join("prism.obj"), obj).unwrap();
        let text = format!(
            "[camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\nfov = {fov}\n\
             [background]\ncolor = [0, 0, 0]\n\
             [material.flint]\ntype = \"dielectric\"\nior = {ior}\nabbe = {abbe}\n\
             fresnel = \"constant\"\nconstant_reflectance = 0\n\
             [material.white]\ntype = \"emissive\"\ncolor = [1, 1, 1]\n\
             [[mesh]]\nfile = \"prism.obj\"\nmaterial = \"flint\"\n\
             [[quad]]\ncorner = [{}, -3, {}]\nedge_u = [{}, 0, {}]\nedge_v = [0, 6, 0]\nmaterial = \"white\"\n",
            corner[0],
            corner[1],
            across[0] * slit_width,
            across[1] * slit_width,
        );
        let scene = Scene::from_toml_str(&text, "prism.toml", models.path()).unwrap();
        SlitThroughPrism {
            ior,
            abbe,
            width,
            height,
            half_h,
            centre,
            dir,
            across,
            slit_width,
            scene,
            _models: models,
        }
    }

    /// The image at `spp` samples by the ray tree `tree`: only camera -> prism -> slit, no
    /// reflections (R = 0), nothing deeper than the exit.
    fn render(&self, spp: u32, tree: TreeMode) -> Film {
        self.render_with(spp, tree, Pattern::Sobol, 0)
    }

    /// [`SlitThroughPrism::render`] with the samples laid out by `pattern` under `seed`.
    fn render_with(&self, spp: u32, tree: TreeMode, pattern: Pattern, seed: u64) -> Film {
        let params = Params {
            spp,
            max_depth: 2,
            min_weight: 0.0,
            tree,
            pattern,
            seed,
            noise_target: None,
            ..Params::default()
        };
        render(&self.scene, &params, self.width, self.height, &())
            .unwrap()
            .0
    }

    /// The column (pixels from the left edge) of the centroid of `channel`.
    fn centroid(&self, film: &Film, channel: usize) -> f64 {
        let (mut sum, mut weight) = (0.0, 0.0);
        for y in 0..self.height {
            for x in 0..self.width {
                let v = film.pixel(x, y)[channel] as f64;
                sum += (x as f64 + 0.5) * v;
                weight += v;
            }
        }
        sum / weight
    }
}

#[test]
fn a_prism_spreads_a_white_slit_where_snells_law_puts_each_wavelength() {
    let setup = SlitThroughPrism::new();
    let SlitThroughPrism {
        ior,
        abbe,
        width,
        half_h,
        centre,
        dir,
        across,
        slit_width,
        ..
    } = setup;
    let film = setup.render(4096, TreeMode::Split);

    // The image column (0 at the left edge) of a camera ray at `angle`.
    let column = |angle: f64| width as f64 / 2.0 * (1.0 + angle.tan() / half_h);
    // Where on the slit (across it, from its centre) the ray at `angle` lands, at index n.
    let on_slit = |angle: f64, n: f64| {
        let (o, d) = through_prism(angle, n)?;
        let t = ((centre[0] - o[0]) * dir[0] + (centre[1] - o[1]) * dir[1])
            / (d[0] * dir[0] + d[1] * dir[1]);
        let hit = [o[0] + t * d[0] - centre[0], o[1] + t * d[1] - centre[1]];
        Some(hit[0] * across[0] + hit[1] * across[1])
    };
    // The camera angle whose ray lands at `s` across the slit, by bisection.
    let angle_for = |s: f64, n: f64| {
        let (mut lo, mut hi) = (3f64.to_radians(), 17f64.to_radians());
        let sign = |a: f64| on_slit(a, n).map(|v| v - s);
        let lo_sign = sign(lo).unwrap().signum();
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if sign(mid).unwrap().signum() == lo_sign {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    };
    // Predicted: each wavelength lights the columns between the two edges of the slit's
    // image at its index; the channel's centroid is their mean over its 100 nm box,
    // weighted by how many columns each wavelength covers.
    let predicted = |band: (f64, f64)| {
        let (mut sum, mut weight) = (0.0, 0.0);
        let steps = 400;
        for i in 0..steps {
            let lambda = band.0 + (band.1 - band.0) * (i as f64 + 0.5) / steps as f64;
            let n = ior_at(ior, abbe, lambda as f32) as f64;
            let a = column(angle_for(-slit_width / 2.0, n));
            let b = column(angle_for(slit_width / 2.0, n));
            sum += 0.5 * (a + b) * (b - a).abs();
            weight += (b - a).abs();
        }
        sum / weight
    };
    let measured = |channel: usize| setup.centroid(&film, channel);
    let deviation = |lambda: f32| {
        let (_, d) = through_prism(10f64.to_radians(), ior_at(ior, abbe, lambda) as f64).unwrap();
        let a = 10f64.to_radians();
        (d[0] * a.sin() - d[1] * a.cos()).acos().to_degrees()
    };
    let (blue, red) = (measured(2), measured(0));
    let (blue_expected, red_expected) = (predicted((400.0, 500.0)), predicted((600.0, 700.0)));
    let report = format!(
        "deviation {:.3}° at 450 nm, {:.3}° at 650 nm; blue centroid {blue:.2} px (Snell {blue_expected:.2}), red {red:.2} px (Snell {red_expected:.2})",
        deviation(450.0),
        deviation(650.0)
    );
    assert!((blue - blue_expected).abs() < 1.0, "{report}");
    assert!((red - red_expected).abs() < 1.0, "{report}");
    // The bands lie well apart: the slit is spread into its spectrum.
    assert!((blue_expected - red_expected).abs() > 10.0, "{report}");
    println!("{report}");
}

#[test]
fn three_wavelengths_per_sample_and_one_give_the_same_spectrum_with_less_noise() {
    // The ray tree splits into three wavelengths, one in each channel's box; a single
    // path (stochastic tree) takes one, its channel times 3. With R = 0 the stochastic
    // tree always refracts: the two differ only in how they sample wavelengths.
    let setup = SlitThroughPrism::new();
    let spp = 1024;
    let three = setup.render(spp, TreeMode::Split);
    let one = setup.render(spp, TreeMode::Stochastic);
    let reference = setup.render(4096, TreeMode::Split);
    let total = |film: &Film, c: usize| film.pixels().map(|p| p[c] as f64).sum::<f64>();
    for c in 0..3 {
        // Both estimate the same integral over the channel's box, so the channel's total
        // over the image agrees within the noise of one wavelength per sample: a sample's
        // channel is 3× a box's value with probability 1/3, relative variance
        // 3 − 1 = 2 per sample, 2 / (spp × lit pixels) for the total. Within 4 standard
        // errors (Sobol's stratification only makes it smaller).
        let lit = reference.pixels().filter(|p| p[c] > 0.0).count() as f64;
        let tolerance = 4.0 * (2.0 / (spp as f64 * lit)).sqrt();
        let (a, b) = (total(&three, c), total(&one, c));
        assert!(
            (a / b - 1.0).abs() < tolerance,
            "channel {c}: {a} vs {b} (tolerance {tolerance})"
        );
        // And the centroids: within half a pixel.
        let (a, b) = (setup.centroid(&three, c), setup.centroid(&one, c));
        assert!((a - b).abs() < 0.5, "channel {c}: centroid {a} vs {b}");
    }
    // Per pixel, splitting is the cleaner estimator: the summed squared difference from
    // the 4096-sample reference is less than half.
    let err = |film: &Film| {
        film.pixels()
            .zip(reference.pixels())
            .map(|(p, r)| (p - r).length_squared() as f64)
            .sum::<f64>()
    };
    assert!(
        err(&three) < 0.5 * err(&one),
        "{} vs {}",
        err(&three),
        err(&one)
    );
}

#[test]
fn wavelengths_drawn_with_the_image_position_give_the_same_spectrum_with_less_noise() {
    // With Sobol samples a sample's wavelength is the third coordinate of its image
    // position's point (a 3D net per pixel); with random samples it is an independent
    // number. Eight seeds of each at 64 samples: the channels' totals over the image agree
    // within the seeds' own scatter, and the net's scatter is the smaller.
    let setup = SlitThroughPrism::new();
    let (spp, seeds) = (64, 8);
    let total = |film: &Film, c: usize| film.pixels().map(|p| p[c] as f64).sum::<f64>();
    // Mean and standard error of the mean over the seeds, for each channel.
    let stats = |pattern: Pattern| {
        let totals: Vec<[f64; 3]> = (0..seeds)
            .map(|seed| {
                let film = setup.render_with(spp, TreeMode::Split, pattern, seed);
                [0, 1, 2].map(|c| total(&film, c))
            })
            .collect();
        [0, 1, 2].map(|c| {
            let n = seeds as f64;
            let mean = totals.iter().map(|t| t[c]).sum::<f64>() / n;
            let var = totals.iter().map(|t| (t[c] - mean).powi(2)).sum::<f64>() / (n - 1.0);
            (mean, (var / n).sqrt())
        })
    };
    let (joint, independent) = (stats(Pattern::Sobol), stats(Pattern::Random));
    for c in 0..3 {
        let ((a, sa), (b, sb)) = (joint[c], independent[c]);
        // 4 standard errors of the difference; the totals are hundreds of pixels' worth.
        assert!(
            (a - b).abs() < 4.0 * (sa * sa + sb * sb).sqrt(),
            "channel {c}: {a} ± {sa} against {b} ± {sb}"
        );
        assert!(sa < 0.5 * sb, "channel {c}: scatter {sa} against {sb}");
    }
    // Per pixel: quadrupling the samples cuts the error against a 4096-sample image by
    // more than the factor 2 of independent samples: 2.8 = 4^0.75 (stratification in
    // image position and wavelength together), where a wavelength drawn as a dimension
    // of its own (padded) gave 1.8.
    let reference = setup.render(4096, TreeMode::Split);
    let err = |spp: u32| {
        let film = setup.render(spp, TreeMode::Split);
        let sq = film
            .pixels()
            .zip(reference.pixels())
            .map(|(p, r)| (p - r).length_squared() as f64)
            .sum::<f64>();
        sq.sqrt()
    };
    let (e64, e256) = (err(64), err(256));
    assert!(e64 / e256 > 2.3, "error {e64} at 64 samples, {e256} at 256");
}

#[test]
fn the_inspector_shows_the_three_wavelengths_the_tree_splits_into() {
    let setup = SlitThroughPrism::new();
    let params = Params::default();
    let tracer = raylab::tracer::Tracer::with_camera(
        &setup.scene,
        &setup.scene.camera,
        &params,
        setup.width,
        setup.height,
    );
    // The centre column's camera ray meets the prism's first face.
    let (tree, radiance) = tracer.inspect(setup.width / 2, 0, 0);
    assert_eq!(
        tree.nodes[0].wavelength, None,
        "the camera ray has none yet"
    );
    // Below the prism's face, three refracted rays, one in each channel's box, each
    // carrying its wavelength down its subtree.
    let refracted: Vec<_> = tree
        .children(0)
        .filter(|(_, n)| n.kind == raylab::tracer::RayKind::Refract)
        .collect();
    let mut channels: Vec<usize> = refracted
        .iter()
        .map(|(_, n)| channel(n.wavelength.unwrap()))
        .collect();
    channels.sort();
    assert_eq!(channels, [0, 1, 2]);
    // The camera ray's interface is shown for the first wavelength, the one its first
    // children carry.
    let first = tree.children(0).next().unwrap().1.wavelength.unwrap();
    let (_, n2) = tree.nodes[0].hit.unwrap().n1_n2.unwrap();
    assert!(
        (n2 - ior_at(setup.ior, setup.abbe, first)).abs() < 1e-6,
        "{n2} at {first} nm"
    );
    for (id, n) in &refracted {
        for (_, child) in tree.children(*id) {
            if child.kind != raylab::tracer::RayKind::Shadow {
                assert_eq!(child.wavelength, n.wavelength);
            }
        }
    }
    assert!(radiance.is_finite());
}
