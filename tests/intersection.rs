//! Intersection: the BVH finds exactly what testing every primitive finds, and rays
//! leaving a surface neither hit it again (acne) nor pass through nearby geometry (leaks).
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

use glam::{Affine3A, Quat};
use raylab::camera::Camera;
use raylab::geometry::{Instance, Mesh, Plane, Quad, Shape, SharedMesh, Sphere};
use raylab::material::{Diffuse, Material};
use raylab::math::{Color, Ray, SampleStream, Vec3, offset_ray_origin};
use raylab::scene::{Scene, SceneDesc};

/// Deterministic uniform numbers for tests.
struct Rng(SampleStream);

impl Rng {
    fn new(seed: u64) -> Self {
        Rng(SampleStream::new(seed, 0, 0))
    }
    fn f(&mut self) -> f32 {
        self.0.next_1d()
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.f()
    }
    fn vec(&mut self, lo: f32, hi: f32) -> Vec3 {
        Vec3::new(self.range(lo, hi), self.range(lo, hi), self.range(lo, hi))
    }
    fn dir(&mut self) -> Vec3 {
        loop {
            let v = self.vec(-1.0, 1.0);
            if v.length_squared() > 1e-4 && v.length_squared() <= 1.0 {
                return v.normalize();
            }
        }
    }
}

fn scene_of(shapes: Vec<Shape>) -> Scene {
    let mut desc = SceneDesc::empty(Camera::looking_at(Vec3::Z, Vec3::ZERO, Vec3::Y, 45.0));
    let grey = Material::Diffuse(Diffuse::solid(Color::splat(0.5)));
    for (i, shape) in shapes.into_iter().enumerate() {
        desc.add(format!("object {i}"), shape, grey.clone());
    }
    desc.build()
}

/// A soup of random triangles in a box of side `size` around `center`.
fn random_mesh(rng: &mut Rng, triangles: usize, center: Vec3, size: f32) -> Mesh {
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    for t in 0..triangles {
        let base = center + rng.vec(-size / 2.0, size / 2.0);
        for _ in 0..3 {
            positions.push(base + rng.vec(-size / 20.0, size / 20.0));
        }
        let i = 3 * t as u32;
        indices.push([i, i + 1, i + 2]);
    }
    Mesh::new(positions, indices, None, None).unwrap()
}

/// `shared` placed: turned by `turn` radians about a tilted axis, scaled by `scale`,
/// moved to `at`, moving by `velocity` over the frame.
fn placed(
    shared: &std::sync::Arc<SharedMesh>,
    turn: f32,
    scale: f32,
    at: Vec3,
    velocity: Vec3,
) -> Instance {
    let axis = glam::Vec3::new(0.3, 1.0, -0.2).normalize();
    let transform = Affine3A::from_scale_rotation_translation(
        glam::Vec3::splat(scale),
        Quat::from_axis_angle(axis, turn),
        at.into(),
    );
    Instance::new(shared.clone(), transform, true, velocity).unwrap()
}

