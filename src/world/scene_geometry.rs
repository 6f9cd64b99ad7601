//! The scene flattened for ray queries: world-space triangles (from every planar shape, mesh
//! and emissive analytic shape), analytic shapes with their world transforms, and placements
//! of meshes several objects share (`placed_mesh.rs`: their triangles kept once). It is the
//! [`PrimitiveSet`] every accelerator indexes, and it finishes hits (the second stage).
//! Primitives are numbered triangles first, then analytic shapes, then placements.

use super::placed_mesh::{MeshLibrary, PLACED_MESH_MIN_TRIANGLES, Placement};
use crate::accel::{PrimHit, PrimitiveSet};
use crate::geometry::{Aabb, LocalHit, Ray, Transform, Triangle, cuboid, plane, sphere};
use crate::scene::{AnalyticKind, MaterialId, Scene, Shape, Texture};
use glam::{Vec2, Vec3};
use std::collections::HashMap;
use std::sync::Arc;

/// Segments used when an emissive curved shape is turned into triangles for light sampling.
pub const EMITTER_SEGMENTS: u32 = 64;

/// Per-triangle data needed only after a hit.
#[derive(Clone, Copy, Debug)]
struct TriangleAttributes {
    /// Unit geometric normal of the front side (counter-clockwise vertex order).
    normal: Vec3,
    object: u32,
    face: u32,
    material: MaterialId,
    uvs: [Vec2; 3],
    /// Index into `shading_normals`, or `u32::MAX` for flat shading.
    normals: u32,
}

/// An analytic shape placed in the world.
#[derive(Clone, Debug)]
struct AnalyticInstance {
    kind: AnalyticKind,
    to_world: Transform,
    bounds: Aabb,
    object: u32,
    material: MaterialId,
}

/// Everything known about a hit after the second stage.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceHit {
    /// Ray parameter.
    pub t: f32,
    /// Hit point (world).
    pub p: Vec3,
    /// Unit geometric normal of the front side.
    pub ng: Vec3,
    /// Unit shading normal, on the same side as `ng`.
    pub ns: Vec3,
    /// Texture coordinates.
    pub uv: Vec2,
    /// Material at the hit.
    pub material: MaterialId,
    /// Scene object hit.
    pub object: u32,
    /// Face of the object (mesh face index; 0 for single-face and analytic shapes).
    pub face: u32,
    /// Primitive index in the geometry.
    pub prim: u32,
    /// True when the ray arrived on the front side.
    pub front_face: bool,
}

/// One triangle of the scene's surfaces, where points can be put on them: a copied triangle,
/// or a triangle of one copy of a placed mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceTriangle {
    /// The primitive: the triangle, or the placement.
    pub prim: u32,
    /// The triangle within a placement's mesh (0 for a copied triangle).
    pub part: u32,
    /// Scene object.
    pub object: u32,
    /// Face of the object.
    pub face: u32,
    /// Area, squared scene units.
    pub area: f64,
}

/// Error while flattening a scene.
#[derive(Debug, thiserror::Error)]
pub enum GeometryError {
    /// An object's shape is degenerate.
    #[error("object '{object}': {reason}")]
    Degenerate {
        /// Report name of the object.
        object: String,
        /// What is wrong.
        reason: String,
    },
    /// A material scatters more light than it receives (its lobe weights sum above 1 in
    /// some channel, or are not numbers): every method would create light with it.
    #[error(
        "material '{material}' scatters more than it receives: its weights sum to {sum} in \
         some channel (must be ≤ 1)"
    )]
    CreatesLight {
        /// The material's name.
        material: String,
        /// The largest per-channel sum of its lobe weights.
        sum: f32,
    },
    /// A scene given to [`super::World::relit`] whose objects or plot are not the world's.
    #[error("a relit world must have the same objects and plot as the world it comes from")]
    NotRelit,
}

