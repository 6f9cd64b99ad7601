//! The final gather: a radiosity solution read through the ray tracer, where the solution's
//! own resolution is not enough.
//!
//! - [`FinalGather`] (`image.rs`): an image whose direct light is ray-traced and whose
//!   indirect light is gathered from the solution at every camera hit;
//! - [`gather_surfaces`] (`surfaces.rs`): the light every reported surface receives,
//!   measured anew at points spread over it, the solution entering only two reflections
//!   away.
//!
//! It sits above the algorithms because it uses two of them.

mod image;
mod surfaces;

pub use image::FinalGather;
pub use surfaces::{
    DEFAULT_BELOW_SHARE, DEFAULT_ERROR, FIRST_PASS_ERROR, FIRST_POINTS, MAX_POINTS,
    MIN_POINTS_PER_SIDE, SurfaceGather, gather_surfaces,
};