#[test]
fn bvh_equals_brute_force_on_random_rays_over_random_meshes() {
    for seed in 0..4u64 {
        let mut rng = Rng::new(seed);
        let mut shapes = vec![
            Shape::Mesh(random_mesh(&mut rng, 3000, Vec3::ZERO, 10.0)),
            Shape::Mesh(random_mesh(&mut rng, 500, Vec3::new(3.0, 1.0, -2.0), 2.0)),
            Shape::Plane(Plane::new(Vec3::new(0.0, -6.0, 0.0), Vec3::Y)),
        ];
        // One mesh placed three times (the two-level BVH), one of them moving.
        let shared = SharedMesh::new(random_mesh(&mut rng, 400, Vec3::ZERO, 2.0));
        for k in 0..3 {
            let at = rng.vec(-4.0, 4.0);
            let velocity = if k == 1 {
                Vec3::new(0.5, 0.2, 0.0)
            } else {
                Vec3::ZERO
            };
            let instance = placed(&shared, k as f32, 0.5 + k as f32, at, velocity);
            shapes.push(Shape::Instance(instance));
        }
        for _ in 0..20 {
            shapes.push(Shape::Sphere(Sphere::new(
                rng.vec(-5.0, 5.0),
                rng.range(0.05, 1.0),
            )));
            shapes.push(Shape::Quad(Quad::new(
                rng.vec(-5.0, 5.0),
                rng.vec(-1.0, 1.0),
                rng.vec(-1.0, 1.0),
            )));
        }
        let scene = scene_of(shapes);
        let mut hits = 0;
        for _ in 0..4000 {
            // Rays from outside and from inside the cloud, in every direction.
            let origin = if rng.f() < 0.5 {
                rng.vec(-6.0, 6.0)
            } else {
                rng.dir() * 15.0
            };
            let ray = Ray::new(origin, rng.dir(), rng.f());
            let t_max = if rng.f() < 0.2 {
                rng.range(0.5, 10.0)
            } else {
                f32::INFINITY
            };
            let bvh = scene.intersect(&ray, t_max);
            let brute = scene.intersect_brute_force(&ray, t_max);
            match (bvh, brute) {
                (None, None) => {}
                (Some(a), Some(b)) => {
                    hits += 1;
                    assert_eq!(
                        a.surface.t, b.surface.t,
                        "seed {seed}: different nearest distance"
                    );
                    // Ties at one distance too: the same object as testing every one.
                    assert_eq!(a.object, b.object, "seed {seed}: different nearest object");
                }
                (a, b) => panic!(
                    "seed {seed}: bvh {:?} vs brute force {:?}",
                    a.map(|h| h.object),
                    b.map(|h| h.object)
                ),
            }
            assert_eq!(
                scene.occluded(&ray, t_max),
                brute.is_some(),
                "seed {seed}: occlusion disagrees"
            );
        }
        assert!(hits > 1000, "too few hits ({hits}) to mean anything");
    }
}

#[test]
fn axis_aligned_rays_with_signed_zeros_hit() {
    // -Vec3::Z is (-0.0, -0.0, -1.0): the box test's reciprocals there are −∞, and the ray
    // must enter each box by its max planes.
    let one_sphere = scene_of(vec![Shape::Sphere(Sphere::new(
        Vec3::new(0.0, 0.0, -2.0),
        0.5,
    ))]);
    let mut rng = Rng::new(11);
    let two_prims = scene_of(vec![
        Shape::Sphere(Sphere::new(Vec3::new(0.0, 0.0, -2.0), 0.5)),
        Shape::Mesh(random_mesh(&mut rng, 50, Vec3::new(0.0, 3.0, 0.0), 1.0)),
    ]);
    for s in [&one_sphere, &two_prims] {
        for dir in [
            -Vec3::Z,
            Vec3::new(0.0, 0.0, -1.0),
            Vec3::new(-0.0, 0.0, -1.0),
            Vec3::new(0.0, -0.0, -1.0),
        ] {
            for x in [-0.45f32, 0.0, 0.3] {
                let ray = Ray::new(Vec3::new(x, 0.0, 0.0), dir, 0.0);
                let hit = s.intersect(&ray, f32::INFINITY).map(|h| h.surface.t);
                assert_eq!(
                    hit,
                    s.intersect_brute_force(&ray, f32::INFINITY)
                        .map(|h| h.surface.t),
                    "{dir:?} at x {x}"
                );
                assert!(hit.is_some());
                assert!(s.occluded(&ray, f32::INFINITY));
            }
        }
        // And reflected from a mirror straight back: reflect() yields signed zeros too.
        let back = Ray::new(
            Vec3::new(0.1, 0.0, -4.0),
            raylab::optics::reflect(-Vec3::Z, Vec3::Z),
            0.0,
        );
        assert!(s.intersect(&back, f32::INFINITY).is_some());
    }
}

/// Shoots rays at `scene` from around it; for each hit on a surface, leaves the surface on
/// both sides in random directions and checks what the new ray hits.
fn check_no_self_hits(
    scene: &Scene,
    rng: &mut Rng,
    extent: f32,
    center: Vec3,
    convex_object: Option<u32>,
) {
    let mut tested = 0;
    for _ in 0..40_000 {
        if tested >= 3000 {
            break;
        }
        let origin = center + rng.dir() * extent * 3.0;
        let target = center + rng.vec(-extent, extent);
        let ray = Ray::new(origin, target - origin, 0.0);
        let Some(hit) = scene.intersect(&ray, f32::INFINITY) else {
            continue;
        };
        let p = hit.surface.p;
        let n = hit.surface.n_geom;
        for side in [1.0f32, -1.0] {
            let n_side = n * side;
            let mut dir = rng.dir();
            if dir.dot(n_side) < 0.0 {
                dir = -dir;
            }
            // Include grazing directions.
            if rng.f() < 0.3 {
                dir = (dir - n_side * dir.dot(n_side) * 0.999).normalize();
            }
            let leave = Ray::new(offset_ray_origin(p, n_side), dir, 0.0);
            if let Some(again) = scene.intersect(&leave, f32::INFINITY)
                && again.object == hit.object
            {
                let outside_of_convex = convex_object == Some(hit.object) && side > 0.0;
                assert!(
                    !outside_of_convex && again.surface.t > 1e-4 * extent,
                    "self-intersection at {p:?} (side {side}): t = {}",
                    again.surface.t
                );
            }
            tested += 1;
        }
    }
    assert!(tested >= 3000, "only {tested} rays tested");
}

