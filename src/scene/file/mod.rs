//! The TOML scene file format (specified in `docs/scene-format.md`): parsing, validation and
//! building a [`Scene`], with errors that name the file, line, column and field.

mod bare_mesh;
mod build;
mod camera;
mod day;
mod error;
mod fields;
mod format;
mod lights;
mod locate;
mod materials;
mod meshes;
mod mgf_scene;
mod number_rows;
mod periodic;
mod photometry;
mod placements;
mod sensors;
mod shapes;
mod spectra;
mod sun;
mod textures;
mod transform;
mod value;

pub use bare_mesh::load_mesh_file;
pub use error::SceneError;
pub use mgf_scene::load_mgf_file;

use super::Scene;
use error::Source;
use std::path::Path;

/// How scene files are read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LoadOptions {
    /// The most texels one texture may have (16 bytes each as linear RGBA); larger images are
    /// refused from their header, before they are decoded.
    pub max_texels: u64,
}

impl Default for LoadOptions {
    /// Textures of up to [`crate::scene::MAX_TEXELS`] texels (1 GiB).
    fn default() -> Self {
        LoadOptions {
            max_texels: crate::scene::MAX_TEXELS,
        }
    }
}

/// Loads the scene file at `path` with the default [`LoadOptions`]; mesh and texture paths
/// in it are relative to its folder. The scene is named after the file's stem.
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    load_with(path, &LoadOptions::default())
}

/// Loads the scene file at `path` as [`load`] does, with `options`.
pub fn load_with(path: &Path, options: &LoadOptions) -> Result<Scene, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|e| SceneError::Unreadable {
        path: path.display().to_string(),
        reason: e.to_string(),
    })?;
    let base_dir = path.parent().unwrap_or(Path::new(""));
    load_str_with(&text, &path.display().to_string(), base_dir, options)
}

/// Loads a scene from TOML `text` with the default [`LoadOptions`]. `file_name` is used in
/// error messages (and its stem names the scene); mesh and texture paths are relative to
/// `base_dir`.
pub fn load_str(text: &str, file_name: &str, base_dir: &Path) -> Result<Scene, SceneError> {
    load_str_with(text, file_name, base_dir, &LoadOptions::default())
}

/// Loads a scene from TOML `text` as [`load_str`] does, with `options`.
pub fn load_str_with(
    text: &str,
    file_name: &str,
    base_dir: &Path,
    options: &LoadOptions,
) -> Result<Scene, SceneError> {
    build::build_scene(
        Source {
            text,
            file: file_name,
        },
        base_dir,
        options,
    )
}
