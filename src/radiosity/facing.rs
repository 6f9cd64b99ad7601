//! The facing test between two patch sides (seed 000 §4.1) refined by the support-plane
//! classification (§4.2), and whether one patch's plane must split another.

use super::clip::SideCounts;
use super::element::Side;
use super::mesh::Patch;

/// Result of the facing test between a receiver and an emitter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Facing {
    /// Each patch lies (up to touching corners) in front of the other: exchange light as they
    /// are.
    Facing,
    /// Each has a part in front of the other, but at least one straddles the other's plane:
    /// split (support-plane split) or clip before computing visibility and form factors.
    /// The solvers treat such a pair as facing: the analytic form factor clips the emitter to
    /// the receiver's front half-space, and the contact splits (`contact.rs`) have
    /// already cut the faces that touch.
    Partly,
    /// They cannot see each other (one lies entirely behind or in the plane of the other).
    Away,
}

/// The seed's facing test (§4.1) refined by the support-plane classification (§4.2), for one
/// side of each patch: the receiver's side and the emitter's side can exchange light only
/// when each patch has some part clearly in front of the other's side. Coplanar patches and
/// sides turned away are [`Facing::Away`]; touching faces (a common edge or corner,
/// otherwise in front) are [`Facing::Facing`].
pub fn facing(
    receiver: &Patch,
    receiver_side: Side,
    emitter: &Patch,
    emitter_side: Side,
) -> Facing {
    let r = SideCounts::of(&emitter_side.plane(emitter), receiver.corners());
    let e = SideCounts::of(&receiver_side.plane(receiver), emitter.corners());
    if r.front == 0 || e.front == 0 {
        Facing::Away
    } else if r.straddles() || e.straddles() {
        Facing::Partly
    } else {
        Facing::Facing
    }
}

