//! A glTF file's scene as its file says: its camera (with its aspect ratio and field of
//! view), its KHR_lights_punctual point and spot lights and its base-colour textures,
//! checked pixel by pixel against the closed form of a diffuse floor under a point light.
// Its helpers unwrap as its tests do: a failure there fails the test (clippy.toml allows
// unwrap in #[test] functions only).
#![allow(clippy::unwrap_used)]

mod common;

use common::glb;
use glam::Vec2;
use raylab::light::LightShape;
use raylab::material::{Material, Texture};
use raylab::math::{Color, Vec3};
use raylab::params::{Params, Transport};
use raylab::render::render;
use raylab::scene::Scene;
use serde_json::{Value, json};
use std::f32::consts::PI;
use std::path::Path;

/// A model of one 4 × 4 floor quad on y = 0 (u = (x + 2)/4, v = (z + 2)/4) in `material`,
/// with `image` (a PNG or JPEG) in the binary chunk as texture 0 if given, and more nodes
/// (cameras, lights) beside the floor's.
struct Floor {
    material: Value,
    image: Option<Vec<u8>>,
    sampler: Value,
    nodes: Vec<Value>,
    cameras: Vec<Value>,
    lights: Vec<Value>,
}

impl Floor {
    fn new(material: Value) -> Floor {
        Floor {
            material,
            image: None,
            sampler: json!({}),
            nodes: Vec::new(),
            cameras: Vec::new(),
            lights: Vec::new(),
        }
    }

