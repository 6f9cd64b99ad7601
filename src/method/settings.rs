//! The settings of each method, with their defaults (the command line's defaults are these),
//! and their one check ([`super::Method::check`]).

use super::SettingError;
use crate::final_gather::SurfaceGather;
use crate::light_model::LightTraceSettings;
use crate::radiosity::solve::hierarchical::HierarchicalSettings;
use crate::radiosity::solve::{
    MatrixSettings, Shading, ShootingSettings, SolverKind, SystemOptions,
};
use crate::radiosity::{MeshOptions, MeshSize};
use crate::scene::Camera;
use crate::trace::{AntialiasMode, ShadowMode};

/// Image size in pixels; a side not given is the scene camera's.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ImageSize {
    /// Width, pixels.
    pub width: Option<u32>,
    /// Height, pixels.
    pub height: Option<u32>,
}

impl ImageSize {
    /// Width and height in pixels, the camera's where not given.
    pub fn resolve(self, camera: &Camera) -> (u32, u32) {
        (
            self.width.unwrap_or(camera.width),
            self.height.unwrap_or(camera.height),
        )
    }
}

/// How camera samples are placed in each pixel (the tiled renderers: ray tracer and final
/// gather).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Antialias {
    /// None, stochastic or adaptive.
    pub mode: AntialiasMode,
    /// Camera samples per pixel (rounded up to a square).
    pub samples_per_pixel: u32,
    /// Colour difference that makes adaptive antialiasing subdivide.
    pub threshold: f32,
}

impl Default for Antialias {
    /// Stochastic, 4 samples per pixel, threshold 0.05.
    fn default() -> Self {
        Antialias {
            mode: AntialiasMode::Stochastic,
            samples_per_pixel: 4,
            threshold: 0.05,
        }
    }
}

/// The standard (Whitted-style) ray tracer's image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayTraceSettings {
    /// Image size.
    pub size: ImageSize,
    /// Seed of all random numbers.
    pub seed: u64,
    /// Reflection/refraction recursion depth (0 turns them off).
    pub max_depth: u32,
    /// Shadow rays per area light and for the sky at every shading point.
    pub light_samples: u32,
    /// Shadows from all objects, or only self-shadowing by facing.
    pub shadows: ShadowMode,
    /// Samples per pixel.
    pub antialias: Antialias,
}

impl Default for RayTraceSettings {
    /// Depth 6, 16 light samples, shadows on, 4 stochastic samples per pixel.
    fn default() -> Self {
        RayTraceSettings {
            size: ImageSize::default(),
            seed: 0,
            max_depth: 6,
            light_samples: 16,
            shadows: ShadowMode::On,
            antialias: Antialias::default(),
        }
    }
}

/// The path tracer's image, rendered in progressive passes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathTraceSettings {
    /// Image size.
    pub size: ImageSize,
    /// Seed of all random numbers.
    pub seed: u64,
    /// Most scattering events per path (`u32::MAX`: paths end by Russian roulette alone).
    pub max_depth: u32,
    /// Paths branching from the first hit of each camera ray.
    pub first_hit_paths: u32,
    /// Paths per pixel.
    pub samples_per_pixel: u32,
    /// Stop after the last pass that fits in this many seconds.
    pub time_limit: Option<f64>,
}

impl Default for PathTraceSettings {
    /// Unbounded depth, one path per first hit, 64 paths per pixel, no time limit.
    fn default() -> Self {
        PathTraceSettings {
            size: ImageSize::default(),
            seed: 0,
            max_depth: u32::MAX,
            first_hit_paths: 1,
            samples_per_pixel: 64,
            time_limit: None,
        }
    }
}

/// Least convergence tolerance of the radiosity solvers (a share of the emitted or source
/// power): below it, a change is round-off in sums of double precision.
pub const MIN_TOLERANCE: f64 = 1e-12;

/// Least error threshold of the hierarchical solvers (a share of the emitted power): the
/// links grow about fivefold for each tenfold smaller error (the built-in Cornell box takes
/// 4 s at 10⁻⁶ and 20 s at 10⁻⁷ on two cores), and below it they would outgrow any machine.
pub const MIN_ERROR: f64 = 1e-8;

/// Least per-surface error besides 0 (off): the built-in Cornell box with per-face reports
/// takes 5 s at 10⁻³ on two cores.
pub const MIN_SURFACE_ERROR: f64 = 1e-4;

/// Least minimum node area of the hierarchical solvers (a share of the scene's surface).
pub const MIN_AREA: f64 = 1e-8;

/// Least target of the final gather at the reported surfaces besides 0 (off): a standard
/// error of 10⁻⁴ of a surface's light takes about 10⁸ points on a dim one.
pub const MIN_SURFACE_GATHER: f64 = 1e-4;

