//! The unit frustum: the truncated cone around the z axis from radius 1 at `z = 0` to radius
//! `k` at `z = 1`, with optional disc caps. Cylinders (`k = 1`) and cones (`k = 0`) are its
//! special cases, so one routine serves all three.

use super::Ray;
use super::local_hit::{LocalHit, quadratic_roots};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Shape parameters of a unit frustum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnitFrustum {
    /// Radius at `z = 1` (0 = cone, 1 = cylinder); the radius at `z = 0` is 1.
    pub top_radius: f32,
    /// Whether the disc at `z = 0` is part of the surface.
    pub bottom_cap: bool,
    /// Whether the disc at `z = 1` is part of the surface (ignored for a cone).
    pub top_cap: bool,
}

/// Part index of the lateral surface.
pub const LATERAL: u32 = 0;
/// Part index of the bottom disc.
pub const BOTTOM: u32 = 1;
/// Part index of the top disc.
pub const TOP: u32 = 2;

impl UnitFrustum {
    fn radius_at(&self, z: f32) -> f32 {
        1.0 + (self.top_radius - 1.0) * z
    }

    /// First stage: smallest `t ∈ (0, t_max]` with the part index hit.
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<(f32, u32)> {
        let mut best: Option<(f32, u32)> = None;
        let mut consider = |t: f32, part: u32| {
            if t > 0.0 && t <= t_max && best.is_none_or(|(b, _)| t < b) {
                best = Some((t, part));
            }
        };
        let (o, d) = (ray.origin, ray.dir);
        let s = self.top_radius - 1.0;
        let r0 = 1.0 + s * o.z;
        let a = d.x * d.x + d.y * d.y - s * s * d.z * d.z;
        let b = 2.0 * (o.x * d.x + o.y * d.y - s * d.z * r0);
        let c = o.x * o.x + o.y * o.y - r0 * r0;
        if let Some((t0, t1)) = quadratic_roots(a, b, c) {
            for t in [t0, t1] {
                let z = o.z + t * d.z;
                if (0.0..=1.0).contains(&z) {
                    consider(t, LATERAL);
                }
            }
        }
        if d.z != 0.0 {
            let caps = [
                (self.bottom_cap, 0.0, 1.0, BOTTOM),
                (
                    self.top_cap && self.top_radius > 0.0,
                    1.0,
                    self.top_radius,
                    TOP,
                ),
            ];
            for (present, z, radius, part) in caps {
                if present {
                    let t = (z - o.z) / d.z;
                    let p = o + d * t;
                    if p.x * p.x + p.y * p.y <= radius * radius {
                        consider(t, part);
                    }
                }
            }
        }
        best
    }

    /// Second stage at point `p` on part `part`. The lateral surface has `u` around the axis
    /// and `v = z`; caps have planar `(u, v)` in `[0, 1]²`.
    pub fn describe(&self, p: Vec3, part: u32) -> LocalHit {
        match part {
            BOTTOM | TOP => {
                let (z, n, r) = if part == TOP {
                    (1.0, Vec3::Z, self.top_radius)
                } else {
                    (0.0, -Vec3::Z, 1.0)
                };
                let p = Vec3::new(p.x, p.y, z);
                LocalHit {
                    p,
                    n,
                    uv: Vec2::new(0.5 + 0.5 * p.x / r, 0.5 + 0.5 * p.y / r),
                }
            }
            _ => {
                let s = self.top_radius - 1.0;
                let z = p.z.clamp(0.0, 1.0);
                let r = self.radius_at(z);
                let phi = p.y.atan2(p.x);
                let (sin_p, cos_p) = phi.sin_cos();
                let p = Vec3::new(r * cos_p, r * sin_p, z);
                // Gradient of x² + y² − (1 + s z)², valid at the apex too via the azimuth.
                let n = Vec3::new(cos_p, sin_p, -s).normalize();
                LocalHit {
                    p,
                    n,
                    uv: Vec2::new(0.5 + phi / (2.0 * PI), z),
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CYLINDER: UnitFrustum = UnitFrustum {
        top_radius: 1.0,
        bottom_cap: true,
        top_cap: true,
    };
    const CONE: UnitFrustum = UnitFrustum {
        top_radius: 0.0,
        bottom_cap: true,
        top_cap: false,
    };

    #[test]
    fn cylinder_side_and_caps() {
        let side = Ray::new(Vec3::new(-3.0, 0.0, 0.5), Vec3::X);
        let (t, part) = CYLINDER.intersect(&side, f32::INFINITY).unwrap();
        assert!((t - 2.0).abs() < 1e-5 && part == LATERAL);
        assert!((CYLINDER.describe(side.at(t), part).n - (-Vec3::X)).length() < 1e-5);
        let top = Ray::new(Vec3::new(0.2, 0.1, 3.0), -Vec3::Z);
        let (t, part) = CYLINDER.intersect(&top, f32::INFINITY).unwrap();
        assert!((t - 2.0).abs() < 1e-5 && part == TOP);
        let inside = Ray::new(Vec3::new(0.0, 0.0, 0.5), Vec3::Z);
        let (t, part) = CYLINDER.intersect(&inside, f32::INFINITY).unwrap();
        assert!((t - 0.5).abs() < 1e-5 && part == TOP);
        let open = UnitFrustum {
            top_cap: false,
            bottom_cap: false,
            ..CYLINDER
        };
        assert!(open.intersect(&top, f32::INFINITY).is_none());
        assert!(
            CYLINDER
                .intersect(&Ray::new(Vec3::new(-3.0, 0.0, 1.5), Vec3::X), 9.0)
                .is_none()
        );
    }

    #[test]
    fn cone_side_normal_leans_up() {
        let r = Ray::new(Vec3::new(-3.0, 0.0, 0.5), Vec3::X);
        let (t, part) = CONE.intersect(&r, f32::INFINITY).unwrap();
        assert!((t - 2.5).abs() < 1e-5 && part == LATERAL);
        let n = CONE.describe(r.at(t), part).n;
        let expected = Vec3::new(-1.0, 0.0, 1.0).normalize();
        assert!((n - expected).length() < 1e-5);
        // Above the apex the lower nappe's mirror must not be hit.
        assert!(
            CONE.intersect(&Ray::new(Vec3::new(-3.0, 0.0, 1.5), Vec3::X), 9.0)
                .is_none()
        );
    }

    #[test]
    fn lateral_normal_is_perpendicular_to_the_surface() {
        let f = UnitFrustum {
            top_radius: 0.5,
            bottom_cap: true,
            top_cap: true,
        };
        let h = f.describe(Vec3::new(0.3, 0.6, 0.4), LATERAL);
        assert!((h.p.truncate().length() - f.radius_at(h.p.z)).abs() < 1e-5);
        // The side line (radius 1 at z = 0 to 0.5 at z = 1) and the circle through the point.
        let (sin_p, cos_p) = h.p.y.atan2(h.p.x).sin_cos();
        let along_side = Vec3::new(-0.5 * cos_p, -0.5 * sin_p, 1.0);
        let around = Vec3::new(-sin_p, cos_p, 0.0);
        assert!(h.n.dot(along_side).abs() < 1e-5 && h.n.dot(around).abs() < 1e-5);
    }
}
