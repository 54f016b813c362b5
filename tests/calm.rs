//! Calm frames: while an image is on its way, the window shows it with its noise smoothed
//! along each surface (`Frame::calm`); the film, and everything read from it, stays the
//! render's bit for bit.
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

use raylab::math::Color;
use raylab::params::Params;
use raylab::render::{Engine, EngineConfig, Frame, render};
use raylab::scene::Scene;
use std::sync::Arc;
use std::time::{Duration, Instant};

const W: u32 = 384;
const H: u32 = 216;

/// The engine's frames of its newest generation until one satisfies `stop` (included).
fn frames_until(e: &Engine, mut stop: impl FnMut(&Frame) -> bool) -> Vec<Frame> {
    let deadline = Instant::now() + Duration::from_secs(120);
    let mut frames = Vec::new();
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        let f = e.frames().recv_timeout(left).expect("a frame in time");
        if f.generation != e.generation() {
            continue;
        }
        let last = stop(&f);
        frames.push(f);
        if last {
            return frames;
        }
    }
}

/// Root mean square difference of two pictures' luminance.
fn rmse(a: &[Color], b: &[Color]) -> f64 {
    let luma = |c: &Color| 0.2126 * c.x as f64 + 0.7152 * c.y as f64 + 0.0722 * c.z as f64;
    let sum: f64 = a
        .iter()
        .zip(b)
        .map(|(a, b)| (luma(a) - luma(b)).powi(2))
        .sum();
    (sum / a.len() as f64).sqrt()
}

/// Cells of side `block` (W × H in all) stretched over the image with bilinear
/// filtering, as a texture is: each cell's value at its centre.
fn stretched(cells: &[Color], block: u32) -> Vec<Color> {
    let (gw, gh) = (W.div_ceil(block) as i64, H.div_ceil(block) as i64);
    let at = |x: i64, y: i64| cells[(y.clamp(0, gh - 1) * gw + x.clamp(0, gw - 1)) as usize];
    (0..W * H)
        .map(|p| {
            let u = ((p % W) as f32 + 0.5) / block as f32 - 0.5;
            let v = ((p / W) as f32 + 0.5) / block as f32 - 0.5;
            let (x, y) = (u.floor(), v.floor());
            let (fx, fy) = (u - x, v - y);
            let (x, y) = (x as i64, y as i64);
            let top = at(x, y) * (1.0 - fx) + at(x + 1, y) * fx;
            let bottom = at(x, y + 1) * (1.0 - fx) + at(x + 1, y + 1) * fx;
            top * (1.0 - fy) + bottom * fy
        })
        .collect()
}

/// The soft-shadow slide's scene with `spp` as its target, and an engine rendering it on
/// two workers.
fn soft_shadows(spp: u32) -> (Arc<Scene>, Params, Engine) {
    let scene = Arc::new(Scene::load("soft-shadows").unwrap());
    let params = Params {
        spp,
        ..scene.params.clone()
    };
    let config = EngineConfig::with_threads(2);
    let engine = Engine::new(Arc::clone(&scene), params.clone(), W, H, config, || {}).unwrap();
    (scene, params, engine)
}

#[test]
fn a_drags_first_frames_are_calm_and_near_the_converged_image() {
    // As in a drag of Light size on the soft-shadow slide: an image refined, then a step
    // of the slider; the new image's first frames (a preview's blocks, one sample per
    // pixel, two) are calmed, and the calmed pictures are nearer the converged image (1024
    // samples) than the raw ones, in root mean square luminance: 3 times at one sample
    // per pixel, 2 at two.
    let (scene, params, mut e) = soft_shadows(256);
    frames_until(&e, |f| f.progress.spp >= 16);
    let stepped = Params {
        light_size: params.light_size * 1.05,
        ..params.clone()
    };
    e.set_params(stepped.clone());
    let frames = frames_until(&e, |f| f.progress.spp >= 2);
    let reference = render(
        &scene,
        &Params {
            spp: 1024,
            ..stepped.clone()
        },
        W,
        H,
        &(),
    )
    .unwrap()
    .0;
    let converged: Vec<Color> = reference.pixels().collect();
    let mut passes = 0;
    for f in &frames {
        let calm = f.calm.as_ref().expect("a frame on its way is calmed");
        if f.is_preview() {
            assert_eq!(calm.block, f.block, "a preview's calm is of its grid");
            assert_eq!(calm.pixels.len(), f.pixels.len());
            continue;
        }
        passes += 1;
        // Compared as the window shows them: the calmed cells stretched bilinearly.
        let shown = stretched(&calm.pixels, calm.block);
        let (raw, calmed) = (rmse(&f.pixels, &converged), rmse(&shown, &converged));
        // Measured: 4.7 times nearer at 1 sample, 2.6 at 2 (Sobol's second sample already
        // halves the raw error; what stays is the 2 × 2 cells' softness at edges).
        let nearer = if f.progress.spp == 1 { 3.0 } else { 2.0 };
        assert!(
            calmed * nearer < raw,
            "at {} spp: calmed {calmed:.4}, raw {raw:.4}",
            f.progress.spp
        );
    }
    assert!(passes >= 1, "no pass among {} frames", frames.len());
}

#[test]
fn calm_frames_leave_the_film_as_rendered_and_stop_at_the_target() {
    // Calm or not, every pass's pixels are the film the kernel renders at that count, bit
    // for bit; the frame at the target carries no calmed picture; with calm off, none does.
    for calm in [true, false] {
        let (scene, params, mut e) = soft_shadows(8);
        e.set_calm(calm);
        // (A change, so that every frame after it is of the setting.)
        let changed = Params {
            seed: params.seed + 1,
            ..params.clone()
        };
        e.set_params(changed.clone());
        let frames = frames_until(&e, |f| f.progress.done());
        let last = frames.last().unwrap();
        assert!(last.calm.is_none(), "the finished image is shown raw");
        let film = render(&scene, &changed, W, H, &()).unwrap().0;
        assert_eq!(*last.pixels, film.pixels().collect::<Vec<_>>());
        if calm {
            assert!(
                frames.iter().any(|f| !f.is_preview() && f.calm.is_some()),
                "no calmed pass on the way"
            );
        } else {
            assert!(frames.iter().all(|f| f.calm.is_none()), "calmed while off");
        }
    }
}
