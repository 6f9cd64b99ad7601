//! The methods the suite runs on each case, with the settings of a quick and a full run, and
//! what each hands back: the sensor readings and, where the method reports surfaces, the
//! power per surface.

use crate::light_model::{LightTraceSettings, trace_light};
use crate::measure::{SensorReading, SurfacePower};
use crate::progress::{Cancel, NoProgress};
use crate::radiosity::solve::hierarchical::{
    HierarchicalSettings, solve_hierarchical, solve_hierarchical_shooting,
};
use crate::radiosity::solve::{
    MatrixSettings, RadiositySystem, ShootingSettings, SystemOptions, solve_matrix,
    solve_progressive,
};
use crate::radiosity::{MeshOptions, MeshSize, VisibilityOptions};
use crate::trace::{PathTracer, SensorSettings, sensor_readings};
use crate::world::World;

/// A method of computing light that the suite checks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Method {
    /// The standard ray tracer's direct light (emitting surfaces sampled, shadow rays).
    Direct,
    /// The path tracer.
    PathTrace,
    /// The light model (photons from the lights).
    LightTrace,
    /// Radiosity, full matrix (Gauss-Seidel).
    Matrix,
    /// Radiosity, progressive refinement.
    Progressive,
    /// Hierarchical shooting.
    HierarchicalShooting,
    /// Hierarchical radiosity.
    Hierarchical,
}

crate::choice::named_values!(Method {
    Method::Direct = "direct", "Standard ray tracer: direct light with shadow rays";
    Method::PathTrace = "pathtrace", "Path tracer";
    Method::LightTrace = "light-trace", "Light model: photons from the lights";
    Method::Matrix = "matrix", "Radiosity: full matrix";
    Method::Progressive = "progressive", "Radiosity: progressive refinement";
    Method::HierarchicalShooting = "hierarchical-shooting", "Hierarchical shooting";
    Method::Hierarchical = "hierarchical", "Hierarchical radiosity";
});

impl Method {
    /// True for Monte Carlo methods, whose figures carry a standard error.
    pub fn is_monte_carlo(self) -> bool {
        matches!(
            self,
            Method::Direct | Method::PathTrace | Method::LightTrace
        )
    }

    /// True when the method reports the power per surface (not only sensors).
    pub fn reports_surfaces(self) -> bool {
        !matches!(self, Method::Direct | Method::PathTrace)
    }

    /// True when the method counts light reflected between surfaces.
    pub fn counts_reflections(self) -> bool {
        self != Method::Direct
    }
}

/// How much work each method spends on a case.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Effort {
    /// Photons of the light model.
    pub photons: u64,
    /// Points per emitting surface for each sensor's direct light, and cosine-distributed
    /// rays per sensor for its indirect light (ray tracers).
    pub samples: u32,
    /// Hierarchical radiosity's error threshold (`--error`), relative to all power emitted
    /// in the scene.
    pub error: f64,
    /// Whether the quick variants of the cases are run (leaving out the slowest).
    pub quick: bool,
}

impl Effort {
    /// The quick run of the test suite: 10⁶ photons, 2¹⁸ samples, the default error.
    pub const QUICK: Effort = Effort {
        photons: 1_000_000,
        samples: 1 << 18,
        error: 1e-4,
        quick: true,
    };
    /// The full run: 8·10⁶ photons, 2²⁰ samples, the default error.
    pub const FULL: Effort = Effort {
        photons: 8_000_000,
        samples: 1 << 20,
        error: 1e-4,
        quick: false,
    };
}

/// What a method measured on a case.
pub struct Outcome {
    /// One reading per sensor of the scene.
    pub sensors: Vec<SensorReading>,
    /// Power per reported surface (methods that report surfaces).
    pub power: Option<SurfacePower>,
    /// Wall-clock seconds of the run.
    pub seconds: f64,
}

/// Why a method could not run on a case.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The light model refused the scene.
    #[error(transparent)]
    LightTrace(#[from] crate::light_model::LightTraceError),
    /// A radiosity solver refused the scene.
    #[error(transparent)]
    Radiosity(#[from] crate::radiosity::solve::SolveError),
}

/// Runs `method` on `world` with the settings of `effort` and the seed `seed`; the flat
/// radiosity solvers mesh every face into `flat_levels` quadtree levels.
pub fn run(
    world: &World,
    method: Method,
    (effort, seed): (Effort, u64),
    flat_levels: u32,
) -> Result<Outcome, RunError> {
    let start = std::time::Instant::now();
    let (sensors, power) = match method {
        Method::Direct | Method::PathTrace => {
            let settings = SensorSettings {
                samples: effort.samples,
                paths: effort.samples,
                seed,
            };
            let tracer = PathTracer::new(world, 1000, 1);
            let integrator = (method == Method::PathTrace).then_some(&tracer as _);
            (sensor_readings(world, integrator, &settings), None)
        }
        Method::LightTrace => {
            let settings = LightTraceSettings {
                photons: effort.photons,
                seed,
                ..LightTraceSettings::default()
            };
            let out = trace_light(world, &settings, &NoProgress, &Cancel::new())?;
            (out.sensors, Some(out.power))
        }
        _ => {
            let (system, solution) =
                solve_radiosity(world, method, (seed, effort.error), flat_levels)?;
            let measured = solution.measurement(&system);
            (measured.sensors, Some(measured.power))
        }
    };
    Ok(Outcome {
        sensors,
        power,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// Solves `world` with the radiosity solver `method` at its default settings (the flat
/// solvers on `flat_levels` quadtree levels, the hierarchical ones from the root patches at
/// the error threshold `error`).
fn solve_radiosity(
    world: &World,
    method: Method,
    (seed, error): (u64, f64),
    flat_levels: u32,
) -> Result<(RadiositySystem<'_>, crate::radiosity::solve::Solution), RunError> {
    let hierarchical = matches!(method, Method::Hierarchical | Method::HierarchicalShooting);
    let options = SystemOptions {
        mesh: MeshOptions {
            size: MeshSize::Levels(if hierarchical { 0 } else { flat_levels }),
            ..MeshOptions::default()
        },
        visibility: VisibilityOptions {
            seed,
            ..VisibilityOptions::default()
        },
        ..SystemOptions::default()
    };
    let (progress, cancel) = (NoProgress, Cancel::new());
    let settings = HierarchicalSettings {
        error,
        ..HierarchicalSettings::default()
    };
    let shooting = ShootingSettings::default();
    Ok(match method {
        Method::Hierarchical => solve_hierarchical(world, options, &settings, &progress, &cancel)?,
        Method::HierarchicalShooting => {
            solve_hierarchical_shooting(world, options, &settings, &shooting, &progress, &cancel)?
        }
        Method::Matrix => {
            let system = RadiositySystem::new(world, options)?;
            let solution = solve_matrix(&system, &MatrixSettings::default(), &progress, &cancel)?;
            (system, solution)
        }
        _ => {
            let system = RadiositySystem::new(world, options)?;
            let solution = solve_progressive(&system, &shooting, &progress, &cancel)?;
            (system, solution)
        }
    })
}
