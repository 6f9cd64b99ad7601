//! Polygons against planes (seed 000 §4.2): which side of a plane a polygon lies on, with an
//! epsilon band so that shared and touching corners (the seed's "variable" points) never
//! cause a split, and Sutherland–Hodgman splitting and clipping of polygons (with their
//! texture coordinates) at a plane. Pure geometry: patches use it ([`super::facing`]), it
//! knows no patch.

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
/// returned empty. The contact splits (`contact.rs`) cut faces with it.
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
