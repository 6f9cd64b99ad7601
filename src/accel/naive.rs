//! The naive accelerator: every ray tests every primitive (seed 002 §4.5,
//! `DefaultIntersectionProcessor`).

use super::{AccelStats, Accelerator, PrimHit, PrimitiveSet, keep_closest};
use crate::geometry::Ray;

/// Tests all primitives in a loop.
#[derive(Clone, Debug)]
pub struct Naive {
    count: u32,
}

impl Naive {
    /// Builds the (trivial) index over `prims`.
    pub fn build<P: PrimitiveSet>(prims: &P) -> Self {
        Naive {
            count: prims.len() as u32,
        }
    }
}

impl<P: PrimitiveSet> Accelerator<P> for Naive {
    fn closest_hit(&self, prims: &P, ray: &Ray, t_max: f32) -> Option<PrimHit> {
        let mut best: Option<PrimHit> = None;
        for prim in 0..self.count {
            let limit = best.map_or(t_max, |b| b.t);
            keep_closest(&mut best, prims.intersect(prim, ray, limit));
        }
        best
    }

    fn any_hit(&self, prims: &P, ray: &Ray, t_max: f32) -> bool {
        (0..self.count).any(|prim| prims.intersect(prim, ray, t_max).is_some())
    }

    fn stats(&self) -> AccelStats {
        AccelStats {
            kind: "naive",
            primitives: self.count as usize,
            references: self.count as usize,
            ..Default::default()
        }
    }
}
