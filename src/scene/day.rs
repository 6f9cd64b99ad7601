//! A day of sun and sky states in a scene (a `day` light of a scene file): which of the
//! scene's lights each state is, so that the day can be solved state by state as well as
//! as the mean over its states, which the lights give together.

use super::Scene;

/// A day: its states in order, each with its lights.
#[derive(Clone, Debug, PartialEq)]
pub struct Day {
    /// The day light's name.
    pub name: String,
    /// The states, in the order given.
    pub states: Vec<DayState>,
}

/// One state of a day: its clock time and its lights (the sun and the CIE sky; none when
/// the sun was below the horizon). Each light holds 1/n of the state's strength, n the
/// number of states, so that the day's lights together give the mean over the states.
#[derive(Clone, Debug, PartialEq)]
pub struct DayState {
    /// The clock time as given (`13:30`).
    pub time: String,
    /// Indices of the state's lights in [`Scene::lights`].
    pub lights: Vec<usize>,
}

impl Scene {
    /// The scene lit by state `state` of its day alone, at the state's full strength, with
    /// every light outside the day as it is: the other states' lights stay in the list,
    /// dark, so that the scene's lights match this one's light for light. Without bands
    /// (the state's figures are RGB). `None` without a day or for a state it lacks.
    pub fn state_scene(&self, state: usize) -> Option<Scene> {
        let day = self.day.as_ref()?;
        let own = &day.states.get(state)?.lights;
        let states = day.states.len() as f32;
        let mut out = self.clone();
        for (i, light) in out.lights.iter_mut().enumerate() {
            let strength = light.kind.strength_mut();
            if own.contains(&i) {
                *strength *= states;
            } else if day.states.iter().any(|s| s.lights.contains(&i)) {
                *strength *= 0.0;
            }
        }
        out.day = None;
        out.spectral = None;
        Some(out)
    }
}
