//! Samples and rays per second on (a) the default scene, (b) a glass sphere before an
//! emitting checkerboard, (c) three emitting checkerboards through a thin lens and (d) a
//! million-triangle mesh, each on one thread and on all; and the BVH build time.
//!
//! `cargo bench` (criterion). Each 1-spp pass is timed twice, once counted in samples
//! (elements/s = samples/s) and once in rays (every ray the pass traces, of every kind,
//! counted up front: the count is deterministic). The `*_by_traversal` groups time one
//! thread's 1-spp pass of (a) and (b) walked each way this processor runs: recursively, and
//! in waves at every lane width it has (the same image each way). (e) times one thread
//! bringing a 16-spp image of the glass scene back to 16 samples after a change of the
//! index of refraction, afresh and with the pixels the change cannot alter kept.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use raylab::camera::Camera;
use raylab::geometry::{Mesh, Plane, Shape};
use raylab::light::{Background, Light};
use raylab::material::{Diffuse, Material, Texture};
use raylab::math::lanes::Width;
use raylab::math::{Color, Vec3};
use raylab::params::{LensModel, Params};
use raylab::render::{Film, render, render_pass, render_pass_by};
use raylab::scene::{Object, Scene, SceneDesc, SceneSource};
use raylab::tracer::Traversal;
use std::f32::consts::PI;
use std::hint::black_box;
use std::time::Duration;

const WIDTH: u32 = 480;
const HEIGHT: u32 = 270;

/// A bumpy sphere of `2 * rings * segments` triangles: (1000, 500) gives a million.
fn bumpy_sphere(segments: u32, rings: u32) -> Mesh {
    let mut positions = Vec::new();
    for j in 0..=rings {
        let theta = PI * j as f32 / rings as f32;
        for i in 0..segments {
            let phi = 2.0 * PI * i as f32 / segments as f32;
            let r = 1.0
                + 0.06 * (7.0 * phi).sin() * (9.0 * theta).sin()
                + 0.02 * (40.0 * phi).sin() * (35.0 * theta).cos();
            positions.push(
                r * Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                ) + Vec3::Y,
            );
        }
    }
    let mut indices = Vec::new();
    for j in 0..rings {
        for i in 0..segments {
            let a = j * segments + i;
            let b = j * segments + (i + 1) % segments;
            let (c, d) = (a + segments, b + segments);
            indices.push([a, c, b]);
            indices.push([b, c, d]);
        }
    }
    Mesh::new(positions, indices, None, None).expect("valid mesh")
}

fn mesh_scene(mesh: Mesh) -> SceneDesc {
    let diffuse = |c: Color| {
        Material::Diffuse(Diffuse {
            albedo: Texture::Solid(c),
            specular: Color::splat(0.2),
            exponent: 40.0,
            emission: None,
        })
    };
    SceneDesc {
        name: "million".into(),
        description: "a million-triangle bumpy sphere".into(),
        camera: Camera::looking_at(
            Vec3::new(0.0, 1.6, 4.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::Y,
            40.0,
        ),
        width: WIDTH,
        height: HEIGHT,
        params: Params::default(),
        warnings: Vec::new(),
        materials: vec![
            ("floor".into(), diffuse(Color::splat(0.7))),
            ("blob".into(), diffuse(Color::new(0.7, 0.4, 0.2))),
        ],
        objects: vec![
            Object {
                name: "floor".into(),
                shape: Shape::Plane(Plane::new(Vec3::ZERO, Vec3::Y)),
                material: 0,
            },
            Object {
                name: "blob".into(),
                shape: Shape::Mesh(mesh),
                material: 1,
            },
        ],
        lights: vec![Light::point(Vec3::new(-3.0, 6.0, 4.0), Color::splat(150.0))],
        ambient: Color::splat(0.05),
        background: Background::Constant(Color::new(0.6, 0.7, 0.9)),
        medium_ior: 1.0,
    }
}

/// Samples per second and rays per second of 1-spp passes over `scene`, on one thread and
/// on all of them.
fn throughput(c: &mut Criterion, name: &str, scene: &Scene) {
    let params = Params {
        spp: 1,
        ..scene.params.clone()
    };
    let rays = render(scene, &params, WIDTH, HEIGHT, &())
        .expect("no cancel")
        .1
        .total_rays();
    let samples = u64::from(WIDTH * HEIGHT);
    let all = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut group = c.benchmark_group(name);
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(3));
    for threads in [1, all] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool");
        for (what, count) in [("samples", samples), ("rays", rays)] {
            group.throughput(Throughput::Elements(count));
            let id = format!("{what}/{threads}_threads/1spp_{WIDTH}x{HEIGHT}");
            group.bench_function(id, |b| {
                b.iter(|| {
                    pool.install(|| {
                        black_box(render(scene, &params, WIDTH, HEIGHT, &()).expect("no cancel"))
                    })
                })
            });
        }
    }
    group.finish();
}

