//! glTF 2.0 models: a `.glb` converted from the bunny renders as its OBJ does, nodes place
//! meshes, materials map to raylab's, buffers come from the container, data URIs or files
//! beside, and bad files get one line naming them.
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

mod common;

use common::{fails, glb, raylab, stderr};
use raylab::material::{Material, Texture};
use raylab::math::Color;
use raylab::params::Params;
use raylab::render::render;
use raylab::scene::{Scene, load_obj};
use std::path::Path;

/// The bunny's triangles and normals as a `.glb`: one mesh, no material, one node.
fn bunny_glb() -> Vec<u8> {
    let obj = std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/models/bunny.obj"))
        .unwrap();
    let parts = load_obj(&obj, "bunny.obj", &|_| None).unwrap().parts;
    assert_eq!(parts.len(), 1);
    let mesh = &parts[0].mesh;
    let (positions, normals, indices) = (mesh.positions(), mesh.normals().unwrap(), mesh.indices());
    let mut bin = Vec::new();
    for p in positions {
        for c in [p.x, p.y, p.z] {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    for n in normals {
        for c in [n.x, n.y, n.z] {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    for t in indices {
        for i in t {
            bin.extend_from_slice(&i.to_le_bytes());
        }
    }
    let (lo, hi) = positions
        .iter()
        .fold((positions[0], positions[0]), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
    let n = positions.len();
    let json = format!(
        r#"{{"asset": {{"version": "2.0"}},
  "scene": 0, "scenes": [{{"nodes": [0]}}], "nodes": [{{"mesh": 0, "name": "bunny"}}],
  "meshes": [{{"name": "bunny", "primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1}}, "indices": 2}}]}}],
  "buffers": [{{"byteLength": {len}}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": {pl}}},
    {{"buffer": 0, "byteOffset": {pl}, "byteLength": {pl}}},
    {{"buffer": 0, "byteOffset": {il_at}, "byteLength": {il}}}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": {n}, "type": "VEC3", "min": [{}, {}, {}], "max": [{}, {}, {}]}},
    {{"bufferView": 1, "componentType": 5126, "count": {n}, "type": "VEC3"}},
    {{"bufferView": 2, "componentType": 5125, "count": {ic}, "type": "SCALAR"}}]}}"#,
        lo.x,
        lo.y,
        lo.z,
        hi.x,
        hi.y,
        hi.z,
        len = bin.len(),
        pl = n * 12,
        il_at = n * 24,
        il = indices.len() * 12,
        ic = indices.len() * 3,
    );
    glb(&json, &bin)
}

#[test]
fn the_bunny_as_glb_renders_as_its_obj_does() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("bunny.glb"), bunny_glb()).unwrap();
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/models/bunny.obj"),
        d.join("bunny.obj"),
    )
    .unwrap();
    // Opened on its own: the same framing, floor and light as an OBJ gets.
    let from_glb = Scene::load(d.join("bunny.glb")).unwrap();
    let from_obj = Scene::load(d.join("bunny.obj")).unwrap();
    assert_eq!(from_glb.camera, from_obj.camera);
    let params = Params {
        spp: 2,
        ..from_obj.params.clone()
    };
    let (a, _) = render(&from_glb, &params, 64, 48, &()).unwrap();
    let (b, _) = render(&from_obj, &params, 64, 48, &()).unwrap();
    // The same triangles; the normals went through one more normalisation on the way
    // (the OBJ's loader normalises them, the .glb carries those, glTF's loader
    // normalises again), which moves them by an ulp or so: every pixel within 1e-5
    // of the OBJ's, relative.
    let worst = a
        .pixels()
        .zip(b.pixels())
        .map(|(x, y)| ((x - y).abs() / y.abs().max(raylab::math::Color::splat(1e-3))).max_element())
        .fold(0.0f32, f32::max);
    assert!(
        worst < 1e-5,
        "the glTF bunny's image differs from the OBJ's by {worst}"
    );
    // And from the command line, into a scene file's [[mesh]] too.
    let o = raylab(
        &[
            "render",
            "bunny.glb",
            "--size",
            "32x24",
            "--spp",
            "1",
            "-o",
            "b.png",
        ],
        d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    std::fs::write(
        d.join("s.toml"),
        "[camera]\nposition = [0, 1, 8]\nlook_at = [0, 1, 0]\n[[mesh]]\nfile = \"bunny.glb\"\nscale = 0.5\n",
    )
    .unwrap();
    let o = raylab(
        &[
            "render", "s.toml", "--size", "32x24", "--spp", "1", "-o", "s.png",
        ],
        d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
}

/// A glTF JSON file of one triangle per material, its buffer a base64 data URI: the node
/// tree places them (a parent's translation and a child's scale compose).
fn triangles_gltf(buffer_uri: &str) -> String {
    format!(
        r#"{{"asset": {{"version": "2.0"}},
  "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior"],
  "scene": 0, "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"translation": [10, 0, 0], "children": [1, 2, 3, 4, 5]}},
            {{"mesh": 0, "scale": [2, 2, 2]}}, {{"mesh": 1}}, {{"mesh": 2}}, {{"mesh": 3}}, {{"mesh": 4}}],
  "materials": [
    {{"name": "Polished gold", "pbrMetallicRoughness": {{"metallicFactor": 1, "roughnessFactor": 0}}}},
    {{"name": "water", "pbrMetallicRoughness": {{"metallicFactor": 0, "roughnessFactor": 0}},
      "extensions": {{"KHR_materials_transmission": {{"transmissionFactor": 1}}, "KHR_materials_ior": {{"ior": 1.33}}}}}},
    {{"name": "lamp", "emissiveFactor": [1, 0.5, 0.25]}},
    {{"name": "clay", "pbrMetallicRoughness": {{"baseColorFactor": [0.5, 0.25, 0.125, 1], "metallicFactor": 0}}}},
    {{"name": "frosted", "pbrMetallicRoughness": {{"metallicFactor": 0, "roughnessFactor": 0.5}},
      "extensions": {{"KHR_materials_transmission": {{"transmissionFactor": 1}}}}}}],
  "meshes": [
    {{"name": "gold", "primitives": [{{"attributes": {{"POSITION": 0}}, "material": 0}}]}},
    {{"name": "water", "primitives": [{{"attributes": {{"POSITION": 0}}, "material": 1}}]}},
    {{"name": "lamp", "primitives": [{{"attributes": {{"POSITION": 0}}, "material": 2}}]}},
    {{"name": "clay", "primitives": [{{"attributes": {{"POSITION": 0}}, "material": 3}}]}},
    {{"name": "frosted", "primitives": [{{"attributes": {{"POSITION": 0}}, "material": 4}}]}}],
  "buffers": [{{"byteLength": 36, "uri": "{buffer_uri}"}}],
  "bufferViews": [{{"buffer": 0, "byteLength": 36}}],
  "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}}]}}"#
    )
}

/// One triangle (0,0,0), (1,0,0), (0,1,0) as little-endian floats.
fn triangle_bytes() -> Vec<u8> {
    [0f32, 0., 0., 1., 0., 0., 0., 1., 0.]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect()
}

fn data_uri(bytes: &[u8]) -> String {
    use base64::Engine as _;
    format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(bytes)
    )
}

#[test]
fn nodes_place_meshes_and_materials_map_to_the_closest_kind() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("t.gltf"),
        triangles_gltf(&data_uri(&triangle_bytes())),
    )
    .unwrap();
    let scene = Scene::load(d.join("t.gltf")).unwrap();
    let material_of = |name: &str| {
        let i = scene
            .object_names
            .iter()
            .position(|n| n.ends_with(name))
            .unwrap_or_else(|| panic!("no object {name}: {:?}", scene.object_names));
        &scene.materials[scene.object_materials[i] as usize]
    };
    let gold = raylab::material::find_metal("gold").unwrap();
    assert!(
        matches!(material_of("gold"), Material::Conductor(c) if c.eta == gold.eta() && c.exponent.is_none()),
        "{:?}",
        material_of("gold")
    );
    assert!(
        matches!(material_of("water"), Material::Dielectric(g) if g.ior == 1.33 && g.roughness == 0.0),
        "{:?}",
        material_of("water")
    );
    // Rough transmission is rough glass, its GGX α the square of glTF's roughness.
    assert!(
        matches!(material_of("frosted"), Material::Dielectric(g) if g.ior == 1.5 && g.roughness == 0.25),
        "{:?}",
        material_of("frosted")
    );
    // An emitting material glows over its base colour (glTF's default, white).
    assert!(
        matches!(material_of("lamp"), Material::Diffuse(d)
            if d.albedo == Texture::Solid(Color::ONE)
                && d.emission == Some(Texture::Solid(Color::new(1.0, 0.5, 0.25)))),
        "{:?}",
        material_of("lamp")
    );
    assert!(matches!(material_of("clay"), Material::Diffuse(_)));
    // The model is framed: the camera looks at the middle of its bounds, which the node
    // tree put at x from 10 (every mesh) to 12 (the gold one, scaled 2).
    let look = scene.camera.look_at;
    assert!((look.x - 11.0).abs() < 1e-4, "{look}");
    assert!((look.y - 1.0).abs() < 1e-4, "{look}");
}

#[test]
fn a_buffer_beside_the_file_is_read_and_bad_files_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("tri.bin"), triangle_bytes()).unwrap();
    std::fs::write(d.join("t.gltf"), triangles_gltf("tri.bin")).unwrap();
    let o = raylab(
        &[
            "render", "t.gltf", "--size", "16x9", "--spp", "1", "-o", "t.png",
        ],
        d,
    );
    assert!(o.status.success(), "{}", stderr(&o));

    // The buffer missing: the file and the buffer are named.
    std::fs::write(d.join("gone.gltf"), triangles_gltf("missing.bin")).unwrap();
    let err = fails(&["render", "gone.gltf", "-o", "x.png"], d, "missing.bin");
    assert!(err.contains("gone.gltf"), "{err}");
    // Broken JSON: its line and column.
    std::fs::write(
        d.join("bad.gltf"),
        "{\"asset\": {\"version\": \"2.0\"},\n  \"nodes\": [}\n",
    )
    .unwrap();
    fails(&["render", "bad.gltf", "-o", "x.png"], d, "bad.gltf:2:");
    // A buffer shorter than it says.
    let short = triangles_gltf(&data_uri(&triangle_bytes()[..24]));
    std::fs::write(d.join("short.gltf"), short).unwrap();
    fails(
        &["render", "short.gltf", "-o", "x.png"],
        d,
        "fewer than the 36",
    );
    // A triangle naming a vertex past the last: the mesh is named.
    let mut bytes = triangle_bytes();
    for i in [0u32, 1, 7] {
        bytes.extend_from_slice(&i.to_le_bytes());
    }
    let past = format!(
        r#"{{"asset": {{"version": "2.0"}},
  "meshes": [{{"name": "torn", "primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
  "buffers": [{{"byteLength": 48, "uri": "{}"}}],
  "bufferViews": [{{"buffer": 0, "byteLength": 36}}, {{"buffer": 0, "byteOffset": 36, "byteLength": 12}}],
  "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
                {{"bufferView": 1, "componentType": 5125, "count": 3, "type": "SCALAR"}}]}}"#,
        data_uri(&bytes)
    );
    std::fs::write(d.join("past.gltf"), past).unwrap();
    let err = fails(&["render", "past.gltf", "-o", "x.png"], d, "mesh `torn`");
    assert!(err.contains("past.gltf"), "{err}");
    // Not glTF at all.
    std::fs::write(d.join("junk.glb"), b"glTF\x02\0\0\0\xff\xff").unwrap();
    fails(&["render", "junk.glb", "-o", "x.png"], d, "junk.glb");
    // In a scene file, the [[mesh]] line is named.
    std::fs::write(
        d.join("s.toml"),
        "[camera]\nposition = [0, 1, 8]\nlook_at = [0, 1, 0]\n[[mesh]]\nfile = \"gone.gltf\"\n",
    )
    .unwrap();
    fails(&["render", "s.toml", "-o", "x.png"], d, "missing.bin");
    std::fs::write(
        d.join("p.toml"),
        "[camera]\nposition = [0, 1, 8]\nlook_at = [0, 1, 0]\n[[mesh]]\nfile = \"bunny.ply\"\n",
    )
    .unwrap();
    fails(
        &["render", "p.toml", "-o", "x.png"],
        d,
        "p.toml:5:8: unsupported model format `.ply`",
    );
    assert!(!d.join("x.png").exists());
}
