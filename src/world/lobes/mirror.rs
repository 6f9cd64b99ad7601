//! The ideal mirror: all the light the lobe's weight lets through leaves in the mirror
//! direction (a delta lobe: no density).

use crate::world::optics::reflect;
use glam::Vec3;

/// The mirror direction of `wo` (unit, toward the viewer) about the unit normal `n`.
#[inline]
pub fn direction(n: Vec3, wo: Vec3) -> Vec3 {
    reflect(wo, n)
}
