//! The methods as one API: every way strahl computes light, named with its settings
//! ([`Method`]), checked in one place ([`Method::check`]) and run by one call ([`run`]) on a
//! compiled scene, with a progress listener and a cancel token, into one shape of result
//! ([`Outcome`]). The command line, the validation suite, the benchmarks and the examples
//! run methods through this module only.
//!
//! ```
//! use std::sync::Arc;
//! use strahl::method::{
//!     AccelKind, Cancel, LightTraceSettings, Method, NoProgress, RadiositySettings, SolverKind,
//!     World, run,
//! };
//!
//! let scene = strahl::scene::open("cornell", &Default::default()).unwrap();
//! let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
//! let absorbed = |method: Method| {
//!     let outcome = run(&world, &method, &NoProgress, &Cancel::new()).unwrap();
//!     outcome.measurement.unwrap().power.totals().absorbed_power.luminance()
//! };
//! let mut radiosity = RadiositySettings::new(SolverKind::Hierarchical);
//! radiosity.hierarchical.error = 1e-3;
//! let photons = LightTraceSettings { photons: 200_000, ..LightTraceSettings::default() };
//! // Two independent methods agree on the power the box absorbs (the light that leaves
//! // through its open front is not absorbed).
//! let (by_radiosity, by_photons) =
//!     (absorbed(Method::Radiosity(radiosity)), absorbed(Method::LightTrace(photons)));
//! assert!((by_radiosity / by_photons - 1.0).abs() < 0.02, "{by_radiosity} {by_photons}");
//! ```

mod batches;
mod error;
mod gather_view;
mod kind;
mod named;
mod outcome;
mod parts;
mod render_batches;
mod run;
mod settings;

pub use batches::{merge_batches, run_batch};
pub use error::{MethodError, SettingError};
pub use gather_view::FinalGatherView;
pub use kind::MethodKind;
pub use named::SettingValue;
pub use outcome::{Outcome, SolvedRadiosity};
pub use parts::{Parts, run_with_parts};
pub use render_batches::{
    RenderBatchSettings, RenderPartial, merge_render_batches, run_render_batch,
};
pub use run::{run, run_keeping, solve_radiosity};
pub use settings::{
    Antialias, FinalGatherSettings, ImageSize, LinkSelection, MIN_AREA, MIN_ERROR,
    MIN_SURFACE_ERROR, MIN_SURFACE_GATHER, MIN_TOLERANCE, PathTraceSettings,
    RadiosityImageSettings, RadiositySettings, RayTraceSettings, SensorTraceSettings,
};

// The vocabulary a front end needs besides this module's own types — the settings' parts,
// compiling a scene, progress and cancellation, what the outcome holds, the memory a run
// uses — so that front ends import this module, `scene`, `report`, `image` and `validate`
// only.
pub use crate::accel::AccelKind;
pub use crate::choice::{Choice, UnknownName};
pub use crate::color::{LUMINOUS_EFFICACY, Rgb, Rgb64};
pub use crate::geometry::Ray;
pub use crate::measure::{
    BandFigures, BandMeasurement, BandValues, Film, LightmappedSurface, LitMesh, Measurement,
    Photometric, RoundSolution, SensorBand, SensorReading, ValueImage, peak_resident_bytes,
    resident_bytes, usable_memory_bytes,
};
pub use crate::progress::{Cancel, NoProgress, ProgressListener};
pub use crate::radiosity::solve::hierarchical::{HierarchicalSettings, Oracle, RefinePass};
pub use crate::radiosity::solve::{
    DisplaySettings, Iteration, KeptLinks, LinkDisplay, MatrixSettings, Probe, ProbeHit,
    RoundStats, Shading, ShootingSettings, Solution, SolverKind, SystemOptions,
};
pub use crate::radiosity::{
    FormFactorMethod, FormFactorOptions, MeshOptions, MeshSize, VisRays, VisibilityOptions,
    non_diffuse_materials,
};
pub use crate::trace::{AntialiasMode, ShadowMode, SurfaceTraceSettings};
pub use crate::world::{GeometryError, QueryTiming, RayBench, RaySet, World, bench_rays};

pub use crate::final_gather::SurfaceGather;
pub use crate::light_model::{LightTracePartial, LightTraceSettings};
pub use crate::sampling::{Batch, MergeError, NoSuchBatch};
use settings::{at_least_one, check_light_trace};

/// A method of computing light with all its settings.
#[derive(Clone, Debug, PartialEq)]
pub enum Method {
    /// The standard (Whitted-style) ray tracer's image.
    RayTrace(RayTraceSettings),
    /// The path tracer's image.
    PathTrace(PathTraceSettings),
    /// A radiosity solution shown through the camera.
    RadiosityImage(RadiosityImageSettings),
    /// Direct light ray-traced, indirect light gathered from a radiosity solution.
    FinalGather(FinalGatherSettings),
    /// The irradiance at the sensors by rays from each sensor.
    SensorTrace(SensorTraceSettings),
    /// The light model: photons from the lights, power per surface and at the sensors.
    LightTrace(LightTraceSettings),
    /// Rays from points on every surface: power per surface and at the sensors.
    SurfaceTrace(SurfaceTraceSettings),
    /// A radiosity solver: power per surface and at the sensors, and the solution.
    Radiosity(RadiositySettings),
}

