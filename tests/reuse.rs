//! A change of parameters re-renders only the pixels it can alter: after the change, the
//! pixels whose samples met what it reaches start again and the passes bring them back,
//! and the film is then bit for bit a fresh render with the new parameters (its sums,
//! its counts and its record), for every parameter the record tells of, in every
//! transport, walked by the recursion and by the waves at every width.
#![allow(clippy::unwrap_used)]

mod common;

use raylab::math::Color;
use raylab::math::lanes::Width;
use raylab::optics::FresnelMode;
use raylab::params::{Params, Transport};
use raylab::render::{Engine, EngineConfig, Film, Frame, PassObserver, render, render_pass_by};
use raylab::scene::{BUILTIN_SCENES, Scene};
use raylab::tracer::{Traversal, reach};
use std::collections::BTreeMap;
use std::sync::Arc;
use std::sync::atomic::{AtomicU32, Ordering};
use std::time::Duration;

const SIZE: (u32, u32) = (32, 24);
const SPP: u32 = 4;

/// Stops a pass after it asked `0` times: a change that comes while a pass is on its way.
struct StopAfter(AtomicU32);

impl PassObserver for StopAfter {
    fn keep_going(&self) -> bool {
        self.0.fetch_sub(1, Ordering::Relaxed) > 0
    }
}

/// `params` rendered afresh to its target.
fn fresh(scene: &Scene, params: &Params, traversal: Traversal) -> Film {
    common::render_by(traversal, scene, params, SIZE)
}

/// `old` rendered to its target but for a last pass stopped half-way (if `ragged`), then
/// changed to `new` and refined by passes of 1, 1, 2, 4, ... samples as the engine's
/// are: the film and how many pixels started again; `None` where the change reaches
/// every sample.
fn refined(
    scene: &Scene,
    (old, new): (&Params, &Params),
    traversal: Traversal,
    ragged: bool,
) -> Option<(Film, usize)> {
    let mut film = Film::new(SIZE.0, SIZE.1);
    let pass = |p: &Params, film: &mut Film, n: u32, o: &dyn PassObserver| {
        render_pass_by(traversal, scene, &scene.camera, p, film, n, o)
    };
    if ragged {
        pass(old, &mut film, old.spp - 1, &()).unwrap();
        // Asked before each pixel by the recursion, each wave (of a band) by the waves.
        let asked = match traversal {
            Traversal::Recursive => SIZE.0 * SIZE.1 / 2,
            _ => 3,
        };
        let half = StopAfter(AtomicU32::new(asked));
        assert!(pass(old, &mut film, 1, &half).is_err());
    } else {
        pass(old, &mut film, old.spp, &()).unwrap();
    }
    let reach = reach(scene, old, new)?;
    let started = film.restart_reached(&reach, film.spp(), &mut Vec::new());
    let mut passes = 0;
    while film.spp() < new.spp {
        let n = (1 << passes.max(1) >> 1).min(new.spp - film.spp());
        pass(new, &mut film, n, &()).unwrap();
        passes += 1;
    }
    Some((film, started))
}

