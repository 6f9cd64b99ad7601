//! Errors while reading or writing image files.

use std::path::PathBuf;

/// The file extensions [`super::save`] and [`super::load`] understand, for messages.
pub(super) const SUPPORTED_EXTENSIONS: &str = ".png, .exr, .pfm";

/// Error while reading or writing an image file; every message names the file.
#[derive(Debug, thiserror::Error)]
pub enum ImageError {
    /// The file extension names no supported format.
    #[error(
        "'{}': unsupported image file extension {}; supported: {SUPPORTED_EXTENSIONS}",
        path.display(),
        extension.as_deref().map_or("(none)".to_string(), |e| format!("'.{e}'"))
    )]
    UnsupportedExtension {
        /// The file.
        path: PathBuf,
        /// Its extension without the dot, `None` when it has none.
        extension: Option<String>,
    },
    /// A false-colour image was asked for in a format other than PNG.
    #[error(
        "'{}': a false-colour image is written as PNG (its colours and legend are display \
         colours, not radiance); name a .png file",
        path.display()
    )]
    FalseColorNotPng {
        /// The file.
        path: PathBuf,
    },
    /// The film has no pixels, which the file formats cannot store.
    #[error("cannot write '{}': the image is empty ({width}×{height})", path.display())]
    EmptyImage {
        /// The file.
        path: PathBuf,
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
    },
    /// Reading or writing the file failed.
    #[error("cannot access '{}': {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating-system error.
        source: std::io::Error,
    },
    /// The PNG encoder or decoder failed.
    #[error("PNG file '{}': {source}", path.display())]
    Png {
        /// The file.
        path: PathBuf,
        /// The codec error.
        source: ::image::ImageError,
    },
    /// The OpenEXR encoder or decoder failed.
    #[error("OpenEXR file '{}': {source}", path.display())]
    Exr {
        /// The file.
        path: PathBuf,
        /// The codec error.
        source: exr::error::Error,
    },
    /// A PFM file is malformed.
    #[error("PFM file '{}': {reason}", path.display())]
    Pfm {
        /// The file.
        path: PathBuf,
        /// What is malformed.
        reason: String,
    },
}
