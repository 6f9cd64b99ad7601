//! Light sources that are not surfaces: point (isotropic or Lambertian), spot, directional,
//! uniform sky and CIE standard sky. (Every emissive surface is an area light; see [`super::Material::emission`].)
//! These lights only send light; they never receive it.

use crate::color::Rgb;
use crate::sky::CieSkyType;
use glam::Vec3;
use std::f32::consts::PI;

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
    /// Lambertian (cosine) point source: intensity `I₀·cos θ` at angle θ from `direction`,
    /// none behind — a small diffuse emitter seen from afar (a downlight). Power π·I₀.
    Lambertian {
        /// Position (scene units).
        position: Vec3,
        /// Unit direction of the largest intensity (the emitter's normal).
        direction: Vec3,
        /// Radiant intensity along `direction`, I₀, W·sr⁻¹; a surface at distance d facing
        /// it receives E = I₀·cos θ/d².
        intensity: Rgb,
    },
    /// Point source limited to a cone, full intensity inside `inner_degrees` of the axis,
    /// falling to zero at `outer_degrees` as the smoothstep of cos θ between the cones' cosines
    /// ([`LightKind::spot_falloff`]).
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
    /// One of the 15 CIE standard general skies (CIE S 011 / ISO 15469) over the upper
    /// hemisphere (y up, −z north, +x east), black below the horizon (there is no ground):
    /// its radiance distribution is the type's relative luminance for the sun in `sun`,
    /// scaled so that an unoccluded upward-facing surface receives `diffuse_horizontal`.
    /// The sun's disc itself is not part of the sky (a [`LightKind::Directional`] light is).
    CieSky {
        /// Which of the 15 standard skies.
        sky: CieSkyType,
        /// Unit direction toward the sun (y ≥ 0 for a sun above the horizon).
        sun: Vec3,
        /// Diffuse horizontal irradiance, W·m⁻² per channel: what an unoccluded upward-facing
        /// surface receives from the sky.
        diffuse_horizontal: Rgb,
    },
}

/// Light arriving at a point from a point (isotropic or Lambertian), spot or directional
/// light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Incidence {
    /// Unit direction from the point toward the light.
    pub wi: Vec3,
    /// Distance to the light (infinite for directional lights).
    pub distance: f32,
    /// Irradiance on a surface facing the light (W·m⁻²); multiply by the cosine at the
    /// receiver for any other orientation.
    pub irradiance: Rgb,
}

impl LightKind {
    /// How a point (isotropic or Lambertian), spot or directional light reaches point `x`
    /// (ignoring occluders): `I/d²` (times the spot or cosine falloff) or the directional
    /// irradiance. `None` for the skies, for
    /// a point at the light's position, or for a spot pointing away.
    pub fn incidence(&self, x: Vec3) -> Option<Incidence> {
        let from_point = |position: Vec3, intensity: Rgb| {
            let d = position - x;
            let dist2 = d.length_squared();
            (dist2 > 0.0).then(|| Incidence {
                wi: d / dist2.sqrt(),
                distance: dist2.sqrt(),
                irradiance: intensity / dist2,
            })
        };
        match *self {
            LightKind::Point {
                position,
                intensity,
            } => from_point(position, intensity),
            LightKind::Lambertian {
                position,
                direction,
                intensity,
            } => {
                let mut inc = from_point(position, intensity)?;
                let cos = -inc.wi.dot(direction);
                inc.irradiance *= cos.max(0.0);
                (cos > 0.0).then_some(inc)
            }
            LightKind::Spot {
                position,
                direction,
                intensity,
                inner_degrees,
                outer_degrees,
            } => {
                let mut inc = from_point(position, intensity)?;
                let falloff =
                    Self::spot_falloff(-inc.wi.dot(direction), inner_degrees, outer_degrees);
                inc.irradiance *= falloff;
                (falloff > 0.0).then_some(inc)
            }
            LightKind::Directional {
                direction,
                irradiance,
            } => Some(Incidence {
                wi: -direction,
                distance: f32::INFINITY,
                irradiance,
            }),
            LightKind::Sky { .. } | LightKind::CieSky { .. } => None,
        }
    }

