//! What each round of a hierarchical solve did, as a solution keeps it.

/// What one round did.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct RoundStats {
    /// Links created by the round's refinement.
    pub links_created: u64,
    /// Links refined (replaced by links to children).
    pub links_refined: u64,
    /// Blocked links looked at again with more rays.
    pub links_looked: u64,
    /// Links after the round (patch links, cluster links and light links).
    pub links: u64,
    /// Of those, links with a cluster at one end at least.
    pub cluster_links: u64,
    /// Of those, blocked patch links (no ray between their ends arrived; they carry
    /// nothing).
    pub blocked_links: u64,
    /// Leaf patches after the round.
    pub leaves: u64,
    /// Visibility and shadow rays cast so far.
    pub rays: u64,
    /// Radiosity change of the round's last gather, as a fraction of the source power.
    pub residual: f64,
    /// Gathers (bounces) in the round.
    pub gathers: u32,
    /// Seconds spent creating links (initial linking in the first round).
    pub seconds_linking: f64,
    /// Seconds spent judging links, with the importance solve that sets their thresholds
    /// under `--surface-error`.
    pub seconds_refine: f64,
    /// Seconds spent gathering.
    pub seconds_gather: f64,
    /// Seconds spent in push-pull.
    pub seconds_push_pull: f64,
    /// Peak resident memory of the process at the end of the round, bytes (where the system
    /// reports it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_memory_bytes: Option<u64>,
}