/// The scene's geometry in world space, ready for ray queries.
#[derive(Clone, Debug, Default)]
pub struct SceneGeometry {
    triangles: Vec<Triangle>,
    attributes: Vec<TriangleAttributes>,
    shading_normals: Vec<[Vec3; 3]>,
    shapes: Vec<AnalyticInstance>,
    /// The meshes placed rather than copied, and their placements.
    meshes: MeshLibrary,
    placements: Vec<Placement>,
    /// Alpha texture per material (cloned so the geometry stands alone).
    alpha: Vec<Option<Texture>>,
    /// Whether any material has an alpha texture (skips the cut-out test when none does).
    any_alpha: bool,
}

impl SceneGeometry {
    /// Flattens `scene`. Emissive analytic shapes are tessellated (boxes exactly, curved ones
    /// with [`EMITTER_SEGMENTS`]) so that the surface hit and the surface sampled as a light
    /// are the same.
    pub fn new(scene: &Scene) -> Result<Self, GeometryError> {
        let mut g = SceneGeometry {
            alpha: scene
                .materials
                .iter()
                .map(|m| m.alpha_texture.map(|t| scene.textures[t as usize].clone()))
                .collect(),
            any_alpha: scene.materials.iter().any(|m| m.alpha_texture.is_some()),
            ..Default::default()
        };
        // Meshes shared by several objects, by address: placed, not copied, where they may be.
        let mut shared: HashMap<*const crate::scene::PolygonMesh, (usize, Option<u32>)> =
            HashMap::new();
        for object in &scene.objects {
            if let Shape::Mesh(mesh) = &object.shape {
                shared.entry(Arc::as_ptr(mesh)).or_insert((0, None)).0 += 1;
            }
        }
        for (index, object) in scene.objects.iter().enumerate() {
            let degenerate = |reason: String| GeometryError::Degenerate {
                object: scene.object_name(index),
                reason,
            };
            let emissive = scene.materials[object.material as usize].is_emissive();
            let analytic = object.shape.analytic();
            let tessellate_emitter = emissive && !matches!(object.shape, Shape::Plane { .. });
            match analytic {
                Some((kind, placement)) if !tessellate_emitter => {
                    let to_world = placement.then(&object.transform);
                    let bounds = match kind {
                        AnalyticKind::Plane => {
                            Aabb::new(Vec3::splat(f32::NEG_INFINITY), Vec3::splat(f32::INFINITY))
                        }
                        AnalyticKind::Sphere => {
                            Aabb::new(Vec3::splat(-1.0), Vec3::ONE).transformed(&to_world.to_world)
                        }
                        AnalyticKind::Cube => {
                            Aabb::new(Vec3::ZERO, Vec3::ONE).transformed(&to_world.to_world)
                        }
                        AnalyticKind::Frustum(_) => {
                            Aabb::new(Vec3::new(-1.0, -1.0, 0.0), Vec3::ONE)
                                .transformed(&to_world.to_world)
                        }
                    };
                    g.shapes.push(AnalyticInstance {
                        kind,
                        to_world,
                        bounds,
                        object: index as u32,
                        material: object.material,
                    });
                }
                None if object.shape.is_analytic() => {
                    return Err(degenerate(format!(
                        "degenerate {}",
                        object.shape.kind_name()
                    )));
                }
                _ if g.place(scene, index, &mut shared).map_err(degenerate)? => {}
                _ => {
                    let mesh = object.shape.to_mesh(EMITTER_SEGMENTS).map_err(degenerate)?;
                    mesh.validate().map_err(degenerate)?;
                    g.add_mesh(index as u32, object.material, &mesh, &object.transform);
                }
            }
        }
        g.sort_triangles_spatially();
        Ok(g)
    }