#[test]
fn rays_leaving_a_surface_do_not_hit_it_again_at_any_scale() {
    let mut rng = Rng::new(7);
    for (scale, offset) in [
        (0.01f32, 0.0f32),
        (1.0, 0.0),
        (1.0, 1000.0),
        (100.0, -5000.0),
        (1000.0, 20000.0),
    ] {
        let c = Vec3::new(offset, 0.5 * offset, -offset);
        let sphere = scene_of(vec![Shape::Sphere(Sphere::new(c, scale))]);
        check_no_self_hits(&sphere, &mut rng, scale, c, Some(0));
        let quad = scene_of(vec![Shape::Quad(Quad::new(
            c - Vec3::new(scale, 0.0, scale),
            Vec3::new(2.0 * scale, 0.3 * scale, 0.0),
            Vec3::new(0.0, 0.2 * scale, 2.0 * scale),
        ))]);
        check_no_self_hits(&quad, &mut rng, scale, c, None);
        let plane = scene_of(vec![Shape::Plane(Plane::new(c, Vec3::new(0.1, 1.0, 0.2)))]);
        check_no_self_hits(&plane, &mut rng, scale, c, None);
        let mesh = scene_of(vec![Shape::Mesh(random_mesh(
            &mut rng,
            200,
            c,
            2.0 * scale,
        ))]);
        check_no_self_hits(&mesh, &mut rng, scale, c, None);
        // A placed mesh: the hit point carried out of the mesh's frame by the transform.
        let shared = SharedMesh::new(random_mesh(&mut rng, 200, Vec3::ZERO, 2.0));
        let instance = placed(&shared, 0.7, scale, c, Vec3::ZERO);
        let placed_mesh = scene_of(vec![Shape::Instance(instance)]);
        check_no_self_hits(&placed_mesh, &mut rng, scale, c, None);
    }
}

