//! Captions that follow more than a number: which sphere the plane of focus holds, what
//! the inspected pixel's ray meets first.

use super::Shown;
use crate::geometry::Shape;

/// The focus distance, and the name of the material of the sphere nearest the plane of
/// focus ("blue") if the plane cuts it: what a thin lens shows sharp. `None` in a scene
/// without spheres.
pub(super) fn sharp_sphere(s: &Shown) -> Option<(Option<String>, f32)> {
    let focus = s
        .params
        .focus_distance
        .unwrap_or_else(|| s.camera.look_distance());
    let forward = s.camera.pinhole(1.0).forward();
    let scene = s.scene;
    let (object, gap) = scene
        .shapes
        .iter()
        .enumerate()
        .filter_map(|(o, shape)| match shape {
            Shape::Sphere(sphere) => {
                let depth = (sphere.center - s.camera.position).dot(forward);
                Some((o, (depth - focus).abs() - sphere.radius))
            }
            _ => None,
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    let material = scene.object_materials[object] as usize;
    let cut = (gap <= 0.0).then(|| scene.material_names.get(material).cloned());
    Some((cut.flatten(), focus))
}

/// The name of the object the inspected pixel's ray meets first ("front sphere"), `None`
/// when it meets nothing; the outer `None` while no pixel is inspected.
pub(super) fn inspected_object<'a>(s: &Shown<'a>) -> Option<Option<&'a str>> {
    s.inspected
        .map(|object| object.and_then(|o| s.scene.object_names.get(o as usize).map(String::as_str)))
}
