//! Amounts of light given photometrically in the scene file: a luminous intensity (cd), a
//! luminous flux (lm), an illuminance (lux) or a luminance (cd/m²), in place of the
//! radiometric colour strahl works in. The conversion is exact: a photometric value `v` of
//! chromaticity `c` (a colour, white by default) is the radiometric colour
//! `c · v / (683 · Y(c))`, whose luminance Y times 683 lm/W is `v` again (lengths in metres).

use super::error::SceneError;
use super::fields::{MAX_COLOUR, Table};
use super::value::Triple;
use crate::color::{LUMINOUS_EFFICACY, Rgb};
use toml::Spanned;

/// An amount given photometrically: the field's name, its value and what to divide it by to
/// reach the unit of the radiometric field it stands for (a light's flux over its solid
/// angle is its intensity; 1 otherwise).
pub(super) type Photometric<'a> = (&'a str, Option<&'a Spanned<f32>>, f32);

/// The colour of one amount of light given either as the radiometric colour `watts` (name and
/// value) or as one of `photometric`, of chromaticity `color` (field `color_name`): exactly
/// one of them, `None` when none is given. `color` applies to photometric amounts only.
pub(super) fn amount(
    t: &Table<'_>,
    watts: (&str, Option<&Spanned<Triple>>),
    photometric: &[Photometric<'_>],
    (color_name, color): (&str, Option<&Spanned<Triple>>),
) -> Result<Option<Rgb>, SceneError> {
    let names = || {
        std::iter::once(watts.0)
            .chain(photometric.iter().map(|p| p.0))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let given: Vec<&Photometric<'_>> = photometric.iter().filter(|p| p.1.is_some()).collect();
    if let Some(second) = given.get(usize::from(watts.1.is_none())) {
        let span = second.1.map_or(t.span.clone(), Spanned::span);
        return Err(t.error(
            span,
            second.0,
            format!("give one of {}, not several", names()),
        ));
    }
    let Some(&&(name, Some(value), divisor)) = given.first() else {
        if let Some(c) = color {
            return Err(t.error(
                c.span(),
                color_name,
                format!(
                    "{color_name} is the colour of a photometric amount ({}); give the colour \
                     in {} itself",
                    photometric
                        .iter()
                        .map(|p| p.0)
                        .collect::<Vec<_>>()
                        .join(", "),
                    watts.0
                ),
            ));
        }
        return t.rgb(watts.0, watts.1);
    };
    let v = *value.get_ref();
    if !(v.is_finite() && v >= 0.0) {
        return Err(t.error(value.span(), name, "must be a finite number ≥ 0"));
    }
    let chromaticity = t.rgb(color_name, color)?.unwrap_or(Rgb::WHITE);
    let y = chromaticity.luminance();
    if y <= 0.0 {
        let span = color.map_or(t.span.clone(), Spanned::span);
        return Err(t.error(span, color_name, "the colour has no luminance"));
    }
    let c = chromaticity
        * (f64::from(v) / (LUMINOUS_EFFICACY * f64::from(divisor) * f64::from(y))) as f32;
    if !(c.is_finite() && c.max_channel() <= MAX_COLOUR) {
        return Err(t.error(
            value.span(),
            name,
            format!("{v:e} is beyond what the renderers' 32-bit sums hold: choose other units"),
        ));
    }
    Ok(Some(c))
}