/// Each parameter the record tells of, as a change from a scene's parameters: its name,
/// and the two sides.
fn changes(base: &Params) -> Vec<(&'static str, Params, Params)> {
    let p = |f: &dyn Fn(&mut Params)| {
        let mut p = base.clone();
        f(&mut p);
        p
    };
    let constant = p(&|p| p.fresnel = Some(FresnelMode::Constant));
    vec![
        ("ior", base.clone(), p(&|p| p.ior = Some(1.7))),
        ("abbe", base.clone(), p(&|p| p.abbe = Some(25.0))),
        ("roughness", base.clone(), p(&|p| p.roughness = Some(0.2))),
        (
            "roughness back to smooth",
            p(&|p| p.roughness = Some(0.2)),
            p(&|p| p.roughness = Some(0.0)),
        ),
        (
            "fresnel",
            base.clone(),
            p(&|p| p.fresnel = Some(FresnelMode::Schlick)),
        ),
        (
            "constant_reflectance",
            constant.clone(),
            Params {
                constant_reflectance: Some(0.4),
                ..constant
            },
        ),
        (
            "absorption_scale",
            base.clone(),
            p(&|p| p.absorption_scale = 3.0),
        ),
        (
            "phong_exponent",
            base.clone(),
            p(&|p| p.phong_exponent = Some(7.0)),
        ),
        (
            "max_depth up",
            base.clone(),
            p(&|p| p.max_depth = base.max_depth + 3),
        ),
        (
            "max_depth down",
            base.clone(),
            p(&|p| p.max_depth = base.max_depth.saturating_sub(2)),
        ),
        ("min_weight up", base.clone(), p(&|p| p.min_weight = 0.2)),
        (
            "min_weight down",
            p(&|p| p.min_weight = 0.2),
            p(&|p| p.min_weight = 0.0),
        ),
        ("light_size", base.clone(), p(&|p| p.light_size = 2.0)),
        ("spp", base.clone(), p(&|p| p.spp = SPP + 3)),
    ]
}

/// Every traversal there is here: the recursion, and the waves at each width.
fn traversals() -> Vec<Traversal> {
    let waves = Width::ALL.into_iter().filter(|w| w.runs_here());
    std::iter::once(Traversal::Recursive)
        .chain(waves.map(Traversal::Waves))
        .collect()
}

#[test]
fn a_change_then_refinement_is_a_fresh_render_bit_for_bit() {
    // Per parameter: the cases that kept some pixels and re-rendered others.
    let mut partial: BTreeMap<&str, u32> = BTreeMap::new();
    let transports = [
        Transport::Whitted,
        Transport::TransmissiveShadows,
        Transport::Path,
        Transport::Photons,
    ];
    for b in BUILTIN_SCENES {
        let scene = Scene::load(b.name).unwrap();
        for (t, transport) in transports.into_iter().enumerate() {
            let base = Params {
                spp: SPP,
                transport,
                ..scene.params.clone()
            };
            // The ray tree at every width; paths have one walk. A cancelled last pass on
            // every other scene.
            let walks = match transport.traces_paths() {
                true => vec![Traversal::Recursive],
                false => traversals(),
            };
            let ragged = (b.name.len() + t) % 2 == 0;
            for (name, old, new) in changes(&base) {
                for &traversal in &walks {
                    let case = format!("{}, {transport:?}, {name}, {traversal:?}", b.name);
                    let Some((film, started)) = refined(&scene, (&old, &new), traversal, ragged)
                    else {
                        continue;
                    };
                    assert!(film == fresh(&scene, &new, traversal), "{case}");
                    if started > 0 && started < film.pixels().count() {
                        *partial.entry(name).or_default() += 1;
                    }
                }
            }
        }
    }
    // Each parameter's cases re-rendered part of an image somewhere (but light size and
    // the target: the one reaches every pixel an area light lights, the other none).
    for (name, _, _) in changes(&Params::default()) {
        let some = partial.get(name).copied().unwrap_or(0);
        match name {
            "light_size" | "spp" => {}
            _ => assert!(some > 0, "{name}: no case kept part of the image"),
        }
    }
}

/// The engine's frames of its newest generation until the one at its target.
fn to_target(engine: &Engine) -> Vec<Frame> {
    let mut frames = Vec::new();
    loop {
        let f = engine
            .frames()
            .recv_timeout(Duration::from_secs(60))
            .unwrap();
        if f.generation == engine.generation() {
            let done = f.progress.done();
            frames.push(f);
            if done {
                return frames;
            }
        }
    }
}

/// The pixels of a fresh render of `params` at `spp` samples.
fn fresh_pixels(scene: &Scene, params: &Params, (w, h): (u32, u32), spp: u32) -> Vec<Color> {
    let params = Params {
        spp,
        ..params.clone()
    };
    render(scene, &params, w, h, &())
        .unwrap()
        .0
        .pixels()
        .collect()
}

