//! A mesh file (`.obj`, `.gltf`, `.glb`) on its own as a scene: the mesh with its materials
//! (faces without one in the default grey), seen by a 90° camera at the centre of its bounds
//! looking along +x — the standard view for benchmarks of bare meshes.

use super::LoadOptions;
use super::error::SceneError;
use super::meshes::{FaceMaterials, MeshCache};
use super::textures::TextureCache;
use crate::geometry::Aabb;
use crate::scene::{Material, Object, Scene, Shape};
use glam::Vec3;
use std::path::Path;

/// Loads the mesh file at `path` as a scene of one object named `mesh`, reading textures
/// with `options`. The scene is named after the file's stem.
pub fn load_mesh_file(path: &Path, options: &LoadOptions) -> Result<Scene, SceneError> {
    let shown = path.display().to_string();
    let error = |message: String| SceneError::Mesh { message };
    let name = path
        .file_stem()
        .map_or_else(|| shown.clone(), |s| s.to_string_lossy().into_owned());
    let mut scene = Scene::empty(&name);
    let fallback = scene.add_material(Material::default());
    let mut textures = TextureCache::new(options.max_texels);
    let faces = FaceMaterials::FromFile {
        fallback,
        file_defined: 0,
    };
    let mesh = MeshCache::default()
        .mesh(&mut scene, &mut textures, path, faces)
        .map_err(error)?;
    let bounds = Aabb::from_points(
        mesh.faces()
            .flatten()
            .filter_map(|&v| mesh.positions.get(v as usize).copied()),
    );
    if bounds.is_empty() {
        return Err(error(format!(
            "mesh file \"{shown}\": the mesh has no faces"
        )));
    }
    scene.objects.push(Object {
        name: Some("mesh".to_string()),
        shape: Shape::Mesh(mesh),
        transform: Default::default(),
        material: fallback,
        per_face: false,
    });
    view_from_centre(&mut scene, &bounds);
    Ok(scene)
}

/// Sets `scene`'s camera to the view of a bare mesh: at the centre of `bounds`, looking
/// along +x with +y up, 90°, 1024 × 1024 (the standard view for benchmarks of bare meshes).
pub(super) fn view_from_centre(scene: &mut Scene, bounds: &Aabb) {
    let centre = bounds.center();
    scene.camera.position = centre;
    scene.camera.look_at = centre + Vec3::X;
    scene.camera.up = Vec3::Y;
    scene.camera.fov_degrees = 90.0;
    scene.camera.width = 1024;
    scene.camera.height = 1024;
}
