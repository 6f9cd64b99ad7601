//! The description of a hit in an analytic shape's own (object) space.

use glam::{Vec2, Vec3};

/// Second-stage hit description in object space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalHit {
    /// Hit point (object space).
    pub p: Vec3,
    /// Unit geometric normal, pointing out of solids (object space).
    pub n: Vec3,
    /// Surface parameters.
    pub uv: Vec2,
}

/// The smaller root of `a t² + b t + c = 0` above zero and at most `t_max`, else the larger
/// one; computed in the cancellation-free form.
pub(crate) fn quadratic_first_root(a: f32, b: f32, c: f32, t_max: f32) -> Option<f32> {
    let (t0, t1) = quadratic_roots(a, b, c)?;
    [t0, t1].into_iter().find(|&t| t > 0.0 && t <= t_max)
}

/// Both real roots of `a t² + b t + c = 0` in increasing order (computed in f64 for stability).
pub(crate) fn quadratic_roots(a: f32, b: f32, c: f32) -> Option<(f32, f32)> {
    let (a, b, c) = (a as f64, b as f64, c as f64);
    if a == 0.0 {
        if b == 0.0 {
            return None;
        }
        let t = (-c / b) as f32;
        return Some((t, t));
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return None;
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    let (r0, r1) = if q == 0.0 { (0.0, 0.0) } else { (q / a, c / q) };
    Some(if r0 <= r1 {
        (r0 as f32, r1 as f32)
    } else {
        (r1 as f32, r0 as f32)
    })
}
