//! The pinhole camera.

use crate::geometry::Ray;
use glam::Vec3;

/// A pinhole camera: position, look-at point, up vector, vertical field of view and the
/// image resolution it is set up for.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    /// Eye position (scene units).
    pub position: Vec3,
    /// Point the camera looks at.
    pub look_at: Vec3,
    /// Approximate up direction.
    pub up: Vec3,
    /// Vertical field of view in degrees.
    pub fov_degrees: f32,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

impl Camera {
    /// A 640 × 480 camera at `position` looking at `look_at` (scene units), y up, with a
    /// vertical field of view of `fov_degrees`: how the built-in scenes frame themselves.
    pub fn landscape(position: Vec3, look_at: Vec3, fov_degrees: f32) -> Camera {
        Camera {
            position,
            look_at,
            up: Vec3::Y,
            fov_degrees,
            width: 640,
            height: 480,
        }
    }

    /// The same camera rendering at another resolution (field of view kept vertical).
    pub fn with_resolution(&self, width: u32, height: u32) -> Camera {
        Camera {
            width,
            height,
            ..self.clone()
        }
    }

    /// Precomputed ray generator for this camera; `None` when the view is degenerate (look-at
    /// equals position, up parallel to the view direction, or field of view outside (0, 180)).
    pub fn rays(&self) -> Option<CameraRays> {
        let forward = (self.look_at - self.position).try_normalize()?;
        let right = forward.cross(self.up).try_normalize()?;
        let up = right.cross(forward);
        let fov_ok = self.fov_degrees > 0.0 && self.fov_degrees < 180.0;
        if !fov_ok || self.width == 0 || self.height == 0 {
            return None;
        }
        let half_h = (self.fov_degrees.to_radians() * 0.5).tan();
        let half_w = half_h * self.width as f32 / self.height as f32;
        Some(CameraRays {
            origin: self.position,
            forward,
            // Image positions map linearly to the view plane: x ∈ [0, width] to −1…1 along
            // `right`, y ∈ [0, height] to 1…−1 along `up`.
            right: right * (2.0 * half_w / self.width as f32),
            up: up * (-2.0 * half_h / self.height as f32),
            corner: forward - right * half_w + up * half_h,
        })
    }
}

/// Turns image positions into world rays for one camera.
#[derive(Clone, Copy, Debug)]
pub struct CameraRays {
    origin: Vec3,
    /// Unit view direction.
    forward: Vec3,
    /// Direction through the top-left corner of the image (unnormalised).
    corner: Vec3,
    /// Change of the direction per pixel to the right.
    right: Vec3,
    /// Change of the direction per pixel down.
    up: Vec3,
}

impl CameraRays {
    /// The unit-direction ray through image position `(x, y)` in pixels, `x` to the right and
    /// `y` down, `(0, 0)` the top-left corner of the image (pixel centres at `+0.5`).
    pub fn ray(&self, x: f32, y: f32) -> Ray {
        let dir = (self.corner + self.right * x + self.up * y).normalize();
        Ray::new(self.origin, dir)
    }

    /// The image position `(x, y)` in pixels of the world point `p` (the inverse of
    /// [`Self::ray`]), `None` when `p` lies behind the camera or in its plane.
    pub fn project(&self, p: Vec3) -> Option<(f32, f32)> {
        let d = p - self.origin;
        let depth = d.dot(self.forward);
        if depth <= 0.0 {
            return None;
        }
        // `corner` has unit length along `forward`; `right` and `up` are across it.
        let v = d / depth - self.corner;
        Some((
            v.dot(self.right) / self.right.length_squared(),
            v.dot(self.up) / self.up.length_squared(),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn project_inverts_ray() {
        let cam = Camera {
            position: Vec3::new(1.0, 2.0, -3.0),
            look_at: Vec3::new(0.5, 1.0, 4.0),
            up: Vec3::Y,
            fov_degrees: 50.0,
            width: 64,
            height: 48,
        };
        let rays = cam.rays().unwrap();
        for (x, y) in [(0.0, 0.0), (12.5, 40.25), (64.0, 48.0)] {
            let ray = rays.ray(x, y);
            let (px, py) = rays.project(ray.origin + ray.dir * 7.0).unwrap();
            assert!((px - x).abs() < 1e-3 && (py - y).abs() < 1e-3, "{px} {py}");
            assert!(rays.project(ray.origin - ray.dir).is_none());
        }
    }

    #[test]
    fn centre_ray_looks_at_target_and_corners_span_fov() {
        let cam = Camera {
            position: Vec3::ZERO,
            look_at: Vec3::new(0.0, 0.0, 5.0),
            up: Vec3::Y,
            fov_degrees: 90.0,
            width: 100,
            height: 100,
        };
        let rays = cam.rays().unwrap();
        assert!((rays.ray(50.0, 50.0).dir - Vec3::Z).length() < 1e-6);
        let top = rays.ray(50.0, 0.0).dir;
        assert!((top.angle_between(Vec3::Z).to_degrees() - 45.0).abs() < 1e-3);
        assert!(top.y > 0.0);
        // Right-handed, y up, looking along +z: image right is world -x.
        assert!(rays.ray(100.0, 50.0).dir.x < 0.0);
        assert!(
            Camera {
                look_at: Vec3::ZERO,
                ..cam.clone()
            }
            .rays()
            .is_none()
        );
    }
}
