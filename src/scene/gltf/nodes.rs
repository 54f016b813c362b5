//! What a glTF scene's nodes place: meshes (their triangle primitives, in world space),
//! the camera and the KHR_lights_punctual lights.

use super::materials::Materials;
use super::{Model, ReadFile};
use crate::camera::Camera;
use crate::geometry::Mesh;
use crate::light::{Cone, Light};
use crate::math::{Color, Vec3};
use crate::scene::obj::{ModelCamera, ObjPart};
use crate::scene::{Location, SceneError};
use glam::{Mat4, Vec2};
use gltf::mesh::Mode;
use std::borrow::Cow;
use std::collections::HashMap;
use std::ops::Range;

/// Every triangle primitive placed by the default scene (or the first; or, with no
/// scenes, every mesh where it stands), transformed to world space; the camera of the
/// lowest index a node places; and every light a node places, in the file's order.
pub(super) fn collect(
    gltf: &gltf::Gltf,
    buffers: &[Cow<[u8]>],
    file: &str,
    read_file: ReadFile,
) -> Result<Model, SceneError> {
    let scene = gltf.default_scene().or_else(|| gltf.scenes().next());
    let mut walk = Walk {
        file,
        buffers,
        materials: Materials::new(buffers, file, read_file),
        parts: Vec::new(),
        camera: None,
        lights: Vec::new(),
        warnings: Vec::new(),
        placements: scene
            .as_ref()
            .map_or_else(Vec::new, |s| placements(gltf, s)),
        read: HashMap::new(),
    };
    match scene {
        Some(scene) => {
            // Depth-first in the file's order (the stack holds each list reversed), with
            // each node's transform composed onto its parent's. The graph is a tree
            // ([`check_tree`]), so each node is visited once, however deep.
            let mut stack: Vec<(gltf::Node, Mat4)> =
                scene.nodes().map(|n| (n, Mat4::IDENTITY)).collect();
            stack.reverse();
            while let Some((node, parent)) = stack.pop() {
                let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
                walk.node(&node, &world)?;
                let first = stack.len();
                stack.extend(node.children().map(|c| (c, world)));
                stack[first..].reverse();
            }
        }
        None => {
            for mesh in gltf.meshes() {
                walk.mesh(&mesh, &Mat4::IDENTITY)?;
            }
        }
    }
    let mut warnings = walk.warnings;
    warnings.extend(walk.materials.into_warnings());
    Ok(Model {
        parts: walk.parts,
        camera: walk.camera.map(|(_, camera)| camera),
        lights: walk.lights,
        warnings,
    })
}

/// The triangles of a primitive's vertex list (its indices, or 0, 1, 2, ...), as glTF
/// assembles them: in threes; a strip's each next vertex with the two before it (every
/// other one turned back, so that all face the same way); a fan's each next pair with
/// the first.
fn triangles_of(mode: Mode, v: &[u32]) -> Vec<[u32; 3]> {
    match mode {
        Mode::TriangleStrip => (0..v.len().saturating_sub(2))
            .map(|i| match i % 2 {
                0 => [v[i], v[i + 1], v[i + 2]],
                _ => [v[i + 1], v[i], v[i + 2]],
            })
            .collect(),
        Mode::TriangleFan => (1..v.len().saturating_sub(1))
            .map(|i| [v[i], v[i + 1], v[0]])
            .collect(),
        _ => v.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
    }
}

