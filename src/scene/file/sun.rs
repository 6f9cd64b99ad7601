//! Where the sun is, for a directional light or a CIE sky: given as a vector, or by date,
//! time and place through NREL's Solar Position Algorithm ([`crate::sky::sun_position`]);
//! and which CIE standard sky a light names.

use super::error::SceneError;
use super::fields::Table;
use super::format::LightEntry;
use super::value::Coords;
use crate::sky::{
    CieSkyType, DEFAULT_DELTA_T_S, LocalTime, Observer, STANDARD_PRESSURE_MBAR,
    STANDARD_TEMPERATURE_C, SUNRISE_REFRACTION_DEG, sun_position,
};
use glam::Vec3;
use std::ops::Range;
use toml::Spanned;

/// The unit direction toward the sun of the light `e`: from the vector field `vector`
/// (name, value, and whether it points toward the sun or along the light) or from the date
/// fields, exactly one of the two. A sun placed by date below the horizon is an error at
/// `time` (it would give no direct light), and so is a vector toward the sun that points
/// below the horizon.
pub(super) fn sun_toward(
    t: &Table<'_>,
    e: &LightEntry,
    (name, vector, toward): (&str, Option<&Spanned<Coords>>, bool),
    why: &str,
) -> Result<Vec3, SceneError> {
    let dated = dated_fields(e);
    match (vector, dated.first()) {
        (Some(_), Some((field, span))) => Err(t.error(
            span.clone(),
            field,
            format!("give {name} or the date, time and place of the sun, not both"),
        )),
        (Some(v), None) => {
            let d = t
                .required_vec3(name, Some(v), why)?
                .try_normalize()
                .ok_or_else(|| t.error(v.span(), name, "direction has zero length"))?;
            if toward && d.y <= 0.0 {
                return Err(t.error(
                    v.span(),
                    name,
                    "the sun must be above the horizon (y > 0): the sky has no ground model",
                ));
            }
            Ok(if toward { d } else { -d })
        }
        (None, Some(_)) => sun_by_date(t, e, why),
        (None, None) => Err(t.error(
            t.span.clone(),
            name,
            format!(
                "missing field: {why} needs {name} or date, time, utc_offset_hours, \
                 latitude_deg and longitude_deg"
            ),
        )),
    }
}

/// The date fields of `e` that are present, with their spans.
fn dated_fields(e: &LightEntry) -> Vec<(&'static str, Range<usize>)> {
    let text = |v: &Option<Spanned<String>>| v.as_ref().map(Spanned::span);
    let real = |v: &Option<Spanned<f64>>| v.as_ref().map(Spanned::span);
    [
        ("date", text(&e.date)),
        ("time", text(&e.time)),
        ("utc_offset_hours", real(&e.utc_offset_hours)),
        ("latitude_deg", real(&e.latitude_deg)),
        ("longitude_deg", real(&e.longitude_deg)),
        ("elevation_m", real(&e.elevation_m)),
        ("pressure_mbar", real(&e.pressure_mbar)),
        ("temperature_c", real(&e.temperature_c)),
        ("delta_t_s", real(&e.delta_t_s)),
    ]
    .into_iter()
    .filter_map(|(name, span)| span.map(|span| (name, span)))
    .collect()
}

/// The direction toward the sun at the date, time and place `e` gives.
fn sun_by_date(t: &Table<'_>, e: &LightEntry, why: &str) -> Result<Vec3, SceneError> {
    let time = e.time.as_ref().ok_or_else(|| t.missing("time", why))?;
    let clock = clock_time(t, time)?;
    let (toward, zenith_deg) = sun_at(t, e, clock, why)?;
    if zenith_deg.is_nan() || zenith_deg >= 90.0 {
        return Err(t.error(
            time.span(),
            "time",
            format!(
                "the sun is {:.2}° below the horizon at this date, time and place (zenith \
                 {:.2}°): it would give no direct light",
                zenith_deg - 90.0,
                zenith_deg
            ),
        ));
    }
    Ok(toward)
}

/// Hour, minute and second of the clock time `time` of table `t` (its field `time`).
pub(super) fn clock_time(
    t: &Table<'_>,
    time: &Spanned<String>,
) -> Result<(u32, u32, f64), SceneError> {
    parse_time(time.get_ref()).ok_or_else(|| {
        t.error(
            time.span(),
            "time",
            "expected a clock time \"HH:MM\" or \"HH:MM:SS\" (seconds may have a fraction)",
        )
    })
}

