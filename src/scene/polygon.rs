//! What every loader asks of a polygon face: is it usable as it is (planar and convex), must
//! it be split into triangles (concave, or bent out of its plane), or is it broken (too few
//! corners, corners that coincide, no area, edges that cross as in a bowtie)? Scene files,
//! OBJ and glTF faces go through the same [`classify`] and [`triangulate`], so a face is
//! refused or split alike wherever it comes from.
//!
//! The tests run in the polygon's own frame (corners relative to the first, divided by the
//! polygon's size, in `f64`), so they give the same answer for a polygon 10⁻⁶ or 10¹⁸ units
//! across.

use crate::geometry::convex2::{cross, signed_area};
use glam::{DVec2, DVec3, Vec3};

/// A corner may lie this fraction of the polygon's size (its bounding-box diagonal) away
/// from the polygon's plane and the face still counts as planar.
pub const PLANARITY_TOLERANCE: f64 = 1e-3;

/// A polygon whose area is below this fraction of its size squared has no area.
const AREA_TOLERANCE: f64 = 1e-9;

/// Concave or bent polygons with more corners than this are refused: splitting them costs
/// the square of the corner count (no exporter writes such faces; a hostile file might).
pub const MAX_SPLIT_CORNERS: usize = 4096;

/// How a usable polygon is to be taken.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// Planar (within [`PLANARITY_TOLERANCE`]) and convex: usable as it is.
    Convex,
    /// Planar but concave: to be split into triangles ([`triangulate`]).
    Concave,
    /// Corner `corner` lies `distance` (scene units) from the polygon's plane, more than
    /// [`PLANARITY_TOLERANCE`] of its size: to be split into triangles ([`triangulate`]).
    NonPlanar {
        /// The corner farthest from the plane (index into the polygon's corners).
        corner: usize,
        /// Its distance from the plane, scene units.
        distance: f64,
        /// That distance over the polygon's size (its bounding-box diagonal).
        relative: f64,
    },
}

/// Why a polygon cannot be used.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PolygonError {
    /// Fewer than three corners.
    #[error("a polygon needs at least 3 vertices, got {0}")]
    TooFew(usize),
    /// A corner is NaN or infinite.
    #[error("vertex {0} is not finite")]
    NotFinite(usize),
    /// Two consecutive corners are the same point.
    #[error("vertices {0} and {1} coincide")]
    Coincide(usize, usize),
    /// The corners lie on a line (or the polygon is vanishingly thin).
    #[error("the polygon has zero area")]
    ZeroArea,
    /// Two edges cross (a bowtie or a star).
    #[error(
        "edges {0}–{1} and {2}–{3} cross: the polygon is not simple (a bowtie?); \
         give its corners in order around it"
    )]
    Crossing(usize, usize, usize, usize),
    /// A concave or bent polygon with too many corners to split.
    #[error(
        "a concave or non-planar polygon of {0} vertices is more than the {MAX_SPLIT_CORNERS} \
         strahl splits into triangles"
    )]
    TooLarge(usize),
}

/// Classifies the polygon with `corners` in order.
pub fn classify(corners: &[Vec3]) -> Result<Shape, PolygonError> {
    let frame = Frame::new(corners)?;
    let (corner, deviation) = frame.farthest_from_plane();
    let planar = deviation <= PLANARITY_TOLERANCE;
    if planar && frame.is_convex() {
        return Ok(Shape::Convex);
    }
    let n = corners.len();
    if n > MAX_SPLIT_CORNERS {
        return Err(PolygonError::TooLarge(n));
    }
    if let Some((i, j)) = frame.crossing_edges() {
        return Err(PolygonError::Crossing(i, (i + 1) % n, j, (j + 1) % n));
    }
    if frame.signed_area().abs() <= AREA_TOLERANCE {
        return Err(PolygonError::ZeroArea);
    }
    Ok(if planar {
        Shape::Concave
    } else {
        Shape::NonPlanar {
            corner,
            distance: deviation * frame.size,
            relative: deviation,
        }
    })
}

