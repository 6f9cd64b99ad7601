//! Polygons in the plane: the signed area of any simple one (positive counter-clockwise),
//! and for convex, counter-clockwise ones clipping by a half-plane and what remains of one
//! when another is cut out of it, as convex pieces. What the exact shadows of a directional
//! light are computed with ([`crate::world::ParallelShadows`]), and the scene's polygons and
//! textures measured.

use glam::DVec2;

/// Twice the signed area of the triangle `(a, b, c)`: positive when it turns
/// counter-clockwise, so `c` lies left of the directed line `a → b`.
#[inline]
pub fn cross(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - a)
}

/// Signed area of the polygon `points` (positive when counter-clockwise), square units.
pub fn signed_area(points: &[DVec2]) -> f64 {
    let n = points.len();
    let twice: f64 = (0..n)
        .map(|i| points[i].perp_dot(points[(i + 1) % n]))
        .sum();
    0.5 * twice
}

/// The part of the convex polygon `points` on one side of the directed line `a → b` — left of
/// it when `left`, else right — written to `out` (emptied first; fewer than three corners
/// when nothing of it is there).
pub fn clip(points: &[DVec2], (a, b): (DVec2, DVec2), left: bool, out: &mut Vec<DVec2>) {
    out.clear();
    let side = |p: DVec2| {
        let s = cross(a, b, p);
        if left { s } else { -s }
    };
    let n = points.len();
    for i in 0..n {
        let (p, q) = (points[i], points[(i + 1) % n]);
        let (sp, sq) = (side(p), side(q));
        if sp >= 0.0 {
            out.push(p);
        }
        if (sp >= 0.0) != (sq >= 0.0) {
            out.push(p + (q - p) * (sp / (sp - sq)));
        }
    }
}

/// Appends to `pieces` what remains of the convex polygon `piece` once the convex,
/// counter-clockwise polygon `hole` is cut out of it: at most one convex piece per edge of
/// `hole` (the part right of that edge and left of every edge before it), those under
/// `min_area` left out. `piece` itself when the two do not overlap.
pub fn subtract(piece: &[DVec2], hole: &[DVec2], min_area: f64, pieces: &mut Vec<Vec<DVec2>>) {
    let mut inside = piece.to_vec();
    let mut part = Vec::with_capacity(piece.len() + 1);
    let mut rest = Vec::with_capacity(piece.len() + 1);
    let n = hole.len();
    for i in 0..n {
        let edge = (hole[i], hole[(i + 1) % n]);
        clip(&inside, edge, false, &mut part);
        if part.len() >= 3 && signed_area(&part) > min_area {
            pieces.push(part.clone());
        }
        clip(&inside, edge, true, &mut rest);
        std::mem::swap(&mut inside, &mut rest);
        if inside.len() < 3 {
            return;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: f64, y: f64, side: f64) -> Vec<DVec2> {
        vec![
            DVec2::new(x, y),
            DVec2::new(x + side, y),
            DVec2::new(x + side, y + side),
            DVec2::new(x, y + side),
        ]
    }

    fn area_of(pieces: &[Vec<DVec2>]) -> f64 {
        pieces.iter().map(|p| signed_area(p)).sum()
    }

    #[test]
    fn a_square_has_its_area_and_a_reversed_one_the_negative() {
        let s = square(1.0, 2.0, 3.0);
        assert_eq!(signed_area(&s), 9.0);
        let reversed: Vec<_> = s.iter().rev().copied().collect();
        assert_eq!(signed_area(&reversed), -9.0);
    }

    #[test]
    fn clipping_a_square_through_its_middle_leaves_half_on_each_side() {
        let s = square(0.0, 0.0, 2.0);
        let line = (DVec2::new(1.0, -5.0), DVec2::new(1.0, 5.0));
        let mut out = Vec::new();
        clip(&s, line, true, &mut out);
        assert!((signed_area(&out) - 2.0).abs() < 1e-12);
        assert!(out.iter().all(|p| p.x <= 1.0 + 1e-12));
        clip(&s, line, false, &mut out);
        assert!((signed_area(&out) - 2.0).abs() < 1e-12);
        assert!(out.iter().all(|p| p.x >= 1.0 - 1e-12));
    }

    #[test]
    fn cutting_out_leaves_the_difference_of_the_areas() {
        // A unit square with a quarter of it covered by a square over its corner.
        let mut pieces = Vec::new();
        subtract(
            &square(0.0, 0.0, 1.0),
            &square(0.5, 0.5, 1.0),
            0.0,
            &mut pieces,
        );
        assert!((area_of(&pieces) - 0.75).abs() < 1e-12);
        assert!(pieces.iter().all(|p| signed_area(p) > 0.0));
        // A hole inside: the frame around it, in four pieces.
        pieces.clear();
        subtract(
            &square(0.0, 0.0, 1.0),
            &square(0.25, 0.25, 0.5),
            0.0,
            &mut pieces,
        );
        assert!((area_of(&pieces) - 0.75).abs() < 1e-12);
        assert_eq!(pieces.len(), 4);
        // Apart: the piece itself; covering it: nothing.
        pieces.clear();
        subtract(
            &square(0.0, 0.0, 1.0),
            &square(2.0, 0.0, 1.0),
            0.0,
            &mut pieces,
        );
        assert_eq!(pieces.len(), 1);
        assert!((area_of(&pieces) - 1.0).abs() < 1e-12);
        pieces.clear();
        subtract(
            &square(0.0, 0.0, 1.0),
            &square(-1.0, -1.0, 3.0),
            0.0,
            &mut pieces,
        );
        assert!(pieces.is_empty());
    }
}
