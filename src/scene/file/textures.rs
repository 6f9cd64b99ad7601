//! Loading textures into a scene once per file (and per decoding).

use crate::scene::{ColorSpace, Scene, Texture, TextureId, Wrap};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Textures already added to the scene being built, so each image is loaded once.
#[derive(Debug)]
pub(super) struct TextureCache {
    /// The bound on one texture's texels.
    max_texels: u64,
    /// (canonical path, sRGB?, alpha from grey?, wrap) → texture.
    files: HashMap<(PathBuf, bool, bool, Wrap), TextureId>,
    /// (canonical mesh path, embedded image index) → texture.
    embedded: HashMap<(PathBuf, usize), TextureId>,
}

impl TextureCache {
    /// An empty cache reading textures of at most `max_texels` texels.
    pub fn new(max_texels: u64) -> TextureCache {
        TextureCache {
            max_texels,
            files: HashMap::new(),
            embedded: HashMap::new(),
        }
    }

    /// The id of image file `path` decoded with `space` and wrapped by `wrap`, loading it on
    /// first use. With `alpha_from_grey`, an image whose alpha is 1 everywhere takes its
    /// alpha from its grey level (mean of the channels). The error message names the path.
    pub fn file(
        &mut self,
        scene: &mut Scene,
        path: &Path,
        space: ColorSpace,
        alpha_from_grey: bool,
        wrap: Wrap,
    ) -> Result<TextureId, String> {
        let canonical = path
            .canonicalize()
            .map_err(|e| format!("cannot read texture \"{}\": {e}", path.display()))?;
        let key = (canonical, space == ColorSpace::Srgb, alpha_from_grey, wrap);
        if let Some(&id) = self.files.get(&key) {
            return Ok(id);
        }
        let mut texture = Texture::load(path, space, self.max_texels).map_err(|e| e.to_string())?;
        texture.wrap = wrap;
        if alpha_from_grey && texture.texels.iter().all(|t| t[3] == 1.0) {
            for t in &mut texture.texels {
                t[3] = (t[0] + t[1] + t[2]) / 3.0;
            }
        }
        let id = scene.add_texture(texture);
        self.files.insert(key, id);
        Ok(id)
    }

    /// The id of image `index` embedded in mesh file `mesh` (canonical path), adding
    /// `texture` on first use.
    pub fn embedded(
        &mut self,
        scene: &mut Scene,
        mesh: &Path,
        index: usize,
        texture: &Texture,
    ) -> TextureId {
        *self
            .embedded
            .entry((mesh.to_path_buf(), index))
            .or_insert_with(|| scene.add_texture(texture.clone()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_file_names_the_path() {
        let mut scene = Scene::empty("t");
        let mut cache = TextureCache::new(crate::scene::MAX_TEXELS);
        let err = cache
            .file(
                &mut scene,
                Path::new("no/such/file.ppm"),
                ColorSpace::Linear,
                false,
                Wrap::Repeat,
            )
            .unwrap_err();
        assert!(err.contains("no/such/file.ppm"), "{err}");
        assert!(scene.textures.is_empty());
    }

    #[test]
    fn embedded_images_are_added_once() {
        let mut scene = Scene::empty("t");
        let mut cache = TextureCache::new(crate::scene::MAX_TEXELS);
        let tex = Texture::from_fn("e", 1, 1, |_, _| [1.0; 4]);
        let a = cache.embedded(&mut scene, Path::new("/m.glb"), 0, &tex);
        let b = cache.embedded(&mut scene, Path::new("/m.glb"), 0, &tex);
        let c = cache.embedded(&mut scene, Path::new("/m.glb"), 1, &tex);
        assert_eq!((a, b, c), (0, 0, 1));
        assert_eq!(scene.textures.len(), 2);
    }
}
