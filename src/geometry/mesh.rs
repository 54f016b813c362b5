//! Triangle meshes.

use super::SurfaceHit;
use crate::math::lanes::{Real, Vector};
use crate::math::{Ray, Vec3};
use glam::Vec2;
use obvhs::aabb::Aabb;

/// An indexed triangle mesh with optional per-vertex normals and texture coordinates,
/// possibly moving: at frame time t it is displaced by `velocity * t`.
#[derive(Clone, Debug)]
pub struct Mesh {
    /// Displacement over the frame (time 0 to 1).
    pub velocity: Vec3,
    positions: Vec<Vec3>,
    normals: Option<Vec<Vec3>>,
    uvs: Option<Vec<Vec2>>,
    indices: Vec<[u32; 3]>,
    // Per triangle (v0, v1 - v0, v2 - v0): what Möller–Trumbore reads, in one cache line.
    edges: Vec<[Vec3; 3]>,
}

/// Why a mesh cannot be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// No triangles.
    #[error("the mesh has no triangles")]
    Empty,
    /// A vertex position is NaN or infinite.
    #[error("vertex {0} has a non-finite position")]
    NonFinite(usize),
    /// An index points past the vertex list.
    #[error("triangle {triangle} uses vertex {index}, but there are only {count} vertices")]
    IndexOutOfRange {
        /// Triangle number.
        triangle: usize,
        /// The index.
        index: u32,
        /// How many vertices there are.
        count: usize,
    },
    /// Normals or texture coordinates are not one per vertex.
    #[error("{what} has {got} entries for {count} vertices")]
    AttributeCount {
        /// "normals" or "texture coordinates".
        what: &'static str,
        /// Entries given.
        got: usize,
        /// Vertices.
        count: usize,
    },
    /// A placement's transform flattens, mirrors or overflows the mesh.
    #[error("its transform is not an invertible one that keeps the mesh's orientation")]
    Transform,
}