    /// Places object `index` as a placement of its mesh when the mesh is shared by several
    /// objects (`shared`: uses and library index per mesh address), has at least
    /// [`PLACED_MESH_MIN_TRIANGLES`] triangles (its polygons' fans) and one material, and the material neither
    /// emits nor cuts out (emitters are sampled triangle by triangle, cut-outs tested per
    /// triangle): true when placed.
    fn place(
        &mut self,
        scene: &Scene,
        index: usize,
        shared: &mut HashMap<*const crate::scene::PolygonMesh, (usize, Option<u32>)>,
    ) -> Result<bool, String> {
        let object = &scene.objects[index];
        let Shape::Mesh(mesh) = &object.shape else {
            return Ok(false);
        };
        let material = &scene.materials[object.material as usize];
        let Some((uses, placed)) = shared.get_mut(&Arc::as_ptr(mesh)) else {
            return Ok(false);
        };
        let triangles: usize = mesh.faces().map(|f| f.len().saturating_sub(2)).sum();
        if *uses < 2
            || triangles < PLACED_MESH_MIN_TRIANGLES
            || mesh.face_materials.is_some()
            || material.is_emissive()
            || material.alpha_texture.is_some()
        {
            return Ok(false);
        }
        let library = match *placed {
            Some(library) => library,
            None => {
                mesh.validate()?;
                let library = self.meshes.add(mesh);
                *placed = Some(library);
                library
            }
        };
        // A mesh of degenerate faces has no bounds to place; copied, it adds nothing.
        if !self.meshes.has_triangles(library) {
            return Ok(false);
        }
        self.placements.push(Placement {
            mesh: library,
            to_world: object.transform,
            bounds: self.meshes.placed_bounds(library, &object.transform),
            object: index as u32,
            material: object.material,
        });
        Ok(true)
    }

