//! Meshes placed many times (instancing, a two-level BVH): each shared mesh's triangles are
//! kept once, in the mesh's own space under a BVH of their own ([`MeshLibrary`]), and each
//! placement is one primitive of the scene's BVH ([`Placement`]) that carries a ray into the
//! mesh's space and asks the mesh's BVH. A field of 10⁵ copies of a plant then holds one
//! plant's triangles and 10⁵ transforms.

use crate::accel::{Accelerator, Bvh, BvhOptions, PrimHit, PrimitiveSet};
use crate::geometry::{Aabb, Ray, Transform, Triangle};
use crate::scene::{MaterialId, PolygonMesh};
use glam::{Vec2, Vec3};

/// Smallest mesh (in triangles) placed rather than copied when several objects share it:
/// below it a copy costs no more memory than a placement (two 4 × 4 matrices and bounds) and
/// is hit faster.
pub const PLACED_MESH_MIN_TRIANGLES: usize = 8;

/// What a hit needs of one of a mesh's triangles, in the mesh's space.
#[derive(Clone, Copy, Debug)]
struct LocalAttributes {
    /// Unit geometric normal of the front side.
    normal: Vec3,
    /// The mesh face (polygon) the triangle belongs to.
    face: u32,
    uvs: [Vec2; 3],
    /// Per-corner shading normals, when the mesh has them.
    normals: Option<[Vec3; 3]>,
}

/// A mesh's triangles in its own space, as the primitive set of its own BVH (all plain
/// triangles, so the BVH tests eight at once).
#[derive(Clone, Debug, Default)]
struct LocalTriangles(Vec<Triangle>);

impl PrimitiveSet for LocalTriangles {
    fn len(&self) -> usize {
        self.0.len()
    }

    fn bounds(&self, prim: u32) -> Aabb {
        Aabb::from_points(self.0[prim as usize].vertices())
    }

    fn intersect(&self, prim: u32, ray: &Ray, t_max: f32) -> Option<PrimHit> {
        let (t, b1, b2) = self.0[prim as usize].intersect(ray, t_max)?;
        Some(PrimHit {
            t,
            prim,
            local: [b1, b2],
            part: 0,
        })
    }

    fn plain_triangle(&self, prim: u32) -> Option<Triangle> {
        Some(self.0[prim as usize])
    }
}

/// One shared mesh, ready to be placed.
#[derive(Clone, Debug)]
struct LocalMesh {
    triangles: LocalTriangles,
    attributes: Vec<LocalAttributes>,
    bvh: Bvh,
    /// Bounds of the triangles, mesh space.
    bounds: Aabb,
}

/// The shared meshes of a scene.
#[derive(Clone, Debug, Default)]
pub struct MeshLibrary {
    meshes: Vec<LocalMesh>,
}

/// One placement of a shared mesh: a primitive of the scene.
#[derive(Clone, Debug)]
pub struct Placement {
    /// Index of the mesh in the [`MeshLibrary`].
    pub mesh: u32,
    /// Mesh space to world space.
    pub to_world: Transform,
    /// World-space bounds.
    pub bounds: Aabb,
    /// The scene object it is.
    pub object: u32,
    /// Its material (placed meshes have one).
    pub material: MaterialId,
}

/// A placed mesh's triangle at a hit, in world space.
#[derive(Clone, Copy, Debug)]
pub struct PlacedPoint {
    /// The point.
    pub p: Vec3,
    /// Unit geometric normal of the front side.
    pub ng: Vec3,
    /// Unit shading normal, on the side of `ng`.
    pub ns: Vec3,
    /// Texture coordinates.
    pub uv: Vec2,
    /// The mesh face.
    pub face: u32,
}

