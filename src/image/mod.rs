//! Images: the film that renderers fill with linear radiance, tone mapping to display
//! values, and image files (tone-mapped sRGB PNG; linear OpenEXR and PFM).

mod error;
mod film;
mod output;
mod pfm;
mod srgb;
mod tonemap;

pub use error::ImageError;
pub use film::Film;
pub use output::{FileFormat, load, save};
pub use srgb::linear_to_srgb;
pub use tonemap::{REINHARD_KEY, ToneMap, ToneMapping};
