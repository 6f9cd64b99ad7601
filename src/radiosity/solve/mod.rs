//! Radiosity solvers on the leaf patches of the mesh: the full matrix with Jacobi or
//! Gauss-Seidel sweeps and progressive refinement (seed 000 ch. 5), both with the
//! emitter-only links of point (isotropic or Lambertian), spot and directional lights and the
//! sky; display of a solution (flat or smooth, with wireframe), and what a solution hands
//! on: its power per reported surface, its statistics and its lit mesh.

mod counted_twice;
mod display;
mod far_field;
pub mod hierarchical;
mod interpolate;
mod kept;
mod kept_couplings;
mod lightmap;
mod lookup;
mod matrix;
mod moves;
mod patch_triangles;
mod progressive;
mod rounds;
mod sensors;
mod solution;
mod solver_kind;
pub mod steady_state;
mod system;
mod unshot_progress;

pub use counted_twice::CountedTwice;
pub use display::{DisplaySettings, LinkDisplay, Probe, ProbeHit, render_solution, value_image};
pub use interpolate::{CornerValues, SmoothCorners, VertexWelding, vertex_radiosity};
pub use kept::KeptLinks;
pub use lookup::{LeafHit, RadiosityLookup, Shading};
pub use matrix::{
    Iteration, MAX_MATRIX_ENTRIES, MatrixSettings, solve_matrix, solve_matrix_keeping,
};
pub use progressive::{COLUMN_CACHE_BYTES, ShootingSettings, solve_progressive};
pub use rounds::RoundStats;
pub use solution::{
    CONVERGENCE_ROWS, GatheredIrradiance, LinkSegment, PhaseTimes, Solution, power_fraction,
    source_power,
};
pub use solver_kind::SolverKind;

/// At most this many items of uneven cost go to one task of a parallel loop (rayon's
/// `with_max_len`). Rayon cuts a slice into a few long runs and cuts a run again only when
/// another thread steals it; where the costly items bunch together (the sky's light links
/// before the sun's), one thread finishes early and waits: `canopy:3000`'s light links ran
/// 1.6 times as fast on two threads as on one, 1.99 times in runs of this many.
pub const UNEVEN_RUN: usize = 16;
pub use system::{Couplings, RadiositySystem, SystemOptions};

use super::MeshError;
use crate::world::GeometryError;

/// Error of a radiosity solve.
#[derive(Debug, thiserror::Error)]
pub enum SolveError {
    /// The scene could not be meshed.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// The surfaces for visibility rays could not be built.
    #[error(transparent)]
    Geometry(#[from] GeometryError),
    /// The scene has no finite surface to put patches on.
    #[error("the scene has no finite surfaces to solve radiosity on")]
    NoPatches,
    /// The full matrix would not fit.
    #[error(
        "{patches} patches need {patches}² matrix entries, more than the {limit} the matrix solver allows: use a coarser mesh or the progressive solver"
    )]
    MatrixTooLarge {
        /// Leaf patches.
        patches: usize,
        /// Largest number of entries allowed.
        limit: u64,
    },
    /// The light is hardly ever absorbed and never leaves (`steady_state.rs`).
    #[error(
        "no steady state: each bounce keeps {:.3} % of the light, so the radiosity grows without bound (surfaces that reflect all light in a closed scene); give some surface a reflectance below {}",
        100.0 * kept,
        steady_state::MAX_KEPT
    )]
    NoSteadyState {
        /// Share of the light the last bounce kept.
        kept: f64,
    },
}