/// True when the divisor's support plane must split `dividend` (seed §4.2 "target split"):
/// its corners lie clearly on both sides of the plane.
pub fn needs_split(divisor: &Patch, dividend: &Patch) -> bool {
    SideCounts::of(&divisor.plane(), dividend.corners()).straddles()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::radiosity::clip::{Plane, clip_to_front, split, unclipped};
    use glam::{DVec2, DVec3};
    use std::borrow::Cow;

    fn quad(corners: [[f64; 3]; 4]) -> Patch {
        Patch::new(&corners.map(DVec3::from_array), &[DVec2::ZERO; 4]).unwrap()
    }

    /// Floor `[0,1]²` at y = 0 facing up.
    fn floor() -> Patch {
        quad([
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [1.0, 0.0, 0.0],
        ])
    }

    #[test]
    fn touching_perpendicular_faces_are_facing_and_not_split() {
        // Wall at x = 0 facing +x, sharing the floor's edge x = 0.
        let wall = quad([
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 1.0, 1.0],
            [0.0, 0.0, 1.0],
        ]);
        assert!(wall.normal.x > 0.99);
        assert_eq!(
            facing(&floor(), Side::Front, &wall, Side::Front),
            Facing::Facing
        );
        assert!(!needs_split(&wall, &floor()));
        assert!(!needs_split(&floor(), &wall));
        // Scaled by 1e6 and moved far away: still exactly the same answers.
        let far = |p: &Patch| {
            let c: Vec<DVec3> = p
                .corners()
                .iter()
                .map(|&x| x * 1e6 + DVec3::splat(3e7))
                .collect();
            Patch::new(&c, &[DVec2::ZERO; 4]).unwrap()
        };
        assert_eq!(
            facing(&far(&floor()), Side::Front, &far(&wall), Side::Front),
            Facing::Facing
        );
        assert!(!needs_split(&far(&wall), &far(&floor())));
    }

    #[test]
    fn receiver_straddling_the_emitter_plane_is_split() {
        // Wall at x = 0.5 reaching below the floor plane.
        let wall = quad([
            [0.5, -0.5, 0.0],
            [0.5, 0.5, 0.0],
            [0.5, 0.5, 1.0],
            [0.5, -0.5, 1.0],
        ]);
        assert!(needs_split(&floor(), &wall));
        let pieces = split(&floor().plane(), wall.corners(), wall.uvs());
        assert_eq!(pieces.front.corners.len(), 4);
        assert_eq!(pieces.back.corners.len(), 4);
        let area = |c: &[DVec3]| Patch::new(c, &vec![DVec2::ZERO; c.len()]).unwrap().area;
        assert!((area(&pieces.front.corners) - 0.5).abs() < 1e-15);
        assert!((area(&pieces.back.corners) - 0.5).abs() < 1e-15);
        assert!(pieces.front.corners.iter().all(|p| p.y >= 0.0));
        assert_eq!(
            facing(&wall, Side::Front, &floor(), Side::Front),
            Facing::Partly
        );
    }

    #[test]
    fn one_shared_corner_still_splits_when_the_polygon_crosses() {
        // Triangle with one corner on the floor plane, one above and one below.
        let tri = Patch::new(
            &[
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(1.0, 1.0, 0.0),
                DVec3::new(1.0, -1.0, 0.5),
            ],
            &[DVec2::ZERO, DVec2::X, DVec2::Y],
        )
        .unwrap();
        assert!(needs_split(&floor(), &tri));
        let pieces = split(&floor().plane(), tri.corners(), tri.uvs());
        assert_eq!(pieces.front.corners.len(), 3);
        assert_eq!(pieces.back.corners.len(), 3);
        // The new corner lies on the plane, halfway along the crossing edge, uv halfway too.
        assert!(pieces.front.corners[2].y.abs() < 1e-15);
        assert!((pieces.front.uvs[2] - DVec2::new(0.5, 0.5)).length() < 1e-15);
    }

    #[test]
    fn back_to_back_and_coplanar_patches_are_away() {
        let under = quad([
            [0.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, -1.0, 1.0],
            [0.0, -1.0, 1.0],
        ]);
        assert!(under.normal.y < -0.99);
        assert_eq!(
            facing(&floor(), Side::Front, &under, Side::Front),
            Facing::Away
        );
        // Back to back: their back sides face each other, and no other pair of sides does.
        assert_eq!(
            facing(&floor(), Side::Back, &under, Side::Back),
            Facing::Facing
        );
        assert_eq!(
            facing(&floor(), Side::Back, &under, Side::Front),
            Facing::Away
        );
        let neighbour = quad([
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 1.0],
            [2.0, 0.0, 1.0],
            [2.0, 0.0, 0.0],
        ]);
        assert_eq!(
            facing(&floor(), Side::Front, &neighbour, Side::Front),
            Facing::Away
        );
        // The back of the floor faces the front of the patch below it.
        let below = quad([
            [0.0, -1.0, 0.0],
            [0.0, -1.0, 1.0],
            [1.0, -1.0, 1.0],
            [1.0, -1.0, 0.0],
        ]);
        assert!(below.normal.y > 0.99);
        assert_eq!(
            facing(&floor(), Side::Back, &below, Side::Front),
            Facing::Facing
        );
        assert_eq!(
            facing(&floor(), Side::Front, &below, Side::Front),
            Facing::Away
        );
    }

    #[test]
    fn a_polygon_touching_the_plane_is_not_clipped() {
        let plane = Plane::new(DVec3::ZERO, DVec3::Z);
        // A wall standing on the plane along its bottom edge.
        let wall = [
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(0.0, 1.0, 1.0),
        ];
        assert!(unclipped(&plane, &wall));
        assert!(matches!(clip_to_front(&plane, &wall), Cow::Borrowed(_)));
        // Reaching a little below it: clipped back to the wall.
        let lower = wall.map(|p| p - DVec3::Z * 0.1);
        assert!(!unclipped(&plane, &lower));
        let clipped = clip_to_front(&plane, &lower);
        assert!(clipped.iter().all(|p| p.z > -1e-12) && clipped.len() == 4);
        // Lying in the plane: nothing is in front.
        let flat = wall.map(|p| DVec3::new(p.x, p.z, 0.0));
        assert!(!unclipped(&plane, &flat));
        assert!(clip_to_front(&plane, &flat).is_empty());
    }

    #[test]
    fn clip_to_front_keeps_only_the_front_part() {
        let plane = Plane::new(DVec3::ZERO, DVec3::Z);
        let poly = [
            DVec3::new(0.0, 1.0, -1.0),
            DVec3::new(1.0, 1.0, -1.0),
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(0.0, 1.0, 1.0),
        ];
        let front = clip_to_front(&plane, &poly);
        assert_eq!(front.len(), 4);
        assert!(front.iter().all(|p| p.z >= 0.0));
        let behind: Vec<DVec3> = poly.iter().map(|p| *p - DVec3::Z * 2.0).collect();
        assert!(clip_to_front(&plane, &behind).is_empty());
        assert_eq!(
            clip_to_front(&plane, &[DVec3::Z, DVec3::new(1.0, 0.0, 1.0), DVec3::ONE]).len(),
            3
        );
    }
}
