//! Hierarchical radiosity (seed 000 ch. 6): light is exchanged over links between nodes of
//! the patch quadtrees, at the level an oracle allows for each pair.
//!
//! 1. **Initial linking** (§6.3): every pair of root-patch sides that face each other and can
//!    see each other is linked, with form factor and visibility stored in the link; every
//!    root side is linked to every point, spot and directional light and the sky that reaches
//!    it. With the asymmetric linking of the mesh (`radiosity/contact.rs`, the
//!    default) faces that others stand on are split at their planes first. With clustering
//!    (the default, `clusters.rs`) root patches far apart against their size are linked as
//!    groups instead, so the links do not grow with the square of the number of faces; a
//!    cluster link the oracle refines is replaced by links to the children of its larger
//!    end, down to pairs of root patches. On a periodic plot every root side also takes
//!    what the endless field beyond the margin sends by rays (`solve/far_field.rs`).
//! 2. **Gather and push-pull** (§6.7, §6.8) until the radiosity changes by less than the
//!    tolerance: every node gathers `Σ F·V·B` over its links, irradiance is pushed down to
//!    the leaves, where it becomes `B = E + ρ·H`, and radiosity is pulled up area-weighted.
//!    The cluster links' geometry is worked out once and kept while they stay
//!    (`cluster_gather.rs`).
//! 3. **Refinement** (§6.4) by the [`Oracle`]: a link that transports its light with too
//!    large an error is replaced by links to the four children of its receiver or its
//!    emitter. `--refine-pass original` judges the links that existed when the pass began and
//!    then gathers again (the seed's faster variant); `all` also judges the links a pass
//!    creates, until none is refined, before gathering. A leaf whose texture makes the light
//!    it sends vary by more than the error (`A·Y(ΔE + Δρ·H)`, seed ch. 7) is split too: a
//!    node's emission and reflectance are the exact means of its textures, so its children
//!    resolve the texture in the light they pass on.
//! 4. Steps 2 and 3 repeat until nothing is refined.
//! 5. Every link whose emitter has been split gathers from then on from the emitter's pieces,
//!    each weighed by its form factor from the receiver (`fine_gather.rs`), and step 2 runs
//!    until the radiosity settles again.
//!
//! Link creation, the oracle and the gather run on all threads of the current rayon pool, in
//! an order that does not depend on the thread count.
//!
//! Hierarchical shooting (§5.3, [`solve_hierarchical_shooting`]) shares the quadtrees, the
//! light links, the link computation and the oracle, but keeps no patch links: each shot
//! goes from one root side to all others, its links refined at either end as the oracle
//! asks, and what a receiver takes is pushed to the leaves.

mod cluster_gather;
mod clusters;
mod fine_gather;
mod importance;
mod kept;
mod links;
mod near_rays;
mod nodes;
mod oracle;
mod shooting;
mod solver;

pub(super) use kept::PatchLinks;
pub use near_rays::NEAR_RAYS_FROM;
pub use oracle::Oracle;
pub use shooting::solve_hierarchical_shooting;
pub use solver::{solve_hierarchical, solve_hierarchical_keeping};

/// Which links a refinement pass judges.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RefinePass {
    /// The links that existed when the pass began; then gather again.
    #[default]
    Original,
    /// Every link, also those the pass creates, until none is refined.
    All,
}

crate::choice::named_values!(RefinePass {
    RefinePass::Original = "original",
        "Judge the links that existed when the pass began, then gather again";
    RefinePass::All = "all", "Judge every link, also new ones, until none is refined";
});

/// Settings of hierarchical radiosity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HierarchicalSettings {
    /// The oracle.
    pub oracle: Oracle,
    /// Largest tolerated uncertainty of the power a link brings, relative to all power
    /// emitted in the scene.
    pub error: f64,
    /// Per-surface error (the hierarchical solver; hierarchical shooting ignores it): each
    /// link is also held to about this share of the power of every reported surface its
    /// light reaches, weighed by importance (`importance.rs`); 0 leaves the scene-wide
    /// `error` alone but for measuring patches (surfaces that scatter and emit nothing), which
    /// are held to 1 % of their own light (`importance.rs`) whatever this says, unless it is
    /// smaller — by both hierarchical solvers (`shooting.rs`).
    pub surface_error: f64,
    /// Nodes are not split below this fraction of the scene's surface area.
    pub min_area: f64,
    /// Which links a refinement pass judges.
    pub refine_pass: RefinePass,
    /// Gathering stops when a gather changes the radiosity by at most this fraction of the
    /// source power.
    pub tolerance: f64,
    /// Refinement rounds at most.
    pub max_rounds: u32,
    /// Group the root patches into clusters that exchange light as a whole while they are
    /// small against their distance.
    pub clustering: bool,
    /// Scenes of at least this many root patches carry the light between clusters too close
    /// for the cluster transport by rays (`near_rays.rs`) instead of by links split down to
    /// pairs of root patches (0: every scene; `usize::MAX`: none).
    pub near_rays_from: usize,
    /// Once refinement is done, links whose emitter has been split gather from its pieces,
    /// each weighed by its form factor from the receiver (`fine_gather.rs`).
    pub fine_gather: bool,
    /// Keep every link at the end as a segment between its ends' centres
    /// (`Solution::link_segments`, for the display of links): 56 bytes a link, off unless
    /// links are shown.
    pub link_segments: bool,
}

impl Default for HierarchicalSettings {
    /// Lischinski's oracle at an error of 10⁻⁴ of the emitted power, minimum area 2·10⁻⁵
    /// of the scene, original passes, tolerance 10⁻⁴, at most 100 rounds, clustering, the
    /// near field by rays from [`NEAR_RAYS_FROM`] root patches and the final gather over the
    /// emitters' pieces on, no link segments kept.
    fn default() -> Self {
        HierarchicalSettings {
            oracle: Oracle::Lischinski,
            error: 1e-4,
            surface_error: 0.0,
            min_area: 2e-5,
            refine_pass: RefinePass::Original,
            tolerance: 1e-4,
            max_rounds: 100,
            clustering: true,
            near_rays_from: NEAR_RAYS_FROM,
            fine_gather: true,
            link_segments: false,
        }
    }
}