#[test]
fn a_placed_mesh_is_hit_where_its_transformed_copy_is() {
    let mut rng = Rng::new(5);
    // A closed sphere of 24 × 12 quads, smooth-shaded, with texture coordinates: rays
    // aimed inside it never graze its outline, so copy and placement meet the same
    // surface.
    let (rings, segments) = (12u32, 24u32);
    let mut positions = Vec::new();
    let mut uvs = Vec::new();
    for i in 0..=rings {
        for j in 0..=segments {
            let theta = std::f32::consts::PI * i as f32 / rings as f32;
            let phi = 2.0 * std::f32::consts::PI * j as f32 / segments as f32;
            positions.push(Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            ));
            uvs.push(glam::Vec2::new(
                j as f32 / segments as f32,
                i as f32 / rings as f32,
            ));
        }
    }
    let mut indices = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let a = i * (segments + 1) + j;
            let (b, c, d) = (a + 1, a + segments + 1, a + segments + 2);
            indices.push([a, c, b]);
            indices.push([b, c, d]);
        }
    }
    let normals = Some(positions.clone());
    let mesh = Mesh::new(positions, indices, normals, Some(uvs)).unwrap();
    let (turn, scale, at) = (1.1, 2.5, Vec3::new(30.0, -4.0, 12.0));
    let velocity = Vec3::new(0.0, 1.5, -0.5);
    let instance = placed(&SharedMesh::new(mesh.clone()), turn, scale, at, velocity);
    let axis = glam::Vec3::new(0.3, 1.0, -0.2).normalize();
    let transform = Affine3A::from_scale_rotation_translation(
        glam::Vec3::splat(scale),
        Quat::from_axis_angle(axis, turn),
        at.into(),
    );
    let mut copy = mesh.transformed(&transform, true).unwrap();
    copy.velocity = velocity;
    let placed_scene = scene_of(vec![Shape::Instance(instance.clone())]);
    let copy_scene = scene_of(vec![Shape::Mesh(copy)]);
    for _ in 0..5000 {
        let time = rng.f();
        let center = at + velocity * time;
        let origin = center + rng.dir() * 4.0 * scale;
        let target = center + rng.dir() * 0.8 * scale * rng.f();
        let ray = Ray::new(origin, target - origin, time);
        let a = placed_scene
            .intersect(&ray, f32::INFINITY)
            .expect("a placed hit");
        let b = copy_scene
            .intersect(&ray, f32::INFINITY)
            .expect("a copy's hit");
        let (a, b) = (a.surface, b.surface);
        assert!((a.t - b.t).abs() < 1e-5 * b.t, "t {} vs {}", a.t, b.t);
        assert!(
            (a.p - b.p).length() < 1e-5 * at.length(),
            "{:?} vs {:?}",
            a.p,
            b.p
        );
        assert!(
            (a.n_geom - b.n_geom).length() < 1e-4,
            "{:?} vs {:?}",
            a.n_geom,
            b.n_geom
        );
        assert!((a.n_shade - b.n_shade).length() < 1e-4);
        assert!((a.uv - b.uv).length() < 1e-4);
        // Shadow rays stop where the copy's do.
        assert!(placed_scene.occluded(&ray, 1.0001 * b.t));
        assert!(!placed_scene.occluded(&ray, 0.9999 * b.t));
    }
    // Areas scale by scale², and points sampled on a placed triangle lie on it.
    let shape = Shape::Instance(instance);
    let area: f32 = (0..shape.primitive_count() as u32)
        .map(|i| shape.primitive_area(i))
        .sum();
    let local: f32 = (0..mesh.triangle_count() as u32)
        .map(|i| Shape::Mesh(mesh.clone()).primitive_area(i))
        .sum();
    assert!(
        (area / (scale * scale * local) - 1.0).abs() < 1e-5,
        "{area} vs {local}"
    );
    for i in 0..shape.primitive_count() as u32 {
        if shape.primitive_area(i) < 1e-6 {
            continue; // the slivers at the poles (sin π is not quite 0)
        }
        let time = rng.f();
        let p = shape
            .sample_point(i, glam::Vec2::new(rng.f(), rng.f()), time)
            .unwrap();
        // Half a unit out along the triangle's normal, a ray back meets it at p.
        let n = shape
            .surface_hit(i, &Ray::new(p + Vec3::Y, -Vec3::Y, time), 1.0, false)
            .n_geom;
        let back = Ray::new(p + 0.5 * n, -n, time);
        let t = shape.intersect_t(i, &back, 1.0);
        assert!(
            t.is_some_and(|t| (t - 0.5).abs() < 1e-3),
            "sample {p:?} off triangle {i}: {t:?}"
        );
    }
}

#[test]
fn rays_do_not_leak_through_thin_or_touching_geometry() {
    // A slab one thousandth of a unit thick: a ray entering the top face must meet the
    // bottom face, never slip past it.
    let thickness = 1e-3;
    let top = Quad::new(
        Vec3::new(-1.0, thickness, -1.0),
        Vec3::new(0.0, 0.0, 2.0),
        Vec3::new(2.0, 0.0, 0.0),
    );
    let bottom = Quad::new(
        Vec3::new(-1.0, 0.0, -1.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 2.0),
    );
    let slab = scene_of(vec![Shape::Quad(top), Shape::Quad(bottom)]);
    let mut rng = Rng::new(3);
    for _ in 0..2000 {
        let target = Vec3::new(rng.range(-0.9, 0.9), thickness, rng.range(-0.9, 0.9));
        let origin = target + Vec3::new(rng.range(-1.0, 1.0), 1.0, rng.range(-1.0, 1.0));
        let hit = slab
            .intersect(&Ray::new(origin, target - origin, 0.0), f32::INFINITY)
            .unwrap();
        assert_eq!(hit.object, 0);
        let down = Vec3::new(rng.range(-0.5, 0.5), -1.0, rng.range(-0.5, 0.5)).normalize();
        let inside = Ray::new(offset_ray_origin(hit.surface.p, -Vec3::Y), down, 0.0);
        let next = slab
            .intersect(&inside, f32::INFINITY)
            .expect("leaked through the slab");
        assert_eq!(
            next.object, 1,
            "the ray inside the slab must meet its bottom face"
        );
    }
    // A sphere resting on a plane: from floor points right beside the contact point, a ray
    // towards the sphere's centre is blocked by the sphere.
    let touching = scene_of(vec![
        Shape::Plane(Plane::new(Vec3::ZERO, Vec3::Y)),
        Shape::Sphere(Sphere::new(Vec3::new(0.0, 1.0, 0.0), 1.0)),
    ]);
    for i in 1..200 {
        let r = i as f32 * 1e-3;
        let p = Vec3::new(r, 0.0, 0.0);
        let to_center = Vec3::new(0.0, 1.0, 0.0) - p;
        let ray = Ray::new(offset_ray_origin(p, Vec3::Y), to_center, 0.0);
        let hit = touching
            .intersect(&ray, f32::INFINITY)
            .expect("escaped between sphere and floor");
        assert_eq!(hit.object, 1);
    }
}

