//! What a method measured of each state of a scene's day, the state alone.

use super::{SensorReading, SurfacePower};

/// What a method measured of one state of a scene's day, the state alone.
#[derive(Clone, Debug)]
pub struct StateMeasurement {
    /// The state's clock time as the scene gives it.
    pub time: String,
    /// Power per reported surface, W (`None` for methods that measure only sensors).
    pub power: Option<SurfacePower>,
    /// Its sensors' readings, W·m⁻².
    pub sensors: Vec<SensorReading>,
}
