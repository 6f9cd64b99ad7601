//! Why a method could not run.

use crate::light_model::LightTraceError;
use crate::radiosity::solve::SolveError;
use crate::sampling::{MergeError, NoSuchBatch};
use crate::scene::SpectralError;
use crate::world::GeometryError;

/// A setting outside its range, named as the command line names it (`min-area`,
/// `time-limit`): displays as `min-area must lie between 0 and 1 (got 0)`.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{setting} {problem}")]
pub struct SettingError {
    /// The setting, in kebab case.
    pub setting: &'static str,
    /// What is wrong with its value.
    pub problem: String,
}

impl SettingError {
    /// `setting` has a value that `problem` describes.
    pub fn new(setting: &'static str, problem: impl Into<String>) -> Self {
        SettingError {
            setting,
            problem: problem.into(),
        }
    }
}

/// An error of [`super::run`].
#[derive(Debug, thiserror::Error)]
pub enum MethodError {
    /// A setting is out of range ([`super::Method::check`]).
    #[error(transparent)]
    Setting(#[from] SettingError),
    /// The camera cannot make rays (look_at at the position, up along the view, or a field
    /// of view outside 0–180°).
    #[error("the camera is degenerate")]
    DegenerateCamera,
    /// A radiosity image was asked to draw the links of an object the scene does not have.
    #[error("links: no object named '{name}' (objects: {})", .objects.join(", "))]
    NoSuchObject {
        /// The name asked for.
        name: String,
        /// The names the scene's objects have.
        objects: Vec<String>,
    },
    /// The light model refused the scene.
    #[error(transparent)]
    LightTrace(#[from] LightTraceError),
    /// Only the light model's runs and the path tracer's images split into batches (the
    /// method named).
    #[error(
        "{0} does not run in batches: only the light model (light-trace) and the path tracer \
         (pathtrace) do"
    )]
    NotInBatches(&'static str),
    /// A scene with wavelength bands: its bands are not split into batches.
    #[error("a scene with wavelength bands is not split into batches yet: solve it in one run")]
    BandsInBatches,
    /// The ray tracers and radiosity light a periodic scene by sun and sky only (the method
    /// named): they light the plot's own lamps and emitting surfaces, not their copies in
    /// every plot.
    #[error(
        "{0} lights a periodic scene (a plot repeated in x and z) by directional lights and \
         skies only; with lamps or emitting surfaces use the light model (light-trace)"
    )]
    PeriodicLamps(&'static str),
    /// A batch that is not one of its count.
    #[error(transparent)]
    NoSuchBatch(#[from] NoSuchBatch),
    /// Batches that do not make one run.
    #[error(transparent)]
    Merge(#[from] MergeError),
    /// A radiosity solver refused the scene.
    #[error(transparent)]
    Radiosity(#[from] SolveError),
    /// The scene's bands cannot be solved (boxed: the error names materials and bands).
    #[error(transparent)]
    Bands(#[from] Box<SpectralError>),
    /// A band's scene could not be compiled.
    #[error(transparent)]
    Geometry(#[from] GeometryError),
}
