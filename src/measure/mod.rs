//! What the algorithms measure, in plain containers that they fill and that `report` and
//! `image` turn into files: the [`Film`] (radiance per pixel), the [`SurfacePower`] (power
//! per reported surface, over the [`SurfaceTable`] of a scene), the [`LitMesh`] (radiosity
//! per polygon corner), the [`ValueImage`] (lux or cd·m⁻² per pixel), the [`SensorReading`]s of the scene's point sensors and the run's
//! [`Stats`], with the process's peak memory; a solver's [`Measurement`] holds its surface
//! power, sensor readings and statistics together.

mod bands;
mod film;
mod lit_mesh;
mod measurement;
mod memory;
mod round_solution;
mod sensor_reading;
mod states;
mod stats;
mod surface_power;
mod surfaces;
mod value_image;

pub use bands::{
    BandFigures, BandMeasurement, BandValues, ChannelErrors, GroupMeasurement, SensorBand,
};
pub use film::Film;
pub use lit_mesh::{LightmappedSurface, LitMesh};
pub use measurement::Measurement;
pub use memory::{peak_resident_bytes, resident_bytes, usable_memory_bytes};
pub use round_solution::RoundSolution;
pub use sensor_reading::SensorReading;
pub use states::StateMeasurement;
pub use stats::Stats;
pub use surface_power::{PowerBalance, SurfacePower, Totals};
pub use surfaces::{ReportSurface, SurfaceTable};
pub use value_image::{Photometric, ValueImage};