/// Splits the simple polygon with `corners` into `n − 2` triangles (indices into `corners`,
/// wound as the polygon), by ear clipping in the polygon's best plane, cutting the shortest
/// diagonal first (a bent quad is split along its shorter diagonal). Call it on polygons
/// [`classify`] accepts.
pub fn triangulate(corners: &[Vec3]) -> Vec<[usize; 3]> {
    let Ok(frame) = Frame::new(corners) else {
        return Vec::new();
    };
    let orientation = frame.signed_area().signum();
    let p = &frame.flat;
    let mut left: Vec<usize> = (0..corners.len()).collect();
    let mut triangles = Vec::with_capacity(corners.len().saturating_sub(2));
    while left.len() > 3 {
        let m = left.len();
        let corner = |k: usize| left[k % m];
        let is_ear = |k: usize| {
            let (a, b, c) = (corner(k + m - 1), corner(k), corner(k + 1));
            cross(p[a], p[b], p[c]) * orientation > 0.0
                && left
                    .iter()
                    .all(|&q| q == a || q == b || q == c || !inside(p[q], p[a], p[b], p[c]))
        };
        let diagonal = |k: usize| p[corner(k + m - 1)].distance_squared(p[corner(k + 1)]);
        // The ear with the shortest diagonal; when rounding leaves none, the flattest corner.
        let k = (0..m)
            .filter(|&k| is_ear(k))
            .min_by(|&a, &b| diagonal(a).total_cmp(&diagonal(b)))
            .unwrap_or_else(|| {
                (0..m)
                    .min_by(|&a, &b| {
                        let bend = |k: usize| {
                            cross(p[corner(k + m - 1)], p[corner(k)], p[corner(k + 1)]).abs()
                        };
                        bend(a).total_cmp(&bend(b))
                    })
                    .unwrap_or(0)
            });
        triangles.push([corner(k + m - 1), corner(k), corner(k + 1)]);
        left.remove(k % m);
    }
    triangles.push([left[0], left[1], left[2]]);
    triangles
}

/// A polygon in its own frame: corners relative to the first, in units of its size.
struct Frame {
    /// Bounding-box diagonal, scene units.
    size: f64,
    /// Corners in units of the size, relative to the first corner.
    local: Vec<DVec3>,
    /// Unit normal of the best plane (Newell's, or the widest corner triangle's).
    normal: DVec3,
    /// Corners projected into the plane.
    flat: Vec<DVec2>,
}

