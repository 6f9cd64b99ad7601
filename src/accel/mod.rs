//! Acceleration structures for ray queries: a SAH bounding-volume hierarchy (the default),
//! the seed's octree (seed 002 §4.5.2) and a naive loop, all behind [`Accelerator`].
//!
//! They work on any [`PrimitiveSet`] and give identical answers: the closest hit is the one
//! with the smallest `t`, ties broken by the smaller primitive index.

mod bvh;
mod naive;
mod octree;

pub use bvh::{Bvh, BvhOptions};
pub use naive::Naive;
pub use octree::{Octree, OctreeOptions};

use crate::geometry::{Aabb, Ray, Triangle};

/// First-stage result of a ray query: where and what was hit, without the hit description.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimHit {
    /// Ray parameter of the hit.
    pub t: f32,
    /// Index of the primitive hit.
    pub prim: u32,
    /// Primitive-specific numbers for the second stage (barycentrics of a triangle, part
    /// index of an analytic shape).
    pub local: [f32; 2],
    /// The triangle hit within a placed mesh's own triangles (0 for other primitives).
    pub part: u32,
}

impl PrimHit {
    /// True when `self` is closer than `other` (smaller `t`, ties to the smaller index).
    #[inline]
    pub fn is_closer_than(&self, other: &PrimHit) -> bool {
        self.t < other.t || (self.t == other.t && self.prim < other.prim)
    }
}

/// Moves the indices of `items` for which `pred` holds to the front (in place, unstably);
/// returns how many there are. Used to split primitive lists when building trees.
pub fn partition(items: &mut [u32], pred: impl Fn(u32) -> bool) -> usize {
    let mut first = 0;
    for i in 0..items.len() {
        if pred(items[i]) {
            items.swap(first, i);
            first += 1;
        }
    }
    first
}

/// Keeps the closer of the current best hit and a candidate.
#[inline]
pub fn keep_closest(best: &mut Option<PrimHit>, candidate: Option<PrimHit>) {
    if let Some(c) = candidate
        && best.is_none_or(|b| c.is_closer_than(&b))
    {
        *best = Some(c);
    }
}

/// A set of primitives an accelerator can index.
pub trait PrimitiveSet: Sync {
    /// Number of primitives.
    fn len(&self) -> usize;
    /// True when there are no primitives.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// World-space bounds of primitive `prim` (may be infinite for unbounded primitives).
    fn bounds(&self, prim: u32) -> Aabb;
    /// First-stage intersection: the hit with `t ∈ (0, t_max]`, if any.
    fn intersect(&self, prim: u32, ray: &Ray, t_max: f32) -> Option<PrimHit>;
    /// Primitive `prim` as a plain triangle, when [`PrimitiveSet::intersect`] for it is exactly
    /// [`Triangle::intersect`] (no cut-outs) with barycentrics as `local`. Accelerators may then
    /// store it inline and test eight at once.
    fn plain_triangle(&self, _prim: u32) -> Option<Triangle> {
        None
    }
}

/// Statistics of a built accelerator.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct AccelStats {
    /// Which accelerator.
    pub kind: &'static str,
    /// Number of primitives indexed.
    pub primitives: usize,
    /// Number of tree nodes (0 for the naive loop).
    pub nodes: usize,
    /// Number of leaves.
    pub leaves: usize,
    /// Depth of the deepest leaf.
    pub max_depth: usize,
    /// Primitive references stored in leaves (primitives can sit in several octree cells).
    pub references: usize,
}

/// An index over a primitive set answering closest-hit and any-hit queries.
pub trait Accelerator<P: PrimitiveSet>: Send + Sync {
    /// The closest hit with `t ∈ (0, t_max]`.
    fn closest_hit(&self, prims: &P, ray: &Ray, t_max: f32) -> Option<PrimHit>;
    /// Whether anything is hit with `t ∈ (0, t_max]` (shadow rays).
    fn any_hit(&self, prims: &P, ray: &Ray, t_max: f32) -> bool;
    /// Size and shape of the structure.
    fn stats(&self) -> AccelStats;
}

/// Which accelerator to build.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AccelKind {
    /// SAH bounding-volume hierarchy.
    #[default]
    Bvh,
    /// The seed's octree with Glassner cell walking.
    Octree,
    /// Test every primitive.
    Naive,
}

crate::choice::named_values!(AccelKind {
    AccelKind::Bvh = "bvh", "SAH bounding-volume hierarchy";
    AccelKind::Octree = "octree", "The seed's octree with Glassner cell walking";
    AccelKind::Naive = "naive", "Test every primitive";
});

impl AccelKind {
    /// Builds this accelerator over `prims` with default options.
    pub fn build<P: PrimitiveSet>(self, prims: &P) -> Box<dyn Accelerator<P>> {
        match self {
            AccelKind::Bvh => Box::new(Bvh::build(prims, &BvhOptions::default())),
            AccelKind::Octree => Box::new(Octree::build(prims, &OctreeOptions::default())),
            AccelKind::Naive => Box::new(Naive::build(prims)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partition_moves_the_items_below_to_the_front() {
        let mut items = [5, 1, 7, 2, 9, 3];
        let below = partition(&mut items, |x| x < 4);
        assert_eq!(below, 3);
        assert!(items[..3].iter().all(|&x| x < 4));
        assert!(items[3..].iter().all(|&x| x >= 4));
    }
}
