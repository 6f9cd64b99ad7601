//! Images: tone mapping of a [`crate::measure::Film`] to display values, image files
//! (tone-mapped sRGB PNG; linear OpenEXR and PFM), and false-colour PNGs of a
//! [`crate::measure::ValueImage`] with their legend.

mod count_map;
mod error;
mod false_color;
mod glyphs;
mod output;
mod pfm;
mod tonemap;

pub use count_map::count_map;
pub use error::ImageError;
pub use false_color::{
    FalseColor, MAX_ISOLINES, STOPS, false_color, nice_ceiling, save_false_color, scale_colour,
};
pub use glyphs::Canvas;
pub use output::{FileFormat, encode_png, load, save};
pub use tonemap::{REINHARD_KEY, ToneMap, ToneMapping};
