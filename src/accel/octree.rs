//! Placeholder until the octree lands (being written now): delegates to the naive loop.

use super::{AccelStats, Accelerator, Naive, PrimHit, PrimitiveSet};
use crate::geometry::Ray;

/// Build options of the octree.
#[derive(Clone, Debug)]
pub struct OctreeOptions {
    /// Cells holding more primitives than this are split.
    pub max_objects_per_cell: usize,
    /// Cells at this depth are never split.
    pub max_depth: usize,
}

impl Default for OctreeOptions {
    fn default() -> Self {
        OctreeOptions {
            max_objects_per_cell: 8,
            max_depth: 10,
        }
    }
}

/// Octree accelerator.
pub struct Octree {
    naive: Naive,
}

impl Octree {
    /// Builds the octree over `prims`.
    pub fn build<P: PrimitiveSet>(prims: &P, _options: &OctreeOptions) -> Self {
        Octree {
            naive: Naive::build(prims),
        }
    }
}

impl<P: PrimitiveSet> Accelerator<P> for Octree {
    fn closest_hit(&self, prims: &P, ray: &Ray, t_max: f32) -> Option<PrimHit> {
        self.naive.closest_hit(prims, ray, t_max)
    }
    fn any_hit(&self, prims: &P, ray: &Ray, t_max: f32) -> bool {
        self.naive.any_hit(prims, ray, t_max)
    }
    fn stats(&self) -> AccelStats {
        <Naive as Accelerator<P>>::stats(&self.naive)
    }
}