/// The unit direction toward the sun and its topocentric zenith angle (degrees; 90 or more
/// below the horizon) at the clock time `(hour, minute, second)` of the date and place `e`
/// gives.
pub(super) fn sun_at(
    t: &Table<'_>,
    e: &LightEntry,
    (hour, minute, second): (u32, u32, f64),
    why: &str,
) -> Result<(Vec3, f64), SceneError> {
    let date = e.date.as_ref().ok_or_else(|| t.missing("date", why))?;
    let (year, month, day) = parse_date(date.get_ref())
        .ok_or_else(|| t.error(date.span(), "date", "expected a date \"YYYY-MM-DD\""))?;
    let number =
        |name: &str, v: Option<&Spanned<f64>>, range: (f64, f64), default: Option<f64>| match v {
            None => default.ok_or_else(|| t.missing(name, why)),
            Some(s) if (range.0..=range.1).contains(s.get_ref()) => Ok(*s.get_ref()),
            Some(s) => Err(t.error(
                s.span(),
                name,
                format!("must be a number in [{}, {}]", range.0, range.1),
            )),
        };
    let local = LocalTime {
        year,
        month,
        day,
        hour,
        minute,
        second,
        utc_offset_hours: number(
            "utc_offset_hours",
            e.utc_offset_hours.as_ref(),
            (-18.0, 18.0),
            None,
        )?,
        delta_ut1_s: 0.0,
        delta_t_s: number(
            "delta_t_s",
            e.delta_t_s.as_ref(),
            (-1e5, 1e5),
            Some(DEFAULT_DELTA_T_S),
        )?,
    };
    let observer = Observer {
        latitude_deg: number("latitude_deg", e.latitude_deg.as_ref(), (-90.0, 90.0), None)?,
        longitude_deg: number(
            "longitude_deg",
            e.longitude_deg.as_ref(),
            (-180.0, 180.0),
            None,
        )?,
        elevation_m: number(
            "elevation_m",
            e.elevation_m.as_ref(),
            (-1e4, 1e5),
            Some(0.0),
        )?,
        pressure_mbar: number(
            "pressure_mbar",
            e.pressure_mbar.as_ref(),
            (1.0, 2000.0),
            Some(STANDARD_PRESSURE_MBAR),
        )?,
        temperature_c: number(
            "temperature_c",
            e.temperature_c.as_ref(),
            (-100.0, 100.0),
            Some(STANDARD_TEMPERATURE_C),
        )?,
        refraction_deg: SUNRISE_REFRACTION_DEG,
    };
    let sun = sun_position(&local, &observer);
    Ok((sun.direction().as_vec3().normalize(), sun.zenith_deg))
}

/// The CIE standard general sky that `e`'s `sky_type` numbers (1–15), required.
pub(super) fn cie_sky_type(
    t: &Table<'_>,
    e: &LightEntry,
    why: &str,
) -> Result<CieSkyType, SceneError> {
    let number = e
        .sky_type
        .as_ref()
        .ok_or_else(|| t.missing("sky_type", why))?;
    u8::try_from(*number.get_ref())
        .ok()
        .and_then(CieSkyType::from_number)
        .ok_or_else(|| {
            t.error(
                number.span(),
                "sky_type",
                "must be a CIE standard general sky number, 1 to 15",
            )
        })
}

/// Year, month and day of `"YYYY-MM-DD"` (a leading `-` for years before 1 AD, astronomical
/// numbering), the day checked against the month's length in the Gregorian calendar.
fn parse_date(text: &str) -> Option<(i32, u32, u32)> {
    let (sign, digits) = match text.strip_prefix('-') {
        Some(rest) => (-1, rest),
        None => (1, text),
    };
    let mut parts = digits.split('-');
    let year: i32 = parts.next()?.parse().ok()?;
    let month: u32 = parts.next()?.parse().ok()?;
    let day: u32 = parts.next()?.parse().ok()?;
    if parts.next().is_some() || !(1..=12).contains(&month) {
        return None;
    }
    let year = sign * year;
    let leap = year % 4 == 0 && (year % 100 != 0 || year % 400 == 0);
    let days = match month {
        2 if leap => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    };
    (1..=days).contains(&day).then_some((year, month, day))
}

/// Hour, minute and second of `"HH:MM"` or `"HH:MM:SS[.fff]"`.
fn parse_time(text: &str) -> Option<(u32, u32, f64)> {
    let mut parts = text.split(':');
    let hour: u32 = parts.next()?.parse().ok()?;
    let minute: u32 = parts.next()?.parse().ok()?;
    let second: f64 = match parts.next() {
        Some(s) => s.parse().ok()?,
        None => 0.0,
    };
    let valid = parts.next().is_none() && hour < 24 && minute < 60 && (0.0..61.0).contains(&second);
    valid.then_some((hour, minute, second))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dates_and_times_parse_and_nonsense_is_refused() {
        assert_eq!(parse_date("2003-10-17"), Some((2003, 10, 17)));
        assert_eq!(parse_date("2024-02-29"), Some((2024, 2, 29)));
        assert_eq!(parse_date("2023-02-29"), None);
        assert_eq!(parse_date("-500-03-01"), Some((-500, 3, 1)));
        assert_eq!(parse_date("2003-13-01"), None);
        assert_eq!(parse_date("2003/10/17"), None);
        assert_eq!(parse_time("12:30:30"), Some((12, 30, 30.0)));
        assert_eq!(parse_time("06:05"), Some((6, 5, 0.0)));
        assert_eq!(parse_time("24:00"), None);
        assert_eq!(parse_time("12:60"), None);
        assert_eq!(parse_time("12:30:30:1"), None);
    }
}
