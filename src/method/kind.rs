//! The methods by name: what a front end lists and parses (`--method`, `--solver`, a Python
//! keyword), each with the [`Method`] of its default settings.

use super::{
    FinalGatherSettings, Method, PathTraceSettings, RadiosityImageSettings, RadiositySettings,
    RayTraceSettings, SensorTraceSettings,
};
use crate::choice::Choice;
use crate::light_model::LightTraceSettings;
use crate::radiosity::solve::SolverKind;
use crate::trace::SurfaceTraceSettings;

/// A method of computing light, without its settings.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum MethodKind {
    /// The standard (Whitted-style) ray tracer: an image.
    RayTrace,
    /// The path tracer: an image, or the sensors' readings.
    PathTrace,
    /// A radiosity solution shown through the camera: an image.
    RadiosityImage,
    /// Direct light ray-traced, indirect light gathered from radiosity: an image.
    FinalGather,
    /// The sensors' direct light by shadow rays.
    Direct,
    /// The light model: power per surface and at the sensors.
    LightTrace,
    /// Rays from points on every surface: power per surface and at the sensors.
    SurfaceTrace,
    /// A radiosity solver: power per surface and at the sensors, and the solution.
    Radiosity(SolverKind),
}

impl Choice for MethodKind {
    const VALUES: &'static [(Self, &'static str, &'static str)] = &[
        (
            MethodKind::RayTrace,
            "raytrace",
            "The standard (Whitted-style) ray tracer: direct light, ideal reflection and refraction",
        ),
        (
            MethodKind::PathTrace,
            "pathtrace",
            "Unbiased Monte Carlo path tracing with next-event estimation and multiple importance sampling (images in progressive passes)",
        ),
        (
            MethodKind::RadiosityImage,
            "radiosity",
            "Radiosity on the patch mesh, shown flat or smooth (--solver, --shading)",
        ),
        (
            MethodKind::FinalGather,
            "final-gather",
            "Direct light ray-traced with exact shadows at each pixel, indirect light gathered from the radiosity solution (--solver, --gather-rays)",
        ),
        (
            MethodKind::Direct,
            "direct",
            "Standard ray tracer: direct light with shadow rays",
        ),
        (
            MethodKind::LightTrace,
            "light-trace",
            "The light model: photons traced from all lights and the sky, Monte Carlo",
        ),
        (
            MethodKind::SurfaceTrace,
            "surface-trace",
            "Rays from points spread over every surface (--points): lights by shadow rays, sky and reflected light by path tracing; every surface to a share of its own light, small and shaded ones too",
        ),
        (
            MethodKind::Radiosity(SolverKind::Matrix),
            "matrix",
            "Radiosity: full form-factor matrix, Jacobi or Gauss-Seidel",
        ),
        (
            MethodKind::Radiosity(SolverKind::Progressive),
            "progressive",
            "Radiosity: progressive refinement (shoot the patch with the most unshot power)",
        ),
        (
            MethodKind::Radiosity(SolverKind::Hierarchical),
            "hierarchical",
            "Hierarchical radiosity: links between quadtree nodes, refined by an oracle",
        ),
        (
            MethodKind::Radiosity(SolverKind::HierarchicalShooting),
            "hierarchical-shooting",
            "Hierarchical shooting: progressive refinement, each root side's unshot light sent over links refined by an oracle",
        ),
    ];

    fn name(self) -> &'static str {
        match self {
            MethodKind::RayTrace => "raytrace",
            MethodKind::PathTrace => "pathtrace",
            MethodKind::RadiosityImage => "radiosity",
            MethodKind::FinalGather => "final-gather",
            MethodKind::Direct => "direct",
            MethodKind::LightTrace => "light-trace",
            MethodKind::SurfaceTrace => "surface-trace",
            MethodKind::Radiosity(solver) => solver.name(),
        }
    }
}

impl std::fmt::Display for MethodKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl MethodKind {
    /// The methods that render an image through the camera.
    pub const IMAGES: [MethodKind; 4] = [
        MethodKind::RayTrace,
        MethodKind::PathTrace,
        MethodKind::RadiosityImage,
        MethodKind::FinalGather,
    ];

    /// The methods that measure the power on every surface: the light model, the rays from
    /// the surfaces and the radiosity solvers.
    pub const SURFACE_SOLVERS: [MethodKind; 6] = [
        MethodKind::LightTrace,
        MethodKind::SurfaceTrace,
        MethodKind::Radiosity(SolverKind::Matrix),
        MethodKind::Radiosity(SolverKind::Progressive),
        MethodKind::Radiosity(SolverKind::Hierarchical),
        MethodKind::Radiosity(SolverKind::HierarchicalShooting),
    ];

    /// True for Monte Carlo methods, whose figures carry a standard error.
    pub fn is_monte_carlo(self) -> bool {
        !matches!(self, MethodKind::RadiosityImage | MethodKind::Radiosity(_))
    }

    /// True when the method reports the power per surface (not only images or sensors).
    pub fn reports_surfaces(self) -> bool {
        matches!(
            self,
            MethodKind::LightTrace | MethodKind::SurfaceTrace | MethodKind::Radiosity(_)
        )
    }

    /// True when the method counts light reflected between surfaces.
    pub fn counts_reflections(self) -> bool {
        self != MethodKind::Direct
    }

    /// The method with its default settings. [`MethodKind::PathTrace`] gives the path-traced
    /// image (the path-traced sensor readings are a [`SensorTraceSettings`]).
    pub fn with_defaults(self) -> Method {
        match self {
            MethodKind::RayTrace => Method::RayTrace(RayTraceSettings::default()),
            MethodKind::PathTrace => Method::PathTrace(PathTraceSettings::default()),
            MethodKind::RadiosityImage => Method::RadiosityImage(RadiosityImageSettings::default()),
            MethodKind::FinalGather => Method::FinalGather(FinalGatherSettings::default()),
            MethodKind::Direct => Method::SensorTrace(SensorTraceSettings::default()),
            MethodKind::LightTrace => Method::LightTrace(LightTraceSettings::default()),
            MethodKind::SurfaceTrace => Method::SurfaceTrace(SurfaceTraceSettings::default()),
            MethodKind::Radiosity(solver) => Method::Radiosity(RadiositySettings::new(solver)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_has_one_name_and_its_defaults_have_that_kind() {
        for &(kind, name, _) in MethodKind::VALUES {
            assert_eq!(MethodKind::from_name(name), Some(kind));
            assert_eq!(kind.name(), name);
            assert_eq!(kind.with_defaults().kind(), kind, "{name}");
        }
    }
}
