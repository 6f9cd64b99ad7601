//! What one radiosity solve of a scene keeps for the next solve of it after objects moved
//! (the viewer's moves, seed 000 requirement 5.1): the hierarchical solver's patch links
//! (`hierarchical/kept.rs`), the matrix solver's couplings and solution
//! (`kept_couplings.rs`). A solve takes what no move can have reached and computes the rest.

use super::hierarchical::PatchLinks;
use super::kept_couplings::KeptCouplings;

/// What the last radiosity solve of a scene kept for its next solve after objects moved
/// (`method::run_keeping`): the hierarchical solver's patch links, or the matrix solver's
/// couplings (the links of its flat system, between every two elements) with its solution,
/// which the next matrix solve starts from. Empty until a solve has used it.
#[derive(Debug, Default)]
pub struct KeptLinks {
    pub(super) patch_links: PatchLinks,
    pub(super) couplings: KeptCouplings,
    /// Whether the last solve was the matrix solver's.
    pub(super) last_matrix: bool,
}

impl KeptLinks {
    /// Nothing kept yet.
    pub fn new() -> KeptLinks {
        KeptLinks::default()
    }

    /// Links the last solve took from the one before: patch links (hierarchical) or
    /// couplings between two elements (matrix).
    pub fn reused(&self) -> u64 {
        if self.last_matrix {
            self.couplings.reused()
        } else {
            self.patch_links.reused()
        }
    }

    /// Links the last solve computed (as [`KeptLinks::reused`] counts them).
    pub fn computed(&self) -> u64 {
        if self.last_matrix {
            self.couplings.computed()
        } else {
            self.patch_links.computed()
        }
    }

    /// Merges what the last hierarchical solve made into the links kept (by the next
    /// solve's start at the latest): the merge costs a final solve of the Cornell box about
    /// 10 ms, which a caller in a hurry spends after showing the solution. Nothing to do
    /// when merged already.
    pub fn settle(&mut self) {
        self.patch_links.settle();
    }
}
