//! Checks that a polygon is usable: non-degenerate, planar, convex and simple.

use glam::Vec3;

/// Relative tolerance of the planarity test: a vertex may lie this fraction of the polygon's
/// size (bounding-box diagonal) away from the polygon's plane.
pub(super) const PLANARITY_TOLERANCE: f32 = 1e-3;

/// A polygon whose area is below this fraction of its size squared counts as degenerate.
const AREA_TOLERANCE: f32 = 1e-7;

/// `Ok` when the polygon `vertices` (in order, at least 3) is non-degenerate, planar within
/// [`PLANARITY_TOLERANCE`], convex and winds around once; otherwise what is wrong.
pub(super) fn check_polygon(vertices: &[Vec3]) -> Result<(), String> {
    let n = vertices.len();
    if n < 3 {
        return Err(format!("a polygon needs at least 3 vertices, got {n}"));
    }
    let (lo, hi) = vertices
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let size = (hi - lo).length();
    for i in 0..n {
        if vertices[i] == vertices[(i + 1) % n] {
            return Err(format!("vertices {i} and {} coincide", (i + 1) % n));
        }
    }
    // Newell's normal around the first vertex (well conditioned far from the origin).
    let origin = vertices[0];
    let newell: Vec3 = (0..n)
        .map(|i| (vertices[i] - origin).cross(vertices[(i + 1) % n] - origin))
        .sum();
    let area = 0.5 * newell.length();
    if area.is_nan() || area <= AREA_TOLERANCE * size * size {
        return Err("polygon has zero area".into());
    }
    let normal = newell / newell.length();
    let centroid = vertices.iter().sum::<Vec3>() / n as f32;
    let tolerance = PLANARITY_TOLERANCE * size;
    for (i, v) in vertices.iter().enumerate() {
        let distance = (*v - centroid).dot(normal).abs();
        if distance > tolerance {
            return Err(format!(
                "polygon is not planar: vertex {i} is {distance:.4} from its plane \
                 (tolerance {tolerance:.4}, 1e-3 of its size)"
            ));
        }
    }
    let mut turning = 0.0f32;
    for i in 0..n {
        let a = vertices[(i + 1) % n] - vertices[i];
        let b = vertices[(i + 2) % n] - vertices[(i + 1) % n];
        let sin = a.cross(b).dot(normal);
        if sin < -1e-6 * a.length() * b.length() {
            return Err(format!("polygon is not convex at vertex {}", (i + 1) % n));
        }
        turning += sin.atan2(a.dot(b));
    }
    if (turning - std::f32::consts::TAU).abs() > 1e-3 {
        return Err("polygon is not simple: its edges wind around more than once".into());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f32, y: f32, z: f32) -> Vec3 {
        Vec3::new(x, y, z)
    }

    #[test]
    fn accepts_convex_planar_polygons_in_either_winding() {
        let square = [v(0., 0., 0.), v(1., 0., 0.), v(1., 1., 0.), v(0., 1., 0.)];
        assert!(check_polygon(&square).is_ok());
        let mut reversed = square;
        reversed.reverse();
        assert!(check_polygon(&reversed).is_ok());
        // A vertex in the middle of an edge is allowed.
        let with_midpoint = [v(0., 0., 0.), v(0.5, 0., 0.), v(1., 0., 0.), v(0., 1., 0.)];
        assert!(check_polygon(&with_midpoint).is_ok());
        // Far from the origin and within the planarity tolerance (1e-4 of a size of ~1.41).
        let far = [
            v(1e4, 0., 0.),
            v(1e4 + 1., 0., 0.),
            v(1e4 + 1., 1., 1e-4),
            v(1e4, 1., 0.),
        ];
        assert!(check_polygon(&far).is_ok());
    }

    #[test]
    fn rejects_degenerate_non_planar_concave_and_star_polygons() {
        let line = [v(0., 0., 0.), v(1., 0., 0.), v(2., 0., 0.)];
        assert!(check_polygon(&line).unwrap_err().contains("zero area"));
        let bent = [v(0., 0., 0.), v(1., 0., 0.), v(1., 1., 0.01), v(0., 1., 0.)];
        assert!(check_polygon(&bent).unwrap_err().contains("not planar"));
        let dart = [
            v(0., 0., 0.),
            v(2., 0., 0.),
            v(1., 0.5, 0.),
            v(2., 2., 0.),
            v(0., 2., 0.),
        ];
        assert!(check_polygon(&dart).unwrap_err().contains("not convex"));
        let star: Vec<Vec3> = (0..5)
            .map(|k| {
                let a = (k as f32) * 4.0 * std::f32::consts::PI / 5.0;
                v(a.cos(), a.sin(), 0.0)
            })
            .collect();
        assert!(check_polygon(&star).unwrap_err().contains("not simple"));
        let repeated = [v(0., 0., 0.), v(1., 0., 0.), v(1., 0., 0.), v(0., 1., 0.)];
        assert!(check_polygon(&repeated).unwrap_err().contains("coincide"));
    }
}