    /// Integral of the spot falloff over the sphere of directions, sr (a spot's power is its
    /// intensity times this).
    pub fn spot_solid_angle(inner_degrees: f32, outer_degrees: f32) -> f32 {
        let ci = inner_degrees.to_radians().cos();
        let co = outer_degrees.to_radians().cos();
        if ci > co {
            2.0 * PI * ((1.0 - ci) + 0.5 * (ci - co))
        } else {
            2.0 * PI * (1.0 - ci)
        }
    }

    /// Power (W) a point (isotropic or Lambertian), spot or directional light sends into a
    /// scene bounded by a sphere of `scene_radius`: 4π·I, π·I₀ for a Lambertian one, I times
    /// the spot's solid angle, E·πR².
    /// `None` for the skies, whose power depends on how they are sampled.
    pub fn power(&self, scene_radius: f32) -> Option<Rgb> {
        match *self {
            LightKind::Point { intensity, .. } => Some(intensity * (4.0 * PI)),
            LightKind::Lambertian { intensity, .. } => Some(intensity * PI),
            LightKind::Spot {
                intensity,
                inner_degrees,
                outer_degrees,
                ..
            } => Some(intensity * Self::spot_solid_angle(inner_degrees, outer_degrees)),
            LightKind::Directional { irradiance, .. } => {
                Some(irradiance * (PI * scene_radius * scene_radius))
            }
            LightKind::Sky { .. } | LightKind::CieSky { .. } => None,
        }
    }

    /// The light's strength, whatever its unit: the intensity of point, Lambertian and spot
    /// lights (W·sr⁻¹), a directional light's irradiance (W·m⁻²), a uniform sky's radiance
    /// (W·sr⁻¹·m⁻²), a CIE sky's diffuse horizontal irradiance (W·m⁻²).
    pub fn strength_mut(&mut self) -> &mut Rgb {
        match self {
            LightKind::Point { intensity, .. }
            | LightKind::Lambertian { intensity, .. }
            | LightKind::Spot { intensity, .. } => intensity,
            LightKind::Directional { irradiance, .. } => irradiance,
            LightKind::Sky { radiance } => radiance,
            LightKind::CieSky {
                diffuse_horizontal, ..
            } => diffuse_horizontal,
        }
    }

    /// Whether this is a sky (uniform or CIE): light from every unblocked direction at
    /// infinity rather than from a point or along one direction.
    pub fn is_sky(&self) -> bool {
        matches!(self, LightKind::Sky { .. } | LightKind::CieSky { .. })
    }

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
    fn incidence_follows_the_inverse_square_law() {
        let point = LightKind::Point {
            position: Vec3::new(0.0, 2.0, 0.0),
            intensity: Rgb::splat(8.0),
        };
        let inc = point.incidence(Vec3::ZERO).unwrap();
        assert_eq!(inc.irradiance, Rgb::splat(2.0));
        assert_eq!((inc.wi, inc.distance), (Vec3::Y, 2.0));
        let spot = LightKind::Spot {
            position: Vec3::new(0.0, 2.0, 0.0),
            direction: Vec3::Y,
            intensity: Rgb::splat(8.0),
            inner_degrees: 10.0,
            outer_degrees: 20.0,
        };
        assert!(spot.incidence(Vec3::ZERO).is_none(), "the spot points away");
        assert!(
            LightKind::Sky {
                radiance: Rgb::WHITE
            }
            .incidence(Vec3::ZERO)
            .is_none()
        );
    }

    #[test]
    fn a_lambertian_light_falls_with_the_cosine_and_sends_pi_times_its_intensity() {
        let light = LightKind::Lambertian {
            position: Vec3::new(0.0, 2.0, 0.0),
            direction: Vec3::NEG_Y,
            intensity: Rgb::splat(8.0),
        };
        assert_eq!(
            light.incidence(Vec3::ZERO).unwrap().irradiance,
            Rgb::splat(2.0)
        );
        // 60° off the axis at distance 4: 8·cos 60°/16.
        let x = Vec3::new(4.0 * 60f32.to_radians().sin(), 2.0 - 2.0, 0.0);
        let at = Vec3::new(x.x, 2.0 - 4.0 * 60f32.to_radians().cos(), 0.0);
        let e = light.incidence(at).unwrap().irradiance.r;
        assert!((e - 8.0 * 0.5 / 16.0).abs() < 1e-6, "{e}");
        assert!(
            light.incidence(Vec3::new(0.0, 3.0, 0.0)).is_none(),
            "behind"
        );
        assert_eq!(light.power(1.0), Some(Rgb::splat(8.0 * PI)));
    }

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
