//! Polygon meshes (from OBJ, glTF or built in): shared vertices, faces of three or more
//! vertices, optional normals and texture coordinates, and a material per face.

use super::MaterialId;
use glam::{Vec2, Vec3};

/// A polygon mesh in its object space. Faces are convex and planar (triangles, quads, …);
/// each lists indices into the vertex arrays, counter-clockwise seen from its front side.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PolygonMesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Per-vertex shading normals (same length as `positions`), if any.
    pub normals: Option<Vec<Vec3>>,
    /// Per-vertex texture coordinates (same length as `positions`), if any.
    pub uvs: Option<Vec<Vec2>>,
    /// Vertex indices of all faces, concatenated.
    pub indices: Vec<u32>,
    /// Number of vertices of each face (≥ 3), in order.
    pub face_sizes: Vec<u32>,
    /// Material of each face; `None` means the owning object's material for all faces.
    pub face_materials: Option<Vec<MaterialId>>,
}

impl PolygonMesh {
    /// A mesh from triangles only.
    pub fn from_triangles(positions: Vec<Vec3>, triangles: &[[u32; 3]]) -> Self {
        PolygonMesh {
            positions,
            indices: triangles.iter().flatten().copied().collect(),
            face_sizes: vec![3; triangles.len()],
            ..Default::default()
        }
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.face_sizes.len()
    }

    /// The vertex indices of every face, in order.
    pub fn faces(&self) -> impl Iterator<Item = &[u32]> + '_ {
        let mut start = 0usize;
        self.face_sizes.iter().map(move |&n| {
            let face = &self.indices[start..start + n as usize];
            start += n as usize;
            face
        })
    }

    /// Number of triangles after fan triangulation.
    pub fn triangle_count(&self) -> usize {
        self.face_sizes.iter().map(|&n| n as usize - 2).sum()
    }

    /// Checks that every index is in range, every face has at least three vertices and the
    /// optional arrays have matching lengths; the message names the first problem.
    pub fn validate(&self) -> Result<(), String> {
        let n = self.positions.len();
        if self.face_sizes.iter().any(|&s| s < 3) {
            return Err("a face has fewer than 3 vertices".into());
        }
        let total: usize = self.face_sizes.iter().map(|&s| s as usize).sum();
        if total != self.indices.len() {
            return Err("face sizes do not add up to the index count".into());
        }
        if let Some(i) = self.indices.iter().find(|&&i| i as usize >= n) {
            return Err(format!("vertex index {i} out of range ({n} vertices)"));
        }
        if self.normals.as_ref().is_some_and(|v| v.len() != n) {
            return Err("normal count differs from vertex count".into());
        }
        if self.uvs.as_ref().is_some_and(|v| v.len() != n) {
            return Err("texture coordinate count differs from vertex count".into());
        }
        if self
            .face_materials
            .as_ref()
            .is_some_and(|m| m.len() != self.face_count())
        {
            return Err("face material count differs from face count".into());
        }
        if self.positions.iter().any(|p| !p.is_finite()) {
            return Err("a vertex position is not finite".into());
        }
        Ok(())
    }
}