/// Refuses a node graph that is not a set of trees, as glTF requires: a node listed as a
/// child of two nodes (or twice by one), a node its own ancestor, or a scene listing a
/// node that is another's child, or one node twice. Each would place a node's meshes
/// more than once, up to 2^depth times, or for ever. Indices past the end are left to
/// the validator, which names them.
pub(super) fn check_tree(root: &gltf::json::Root) -> Result<(), String> {
    const TREE: &str = "a glTF node graph must be a tree";
    let n = root.nodes.len();
    let mut parent: Vec<Option<usize>> = vec![None; n];
    for (p, node) in root.nodes.iter().enumerate() {
        for c in node.children.iter().flatten().map(|c| c.value()) {
            if c == p {
                return Err(format!("nodes[{p}] lists itself as a child: {TREE}"));
            }
            match parent.get(c).copied() {
                Some(Some(q)) if q == p => {
                    return Err(format!("nodes[{p}] lists nodes[{c}] twice: {TREE}"));
                }
                Some(Some(q)) => {
                    return Err(format!(
                        "nodes[{c}] is a child of nodes[{q}] and again of nodes[{p}]: {TREE} (to place a mesh twice, give two nodes the same mesh)"
                    ));
                }
                Some(None) => parent[c] = Some(p),
                None => {}
            }
        }
    }
    // With one parent each, a node on a cycle never climbs to a root.
    const UNSEEN: u8 = 0;
    const CLIMBING: u8 = 1;
    const ROOTED: u8 = 2;
    let mut state = vec![UNSEEN; n];
    let mut path = Vec::new();
    for start in 0..n {
        let mut at = start;
        while state[at] != ROOTED {
            if state[at] == CLIMBING {
                return Err(format!(
                    "nodes[{at}] is its own ancestor (its children lead back to it): {TREE}"
                ));
            }
            state[at] = CLIMBING;
            path.push(at);
            match parent[at] {
                Some(p) => at = p,
                None => break,
            }
        }
        for v in path.drain(..) {
            state[v] = ROOTED;
        }
    }
    for (s, scene) in root.scenes.iter().enumerate() {
        let mut listed = std::collections::HashSet::new();
        for (i, r) in scene.nodes.iter().map(|r| r.value()).enumerate() {
            if let Some(Some(p)) = parent.get(r) {
                return Err(format!(
                    "scenes[{s}].nodes[{i}] is nodes[{r}], a child of nodes[{p}]: a scene lists root nodes only"
                ));
            }
            if !listed.insert(r) {
                return Err(format!("scenes[{s}].nodes lists nodes[{r}] twice"));
            }
        }
    }
    Ok(())
}

/// How many nodes of `scene` place each mesh (by index).
fn placements(gltf: &gltf::Gltf, scene: &gltf::Scene) -> Vec<usize> {
    let mut count = vec![0usize; gltf.meshes().len()];
    let mut stack: Vec<gltf::Node> = scene.nodes().collect();
    while let Some(node) = stack.pop() {
        if let Some(slot) = node.mesh().and_then(|m| count.get_mut(m.index())) {
            *slot += 1;
        }
        stack.extend(node.children());
    }
    count
}

/// What the walk over the nodes has found so far.
struct Walk<'a> {
    file: &'a str,
    buffers: &'a [Cow<'a, [u8]>],
    materials: Materials<'a>,
    parts: Vec<ObjPart>,
    // The camera of the lowest index placed so far, with that index.
    camera: Option<(usize, ModelCamera)>,
    lights: Vec<Light>,
    warnings: Vec<String>,
    // How many nodes place each mesh, and the parts of each mesh several nodes place,
    // read once.
    placements: Vec<usize>,
    read: HashMap<usize, Range<usize>>,
}