    /// Reorders the triangles along a Morton (Z-order) curve through their centroids, so
    /// primitive indices that are close are close in space. Accelerator leaves then read
    /// neighbouring memory. Done once here, so every accelerator sees the same indices.
    fn sort_triangles_spatially(&mut self) {
        let bounds = self
            .triangles
            .iter()
            .fold(Aabb::EMPTY, |b, t| b.union(Aabb::from_points(t.vertices())));
        if self.triangles.len() < 2 || bounds.is_empty() {
            return;
        }
        let scale = Vec3::splat(1023.0) / bounds.extent().max(Vec3::splat(f32::MIN_POSITIVE));
        let mut order: Vec<(u32, u32)> = self
            .triangles
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let c = (t.p0 + (t.e1 + t.e2) / 3.0 - bounds.min) * scale;
                (morton3(c.x as u32, c.y as u32, c.z as u32), i as u32)
            })
            .collect();
        order.sort_unstable();
        self.triangles = order
            .iter()
            .map(|&(_, i)| self.triangles[i as usize])
            .collect();
        self.attributes = order
            .iter()
            .map(|&(_, i)| self.attributes[i as usize])
            .collect();
    }

    fn add_mesh(
        &mut self,
        object: u32,
        material: MaterialId,
        mesh: &crate::scene::PolygonMesh,
        transform: &Transform,
    ) {
        let flip = transform.flips_orientation();
        let world: Vec<Vec3> = mesh.positions.iter().map(|&p| transform.point(p)).collect();
        let normals: Option<Vec<Vec3>> = mesh.normals.as_ref().map(|ns| {
            ns.iter()
                .map(|&n| transform.normal(n).normalize_or_zero())
                .collect()
        });
        for (face, indices) in mesh.faces().enumerate() {
            let face_material = mesh.face_materials.as_ref().map_or(material, |m| m[face]);
            for k in 1..indices.len() - 1 {
                let mut corner = [indices[0], indices[k], indices[k + 1]];
                if flip {
                    corner.swap(1, 2);
                }
                let [a, b, c] = corner.map(|i| i as usize);
                let tri = Triangle::new(world[a], world[b], world[c]);
                if tri.area() <= 0.0 {
                    continue;
                }
                // Without texture coordinates a triangle's corners take (0,0), (1,0), (0,1) in
                // the mesh's own order, mirrored or not (as a placed copy's do).
                let default = if flip {
                    [Vec2::ZERO, Vec2::Y, Vec2::X]
                } else {
                    [Vec2::ZERO, Vec2::X, Vec2::Y]
                };
                let uvs = mesh.uvs.as_ref().map_or(default, |u| [u[a], u[b], u[c]]);
                let normals = match &normals {
                    Some(n) if [n[a], n[b], n[c]].iter().all(|v| *v != Vec3::ZERO) => {
                        self.shading_normals.push([n[a], n[b], n[c]]);
                        (self.shading_normals.len() - 1) as u32
                    }
                    _ => u32::MAX,
                };
                self.triangles.push(tri);
                self.attributes.push(TriangleAttributes {
                    normal: tri.normal_area2().normalize(),
                    object,
                    face: face as u32,
                    material: face_material,
                    uvs,
                    normals,
                });
            }
        }
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Number of analytic shapes.
    pub fn analytic_count(&self) -> usize {
        self.shapes.len()
    }

    /// Number of placed meshes (primitives after the triangles and analytic shapes).
    pub fn placement_count(&self) -> usize {
        self.placements.len()
    }

    /// Triangles the placed meshes keep, each mesh once.
    pub fn placed_mesh_triangles(&self) -> usize {
        self.meshes.total_triangles()
    }

    /// Calls `f` with every triangle of the scene's triangle meshes: the copied triangles
    /// and every placement's (analytic shapes are not triangles).
    pub fn for_each_surface_triangle(&self, mut f: impl FnMut(SurfaceTriangle)) {
        for (prim, (tri, attr)) in self.triangles.iter().zip(&self.attributes).enumerate() {
            f(SurfaceTriangle {
                prim: prim as u32,
                part: 0,
                object: attr.object,
                face: attr.face,
                area: tri.area() as f64,
            });
        }
        let first = (self.triangles.len() + self.shapes.len()) as u32;
        for (placement, prim) in self.placements.iter().zip(first..) {
            for (part, (face, area)) in self.meshes.triangle_areas(placement).enumerate() {
                f(SurfaceTriangle {
                    prim,
                    part: part as u32,
                    object: placement.object,
                    face,
                    area,
                });
            }
        }
    }

    /// The surface at barycentrics `(b1, b2)` of `triangle`, seen from its front side.
    pub fn surface_point(&self, triangle: &SurfaceTriangle, b1: f32, b2: f32) -> SurfaceHit {
        let hit = PrimHit {
            t: 0.0,
            prim: triangle.prim,
            local: [b1, b2],
            part: triangle.part,
        };
        // The ray's direction only decides the side seen, set here.
        let surface = self.describe(&hit, &Ray::new(Vec3::ZERO, Vec3::Y));
        SurfaceHit {
            front_face: true,
            ..surface
        }
    }

    /// False where `material`'s alpha texture cuts the surface away at `uv`.
    #[inline]
    pub fn is_present(&self, material: MaterialId, uv: Vec2) -> bool {
        !self.cut_away(material, || uv)
    }

    /// Whether some material has an alpha texture, cutting surfaces away.
    pub fn has_alpha(&self) -> bool {
        self.any_alpha
    }

    /// The triangle of primitive `prim`, if it is one.
    #[inline]
    pub fn triangle(&self, prim: u32) -> Option<&Triangle> {
        self.triangles.get(prim as usize)
    }

    /// Object and material of primitive `prim`.
    #[inline]
    pub fn owner(&self, prim: u32) -> (u32, MaterialId) {
        match self.attributes.get(prim as usize) {
            Some(a) => (a.object, a.material),
            None => match self.shapes.get(prim as usize - self.triangles.len()) {
                Some(s) => (s.object, s.material),
                None => {
                    let p = self.placement(prim);
                    (p.object, p.material)
                }
            },
        }
    }

    /// The placement that is primitive `prim` (past the triangles and analytic shapes).
    #[inline]
    fn placement(&self, prim: u32) -> &Placement {
        &self.placements[prim as usize - self.triangles.len() - self.shapes.len()]
    }

    /// Bounds of all bounded primitives.
    pub fn bounds(&self) -> Aabb {
        (0..self.len() as u32)
            .map(|i| PrimitiveSet::bounds(self, i))
            .filter(|b| b.min.is_finite() && b.max.is_finite())
            .fold(Aabb::EMPTY, Aabb::union)
    }

    /// Centre and radius of a sphere holding all bounded primitives (the unit sphere at the
    /// origin when there are none).
    pub fn bounding_sphere(&self) -> (Vec3, f32) {
        let b = self.bounds();
        if b.is_empty() {
            (Vec3::ZERO, 1.0)
        } else {
            (b.center(), 0.5 * b.extent().length())
        }
    }

    /// Texture coordinates at barycentrics `(b1, b2)` of triangle `prim`.
    #[inline]
    pub fn triangle_uv(&self, prim: usize, b1: f32, b2: f32) -> Vec2 {
        let uv = &self.attributes[prim].uvs;
        uv[0] * (1.0 - b1 - b2) + uv[1] * b1 + uv[2] * b2
    }

    #[inline(always)]
    fn cut_away(&self, material: MaterialId, uv: impl FnOnce() -> Vec2) -> bool {
        self.any_alpha
            && self.alpha[material as usize]
                .as_ref()
                .is_some_and(|t| !t.is_present(uv()))
    }

    fn intersect_shape(
        &self,
        shape: &AnalyticInstance,
        ray: &Ray,
        t_max: f32,
    ) -> Option<(f32, u32)> {
        let local = shape.to_world.ray_to_object(ray);
        match shape.kind {
            AnalyticKind::Sphere => sphere::intersect(&local, t_max).map(|t| (t, 0)),
            AnalyticKind::Cube => cuboid::intersect(&local, t_max),
            AnalyticKind::Frustum(f) => f.intersect(&local, t_max),
            AnalyticKind::Plane => plane::intersect(&local, t_max).map(|t| (t, 0)),
        }
    }

    fn describe_shape(shape: &AnalyticInstance, p_local: Vec3, part: u32) -> LocalHit {
        match shape.kind {
            AnalyticKind::Sphere => sphere::describe(p_local),
            AnalyticKind::Cube => cuboid::describe(p_local, part),
            AnalyticKind::Frustum(f) => f.describe(p_local, part),
            AnalyticKind::Plane => plane::describe(p_local),
        }
    }

    /// Point and unit front normal at barycentrics `(b1, b2)` of triangle `prim`: the part of
    /// [`SceneGeometry::point_on_triangle`] light sampling needs.
    #[inline]
    pub fn triangle_point(&self, prim: u32, b1: f32, b2: f32) -> (Vec3, Vec3) {
        (
            self.triangles[prim as usize].point(b1, b2),
            self.attributes[prim as usize].normal,
        )
    }

    /// The surface description at barycentrics `(b1, b2)` of triangle `prim` (seen from its
    /// front side).
    pub fn point_on_triangle(&self, prim: u32, b1: f32, b2: f32) -> SurfaceHit {
        let toward_front = -self.triangles[prim as usize].normal_area2();
        let hit = PrimHit {
            t: 0.0,
            prim,
            local: [b1, b2],
            part: 0,
        };
        self.describe(&hit, &Ray::new(Vec3::ZERO, toward_front))
    }

    /// First stage for an analytic shape, walking past cut-away points (an alpha-textured
    /// solid shows its inside through its holes).
    #[inline(never)]
    fn intersect_analytic(&self, prim: u32, ray: &Ray, t_max: f32) -> Option<PrimHit> {
        let Some(shape) = self.shapes.get(prim as usize - self.triangles.len()) else {
            return self
                .meshes
                .intersect(self.placement(prim), prim, ray, t_max);
        };
        let mut t_start = 0.0f32;
        for _ in 0..4 {
            let moved = Ray::new(ray.at(t_start), ray.dir);
            let (t, part) = self.intersect_shape(shape, &moved, t_max - t_start)?;
            let t = t + t_start;
            let cut = self.cut_away(shape.material, || {
                let local = shape.to_world.ray_to_object(ray);
                Self::describe_shape(shape, local.at(t), part).uv
            });
            if !cut {
                return Some(PrimHit {
                    t,
                    prim,
                    local: [part as f32, 0.0],
                    part: 0,
                });
            }
            t_start = t * (1.0 + 1e-5) + 1e-7;
        }
        None
    }

    /// Second stage: the full description of `hit` found along `ray`.
    pub fn describe(&self, hit: &PrimHit, ray: &Ray) -> SurfaceHit {
        let prim = hit.prim as usize;
        let surface = if let Some(tri) = self.triangles.get(prim) {
            let attr = &self.attributes[prim];
            let [b1, b2] = hit.local;
            let b0 = 1.0 - b1 - b2;
            let ng = attr.normal;
            let ns = if attr.normals == u32::MAX {
                ng
            } else {
                let n = self.shading_normals[attr.normals as usize];
                let s = (n[0] * b0 + n[1] * b1 + n[2] * b2).normalize_or(ng);
                if s.dot(ng) < 0.0 { ng } else { s }
            };
            SurfaceHit {
                t: hit.t,
                p: tri.point(b1, b2),
                ng,
                ns,
                uv: self.triangle_uv(prim, b1, b2),
                material: attr.material,
                object: attr.object,
                face: attr.face,
                prim: hit.prim,
                front_face: true,
            }
        } else if prim >= self.triangles.len() + self.shapes.len() {
            let placement = self.placement(hit.prim);
            let at = self.meshes.describe(placement, hit.part, hit.local);
            SurfaceHit {
                t: hit.t,
                p: at.p,
                ng: at.ng,
                ns: at.ns,
                uv: at.uv,
                material: placement.material,
                object: placement.object,
                face: at.face,
                prim: hit.prim,
                front_face: true,
            }
        } else {
            let shape = &self.shapes[prim - self.triangles.len()];
            let local_ray = shape.to_world.ray_to_object(ray);
            let local = Self::describe_shape(shape, local_ray.at(hit.t), hit.local[0] as u32);
            let ng = shape.to_world.normal(local.n).normalize();
            SurfaceHit {
                t: hit.t,
                p: shape.to_world.point(local.p),
                ng,
                ns: ng,
                uv: local.uv,
                material: shape.material,
                object: shape.object,
                face: 0,
                prim: hit.prim,
                front_face: true,
            }
        };
        SurfaceHit {
            front_face: ray.dir.dot(surface.ng) < 0.0,
            ..surface
        }
    }
}