#[test]
fn the_engine_re_renders_part_of_the_image_and_ends_at_the_fresh_render() {
    let scene = Arc::new(Scene::load("glass").unwrap());
    let (w, h) = (64, 48);
    let old = Params {
        spp: 8,
        ..scene.params.clone()
    };
    let config = EngineConfig::with_threads(2);
    let mut engine = Engine::new(Arc::clone(&scene), old.clone(), w, h, config, || {}).unwrap();
    // (Calmed pictures are the screen's: the frames' pixels are the film's either way.)
    engine.set_calm(false);
    to_target(&engine);
    // A change of the index of refraction, then one of the exponent (no glossy surface
    // here: nothing to render again), then one of the seed (everything).
    let ior = Params {
        ior: Some(1.7),
        ..old.clone()
    };
    let exponent = Params {
        phong_exponent: Some(3.0),
        ..ior.clone()
    };
    let seed = Params {
        seed: 9,
        ..exponent.clone()
    };
    for (params, part) in [(ior, 0.05..0.5), (exponent, 0.0..0.0), (seed, 1.0..1.0)] {
        engine.set_params(params.clone());
        let frames = to_target(&engine);
        let last = frames.last().unwrap();
        let reached = last.progress.reached;
        assert!(
            part.contains(&reached) || reached == part.start,
            "{reached} of the pixels re-rendered, not within {part:?}"
        );
        // Every frame after a pass is the new image: each pixel kept (the new image at
        // the old samples) or re-rendered (at the frame's samples); the last one all of it.
        let kept = fresh_pixels(&scene, &params, (w, h), old.spp);
        // (A preview of the pixels started again shows them coarser: its blocks.)
        let previews = frames.iter().filter(|f| f.coarsest > 1).count();
        assert!(previews <= 3, "{previews} previews");
        for f in frames.iter().filter(|f| f.coarsest == 1) {
            let now = fresh_pixels(&scene, &params, (w, h), f.progress.spp);
            let mut re_rendered = 0;
            for ((p, k), n) in f.pixels.iter().zip(&kept).zip(&now) {
                let same = |a: &Color, b: &Color| {
                    a.to_array().map(f32::to_bits) == b.to_array().map(f32::to_bits)
                };
                assert!(
                    same(p, k) || same(p, n),
                    "{params:?} at {} spp",
                    f.progress.spp
                );
                re_rendered += usize::from(!same(p, k));
            }
            assert!(re_rendered as f32 <= reached * (w * h) as f32);
        }
        assert!(last.calm.is_none());
        assert_eq!(last.progress.spp, old.spp);
    }
}

#[test]
fn with_adaptive_sampling_a_change_before_its_first_decision_keeps_pixels_and_is_exact() {
    // Adaptive sampling first decides at 16 samples, on the whole film: until then a
    // pixel's samples are its own. An image of 16 samples changed, then refined on to 48
    // (deciding at 16, 24, 32 and 40, a loose target stopping pixels at each), is the
    // fresh render bit for bit. (From 32 samples on, it would not be.)
    let mut partial = 0;
    for name in ["default", "glass", "glossy"] {
        let scene = Scene::load(name).unwrap();
        let old = Params {
            spp: 16,
            noise_target: Some(10.0),
            ..scene.params.clone()
        };
        let changes = [
            Params {
                ior: Some(1.7),
                ..old.clone()
            },
            Params {
                phong_exponent: Some(5.0),
                spp: 48,
                ..old.clone()
            },
        ];
        for new in changes {
            let new = Params { spp: 48, ..new };
            let traversal = Traversal::best();
            let (film, started) = refined(&scene, (&old, &new), traversal, false).unwrap();
            assert!(film == fresh(&scene, &new, traversal), "{name}: {new:?}");
            assert!(film.done_pixels() > 0, "adaptive sampling stopped pixels");
            partial += usize::from(started > 0 && started < film.pixels().count());
        }
    }
    assert!(partial >= 3, "{partial} cases kept part of the image");
}
