//! No valid file exhausts the machine, and real files read as glTF says (issue 52, items 4,
//! 5 and 7): a node graph must be a tree (fan-out, cycles refused at their index; depth is
//! no limit); a mesh a hundred nodes place is built once; a quarter of a million lights
//! render in bounded memory; strips and fans, an application's attributes, animations and
//! glTF 1.0 are read, ignored or refused in one line.

// Its helpers unwrap as its tests do: a failure there fails the test.
#![allow(clippy::unwrap_used)]

mod common;

use common::{glb, stderr, under_two_gigabytes};
use raylab::scene::{Scene, load_gltf};
use std::path::Path;

/// One triangle (0,0,0), (1,0,0), (0,1,0) and a fourth vertex (1,1,0), as floats.
fn quad_bytes() -> Vec<u8> {
    [0f32, 0., 0., 1., 0., 0., 0., 1., 0., 1., 1., 0.]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect()
}

/// A glTF of one mesh (the four vertices of [`quad_bytes`], as `primitive` says) placed
/// by `nodes` (JSON), the scene's roots `roots`; `extra` adds members to the root.
fn gltf(nodes: &str, roots: &str, primitive: &str, extra: &str) -> String {
    use base64::Engine as _;
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(quad_bytes())
    );
    format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": {roots}}}],
  "nodes": {nodes},
  "meshes": [{{"primitives": [{primitive}]}}],
  "buffers": [{{"byteLength": 48, "uri": "{uri}"}}],
  "bufferViews": [{{"buffer": 0, "byteLength": 48}}],
  "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
                {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"}}]{extra}}}"#
    )
}

const TRIANGLES: &str = r#"{"attributes": {"POSITION": 0}, "indices": null}"#;

