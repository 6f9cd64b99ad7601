//! `type = "mesh"` objects: importing each mesh file once and merging its materials into the
//! scene.
//!
//! An imported material keeps its name unless the scene file defines a material of that name
//! (the scene file's wins). When another mesh file already brought a different material of
//! the same name, the newcomer is renamed `NAME@FILE` (`NAME@FILE#2`, … if needed).

use super::textures::TextureCache;
use crate::scene::import::{self, ImportedMaterial, ImportedMesh, TextureSource};
use crate::scene::{Material, MaterialId, PolygonMesh, Scene, TextureId, Wrap};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// One imported file and the scene ids of its materials (once assigned).
struct Imported {
    data: ImportedMesh,
    material_ids: Option<Vec<MaterialId>>,
}

/// Mesh files imported so far in the scene being built.
#[derive(Default)]
pub(super) struct MeshCache {
    files: HashMap<PathBuf, Imported>,
    /// (canonical path, object material when the faces may fall back to it) → mesh.
    built: HashMap<(PathBuf, Option<MaterialId>), Arc<PolygonMesh>>,
}

/// How the faces of a mesh object get their materials.
#[derive(Clone, Copy, Debug)]
pub(super) enum FaceMaterials {
    /// Every face uses the object's material (`material = "…"` was given).
    Object,
    /// Faces use the file's materials; faces without one use this material.
    FromFile {
        /// Material of faces the file gives no material.
        fallback: MaterialId,
        /// Number of leading scene materials that the scene file defined.
        file_defined: usize,
    },
}

impl MeshCache {
    /// The mesh of file `path` with face materials per `faces`. Warnings of the import are
    /// printed to stderr when the file is first read. The error message names the path.
    pub fn mesh(
        &mut self,
        scene: &mut Scene,
        textures: &mut TextureCache,
        path: &Path,
        faces: FaceMaterials,
    ) -> Result<Arc<PolygonMesh>, String> {
        let canonical = path
            .canonicalize()
            .map_err(|e| format!("cannot read mesh file \"{}\": {e}", path.display()))?;
        if !self.files.contains_key(&canonical) {
            let data = import::load_mesh(path).map_err(|e| e.to_string())?;
            for warning in &data.warnings {
                eprintln!("warning: {warning}");
            }
            self.files.insert(
                canonical.clone(),
                Imported {
                    data,
                    material_ids: None,
                },
            );
        }
        let fallback = match faces {
            FaceMaterials::Object => None,
            FaceMaterials::FromFile { fallback, .. } => Some(fallback),
        };
        let key = (canonical.clone(), fallback);
        if let Some(mesh) = self.built.get(&key) {
            return Ok(mesh.clone());
        }
        let imported = self
            .files
            .get_mut(&canonical)
            .ok_or("mesh file vanished from the cache")?;
        let mut mesh = imported.data.mesh.clone();
        if let FaceMaterials::FromFile {
            fallback,
            file_defined,
        } = faces
        {
            if imported.material_ids.is_none() {
                let ids = imported
                    .data
                    .materials
                    .iter()
                    .map(|m| {
                        add_material(scene, textures, &imported.data, m, &canonical, file_defined)
                    })
                    .collect::<Result<Vec<_>, _>>()
                    .map_err(|e| format!("mesh file \"{}\": {e}", path.display()))?;
                imported.material_ids = Some(ids);
            }
            let ids = imported.material_ids.as_deref().unwrap_or(&[]);
            let per_face = &imported.data.face_materials;
            if per_face.iter().any(Option::is_some) {
                mesh.face_materials = Some(
                    per_face
                        .iter()
                        .map(|f| {
                            f.and_then(|i| ids.get(i as usize).copied())
                                .unwrap_or(fallback)
                        })
                        .collect(),
                );
            }
        }
        let mesh = Arc::new(mesh);
        self.built.insert(key, mesh.clone());
        Ok(mesh)
    }
}

/// The scene id for imported material `m` of mesh file `mesh_path`, adding it (with its
/// textures) unless the scene file defines that name.
fn add_material(
    scene: &mut Scene,
    textures: &mut TextureCache,
    data: &ImportedMesh,
    m: &ImportedMaterial,
    mesh_path: &Path,
    file_defined: usize,
) -> Result<MaterialId, String> {
    let name = m.material.name.as_str();
    if let Some(id) = scene
        .material_id(name)
        .filter(|&id| (id as usize) < file_defined)
    {
        return Ok(id);
    }
    let mut texture = |source: &Option<TextureSource>| -> Result<Option<TextureId>, String> {
        match source {
            None => Ok(None),
            Some(TextureSource::File {
                path,
                color_space,
                alpha_from_grey,
            }) => textures
                .file(scene, path, *color_space, *alpha_from_grey, Wrap::Repeat)
                .map(Some),
            Some(TextureSource::Embedded(i)) => {
                let t = data
                    .embedded_textures
                    .get(*i)
                    .ok_or_else(|| format!("embedded image {i} is missing"))?;
                Ok(Some(textures.embedded(scene, mesh_path, *i, t)))
            }
        }
    };
    let material = Material {
        diffuse_texture: texture(&m.diffuse_texture)?,
        emission_texture: texture(&m.emission_texture)?,
        alpha_texture: texture(&m.alpha_texture)?,
        ..m.material.clone()
    };
    let file = mesh_path
        .file_name()
        .map_or_else(String::new, |f| f.to_string_lossy().into_owned());
    let mut attempt = 0u32;
    loop {
        let candidate = match attempt {
            0 => name.to_string(),
            1 => format!("{name}@{file}"),
            n => format!("{name}@{file}#{n}"),
        };
        let renamed = Material {
            name: candidate,
            ..material.clone()
        };
        match scene.material_id(&renamed.name) {
            None => return Ok(scene.add_material(renamed)),
            Some(id) if scene.materials[id as usize] == renamed => return Ok(id),
            Some(_) => attempt += 1,
        }
    }
}
