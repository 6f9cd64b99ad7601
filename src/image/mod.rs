//! Images: tone mapping of a [`crate::measure::Film`] to display values, and image files
//! (tone-mapped sRGB PNG; linear OpenEXR and PFM).

mod count_map;
mod error;
mod output;
mod pfm;
mod tonemap;

pub use count_map::count_map;
pub use error::ImageError;
pub use output::{FileFormat, load, save};
pub use tonemap::{REINHARD_KEY, ToneMap, ToneMapping};
