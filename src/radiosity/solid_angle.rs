//! Points on a convex polygon spread evenly over the solid angle it subtends from a point (Arvo,
//! "Stratified sampling of spherical triangles", SIGGRAPH 1995): a ray from the point to
//! each is then equally likely per steradian, so the form factor's `cos θ'/d²` needs no
//! weighting, only the receiver's `cos θ`. Visibility estimated from a few such rays is not
//! pulled towards the far part of a large, close patch as area-uniform points are.

use crate::geometry::angle::upper_angle;
use glam::DVec3;

/// Below this solid angle, steradians, a patch is sampled by area instead (it is nearly
/// edge-on or far, and the two samplings agree).
const MIN_SOLID_ANGLE: f64 = 1e-9;

/// A spherical triangle seen from a point, with what sampling it needs: its vertices as
/// unit directions, the cosine and sine of its interior angle at `a`, the cosine of the arc
/// from `a` to `b`, the unit direction at `a` towards `c` along the sphere, and its area
/// (the solid angle).
struct SphericalTriangle {
    a: DVec3,
    b: DVec3,
    cos_alpha: f64,
    sin_alpha: f64,
    cos_ab: f64,
    towards_c: DVec3,
    area: f64,
}

impl SphericalTriangle {
    /// The triangle of directions from `x` to `corners`; `None` when degenerate.
    fn new(x: DVec3, corners: [DVec3; 3]) -> Option<SphericalTriangle> {
        let [a, b, c] = corners.map(|v| (v - x).normalize_or_zero());
        if a == DVec3::ZERO || b == DVec3::ZERO || c == DVec3::ZERO {
            return None;
        }
        // Van Oosterom and Strackee: tan(Ω/2) = |a·(b×c)| / (1 + a·b + b·c + c·a).
        let (ab, bc, ca) = (a.dot(b), b.dot(c), c.dot(a));
        let area = 2.0 * upper_angle(a.dot(b.cross(c)).abs(), 1.0 + ab + bc + ca);
        // The angle at `a` between the great arcs to `b` and to `c`.
        let (n1, n2) = (
            a.cross(b).normalize_or_zero(),
            a.cross(c).normalize_or_zero(),
        );
        let towards_c = (c - a * ca).normalize_or_zero();
        (area.is_finite() && area > MIN_SOLID_ANGLE && towards_c != DVec3::ZERO).then_some(
            SphericalTriangle {
                a,
                b,
                cos_alpha: n1.dot(n2).clamp(-1.0, 1.0),
                sin_alpha: n1.cross(n2).length().min(1.0),
                cos_ab: ab,
                towards_c,
                area,
            },
        )
    }

    /// The direction at `(s, t) ∈ [0,1]²`, uniform in solid angle for uniform `(s, t)` and
    /// continuous, so strata of the square stay strata of the triangle.
    fn direction(&self, s: f64, t: f64) -> DVec3 {
        let (a, b) = (self.a, self.b);
        let (cos_alpha, sin_alpha) = (self.cos_alpha, self.sin_alpha);
        // The sub-triangle of area s·area fixes the point ĉ on the arc from a to c
        // (Arvo's construction, with sin and cos of area − α expanded).
        let (sin_sub, cos_sub) = (s * self.area).sin_cos();
        let sin_s = sin_sub * cos_alpha - cos_sub * sin_alpha;
        let cos_s = cos_sub * cos_alpha + sin_sub * sin_alpha;
        let u = cos_s - cos_alpha;
        let v = sin_s + sin_alpha * self.cos_ab;
        let q = ((v * cos_s - u * sin_s) * cos_alpha - v) / ((v * sin_s + u * cos_s) * sin_alpha);
        let q = if q.is_finite() {
            q.clamp(-1.0, 1.0)
        } else {
            1.0
        };
        let c_hat = a * q + self.towards_c * (1.0 - q * q).max(0.0).sqrt();
        // Then uniformly in the cosine along the arc from b to ĉ.
        let z = 1.0 - t * (1.0 - c_hat.dot(b));
        (b * z + (c_hat - b * c_hat.dot(b)).normalize_or_zero() * (1.0 - z * z).max(0.0).sqrt())
            .normalize_or_zero()
    }
}

