//! A `day` light: the sun and a CIE sky at a list of clock times of one date and place (a
//! weather file's rows), given as their mean — each state's sun and sky with 1/n of its
//! irradiance — so that one solve gives every surface the mean light over the states, and a
//! day's sums are the mean times the time the states stand for.

use super::error::SceneError;
use super::fields::Table;
use super::format::LightEntry;
use super::sun::{cie_sky_type, clock_time, sun_at};
use crate::scene::{Day, DayState, Light, LightKind};

/// The lights of the day `e`: for every state whose sun is above the horizon, a directional
/// light (its `direct_normal` irradiance over the number of states) and the CIE sky of
/// `sky_type` (its `diffuse_horizontal` over the number of states), named `<name> <time>
/// sun` and `<name> <time> sky`; a state with the sun below the horizon adds nothing but
/// counts in the mean. With them the [`Day`]: each state's lights, by index into the list.
pub(super) fn build_day(
    t: &Table<'_>,
    e: &LightEntry,
    why: &str,
) -> Result<(Vec<Light>, Day), SceneError> {
    let sky = cie_sky_type(t, e, why)?;
    let states = e.states.as_ref().ok_or_else(|| t.missing("states", why))?;
    if states.get_ref().is_empty() {
        return Err(t.error(states.span(), "states", "a day needs at least one state"));
    }
    let share = 1.0 / states.get_ref().len() as f32;
    let name = e.name.clone().unwrap_or_else(|| "day".to_string());
    let mut lights = Vec::new();
    let mut day = Day {
        name: name.clone(),
        states: Vec::with_capacity(states.get_ref().len()),
    };
    for (i, state) in states.get_ref().iter().enumerate() {
        let s = Table::new(t.src, t.field(&format!("states[{i}]")), state.span());
        let entry = state.get_ref();
        let state_why = "a day's state";
        let time = entry
            .time
            .as_ref()
            .ok_or_else(|| s.missing("time", state_why))?;
        let clock = clock_time(&s, time)?;
        // Finite and not negative (`Table::rgb`), required.
        let irradiance =
            |field: &str, v| s.rgb(field, v)?.ok_or_else(|| s.missing(field, state_why));
        let direct = irradiance("direct_normal", entry.direct_normal.as_ref())?;
        let diffuse = irradiance("diffuse_horizontal", entry.diffuse_horizontal.as_ref())?;
        let (toward, zenith_deg) = sun_at(t, e, clock, why)?;
        let at = time.get_ref();
        day.states.push(DayState {
            time: at.clone(),
            lights: Vec::new(),
        });
        if zenith_deg.is_nan() || zenith_deg >= 90.0 {
            continue;
        }
        if let Some(state) = day.states.last_mut() {
            state.lights = vec![lights.len(), lights.len() + 1];
        }
        lights.push(Light {
            name: Some(format!("{name} {at} sun")),
            kind: LightKind::Directional {
                direction: -toward,
                irradiance: direct * share,
            },
        });
        lights.push(Light {
            name: Some(format!("{name} {at} sky")),
            kind: LightKind::CieSky {
                sky,
                sun: toward,
                diffuse_horizontal: diffuse * share,
            },
        });
    }
    Ok((lights, day))
}
