//! Turning a SCENE argument into a scene: a built-in name, a scene file (`.toml`) or a bare
//! mesh file (`.obj`, `.gltf`, `.glb`) viewed from the centre of its bounds.

use anyhow::{Context, Result, bail};
use glam::Vec3;
use std::path::Path;
use strahl::scene::{self, LoadOptions, Scene};

/// True for paths that name a mesh file rather than a scene file.
pub fn is_mesh_file(spec: &str) -> bool {
    let ext = Path::new(spec)
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    matches!(ext.as_deref(), Some("obj" | "gltf" | "glb"))
}

/// Loads the scene named by `spec`, reading files with `options`.
pub fn load(spec: &str, options: &LoadOptions) -> Result<Scene> {
    if let Some(builtin) = scene::builtin::load(spec) {
        return builtin.map_err(|e| anyhow::anyhow!("{spec}: {e}"));
    }
    let path = Path::new(spec);
    if !path.exists() {
        let names: Vec<&str> = scene::builtin::names().iter().map(|(n, _)| *n).collect();
        bail!(
            "'{spec}' is neither a file nor a built-in scene (built-in: {})",
            names.join(", ")
        );
    }
    if is_mesh_file(spec) {
        return load_bare_mesh(path, options);
    }
    Ok(scene::load_with(path, options)?)
}

/// A scene holding just the mesh in `path` (default grey material), with a 90° camera at the
/// centre of the mesh bounds looking along +x. This is the standard view for benchmarks of
/// bare meshes.
fn load_bare_mesh(path: &Path, options: &LoadOptions) -> Result<Scene> {
    let absolute = path
        .canonicalize()
        .with_context(|| format!("cannot open {}", path.display()))?;
    let file = toml::Value::String(absolute.display().to_string());
    let text = format!(
        "[camera]\nposition = [0, 0, 0]\nlook_at = [1, 0, 0]\nfov = 90\n\n\
         [[objects]]\nname = \"mesh\"\ntype = \"mesh\"\nfile = {file}\n"
    );
    let mut scene =
        scene::load_str_with(&text, &path.display().to_string(), Path::new("."), options)?;
    let geometry = strahl::world::SceneGeometry::new(&scene)?;
    let bounds = geometry.bounds();
    if bounds.is_empty() {
        bail!("{}: the mesh has no faces", path.display());
    }
    let centre = bounds.center();
    scene.camera.position = centre;
    scene.camera.look_at = centre + Vec3::X;
    scene.camera.up = Vec3::Y;
    scene.camera.fov_degrees = 90.0;
    scene.camera.width = 1024;
    scene.camera.height = 1024;
    Ok(scene)
}
