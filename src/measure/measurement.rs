//! Everything one solver run measured on a scene's surfaces, as `report` takes it.

use super::{SensorReading, Stats, SurfacePower};

/// What a solver measured: the power per reported surface (W), the irradiance at every
/// point sensor of the scene (W·m⁻²) and the run's statistics, under the solver's name.
#[derive(Clone, Debug)]
pub struct Measurement {
    /// The solver's name in reports (`light-trace`, `hierarchical`, …).
    pub solver: &'static str,
    /// Incident, absorbed, emitted and reflected power per reported surface, W.
    pub power: SurfacePower,
    /// One reading per sensor of the scene, in scene order.
    pub sensors: Vec<SensorReading>,
    /// Time, rays and the solver's own counts.
    pub stats: Stats,
}
