//! The section view and the interface workbench: the lecture's 2D diagrams agree with the
//! ray tree the tracer records, with Snell's law, and with `raylab fresnel`'s numbers.
// Its helpers unwrap as its tests do: a failure there fails the test.
#![allow(clippy::unwrap_used)]

use glam::Vec2;
use raylab::optics::{critical_angle, fresnel_table};
use raylab::params::Params;
use raylab::render::{INCIDENCE_BAND, incidence_band, incidence_map};
use raylab::scene::Scene;
use raylab::section::{Item, Room, SectionPlane, Theme, Workbench, section, text_size, to_svg};
use raylab::tracer::{End, RayKind, RayTree, Tracer};

const SIZE: (u32, u32) = (192, 108);
const FIGURE: (u32, u32) = (960, 720);

/// The tree of sample 0 of the pixel of the glass scene whose camera ray meets the glass
/// sphere at the angle nearest `angle`, with the scene and tracer it came from.
fn glass_tree(angle: f32) -> (Scene, Params, RayTree, (u32, u32)) {
    let scene = Scene::load("glass").unwrap();
    let params = scene.params.clone();
    let tracer = Tracer::new(&scene, &params, SIZE.0, SIZE.1);
    let glass = scene
        .object_names
        .iter()
        .position(|n| n == "glass sphere")
        .unwrap() as u32;
    let mut best = (f32::INFINITY, (0, 0));
    for y in 0..SIZE.1 {
        for x in 0..SIZE.0 {
            let (tree, _) = tracer.inspect(x, y, 0);
            if let Some(h) = tree.nodes[0].hit.filter(|h| h.object == glass) {
                let off = (h.theta_i - angle).abs();
                if off < best.0 {
                    best = (off, (x, y));
                }
            }
        }
    }
    let (x, y) = best.1;
    let (tree, _) = tracer.inspect(x, y, 0);
    (scene, params, tree, (x, y))
}

fn canvas() -> Room {
    Room {
        size: Vec2::new(FIGURE.0 as f32, FIGURE.1 as f32),
        text: text_size(FIGURE.0, FIGURE.1),
        zoom: 1.0,
        titled: true,
    }
}

#[test]
fn the_section_of_a_pixel_through_the_glass_sphere_is_its_tree_ray_for_ray() {
    let (scene, params, tree, pixel) = glass_tree(40.0);
    let tracer = Tracer::new(&scene, &params, SIZE.0, SIZE.1);
    let diagram = section(&scene, tracer.frame(), &tree, pixel, canvas()).unwrap();
    let plane = SectionPlane::of_tree(&tree, raylab::math::Vec3::Y).unwrap();
    // The plane holds the camera ray and the first normal; its frame is orthonormal.
    let root = &tree.nodes[0];
    let hit = root.hit.unwrap();
    assert!(plane.normal.dot(root.ray.dir).abs() < 1e-5);
    assert!(plane.normal.dot(hit.normal).abs() < 1e-5);
    assert!((plane.x.dot(plane.y)).abs() < 1e-6 && (plane.x.length() - 1.0).abs() < 1e-6);
    let rays: Vec<_> = diagram.rays().collect();
    assert_eq!(rays.len(), tree.nodes.len(), "one line per ray of the tree");
    let mut in_plane = 0;
    for (i, (r, n)) in rays.iter().zip(&tree.nodes).enumerate() {
        assert_eq!(r.node, Some(i));
        assert_eq!(r.kind, n.kind);
        // The 2D points are the 3D ones in the plane's frame.
        if !r.projected {
            assert!(
                plane.to_space(r.a).distance(n.ray.origin) < 1e-4,
                "ray {i}'s start"
            );
            if let Some(h) = n.hit {
                assert!(
                    plane.to_space(r.b).distance(h.point) < 1e-4,
                    "ray {i}'s hit"
                );
                in_plane += 1;
            }
        }
        // A sphere's tree stays in the plane through its centre: only shadow rays to the
        // light (off the plane) are drawn projected.
        if n.kind != RayKind::Shadow {
            assert!(!r.projected, "ray {i} ({:?}) lies in the plane", n.kind);
        }
    }
    assert!(
        in_plane >= 3,
        "the camera ray, and in and out of the glass: {in_plane}"
    );
    // Widths by weight: the refracted child carries 1 − R, the reflected R.
    let children: Vec<_> = tree.children(0).collect();
    for (id, child) in children {
        let r = rays[id];
        assert_eq!(r.weight, child.path_weight);
    }
    let r = hit.r.unwrap();
    assert!(r > 0.0 && r < 0.2);
}

/// The numbers in `text` after `name = `, before the first character that is not part
/// of a number.
fn value(text: &str, name: &str) -> Option<f32> {
    let start = text.find(&format!("{name} = "))? + name.len() + 3;
    let number: String = text[start..]
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.' || *c == '-')
        .collect();
    number.parse().ok()
}

