//! Image textures: any size, PPM/PGM (the seeds' formats), PNG and JPEG, stored as linear RGBA.

use crate::color::{Rgb, srgb_to_linear};
use glam::Vec2;
use std::path::Path;

mod average;

pub use average::{Coverage, TexelStats};

/// Where an alpha texture's alpha is below this, the surface it cuts is absent.
pub const ALPHA_CUTOFF: f32 = 0.5;

/// Index of a texture in [`super::Scene::textures`].
pub type TextureId = u32;

/// How 8-bit texel values map to linear values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColorSpace {
    /// Texel / 255, no decoding (the seeds' convention for reflectance maps).
    Linear,
    /// sRGB transfer curve decoded to linear.
    Srgb,
}

impl ColorSpace {
    /// The conventional colour space for a file: sRGB for PNG and JPEG, linear otherwise.
    pub fn default_for(path: &Path) -> ColorSpace {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
            .as_deref()
        {
            Some("png" | "jpg" | "jpeg") => ColorSpace::Srgb,
            _ => ColorSpace::Linear,
        }
    }
}

/// What a texture shows outside `[0, 1]²`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Wrap {
    /// The image repeats.
    #[default]
    Repeat,
    /// The edge texels extend outwards.
    Clamp,
}

/// Widest and tallest texture read, texels.
pub const MAX_TEXTURE_SIDE: u32 = 1 << 16;

/// The default bound on the texels of one texture (each takes 16 bytes as linear RGBA: 1 GiB).
pub const MAX_TEXELS: u64 = 1 << 26;

/// A texture: linear RGBA texels, row 0 at the top of the image. Texture coordinate
/// `(0, 0)` is the bottom-left corner and `(1, 1)` the top-right (the OBJ convention);
/// lookups outside `[0, 1]²` follow the wrap mode.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// Name (file path or a generated name).
    pub name: String,
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Row-major texels, `[r, g, b, a]`, linear.
    pub texels: Vec<[f32; 4]>,
    /// What lookups outside `[0, 1]²` see.
    pub wrap: Wrap,
}

/// Error while reading a texture file.
#[derive(Debug, thiserror::Error)]
#[error("cannot read texture '{path}': {reason}")]
pub struct TextureError {
    /// The file.
    pub path: String,
    /// What went wrong.
    pub reason: String,
}

impl Texture {
    /// A repeating texture computed per texel by `f(x, y) -> [r, g, b, a]` (row 0 on top).
    pub fn from_fn(name: &str, width: u32, height: u32, f: impl Fn(u32, u32) -> [f32; 4]) -> Self {
        let texels = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .map(|(x, y)| f(x, y))
            .collect();
        Texture {
            name: name.to_string(),
            width,
            height,
            texels,
            wrap: Wrap::Repeat,
        }
    }

    /// Reads an image file (PNG, JPEG, PPM, PGM, PAM) into linear RGBA, repeating. Grey images
    /// fill all three colour channels; images without alpha get alpha 1. An image of more
    /// than `max_texels` texels (or over [`MAX_TEXTURE_SIDE`] a side) is refused from its
    /// header, before it is decoded.
    pub fn load(path: &Path, space: ColorSpace, max_texels: u64) -> Result<Texture, TextureError> {
        let err = |reason: String| TextureError {
            path: path.display().to_string(),
            reason,
        };
        let open = || {
            image::ImageReader::open(path)
                .map_err(|e| err(e.to_string()))?
                .with_guessed_format()
                .map_err(|e| err(e.to_string()))
        };
        // The header first: a small file may declare a huge image (a decompression bomb).
        let (width, height) = open()?.into_dimensions().map_err(|e| err(e.to_string()))?;
        let texels = u64::from(width) * u64::from(height);
        if width > MAX_TEXTURE_SIDE || height > MAX_TEXTURE_SIDE || texels > max_texels {
            return Err(err(format!(
                "the image is {width}×{height} = {texels} texels; textures of at most \
                 {MAX_TEXTURE_SIDE} texels a side and {max_texels} texels in all are read \
                 (raise the bound with --max-texels)"
            )));
        }
        let img = open()?
            .decode()
            .map_err(|e| err(format!("{e} (a truncated or corrupt image?)")))?;
        if img.width() == 0 || img.height() == 0 {
            return Err(err("image is empty".into()));
        }
        let rgba = img.to_rgba32f();
        let decode = |v: f32| match space {
            ColorSpace::Linear => v,
            ColorSpace::Srgb => srgb_to_linear(v),
        };
        let texels = rgba
            .pixels()
            .map(|p| [decode(p[0]), decode(p[1]), decode(p[2]), p[3]])
            .collect();
        Ok(Texture {
            name: path.display().to_string(),
            width: img.width(),
            height: img.height(),
            texels,
            wrap: Wrap::Repeat,
        })
    }

