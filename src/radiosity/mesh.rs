//! The radiosity patch mesh: every planar face of the scene becomes a root patch (a triangle
//! or a convex planar quad) with a quadtree of children. Quads split into four quads at their
//! edge midpoints and vertex mean, triangles into four triangles at their edge midpoints;
//! children inherit texture coordinates by the same midpoint subdivision.
//!
//! All geometry is in world space, in `f64`, in scene units. A patch's front side is the side
//! its corners wind counter-clockwise around (its `normal` points there).

use super::clip::Plane;
use super::contact::{Face, split_at_contacts};
use crate::scene::{MaterialId, Object, PolygonMesh, Scene, Shape};
use glam::{DVec2, DVec3, Vec2, Vec3};
use rayon::prelude::*;
use std::fmt;
use std::str::FromStr;

/// Index of a patch in [`PatchMesh::patches`].
pub type PatchId = u32;

/// Relative distance from the plane of a quad's first three corners beyond which the quad is
/// treated as non-planar and split into two triangles.
const PLANARITY_TOLERANCE: f64 = 1e-6;

/// Deepest quadtree level [`MeshSize::MaxEdge`] subdivides to (4¹² leaves per root).
const MAX_UNIFORM_DEPTH: u32 = 12;

/// A planar triangle or convex quad of the mesh, with its place in the quadtree.
#[derive(Clone, Debug, PartialEq)]
pub struct Patch {
    corners: [DVec3; 4],
    uvs: [DVec2; 4],
    sides: u8,
    /// Unit normal of the front side (the side the corners wind counter-clockwise around).
    pub normal: DVec3,
    /// Area in scene units².
    pub area: f64,
    /// Area centroid (world space).
    pub centroid: DVec3,
    /// Index of the scene object the patch belongs to.
    pub object: u32,
    /// Face of the object's polygon mesh the patch comes from.
    pub face: u32,
    /// Material of the face.
    pub material: MaterialId,
    /// The patch this one was split from (`None` for a root).
    pub parent: Option<PatchId>,
    /// The four children, once split.
    pub children: Option<[PatchId; 4]>,
    /// Quadtree level: 0 for roots.
    pub depth: u32,
    /// Gauss points ([`Patch::gauss_points`]).
    gauss: [DVec3; 4],
    /// Their area weights.
    gauss_weights: [f64; 4],
}

impl Patch {
    /// A patch from a triangle or convex planar quad (corners counter-clockwise around the
    /// front side) with texture coordinates per corner. `None` when the polygon has neither
    /// 3 nor 4 corners, the lengths differ, or its area is zero or not finite.
    pub fn new(corners: &[DVec3], uvs: &[DVec2]) -> Option<Patch> {
        let sides = corners.len();
        if !(3..=4).contains(&sides) || uvs.len() != sides {
            return None;
        }
        let newell = newell_vector(corners);
        let twice_area = newell.length();
        if !(twice_area.is_finite() && twice_area > 0.0) {
            return None;
        }
        let mut c = [DVec3::ZERO; 4];
        let mut t = [DVec2::ZERO; 4];
        c[..sides].copy_from_slice(corners);
        t[..sides].copy_from_slice(uvs);
        let (gauss, gauss_weights) = gauss_rule(corners);
        Some(Patch {
            corners: c,
            uvs: t,
            sides: sides as u8,
            normal: newell / twice_area,
            area: 0.5 * twice_area,
            centroid: area_centroid(corners),
            object: 0,
            face: 0,
            material: 0,
            parent: None,
            children: None,
            depth: 0,
            gauss,
            gauss_weights,
        })
    }

    /// The Gauss points (world space): the 2 × 2 Gauss–Legendre points of a quad (exact for
    /// bicubic functions over a parallelogram), the three-point rule of a triangle (exact for
    /// quadratics). With [`Patch::gauss_weights`], the area average of a smooth function
    /// over the patch is `Σ w·f(p)`. A quad's point `k` lies in the quarter its child `k`
    /// covers, a triangle's in its corner child `k`.
    pub fn gauss_points(&self) -> &[DVec3] {
        &self.gauss[..self.sides as usize]
    }

    /// The area weights of the Gauss points (summing to 1).
    pub fn gauss_weights(&self) -> &[f64] {
        &self.gauss_weights[..self.sides as usize]
    }

    /// The support plane of the patch (front side = the patch's front side).
    #[inline]
    pub fn plane(&self) -> Plane {
        Plane::new(self.centroid, self.normal)
    }