/// Samples per second of one thread's 1-spp pass over `scene`, walked recursively and in
/// waves at each lane width this processor runs.
fn traversals(c: &mut Criterion, name: &str, scene: &Scene) {
    let params = Params {
        spp: 1,
        ..scene.params.clone()
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a thread pool");
    let ways = std::iter::once(Traversal::Recursive).chain(
        Width::ALL
            .into_iter()
            .filter(|w| w.runs_here())
            .map(Traversal::Waves),
    );
    let mut group = c.benchmark_group(format!("{name}_by_traversal"));
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(3));
    group.throughput(Throughput::Elements(u64::from(WIDTH * HEIGHT)));
    for way in ways {
        let id = match way {
            Traversal::Recursive => "recursion".to_string(),
            Traversal::Waves(w) => format!("waves_{}_lanes", w.lanes()),
        };
        group.bench_function(id, |b| {
            b.iter(|| {
                pool.install(|| {
                    let mut film = Film::new(WIDTH, HEIGHT);
                    let stats =
                        render_pass_by(way, scene, &scene.camera, &params, &mut film, 1, &());
                    black_box((film, stats.expect("no cancel")))
                })
            })
        });
    }
    group.finish();
}

/// After a change of the index of refraction, a 16-spp image of the glass scene brought
/// back to 16 samples with the pixels the change cannot alter kept, against rendering it
/// afresh, on one thread.
fn reuse(c: &mut Criterion) {
    let scene = Scene::load("glass").expect("built-in scene");
    let old = Params {
        spp: 16,
        ..scene.params.clone()
    };
    let new = Params {
        ior: Some(1.6),
        ..old.clone()
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a thread pool");
    let before = pool.install(|| {
        render(&scene, &old, WIDTH, HEIGHT, &())
            .expect("no cancel")
            .0
    });
    let reach = raylab::tracer::reach(&scene, &old, &new).expect("a change of materials");
    let mut group = c.benchmark_group("e_change_of_ior");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(3));
    group.bench_function("glass_16spp_afresh", |b| {
        b.iter(|| pool.install(|| black_box(render(&scene, &new, WIDTH, HEIGHT, &()))))
    });
    group.bench_function("glass_16spp_kept_where_unreached", |b| {
        b.iter(|| {
            pool.install(|| {
                let mut film = before.clone();
                film.restart_reached(&reach, 16, &mut Vec::new());
                let stats = render_pass(&scene, &scene.camera, &new, &mut film, 16, &());
                black_box((film, stats.expect("no cancel")))
            })
        })
    });
    group.finish();
}

/// A benchmark scene of benches/.
fn bench_scene(file: &str) -> Scene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("benches")
        .join(file);
    Scene::load_file(&path).expect("benchmark scene")
}

fn benches(c: &mut Criterion) {
    let default = Scene::load("default").expect("built-in scene");
    throughput(c, "a_default_scene", &default);
    throughput(c, "b_specular", &bench_scene("specular.toml"));
    throughput(c, "c_thin_lens", &bench_scene("thin-lens.toml"));
    // (c) again through a real lens: the double Gauss wide open, its glass traced.
    let mut real_lens = bench_scene("thin-lens.toml");
    real_lens.params.lens = LensModel::DoubleGauss50;
    throughput(c, "c_real_lens", &real_lens);
    traversals(c, "a_default_scene", &default);
    traversals(c, "b_specular", &bench_scene("specular.toml"));
    reuse(c);

    let mesh = bumpy_sphere(1000, 500);
    assert!(mesh.triangle_count() >= 1_000_000);
    let desc = mesh_scene(mesh);
    let mut group = c.benchmark_group("million_triangles");
    group.sample_size(10);
    group.throughput(Throughput::Elements(1_000_000));
    group.bench_function("bvh_build", |b| {
        b.iter_batched(
            || desc.clone(),
            |d| black_box(Scene::new(d, SceneSource::Code)),
            criterion::BatchSize::LargeInput,
        )
    });
    group.finish();
    let scene = Scene::new(desc, SceneSource::Code);
    throughput(c, "d_million_triangles", &scene);
}

criterion_group!(render_benches, benches);
criterion_main!(render_benches);