impl MeshLibrary {
    /// Adds `mesh` (checked by the caller) and returns its index: its triangles (fans of its
    /// polygons, degenerate ones dropped) in its own space under their own BVH.
    pub fn add(&mut self, mesh: &PolygonMesh) -> u32 {
        let mut triangles = Vec::new();
        let mut attributes = Vec::new();
        for (face, indices) in mesh.faces().enumerate() {
            for k in 1..indices.len() - 1 {
                let [a, b, c] = [indices[0], indices[k], indices[k + 1]].map(|i| i as usize);
                let p = &mesh.positions;
                let tri = Triangle::new(p[a], p[b], p[c]);
                if tri.area() <= 0.0 {
                    continue;
                }
                let uvs = mesh
                    .uvs
                    .as_ref()
                    .map_or([Vec2::ZERO, Vec2::X, Vec2::Y], |u| [u[a], u[b], u[c]]);
                let normals = mesh.normals.as_ref().and_then(|n| {
                    let corners = [n[a], n[b], n[c]].map(Vec3::normalize_or_zero);
                    corners.iter().all(|v| *v != Vec3::ZERO).then_some(corners)
                });
                triangles.push(tri);
                attributes.push(LocalAttributes {
                    normal: tri.normal_area2().normalize(),
                    face: face as u32,
                    uvs,
                    normals,
                });
            }
        }
        let triangles = LocalTriangles(triangles);
        let bvh = Bvh::build(&triangles, &BvhOptions::default());
        let bounds = (0..triangles.len() as u32)
            .map(|i| triangles.bounds(i))
            .fold(Aabb::EMPTY, Aabb::union);
        self.meshes.push(LocalMesh {
            triangles,
            attributes,
            bvh,
            bounds,
        });
        (self.meshes.len() - 1) as u32
    }

    /// Whether mesh `mesh` kept any triangle (a mesh of degenerate faces keeps none).
    pub fn has_triangles(&self, mesh: u32) -> bool {
        !self.meshes[mesh as usize].triangles.0.is_empty()
    }

    /// Triangles kept for all meshes together.
    pub fn total_triangles(&self) -> usize {
        self.meshes.iter().map(|m| m.triangles.len()).sum()
    }

    /// World-space bounds of mesh `mesh` placed by `to_world`.
    pub fn placed_bounds(&self, mesh: u32, to_world: &Transform) -> Aabb {
        self.meshes[mesh as usize]
            .bounds
            .transformed(&to_world.to_world)
    }

    /// The closest hit of `ray` (world space) with placement `placement`, as a hit of
    /// primitive `prim` whose `part` is the mesh's triangle.
    pub fn intersect(
        &self,
        placement: &Placement,
        prim: u32,
        ray: &Ray,
        t_max: f32,
    ) -> Option<PrimHit> {
        let mesh = &self.meshes[placement.mesh as usize];
        // The direction is not renormalised: `t` means the same point in both spaces.
        let local = placement.to_world.ray_to_object(ray);
        let hit = mesh.bvh.closest_hit(&mesh.triangles, &local, t_max)?;
        Some(PrimHit {
            t: hit.t,
            prim,
            local: hit.local,
            part: hit.prim,
        })
    }

    /// The world-space point, normals, texture coordinates and face at barycentrics
    /// `local` of triangle `part` of `placement`'s mesh.
    pub fn describe(&self, placement: &Placement, part: u32, local: [f32; 2]) -> PlacedPoint {
        let mesh = &self.meshes[placement.mesh as usize];
        let (tri, attr) = (
            &mesh.triangles.0[part as usize],
            &mesh.attributes[part as usize],
        );
        let [b1, b2] = local;
        let b0 = 1.0 - b1 - b2;
        let to_world = &placement.to_world;
        // The inverse transpose keeps the front the transformed front, also where the
        // placement mirrors the mesh.
        let ng = to_world.normal(attr.normal).normalize();
        let ns = match attr.normals {
            Some(n) => {
                let s = to_world
                    .normal(n[0] * b0 + n[1] * b1 + n[2] * b2)
                    .normalize_or(ng);
                if s.dot(ng) < 0.0 { ng } else { s }
            }
            None => ng,
        };
        PlacedPoint {
            p: to_world.point(tri.point(b1, b2)),
            ng,
            ns,
            uv: attr.uvs[0] * b0 + attr.uvs[1] * b1 + attr.uvs[2] * b2,
            face: attr.face,
        }
    }

    /// World-space area of each of the faces of `placement`'s mesh, as `(face, m²)` per
    /// triangle.
    pub fn triangle_areas<'a>(
        &'a self,
        placement: &'a Placement,
    ) -> impl Iterator<Item = (u32, f64)> + 'a {
        let mesh = &self.meshes[placement.mesh as usize];
        mesh.triangles.0.iter().zip(&mesh.attributes).map(|(t, a)| {
            let [p0, p1, p2] = t.vertices().map(|v| placement.to_world.point(v));
            (a.face, 0.5 * f64::from((p1 - p0).cross(p2 - p0).length()))
        })
    }
}
