//! A solution between the rounds of a solver that refines in rounds, for an observer that
//! shows it while it refines (the seed's observer mode, 000 §13.1).

use super::LitMesh;

/// The solution after one round: the leaves so far, each side lit flat by its own light.
#[derive(Clone, Debug, Default)]
pub struct RoundSolution {
    /// The round, from 1.
    pub round: usize,
    /// Links in use.
    pub links: u64,
    /// Leaf patches.
    pub leaves: u64,
    /// The round's convergence measure (the solver's own: for hierarchical radiosity the
    /// largest change of a gather, as a share of the emitted power).
    pub change: f64,
    /// Every side of every leaf with its radiosity and irradiance (the same at each corner),
    /// W·m⁻².
    pub mesh: LitMesh,
}
