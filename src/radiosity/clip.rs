//! Facing test and support-plane split (seed 000 §4.1, §4.2): which side of a patch's plane
//! another polygon lies on, with an epsilon band so that shared and touching corners (the
//! seed's "variable" points) never cause a split, and Sutherland–Hodgman splitting and
//! clipping of polygons (with their texture coordinates) at a plane.

use super::element::Side;
use super::mesh::Patch;
use glam::{DVec2, DVec3};
use std::borrow::Cow;

/// Relative width of the band around a plane in which a point counts as lying on it: the band
/// is this fraction of the size of the configuration tested, so the answer does not change
/// when the scene is scaled.
pub const PLANE_EPSILON: f64 = 1e-9;

/// An oriented plane `normal · x = offset` (unit normal; front side where `normal · x > offset`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// Unit normal of the front side.
    pub normal: DVec3,
    /// `normal · x` for points on the plane (scene units).
    pub offset: f64,
}

impl Plane {
    /// The plane through `point` with front normal `normal` (unit length).
    pub fn new(point: DVec3, normal: DVec3) -> Plane {
        Plane {
            normal,
            offset: normal.dot(point),
        }
    }

    /// The support plane of a patch (front side = the patch's front side).
    pub fn of_patch(patch: &Patch) -> Plane {
        Plane::new(patch.centroid, patch.normal)
    }

    /// The support plane of one side of a patch (front side = that side).
    pub fn of_side(patch: &Patch, side: Side) -> Plane {
        Plane::new(patch.centroid, side.normal(patch))
    }

    /// Signed distance of `p` (scene units; positive in front).
    pub fn distance(&self, p: DVec3) -> f64 {
        self.normal.dot(p) - self.offset
    }
}

/// Where a point lies relative to a plane, with the epsilon band.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlaneSide {
    /// Clearly in front.
    Front,
    /// Clearly behind.
    Back,
    /// Within the epsilon band: on the plane (a shared or touching corner).
    On,
}

/// How a polygon's corners lie relative to a plane.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SideCounts {
    /// Corners clearly in front.
    pub front: usize,
    /// Corners clearly behind.
    pub back: usize,
    /// Corners on the plane (within the epsilon band).
    pub on: usize,
}

impl SideCounts {
    /// Counts the corners of `polygon` on each side of `plane`. The band half-width is
    /// [`PLANE_EPSILON`] times the largest coordinate difference between a corner and the
    /// plane's point nearest the origin, so it scales with the configuration.
    pub fn of(plane: &Plane, polygon: &[DVec3]) -> SideCounts {
        let eps = band(plane, polygon);
        let mut counts = SideCounts::default();
        for &p in polygon {
            match side(plane.distance(p), eps) {
                PlaneSide::Front => counts.front += 1,
                PlaneSide::Back => counts.back += 1,
                PlaneSide::On => counts.on += 1,
            }
        }
        counts
    }

    /// True when the polygon lies clearly on both sides, so the plane cuts it into two
    /// pieces of non-zero area. Corners on the plane (shared or touching ones) never cause a
    /// split by themselves; a polygon touching the plane along an edge or at one corner and
    /// otherwise on one side is not split, while one that touches at a corner but also
    /// crosses is.
    pub fn straddles(&self) -> bool {
        self.front > 0 && self.back > 0
    }
}

fn side(distance: f64, eps: f64) -> PlaneSide {
    if distance > eps {
        PlaneSide::Front
    } else if distance < -eps {
        PlaneSide::Back
    } else {
        PlaneSide::On
    }
}

/// Half-width of the "on the plane" band for `polygon`: relative to the polygon's distance
/// from the plane's reference point and its extent, hence invariant under uniform scaling.
fn band(plane: &Plane, polygon: &[DVec3]) -> f64 {
    let reference = plane.normal * plane.offset;
    let size = polygon
        .iter()
        .map(|p| (*p - reference).abs().max_element())
        .fold(0.0, f64::max);
    PLANE_EPSILON * size.max(f64::MIN_POSITIVE)
}

/// Result of the facing test between a receiver and an emitter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Facing {
    /// Each patch lies (up to touching corners) in front of the other: exchange light as they
    /// are.
    Facing,
    /// Each has a part in front of the other, but at least one straddles the other's plane:
    /// split (support-plane split) or clip before computing visibility and form factors.
    /// The solvers treat such a pair as facing: the analytic form factor clips the emitter to
    /// the receiver's front half-space, and the contact splits ([`super::contact`]) have
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
    let r = SideCounts::of(&Plane::of_side(emitter, emitter_side), receiver.corners());
    let e = SideCounts::of(&Plane::of_side(receiver, receiver_side), emitter.corners());
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
    SideCounts::of(&Plane::of_patch(divisor), dividend.corners()).straddles()
}