impl Frame {
    fn new(corners: &[Vec3]) -> Result<Frame, PolygonError> {
        let n = corners.len();
        if n < 3 {
            return Err(PolygonError::TooFew(n));
        }
        if let Some(i) = corners.iter().position(|c| !c.is_finite()) {
            return Err(PolygonError::NotFinite(i));
        }
        if let Some(i) = (0..n).find(|&i| corners[i] == corners[(i + 1) % n]) {
            return Err(PolygonError::Coincide(i, (i + 1) % n));
        }
        let origin = corners[0].as_dvec3();
        let (lo, hi) = corners
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), c| {
                (lo.min(c.as_dvec3()), hi.max(c.as_dvec3()))
            });
        let size = (hi - lo).length();
        let local: Vec<DVec3> = corners
            .iter()
            .map(|c| (c.as_dvec3() - origin) / size)
            .collect();
        let newell: DVec3 = (0..n).map(|i| local[i].cross(local[(i + 1) % n])).sum();
        // A symmetric bowtie has no Newell normal: its plane is then that of its widest
        // corner triangle.
        let widest = (1..n - 1)
            .map(|i| local[i].cross(local[i + 1]))
            .max_by(|a, b| a.length_squared().total_cmp(&b.length_squared()))
            .unwrap_or(DVec3::ZERO);
        let normal = if newell.length() > AREA_TOLERANCE {
            newell.normalize()
        } else if widest.length() > AREA_TOLERANCE {
            widest.normalize()
        } else {
            return Err(PolygonError::ZeroArea);
        };
        let u = normal.any_orthonormal_vector();
        let v = normal.cross(u);
        let flat = local
            .iter()
            .map(|c| DVec2::new(c.dot(u), c.dot(v)))
            .collect();
        Ok(Frame {
            size,
            local,
            normal,
            flat,
        })
    }

    /// The corner farthest from the best plane through the centroid, and its distance in
    /// units of the size.
    fn farthest_from_plane(&self) -> (usize, f64) {
        let centroid = self.local.iter().sum::<DVec3>() / self.local.len() as f64;
        self.local
            .iter()
            .map(|c| (*c - centroid).dot(self.normal).abs())
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((0, 0.0))
    }

    /// Signed area in the plane, in units of the size squared.
    fn signed_area(&self) -> f64 {
        signed_area(&self.flat)
    }

    /// True when every corner turns the same way and the edges go around once.
    fn is_convex(&self) -> bool {
        let p = &self.flat;
        let n = p.len();
        let orientation = self.signed_area().signum();
        let mut turning = 0.0;
        for i in 0..n {
            let a = p[(i + 1) % n] - p[i];
            let b = p[(i + 2) % n] - p[(i + 1) % n];
            let sin = a.perp_dot(b) * orientation;
            if sin < -1e-9 * a.length() * b.length() {
                return false;
            }
            turning += sin.atan2(a.dot(b));
        }
        (turning - std::f64::consts::TAU).abs() < 1e-6
    }

    /// The first two non-adjacent edges (by their first corners) that cross.
    fn crossing_edges(&self) -> Option<(usize, usize)> {
        let p = &self.flat;
        let n = p.len();
        for i in 0..n {
            for j in i + 2..n {
                if i == 0 && j == n - 1 {
                    continue;
                }
                let (a, b, c, d) = (p[i], p[(i + 1) % n], p[j], p[(j + 1) % n]);
                let (c1, c2) = (cross(a, b, c), cross(a, b, d));
                let (c3, c4) = (cross(c, d, a), cross(c, d, b));
                if c1 * c2 < 0.0 && c3 * c4 < 0.0 {
                    return Some((i, j));
                }
            }
        }
        None
    }
}