/// Rays that run exactly along the faces of the BVH's boxes (axis-aligned triangles on a
/// grid of integer coordinates, rays in those planes and along those lines) find what
/// testing every triangle finds: the box test enlarges each exit against rounding, so a
/// box a ray only touches is still entered.
#[test]
fn rays_along_the_boxes_faces_find_what_every_triangle_finds() {
    // A staircase of unit squares (two triangles each) facing +z, +x and +y in turn: every
    // box face lies on an integer plane.
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for k in 0..40u32 {
        let (x, y, z) = ((k % 7) as f32, (k / 7) as f32, (k % 5) as f32);
        let corners = match k % 3 {
            0 => [
                [x, y, z],
                [x + 1.0, y, z],
                [x + 1.0, y + 1.0, z],
                [x, y + 1.0, z],
            ],
            1 => [
                [x, y, z],
                [x, y + 1.0, z],
                [x, y + 1.0, z + 1.0],
                [x, y, z + 1.0],
            ],
            _ => [
                [x, y, z],
                [x, y, z + 1.0],
                [x + 1.0, y, z + 1.0],
                [x + 1.0, y, z],
            ],
        };
        let base = positions.len() as u32;
        positions.extend(corners.map(Vec3::from_array));
        triangles.push([base, base + 1, base + 2]);
        triangles.push([base, base + 2, base + 3]);
    }
    let mesh = Mesh::new(positions, triangles, None, None).unwrap();
    let scene = scene_of(vec![Shape::Mesh(mesh)]);
    let mut hits = 0;
    for a in -1..9 {
        for b in -1..9 {
            let (a, b) = (a as f32, b as f32 * 0.5);
            for dir in [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z] {
                // From outside the staircase, on grid lines and half-way between them.
                let origin = match () {
                    _ if dir.x != 0.0 => Vec3::new(-20.0 * dir.x, a, b),
                    _ if dir.y != 0.0 => Vec3::new(a, -20.0 * dir.y, b),
                    _ => Vec3::new(a, b, -20.0 * dir.z),
                };
                let ray = Ray::new(origin, dir, 0.0);
                let found = scene.intersect(&ray, f32::INFINITY).map(|h| h.surface.t);
                let every = scene
                    .intersect_brute_force(&ray, f32::INFINITY)
                    .map(|h| h.surface.t);
                assert_eq!(found, every, "from {origin} along {dir}");
                assert_eq!(scene.occluded(&ray, f32::INFINITY), every.is_some());
                hits += every.is_some() as u32;
            }
        }
    }
    // Rays from all around aimed at the squares' corners, which are the boxes' corners:
    // where the triangle test takes a hit on the corner, the rounded box test must too.
    let mut rng = Rng::new(5);
    for _ in 0..20_000 {
        let corner = Vec3::new(
            (rng.f() * 8.0).floor(),
            (rng.f() * 7.0).floor(),
            (rng.f() * 6.0).floor(),
        );
        let origin = corner - rng.dir() * rng.range(1.0, 30.0);
        let ray = Ray::new(origin, (corner - origin).normalize(), 0.0);
        let found = scene.intersect(&ray, f32::INFINITY).map(|h| h.surface.t);
        let every = scene
            .intersect_brute_force(&ray, f32::INFINITY)
            .map(|h| h.surface.t);
        assert_eq!(found, every, "from {origin} to {corner}");
        hits += every.is_some() as u32;
    }
    assert!(hits > 100, "too few hits ({hits}) to mean anything");
}