impl Method {
    /// The method's kind (its name without settings).
    pub fn kind(&self) -> MethodKind {
        match self {
            Method::RayTrace(_) => MethodKind::RayTrace,
            Method::PathTrace(_) => MethodKind::PathTrace,
            Method::RadiosityImage(_) => MethodKind::RadiosityImage,
            Method::FinalGather(_) => MethodKind::FinalGather,
            Method::SensorTrace(s) if s.path_tracing => MethodKind::PathTrace,
            Method::SensorTrace(_) => MethodKind::Direct,
            Method::LightTrace(_) => MethodKind::LightTrace,
            Method::SurfaceTrace(_) => MethodKind::SurfaceTrace,
            Method::Radiosity(r) => MethodKind::Radiosity(r.solver),
        }
    }

    /// The radiosity solve the method includes, if any.
    pub fn radiosity(&self) -> Option<&RadiositySettings> {
        match self {
            Method::RadiosityImage(s) => Some(&s.radiosity),
            Method::FinalGather(s) => Some(&s.radiosity),
            Method::Radiosity(s) => Some(s),
            Method::RayTrace(_)
            | Method::PathTrace(_)
            | Method::SensorTrace(_)
            | Method::LightTrace(_)
            | Method::SurfaceTrace(_) => None,
        }
    }

    /// The method with every random number it draws seeded by `seed` (same seed, same
    /// result, for any thread count).
    pub fn with_seed(mut self, seed: u64) -> Self {
        match &mut self {
            Method::RayTrace(s) => s.seed = seed,
            Method::PathTrace(s) => s.seed = seed,
            Method::RadiosityImage(s) => s.radiosity.system.visibility.seed = seed,
            Method::FinalGather(s) => {
                s.seed = seed;
                s.radiosity.system.visibility.seed = seed;
            }
            Method::SensorTrace(s) => s.seed = seed,
            Method::LightTrace(s) => s.seed = seed,
            Method::SurfaceTrace(s) => s.seed = seed,
            Method::Radiosity(s) => s.system.visibility.seed = seed,
        }
        self
    }

    /// Checks every setting the method uses; the error names the setting as the command
    /// line does.
    pub fn check(&self) -> Result<(), SettingError> {
        match self {
            Method::RayTrace(s) => {
                at_least_one("light-samples", s.light_samples)?;
                check_antialias(&s.antialias)
            }
            Method::PathTrace(s) => {
                if s.samples_per_pixel == 0 {
                    return Err(SettingError::new("spp", "must be at least 1 for pathtrace"));
                }
                at_least_one("first-hit-paths", s.first_hit_paths)?;
                match s.time_limit {
                    Some(t) if !(t.is_finite() && t > 0.0) => Err(SettingError::new(
                        "time-limit",
                        format!("must be a positive number of seconds (got {t})"),
                    )),
                    _ => Ok(()),
                }
            }
            Method::RadiosityImage(s) => {
                s.radiosity.check()?;
                no_surface_gather(&s.radiosity)?;
                at_least_one("spp", s.samples_per_pixel)?;
                if s.links != LinkSelection::None
                    && s.radiosity.solver != crate::radiosity::solve::SolverKind::Hierarchical
                {
                    return Err(SettingError::new(
                        "links",
                        "needs --solver hierarchical (the other solvers keep no links)",
                    ));
                }
                Ok(())
            }
            Method::FinalGather(s) => {
                s.radiosity.check()?;
                no_surface_gather(&s.radiosity)?;
                at_least_one("gather-rays", s.gather_rays)?;
                at_least_one("light-samples", s.light_samples)?;
                check_antialias(&s.antialias)
            }
            Method::SensorTrace(s) => {
                at_least_one("samples", s.samples)?;
                at_least_one("samples", s.paths)
            }
            Method::LightTrace(s) => check_light_trace(s),
            Method::SurfaceTrace(s) if s.points < 2 => Err(SettingError::new(
                "points",
                format!(
                    "must be at least 2, for each surface's standard error (got {})",
                    s.points
                ),
            )),
            Method::SurfaceTrace(s) if !(0.0..1.0).contains(&s.standard_error) => {
                Err(SettingError::new(
                    "standard-error",
                    format!(
                        "must be a share of each surface's light, 0 (off) to under 1 (got {})",
                        s.standard_error
                    ),
                ))
            }
            Method::SurfaceTrace(_) => Ok(()),
            Method::Radiosity(s) => s.check(),
        }
    }
}

/// The final gather at the reported surfaces off: it measures a solve's report, and an
/// image method makes none.
fn no_surface_gather(radiosity: &RadiositySettings) -> Result<(), SettingError> {
    if radiosity.surface_gather.is_on() {
        return Err(SettingError::new(
            "surface-gather",
            "measures the reported surfaces of a solve; an image reports none",
        ));
    }
    Ok(())
}

/// Samples per pixel at least 1 and a finite threshold.
fn check_antialias(antialias: &Antialias) -> Result<(), SettingError> {
    at_least_one("spp", antialias.samples_per_pixel)?;
    if !antialias.threshold.is_finite() {
        return Err(SettingError::new(
            "aa-threshold",
            format!("must be a finite number (got {})", antialias.threshold),
        ));
    }
    Ok(())
}
