//! The ray-tree inspector records exactly the tree the renderer traces.

use raylab::optics::{cos_transmitted, fresnel_exact, schlick};
use raylab::params::Params;
use raylab::scene::Scene;
use raylab::tracer::{End, RayKind, Stats, Tracer};

#[test]
fn at_the_centre_of_a_glass_sphere_the_tree_splits_by_fresnel() {
    let scene = Scene::load("glass").unwrap();
    let params = Params {
        spp: 1,
        ..scene.params.clone()
    };
    let (w, h) = (96, 54);
    let tracer = Tracer::new(&scene, &params, w, h);
    // The pixel whose pinhole ray hits the glass sphere closest to head-on.
    let glass = scene
        .object_names
        .iter()
        .position(|n| n == "glass sphere")
        .unwrap() as u32;
    let (mut best, mut best_angle) = (None, f32::INFINITY);
    for y in 0..h {
        for x in 0..w {
            let (tree, _) = tracer.inspect(x, y, 0);
            if let Some(hit) = tree.nodes[0].hit.filter(|h| h.object == glass)
                && hit.theta_i < best_angle
            {
                best_angle = hit.theta_i;
                best = Some((x, y));
            }
        }
    }
    let (x, y) = best.expect("the sphere is in view");
    assert!(best_angle < 3.0, "a pixel near the centre: {best_angle}°");
    let (tree, radiance) = tracer.inspect(x, y, 0);
    // The same radiance as the renderer's sample.
    assert_eq!(radiance, tracer.sample(x, y, 0, &mut Stats::default()));

    let root = &tree.nodes[0];
    assert_eq!(
        (root.kind, root.end, root.depth),
        (RayKind::Camera, End::Split, 0)
    );
    let hit = root.hit.unwrap();
    let (n1, n2) = hit.n1_n2.unwrap();
    assert_eq!((n1, n2), (1.0, 1.5), "air into glass");
    let cos_i = hit.theta_i.to_radians().cos();
    let (f_s, f_p, r) = fresnel_exact(cos_i, n1, n2);
    assert!(
        (hit.f_s_f_p.unwrap().0 - f_s).abs() < 1e-4 && (hit.f_s_f_p.unwrap().1 - f_p).abs() < 1e-4
    );
    assert!((hit.r_exact_schlick.unwrap().0 - r).abs() < 1e-4);
    assert!((hit.r_exact_schlick.unwrap().1 - schlick(cos_i, n1, n2)).abs() < 1e-4);
    let theta_t = cos_transmitted(cos_i, n1, n2).unwrap().acos().to_degrees();
    assert!((hit.theta_t.unwrap() - theta_t).abs() < 1e-2);
    assert!((r - 0.04).abs() < 1e-3, "near normal incidence R ≈ 4%: {r}");

    let children: Vec<_> = tree.children(0).map(|(_, n)| *n).collect();
    let reflect = children
        .iter()
        .find(|n| n.kind == RayKind::Reflect)
        .expect("a reflected child");
    let refract = children
        .iter()
        .find(|n| n.kind == RayKind::Refract)
        .expect("a refracted child");
    assert!((reflect.branch_weight - hit.r.unwrap()).abs() < 1e-6);
    assert!((refract.branch_weight - (1.0 - hit.r.unwrap())).abs() < 1e-6);
    assert!(
        (reflect.path_weight - r).abs() < 1e-4 && (refract.path_weight - (1.0 - r)).abs() < 1e-4
    );
    // The refracted ray goes on through the sphere: its child leaves glass for air.
    let (inner_id, _) = tree
        .children(0)
        .find(|(_, n)| n.kind == RayKind::Refract)
        .unwrap();
    let inner = tree.nodes[inner_id].hit.unwrap();
    assert_eq!(inner.n1_n2, Some((1.5, 1.0)), "glass out to air");
    // The parent's radiance is R·L_reflect + (1 − R)·L_refract.
    let expected =
        reflect.branch_weight * reflect.radiance + refract.branch_weight * refract.radiance;
    assert!((root.radiance - expected).abs().max_element() < 1e-5);
}

#[test]
fn the_tree_says_why_each_branch_ended() {
    // Glass spheres behind one another, cut at depth 2: misses, diffuse ends, splits,
    // depth limits, and shadow rays lit and blocked.
    let scene = Scene::load("ray-tree").unwrap();
    let params = Params {
        max_depth: 2,
        ..scene.params.clone()
    };
    let tracer = Tracer::new(&scene, &params, 96, 54);
    let mut ends = std::collections::BTreeSet::new();
    for y in (0..54).step_by(3) {
        for x in (0..96).step_by(3) {
            let (tree, _) = tracer.inspect(x, y, 0);
            for n in &tree.nodes {
                ends.insert(format!("{:?}", n.end));
                assert!(n.depth <= 3);
            }
        }
    }
    for end in ["Miss", "Absorbed", "Split", "DepthLimit", "Lit", "Occluded"] {
        assert!(ends.contains(end), "no branch ended by {end}: {ends:?}");
    }
}

#[test]
fn the_metals_scene_shows_the_sky_along_its_top_edge_not_its_softbox() {
    // The softbox lights the metals' highlights from above the frame: seen directly it
    // was a white band across the top of slides 1 and 6.
    let scene = Scene::load("metals").unwrap();
    let (w, h) = (scene.width, scene.height);
    let tracer = Tracer::new(&scene, &scene.params, w, h);
    for x in (0..w).step_by(40) {
        for sample in 0..4 {
            let (tree, _) = tracer.inspect(x, 0, sample);
            let hit = tree.nodes[0]
                .hit
                .map(|h| &scene.object_names[h.object as usize]);
            assert_eq!(hit, None, "pixel ({x}, 0), sample {sample}");
        }
    }
}
