//! The methods the suite runs on each case, with the settings of a quick and a full run.

use crate::method::{
    self, LightTraceSettings, MeshSize, MethodKind, RadiositySettings, SensorTraceSettings,
    SolverKind, SurfaceGather, SurfaceTraceSettings,
};

/// The methods the suite checks, in the order it runs them: the direct light of the
/// standard ray tracer and the path tracer at the sensors, the light model, the surface
/// tracer, and every radiosity solver.
pub const SUITE: [MethodKind; 8] = [
    MethodKind::Direct,
    MethodKind::PathTrace,
    MethodKind::LightTrace,
    MethodKind::SurfaceTrace,
    MethodKind::Radiosity(SolverKind::Matrix),
    MethodKind::Radiosity(SolverKind::Progressive),
    MethodKind::Radiosity(SolverKind::HierarchicalShooting),
    MethodKind::Radiosity(SolverKind::Hierarchical),
];

/// How much work each method spends on a case.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Effort {
    /// Photons of the light model.
    pub photons: u64,
    /// Points per emitting surface for each sensor's direct light, and cosine-distributed
    /// rays per sensor for its indirect light (ray tracers).
    pub samples: u32,
    /// Points per surface of the surface tracer (and its rays per sensor).
    pub points: u32,
    /// Hierarchical radiosity's error threshold (`--error`), relative to all power emitted
    /// in the scene.
    pub error: f64,
    /// Whether the quick variants of the cases are run (leaving out the slowest).
    pub quick: bool,
    /// The radiosity solvers' final gather at the reported surfaces (`--surface-gather`).
    pub surface_gather: SurfaceGather,
}

impl Effort {
    /// The quick run of the test suite: 10⁶ photons, 2¹⁸ samples, 2¹⁶ points, the default
    /// error.
    pub const QUICK: Effort = Effort {
        photons: 1_000_000,
        samples: 1 << 18,
        points: 1 << 16,
        error: 1e-4,
        quick: true,
        surface_gather: SurfaceGather::DEFAULT,
    };
    /// The full run: 8·10⁶ photons, 2²⁰ samples, 2¹⁸ points, the default error.
    pub const FULL: Effort = Effort {
        photons: 8_000_000,
        samples: 1 << 20,
        points: 1 << 18,
        error: 1e-4,
        quick: false,
        surface_gather: SurfaceGather::DEFAULT,
    };
}

/// The method `kind` as the suite runs it with the work of `effort` and the seed `seed`: the
/// ray tracers at the sensors, the light model, the flat radiosity solvers on `flat_levels`
/// quadtree levels per face and the hierarchical ones from the root patches at the error of
/// `effort`, each with the final gather at the reported surfaces `effort` asks for. `None` for a kind the suite does not run.
pub fn suite_method(
    kind: MethodKind,
    (effort, seed): (Effort, u64),
    flat_levels: u32,
) -> Option<method::Method> {
    let method = match kind {
        MethodKind::Direct | MethodKind::PathTrace => {
            method::Method::SensorTrace(SensorTraceSettings {
                samples: effort.samples,
                paths: effort.samples,
                path_tracing: kind == MethodKind::PathTrace,
                seed,
            })
        }
        MethodKind::LightTrace => method::Method::LightTrace(LightTraceSettings {
            photons: effort.photons,
            ..LightTraceSettings::default()
        }),
        MethodKind::Radiosity(solver) => {
            let mut settings = RadiositySettings::new(solver);
            if !solver.is_hierarchical() {
                settings.system.mesh.size = MeshSize::Levels(flat_levels);
            }
            settings.hierarchical.error = effort.error;
            settings.surface_gather = effort.surface_gather;
            method::Method::Radiosity(settings)
        }
        MethodKind::SurfaceTrace => method::Method::SurfaceTrace(SurfaceTraceSettings {
            points: effort.points,
            seed,
            ..SurfaceTraceSettings::default()
        }),
        MethodKind::RayTrace | MethodKind::RadiosityImage | MethodKind::FinalGather => {
            return None;
        }
    };
    Some(method.with_seed(seed))
}
