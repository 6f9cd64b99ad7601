//! Per-object light reports (`strahl solve --report OUT.json|OUT.csv`): the schema shared by
//! every solver ([`Report`]), the surfaces it lists ([`SurfaceTable`]), a solver-neutral
//! accumulator ([`PowerAccumulator`]) and the JSON/CSV writers ([`write_report`]).

mod accumulate;
mod schema;
mod surfaces;
mod write;

pub use accumulate::PowerAccumulator;
pub use schema::{ObjectReport, PowerBalance, Report, Rgb64, Stats, Totals, Units, add, luminance};
pub use surfaces::{ReportSurface, SurfaceTable};
pub use write::{ReportError, ReportFormat, write_report};
