//! Reports and exports of what the solvers measured: the per-object light report shared by
//! every solver ([`Report`], built from a [`crate::measure::SurfacePower`]) with its JSON/CSV
//! writers ([`write_report`]), and the export of a [`crate::measure::LitMesh`] as glTF or
//! PLY ([`export_lit_mesh`]).

mod bands;
mod export;
mod schema;
mod write;

pub use bands::{BandObjectReport, BandReport, BandSensorReport, RedFarRedReport};
pub use export::{ExportError, ExportFormat, export_lit_mesh};
pub use schema::{ObjectReport, Report, SensorReport, StateReport, Units};
pub use write::{ReportError, ReportFormat, sensors_csv_path, write_report};
