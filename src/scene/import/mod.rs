//! Mesh importers: Wavefront OBJ with its MTL materials ([`obj`]) and glTF 2.0 ([`gltf`]);
//! and the MGF scene reader ([`mgf`]).
//!
//! Each mesh importer turns a whole file into one [`PolygonMesh`] (in the file's own
//! coordinates and units) plus the materials its faces use; the MGF reader gives one mesh per
//! MGF object. Materials and textures are not yet part of a scene: the scene loader decides
//! which of them to keep and assigns their ids.

mod faces;
pub mod gltf;
pub mod mgf;
mod mgf_color;
mod mgf_context;
mod mgf_shapes;
mod mgf_syntax;
pub mod obj;
mod obj_syntax;

use super::{ColorSpace, Material, PolygonMesh, Texture};
use std::path::{Path, PathBuf};

/// A mesh file read into memory.
#[derive(Clone, Debug, PartialEq)]
pub struct ImportedMesh {
    /// All faces of the file in one mesh, in the file's coordinates; `face_materials` is
    /// `None` (see [`ImportedMesh::face_materials`]).
    pub mesh: PolygonMesh,
    /// Per face: index into [`ImportedMesh::materials`], or `None` when the file gives the
    /// face no material (the owning object's material applies).
    pub face_materials: Vec<Option<u32>>,
    /// The materials used by the faces, in order of first use.
    pub materials: Vec<ImportedMaterial>,
    /// Images decoded from inside the file (glTF), referenced by [`TextureSource::Embedded`].
    pub embedded_textures: Vec<Texture>,
    /// Problems that did not stop the import (for example a missing material library).
    pub warnings: Vec<String>,
}

/// A material read from a mesh file. Its texture ids in `material` are `None`; the textures
/// it uses are described by the `*_texture` fields until the scene loader loads them.
#[derive(Clone, Debug, PartialEq)]
pub struct ImportedMaterial {
    /// The material's values (name as in the file; weights already within `[0, 1]` and
    /// energy-conserving).
    pub material: Material,
    /// Texture multiplied into the diffuse reflectance.
    pub diffuse_texture: Option<TextureSource>,
    /// Texture multiplied into the emitted radiance.
    pub emission_texture: Option<TextureSource>,
    /// Cut-out texture (alpha below ½ removes the surface).
    pub alpha_texture: Option<TextureSource>,
}

/// Where the texels of an imported texture come from.
#[derive(Clone, Debug, PartialEq)]
pub enum TextureSource {
    /// An image file next to the mesh file.
    File {
        /// Path of the image (already joined with the mesh file's folder).
        path: PathBuf,
        /// How the image's 8-bit values map to linear values.
        color_space: ColorSpace,
        /// Use the grey level as alpha when the image has no alpha (every texel's alpha is 1),
        /// as OBJ `map_d` dissolve maps are grey images.
        alpha_from_grey: bool,
    },
    /// An image decoded from the mesh file: index into [`ImportedMesh::embedded_textures`].
    Embedded(usize),
}

/// Error while importing a mesh file.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ImportError {
    /// The file could not be opened or read.
    #[error("cannot read mesh file \"{path}\": {reason}")]
    Unreadable {
        /// The file.
        path: String,
        /// What went wrong.
        reason: String,
    },
    /// The file was read but its content is malformed or unusable.
    #[error("mesh file \"{path}\": {reason}")]
    Invalid {
        /// The file.
        path: String,
        /// What is wrong.
        reason: String,
    },
    /// The file name has an extension no importer handles.
    #[error("mesh file \"{path}\": unsupported format (expected .obj, .gltf or .glb)")]
    UnsupportedFormat {
        /// The file.
        path: String,
    },
}

impl ImportError {
    /// An [`ImportError::Unreadable`] for `path`.
    pub(crate) fn unreadable(path: &Path, reason: impl ToString) -> Self {
        ImportError::Unreadable {
            path: path.display().to_string(),
            reason: reason.to_string(),
        }
    }

    /// An [`ImportError::Invalid`] for `path`.
    pub(crate) fn invalid(path: &Path, reason: impl ToString) -> Self {
        ImportError::Invalid {
            path: path.display().to_string(),
            reason: reason.to_string(),
        }
    }
}

/// Imports an OBJ (`.obj`) or glTF (`.gltf`, `.glb`) file, chosen by its extension
/// (case-insensitive).
pub fn load_mesh(path: &Path) -> Result<ImportedMesh, ImportError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    match extension.as_deref() {
        Some("obj") => obj::load(path),
        Some("gltf" | "glb") => gltf::load(path),
        _ => Err(ImportError::UnsupportedFormat {
            path: path.display().to_string(),
        }),
    }
}

/// Appends `mesh` to `target`, offsetting its indices. Normals survive only when both
/// meshes have them (an empty `target` counts as having them); missing texture coordinates
/// are filled with `(0, 0)`.
pub(crate) fn append_mesh(target: &mut PolygonMesh, mesh: PolygonMesh) {
    let offset = target.positions.len() as u32;
    let was_empty = target.positions.is_empty();
    let (old_len, new_len) = (target.positions.len(), mesh.positions.len());
    target.normals = match (target.normals.take(), mesh.normals) {
        (Some(mut a), Some(b)) => {
            a.extend(b);
            Some(a)
        }
        (None, Some(b)) if was_empty => Some(b),
        _ => None,
    };
    if target.uvs.is_some() || mesh.uvs.is_some() {
        let mut uvs = target
            .uvs
            .take()
            .unwrap_or_else(|| vec![glam::Vec2::ZERO; old_len]);
        uvs.extend(mesh.uvs.unwrap_or_else(|| vec![glam::Vec2::ZERO; new_len]));
        target.uvs = Some(uvs);
    }
    target.positions.extend(mesh.positions);
    target
        .indices
        .extend(mesh.indices.iter().map(|&i| i + offset));
    target.face_sizes.extend(mesh.face_sizes);
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Vec2, Vec3};

    #[test]
    fn append_offsets_indices_and_fills_missing_uvs() {
        let mut target = PolygonMesh::default();
        let tri = PolygonMesh::from_triangles(vec![Vec3::ZERO, Vec3::X, Vec3::Y], &[[0, 1, 2]]);
        append_mesh(&mut target, tri.clone());
        let mut with_uvs = tri.clone();
        with_uvs.uvs = Some(vec![Vec2::ONE; 3]);
        append_mesh(&mut target, with_uvs);
        assert_eq!(target.indices, vec![0, 1, 2, 3, 4, 5]);
        assert_eq!(target.face_sizes, vec![3, 3]);
        let uvs = target.uvs.unwrap();
        assert_eq!(uvs[0], Vec2::ZERO);
        assert_eq!(uvs[5], Vec2::ONE);
        assert!(target.normals.is_none());
    }

    #[test]
    fn unknown_extension_is_an_error() {
        let err = load_mesh(Path::new("model.stl")).unwrap_err();
        assert!(matches!(err, ImportError::UnsupportedFormat { .. }));
    }
}