/// Interleaves the low 10 bits of three integers into a 30-bit Morton code.
fn morton3(x: u32, y: u32, z: u32) -> u32 {
    fn spread(v: u32) -> u32 {
        let mut v = v.min(1023);
        v = (v | (v << 16)) & 0x0300_00ff;
        v = (v | (v << 8)) & 0x0300_f00f;
        v = (v | (v << 4)) & 0x030c_30c3;
        (v | (v << 2)) & 0x0924_9249
    }
    spread(x) | (spread(y) << 1) | (spread(z) << 2)
}

impl PrimitiveSet for SceneGeometry {
    fn len(&self) -> usize {
        self.triangles.len() + self.shapes.len() + self.placements.len()
    }

    fn bounds(&self, prim: u32) -> Aabb {
        match self.triangles.get(prim as usize) {
            Some(t) => Aabb::from_points(t.vertices()),
            None => match self.shapes.get(prim as usize - self.triangles.len()) {
                Some(s) => s.bounds,
                None => self.placement(prim).bounds,
            },
        }
    }

    fn plain_triangle(&self, prim: u32) -> Option<Triangle> {
        let tri = self.triangles.get(prim as usize)?;
        let material = self.attributes[prim as usize].material as usize;
        self.alpha[material].is_none().then_some(*tri)
    }

    #[inline(always)]
    fn intersect(&self, prim: u32, ray: &Ray, t_max: f32) -> Option<PrimHit> {
        let index = prim as usize;
        let Some(tri) = self.triangles.get(index) else {
            return self.intersect_analytic(prim, ray, t_max);
        };
        let (t, b1, b2) = tri.intersect(ray, t_max)?;
        let cut = self.any_alpha
            && self.cut_away(self.attributes[index].material, || {
                self.triangle_uv(index, b1, b2)
            });
        (!cut).then_some(PrimHit {
            t,
            prim,
            local: [b1, b2],
            part: 0,
        })
    }
}