    /// The corners, counter-clockwise around the front side (3 or 4).
    pub fn corners(&self) -> &[DVec3] {
        &self.corners[..self.sides as usize]
    }

    /// A 64-bit hash of what the patch is — its object and its corners times `scale`, bit
    /// for bit — the same for the same patch in every mesh of a scene whatever its index
    /// there (a mesh made again after an object moved numbers its patches anew).
    pub fn geometry_key(&self, scale: f64) -> u64 {
        let words = std::iter::once(u64::from(self.object)).chain(
            self.corners()
                .iter()
                .flat_map(|&c| (c * scale).to_array().map(f64::to_bits)),
        );
        words.fold(0x243F_6A88_85A3_08D3, |h, w| crate::sampling::hash64(h ^ w))
    }

    /// The texture coordinates of the corners.
    pub fn uvs(&self) -> &[DVec2] {
        &self.uvs[..self.sides as usize]
    }

    /// True for a triangle, false for a quad.
    pub fn is_triangle(&self) -> bool {
        self.sides == 3
    }

    /// Longest edge length (scene units).
    pub fn longest_edge(&self) -> f64 {
        let c = self.corners();
        (0..c.len())
            .map(|i| c[i].distance(c[(i + 1) % c.len()]))
            .fold(0.0, f64::max)
    }

    /// The point at parametric coordinates `(s, t) ∈ [0,1]²`: bilinear over a quad; over a
    /// triangle the area-preserving square-to-triangle map (so uniform `(s, t)` give uniform
    /// points and strata stay strata).
    pub fn point_at(&self, s: f64, t: f64) -> DVec3 {
        parametric(self.corners(), s, t)
    }

    /// The area element of [`Patch::point_at`] at `(s, t)`, `|∂p/∂s × ∂p/∂t|` (scene units²
    /// per unit of `s·t`): the patch's area everywhere on a triangle and a parallelogram, so
    /// that `1/area_element` is the density of uniform `(s, t)` over the patch's area.
    pub fn area_element(&self, s: f64, t: f64) -> f64 {
        if self.is_triangle() {
            return self.area;
        }
        quad_area_element(self.corners(), s, t)
    }

    /// The texture coordinates at parametric coordinates `(s, t)`, by the map of
    /// [`Patch::point_at`].
    pub fn uv_at(&self, s: f64, t: f64) -> DVec2 {
        parametric(self.uvs(), s, t)
    }

    /// The four children's corners and texture coordinates, by midpoint subdivision.
    fn split_geometry(&self) -> [(Vec<DVec3>, Vec<DVec2>); 4] {
        let (c, u) = (self.corners(), self.uvs());
        let mid = |a: usize, b: usize| ((c[a] + c[b]) * 0.5, (u[a] + u[b]) * 0.5);
        if self.is_triangle() {
            let (m01, n01) = mid(0, 1);
            let (m12, n12) = mid(1, 2);
            let (m20, n20) = mid(2, 0);
            [
                (vec![c[0], m01, m20], vec![u[0], n01, n20]),
                (vec![m01, c[1], m12], vec![n01, u[1], n12]),
                (vec![m20, m12, c[2]], vec![n20, n12, u[2]]),
                (vec![m01, m12, m20], vec![n01, n12, n20]),
            ]
        } else {
            let (m01, n01) = mid(0, 1);
            let (m12, n12) = mid(1, 2);
            let (m23, n23) = mid(2, 3);
            let (m30, n30) = mid(3, 0);
            let centre = (c[0] + c[1] + c[2] + c[3]) * 0.25;
            let centre_uv = (u[0] + u[1] + u[2] + u[3]) * 0.25;
            [
                (
                    vec![c[0], m01, centre, m30],
                    vec![u[0], n01, centre_uv, n30],
                ),
                (
                    vec![m01, c[1], m12, centre],
                    vec![n01, u[1], n12, centre_uv],
                ),
                (
                    vec![centre, m12, c[2], m23],
                    vec![centre_uv, n12, u[2], n23],
                ),
                (
                    vec![m30, centre, m23, c[3]],
                    vec![n30, centre_uv, n23, u[3]],
                ),
            ]
        }
    }
}

/// Twice the vector area of a polygon (Newell's method).
fn newell_vector(corners: &[DVec3]) -> DVec3 {
    let n = corners.len();
    (0..n).map(|i| corners[i].cross(corners[(i + 1) % n])).sum()
}