impl Mesh {
    /// A mesh from positions and triangles, with optional per-vertex normals and uvs.
    /// Degenerate (zero-area) triangles are kept: they are simply never hit.
    pub fn new(
        positions: Vec<Vec3>,
        indices: Vec<[u32; 3]>,
        normals: Option<Vec<Vec3>>,
        uvs: Option<Vec<Vec2>>,
    ) -> Result<Self, MeshError> {
        if indices.is_empty() {
            return Err(MeshError::Empty);
        }
        if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFinite(i));
        }
        let count = positions.len();
        for (triangle, tri) in indices.iter().enumerate() {
            if let Some(&index) = tri.iter().find(|&&i| i as usize >= count) {
                return Err(MeshError::IndexOutOfRange {
                    triangle,
                    index,
                    count,
                });
            }
        }
        // Normals that are zero or non-finite are useless for shading: drop them all.
        let normals = match normals {
            Some(n) if n.len() != count => {
                return Err(MeshError::AttributeCount {
                    what: "normals",
                    got: n.len(),
                    count,
                });
            }
            Some(n) if n.iter().all(|v| v.is_finite() && v.length_squared() > 0.0) => {
                Some(n.into_iter().map(Vec3::normalize).collect())
            }
            _ => None,
        };
        if let Some(uv) = &uvs
            && uv.len() != count
        {
            return Err(MeshError::AttributeCount {
                what: "texture coordinates",
                got: uv.len(),
                count,
            });
        }
        let edges = indices
            .iter()
            .map(|&[a, b, c]| {
                let v0 = positions[a as usize];
                [v0, positions[b as usize] - v0, positions[c as usize] - v0]
            })
            .collect();
        Ok(Mesh {
            velocity: Vec3::ZERO,
            positions,
            normals,
            uvs,
            indices,
            edges,
        })
    }

    /// This mesh moved by `transform` (normals by its inverse transpose). With `smooth`
    /// false the vertex normals are dropped, for flat shading.
    pub fn transformed(&self, transform: &glam::Affine3A, smooth: bool) -> Result<Self, MeshError> {
        let positions = self
            .positions
            .iter()
            .map(|&p| transform.transform_point3a(p))
            .collect();
        let normal_matrix = transform.matrix3.inverse().transpose();
        let normals = match (&self.normals, smooth) {
            (Some(n), true) => Some(n.iter().map(|&v| normal_matrix * v).collect()),
            _ => None,
        };
        Mesh::new(positions, self.indices.clone(), normals, self.uvs.clone())
    }

    /// The closed box between the corners `min` and `max`, 12 triangles wound so that
    /// their normals point out (flat shaded).
    pub fn cuboid(min: Vec3, max: Vec3) -> Result<Self, MeshError> {
        // Corner i has x from bit 0, y from bit 1, z from bit 2 (0: min, 1: max).
        let positions = (0..8)
            .map(|i| {
                Vec3::select(
                    glam::BVec3A::new(i & 1 != 0, i & 2 != 0, i & 4 != 0),
                    max,
                    min,
                )
            })
            .collect();
        // Each face counter-clockwise seen from outside.
        let faces = [
            [0, 4, 6, 2],
            [1, 3, 7, 5],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 2, 3, 1],
            [4, 5, 7, 6],
        ];
        let indices = faces
            .iter()
            .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
            .collect();
        Mesh::new(positions, indices, None, None)
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len()
    }

    /// Vertex positions.
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Unit vertex normals, if the mesh is smooth shaded.
    pub fn normals(&self) -> Option<&[Vec3]> {
        self.normals.as_deref()
    }

    /// Triangles as vertex indices.
    pub fn indices(&self) -> &[[u32; 3]] {
        &self.indices
    }

    /// Bounds of triangle `i` over the whole frame.
    pub fn triangle_bounds(&self, i: usize) -> Aabb {
        let [v0, e1, e2] = self.edges[i];
        let v = self.velocity;
        Aabb::from_points(&[v0, v0 + e1, v0 + e2, v0 + v, v0 + e1 + v, v0 + e2 + v])
    }

    /// The area of triangle `i`.
    pub fn triangle_area(&self, i: usize) -> f32 {
        let [_, e1, e2] = self.edges[i];
        0.5 * e1.cross(e2).length()
    }

    /// A point uniform over triangle `i` at frame time `time`: barycentrics (1 − √u₁,
    /// u₂ √u₁) are uniform in area.
    pub fn sample_point(&self, i: usize, u: Vec2, time: f32) -> Vec3 {
        let [v0, e1, e2] = self.edges[i];
        let s = u.x.sqrt();
        let (b1, b2) = (s * (1.0 - u.y), s * u.y);
        v0 + b1 * e1 + b2 * e2 + self.velocity * time
    }

    /// `ray` in the mesh's own frame at the ray's time (the mesh only translates).
    #[inline]
    fn local(&self, ray: &Ray) -> Ray {
        Ray {
            origin: ray.origin - self.velocity * ray.time,
            ..*ray
        }
    }

    /// Möller–Trumbore: distance and barycentrics (u, v) of triangle `i`, if hit in (0, t_max).
    /// Both sides of the triangle are hit.
    #[inline]
    pub fn intersect_t(&self, i: usize, ray: &Ray, t_max: f32) -> Option<(f32, Vec2)> {
        let ray = &self.local(ray);
        let (t, u, v) = triangle_nearest(self.edges[i], ray.origin, ray.dir, t_max);
        (t != f32::INFINITY).then_some((t, Vec2::new(u, v)))
    }

    /// Per triangle (v0, v1 − v0, v2 − v0), what [`triangle_nearest`] reads.
    pub(crate) fn edges(&self) -> &[[Vec3; 3]] {
        &self.edges
    }

    /// The hit record of triangle `i` at `t`, with the point rebuilt from barycentrics.
    pub fn surface_hit(&self, i: usize, ray: &Ray, t: f32) -> SurfaceHit {
        self.surface_hit_shaded(i, ray, t, true)
    }

    /// [`Mesh::surface_hit`], with the vertex normals used only where `smooth`.
    pub(super) fn surface_hit_shaded(
        &self,
        i: usize,
        ray: &Ray,
        t: f32,
        smooth: bool,
    ) -> SurfaceHit {
        let [v0, e1, e2] = self.edges[i];
        // Barycentrics of the point at t, by projecting onto the triangle's edges.
        let (u, v) = match self.intersect_t(i, ray, f32::INFINITY) {
            Some((_, b)) => (b.x, b.y),
            None => barycentrics(self.local(ray).at(t) - v0, e1, e2),
        };
        let w = 1.0 - u - v;
        let p = v0 + u * e1 + v * e2 + self.velocity * ray.time;
        let mut n_geom = e1.cross(e2).normalize_or_zero();
        let [a, b, c] = self.indices[i].map(|k| k as usize);
        let n_shade = match self.normals.as_ref().filter(|_| smooth) {
            Some(n) => {
                let s = (w * n[a] + u * n[b] + v * n[c]).normalize_or_zero();
                if s == Vec3::ZERO { n_geom } else { s }
            }
            None => n_geom,
        };
        // Vertex normals define the outside when present: turn the geometric normal to
        // agree, so that a mesh with flipped winding still shades and refracts right.
        if n_geom.dot(n_shade) < 0.0 {
            n_geom = -n_geom;
        }
        let uv = match &self.uvs {
            Some(t) => w * t[a] + u * t[b] + v * t[c],
            None => Vec2::new(u, v),
        };
        SurfaceHit {
            t,
            p,
            n_geom,
            n_shade,
            uv,
        }
    }
}

