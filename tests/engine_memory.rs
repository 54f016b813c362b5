//! Memory does not grow with restarts (its own test binary, so that no other test's
//! allocations disturb the measurement). Linux only: resident memory is read from /proc.
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]
#![cfg(target_os = "linux")]

use raylab::params::Params;
use raylab::render::{Engine, EngineConfig};
use raylab::scene::Scene;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Resident memory in bytes.
fn rss() -> u64 {
    let statm = std::fs::read_to_string("/proc/self/statm").unwrap();
    statm
        .split_whitespace()
        .nth(1)
        .unwrap()
        .parse::<u64>()
        .unwrap()
        * 4096
}

#[test]
fn memory_does_not_grow_over_ten_thousand_restarts() {
    let scene = Arc::new(Scene::load("default").unwrap());
    let base = Params {
        spp: 2,
        ..scene.params.clone()
    };
    let mut e = Engine::new(
        Arc::clone(&scene),
        base.clone(),
        160,
        90,
        EngineConfig::with_threads(2),
        || {},
    )
    .unwrap();
    let settle = |e: &Engine| {
        let generation = e.generation();
        let deadline = Instant::now() + Duration::from_secs(30);
        loop {
            let f = e
                .frames()
                .recv_timeout(deadline.saturating_duration_since(Instant::now()))
                .unwrap();
            if f.generation == generation && f.progress.done() {
                return;
            }
        }
    };
    // Warm up: the first thousand restarts grow every buffer to its working size.
    for i in 0..1000u64 {
        e.set_params(Params {
            seed: i,
            ..base.clone()
        });
    }
    settle(&e);
    let before = rss();
    for i in 0..10_000u64 {
        e.set_params(Params {
            seed: i,
            ..base.clone()
        });
        // Drain now and then, as a display would.
        if i % 100 == 0 {
            while e.frames().try_recv().is_ok() {}
        }
    }
    settle(&e);
    let after = rss();
    let growth = after as i64 - before as i64;
    // A frame of 160×90 pixels is 230 kB; the channel holds at most five.
    assert!(
        growth < 8 << 20,
        "resident memory grew by {growth} bytes over 10,000 restarts"
    );
    e.shutdown();
}