/// Area centroid of a convex planar polygon (fan of triangles from the first corner).
fn area_centroid(corners: &[DVec3]) -> DVec3 {
    let mut weighted = DVec3::ZERO;
    let mut total = 0.0;
    for k in 1..corners.len() - 1 {
        let (a, b, c) = (corners[0], corners[k], corners[k + 1]);
        let w = (b - a).cross(c - a).length();
        weighted += (a + b + c) * (w / 3.0);
        total += w;
    }
    if total > 0.0 {
        weighted / total
    } else {
        corners.iter().sum::<DVec3>() / corners.len() as f64
    }
}

/// The initial uniform subdivision of every root patch (`--mesh-size`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MeshSize {
    /// Split every root this many quadtree levels (`2ᴺ × 2ᴺ` leaves per quad root). A piece
    /// cut from a face is split to the patch size of the whole face, and a facet of a curved
    /// shape to `1/2ᴺ` of the shape's size (the longest of its bounding box's sides and its
    /// facets' edges).
    Levels(u32),
    /// Split every patch until its longest edge is at most this length (scene units).
    MaxEdge(f64),
}

impl Default for MeshSize {
    /// No initial subdivision.
    fn default() -> Self {
        MeshSize::Levels(0)
    }
}

impl fmt::Display for MeshSize {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeshSize::Levels(n) => write!(f, "levels:{n}"),
            MeshSize::MaxEdge(len) => write!(f, "{len}"),
        }
    }
}

impl FromStr for MeshSize {
    type Err = String;

    /// `levels:N` (N quadtree levels) or a positive number (the longest patch edge in scene
    /// units).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        if let Some(levels) = s.strip_prefix("levels:") {
            return levels
                .trim()
                .parse::<u32>()
                .ok()
                .filter(|&n| n <= MAX_UNIFORM_DEPTH)
                .map(MeshSize::Levels)
                .ok_or_else(|| {
                    format!("mesh size '{s}': levels must be an integer 0..={MAX_UNIFORM_DEPTH}")
                });
        }
        match s.trim().parse::<f64>() {
            Ok(len) if len.is_finite() && len > 0.0 => Ok(MeshSize::MaxEdge(len)),
            _ => Err(format!(
                "mesh size '{s}': expected 'levels:N' or a positive edge length"
            )),
        }
    }
}

/// How the scene is turned into patches.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshOptions {
    /// Segments around the axis for curved shapes (spheres, cylinders, cones, frusta).
    pub segments: u32,
    /// Initial uniform subdivision.
    pub size: MeshSize,
    /// Split faces that other faces touch at the toucher's plane first
    /// (`contact.rs`), so no patch lies partly inside a touching solid.
    pub contact_splits: bool,
    /// Most patches (all quadtree nodes) the mesh may have before any refinement: a finer
    /// initial mesh is refused with [`MeshError::TooManyPatches`].
    pub max_patches: usize,
}

impl Default for MeshOptions {
    /// 16 segments, no initial subdivision, contact splits, at most 4 million patches.
    fn default() -> Self {
        MeshOptions {
            segments: 16,
            size: MeshSize::default(),
            contact_splits: true,
            max_patches: 4_000_000,
        }
    }
}

/// Error while building the patch mesh.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum MeshError {
    /// An object's shape cannot be turned into polygons.
    #[error("object '{object}': {reason}")]
    Shape {
        /// Report name of the object.
        object: String,
        /// What is wrong.
        reason: String,
    },
    /// The initial mesh would exceed [`MeshOptions::max_patches`].
    #[error(
        "the mesh would have more than {limit} patches: choose a coarser --mesh-size or fewer \
         --segments, or raise --max-patches"
    )]
    TooManyPatches {
        /// The bound that was reached.
        limit: usize,
    },
}

/// The world-space faces of object `index` of `scene` (`object`), curved shapes
/// tessellated with `segments`; `None` for an infinite plane, which has no finite surface.
fn object_faces(
    scene: &Scene,
    index: usize,
    object: &Object,
    segments: u32,
) -> Result<Option<Vec<Face>>, MeshError> {
    if matches!(object.shape, Shape::Plane { .. }) {
        return Ok(None);
    }
    let error = |reason: String| MeshError::Shape {
        object: scene.object_name(index),
        reason,
    };
    let polygons = object.shape.to_mesh(segments).map_err(error)?;
    polygons.validate().map_err(error)?;
    let to_world = |p: Vec3| object.transform.point(p).as_dvec3();
    let mut faces = world_faces(
        &polygons,
        index as u32,
        object.material,
        to_world,
        object.transform.flips_orientation(),
    );
    if object.shape.is_curved() {
        // The facets are parts of one surface as large as the shape.
        let size = shape_size(&faces);
        for face in &mut faces {
            face.source_edge = size;
            face.part = true;
        }
    }
    Ok(Some(faces))
}