fn load(text: &str) -> Result<raylab::scene::Model, String> {
    let text = text.replace(r#", "indices": null"#, "");
    load_gltf(text.as_bytes(), "t.gltf", &|_| Err("no files".into())).map_err(|e| e.to_string())
}

#[test]
fn a_node_graph_that_is_not_a_tree_is_refused_at_its_index() {
    // Each of 40 levels lists the next node twice: 2^40 paths in a 1.5 kB file (on
    // 10fbafe it ran out of memory).
    let fan: Vec<String> = (0..40)
        .map(|i| format!(r#"{{"children": [{}, {}]}}"#, i + 1, i + 1))
        .chain([r#"{"mesh": 0}"#.to_string()])
        .collect();
    let fan = format!("[{}]", fan.join(","));
    let cases = [
        (fan.as_str(), "[0]", "nodes[0] lists nodes[1] twice"),
        (
            r#"[{"children": [2]}, {"children": [2]}, {"mesh": 0}]"#,
            "[0, 1]",
            "nodes[2] is a child of nodes[0] and again of nodes[1]",
        ),
        (
            r#"[{"children": [1]}, {"children": [0], "mesh": 0}]"#,
            "[0]",
            "is its own ancestor",
        ),
        (
            r#"[{"children": [0], "mesh": 0}]"#,
            "[0]",
            "nodes[0] lists itself as a child",
        ),
        (
            r#"[{"children": [1]}, {"mesh": 0}]"#,
            "[0, 1]",
            "scenes[0].nodes[1] is nodes[1], a child of nodes[0]: a scene lists root nodes only",
        ),
        (
            r#"[{"mesh": 0}]"#,
            "[0, 0]",
            "scenes[0].nodes lists nodes[0] twice",
        ),
    ];
    for (nodes, roots, words) in cases {
        let e = load(&gltf(nodes, roots, TRIANGLES, "")).unwrap_err();
        assert!(e.starts_with("t.gltf: invalid glTF: "), "{e}");
        assert!(e.contains(words), "expected `{words}` in: {e}");
    }
}

#[test]
fn a_chain_of_any_depth_places_its_mesh() {
    // 300 levels, each moved 0.01 along z: nothing dropped (on 10fbafe, past 65 levels
    // the mesh was left out without a word).
    let chain: Vec<String> = (0..300)
        .map(|i| {
            format!(
                r#"{{"children": [{}], "translation": [0, 0, 0.01]}}"#,
                i + 1
            )
        })
        .chain([r#"{"mesh": 0}"#.to_string()])
        .collect();
    let model = load(&gltf(
        &format!("[{}]", chain.join(",")),
        "[0]",
        TRIANGLES,
        "",
    ))
    .unwrap();
    assert_eq!(model.parts.len(), 1);
    for p in model.parts[0].mesh.positions() {
        assert!((p.z - 3.0).abs() < 1e-3, "{p}");
    }
}

#[test]
fn strips_fans_custom_attributes_and_animations_are_read_as_gltf_says() {
    for (mode, triangles) in [(5, 2), (6, 2), (4, 1)] {
        let primitive = format!(r#"{{"attributes": {{"POSITION": 0}}, "mode": {mode}}}"#);
        let model = load(&gltf(r#"[{"mesh": 0}]"#, "[0]", &primitive, "")).unwrap();
        assert_eq!(
            model.parts[0].mesh.triangle_count(),
            triangles,
            "mode {mode}"
        );
    }
    // An application's attribute (glTF: names starting with `_`) is not read.
    let custom = r#"{"attributes": {"POSITION": 0, "_TEMPERATURE": 1}}"#;
    let model = load(&gltf(r#"[{"mesh": 0}]"#, "[0]", custom, "")).unwrap();
    assert_eq!(model.parts[0].mesh.triangle_count(), 1);
    // Animations driven by KHR_animation_pointer: the still scene, and a line saying so.
    let animated = r#", "extensionsUsed": ["KHR_animation_pointer"],
      "extensionsRequired": ["KHR_animation_pointer"],
      "animations": [{"channels": [{"sampler": 0, "target": {"path": "pointer",
        "extensions": {"KHR_animation_pointer": {"pointer": "/nodes/0/translation"}}}}],
        "samplers": [{"input": 1, "output": 1}]}]"#;
    let model = load(&gltf(r#"[{"mesh": 0}]"#, "[0]", TRIANGLES, animated)).unwrap();
    assert_eq!(model.parts.len(), 1);
    assert!(
        model
            .warnings
            .iter()
            .any(|w| w.contains("KHR_animation_pointer")),
        "{:?}",
        model.warnings
    );
}

#[test]
fn gltf_1_is_refused_by_name() {
    let v1 = r#"{"asset": {"version": "1.0"}, "scene": "defaultScene",
      "scenes": {"defaultScene": {"nodes": ["node_1"]}}, "nodes": {"node_1": {"meshes": ["m"]}}}"#;
    let e = load(v1).unwrap_err();
    assert!(e.contains("is glTF 1.0, which raylab does not read"), "{e}");
    // A binary glTF 1.0 container says its version in its header.
    let mut binary = glb("{}", &[]);
    binary[4..8].copy_from_slice(&1u32.to_le_bytes());
    let e = load_gltf(&binary, "old.glb", &|_| Err("no files".into()))
        .unwrap_err()
        .to_string();
    assert!(e.contains("old.glb: is glTF 1.0"), "{e}");
}

/// A glTF grid `STEM.gltf` of `n` × `n` squares (2n² triangles) on the unit square of the
/// x–z plane, placed by `nodes` nodes side by side, its buffer in `STEM.bin` beside it.
fn grid_gltf(dir: &Path, stem: &str, n: u32, nodes: usize) {
    let mut bin = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            for v in [i as f32 / n as f32, 0.0, j as f32 / n as f32] {
                bin.extend_from_slice(&v.to_le_bytes());
            }
        }
    }
    let positions = bin.len();
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            for v in [a, a + n + 1, a + 1, a + 1, a + n + 1, a + n + 2] {
                bin.extend_from_slice(&v.to_le_bytes());
            }
        }
    }
    std::fs::write(dir.join(format!("{stem}.bin")), &bin).unwrap();
    let placed: Vec<String> = (0..nodes)
        .map(|k| {
            format!(
                r#"{{"mesh": 0, "translation": [{}, 0, 0]}}"#,
                k as f32 * 1.1
            )
        })
        .collect();
    let roots: Vec<String> = (0..nodes).map(|k| k.to_string()).collect();
    let json = format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [{}]}}],
  "nodes": [{}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
  "buffers": [{{"byteLength": {}, "uri": "{stem}.bin"}}],
  "bufferViews": [{{"buffer": 0, "byteLength": {positions}}}, {{"buffer": 0, "byteOffset": {positions}, "byteLength": {}}}],
  "accessors": [{{"bufferView": 0, "componentType": 5126, "count": {}, "type": "VEC3", "min": [0, 0, 0], "max": [1, 0, 1]}},
                {{"bufferView": 1, "componentType": 5125, "count": {}, "type": "SCALAR"}}]}}"#,
        roots.join(","),
        placed.join(","),
        bin.len(),
        bin.len() - positions,
        (n + 1) * (n + 1),
        6 * n * n,
    );
    std::fs::write(dir.join(format!("{stem}.gltf")), json).unwrap();
}

// `ulimit -v` is Linux's.
#[cfg(target_os = "linux")]
#[test]
fn a_mesh_a_hundred_nodes_place_is_built_once() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    // 1,000,000 triangles placed by 100 nodes: 100 million copied (on 10fbafe, 50 nodes
    // aborted under 4 GB); built once, they render under 2 GB.
    grid_gltf(dir, "grid", 708, 100);
    std::fs::write(
        dir.join("grid.toml"),
        "[camera]\nposition = [55, 60, 40]\nlook_at = [55, 0, 0]\n[[mesh]]\nfile = \"grid.gltf\"\n",
    )
    .unwrap();
    let o = under_two_gigabytes("render grid.toml -o g.png --size 64x36 --spp 1", dir);
    assert!(o.status.success(), "{}", stderr(&o));
    let scene = Scene::load(dir.join("grid.toml")).unwrap();
    assert_eq!(scene.object_names.len(), 100);
}

#[test]
fn an_instanced_placement_renders_as_copies_do() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    // 4 × 4 squares, 32 triangles: over the 16 a part may have and still be copied.
    grid_gltf(dir, "grid", 4, 3);
    let scene = "[camera]\nposition = [1.6, 2, 3]\nlook_at = [1.6, 0, 0.5]\n[[point_light]]\nposition = [1.6, 3, 1]\nintensity = 20\n";
    std::fs::write(
        dir.join("nodes.toml"),
        format!("{scene}[[mesh]]\nfile = \"grid.gltf\"\n"),
    )
    .unwrap();
    // The same grid from three files, each placed once by the scene file: three copies.
    let mut copies = scene.to_string();
    for k in 0..3 {
        grid_gltf(dir, &format!("one{k}"), 4, 1);
        copies += &format!(
            "[[mesh]]\nfile = \"one{k}.gltf\"\ntranslate = [{}, 0, 0]\n",
            k as f32 * 1.1
        );
    }
    std::fs::write(dir.join("copies.toml"), copies).unwrap();
    let render = |file: &str, instanced: bool| {
        let scene = Scene::load(dir.join(file)).unwrap();
        let shapes = scene.shapes.iter();
        let instances = shapes
            .filter(|s| matches!(s, raylab::geometry::Shape::Instance(_)))
            .count();
        assert_eq!(instances, if instanced { 3 } else { 0 }, "{file}");
        let params = raylab::params::Params {
            spp: 4,
            ..Default::default()
        };
        let (film, _) = raylab::render::render(&scene, &params, 96, 54, &()).unwrap();
        film.pixels().collect::<Vec<_>>()
    };
    let (a, b) = (render("nodes.toml", true), render("copies.toml", false));
    // Transforms composed in another order: the same image to float rounding.
    let worst = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (*x - *y).abs().max_element())
        .fold(0.0f32, f32::max);
    let mean = a.iter().map(|c| c.max_element()).sum::<f32>() / a.len() as f32;
    assert!(mean > 0.01, "the grids are lit: {mean}");
    assert!(worst < 1e-3, "{worst}");
}

// `ulimit -v` is Linux's.
#[cfg(target_os = "linux")]
#[test]
fn many_lights_render_in_bounded_memory() {
    let d = tempfile::tempdir().unwrap();
    let dir = d.path();
    let mut scene = String::from(
        "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 0, 0]\n[[sphere]]\ncenter = [0, 0, 0]\nradius = 1\n[[plane]]\npoint = [0, -1, 0]\nnormal = [0, 1, 0]\n",
    );
    // 40,000 point lights (on 10fbafe the waves kept a shadow ray per light and node:
    // 1.7 GB at 64 × 36, aborted here; 250,000 kept 20 GB).
    let lights = 40_000;
    assert!(lights > raylab::tracer::MAX_WAVE_LIGHTS);
    for k in 0..lights {
        let (x, z) = ((k % 200) as f32 / 20.0 - 5.0, (k / 200) as f32 / 20.0 - 5.0);
        scene += &format!("[[point_light]]\nposition = [{x}, 4, {z}]\nintensity = 0.01\n");
    }
    std::fs::write(dir.join("lights.toml"), scene).unwrap();
    let o = under_two_gigabytes("render lights.toml -o l.png --size 64x36 --spp 1", dir);
    assert!(o.status.success(), "{}", stderr(&o));
}
