//! Shaft culling (after Haines & Wallace 1994; the seed's "outcode" pre-test, §4.4.2, is its
//! simplest form): the convex volume spanned by two patches, used to discard candidate
//! occluders that lie entirely outside it before any ray is cast.
//!
//! The shaft between two convex polygons ([`Shaft::between_polygons`]) is the union of their
//! bounding boxes cut by the faces of the polygons' convex hull, which holds every segment
//! from one polygon to the other (much tighter than Haines and Wallace's shaft between the
//! boxes for tilted or far-apart patches).

use crate::geometry::DVec3x4;
use glam::DVec3;
use smallvec::SmallVec;
use wide::{CmpGt, CmpLt, f64x4};

/// An axis-aligned box in scene units (`f64`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// Lower corner.
    pub min: DVec3,
    /// Upper corner.
    pub max: DVec3,
}

impl Bounds {
    /// The smallest box holding `points` (an empty iterator gives an inverted box that
    /// overlaps nothing).
    pub fn from_points(points: impl IntoIterator<Item = DVec3>) -> Bounds {
        points.into_iter().fold(
            Bounds {
                min: DVec3::INFINITY,
                max: DVec3::NEG_INFINITY,
            },
            |b, p| Bounds {
                min: b.min.min(p),
                max: b.max.max(p),
            },
        )
    }

