//! The TOML scene file format (specified in `docs/scene-format.md`): parsing, validation and
//! building a [`Scene`], with errors that name the file, line, column and field.

mod build;
mod camera;
mod error;
mod fields;
mod format;
mod lights;
mod locate;
mod materials;
mod meshes;
mod polygon;
mod shapes;
mod textures;
mod transform;
mod value;

pub use error::SceneError;

use super::Scene;
use error::Source;
use std::path::Path;

/// Loads the scene file at `path`; mesh and texture paths in it are relative to its folder.
/// The scene is named after the file's stem.
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|e| SceneError::Unreadable {
        path: path.display().to_string(),
        reason: e.to_string(),
    })?;
    let base_dir = path.parent().unwrap_or(Path::new(""));
    load_str(&text, &path.display().to_string(), base_dir)
}

/// Loads a scene from TOML `text`. `file_name` is used in error messages (and its stem names
/// the scene); mesh and texture paths are relative to `base_dir`.
pub fn load_str(text: &str, file_name: &str, base_dir: &Path) -> Result<Scene, SceneError> {
    build::build_scene(
        Source {
            text,
            file: file_name,
        },
        base_dir,
    )
}