    /// The texel at column `x`, row `y` (row 0 on top), brought into range by the wrap mode.
    pub fn texel(&self, x: i64, y: i64) -> [f32; 4] {
        let (w, h) = (self.width as i64, self.height as i64);
        let (xi, yi) = match self.wrap {
            Wrap::Repeat => (x.rem_euclid(w), y.rem_euclid(h)),
            Wrap::Clamp => (x.clamp(0, w - 1), y.clamp(0, h - 1)),
        };
        self.texels[(yi * w + xi) as usize]
    }

    /// Bilinearly filtered RGBA at texture coordinate `uv`.
    pub fn sample(&self, uv: Vec2) -> [f32; 4] {
        let x = uv.x * self.width as f32 - 0.5;
        let y = (1.0 - uv.y) * self.height as f32 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let mut out = [0.0; 4];
        for (dx, dy, w) in [
            (0, 0, (1.0 - fx) * (1.0 - fy)),
            (1, 0, fx * (1.0 - fy)),
            (0, 1, (1.0 - fx) * fy),
            (1, 1, fx * fy),
        ] {
            let t = self.texel(x0 + dx, y0 + dy);
            for c in 0..4 {
                out[c] += w * t[c];
            }
        }
        out
    }

    /// Filtered colour at `uv`.
    pub fn color(&self, uv: Vec2) -> Rgb {
        let t = self.sample(uv);
        Rgb::new(t[0], t[1], t[2])
    }

    /// Nearest-texel alpha at `uv` (cut-outs stay sharp).
    pub fn alpha(&self, uv: Vec2) -> f32 {
        let x = (uv.x * self.width as f32).floor() as i64;
        let y = ((1.0 - uv.y) * self.height as f32).floor() as i64;
        self.texel(x, y)[3]
    }

    /// Whether a surface cut by this alpha texture is present at `uv` (its nearest texel's
    /// alpha is at least [`ALPHA_CUTOFF`]).
    pub fn is_present(&self, uv: Vec2) -> bool {
        self.alpha(uv) >= ALPHA_CUTOFF
    }

    /// Mean colour over all texels.
    pub fn mean_color(&self) -> Rgb {
        let sum = self
            .texels
            .iter()
            .fold(Rgb::BLACK, |s, t| s + Rgb::new(t[0], t[1], t[2]));
        sum / self.texels.len() as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_image_declaring_a_huge_size_is_refused_before_it_is_decoded() {
        // A few bytes whose header promises 20,000 × 20,000 texels (6.4 GB as linear RGBA).
        let dir = std::env::temp_dir().join(format!("strahl-texture-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("bomb.ppm");
        std::fs::write(&path, b"P6\n20000 20000\n255\n\0\0\0").unwrap();
        let e = Texture::load(&path, ColorSpace::Srgb, MAX_TEXELS)
            .unwrap_err()
            .to_string();
        assert!(e.contains("bomb.ppm") && e.contains("20000×20000"), "{e}");
        assert!(e.contains("--max-texels"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    fn two_by_one() -> Texture {
        Texture::from_fn("t", 2, 1, |x, _| {
            if x == 0 {
                [0.0, 0.0, 0.0, 0.0]
            } else {
                [1.0, 1.0, 1.0, 1.0]
            }
        })
    }

    #[test]
    fn clamping_extends_the_edge_texels() {
        let t = Texture {
            wrap: Wrap::Clamp,
            ..two_by_one()
        };
        assert_eq!(t.color(Vec2::new(1.75, 0.5)).r, 1.0);
        assert_eq!(t.color(Vec2::new(-0.75, 0.5)).r, 0.0);
        assert_eq!(t.texel(-5, 3), [0.0; 4]);
        assert_eq!(t.texel(9, -1), [1.0; 4]);
    }

    #[test]
    fn bilinear_blends_between_texel_centres_and_wraps() {
        let t = two_by_one();
        assert!((t.color(Vec2::new(0.25, 0.5)).r - 0.0).abs() < 1e-6);
        assert!((t.color(Vec2::new(0.75, 0.5)).r - 1.0).abs() < 1e-6);
        assert!((t.color(Vec2::new(0.5, 0.5)).r - 0.5).abs() < 1e-6);
        assert!((t.color(Vec2::new(1.75, 0.5)).r - 1.0).abs() < 1e-6);
        assert_eq!(t.alpha(Vec2::new(0.1, 0.5)), 0.0);
        assert_eq!(t.alpha(Vec2::new(0.9, 0.5)), 1.0);
    }
}
