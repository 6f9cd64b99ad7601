//! Light sources that are not surfaces: point, spot, directional and sky. (Every emissive
//! surface is an area light; see [`super::Material::emission`].) These lights only send
//! light; they never receive it.

use crate::color::Rgb;
use glam::Vec3;

/// A light source.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    /// Name used in reports; `light-<index>` when absent.
    pub name: Option<String>,
    /// What kind of light and its parameters.
    pub kind: LightKind,
}

/// The kinds of non-surface lights.
#[derive(Clone, Debug, PartialEq)]
pub enum LightKind {
    /// Isotropic point source.
    Point {
        /// Position (scene units).
        position: Vec3,
        /// Radiant intensity I in W·sr⁻¹; a surface at distance d receives E = I·cosθ/d².
        intensity: Rgb,
    },
    /// Point source limited to a cone, full intensity inside `inner_degrees` of the axis,
    /// falling smoothly (smoothstep in cos θ) to zero at `outer_degrees`.
    Spot {
        /// Position (scene units).
        position: Vec3,
        /// Unit axis direction the spot points along.
        direction: Vec3,
        /// Radiant intensity on the axis, W·sr⁻¹.
        intensity: Rgb,
        /// Half-angle of full intensity, degrees.
        inner_degrees: f32,
        /// Half-angle where intensity reaches zero, degrees.
        outer_degrees: f32,
    },
    /// Parallel light from infinitely far away.
    Directional {
        /// Unit direction the light travels in.
        direction: Vec3,
        /// Irradiance on a surface facing the light, W·m⁻².
        irradiance: Rgb,
    },
    /// Uniform radiance arriving from every direction not blocked by the scene.
    Sky {
        /// Radiance, W·sr⁻¹·m⁻²; an unoccluded upward-facing surface receives E = π·L.
        radiance: Rgb,
    },
}

impl LightKind {
    /// Relative intensity of a spot light in a direction at angle θ from its axis, given
    /// `cos θ`: 1 inside the inner cone, 0 outside the outer cone, smoothstep in between.
    pub fn spot_falloff(cos_theta: f32, inner_degrees: f32, outer_degrees: f32) -> f32 {
        let cos_inner = inner_degrees.to_radians().cos();
        let cos_outer = outer_degrees.to_radians().cos();
        if cos_theta >= cos_inner {
            1.0
        } else if cos_theta <= cos_outer {
            0.0
        } else {
            let x = (cos_theta - cos_outer) / (cos_inner - cos_outer);
            x * x * (3.0 - 2.0 * x)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spot_falloff_is_one_inside_zero_outside_monotone_between() {
        assert_eq!(LightKind::spot_falloff(1.0, 20.0, 30.0), 1.0);
        assert_eq!(
            LightKind::spot_falloff(35f32.to_radians().cos(), 20.0, 30.0),
            0.0
        );
        let a = LightKind::spot_falloff(22f32.to_radians().cos(), 20.0, 30.0);
        let b = LightKind::spot_falloff(28f32.to_radians().cos(), 20.0, 30.0);
        assert!(a > b && a < 1.0 && b > 0.0);
    }
}
