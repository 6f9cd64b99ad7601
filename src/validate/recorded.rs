//! The one reference of the suite that is not a closed form: the built-in Cornell box with
//! every face of every object reported on its own, measured by the light model at 2·10⁸
//! photons (each face's standard error 0.01–0.2 % of its light), recorded in
//! `cornell_per_face_light_model.json` beside this file with the commit that made it and how
//! to make it again. No formula gives the light on a block face in the box's shadow; an
//! independent method at many times the work does, and `tests/per_surface.rs` checks that
//! the recording still describes the light model of this code.

use crate::color::Rgb64;
use serde::Deserialize;

/// One face of the recording.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct RecordedFace {
    /// The object's name in the built-in scene.
    pub object: String,
    /// The face of the object (its side of a block, its triangle pair of a wall).
    pub face: u32,
    /// Power arriving on the face, both sides, W per channel.
    pub incident_power: [f64; 3],
    /// Standard error of `incident_power`, W per channel.
    pub incident_power_standard_error: [f64; 3],
    /// Power the face absorbs, W per channel.
    pub absorbed_power: [f64; 3],
}

impl RecordedFace {
    /// [`Self::incident_power`] as a colour, W.
    pub fn incident(&self) -> Rgb64 {
        let [r, g, b] = self.incident_power;
        Rgb64::new(r, g, b)
    }

    /// [`Self::incident_power_standard_error`] as a colour, W.
    pub fn incident_error(&self) -> Rgb64 {
        let [r, g, b] = self.incident_power_standard_error;
        Rgb64::new(r, g, b)
    }
}

/// The recording's file.
#[derive(Deserialize)]
struct Recording {
    faces: Vec<RecordedFace>,
}

/// Every face of the built-in Cornell box as the light model measured it (see the module).
pub fn cornell_faces() -> Vec<RecordedFace> {
    let text = include_str!("cornell_per_face_light_model.json");
    serde_json::from_str::<Recording>(text)
        .expect("the recorded Cornell box faces are valid JSON (checked by this module's test)")
        .faces
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_recording_holds_every_face_with_its_error() {
        let faces = cornell_faces();
        assert_eq!(faces.len(), 20);
        for f in &faces {
            for c in 0..3 {
                let (p, e) = (f.incident_power[c], f.incident_power_standard_error[c]);
                assert!(p > 0.0 && e > 0.0 && e < 0.003 * p, "{f:?}");
                assert!(
                    f.absorbed_power[c] > 0.0 && f.absorbed_power[c] < p,
                    "{f:?}"
                );
            }
        }
    }
}
