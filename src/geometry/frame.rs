//! Orthonormal frames for turning directions between world space and a local frame, for one
//! direction at a time ([`Frame`]) or for eight ([`to_world_about`] on [`crate::lanes`]).

use crate::lanes::{Real, V3};
use glam::Vec3;

/// An orthonormal frame whose `n` axis is a given unit vector.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    /// First tangent.
    pub s: Vec3,
    /// Second tangent.
    pub t: Vec3,
    /// Normal (the local z axis).
    pub n: Vec3,
}

impl Frame {
    /// A frame around the unit vector `n` (Duff et al., "Building an orthonormal basis,
    /// revisited", 2017).
    #[inline]
    pub fn from_normal(n: Vec3) -> Self {
        let (s, t) = tangents(V3::from(n));
        Frame {
            s: s.into(),
            t: t.into(),
            n,
        }
    }

    /// Local coordinates to world direction.
    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

/// The two tangents `(s, t)` of the frame around the unit vector `n` (Duff et al. 2017).
#[inline(always)]
fn tangents<R: Real>(n: V3<R>) -> (V3<R>, V3<R>) {
    let one = R::splat(1.0);
    let sign = n.z.sign_one();
    let a = -(one / (sign + n.z));
    let b = n.x * n.y * a;
    let s = V3::new(one + sign * n.x * n.x * a, sign * b, -(sign * n.x));
    let t = V3::new(b, sign + n.y * n.y * a, -n.y);
    (s, t)
}

/// The local direction `v` turned into world space in the frame around the unit vector `n`:
/// `Frame::from_normal(n).to_world(v)`, lane by lane.
#[inline(always)]
pub fn to_world_about<R: Real>(n: V3<R>, v: V3<R>) -> V3<R> {
    let (s, t) = tangents(n);
    V3::new(
        s.x * v.x + t.x * v.y + n.x * v.z,
        s.y * v.x + t.y * v.y + n.y * v.z,
        s.z * v.x + t.z * v.y + n.z * v.z,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eight_lanes_turn_directions_as_the_frame_does_bit_for_bit() {
        use crate::lanes::{LANES, Vec3x8};
        let mut seed = 7u32;
        let mut next = || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as f32 / 16_777_216.0 * 2.0 - 1.0
        };
        for _ in 0..500 {
            // Normals along ±z too, where the frame switches its sign.
            let normals: [Vec3; LANES] = std::array::from_fn(|i| match i {
                0 => Vec3::Z,
                1 => -Vec3::Z,
                _ => Vec3::new(next(), next(), next()).normalize_or(Vec3::X),
            });
            let local: [Vec3; LANES] = std::array::from_fn(|_| Vec3::new(next(), next(), next()));
            let lanes = to_world_about(Vec3x8::from_lanes(&normals), Vec3x8::from_lanes(&local));
            for i in 0..LANES {
                let one = Frame::from_normal(normals[i]).to_world(local[i]);
                assert_eq!(lanes.lane(i), one, "lane {i}: n = {:?}", normals[i]);
            }
        }
    }

    #[test]
    fn frames_are_orthonormal() {
        for n in [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.3, -0.4, 0.5).normalize(),
        ] {
            let f = Frame::from_normal(n);
            assert!((f.s.length() - 1.0).abs() < 1e-5);
            assert!((f.t.length() - 1.0).abs() < 1e-5);
            assert!(f.s.dot(f.t).abs() < 1e-5 && f.s.dot(n).abs() < 1e-5);
            assert!((f.s.cross(f.t) - n).length() < 1e-5);
        }
    }
}
