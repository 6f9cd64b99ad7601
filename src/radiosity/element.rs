//! The unknowns of radiosity: one side of one patch. Every surface has two sides, each with its
//! own radiosity, as the ray tracers and the light model see it: a side reflects when the
//! material does on that side, a translucent material passes light to the other side (the back
//! of a `one_sided` material reflects nothing but still absorbs what reaches it) and emits when
//! the material emits there (the back only for a `two_sided` emitter).

use super::clip::Plane;
use super::mesh::{Patch, PatchId};
use glam::DVec3;

/// One of the two sides of a patch.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Side {
    /// The side the patch's normal points to (corners counter-clockwise).
    Front,
    /// The other side.
    Back,
}

impl Side {
    /// Both sides, front first.
    pub const BOTH: [Side; 2] = [Side::Front, Side::Back];

    /// The unit normal of `patch` on this side.
    #[inline]
    pub fn normal(self, patch: &Patch) -> DVec3 {
        match self {
            Side::Front => patch.normal,
            Side::Back => -patch.normal,
        }
    }

    /// The support plane of this side of `patch` (front side = this side).
    #[inline]
    pub fn plane(self, patch: &Patch) -> Plane {
        Plane::new(patch.centroid, self.normal(patch))
    }

    /// The side a direction `dir` arriving at `patch` hits (the front when it travels against
    /// the normal).
    #[inline]
    pub fn hit_by(patch: &Patch, dir: DVec3) -> Side {
        if dir.dot(patch.normal) < 0.0 {
            Side::Front
        } else {
            Side::Back
        }
    }

    /// The other side.
    #[inline]
    pub fn other(self) -> Side {
        match self {
            Side::Front => Side::Back,
            Side::Back => Side::Front,
        }
    }

    /// 0 for the front, 1 for the back (for per-side arrays).
    #[inline]
    pub fn index(self) -> usize {
        self as usize
    }
}

/// One side of one patch: an unknown of the radiosity system.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Element {
    /// The patch.
    pub patch: PatchId,
    /// Which of its sides.
    pub side: Side,
}