/// All patches of a scene: the roots (one per planar face) and every quadtree node below them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PatchMesh {
    /// Every patch, roots and children; indexed by [`PatchId`].
    pub patches: Vec<Patch>,
    /// The root patches, in scene order (object, then face).
    pub roots: Vec<PatchId>,
    /// Objects left out because they have no finite surface (infinite planes). They still
    /// block light in visibility tests.
    pub skipped_objects: Vec<u32>,
    /// The scale the patches' keys take their corners in ([`PatchMesh::patch_key`]): one
    /// over the power of two at or below the diagonal of the faces' bounding box, so that a
    /// scene scaled by a power of two keys its patches alike (0 in a mesh not made from a
    /// scene: the corners as they are).
    pub key_scale: f64,
}

impl PatchMesh {
    /// What patch `id` is: [`Patch::geometry_key`] in the mesh's [`PatchMesh::key_scale`].
    pub fn patch_key(&self, id: PatchId) -> u64 {
        let scale = if self.key_scale > 0.0 {
            self.key_scale
        } else {
            1.0
        };
        self.patch(id).geometry_key(scale)
    }

    /// The patch mesh of `scene`: every planar face (polygons, mesh faces, parallelograms,
    /// box faces, curved shapes tessellated with `options.segments`) becomes a root patch,
    /// non-planar quads and faces with more than four corners become triangle fans; then every
    /// root is subdivided as `options.size` asks. Degenerate faces (zero area) are dropped.
    pub fn from_scene(scene: &Scene, options: &MeshOptions) -> Result<PatchMesh, MeshError> {
        let mut mesh = PatchMesh::default();
        // Each object's faces on its own (in parallel: a canopy has thousands of leaves),
        // then taken in scene order, the first error with them.
        let per_object: Vec<Result<Option<Vec<Face>>, MeshError>> = scene
            .objects
            .par_iter()
            .enumerate()
            .map(|(index, object)| object_faces(scene, index, object, options.segments))
            .collect();
        let count = per_object.iter().flatten().flatten().map(Vec::len).sum();
        let mut faces = Vec::with_capacity(count);
        for (index, object_faces) in per_object.into_iter().enumerate() {
            match object_faces? {
                Some(object_faces) => faces.extend(object_faces),
                None => mesh.skipped_objects.push(index as u32),
            }
        }
        if options.contact_splits {
            faces = split_at_contacts(faces);
        }
        let corners = faces.iter().flat_map(|f| f.corners.iter());
        let (lo, hi) = corners.fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &c| {
            (lo.min(c), hi.max(c))
        });
        let diagonal = (hi - lo).length();
        if diagonal.is_finite() && diagonal > 0.0 {
            mesh.key_scale = (-diagonal.log2().floor()).exp2();
        }
        for face in faces {
            // A piece cut from a face is subdivided to the patch size the whole face would
            // have had, not by as many levels again; a facet of a curved shape to that of a
            // face as large as the shape.
            let size = match options.size {
                MeshSize::Levels(n) if face.part => MeshSize::MaxEdge(
                    face.source_edge / f64::from(1u32 << n.min(MAX_UNIFORM_DEPTH)),
                ),
                size => size,
            };
            for (c, u) in planar_pieces(&face.corners, &face.uvs) {
                if let Some(mut patch) = Patch::new(&c, &u) {
                    patch.object = face.object;
                    patch.face = face.face;
                    patch.material = face.material;
                    let bound = (mesh.len() as u64).saturating_add(uniform_tree_size(&patch, size));
                    if bound > options.max_patches as u64 {
                        return Err(MeshError::TooManyPatches {
                            limit: options.max_patches,
                        });
                    }
                    let id = mesh.push(patch);
                    mesh.roots.push(id);
                    mesh.subdivide_uniformly(id, size);
                }
            }
        }
        Ok(mesh)
    }

    fn push(&mut self, patch: Patch) -> PatchId {
        self.patches.push(patch);
        (self.patches.len() - 1) as PatchId
    }

    /// The patch with id `id`.
    pub fn patch(&self, id: PatchId) -> &Patch {
        &self.patches[id as usize]
    }

    /// Number of patches (all quadtree nodes).
    pub fn len(&self) -> usize {
        self.patches.len()
    }

    /// True when the scene had no finite surfaces.
    pub fn is_empty(&self) -> bool {
        self.patches.is_empty()
    }

    /// Splits patch `id` into four children (midpoint subdivision) and returns their ids; a
    /// patch already split returns its existing children.
    pub fn subdivide(&mut self, id: PatchId) -> [PatchId; 4] {
        if let Some(children) = self.patch(id).children {
            return children;
        }
        let parent = self.patch(id).clone();
        let mut ids = [0; 4];
        for (k, (corners, uvs)) in parent.split_geometry().into_iter().enumerate() {
            // Midpoint children of a valid patch have a quarter of its area, never zero.
            let mut child = Patch::new(&corners, &uvs).unwrap_or_else(|| Patch {
                area: parent.area * 0.25,
                ..parent.clone()
            });
            child.normal = parent.normal;
            child.object = parent.object;
            child.face = parent.face;
            child.material = parent.material;
            child.parent = Some(id);
            child.children = None;
            child.depth = parent.depth + 1;
            ids[k] = self.push(child);
        }
        self.patches[id as usize].children = Some(ids);
        ids
    }

    /// Subdivides the subtree under `id` uniformly to `size`.
    pub fn subdivide_uniformly(&mut self, id: PatchId, size: MeshSize) {
        let mut stack = vec![id];
        while let Some(p) = stack.pop() {
            let patch = self.patch(p);
            let split = match size {
                MeshSize::Levels(n) => patch.depth < n.min(MAX_UNIFORM_DEPTH),
                MeshSize::MaxEdge(len) => {
                    patch.longest_edge() > len && patch.depth < MAX_UNIFORM_DEPTH
                }
            };
            if split {
                stack.extend(self.subdivide(p));
            }
        }
    }

    /// The leaves under `id` (itself when unsplit), depth first.
    pub fn leaves_under(&self, id: PatchId) -> Vec<PatchId> {
        let mut out = Vec::new();
        let mut stack = vec![id];
        while let Some(p) = stack.pop() {
            match self.patch(p).children {
                Some(children) => stack.extend(children.iter().rev()),
                None => out.push(p),
            }
        }
        out
    }

    /// All leaves of the mesh, root by root.
    pub fn leaves(&self) -> Vec<PatchId> {
        self.roots
            .iter()
            .flat_map(|&r| self.leaves_under(r))
            .collect()
    }
}