    /// The smallest box holding both.
    pub fn union(self, other: Bounds) -> Bounds {
        Bounds {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// True when the boxes share at least a boundary point.
    pub fn overlaps(&self, other: &Bounds) -> bool {
        self.min.cmple(other.max).all() && other.min.cmple(self.max).all()
    }
}

/// The shaft between two polygons: everything a segment from one to the other can touch.
#[derive(Clone, Debug, PartialEq)]
pub struct Shaft {
    /// The union of the polygons' bounding boxes.
    pub bounds: Bounds,
    /// Faces `normal · x ≤ offset` (unit normals) of the convex hull of the two polygons.
    hull: SmallVec<[(DVec3, f64); 16]>,
    /// Tolerance added to every plane test (relative to the shaft's size), so that boxes
    /// touching the shaft are kept.
    tolerance: f64,
}

/// Relative tolerance of the plane tests.
const SHAFT_TOLERANCE: f64 = 1e-9;

impl Shaft {
    /// The shaft between the convex planar polygons `a` and `b` (corners in order): the
    /// union of their bounding boxes cut by the faces of their convex hull (which lies
    /// inside the boxes' shaft, so the boxes' cutting planes are left out). A hull face is
    /// the plane of one polygon or holds an edge of one polygon and a corner of the other
    /// (a face holding two corners of a planar convex polygon holds the polygon's plane or
    /// one of its edges), so those candidates are tried and the supporting ones kept.
    pub fn between_polygons(a: &[DVec3], b: &[DVec3]) -> Shaft {
        let bounds = Bounds::from_points(a.iter().chain(b).copied());
        let mut shaft = Shaft {
            bounds,
            hull: SmallVec::new(),
            tolerance: tolerance(&bounds),
        };
        let points = Lanes::of(a.iter().chain(b).copied());
        let tolerance = shaft.tolerance;
        let mut add = |normal: DVec3, at: DVec3| {
            let length = normal.length();
            if length.is_nan() || length <= 0.0 {
                return;
            }
            // Degenerate (near-parallel) candidates give a direction of no use; the
            // supporting test below rejects those that do not bound the points. It runs on
            // the candidate's normal as it is, the tolerance scaled to its length; only a
            // face kept is normalised.
            let (above, below) = points.sides(normal, normal.dot(at), tolerance * length);
            if above && below {
                return;
            }
            let n = normal / length;
            let offset = n.dot(at);
            match (above, below) {
                (false, true) => shaft.hull.push((n, offset)),
                (true, false) => shaft.hull.push((-n, -offset)),
                (false, false) => {
                    // Every point on the plane: the hull is flat, bounded on both sides.
                    shaft.hull.push((n, offset));
                    shaft.hull.push((-n, -offset));
                }
                (true, true) => {}
            }
        };
        for (polygon, other) in [(a, b), (b, a)] {
            if let [p0, p1, p2, ..] = polygon {
                add((*p1 - *p0).cross(*p2 - *p0), *p0);
            }
            for (i, &p) in polygon.iter().enumerate() {
                let edge = polygon[(i + 1) % polygon.len()] - p;
                for &q in other {
                    add(edge.cross(q - p), p);
                }
            }
        }
        shaft
    }

    /// False when `candidate` lies outside the union box or on or outside one of the hull's
    /// faces (it can block no segment through the hull's interior — the box of the solid a
    /// patch is a face of, say); true when it may intersect the shaft. Conservative: boxes
    /// with infinite extent are always kept.
    pub fn may_intersect(&self, candidate: &Bounds) -> bool {
        if !(candidate.min.is_finite() && candidate.max.is_finite()) {
            return true;
        }
        if !self.bounds.overlaps(candidate) {
            return false;
        }
        // The candidate's corner furthest into the shaft side of plane `n`.
        let nearest = |n: DVec3| DVec3::select(n.cmpgt(DVec3::ZERO), candidate.min, candidate.max);
        self.hull
            .iter()
            .all(|&(n, offset)| n.dot(nearest(n)) < offset - self.tolerance)
    }

    /// False when the convex hull of `points` (a triangle that passed
    /// [`Shaft::may_intersect`] on its bounds) lies on or outside one of the hull faces of a
    /// shaft between polygons, so that it can block no segment through the hull's interior
    /// — a face of a box touching the patch along an edge, say; true otherwise.
    pub fn may_intersect_points(&self, points: &[DVec3]) -> bool {
        self.hull
            .iter()
            .all(|&(n, offset)| points.iter().any(|p| n.dot(*p) < offset - self.tolerance))
    }
}

/// Points four to a lane group (the last group padded with the first point, which changes
/// no side test).
struct Lanes(SmallVec<[DVec3x4; 2]>);

impl Lanes {
    fn of(points: impl Iterator<Item = DVec3>) -> Lanes {
        let all: SmallVec<[DVec3; 8]> = points.collect();
        let first = all.first().copied().unwrap_or(DVec3::ZERO);
        Lanes(
            all.chunks(4)
                .map(|c| DVec3x4::from_fn(|k| c.get(k).copied().unwrap_or(first)))
                .collect(),
        )
    }

    /// Whether any point lies more than `tolerance` above the plane `n · x = offset`, and
    /// whether any lies more than `tolerance` below it.
    fn sides(&self, n: DVec3, offset: f64, tolerance: f64) -> (bool, bool) {
        let (mut above, mut below) = (false, false);
        for group in &self.0 {
            let d = group.dot_one(n) - offset;
            above |= d.cmp_gt(f64x4::splat(tolerance)).any();
            below |= d.cmp_lt(f64x4::splat(-tolerance)).any();
        }
        (above, below)
    }
}

/// The absolute tolerance of the plane tests of a shaft whose union box is `bounds`.
fn tolerance(bounds: &Bounds) -> f64 {
    let size = (bounds.max - bounds.min)
        .abs()
        .max_element()
        .max(bounds.max.abs().max_element());
    SHAFT_TOLERANCE * size
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bounds(min: [f64; 3], max: [f64; 3]) -> Bounds {
        Bounds {
            min: DVec3::from_array(min),
            max: DVec3::from_array(max),
        }
    }

    /// A unit square about `centre`, horizontal (normal +y) when `tilt` is 0, tilted by
    /// `tilt` radians about the x axis.
    fn square(centre: DVec3, tilt: f64) -> Vec<DVec3> {
        let (sin, cos) = tilt.sin_cos();
        [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]
            .map(|(x, z)| centre + DVec3::new(x, z * sin, z * cos))
            .to_vec()
    }

    #[test]
    fn polygon_shaft_keeps_every_segment_between_the_polygons() {
        let a = square(DVec3::ZERO, 0.3);
        let b = square(DVec3::new(2.0, 3.0, -1.0), -1.1);
        let shaft = Shaft::between_polygons(&a, &b);
        let f = |x: u32| 0.02 + 0.96 * (x as f64 * 0.618_033_988_75).fract();
        let inside = |quad: &[DVec3], u: f64, v: f64| {
            quad[0].lerp(quad[1], u).lerp(quad[3].lerp(quad[2], u), v)
        };
        for k in 0..1000 {
            let p = inside(&a, f(k), f(k + 7));
            let q = inside(&b, f(k + 3), f(k + 11));
            let x = p.lerp(q, f(k + 5));
            let tiny = 1e-6;
            let triangle = [x, x + DVec3::X * tiny, x + DVec3::Y * tiny];
            assert!(shaft.may_intersect(&Bounds { min: x, max: x }));
            assert!(
                shaft.may_intersect_points(&triangle),
                "segment point {x} culled"
            );
        }
    }

    #[test]
    fn polygon_shaft_drops_what_only_touches_it_or_lies_beside_it() {
        // A floor patch and a parallel ceiling patch 2 above it.
        let floor = square(DVec3::ZERO, 0.0);
        let ceiling = square(DVec3::new(0.0, 2.0, 0.0), 0.0);
        let shaft = Shaft::between_polygons(&floor, &ceiling);
        // A blocker half-way up: kept.
        let blocker = [
            DVec3::new(-0.2, 1.0, -0.2),
            DVec3::new(0.2, 1.0, -0.2),
            DVec3::new(0.0, 1.0, 0.2),
        ];
        assert!(shaft.may_intersect_points(&blocker));
        // A wall hanging down from the floor's edge (a box face sharing the edge): dropped.
        let below = [
            DVec3::new(-0.5, 0.0, 0.5),
            DVec3::new(0.5, 0.0, 0.5),
            DVec3::new(0.0, -1.0, 0.5),
        ];
        assert!(!shaft.may_intersect_points(&below));
        // A triangle inside the union box of an offset pair but beside their hull (below
        // the plane through the near edge of one and the far edge of the other): dropped.
        let a = square(DVec3::ZERO, 0.0);
        let b = square(DVec3::new(3.0, 1.0, 0.0), 0.0);
        let side = Shaft::between_polygons(&a, &b);
        let off = [
            DVec3::new(2.9, 0.1, 0.0),
            DVec3::new(3.1, 0.1, 0.1),
            DVec3::new(3.0, 0.2, -0.1),
        ];
        assert!(side.bounds.overlaps(&Bounds::from_points(off)));
        assert!(!side.may_intersect_points(&off));
    }

    #[test]
    fn boxes_off_the_hull_are_culled_and_unbounded_ones_kept() {
        // A floor square at the origin and a ceiling square 3 along x and 1 up: the hull is
        // a slanted slab inside their union box.
        let shaft = Shaft::between_polygons(
            &square(DVec3::ZERO, 0.0),
            &square(DVec3::new(3.0, 1.0, 0.0), 0.0),
        );
        // On the segment between the centres: kept.
        assert!(shaft.may_intersect(&bounds([1.4, 0.4, -0.1], [1.6, 0.6, 0.1])));
        // In the union box below the ceiling square, beneath the hull (whose lower face is
        // at y ≈ 0.93 there): culled.
        assert!(!shaft.may_intersect(&bounds([3.2, 0.0, -0.1], [3.4, 0.1, 0.1])));
        // Outside the union box: culled.
        assert!(!shaft.may_intersect(&bounds([1.4, 1.5, -0.1], [1.6, 2.0, 0.1])));
        // Infinite boxes are kept.
        assert!(shaft.may_intersect(&bounds([f64::NEG_INFINITY; 3], [f64::INFINITY; 3])));
    }
}
