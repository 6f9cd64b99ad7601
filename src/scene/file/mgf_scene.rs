//! An MGF file as a scene: one object per MGF object (faces outside every object in one named
//! after the file's stem), the MGF materials (each once), seen by a 90° camera at the centre
//! of the bounds looking along +x, as a bare mesh is ([`super::load_mesh_file`]). Materials
//! that emit (`ed`) make their faces area lights for every method.

use super::error::SceneError;
use crate::geometry::Aabb;
use crate::scene::import::mgf;
use crate::scene::{Object, Scene, Shape};
use std::path::Path;
use std::sync::Arc;

/// Loads the MGF file at `path` (with the files it includes) as a scene named after the
/// file's stem. Warnings of the import are printed to stderr.
pub fn load_mgf_file(path: &Path) -> Result<Scene, SceneError> {
    let error = |message: String| SceneError::Mesh { message };
    let read = mgf::load(path).map_err(|e| error(e.to_string()))?;
    for warning in &read.warnings {
        eprintln!("warning: {warning}");
    }
    let name = path.file_stem().map_or_else(
        || path.display().to_string(),
        |s| s.to_string_lossy().into_owned(),
    );
    let mut scene = Scene::empty(&name);
    let first = scene.materials.len() as u32;
    scene.materials.extend(read.materials);
    let mut bounds = Aabb::from_points(std::iter::empty());
    for object in read.objects {
        let mut mesh = object.mesh;
        bounds = bounds.union(Aabb::from_points(mesh.positions.iter().copied()));
        let ids: Vec<u32> = object.face_materials.iter().map(|&m| first + m).collect();
        let material = ids.first().copied().unwrap_or(first);
        if ids.iter().any(|&m| m != material) {
            mesh.face_materials = Some(ids);
        }
        scene.objects.push(Object {
            name: Some(object.name),
            shape: Shape::Mesh(Arc::new(mesh)),
            transform: Default::default(),
            material,
            per_face: false,
        });
    }
    if bounds.is_empty() {
        return Err(error(format!(
            "MGF file \"{}\": the file has no faces",
            path.display()
        )));
    }
    super::bare_mesh::view_from_centre(&mut scene, &bounds);
    Ok(scene)
}