/// The most nodes [`PatchMesh::subdivide_uniformly`] can give the quadtree of `root` (itself
/// included), known before any is made: `(4ᵈ⁺¹ − 1)/3` for the depth `d` it reaches.
fn uniform_tree_size(root: &Patch, size: MeshSize) -> u64 {
    let depth = match size {
        MeshSize::Levels(n) => n.min(MAX_UNIFORM_DEPTH),
        MeshSize::MaxEdge(len) => {
            // Each split halves every edge of a quad or triangle.
            let ratio = root.longest_edge() / len;
            if ratio > 1.0 {
                (ratio.log2().ceil() as u32).min(MAX_UNIFORM_DEPTH)
            } else {
                0
            }
        }
    };
    ((1u64 << (2 * (depth + 1))) - 1) / 3
}

/// The faces of `polygons` in world space (corners counter-clockwise around the front even
/// when `flip` mirrors the object), with texture coordinates.
fn world_faces(
    polygons: &PolygonMesh,
    object: u32,
    material: MaterialId,
    to_world: impl Fn(Vec3) -> DVec3,
    flip: bool,
) -> Vec<Face> {
    let world: Vec<DVec3> = polygons.positions.iter().map(|&p| to_world(p)).collect();
    polygons
        .faces()
        .enumerate()
        .map(|(face, indices)| {
            let mut order: Vec<usize> = indices.iter().map(|&i| i as usize).collect();
            if flip {
                order.reverse();
            }
            let corners: Vec<DVec3> = order.iter().map(|&i| world[i]).collect();
            Face {
                source_edge: Face::longest_edge(&corners),
                part: false,
                corners,
                uvs: order
                    .iter()
                    .enumerate()
                    .map(|(k, &i)| {
                        polygons
                            .uvs
                            .as_ref()
                            .map_or_else(|| default_uv(k, order.len()), |u| u[i])
                            .as_dvec2()
                    })
                    .collect(),
                object,
                face: face as u32,
                material: polygons
                    .face_materials
                    .as_ref()
                    .map_or(material, |m| m[face]),
            }
        })
        .collect()
}