/// A convex polygon with texture coordinates per corner.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Polygon {
    /// Corners, in the winding of the polygon it came from.
    pub corners: Vec<DVec3>,
    /// Texture coordinates per corner.
    pub uvs: Vec<DVec2>,
}

/// The two pieces of a polygon split at a plane (either may be empty).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SplitPolygon {
    /// The part in front of the plane (including on-plane corners).
    pub front: Polygon,
    /// The part behind the plane (including on-plane corners).
    pub back: Polygon,
}

/// Splits a convex polygon (corners and texture coordinates, same length) at `plane`
/// (Sutherland–Hodgman on both sides; seed §4.2.2). Corners within the epsilon band count as
/// on the plane and go to both pieces; new corners are placed where edges cross the plane,
/// with linearly interpolated texture coordinates. A piece with fewer than three corners is
/// returned empty. The contact splits of [`super::contact`] cut faces with it.
pub fn split(plane: &Plane, corners: &[DVec3], uvs: &[DVec2]) -> SplitPolygon {
    let eps = band(plane, corners);
    let n = corners.len().min(uvs.len());
    let d: Vec<f64> = corners[..n]
        .iter()
        .map(|&p| {
            let x = plane.distance(p);
            if x.abs() <= eps { 0.0 } else { x }
        })
        .collect();
    let mut out = SplitPolygon::default();
    for i in 0..n {
        let j = (i + 1) % n;
        if d[i] >= 0.0 {
            out.front.corners.push(corners[i]);
            out.front.uvs.push(uvs[i]);
        }
        if d[i] <= 0.0 {
            out.back.corners.push(corners[i]);
            out.back.uvs.push(uvs[i]);
        }
        if (d[i] > 0.0 && d[j] < 0.0) || (d[i] < 0.0 && d[j] > 0.0) {
            let t = d[i] / (d[i] - d[j]);
            let p = corners[i].lerp(corners[j], t);
            let uv = uvs[i].lerp(uvs[j], t);
            for piece in [&mut out.front, &mut out.back] {
                piece.corners.push(p);
                piece.uvs.push(uv);
            }
        }
    }
    for piece in [&mut out.front, &mut out.back] {
        if piece.corners.len() < 3 {
            *piece = Polygon::default();
        }
    }
    out
}

/// True when clipping `polygon` to the front of `plane` leaves it as it is: no corner lies
/// behind the plane beyond the epsilon band, and one lies in front beyond it (corners in the
/// band are on the plane, where the clipped polygon keeps them). [`clip_to_front`] returns
/// such a polygon as it is.
#[inline(always)]
pub fn unclipped(plane: &Plane, polygon: &[DVec3]) -> bool {
    let eps = band(plane, polygon);
    let mut in_front = false;
    for &p in polygon {
        let d = plane.distance(p);
        if d < -eps {
            return false;
        }
        in_front |= d > eps;
    }
    in_front
}

/// The part of a convex polygon strictly in front of `plane` (corners in the epsilon band
/// count as on it). Returns an empty list when nothing lies clearly in front, in particular
/// for a polygon lying in the plane. Used to clip an emitter to a receiver's front
/// half-space before the contour integral.
#[inline(always)]
pub fn clip_to_front<'a>(plane: &Plane, polygon: &'a [DVec3]) -> Cow<'a, [DVec3]> {
    // The common case, a polygon in front (touching the plane at most), is returned as it
    // is.
    if unclipped(plane, polygon) {
        return Cow::Borrowed(polygon);
    }
    let eps = band(plane, polygon);
    let distance = |p: DVec3| {
        let x = plane.distance(p);
        if x.abs() <= eps { 0.0 } else { x }
    };
    let n = polygon.len();
    let mut out = Vec::with_capacity(n + 1);
    for i in 0..n {
        let j = (i + 1) % n;
        let (di, dj) = (distance(polygon[i]), distance(polygon[j]));
        if di > 0.0 {
            out.push(polygon[i]);
        }
        if (di > 0.0) != (dj > 0.0) {
            // The crossing (an on-plane end is the crossing itself: t = 0 or 1).
            let t = di / (di - dj);
            out.push(polygon[i].lerp(polygon[j], t));
        }
    }
    if out.len() < 3 {
        out.clear();
    }
    Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let pieces = split(&Plane::of_patch(&floor()), wall.corners(), wall.uvs());
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
        let pieces = split(&Plane::of_patch(&floor()), tri.corners(), tri.uvs());
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