    /// The glTF JSON and its binary buffer (to go in a .glb, or a data URI).
    fn json_and_bin(&self) -> (Value, Vec<u8>) {
        let corners = [[-2f32, 0., -2.], [2., 0., -2.], [2., 0., 2.], [-2., 0., 2.]];
        let mut bin: Vec<u8> = Vec::new();
        let floats = |values: &mut dyn Iterator<Item = f32>, bin: &mut Vec<u8>| {
            for v in values {
                bin.extend_from_slice(&v.to_le_bytes());
            }
        };
        floats(&mut corners.iter().flatten().copied(), &mut bin);
        floats(&mut [0f32, 1., 0.].repeat(4).into_iter(), &mut bin);
        let uv = corners
            .iter()
            .flat_map(|c| [(c[0] + 2.) / 4., (c[2] + 2.) / 4.]);
        floats(&mut uv.collect::<Vec<_>>().into_iter(), &mut bin);
        // Counter-clockwise seen from above: the faces' normals are +y.
        for i in [0u32, 3, 2, 0, 2, 1] {
            bin.extend_from_slice(&i.to_le_bytes());
        }
        let mut views = vec![
            json!({"buffer": 0, "byteOffset": 0, "byteLength": 48}),
            json!({"buffer": 0, "byteOffset": 48, "byteLength": 48}),
            json!({"buffer": 0, "byteOffset": 96, "byteLength": 32}),
            json!({"buffer": 0, "byteOffset": 128, "byteLength": 24}),
        ];
        let mut gltf = json!({
            "asset": {"version": "2.0"},
            "scene": 0,
            "meshes": [{"name": "floor", "primitives": [{
                "attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                "indices": 3, "material": 0}]}],
            "materials": [self.material],
            "accessors": [
                {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                 "min": [-2, 0, -2], "max": [2, 0, 2]},
                {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
                {"bufferView": 3, "componentType": 5125, "count": 6, "type": "SCALAR"}],
        });
        if let Some(image) = &self.image {
            views.push(json!({"buffer": 0, "byteOffset": bin.len(), "byteLength": image.len()}));
            bin.extend_from_slice(image);
            gltf["images"] = json!([{"bufferView": 4, "mimeType": "image/png"}]);
            gltf["samplers"] = json!([self.sampler]);
            gltf["textures"] = json!([{"source": 0, "sampler": 0}]);
        }
        let mut nodes = vec![json!({"mesh": 0})];
        nodes.extend(self.nodes.iter().cloned());
        gltf["scenes"] = json!([{"nodes": (0..nodes.len()).collect::<Vec<_>>()}]);
        gltf["nodes"] = Value::Array(nodes);
        gltf["bufferViews"] = Value::Array(views);
        gltf["buffers"] = json!([{"byteLength": bin.len()}]);
        if !self.cameras.is_empty() {
            gltf["cameras"] = Value::Array(self.cameras.clone());
        }
        if !self.lights.is_empty() {
            gltf["extensionsUsed"] = json!(["KHR_lights_punctual"]);
            gltf["extensions"] = json!({"KHR_lights_punctual": {"lights": self.lights}});
        }
        (gltf, bin)
    }

    /// The model as a `.glb` written to `path`.
    fn write_glb(&self, path: &Path) {
        let (json, bin) = self.json_and_bin();
        std::fs::write(path, glb(&json.to_string(), &bin)).unwrap();
    }
}

/// The rotation that turns a node's −z (where glTF cameras look and spots shine) to −y,
/// as a glTF quaternion [x, y, z, w]: −90° about x. Its +y turns to −z.
fn looking_down() -> Value {
    let h = std::f32::consts::FRAC_1_SQRT_2;
    json!([-h, 0.0, 0.0, h])
}

/// `rgb` (8-bit sRGB, `width` × `height`, row by row from the top) as a PNG or a JPEG.
fn picture(width: u32, height: u32, rgb: Vec<u8>, format: image::ImageFormat) -> Vec<u8> {
    let img = image::RgbImage::from_raw(width, height, rgb).unwrap();
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, format).unwrap();
    out.into_inner()
}

/// sRGB byte to linear, by the sRGB curve.
fn linear(byte: u8) -> f32 {
    let c = byte as f32 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Renders `scene` at `width` × `height` with the lecture's tracer (point lights and the
/// ambient term, no noise but the pixel's own area) and checks the pixels that see the
/// floor at each of `points` against `radiance`, the closed form of the light leaving the
/// floor at a point, averaged over the pixel's area (8 × 8 points of it).
fn check_floor(
    scene: &Scene,
    (width, height): (u32, u32),
    points: &[Vec3],
    radiance: &dyn Fn(Vec3) -> Color,
) {
    let params = Params {
        spp: 64,
        transport: Transport::Whitted,
        ..scene.params.clone()
    };
    let (film, _) = render(scene, &params, width, height, &()).unwrap();
    let frame = scene.camera.pinhole(width as f32 / height as f32);
    for &p in points {
        let at = frame.project(p).unwrap();
        let (x, y) = ((at.x * width as f32) as u32, (at.y * height as f32) as u32);
        let mut expected = Color::ZERO;
        for k in 0..64 {
            let film = Vec2::new(
                (x as f32 + (k % 8) as f32 / 8.0 + 1.0 / 16.0) / width as f32,
                (y as f32 + (k / 8) as f32 / 8.0 + 1.0 / 16.0) / height as f32,
            );
            let ray = frame.ray(film, Vec2::ZERO, 0.0);
            let on_floor = ray.origin + ray.dir * (-ray.origin.y / ray.dir.y);
            expected += radiance(on_floor) / 64.0;
        }
        let got = film.pixel(x, y);
        let error = ((got - expected).abs() / expected.max(Color::splat(1e-3))).max_element();
        assert!(
            error < 0.01,
            "pixel ({x}, {y}) seeing {p}: {got} where the closed form gives {expected}"
        );
    }
}

/// The ambient radiance raylab puts around a model it shows.
const AMBIENT: f32 = 0.05;

#[test]
fn a_gltf_camera_point_light_and_texture_render_the_floor_as_the_file_says() {
    let dir = tempfile::tempdir().unwrap();
    // Two texels, red and blue, clamped at the edges: u < 0.25 is red, u > 0.75 blue,
    // and between them the texels blend linearly.
    let mut floor = Floor::new(json!({"name": "tiles", "pbrMetallicRoughness": {
        "baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0,
        "baseColorTexture": {"index": 0}}}));
    let (red, blue) = ([230u8, 20, 10], [10u8, 40, 200]);
    floor.image = Some(picture(2, 1, [red, blue].concat(), image::ImageFormat::Png));
    floor.sampler = json!({"wrapS": 33071, "wrapT": 33071});
    // The camera 6 above the floor, looking down with −z at the image's top; 60° high,
    // 3:2.
    floor.cameras = vec![json!({"name": "top", "type": "perspective",
        "perspective": {"yfov": PI / 3.0, "aspectRatio": 1.5, "znear": 0.1}})];
    floor.lights = vec![json!({"name": "bulb", "type": "point",
        "color": [1.0, 0.8, 0.6], "intensity": 12.0, "range": 3.0})];
    floor.nodes = vec![
        json!({"camera": 0, "translation": [0, 6, 0], "rotation": looking_down()}),
        json!({"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0.5, 2, 0]}),
    ];
    let path = dir.path().join("tiles.glb");
    floor.write_glb(&path);
    let scene = Scene::load(&path).unwrap();

    // The file's camera, and an image of its shape with as many pixels as 960 × 540.
    let camera = &scene.camera;
    assert!((camera.position - Vec3::new(0.0, 6.0, 0.0)).length() < 1e-5);
    let forward = (camera.look_at - camera.position).normalize();
    assert!((forward - Vec3::NEG_Y).length() < 1e-5, "{forward}");
    assert!((camera.up - Vec3::NEG_Z).length() < 1e-5, "{}", camera.up);
    assert!((camera.fov_deg - 60.0).abs() < 1e-4);
    assert_eq!((scene.width, scene.height), (882, 588));
    // The file's light, not the one raylab puts over a model that has none.
    assert_eq!(scene.lights.len(), 1);

    // E = I cos θ / d² at the floor, L = a(u)/π E + a(u) × ambient; range is not applied
    // (the floor's far corners are beyond it and still lit).
    let light = Vec3::new(0.5, 2.0, 0.0);
    let intensity = Color::new(1.0, 0.8, 0.6) * 12.0;
    let texel = |t: [u8; 3]| Color::new(linear(t[0]), linear(t[1]), linear(t[2]));
    let albedo = |u: f32| {
        let s = ((u - 0.25) / 0.5).clamp(0.0, 1.0);
        (texel(red) * (1.0 - s) + texel(blue) * s) * 0.8
    };
    let radiance = |p: Vec3| {
        let to = light - p;
        let d = to.length();
        let irradiance = intensity * (to.y / d) / (d * d);
        albedo((p.x + 2.0) / 4.0) * (irradiance / PI + Color::splat(AMBIENT))
    };
    let points = [
        Vec3::new(-1.6, 0.0, 0.4),
        Vec3::new(0.0, 0.0, -0.3),
        Vec3::new(1.6, 0.0, 1.5),
        Vec3::new(-1.8, 0.0, -1.8),
    ];
    check_floor(&scene, (90, 60), &points, &radiance);
}

#[test]
fn a_gltf_spot_lights_its_cone_and_leaves_the_rest_to_the_ambient() {
    let dir = tempfile::tempdir().unwrap();
    let mut floor = Floor::new(json!({"pbrMetallicRoughness": {
        "baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0}}));
    floor.cameras = vec![json!({"type": "perspective",
        "perspective": {"yfov": 1.0, "aspectRatio": 1.0, "znear": 0.1}})];
    // 2 above the floor, shining down: full within 20°, dark beyond 30°.
    let (inner, outer) = (20f32.to_radians(), 30f32.to_radians());
    floor.lights = vec![
        json!({"type": "spot", "color": [1.0, 0.5, 0.25], "intensity": 10.0,
        "spot": {"innerConeAngle": inner, "outerConeAngle": outer}}),
    ];
    floor.nodes = vec![
        json!({"camera": 0, "translation": [0, 5, 0], "rotation": looking_down()}),
        json!({"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 2, 0],
            "rotation": looking_down()}),
    ];
    let path = dir.path().join("spot.glb");
    floor.write_glb(&path);
    let scene = Scene::load(&path).unwrap();
    assert_eq!((scene.width, scene.height), (720, 720));
    let intensity = Color::new(1.0, 0.5, 0.25) * 10.0;
    let radiance = |p: Vec3| {
        let to = Vec3::new(0.0, 2.0, 0.0) - p;
        let d = to.length();
        let cos = to.y / d;
        // KHR_lights_punctual's falloff: t², t = (cos θ − cos θ_o)/(cos θ_i − cos θ_o).
        let t = ((cos - outer.cos()) / (inner.cos() - outer.cos())).clamp(0.0, 1.0);
        0.5 * (intensity * t * t * cos / (d * d) / PI + Color::splat(AMBIENT))
    };
    // Inside the inner cone, in the falloff, and outside the cone (ambient alone).
    let points =
        [10f32, 24.0, 27.0, 40.0].map(|deg| Vec3::new(2.0 * deg.to_radians().tan(), 0.0, 0.3));
    check_floor(&scene, (64, 64), &points, &radiance);
}

#[test]
fn an_emission_map_glows_over_the_base_colour_which_is_lit_where_the_map_is_dark() {
    // glTF adds emission to the base: where the emission map is black the floor is its base
    // colour, lit; elsewhere the map's glow (× factor × strength) is added. Its metallic
    // factor of 1 is not kept (raylab's glowing surfaces are diffuse).
    let mut floor = Floor::new(json!({"name": "screen",
        "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.6, 0.7, 1]},
        "emissiveFactor": [1.0, 0.5, 1.0], "emissiveTexture": {"index": 0},
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2.0}}}));
    let (dark, glow) = ([0u8, 0, 0], [200u8, 120, 40]);
    floor.image = Some(picture(
        2,
        1,
        [dark, glow].concat(),
        image::ImageFormat::Png,
    ));
    floor.sampler = json!({"wrapS": 33071, "wrapT": 33071});
    floor.cameras = vec![json!({"type": "perspective",
        "perspective": {"yfov": PI / 3.0, "aspectRatio": 1.5, "znear": 0.1}})];
    floor.lights = vec![json!({"type": "point", "intensity": 8.0})];
    floor.nodes = vec![
        json!({"camera": 0, "translation": [0, 6, 0], "rotation": looking_down()}),
        json!({"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 2, 0]}),
    ];
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("screen.glb");
    floor.write_glb(&path);
    let scene = Scene::load(&path).unwrap();
    let base = Color::new(0.5, 0.6, 0.7);
    let texel = |t: [u8; 3]| Color::new(linear(t[0]), linear(t[1]), linear(t[2]));
    let emission = |u: f32| {
        let s = ((u - 0.25) / 0.5).clamp(0.0, 1.0);
        (texel(dark) * (1.0 - s) + texel(glow) * s) * Color::new(1.0, 0.5, 1.0) * 2.0
    };
    let radiance = |p: Vec3| {
        let to = Vec3::new(0.0, 2.0, 0.0) - p;
        let d = to.length();
        let irradiance = 8.0 * (to.y / d) / (d * d);
        base * (Color::splat(irradiance / PI) + Color::splat(AMBIENT)) + emission((p.x + 2.0) / 4.0)
    };
    // Where the map is black (u < 0.25), in its blend, and where it glows (u > 0.75).
    let points = [
        Vec3::new(-1.6, 0.0, 0.4),
        Vec3::new(-1.2, 0.0, -1.0),
        Vec3::new(0.2, 0.0, 0.3),
        Vec3::new(1.5, 0.0, -0.5),
    ];
    check_floor(&scene, (90, 60), &points, &radiance);
}

/// The albedo texture of the first object of `scene` that has one.
fn albedo_of(scene: &Scene) -> &Texture {
    scene
        .materials
        .iter()
        .find_map(|m| match m {
            Material::Diffuse(d) if !matches!(d.albedo, Texture::Solid(_)) => Some(&d.albedo),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no textured material in {:?}", scene.material_names))
}

#[test]
fn textures_come_from_files_beside_a_gltf_and_what_cannot_be_read_is_said() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut floor = Floor::new(json!({"name": "painted", "pbrMetallicRoughness": {
        "baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0,
        "baseColorTexture": {"index": 0}}}));
    floor.lights = vec![json!({"name": "sun", "type": "directional"})];
    floor.cameras = vec![json!({"name": "plan", "type": "orthographic",
        "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}})];
    floor.nodes = vec![
        json!({"extensions": {"KHR_lights_punctual": {"light": 0}}}),
        json!({"camera": 0, "translation": [0, 5, 0]}),
    ];
    let (mut gltf, bin) = floor.json_and_bin();
    use base64::Engine as _;
    let encoded = base64::engine::general_purpose::STANDARD.encode(&bin);
    gltf["buffers"][0]["uri"] = json!(format!("data:application/octet-stream;base64,{encoded}"));
    // A JPEG beside the file, its name percent-encoded in the URI as exporters write it.
    gltf["images"] = json!([{"uri": "paint%20coat.jpg"}]);
    gltf["textures"] = json!([{"source": 0}]);
    std::fs::write(d.join("painted.gltf"), gltf.to_string()).unwrap();
    let colour = [200u8, 100, 50];
    let jpeg = picture(8, 8, colour.repeat(64), image::ImageFormat::Jpeg);
    std::fs::write(d.join("paint coat.jpg"), jpeg).unwrap();

    let scene = Scene::load(d.join("painted.gltf")).unwrap();
    let got = albedo_of(&scene).eval(Vec2::new(0.3, 0.6));
    let expected = Color::new(linear(colour[0]), linear(colour[1]), linear(colour[2]));
    // JPEG is lossy: a flat colour comes back within a few levels.
    assert!(
        (got - expected).abs().max_element() < 0.02,
        "{got} vs {expected}"
    );
    // What raylab does not have is left out, each said once, naming the file: the
    // directional light (so raylab's own light is put up) and the orthographic camera.
    let said = scene.warnings.join("\n");
    assert!(
        said.contains("painted.gltf") && said.contains("light `sun` is directional"),
        "{said}"
    );
    assert!(said.contains("camera `plan` is orthographic"), "{said}");
    assert_eq!(scene.lights.len(), 1);

    // Without its picture the model still opens, drawn in its colour factor, and says so.
    std::fs::remove_file(d.join("paint coat.jpg")).unwrap();
    let scene = Scene::load(d.join("painted.gltf")).unwrap();
    let said = scene.warnings.join("\n");
    assert!(
        said.contains("image 0: cannot read `paint coat.jpg`")
            && said.contains("material `painted`"),
        "{said}"
    );
    let painted = scene
        .material_names
        .iter()
        .position(|n| n.ends_with("painted"))
        .unwrap();
    let Material::Diffuse(diffuse) = &scene.materials[painted] else {
        panic!("{:?}", scene.materials[painted]);
    };
    assert_eq!(diffuse.albedo, Texture::Solid(Color::ONE));
    // A picture that is not one: the same.
    std::fs::write(d.join("paint coat.jpg"), b"not a picture").unwrap();
    let scene = Scene::load(d.join("painted.gltf")).unwrap();
    assert!(
        scene
            .warnings
            .join("\n")
            .contains("not a picture raylab reads")
    );
}

#[test]
fn a_scene_files_mesh_places_its_models_lights_with_it() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut floor = Floor::new(json!({"pbrMetallicRoughness": {"metallicFactor": 0}}));
    floor.lights = vec![
        json!({"type": "spot", "intensity": 3.0, "spot": {"outerConeAngle": 0.5}}),
        json!({"type": "point", "intensity": 2.0}),
    ];
    floor.nodes = vec![
        json!({"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 2, 0],
            "rotation": looking_down()}),
        json!({"extensions": {"KHR_lights_punctual": {"light": 1}}, "translation": [1, 1, 0]}),
    ];
    floor.write_glb(&d.join("lamp.glb"));
    // Scaled 2×, turned 90° about z (so −y becomes +x), moved 5 along x; beside the
    // file's own light, which comes first.
    std::fs::write(
        d.join("room.toml"),
        "[camera]\nposition = [0, 3, 9]\nlook_at = [0, 0, 0]\n\
         [[point_light]]\nposition = [0, 9, 0]\nintensity = 1.0\n\
         [[mesh]]\nfile = \"lamp.glb\"\nscale = 2\nrotate = [0, 0, 90]\ntranslate = [5, 0, 0]\n",
    )
    .unwrap();
    let scene = Scene::load(d.join("room.toml")).unwrap();
    assert_eq!(scene.lights.len(), 3);
    assert_eq!(scene.lights[0].center(), Vec3::new(0.0, 9.0, 0.0));
    let LightShape::Spot { center, cone } = &scene.lights[1].shape else {
        panic!("{:?}", scene.lights[1]);
    };
    // (0, 2, 0) scaled to (0, 4, 0), turned to (−4, 0, 0), moved to (1, 0, 0).
    assert!(
        (*center - Vec3::new(1.0, 0.0, 0.0)).length() < 1e-5,
        "{center}"
    );
    assert!((cone.axis - Vec3::X).length() < 1e-5, "{}", cone.axis);
    assert!((cone.cos_outer - 0.5f32.cos()).abs() < 1e-6 && cone.cos_inner == 1.0);
    assert_eq!(scene.lights[1].intensity, Color::splat(3.0));
    // (1, 1, 0) scaled to (2, 2, 0), turned to (−2, 2, 0), moved to (3, 2, 0).
    assert!((scene.lights[2].center() - Vec3::new(3.0, 2.0, 0.0)).length() < 1e-5);
}

#[test]
fn a_light_the_specification_does_not_allow_is_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            json!({"name": "wide", "type": "spot", "spot": {"innerConeAngle": 0.6, "outerConeAngle": 0.4}}),
            "light `wide`: a spot needs 0 ≤ innerConeAngle < outerConeAngle ≤ π/2",
        ),
        (
            json!({"name": "dark", "type": "point", "intensity": -1.0}),
            "light `dark`: its color and intensity must be finite and not negative",
        ),
    ];
    for (light, words) in cases {
        let mut floor = Floor::new(json!({}));
        floor.lights = vec![light];
        floor.nodes = vec![json!({"extensions": {"KHR_lights_punctual": {"light": 0}}})];
        let path = dir.path().join("bad.glb");
        floor.write_glb(&path);
        let Err(e) = Scene::load(&path) else {
            panic!("{words}: not refused");
        };
        let e = e.to_string();
        assert!(e.contains("bad.glb") && e.contains(words), "{e}");
    }
}

#[test]
fn a_scene_files_spot_light_is_the_same_light_as_a_gltf_spot() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut floor = Floor::new(json!({}));
    floor.lights = vec![
        json!({"type": "spot", "color": [1.0, 0.5, 0.25], "intensity": 10.0,
        "spot": {"innerConeAngle": 20f32.to_radians(), "outerConeAngle": 30f32.to_radians()}}),
    ];
    floor.nodes = vec![json!({"extensions": {"KHR_lights_punctual": {"light": 0}},
        "translation": [0, 2, 0], "rotation": looking_down()})];
    floor.write_glb(&d.join("spot.glb"));
    let from_gltf = Scene::load(d.join("spot.glb")).unwrap().lights[0].clone();
    let text = "[camera]\nposition = [0, 3, 9]\nlook_at = [0, 0, 0]\n\
                [[spot_light]]\nposition = [0, 2, 0]\ndirection = [0, -1, 0]\n\
                inner_angle = 20\nouter_angle = 30\ncolor = [1, 0.5, 0.25]\nintensity = 10\n";
    let from_toml = Scene::from_toml_str(text, "spot.toml", d).unwrap().lights[0].clone();
    let (
        LightShape::Spot {
            center: a,
            cone: ca,
        },
        LightShape::Spot {
            center: b,
            cone: cb,
        },
    ) = (&from_gltf.shape, &from_toml.shape)
    else {
        panic!("{from_gltf:?} {from_toml:?}");
    };
    assert!((*a - *b).length() < 1e-6 && (ca.axis - cb.axis).length() < 1e-6);
    assert!((ca.cos_inner - cb.cos_inner).abs() < 1e-6);
    assert!((ca.cos_outer - cb.cos_outer).abs() < 1e-6);
    assert_eq!(from_gltf.intensity, from_toml.intensity);
    // A cone the other way round is refused where it is written.
    let bad = text.replace("inner_angle = 20", "inner_angle = 40");
    let Err(e) = Scene::from_toml_str(&bad, "spot.toml", d) else {
        panic!("an inner angle past the outer one is accepted");
    };
    let e = e.to_string();
    assert!(
        e.starts_with("spot.toml:4:1") && e.contains("0 ≤ inner_angle < outer_angle ≤ 90"),
        "{e}"
    );
}