/// True when `q` lies inside the triangle `a, b, c` or on its edges (either winding).
fn inside(q: DVec2, a: DVec2, b: DVec2, c: DVec2) -> bool {
    let (d1, d2, d3) = (cross(a, b, q), cross(b, c, q), cross(c, a, q));
    let negative = d1 < 0.0 || d2 < 0.0 || d3 < 0.0;
    let positive = d1 > 0.0 || d2 > 0.0 || d3 > 0.0;
    !(negative && positive)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f32, y: f32, z: f32) -> Vec3 {
        Vec3::new(x, y, z)
    }

    /// The area of `corners` (planar) summed over `triangles`.
    fn area(corners: &[Vec3], triangles: &[[usize; 3]]) -> f32 {
        triangles
            .iter()
            .map(|t| 0.5 * (corners[t[1]] - corners[t[0]]).cross(corners[t[2]] - corners[t[0]]))
            .map(|n| n.z)
            .sum()
    }

    #[test]
    fn convex_planar_polygons_are_usable_as_they_are_at_any_scale() {
        let square = [v(0., 0., 0.), v(1., 0., 0.), v(1., 1., 0.), v(0., 1., 0.)];
        assert_eq!(classify(&square), Ok(Shape::Convex));
        let mut reversed = square;
        reversed.reverse();
        assert_eq!(classify(&reversed), Ok(Shape::Convex));
        // A corner in the middle of an edge is allowed.
        let with_midpoint = [v(0., 0., 0.), v(0.5, 0., 0.), v(1., 0., 0.), v(0., 1., 0.)];
        assert_eq!(classify(&with_midpoint), Ok(Shape::Convex));
        for scale in [1e-6, 1e10, 1e18, 1e19] {
            let big = square.map(|c| c * scale);
            assert_eq!(classify(&big), Ok(Shape::Convex), "scale {scale}");
        }
        let far = [
            v(1e4, 0., 0.),
            v(1e4 + 1., 0., 0.),
            v(1e4 + 1., 1., 1e-4),
            v(1e4, 1., 0.),
        ];
        assert_eq!(classify(&far), Ok(Shape::Convex));
    }

    #[test]
    fn concave_and_bent_polygons_are_split_and_broken_ones_refused() {
        let dart = [
            v(0., 0., 0.),
            v(2., 0., 0.),
            v(1., 0.5, 0.),
            v(2., 2., 0.),
            v(0., 2., 0.),
        ];
        assert_eq!(classify(&dart), Ok(Shape::Concave));
        let triangles = triangulate(&dart);
        assert_eq!(triangles.len(), 3);
        // The triangles cover the dart exactly: the square less the notch, 4 − 0.5·2·1 = 3.
        assert!((area(&dart, &triangles) - 3.0).abs() < 1e-6);
        // A quad 1 % bent: split along the shorter diagonal (corners 1 and 3).
        let bent = [
            v(0., 0., 0.),
            v(1., 0., 0.),
            v(1.2, 1., 0.01),
            v(0., 1., 0.),
        ];
        match classify(&bent) {
            Ok(Shape::NonPlanar {
                corner, distance, ..
            }) => {
                assert!(distance > 0.002 && distance < 0.003, "{distance}");
                assert!(corner < 4);
            }
            other => panic!("{other:?}"),
        }
        let split = triangulate(&bent);
        assert!(
            split.iter().all(|t| t.contains(&1) && t.contains(&3)),
            "{split:?}"
        );
        let bowtie = [v(0., 0., 0.), v(1., 1., 0.), v(1., 0., 0.), v(0., 1., 0.)];
        assert_eq!(classify(&bowtie), Err(PolygonError::Crossing(0, 1, 2, 3)));
        let lopsided = [v(0., 0., 0.), v(2., 1., 0.), v(2., 0., 0.), v(0., 1., 0.)];
        assert!(matches!(
            classify(&lopsided),
            Err(PolygonError::Crossing(..))
        ));
        let star: Vec<Vec3> = (0..5)
            .map(|k| {
                let a = (k as f32) * 4.0 * std::f32::consts::PI / 5.0;
                v(a.cos(), a.sin(), 0.0)
            })
            .collect();
        assert!(matches!(classify(&star), Err(PolygonError::Crossing(..))));
        let line = [v(0., 0., 0.), v(1., 0., 0.), v(2., 0., 0.)];
        assert_eq!(classify(&line), Err(PolygonError::ZeroArea));
        let repeated = [v(0., 0., 0.), v(1., 0., 0.), v(1., 0., 0.), v(0., 1., 0.)];
        assert_eq!(classify(&repeated), Err(PolygonError::Coincide(1, 2)));
        let nan = [v(0., 0., 0.), v(f32::NAN, 0., 0.), v(0., 1., 0.)];
        assert_eq!(classify(&nan), Err(PolygonError::NotFinite(1)));
        assert_eq!(classify(&nan[..2]), Err(PolygonError::TooFew(2)));
    }

    #[test]
    fn ear_clipping_covers_a_comb_exactly() {
        // A comb: a 9 × 1 bar with five teeth 1 wide and 2 tall; 20 corners, area 19.
        let mut comb = vec![v(0., 0., 0.), v(9., 0., 0.)];
        for t in (0..5).rev() {
            let x = 2.0 * t as f32;
            comb.extend([v(x + 1., 3., 0.), v(x, 3., 0.)]);
            if t > 0 {
                comb.extend([v(x, 1., 0.), v(x - 1., 1., 0.)]);
            }
        }
        assert_eq!(comb.len(), 20);
        assert_eq!(classify(&comb), Ok(Shape::Concave));
        let triangles = triangulate(&comb);
        assert_eq!(triangles.len(), 18);
        assert!((area(&comb, &triangles) - 19.0).abs() < 1e-5);
        assert!(triangles.iter().all(|t| area(&comb, &[*t]) > 0.0));
    }
}