/// A radiosity solver with everything it is set up by. Only the settings of `solver` are
/// used (`matrix` for the matrix solver, `shooting` for progressive refinement,
/// `hierarchical` for hierarchical radiosity, both of the last two for hierarchical
/// shooting).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RadiositySettings {
    /// Which solver.
    pub solver: SolverKind,
    /// The mesh, form factors, visibility (with the seed of its jitter) and light links.
    pub system: SystemOptions,
    /// The matrix solver's iteration.
    pub matrix: MatrixSettings,
    /// Progressive refinement and hierarchical shooting: tolerance, most shots, overshoot.
    pub shooting: ShootingSettings,
    /// The hierarchical solvers' oracle, error, minimum area and rounds.
    pub hierarchical: HierarchicalSettings,
    /// Once the solve is done, the final gather measures the light of the reported surfaces
    /// that receive little of it anew, to a standard error (`final_gather::gather_surfaces`;
    /// on by default, [`SurfaceGather::OFF`]: the solution's own values). The image methods
    /// make no report and take it off.
    pub surface_gather: SurfaceGather,
}

impl RadiositySettings {
    /// `solver` at its defaults, on its default initial mesh
    /// ([`SolverKind::default_mesh_size`]).
    pub fn new(solver: SolverKind) -> Self {
        RadiositySettings {
            solver,
            system: SystemOptions {
                mesh: MeshOptions {
                    size: solver.default_mesh_size(),
                    ..MeshOptions::default()
                },
                ..SystemOptions::default()
            },
            matrix: MatrixSettings::default(),
            shooting: ShootingSettings::default(),
            hierarchical: HierarchicalSettings::default(),
            surface_gather: SurfaceGather::default(),
        }
    }

    /// These settings without the final gather at the reported surfaces (for the image
    /// methods, which make no report).
    pub fn without_surface_gather(self) -> Self {
        RadiositySettings {
            surface_gather: SurfaceGather::OFF,
            ..self
        }
    }

    /// Sets the convergence tolerance of every solver (a fraction of the emitted power).
    pub fn with_tolerance(mut self, tolerance: f64) -> Self {
        self.matrix.tolerance = tolerance;
        self.shooting.tolerance = tolerance;
        self.hierarchical.tolerance = tolerance;
        self
    }

    /// Checks the settings the solver uses.
    pub fn check(&self) -> Result<(), SettingError> {
        let tolerance = match self.solver {
            SolverKind::Matrix => self.matrix.tolerance,
            SolverKind::Progressive | SolverKind::HierarchicalShooting => self.shooting.tolerance,
            SolverKind::Hierarchical => self.hierarchical.tolerance,
        };
        if !(tolerance.is_finite() && (MIN_TOLERANCE..1.0).contains(&tolerance)) {
            return Err(SettingError::new(
                "tolerance",
                format!(
                    "must lie between {MIN_TOLERANCE:e} and 1, 1 not included (got {tolerance}): \
                     at 1 or more the solve would stop before light bounced once"
                ),
            ));
        }
        let h = &self.hierarchical;
        if !(h.error.is_finite() && (MIN_ERROR..=1.0).contains(&h.error)) {
            return Err(SettingError::new(
                "error",
                format!("must lie between {MIN_ERROR:e} and 1 (got {})", h.error),
            ));
        }
        if !(h.surface_error.is_finite()
            && (h.surface_error == 0.0 || (MIN_SURFACE_ERROR..1.0).contains(&h.surface_error)))
        {
            return Err(SettingError::new(
                "surface-error",
                format!(
                    "must be 0 (off) or lie between {MIN_SURFACE_ERROR:e} and 1 (got {})",
                    h.surface_error
                ),
            ));
        }
        let gather = self.surface_gather.error;
        if !(gather.is_finite() && (gather == 0.0 || (MIN_SURFACE_GATHER..1.0).contains(&gather))) {
            return Err(SettingError::new(
                "surface-gather",
                format!(
                    "must be 0 (off) or lie between {MIN_SURFACE_GATHER:e} and 1 (got {gather})"
                ),
            ));
        }
        let share = self.surface_gather.below_share;
        if !(share.is_finite() && share > 0.0 && share <= 1.0) {
            return Err(SettingError::new(
                "gather-below",
                format!("must lie above 0 and at most 1 (got {share})"),
            ));
        }
        if !(h.min_area.is_finite() && (MIN_AREA..1.0).contains(&h.min_area)) {
            return Err(SettingError::new(
                "min-area",
                format!(
                    "must lie between {MIN_AREA:e} and 1, 1 not included (got {})",
                    h.min_area
                ),
            ));
        }
        let system = &self.system;
        // A solve of no rounds, sweeps or shots gathers nothing past the direct light: its
        // report would be the direct light with a negative indirect part.
        for (setting, count) in [
            ("segments", u64::from(system.mesh.segments)),
            (
                "receiver-samples",
                u64::from(system.form_factor.receiver_samples),
            ),
            ("link-samples", u64::from(system.link_samples)),
            ("max-rounds", u64::from(h.max_rounds)),
            ("max-iterations", u64::from(self.matrix.max_iterations)),
            ("max-shots", self.shooting.max_shots),
        ] {
            if count == 0 {
                return Err(SettingError::new(setting, "must be at least 1"));
            }
        }
        if let Some(margin) = system.periodic_margin
            && !(margin.is_finite() && margin >= 0.0)
        {
            return Err(SettingError::new(
                "periodic-margin",
                format!("must be a length of 0 or more (got {margin})"),
            ));
        }
        if let MeshSize::MaxEdge(length) = system.mesh.size
            && !(length.is_finite() && length > 0.0)
        {
            return Err(SettingError::new(
                "mesh-size",
                format!("must be a positive length (got {length})"),
            ));
        }
        Ok(())
    }
}

