//! From what a user names to a scene, in one call: a built-in scene (`cornell`,
//! `spheres:200`, …), a scene file (`.toml`), an MGF file (`.mgf`) or a bare mesh file
//! (`.obj`, `.gltf`, `.glb`).

use super::file::{LoadOptions, SceneError, load_mesh_file, load_mgf_file, load_with};
use super::{Scene, builtin};
use std::path::Path;

/// Why a named scene could not be opened.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum OpenError {
    /// A built-in scene refused its parameter.
    #[error("{spec}: {message}")]
    Builtin {
        /// The name as given (`spheres:x`).
        spec: String,
        /// What is wrong with it.
        message: String,
    },
    /// The name is neither a file nor a built-in scene.
    #[error("'{spec}' is neither a file nor a built-in scene (built-in: {})", .builtins.join(", "))]
    Unknown {
        /// The name as given.
        spec: String,
        /// The built-in scenes' names.
        builtins: Vec<&'static str>,
    },
    /// The scene or mesh file could not be read (the message names file, line and field).
    #[error(transparent)]
    File(#[from] SceneError),
}

/// True for paths that name a mesh file rather than a scene file.
pub fn is_mesh_file(path: &Path) -> bool {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    matches!(ext.as_deref(), Some("obj" | "gltf" | "glb"))
}

/// True for paths that name an MGF file (`.mgf`, any case).
fn is_mgf_file(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("mgf"))
}

/// The scene named by `spec`: a built-in scene when one has that name, else the scene file,
/// MGF file (`docs/scene-format.md`, "MGF files") or bare mesh file (see
/// [`load_mesh_file`]) at that path, read with `options`.
pub fn open(spec: &str, options: &LoadOptions) -> Result<Scene, OpenError> {
    if let Some(built) = builtin::load(spec) {
        return built.map_err(|message| OpenError::Builtin {
            spec: spec.to_string(),
            message,
        });
    }
    let path = Path::new(spec);
    if !path.exists() {
        return Err(OpenError::Unknown {
            spec: spec.to_string(),
            builtins: builtin::names().iter().map(|(n, _)| *n).collect(),
        });
    }
    Ok(if is_mgf_file(path) {
        load_mgf_file(path)?
    } else if is_mesh_file(path) {
        load_mesh_file(path, options)?
    } else {
        load_with(path, options)?
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_open_built_in_scenes_and_mesh_files() {
        let options = LoadOptions::default();
        assert_eq!(open("cornell", &options).unwrap().name, "cornell");
        let mesh = open("tests/data/tiny.gltf", &options).unwrap();
        assert_eq!(mesh.objects.len(), 1);
        assert_eq!(mesh.camera.fov_degrees, 90.0);
        let mgf = open("tests/data/cornell.mgf", &options).unwrap();
        assert_eq!((mgf.name.as_str(), mgf.objects.len()), ("cornell", 8));
        assert_eq!(mgf.camera.fov_degrees, 90.0);
        let e = open("nowhere-at-all", &options).unwrap_err().to_string();
        assert!(e.contains("neither a file nor a built-in scene") && e.contains("cornell"));
        let e = open("spheres:x", &options).unwrap_err().to_string();
        assert!(e.starts_with("spheres:x: "), "{e}");
        // A bare mesh's errors name the file as the user gave it.
        let dir = std::env::temp_dir().join(format!("strahl-open-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let lonely = dir.join("points.obj");
        std::fs::write(&lonely, "v 0 0 0\nv 1 0 0\n").unwrap();
        let e = open(lonely.to_str().unwrap(), &options)
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            format!("mesh file \"{}\": the mesh has no faces", lonely.display())
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
