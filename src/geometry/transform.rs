//! Affine transforms between object space and world space.

use super::Ray;
use glam::{Mat3, Mat4, Vec3};

/// An affine object-to-world transform with its inverse.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    /// Object-to-world matrix.
    pub to_world: Mat4,
    /// World-to-object matrix.
    pub to_object: Mat4,
}

impl Default for Transform {
    fn default() -> Self {
        Transform::IDENTITY
    }
}

impl Transform {
    /// The identity.
    pub const IDENTITY: Transform = Transform {
        to_world: Mat4::IDENTITY,
        to_object: Mat4::IDENTITY,
    };

    /// A transform from its object-to-world matrix; `None` when the matrix is singular or not
    /// finite.
    pub fn from_matrix(m: Mat4) -> Option<Self> {
        let det = m.determinant();
        if !det.is_finite() || det.abs() < 1e-20 || !m.is_finite() {
            return None;
        }
        Some(Transform {
            to_world: m,
            to_object: m.inverse(),
        })
    }

    /// Translation by `v`.
    pub fn translate(v: Vec3) -> Self {
        Transform {
            to_world: Mat4::from_translation(v),
            to_object: Mat4::from_translation(-v),
        }
    }

    /// Rotation by `degrees` about `axis` (right-handed, counter-clockwise looking down the
    /// axis); `None` for a zero axis.
    pub fn rotate(axis: Vec3, degrees: f32) -> Option<Self> {
        let axis = axis.try_normalize()?;
        let m = Mat4::from_axis_angle(axis, degrees.to_radians());
        Some(Transform {
            to_world: m,
            to_object: m.transpose(),
        })
    }

    /// Scaling by `s` per axis; `None` when a factor is zero.
    pub fn scale(s: Vec3) -> Option<Self> {
        Transform::from_matrix(Mat4::from_scale(s))
    }

    /// `other` applied after `self`.
    pub fn then(&self, other: &Transform) -> Transform {
        Transform {
            to_world: other.to_world * self.to_world,
            to_object: self.to_object * other.to_object,
        }
    }

    /// Object-space point to world space.
    pub fn point(&self, p: Vec3) -> Vec3 {
        self.to_world.transform_point3(p)
    }

    /// Object-space direction to world space.
    pub fn vector(&self, v: Vec3) -> Vec3 {
        self.to_world.transform_vector3(v)
    }

    /// Object-space normal to world space (inverse transpose), not normalised.
    pub fn normal(&self, n: Vec3) -> Vec3 {
        Mat3::from_mat4(self.to_object).transpose() * n
    }

    /// World-space ray to object space. The direction is not renormalised, so the ray
    /// parameter `t` means the same point in both spaces.
    pub fn ray_to_object(&self, ray: &Ray) -> Ray {
        Ray::new(
            self.to_object.transform_point3(ray.origin),
            self.to_object.transform_vector3(ray.dir),
        )
    }

    /// True when the map flips orientation (negative determinant).
    pub fn flips_orientation(&self) -> bool {
        self.to_world.determinant() < 0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn composition_order_and_inverse() {
        let t = Transform::scale(Vec3::splat(2.0))
            .unwrap()
            .then(&Transform::translate(Vec3::X));
        assert!((t.point(Vec3::ONE) - Vec3::new(3.0, 2.0, 2.0)).length() < 1e-6);
        let back = t.to_object.transform_point3(Vec3::new(3.0, 2.0, 2.0));
        assert!((back - Vec3::ONE).length() < 1e-6);
    }

    #[test]
    fn normals_stay_perpendicular_under_nonuniform_scale() {
        let t = Transform::scale(Vec3::new(4.0, 1.0, 1.0)).unwrap();
        let tangent = t.vector(Vec3::new(1.0, -1.0, 0.0));
        let n = t.normal(Vec3::new(1.0, 1.0, 0.0));
        assert!(tangent.dot(n).abs() < 1e-6);
    }

    #[test]
    fn rotation_is_counter_clockwise() {
        let r = Transform::rotate(Vec3::Y, 90.0).unwrap();
        assert!((r.vector(Vec3::Z) - Vec3::X).length() < 1e-6);
        assert!(Transform::rotate(Vec3::ZERO, 10.0).is_none());
        assert!(Transform::scale(Vec3::new(1.0, 0.0, 1.0)).is_none());
    }
}