impl Walk<'_> {
    fn error(&self, message: String) -> SceneError {
        SceneError::new(Location::file(self.file), message)
    }

    /// What one node places, at its world transform.
    fn node(&mut self, node: &gltf::Node, world: &Mat4) -> Result<(), SceneError> {
        if let Some(mesh) = node.mesh() {
            self.mesh(&mesh, world)?;
        }
        if let Some(camera) = node.camera() {
            self.camera(&camera, world);
        }
        if let Some(light) = node.light() {
            self.light(&light, world)?;
        }
        Ok(())
    }

    /// A node's camera: glTF's looks down its node's −z with +y up. Kept if its index is
    /// the lowest yet (the file's first camera, as glTF viewers choose).
    fn camera(&mut self, camera: &gltf::Camera, world: &Mat4) {
        if self
            .camera
            .as_ref()
            .is_some_and(|(i, _)| *i <= camera.index())
        {
            return;
        }
        let name = camera
            .name()
            .map_or_else(|| format!("camera{}", camera.index()), str::to_string);
        let gltf::camera::Projection::Perspective(p) = camera.projection() else {
            self.warnings.push(format!(
                "{}: camera `{name}` is orthographic, which raylab does not render: left out",
                self.file
            ));
            return;
        };
        let position: Vec3 = world.transform_point3(glam::Vec3::ZERO).into();
        let forward: Vec3 = world
            .transform_vector3(glam::Vec3::NEG_Z)
            .normalize_or_zero()
            .into();
        let camera_here = Camera::looking_at(
            position,
            position + forward,
            world.transform_vector3(glam::Vec3::Y).into(),
            p.yfov().to_degrees(),
        );
        let aspect = p.aspect_ratio().filter(|a| a.is_finite() && *a > 0.0);
        match camera_here.check() {
            Ok(()) => {
                let model_camera = ModelCamera {
                    camera: camera_here,
                    aspect,
                };
                self.camera = Some((camera.index(), model_camera));
            }
            Err(e) => self.warnings.push(format!(
                "{}: camera `{name}` is not a view raylab can take ({e}): left out",
                self.file
            )),
        }
    }

    /// A node's light: a point or a spot at the node's origin (a spot shines down the
    /// node's −z), of intensity `color` × `intensity`, read as raylab's radiant intensity
    /// (glTF's candela, one for one). glTF's `range` is not applied: light falls off as
    /// 1/d² everywhere, as the specification's physical model says.
    fn light(
        &mut self,
        light: &gltf::khr_lights_punctual::Light,
        world: &Mat4,
    ) -> Result<(), SceneError> {
        let name = light
            .name()
            .map_or_else(|| format!("light{}", light.index()), str::to_string);
        let color = light.color();
        let intensity = light.intensity();
        let valid = |x: f32| x.is_finite() && x >= 0.0;
        if !valid(intensity) || !color.iter().all(|&c| valid(c)) {
            return Err(self.error(format!(
                "light `{name}`: its color and intensity must be finite and not negative"
            )));
        }
        let power = Color::from(color) * intensity;
        let position: Vec3 = world.transform_point3(glam::Vec3::ZERO).into();
        if !crate::geometry::within_limits(position) {
            return Err(self.error(format!(
                "light `{name}` is not at a finite point within the limits"
            )));
        }
        match light.kind() {
            gltf::khr_lights_punctual::Kind::Point => {
                self.lights.push(Light::point(position, power));
            }
            gltf::khr_lights_punctual::Kind::Spot {
                inner_cone_angle,
                outer_cone_angle,
            } => {
                let half_pi = std::f32::consts::FRAC_PI_2;
                let angles_valid = inner_cone_angle >= 0.0
                    && inner_cone_angle < outer_cone_angle
                    && outer_cone_angle <= half_pi;
                if !angles_valid {
                    return Err(self.error(format!(
                        "light `{name}`: a spot needs 0 ≤ innerConeAngle < outerConeAngle ≤ π/2, not {inner_cone_angle} and {outer_cone_angle}"
                    )));
                }
                let axis: Vec3 = world
                    .transform_vector3(glam::Vec3::NEG_Z)
                    .normalize_or_zero()
                    .into();
                if axis == Vec3::ZERO {
                    return Err(self.error(format!(
                        "light `{name}`: its node's transform flattens the spot's direction"
                    )));
                }
                let cone = Cone {
                    axis,
                    cos_inner: inner_cone_angle.cos(),
                    cos_outer: outer_cone_angle.cos(),
                };
                self.lights.push(Light::spot(position, cone, power));
            }
            gltf::khr_lights_punctual::Kind::Directional => self.warnings.push(format!(
                "{}: light `{name}` is directional (a sun), which raylab does not have: left out",
                self.file
            )),
        }
        Ok(())
    }

    /// Each triangle primitive of `mesh`, at `world`: moved there if one node places
    /// the mesh; else read once in its own coordinates and placed by each node's
    /// transform, so that a mesh a hundred nodes place costs the memory of one.
    fn mesh(&mut self, mesh: &gltf::Mesh, world: &Mat4) -> Result<(), SceneError> {
        let times = self.placements.get(mesh.index()).copied().unwrap_or(1);
        if times <= 1 {
            return self.primitives(mesh, world, glam::Affine3A::IDENTITY);
        }
        let at = glam::Affine3A::from_mat4(*world);
        if !at.is_finite() {
            return Err(self.error(format!(
                "a node places mesh {} by a transform that is not finite",
                mesh.index()
            )));
        }
        match self.read.get(&mesh.index()) {
            Some(parts) => {
                for part in &mut self.parts[parts.clone()] {
                    part.at.push(at);
                }
            }
            None => {
                let first = self.parts.len();
                self.primitives(mesh, &Mat4::IDENTITY, at)?;
                self.read.insert(mesh.index(), first..self.parts.len());
            }
        }
        Ok(())
    }

    /// Each triangle primitive of `mesh`, its vertices moved by `world`, placed `at`.
    fn primitives(
        &mut self,
        mesh: &gltf::Mesh,
        world: &Mat4,
        at: glam::Affine3A,
    ) -> Result<(), SceneError> {
        let name = mesh
            .name()
            .map_or_else(|| format!("mesh{}", mesh.index()), str::to_string);
        let file = self.file;
        let error = |message: String| {
            SceneError::new(Location::file(file), format!("mesh `{name}`: {message}"))
        };
        let normal_matrix = glam::Mat3::from_mat4(*world).inverse().transpose();
        let buffers = self.buffers;
        for primitive in mesh.primitives() {
            let mode = primitive.mode();
            if !matches!(
                mode,
                Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
            ) {
                continue; // points and lines are not surfaces raylab renders
            }
            let reader = primitive.reader(|b| buffers.get(b.index()).map(|bytes| &bytes[..]));
            let Some(positions) = reader.read_positions() else {
                continue;
            };
            let positions: Vec<Vec3> = positions
                .map(|p| world.transform_point3(glam::Vec3::from(p)).into())
                .collect();
            if !positions.iter().all(|&p| crate::geometry::within_limits(p)) {
                return Err(error(
                    "a vertex is not a finite point within the limits".into(),
                ));
            }
            let flat: Vec<u32> = match reader.read_indices() {
                Some(indices) => indices.into_u32().collect(),
                None => (0..positions.len() as u32).collect(),
            };
            // Mesh::new refuses an index past the last vertex.
            let indices = triangles_of(mode, &flat);
            if indices.is_empty() {
                continue;
            }
            let normals = reader.read_normals().map(|n| {
                n.map(|n| (normal_matrix * glam::Vec3::from(n)).into())
                    .collect::<Vec<Vec3>>()
            });
            let normals = normals.filter(|n| n.len() == positions.len());
            let material = primitive.material();
            // The texture coordinates the material's textures are mapped by.
            let uv_set = Materials::uv_set(&material);
            let uvs = reader
                .read_tex_coords(uv_set)
                .map(|t| t.into_f32().map(Vec2::from).collect::<Vec<_>>())
                .filter(|t| t.len() == positions.len());
            let triangles =
                Mesh::new(positions, indices, normals, uvs).map_err(|e| error(e.to_string()))?;
            // The glTF default material (no `material`) is left to the scene.
            let material = match material.index() {
                Some(index) => {
                    let name = material
                        .name()
                        .map_or_else(|| format!("material{index}"), str::to_string);
                    let mapped = self.materials.map(&material, &name);
                    Some((name, mapped))
                }
                None => None,
            };
            self.parts.push(ObjPart {
                name: if mesh.primitives().len() > 1 {
                    format!("{name}.{}", primitive.index())
                } else {
                    name.clone()
                },
                mesh: triangles,
                material,
                at: vec![at],
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_and_fans_make_triangles_facing_one_way() {
        let v = [0, 1, 2, 3, 4];
        assert_eq!(
            triangles_of(Mode::TriangleStrip, &v),
            vec![[0, 1, 2], [2, 1, 3], [2, 3, 4]]
        );
        assert_eq!(
            triangles_of(Mode::TriangleFan, &v),
            vec![[1, 2, 0], [2, 3, 0], [3, 4, 0]]
        );
        assert_eq!(triangles_of(Mode::Triangles, &v), vec![[0, 1, 2]]);
        assert!(triangles_of(Mode::TriangleStrip, &v[..2]).is_empty());
        assert!(triangles_of(Mode::TriangleFan, &[]).is_empty());
    }
}