impl Default for RadiositySettings {
    /// Hierarchical radiosity at its defaults.
    fn default() -> Self {
        RadiositySettings::new(SolverKind::Hierarchical)
    }
}

/// Which links of a hierarchical solution a radiosity image draws.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum LinkSelection {
    /// None.
    #[default]
    None,
    /// Every link.
    All,
    /// The links that receive on or emit from the object of this name.
    Object(String),
}

/// A radiosity solution shown through the camera.
#[derive(Clone, Debug, PartialEq)]
pub struct RadiosityImageSettings {
    /// Image size.
    pub size: ImageSize,
    /// The solve.
    pub radiosity: RadiositySettings,
    /// Flat patches or radiosity interpolated to the vertices.
    pub shading: Shading,
    /// Draw the patch edges.
    pub wireframe: bool,
    /// Links drawn over the image (hierarchical radiosity only).
    pub links: LinkSelection,
    /// Camera rays per pixel (a regular grid, rounded up to a square).
    pub samples_per_pixel: u32,
}

impl Default for RadiosityImageSettings {
    /// Hierarchical radiosity shown smooth, 4 rays per pixel.
    fn default() -> Self {
        RadiosityImageSettings {
            size: ImageSize::default(),
            radiosity: RadiositySettings::default().without_surface_gather(),
            shading: Shading::Smooth,
            wireframe: false,
            links: LinkSelection::None,
            samples_per_pixel: 4,
        }
    }
}

/// Direct light ray-traced at each pixel, indirect light gathered from a radiosity solution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FinalGatherSettings {
    /// Image size.
    pub size: ImageSize,
    /// Seed of the camera samples and gather rays.
    pub seed: u64,
    /// The solve.
    pub radiosity: RadiositySettings,
    /// How the solution is looked up where gather rays land: flat or smooth.
    pub shading: Shading,
    /// Shadow rays per area light and for the sky at every camera hit.
    pub light_samples: u32,
    /// Gather rays per camera sample (rounded up to a square).
    pub gather_rays: u32,
    /// Samples per pixel.
    pub antialias: Antialias,
}

impl Default for FinalGatherSettings {
    /// Hierarchical radiosity looked up smooth, 16 light samples, 64 gather rays, 4
    /// stochastic samples per pixel.
    fn default() -> Self {
        FinalGatherSettings {
            size: ImageSize::default(),
            seed: 0,
            radiosity: RadiositySettings::default().without_surface_gather(),
            shading: Shading::Smooth,
            light_samples: 16,
            gather_rays: 64,
            antialias: Antialias::default(),
        }
    }
}

/// The irradiance at the scene's sensors by rays from each sensor: the direct light of the
/// standard ray tracer, and with `path_tracing` the indirect light of the path tracer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SensorTraceSettings {
    /// Points sampled on each emitting surface per sensor.
    pub samples: u32,
    /// Cosine-distributed rays per sensor for the indirect light.
    pub paths: u32,
    /// Add the indirect light by path tracing (else direct light only).
    pub path_tracing: bool,
    /// Seed of all random numbers.
    pub seed: u64,
}

impl Default for SensorTraceSettings {
    /// Direct light only, 2¹⁸ points per emitter.
    fn default() -> Self {
        SensorTraceSettings {
            samples: 1 << 18,
            paths: 1 << 18,
            path_tracing: false,
            seed: 0,
        }
    }
}

/// Refuses a count of 0 for `setting`.
pub(super) fn at_least_one(setting: &'static str, count: u32) -> Result<(), SettingError> {
    if count == 0 {
        return Err(SettingError::new(setting, "must be at least 1"));
    }
    Ok(())
}

/// The light model's settings checked: at least one photon.
pub(super) fn check_light_trace(settings: &LightTraceSettings) -> Result<(), SettingError> {
    if settings.photons == 0 {
        return Err(SettingError::new("photons", "must be at least 1"));
    }
    Ok(())
}