#[test]
fn the_svgs_labelled_angles_satisfy_snells_law() {
    let (scene, params, tree, pixel) = glass_tree(40.0);
    let tracer = Tracer::new(&scene, &params, SIZE.0, SIZE.1);
    let diagram = section(&scene, tracer.frame(), &tree, pixel, canvas()).unwrap();
    let svg = to_svg(&diagram, FIGURE.0, FIGURE.1, Theme::Light);
    let mut checked = 0;
    for group in svg.split("<g class=\"interface\"").skip(1) {
        let group = &group[..group.find("</g>").unwrap()];
        let text: String = group
            .split("<text")
            .skip(1)
            .map(|t| &t[t.find('>').unwrap() + 1..t.find("</text>").unwrap()])
            .collect::<Vec<_>>()
            .join("; ");
        let (Some(t1), Some(t2), Some(n1), Some(n2)) = (
            value(&text, "θi"),
            value(&text, "θt"),
            value(&text, "η1"),
            value(&text, "η2"),
        ) else {
            continue;
        };
        // Each angle is written to 0.1°: θt is off by up to 0.05° itself, and by up to
        // 0.05° times dθt/dθi = η1 cos θi / (η2 cos θt) through the written θi.
        let (r1, r2) = (t1.to_radians(), t2.to_radians());
        let from_snell = (n1 * r1.sin() / n2).asin().to_degrees();
        let tolerance = 0.05 + 0.05 * (n1 * r1.cos() / (n2 * r2.cos())) + 1e-3;
        assert!(
            (from_snell - t2).abs() <= tolerance,
            "{text}: η1 sin θi / η2 gives θt = {from_snell:.3}°"
        );
        assert!(text.contains('°'), "{text}");
        checked += 1;
    }
    assert!(
        checked >= 2,
        "into and out of the sphere at least: {checked}\n{svg}"
    );
}

#[test]
fn the_workbench_shows_raylab_fresnels_numbers_at_every_angle() {
    for (n1, n2) in [(1.0, 1.5), (1.5, 1.0), (1.33, 1.0), (1.0, 2.42)] {
        for row in fresnel_table(n1, n2, 1.0) {
            if row.theta_i > raylab::section::MAX_ANGLE {
                continue;
            }
            let bench = Workbench {
                n1,
                n2,
                theta_i: row.theta_i,
                roughness: 0.0,
            };
            assert_eq!(bench.row(), row, "{n1} → {n2} at {}°", row.theta_i);
            let notes = bench.diagram().notes.join("\n");
            let r = value(&notes, "R").unwrap();
            assert!((r - row.r_exact).abs() <= 5e-5, "{notes}");
            let f_s = value(&notes, "F_s").unwrap();
            assert!((f_s - row.f_s).abs() <= 5e-5, "{notes}");
        }
    }
}

#[test]
fn total_internal_reflection_appears_exactly_past_the_critical_angle() {
    let (n1, n2) = (1.5, 1.0);
    let critical = critical_angle(n1, n2).unwrap().to_degrees();
    let refracted = |theta_i: f32| {
        let d = Workbench {
            n1,
            n2,
            theta_i,
            roughness: 0.0,
        }
        .diagram();
        let ray = d.rays().any(|r| r.kind == RayKind::Refract);
        let label = d
            .labels
            .iter()
            .any(|l| l.text == "total internal reflection");
        assert_ne!(ray, label, "a refracted ray or the words, never both");
        ray
    };
    assert!(refracted(critical - 0.1));
    assert!(!refracted(critical + 0.1));
    // Into the denser side there is no critical angle: always a refracted ray.
    let into = Workbench {
        n1: 1.0,
        n2: 1.5,
        theta_i: 89.0,
        roughness: 0.0,
    };
    assert!(into.diagram().rays().any(|r| r.kind == RayKind::Refract));
    assert_eq!(into.critical_angle(), None);
    assert!((into.swapped().critical_angle().unwrap() - critical).abs() < 1e-4);
}

#[test]
fn the_workbench_draws_widths_r_and_one_minus_r() {
    let bench = Workbench {
        n1: 1.0,
        n2: 1.5,
        theta_i: 60.0,
        roughness: 0.0,
    };
    let row = bench.row();
    let d = bench.diagram();
    let weight = |kind| d.rays().find(|r| r.kind == kind).unwrap().weight;
    assert_eq!(weight(RayKind::Reflect), row.r_exact);
    assert_eq!(weight(RayKind::Refract), 1.0 - row.r_exact);
    let arcs = d
        .items
        .iter()
        .filter(|i| matches!(i, Item::Arc { .. }))
        .count();
    assert_eq!(arcs, 3, "θi, θr and θt");
}

#[test]
fn the_outlined_pixels_are_those_the_tracer_records_within_the_band() {
    let scene = Scene::load("glass").unwrap();
    let params = scene.params.clone();
    let (w, h) = (96, 54);
    let map = incidence_map(&scene, &scene.camera, &params, w, h);
    let tracer = Tracer::new(&scene, &params, w, h);
    for angle in [20.0, 41.8, 70.0] {
        let band = incidence_band(&map, angle);
        let mut outlined = 0;
        for y in 0..h {
            for x in 0..w {
                let (tree, _) = tracer.inspect(x, y, 0);
                let recorded = tree.nodes[0]
                    .hit
                    .filter(|h| h.n1_n2.is_some() && tree.nodes[0].end != End::LightHit)
                    .map(|h| h.theta_i);
                assert_eq!(map[(y * w + x) as usize], recorded, "pixel ({x}, {y})");
                let within = recorded.is_some_and(|t| (t - angle).abs() <= INCIDENCE_BAND);
                assert_eq!(band[(y * w + x) as usize], within);
                outlined += within as usize;
            }
        }
        assert!(outlined > 0, "the sphere meets {angle}° somewhere");
    }
}
