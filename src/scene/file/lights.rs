//! `[[lights]]` entries: point, Lambertian point, spot, directional, sky and CIE sky lights,
//! and a day of sun and sky states (`day.rs`).

use super::day::build_day;
use super::error::SceneError;
use super::fields::Table;
use super::format::{LightEntry, LightType};
use super::photometry::{self, Photometric};
use super::sun::{cie_sky_type, sun_toward};
use crate::scene::{Day, Light, LightKind};
use glam::Vec3;
use std::f32::consts::PI;
use toml::Spanned;

/// The lights described by `e`: one, or a day's suns and skies with the [`Day`] that tells
/// its states apart (its light indices into the returned list).
pub(super) fn build_lights(
    t: &Table<'_>,
    e: &LightEntry,
) -> Result<(Vec<Light>, Option<Day>), SceneError> {
    let kind = *e.kind.get_ref();
    t.only_fields(&e.kind_fields(), &kind.fields(), kind.name())?;
    let why = format!("type {}", kind.name());
    let why = why.as_str();
    // The light's amount, radiometric (`name`) or photometric (`photometric`, each with the
    // solid angle its flux spreads over, or 1), one of them required.
    let color =
        |name: &str, v: Option<&Spanned<super::value::Triple>>, photometric: &[Photometric<'_>]| {
            photometry::amount(t, (name, v), photometric, ("color", e.color.as_ref()))?
                .ok_or_else(|| t.missing(name, why))
        };
    let intensity = |solid_angle: f32| {
        color(
            "intensity",
            e.intensity.as_ref(),
            &[
                ("intensity_cd", e.intensity_cd.as_ref(), 1.0),
                ("flux_lm", e.flux_lm.as_ref(), solid_angle),
            ],
        )
    };
    let kind = match kind {
        LightType::Point => LightKind::Point {
            position: t.required_vec3("position", e.position.as_ref(), why)?,
            intensity: intensity(4.0 * PI)?,
        },
        LightType::Lambertian => {
            let position = t.required_vec3("position", e.position.as_ref(), why)?;
            LightKind::Lambertian {
                position,
                direction: aim(t, e, position, why)?,
                intensity: intensity(PI)?,
            }
        }
        LightType::Spot => {
            let position = t.required_vec3("position", e.position.as_ref(), why)?;
            let direction = aim(t, e, position, why)?;
            let inner = t.required_number("inner_degrees", e.inner_degrees.as_ref(), why)?;
            let outer = t.required_number("outer_degrees", e.outer_degrees.as_ref(), why)?;
            if !(outer > 0.0 && outer <= 180.0) {
                let span = e
                    .outer_degrees
                    .as_ref()
                    .map_or(t.span.clone(), Spanned::span);
                return Err(t.error(span, "outer_degrees", "must be in (0, 180]"));
            }
            if !(0.0..=outer).contains(&inner) {
                let span = e
                    .inner_degrees
                    .as_ref()
                    .map_or(t.span.clone(), Spanned::span);
                return Err(t.error(span, "inner_degrees", "must be in [0, outer_degrees]"));
            }
            LightKind::Spot {
                position,
                direction,
                intensity: intensity(LightKind::spot_solid_angle(inner, outer))?,
                inner_degrees: inner,
                outer_degrees: outer,
            }
        }
        LightType::Directional => LightKind::Directional {
            direction: -sun_toward(t, e, ("direction", e.direction.as_ref(), false), why)?,
            irradiance: color(
                "irradiance",
                e.irradiance.as_ref(),
                &[("illuminance_lux", e.illuminance_lux.as_ref(), 1.0)],
            )?,
        },
        LightType::Sky => LightKind::Sky {
            radiance: color(
                "radiance",
                e.radiance.as_ref(),
                &[("luminance_cd_m2", e.luminance_cd_m2.as_ref(), 1.0)],
            )?,
        },
        LightType::CieSky => LightKind::CieSky {
            sky: cie_sky_type(t, e, why)?,
            sun: sun_toward(t, e, ("sun_direction", e.sun_direction.as_ref(), true), why)?,
            diffuse_horizontal: color(
                "diffuse_horizontal",
                e.diffuse_horizontal.as_ref(),
                &[("illuminance_lux", e.illuminance_lux.as_ref(), 1.0)],
            )?,
        },
        LightType::Day => {
            let (lights, day) = build_day(t, e, why)?;
            return Ok((lights, Some(day)));
        }
    };
    let light = Light {
        name: e.name.clone(),
        kind,
    };
    Ok((vec![light], None))
}

/// The unit axis of a light at `position` aimed by `direction` or `look_at` (exactly one).
fn aim(t: &Table<'_>, e: &LightEntry, position: Vec3, why: &str) -> Result<Vec3, SceneError> {
    match (e.direction.as_ref(), e.look_at.as_ref()) {
        (Some(_), Some(l)) => {
            Err(t.error(l.span(), "look_at", "give direction or look_at, not both"))
        }
        (Some(d), None) => unit(
            t,
            "direction",
            d,
            t.required_vec3("direction", Some(d), why)?,
        ),
        (None, Some(l)) => {
            let target = t.required_vec3("look_at", Some(l), why)?;
            unit(t, "look_at", l, target - position)
        }
        (None, None) => Err(t.error(
            t.span.clone(),
            "direction",
            format!("missing field: {why} needs direction or look_at"),
        )),
    }
}

/// `v` normalised; an error at `field` when it is zero.
fn unit(
    t: &Table<'_>,
    field: &str,
    at: &Spanned<super::value::Coords>,
    v: Vec3,
) -> Result<Vec3, SceneError> {
    v.try_normalize()
        .ok_or_else(|| t.error(at.span(), field, "direction has zero length"))
}