/// The size of a curved shape from its facets, scene units: the longest of its bounding
/// box's sides and its facets' edges (a cone's slant is longer than its height).
fn shape_size(facets: &[Face]) -> f64 {
    let (lo, hi) = facets
        .iter()
        .flat_map(|f| f.corners.iter())
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &c| {
            (lo.min(c), hi.max(c))
        });
    facets
        .iter()
        .map(|f| Face::longest_edge(&f.corners))
        .fold((hi - lo).max_element(), f64::max)
}

/// Default texture coordinates of corner `k` of an `n`-gon without any: the unit square for
/// quads, `(0,0), (1,0), (0,1)` for triangles, the unit circle mapped to `[0,1]²` otherwise.
fn default_uv(k: usize, n: usize) -> Vec2 {
    match (n, k) {
        (4, _) => [Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y][k],
        (3, _) => [Vec2::ZERO, Vec2::X, Vec2::Y][k],
        _ => {
            let a = std::f32::consts::TAU * k as f32 / n as f32;
            Vec2::new(0.5 + 0.5 * a.cos(), 0.5 + 0.5 * a.sin())
        }
    }
}

/// A face as root-patch polygons: triangles and planar quads as they are, everything else
/// (non-planar quads, faces with more than four corners) as a triangle fan.
fn planar_pieces(corners: &[DVec3], uvs: &[DVec2]) -> Vec<(Vec<DVec3>, Vec<DVec2>)> {
    let n = corners.len();
    let planar_quad = n == 4 && {
        let normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
        let size = (corners[2] - corners[0]).length();
        normal.length() > 0.0
            && (corners[3] - corners[0]).dot(normal.normalize()).abs() <= PLANARITY_TOLERANCE * size
    };
    if n == 3 || planar_quad {
        return vec![(corners.to_vec(), uvs.to_vec())];
    }
    (1..n - 1)
        .map(|k| {
            (
                vec![corners[0], corners[k], corners[k + 1]],
                vec![uvs[0], uvs[k], uvs[k + 1]],
            )
        })
        .collect()
}

/// The value at parametric `(s, t)` of per-corner values `c` (3 for a triangle, 4 for a quad)
/// by the map of [`Patch::point_at`].
/// [`Patch::area_element`] of the quad with corners `c` at `(s, t)`.
fn quad_area_element(c: &[DVec3], s: f64, t: f64) -> f64 {
    let along_s = (c[1] - c[0]).lerp(c[2] - c[3], t);
    let along_t = c[3].lerp(c[2], s) - c[0].lerp(c[1], s);
    along_s.cross(along_t).length()
}

/// The Gauss points of the triangle or quad with corners `c` and their area weights
/// ([`Patch::gauss_points`]; unused entries zero).
fn gauss_rule(c: &[DVec3]) -> ([DVec3; 4], [f64; 4]) {
    if c.len() == 3 {
        let (a, b) = (2.0 / 3.0, 1.0 / 6.0);
        let points = [
            c[0] * a + c[1] * b + c[2] * b,
            c[0] * b + c[1] * a + c[2] * b,
            c[0] * b + c[1] * b + c[2] * a,
            DVec3::ZERO,
        ];
        return (points, [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, 0.0]);
    }
    let g = 0.5 / 3f64.sqrt();
    let st = [
        (0.5 - g, 0.5 - g),
        (0.5 + g, 0.5 - g),
        (0.5 + g, 0.5 + g),
        (0.5 - g, 0.5 + g),
    ];
    let elements = st.map(|(s, t)| quad_area_element(c, s, t));
    let total: f64 = elements.iter().sum();
    (
        st.map(|(s, t)| parametric(c, s, t)),
        elements.map(|e| e / total),
    )
}

