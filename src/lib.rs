//! strahl — a global-illumination engine: radiosity and ray tracing with per-object light
//! reports.
//!
//! Conventions (shared by every module): right-handed coordinates, y up unless a scene says
//! otherwise; lengths in scene units (metres for photometric reports); colours are linear
//! Rec.709 RGB; emission is radiance L in W·sr⁻¹·m⁻²; reflectance ρ ∈ [0, 1] per channel.

#![warn(missing_docs)]

pub mod accel;
pub mod cli;
pub mod color;
pub mod geometry;
pub mod image;
pub mod radiosity;
pub mod report;
pub mod scene;
pub mod trace;
