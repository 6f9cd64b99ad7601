//! strahl — a global-illumination engine: radiosity and ray tracing with per-object light
//! reports.
//!
//! Conventions (shared by every module): right-handed coordinates, y up unless a scene says
//! otherwise; lengths in scene units (metres for photometric reports); colours are linear
//! Rec.709 RGB; emission is radiance L in W·sr⁻¹·m⁻²; reflectance ρ ∈ [0, 1] per channel.
//!
//! The modules form layers; each imports only the layers below it (`docs/ARCHITECTURE.md`
//! has the map):
//!
//! 1. [`color`], [`geometry`], [`lanes`], [`sampling`], [`progress`], [`choice`],
//!    [`atomic_file`], [`sky`] — foundations;
//! 2. [`scene`] — the scene model, its files and the built-in scenes;
//! 3. [`accel`] — acceleration structures over any primitive set;
//! 4. [`world`] — the scene compiled for ray queries;
//! 5. [`measure`] — what the algorithms fill: films, surface power, lit meshes;
//! 6. [`trace`], [`light_model`], [`radiosity`] — the algorithms, which never import each
//!    other;
//! 7. [`final_gather`] — images from two algorithms together (ray-traced direct light,
//!    indirect light from radiosity);
//! 8. [`method`] — every method named with its settings and run by one call: the API the
//!    command line, the validation suite and embedding programs use;
//! 9. [`image`], then [`report`] — files made from what was measured;
//! 10. [`validate`] — the analytic validation suite, which runs the methods on scenes with
//!     closed-form answers.

//! # Embedding
//!
//! Programs run strahl through [`method`]: build or [open](scene::open) a scene, compile it
//! into a [`world::World`] shared by [`std::sync::Arc`], and [`method::run`] any method on
//! it; the outcome is owned (image, per-surface measurement, radiosity solution). The
//! example `examples/embed.rs`, run here as a test:
//!
#![doc = concat!("```\n", include_str!("../examples/embed.rs"), "\n```")]
#![warn(missing_docs)]

pub mod accel;
pub mod atomic_file;
pub mod choice;
pub mod color;
pub mod final_gather;
pub mod geometry;
pub mod image;
pub mod lanes;
pub mod light_model;
pub mod measure;
pub mod method;
pub mod progress;
pub mod radiosity;
pub mod report;
pub mod sampling;
pub mod scene;
pub mod sky;
pub mod trace;
pub mod validate;
pub mod world;
