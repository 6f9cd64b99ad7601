//! The image loops: an integrator driven over the camera's pixels on all threads of the
//! current rayon pool, with progress and cancellation — tiles with antialiasing for any
//! integrator ([`render`]), whole-image passes of a few samples per pixel for Monte Carlo
//! integrators ([`render_progressive`], or any range of their samples, [`render_samples`]),
//! summed exactly per pixel ([`PixelSums`]). Every sample's random numbers depend only on the
//! seed and its image position, so images do not depend on the thread count.

pub mod antialias;
mod passes;
mod sums;
mod tiles;

pub use antialias::AntialiasMode;
pub use passes::{
    ProgressiveOutput, ProgressiveSettings, RenderedSamples, render_progressive, render_samples,
};
pub use sums::PixelSums;
pub use tiles::{RenderOutput, RenderSettings, render};