fn parametric<T>(c: &[T], s: f64, t: f64) -> T
where
    T: Copy + std::ops::Add<Output = T> + std::ops::Mul<f64, Output = T>,
{
    // The same operations as glam's `lerp`: a·(1 − s) + b·s.
    let lerp = |a: T, b: T, s: f64| a * (1.0 - s) + b * s;
    if c.len() == 3 {
        let r = s.sqrt();
        c[0] * (1.0 - r) + c[1] * (r * (1.0 - t)) + c[2] * (r * t)
    } else {
        lerp(lerp(c[0], c[1], s), lerp(c[3], c[2], s), t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Transform;
    use crate::scene::{Material, Object};

    #[test]
    fn gauss_points_integrate_quadratics_exactly() {
        // ∫ x² over the unit square is 1/3, over the triangle (0,0),(1,0),(0,1) (mean) 1/6.
        let mean = |patch: &Patch, f: fn(DVec3) -> f64| -> f64 {
            let weights = patch.gauss_weights();
            assert!((weights.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            patch
                .gauss_points()
                .iter()
                .zip(weights)
                .map(|(&p, w)| w * f(p))
                .sum()
        };
        let square = Patch::new(
            &[DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            &[DVec2::ZERO; 4],
        )
        .unwrap();
        let m = mean(&square, |p| p.x * p.x);
        assert!((m - 1.0 / 3.0).abs() < 1e-14, "{m}");
        let tri = Patch::new(&[DVec3::ZERO, DVec3::X, DVec3::Y], &[DVec2::ZERO; 3]).unwrap();
        let m = mean(&tri, |p| p.x * p.y);
        assert!((m - 1.0 / 12.0).abs() < 1e-14, "{m}");
        // A trapezoid: the weights follow the area element.
        let trapezoid = Patch::new(
            &[
                DVec3::ZERO,
                DVec3::new(4.0, 0.0, 0.0),
                DVec3::new(3.0, 1.0, 0.0),
                DVec3::new(1.0, 1.0, 0.0),
            ],
            &[DVec2::ZERO; 4],
        )
        .unwrap();
        let m = mean(&trapezoid, |p| p.y);
        // Centroid height of a trapezoid with parallel sides 4 (y = 0) and 2 (y = 1): 4/9.
        assert!((m - 4.0 / 9.0).abs() < 1e-14, "{m}");
    }

    fn square() -> Patch {
        Patch::new(
            &[
                DVec3::ZERO,
                DVec3::new(2.0, 0.0, 0.0),
                DVec3::new(2.0, 2.0, 0.0),
                DVec3::new(0.0, 2.0, 0.0),
            ],
            &[DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y],
        )
        .unwrap()
    }

    #[test]
    fn quad_has_area_normal_and_centroid() {
        let p = square();
        assert!((p.area - 4.0).abs() < 1e-15);
        assert!((p.normal - DVec3::Z).length() < 1e-15);
        assert!((p.centroid - DVec3::new(1.0, 1.0, 0.0)).length() < 1e-15);
    }

    #[test]
    fn trapezoid_centroid_is_the_area_centroid_not_the_vertex_mean() {
        // Trapezoid with parallel sides 2 (y=0) and 1 (y=1): centroid y = (2·1+1)/(3·3)·1 = 4/9.
        let p = Patch::new(
            &[
                DVec3::ZERO,
                DVec3::new(2.0, 0.0, 0.0),
                DVec3::new(1.5, 1.0, 0.0),
                DVec3::new(0.5, 1.0, 0.0),
            ],
            &[DVec2::ZERO; 4],
        )
        .unwrap();
        assert!((p.centroid.y - 4.0 / 9.0).abs() < 1e-14);
        assert!((p.area - 1.5).abs() < 1e-14);
    }

    #[test]
    fn degenerate_polygons_are_rejected() {
        let line = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        assert!(Patch::new(&line, &[DVec2::ZERO; 3]).is_none());
        assert!(Patch::new(&[DVec3::ZERO, DVec3::X], &[DVec2::ZERO; 2]).is_none());
    }

    #[test]
    fn children_tile_the_parent_and_inherit_midpoint_uvs() {
        let mut mesh = PatchMesh::default();
        let root = mesh.push(square());
        mesh.roots.push(root);
        let kids = mesh.subdivide(root);
        let total: f64 = kids.iter().map(|&k| mesh.patch(k).area).sum();
        assert!((total - 4.0).abs() < 1e-14);
        let first = mesh.patch(kids[0]);
        assert_eq!(first.uvs()[2], DVec2::new(0.5, 0.5));
        assert_eq!(first.corners()[2], DVec3::new(1.0, 1.0, 0.0));
        assert_eq!(first.depth, 1);
        assert_eq!(first.parent, Some(root));
        assert_eq!(
            mesh.subdivide(root),
            kids,
            "splitting twice keeps the children"
        );
    }

    #[test]
    fn triangle_splits_into_four_triangles_of_equal_area() {
        let mut mesh = PatchMesh::default();
        let tri = Patch::new(
            &[DVec3::ZERO, DVec3::X, DVec3::Y],
            &[DVec2::ZERO, DVec2::X, DVec2::Y],
        )
        .unwrap();
        let root = mesh.push(tri);
        for k in mesh.subdivide(root) {
            let child = mesh.patch(k);
            assert!(child.is_triangle());
            assert!((child.area - 0.125).abs() < 1e-15);
            assert!((child.normal - DVec3::Z).length() < 1e-15);
        }
    }

    #[test]
    fn uniform_levels_give_four_to_the_n_leaves() {
        let mut scene = Scene::empty("t");
        let m = scene.add_material(Material::default());
        scene.add_object(
            "box",
            Shape::Box {
                min: Vec3::ZERO,
                max: Vec3::ONE,
            },
            m,
        );
        let options = MeshOptions {
            segments: 8,
            size: MeshSize::Levels(2),
            ..MeshOptions::default()
        };
        let mesh = PatchMesh::from_scene(&scene, &options).unwrap();
        assert_eq!(mesh.roots.len(), 6);
        let leaves = mesh.leaves();
        assert_eq!(leaves.len(), 6 * 16);
        let area: f64 = leaves.iter().map(|&l| mesh.patch(l).area).sum();
        assert!((area - 6.0).abs() < 1e-6);
        // Box faces point out of the box.
        for &r in &mesh.roots {
            let p = mesh.patch(r);
            assert!((p.centroid - DVec3::splat(0.5)).dot(p.normal) > 0.49);
        }
    }

    #[test]
    fn levels_cut_a_curved_shape_to_a_share_of_its_size_not_of_each_facet() {
        // A ball of diameter 0.8 at levels:3: patches of at most 0.1, so each of its 128
        // facets (edges about 0.16) is split once, not 3 levels (8,192 patches).
        let mut scene = Scene::empty("t");
        let m = scene.add_material(Material::default());
        scene.add_object(
            "ball",
            Shape::Sphere {
                center: Vec3::ZERO,
                radius: 0.4,
            },
            m,
        );
        let options = MeshOptions {
            segments: 16,
            size: MeshSize::Levels(3),
            ..MeshOptions::default()
        };
        let mesh = PatchMesh::from_scene(&scene, &options).unwrap();
        assert_eq!(mesh.roots.len(), 128);
        let leaves = mesh.leaves();
        assert_eq!(leaves.len(), 4 * 128);
        assert!(leaves.iter().all(|&l| mesh.patch(l).longest_edge() <= 0.1));
    }

    #[test]
    fn max_edge_refines_until_edges_are_short_enough() {
        let mut mesh = PatchMesh::default();
        let root = mesh.push(square());
        mesh.roots.push(root);
        mesh.subdivide_uniformly(root, MeshSize::MaxEdge(0.6));
        let leaves = mesh.leaves();
        assert_eq!(leaves.len(), 16, "edge 2 → 0.5 after two levels");
        assert!(leaves.iter().all(|&l| mesh.patch(l).longest_edge() <= 0.6));
    }

    #[test]
    fn mirrored_transform_keeps_the_normal_on_the_winding_side() {
        let mut scene = Scene::empty("t");
        let m = scene.add_material(Material::default());
        scene.objects.push(Object {
            name: None,
            shape: Shape::Parallelogram {
                origin: Vec3::ZERO,
                edge_u: Vec3::X,
                edge_v: Vec3::Y,
            },
            transform: Transform::scale(Vec3::new(-1.0, 1.0, 1.0)).unwrap(),
            material: m,
            per_face: false,
        });
        let mesh = PatchMesh::from_scene(&scene, &MeshOptions::default()).unwrap();
        // The mirrored parallelogram's front (edge_u × edge_v = +z) stays +z.
        assert!((mesh.patch(0).normal - DVec3::Z).length() < 1e-12);
    }

    #[test]
    fn non_planar_quads_and_pentagons_become_triangles() {
        let bent = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.3), DVec3::Y];
        assert_eq!(planar_pieces(&bent, &[DVec2::ZERO; 4]).len(), 2);
        let pentagon: Vec<DVec3> = (0..5)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 5.0;
                DVec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        assert_eq!(planar_pieces(&pentagon, &[DVec2::ZERO; 5]).len(), 3);
    }

    #[test]
    fn mesh_size_parses_levels_and_edge_lengths() {
        assert_eq!("levels:4".parse(), Ok(MeshSize::Levels(4)));
        assert_eq!("0.25".parse(), Ok(MeshSize::MaxEdge(0.25)));
        assert!("-1".parse::<MeshSize>().is_err());
        assert!("levels:x".parse::<MeshSize>().is_err());
    }
}