/// One point per stratum of an `m × m` grid over the solid angle that the convex planar
/// `polygon` (unit normal `normal`) subtends from `x` — a fan of triangles, the first
/// coordinate choosing among them by their solid angles — with `jitter` giving the offset
/// within each stratum, and that solid angle (sr). `None` when the polygon subtends
/// (almost) no solid angle from `x` or a point cannot be placed.
pub fn points_by_solid_angle(
    polygon: &[DVec3],
    normal: DVec3,
    x: DVec3,
    m: u32,
    mut jitter: impl FnMut() -> (f64, f64),
) -> Option<(Vec<DVec3>, f64)> {
    let (&first, rest) = polygon.split_first()?;
    let triangles: Vec<SphericalTriangle> = rest
        .windows(2)
        .filter_map(|w| SphericalTriangle::new(x, [first, w[0], w[1]]))
        .collect();
    let total: f64 = triangles.iter().map(|t| t.area).sum();
    if triangles.is_empty() || total <= MIN_SOLID_ANGLE {
        return None;
    }
    let plane = normal.dot(first - x);
    let step = 1.0 / m as f64;
    let mut points = Vec::with_capacity((m * m) as usize);
    for i in 0..m {
        for j in 0..m {
            let (ds, dt) = jitter();
            let (s, t) = ((i as f64 + ds) * step, (j as f64 + dt) * step);
            // The triangle whose share of the solid angle holds `s`, and `s` within it.
            let mut below = 0.0;
            let mut chosen = (&triangles[triangles.len() - 1], 1.0);
            for triangle in &triangles {
                let share = triangle.area / total;
                if s < below + share {
                    chosen = (triangle, ((s - below) / share).clamp(0.0, 1.0));
                    break;
                }
                below += share;
            }
            let direction = chosen.0.direction(chosen.1, t);
            let distance = plane / normal.dot(direction);
            if !(distance.is_finite() && distance > 0.0) {
                return None;
            }
            points.push(x + direction * distance);
        }
    }
    Some((points, total))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::radiosity::form_factor::point_to_polygon;
    use crate::radiosity::mesh::Patch;
    use glam::DVec2;

    fn square(size: f64, height: f64) -> Patch {
        let corners = [
            DVec3::new(0.0, height, 0.0),
            DVec3::new(0.0, height, size),
            DVec3::new(size, height, size),
            DVec3::new(size, height, 0.0),
        ];
        Patch::new(&corners, &[DVec2::ZERO; 4]).unwrap()
    }

    #[test]
    fn points_lie_on_the_patch_and_their_cosines_average_to_the_form_factor() {
        // A 1 m square 0.2 m above a point near one corner: area sampling would put most
        // points far away; by solid angle the mean receiver cosine times the solid angle
        // over π is the point form factor.
        let patch = square(1.0, 0.2);
        let x = DVec3::new(0.1, 0.0, 0.15);
        let normal = DVec3::Y;
        let mut k = 0u32;
        // A fixed low-discrepancy jitter (golden-ratio sequence).
        let mut jitter = || {
            k += 1;
            let g = 0.618_033_988_749_895;
            ((f64::from(k) * g).fract(), (f64::from(k) * g * g).fract())
        };
        let (points, solid_angle) =
            points_by_solid_angle(patch.corners(), patch.normal, x, 32, &mut jitter).unwrap();
        for p in &points {
            assert!((p.y - 0.2).abs() < 1e-9 && p.x > -1e-9 && p.x < 1.0 + 1e-9);
            assert!(p.z > -1e-9 && p.z < 1.0 + 1e-9);
        }
        let exact_solid_angle = crate::radiosity::light_links::solid_angle(x, patch.corners());
        assert!((solid_angle / exact_solid_angle - 1.0).abs() < 1e-12);
        let mean_cos = points
            .iter()
            .map(|p| normal.dot((*p - x).normalize()))
            .sum::<f64>()
            / points.len() as f64;
        let exact = point_to_polygon(x, normal, patch.corners());
        let estimate = mean_cos * solid_angle / std::f64::consts::PI;
        assert!(
            (estimate / exact - 1.0).abs() < 2e-3,
            "{estimate} vs {exact}"
        );
    }

    #[test]
    fn a_patch_seen_edge_on_is_left_to_area_sampling() {
        let patch = square(1.0, 0.0);
        assert!(
            points_by_solid_angle(
                patch.corners(),
                patch.normal,
                DVec3::new(2.0, 0.0, 0.5),
                2,
                || (0.5, 0.5)
            )
            .is_none()
        );
    }
}
