//! What a solver read at the scene's point sensors.

use crate::color::Rgb64;
use crate::scene::Sensor;

/// The irradiance one sensor received on the side its normal faces, W·m⁻² per channel,
/// split into the light that came straight from the light sources and the light that was
/// reflected at least once on its way.
#[derive(Clone, Debug, PartialEq)]
pub struct SensorReading {
    /// The sensor.
    pub sensor: Sensor,
    /// Irradiance straight from the lights and emitting surfaces, W·m⁻².
    pub direct: Rgb64,
    /// Irradiance reflected by surfaces on its way, W·m⁻².
    pub indirect: Rgb64,
    /// Standard error of `direct + indirect` for Monte Carlo solvers, W·m⁻²; `None` where the
    /// solver is deterministic.
    pub standard_error: Option<Rgb64>,
}

impl SensorReading {
    /// Direct plus indirect irradiance, W·m⁻².
    pub fn irradiance(&self) -> Rgb64 {
        self.direct + self.indirect
    }
}
