//! Four `f64` 3-vectors side by side, coordinate by coordinate (`wide::f64x4`, one AVX
//! register per coordinate where the CPU has AVX): the radiosity contour integrals and shaft
//! tests take their edges, points or corners four at a time.

use glam::DVec3;
use std::ops::Sub;
use wide::f64x4;

/// Four 3-vectors, lane `k` of each coordinate belonging to vector `k`.
#[derive(Clone, Copy, Debug)]
pub struct DVec3x4 {
    /// The x coordinates.
    pub x: f64x4,
    /// The y coordinates.
    pub y: f64x4,
    /// The z coordinates.
    pub z: f64x4,
}

impl DVec3x4 {
    /// Vector `k` is `f(k)`.
    #[inline]
    pub fn from_fn(f: impl Fn(usize) -> DVec3) -> DVec3x4 {
        let v: [DVec3; 4] = std::array::from_fn(f);
        DVec3x4 {
            x: f64x4::from(v.map(|v| v.x)),
            y: f64x4::from(v.map(|v| v.y)),
            z: f64x4::from(v.map(|v| v.z)),
        }
    }

    /// `v` in every lane.
    #[inline]
    pub fn splat(v: DVec3) -> DVec3x4 {
        DVec3x4 {
            x: f64x4::splat(v.x),
            y: f64x4::splat(v.y),
            z: f64x4::splat(v.z),
        }
    }

    /// Lane-wise cross product.
    #[inline]
    pub fn cross(self, o: DVec3x4) -> DVec3x4 {
        DVec3x4 {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }

    /// Lane-wise dot product.
    #[inline]
    pub fn dot(self, o: DVec3x4) -> f64x4 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Dot product of every lane with the one vector `v`.
    #[inline]
    pub fn dot_one(self, v: DVec3) -> f64x4 {
        self.x * v.x + self.y * v.y + self.z * v.z
    }
}

impl Sub for DVec3x4 {
    type Output = DVec3x4;
    #[inline]
    fn sub(self, o: DVec3x4) -> DVec3x4 {
        DVec3x4 {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_match_glam() {
        let a = [
            DVec3::X,
            DVec3::new(1.0, 2.0, 3.0),
            -DVec3::Z,
            DVec3::splat(0.5),
        ];
        let b = [
            DVec3::Y,
            DVec3::new(-4.0, 0.5, 2.0),
            DVec3::X,
            DVec3::new(3.0, -1.0, 2.0),
        ];
        let (la, lb) = (DVec3x4::from_fn(|k| a[k]), DVec3x4::from_fn(|k| b[k]));
        let (cross, dot, diff) = (la.cross(lb), la.dot(lb), la - lb);
        let one = la.dot_one(b[1]);
        for k in 0..4 {
            let c = DVec3::new(
                cross.x.to_array()[k],
                cross.y.to_array()[k],
                cross.z.to_array()[k],
            );
            assert_eq!(c, a[k].cross(b[k]));
            assert_eq!(dot.to_array()[k], a[k].dot(b[k]));
            assert_eq!(diff.x.to_array()[k], (a[k] - b[k]).x);
            assert_eq!(one.to_array()[k], a[k].dot(b[1]));
        }
    }
}