/// Möller–Trumbore for one ray or one per lane (origin `o`, direction `d`), against the
/// triangle (v0, v0 + e1, v0 + e2) given as `[v0, e1, e2]`, either side: the distance
/// t = e2·q / det where it is hit in (0, t_max), else +∞, and the barycentrics
/// u = (o − v0)·p / det, v = d·q / det, with p = d × e2, q = (o − v0) × e1, det = e1·p.
/// A hit needs det ≠ 0, u in [0, 1], v ≥ 0 and u + v ≤ 1.
#[inline(always)]
pub(crate) fn triangle_nearest<R: Real>(
    [v0, e1, e2]: [R::V3; 3],
    o: R::V3,
    d: R::V3,
    t_max: R,
) -> (R, R, R) {
    let (zero, one, miss) = (R::splat(0.0), R::splat(1.0), R::splat(f32::INFINITY));
    let pvec = d.cross(e2);
    let det = e1.dot(pvec);
    let hit = !det.equal(zero);
    if !R::any(hit) {
        return (miss, zero, zero);
    }
    let inv_det = one / det;
    let tvec = o - v0;
    let u = tvec.dot(pvec) * inv_det;
    let hit = hit & zero.less_eq(u) & u.less_eq(one);
    if !R::any(hit) {
        return (miss, u, zero);
    }
    let qvec = tvec.cross(e1);
    let v = d.dot(qvec) * inv_det;
    // Not v < 0 and not u + v > 1: a NaN passes here and fails at t.
    let hit = hit & !v.less(zero) & !one.less(u + v);
    if !R::any(hit) {
        return (miss, u, v);
    }
    let t = e2.dot(qvec) * inv_det;
    let hit = hit & zero.less(t) & t.less(t_max);
    (R::select(hit, t, miss), u, v)
}

/// Barycentric coordinates of `rel = p - v0` in the triangle (v0, v0 + e1, v0 + e2).
fn barycentrics(rel: Vec3, e1: Vec3, e2: Vec3) -> (f32, f32) {
    let (d00, d01, d11) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (d20, d21) = (rel.dot(e1), rel.dot(e2));
    let denom = d00 * d11 - d01 * d01;
    if denom == 0.0 {
        return (0.0, 0.0);
    }
    let u = (d11 * d20 - d01 * d21) / denom;
    let v = (d00 * d21 - d01 * d20) / denom;
    (u, v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_triangle() -> Mesh {
        Mesh::new(
            vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            vec![[0, 1, 2]],
            None,
            None,
        )
        .unwrap()
    }

    #[test]
    fn triangle_hit_barycentrics_and_normal() {
        let m = unit_triangle();
        let ray = Ray::new(Vec3::new(0.25, 0.5, 2.0), -Vec3::Z, 0.0);
        let (t, b) = m.intersect_t(0, &ray, f32::INFINITY).unwrap();
        assert!((t - 2.0).abs() < 1e-6);
        assert!((b - Vec2::new(0.25, 0.5)).length() < 1e-6);
        let hit = m.surface_hit(0, &ray, t);
        assert!((hit.p - Vec3::new(0.25, 0.5, 0.0)).length() < 1e-6);
        assert!((hit.n_geom - Vec3::Z).length() < 1e-6);
        // From behind too (double-sided), and misses outside the edges.
        let back = Ray::new(Vec3::new(0.25, 0.5, -2.0), Vec3::Z, 0.0);
        assert!(m.intersect_t(0, &back, f32::INFINITY).is_some());
        let outside = Ray::new(Vec3::new(0.6, 0.6, 2.0), -Vec3::Z, 0.0);
        assert!(m.intersect_t(0, &outside, f32::INFINITY).is_none());
    }

    #[test]
    fn bad_meshes_are_errors() {
        assert_eq!(
            Mesh::new(vec![Vec3::ZERO], vec![], None, None).unwrap_err(),
            MeshError::Empty
        );
        assert!(matches!(
            Mesh::new(vec![Vec3::ZERO, Vec3::X], vec![[0, 1, 2]], None, None),
            Err(MeshError::IndexOutOfRange { index: 2, .. })
        ));
        assert_eq!(
            Mesh::new(
                vec![Vec3::ZERO, Vec3::X, Vec3::splat(f32::NAN)],
                vec![[0, 1, 2]],
                None,
                None
            )
            .unwrap_err(),
            MeshError::NonFinite(2)
        );
    }

    #[test]
    fn cuboid_normals_point_out() {
        let m = Mesh::cuboid(Vec3::splat(-1.0), Vec3::new(1.0, 2.0, 3.0)).unwrap();
        assert_eq!(m.triangle_count(), 12);
        let center = Vec3::new(0.0, 0.5, 1.0);
        for i in 0..12 {
            let [v0, e1, e2] = m.edges[i];
            let centroid = v0 + (e1 + e2) / 3.0;
            assert!(
                e1.cross(e2).dot(centroid - center) > 0.0,
                "triangle {i} faces in"
            );
        }
    }

    #[test]
    fn vertex_normals_decide_the_outside() {
        let m = Mesh::new(
            vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            vec![[0, 1, 2]],
            Some(vec![-Vec3::Z; 3]),
            None,
        )
        .unwrap();
        let ray = Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z, 0.0);
        let hit = m.surface_hit(0, &ray, 1.0);
        assert!((hit.n_geom + Vec3::Z).length() < 1e-6);
        assert!((hit.n_shade + Vec3::Z).length() < 1e-6);
    }
}
