//! The radiosity options shared by `strahl solve` and `strahl render --method
//! radiosity|final-gather`, turned into the library's [`RadiositySettings`], and what the
//! command line prints and writes about a solve.

use super::choice::{choice, choice_among};
use super::limits::{LimitArgs, finite};
use anyhow::{Result, bail};
use clap::{Args, ValueEnum};
use std::path::{Path, PathBuf};
use strahl::image::ToneMapping;
use strahl::method::{
    FormFactorMethod, FormFactorOptions, HierarchicalSettings, Iteration, LinkSelection,
    MatrixSettings, MeshOptions, MeshSize, MethodError, MethodKind, Oracle, RadiositySettings,
    RefinePass, Shading, ShootingSettings, Solution, SolvedRadiosity, SolverKind, SurfaceGather,
    SystemOptions, VisRays, VisibilityOptions,
};
use strahl::report::{ExportFormat, export_lit_mesh};
use strahl::scene::Scene;

/// How faces are prepared for linking (seed §6.3.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Linking {
    /// Every face as it is.
    Normal,
    /// Faces that others stand on are split at the standing faces' planes first.
    Asymmetric,
}

/// The final gather at the reported surfaces (`strahl solve` and `strahl validate`).
#[derive(Debug, Args)]
pub struct SurfaceGatherArgs {
    /// radiosity: once solved, measure the light of the reported surfaces that receive little
    /// of it (see --gather-below) anew, until each one's standard error is at most this share
    /// of it: direct light by shadow rays, indirect by gather rays that take the solution's
    /// light two reflections away. The report then gives their standard errors. Dim surfaces
    /// the solution gets a few per cent wrong come out right (0: off, the solution's own
    /// values; 10⁻⁴ up to 1) [default: 0.01].
    #[arg(long, value_parser = finite::<f64>)]
    pub surface_gather: Option<f64>,
    /// radiosity: the final gather measures the surfaces that receive less than this share of
    /// the light all surfaces receive and a quarter or more of theirs otherwise than from the
    /// scene's lights and the sky (reflected, or straight from emitting surfaces, by the
    /// solution), and at least 10⁻⁴ of the light unless they scatter nothing (a black
    /// measuring patch); the others, which the solution gets right within a fraction of a per
    /// cent, or hold too little light to matter (a field's leaves), keep its values (1: every
    /// surface; above 0, at most 1) [default: 0.02].
    #[arg(long, value_parser = finite::<f64>)]
    pub gather_below: Option<f64>,
}

impl SurfaceGatherArgs {
    /// Whether either option was given.
    pub fn given(&self) -> bool {
        self.surface_gather.is_some() || self.gather_below.is_some()
    }

    /// The gather these options ask for (the library's defaults where not given).
    pub fn settings(&self) -> SurfaceGather {
        SurfaceGather {
            error: self.surface_gather.unwrap_or(SurfaceGather::DEFAULT.error),
            below_share: self
                .gather_below
                .unwrap_or(SurfaceGather::DEFAULT.below_share),
        }
    }
}

/// Options of the radiosity solvers.
#[derive(Debug, Args)]
#[command(
    next_help_heading = "Radiosity (--solver matrix|progressive|hierarchical|hierarchical-shooting)"
)]
pub struct RadiosityArgs {
    /// Initial patch size: `levels:N` (2ᴺ × 2ᴺ patches per face; the facets of a curved
    /// shape get patches of 1/2ᴺ of the shape's size) or the longest patch edge in scene
    /// units [default: levels:3; hierarchical: levels:0, it refines by itself].
    #[arg(long)]
    pub mesh_size: Option<MeshSize>,
    /// Segments around the axis when curved shapes are meshed.
    #[arg(long, default_value_t = MeshOptions::default().segments, value_parser = clap::value_parser!(u32).range(3..=1024))]
    pub segments: u32,
    /// Initial linking: `asymmetric` first splits faces at the planes of faces that stand on
    /// them (a box on the floor) and along the outline of faces hovering just in front of them
    /// (a sign on a wall), so no patch lies partly under a touching solid and no light leaks;
    /// `normal` meshes every face as it is.
    #[arg(long, value_enum, default_value_t = Linking::Asymmetric)]
    pub linking: Linking,
    /// matrix, progressive: form-factor approximation (the hierarchical solvers integrate the
    /// exact point form factor over Gauss points of the smaller patch).
    #[arg(long, value_parser = choice::<FormFactorMethod>(), default_value_t = FormFactorOptions::default().method)]
    pub form_factor: FormFactorMethod,
    /// matrix, progressive: points per axis on the smaller patch of a pair for the analytic
    /// form factor (1 = the centroid).
    #[arg(long, default_value_t = FormFactorOptions::default().receiver_samples, value_parser = clap::value_parser!(u32).range(1..))]
    pub receiver_samples: u32,
    /// matrix, progressive: visibility rays per patch pair, a count or `adaptive` (the
    /// hierarchical solvers choose their rays per link themselves).
    #[arg(long, default_value = "adaptive")]
    pub vis_rays: VisRays,
    /// Test every visibility ray against the whole scene instead of culling by shafts.
    #[arg(long)]
    pub no_shaft_culling: bool,
    /// Receiver points per axis for the links from point (isotropic or Lambertian), spot and
    /// directional lights and the sky.
    #[arg(long, default_value_t = SystemOptions::default().link_samples, value_parser = clap::value_parser!(u32).range(1..))]
    pub link_samples: u32,
    /// A periodic scene (a plot repeated in x and z): how far around the plot its copies are
    /// solved with it, scene units [default: 0; the light the field beyond the margin reflects
    /// comes by rays]
    #[arg(long, value_parser = finite::<f32>)]
    pub periodic_margin: Option<f32>,
    /// matrix: the iteration scheme.
    #[arg(long, value_parser = choice::<Iteration>(), default_value_t = MatrixSettings::default().iteration)]
    pub iteration: Iteration,
    /// Stop when the residual (matrix) or the unshot power (progressive) is at most this
    /// fraction of the emitted power (10⁻¹² up to 1, not included).
    #[arg(long, default_value_t = MatrixSettings::default().tolerance, value_parser = finite::<f64>)]
    pub tolerance: f64,
    /// matrix: most sweeps.
    #[arg(long, default_value_t = MatrixSettings::default().max_iterations)]
    pub max_iterations: u32,
    /// progressive: most shots.
    #[arg(long, default_value_t = ShootingSettings::default().max_shots)]
    pub max_shots: u64,
    /// progressive: shoot ahead the light a patch will still receive (negative radiosity).
    #[arg(long)]
    pub overshoot: bool,
    /// hierarchical: the oracle that decides where links are refined.
    #[arg(long, value_parser = choice::<Oracle>(), default_value_t = HierarchicalSettings::default().oracle)]
    pub oracle: Oracle,
    /// hierarchical: largest uncertainty of the power a link brings, as a share of all power emitted in the scene (10⁻⁸ to 1).
    #[arg(long, default_value_t = HierarchicalSettings::default().error, value_parser = finite::<f64>)]
    pub error: f64,
    /// hierarchical: also hold every reported surface (object, or face with per_face) to about this share of its own power, weighing each link by the importance of its light to every surface (0: off; a measuring patch, a surface that scatters and emits nothing, is held to 1 % regardless). Dim faces and small leaves then come out right, at many times the links (0.003 takes the built-in Cornell box with per-face reports from 0.17 s to 2.5 s on two threads, its worst face from +4.8 % to +1.4 %); 0, or 10⁻⁴ up to 1.
    #[arg(long, default_value_t = HierarchicalSettings::default().surface_error, value_parser = finite::<f64>)]
    pub surface_error: f64,
    /// hierarchical: nodes are not split below this fraction of the scene's surface area (10⁻⁸ up to 1).
    #[arg(long, default_value_t = HierarchicalSettings::default().min_area, value_parser = finite::<f64>)]
    pub min_area: f64,
    /// hierarchical: which links a refinement pass judges.
    #[arg(long, value_parser = choice::<RefinePass>(), default_value_t = HierarchicalSettings::default().refine_pass)]
    pub refine_pass: RefinePass,
    /// hierarchical: refinement rounds at most.
    #[arg(long, default_value_t = HierarchicalSettings::default().max_rounds)]
    pub max_rounds: u32,
    /// hierarchical: link every pair of root patches instead of grouping them into clusters.
    #[arg(long)]
    pub no_clustering: bool,
    /// hierarchical: scenes of at least this many root patches carry the light between clusters too close for the cluster transport by rays cast from every root patch, instead of by links split down to pairs of root patches (0: every scene).
    #[arg(long, default_value_t = HierarchicalSettings::default().near_rays_from)]
    pub near_rays_from: usize,
    /// hierarchical: leave out the final gather over the emitters' pieces (links whose emitter was split keep gathering its mean radiosity, or its quarters').
    #[arg(long)]
    pub no_fine_gather: bool,
    /// Write the solution as a mesh with radiosity vertex colours (.glb, .gltf or .ply).
    #[arg(long)]
    pub export: Option<PathBuf>,
}

/// Options of the radiosity display.
#[derive(Debug, Args)]
#[command(next_help_heading = "Radiosity (--method radiosity|final-gather)")]
pub struct RadiosityDisplayArgs {
    /// The radiosity solver [default: hierarchical, it refines where the light needs it].
    #[arg(long, value_parser = choice_among(MethodKind::SURFACE_SOLVERS))]
    pub solver: Option<MethodKind>,
    /// Flat patches or radiosity interpolated to the vertices.
    #[arg(long, value_parser = choice::<Shading>(), default_value_t = Shading::default())]
    pub shading: Shading,
    /// Draw the patch edges.
    #[arg(long)]
    pub wireframe: bool,
    /// hierarchical: draw the links of the solution as lines, all of them or (`--links OBJECT`)
    /// those that receive on or emit from the named object.
    #[arg(long, value_name = "OBJECT", num_args = 0..=1, default_missing_value = "")]
    pub links: Option<String>,
    /// Solver options.
    #[command(flatten)]
    pub solve: RadiosityArgs,
}

impl RadiosityDisplayArgs {
    /// The solve for `--method NAME` (`radiosity` or `final-gather`): `--solver` (hierarchical
    /// when none is given) with the solver options, seeded by `seed`.
    pub fn settings(
        &self,
        method: &str,
        seed: u64,
        limits: &LimitArgs,
    ) -> Result<RadiositySettings> {
        let solver = match self.solver {
            None => SolverKind::Hierarchical,
            Some(MethodKind::Radiosity(solver)) => solver,
            Some(_) => {
                bail!("--method {method} needs --solver matrix, progressive or hierarchical")
            }
        };
        // An image makes no report for the final gather at the surfaces to measure.
        Ok(self
            .solve
            .settings(solver, seed, limits)?
            .without_surface_gather())
    }

    /// The links `--links` asks to draw.
    pub fn links(&self) -> LinkSelection {
        match self.links.as_deref() {
            None => LinkSelection::None,
            Some("") => LinkSelection::All,
            Some(name) => LinkSelection::Object(name.to_string()),
        }
    }
}

impl RadiosityArgs {
    /// The settings of `solver` these options give, with visibility jitter seeded by `seed`,
    /// checked.
    pub fn settings(
        &self,
        solver: SolverKind,
        seed: u64,
        limits: &LimitArgs,
    ) -> Result<RadiositySettings> {
        let squared = |n: u32| u64::from(n) * u64::from(n);
        limits.check_samples("--receiver-samples²", squared(self.receiver_samples))?;
        limits.check_samples("--link-samples²", squared(self.link_samples))?;
        if let VisRays::Fixed(rays) = self.vis_rays {
            limits.check_samples("--vis-rays", rays.into())?;
        }
        let mut settings = RadiositySettings::new(solver).with_tolerance(self.tolerance);
        settings.system = SystemOptions {
            mesh: MeshOptions {
                segments: self.segments,
                size: self.mesh_size.unwrap_or(solver.default_mesh_size()),
                contact_splits: self.linking == Linking::Asymmetric,
                max_patches: usize::try_from(limits.max_patches).unwrap_or(usize::MAX),
            },
            form_factor: FormFactorOptions {
                method: self.form_factor,
                receiver_samples: self.receiver_samples,
                ..FormFactorOptions::default()
            },
            visibility: VisibilityOptions {
                rays: self.vis_rays,
                shaft_culling: !self.no_shaft_culling,
                seed,
            },
            link_samples: self.link_samples,
            periodic_margin: self.periodic_margin,
        };
        settings.matrix.iteration = self.iteration;
        settings.matrix.max_iterations = self.max_iterations;
        settings.shooting.max_shots = self.max_shots;
        settings.shooting.overshoot = self.overshoot;
        settings.hierarchical = HierarchicalSettings {
            oracle: self.oracle,
            error: self.error,
            surface_error: self.surface_error,
            min_area: self.min_area,
            refine_pass: self.refine_pass,
            tolerance: self.tolerance,
            max_rounds: self.max_rounds,
            clustering: !self.no_clustering,
            near_rays_from: self.near_rays_from,
            fine_gather: !self.no_fine_gather,
            // The method keeps them when the links are shown.
            link_segments: false,
        };
        settings.check().map_err(|e| method_error(e.into()))?;
        Ok(settings)
    }
}

/// A library error as the command line words it: settings by their flags.
pub fn method_error(e: MethodError) -> anyhow::Error {
    match e {
        MethodError::Setting(_) | MethodError::NoSuchObject { .. } => anyhow::anyhow!("--{e}"),
        e => e.into(),
    }
}

/// Warns that `method` (radiosity, or the surface tracer, which solves what radiosity
/// solves) counts the light that non-diffuse materials of `scene` reflect specularly or
/// transmit as absorbed.
pub fn warn_non_diffuse(scene: &Scene, method: MethodKind) {
    let non_diffuse = strahl::method::non_diffuse_materials(scene);
    if non_diffuse.is_empty() {
        return;
    }
    let names: Vec<String> = non_diffuse.iter().map(|n| format!("'{n}'")).collect();
    let (materials, verbs) = if names.len() == 1 {
        ("material", "reflects specularly or transmits")
    } else {
        ("materials", "reflect specularly or transmit")
    };
    eprintln!(
        "warning: {} reflects light diffusely only: the light that {materials} {} \
         {verbs} is counted as absorbed (the light model, --solver light-trace, and the \
         path tracer follow it)",
        if method == MethodKind::SurfaceTrace {
            "surface-trace"
        } else {
            "radiosity"
        },
        names.join(", ")
    );
}

/// The share of the light arriving on all surfaces that, counted twice on overlapping faces,
/// is worth a warning (the conference room counts 0.02 % twice on 51,279 small faces lying
/// on others, the Šibenik cathedral 0.5 %).
const COUNTED_TWICE_WARNING: f64 = 1e-3;

/// Prints one line on the solve unless `quiet`, and writes `export` (the solution as a lit
/// mesh) when given.
pub fn finish_solve(
    solved: &SolvedRadiosity,
    export: Option<&Path>,
    tone_mapping: &ToneMapping,
    quiet: bool,
) -> Result<()> {
    if !quiet {
        eprintln!("{}: {}", solved.solution.solver_name, solved.summary());
    }
    let twice = solved.solution.light_counted_twice(&solved.system);
    if twice.power > COUNTED_TWICE_WARNING * twice.received {
        eprintln!(
            "warning: {} faces lie on other faces in their plane and are lit on the same side \
             ({:.4} units² overlapped): the radiosity solvers light each of them where a ray \
             meets only one, {:.2} % of the light arriving is counted twice; remove the \
             doubled faces",
            twice.patches,
            twice.area,
            100.0 * twice.power / twice.received
        );
    }
    if let Some(path) = export {
        let lightmaps = ExportFormat::from_path(path)?.carries_lightmaps();
        export_lit_mesh(
            &solved.lit_mesh(lightmaps),
            &solved.world().scene.textures,
            tone_mapping,
            path,
        )?;
        if !quiet {
            eprintln!("export: {}", path.display());
        }
    }
    Ok(())
}

/// Prints the convergence history to standard error: one line per iteration, or for a
/// hierarchical solver one line per round of refinement, with the seconds of its phases
/// (linking, refinement decisions and gathers run on all threads; the push-pull down and up
/// the quadtrees runs on one).
pub fn print_convergence(solution: &Solution) {
    if !solution.rounds.is_empty() {
        eprintln!(
            "{:>5} {:>9} {:>9} {:>7} {:>9} {:>9} {:>8} {:>8} {:>10} {:>7} {:>10} {:>8} {:>8} {:>8} {:>9} {:>8}",
            "round",
            "created",
            "refined",
            "looked",
            "links",
            "clusters",
            "blocked",
            "leaves",
            "rays",
            "gathers",
            "change",
            "link s",
            "refine s",
            "gather s",
            "serial s",
            "peak MB"
        );
        for (k, r) in solution.rounds.iter().enumerate() {
            eprintln!(
                "{:>5} {:>9} {:>9} {:>7} {:>9} {:>9} {:>8} {:>8} {:>10} {:>7} {:>10.3e} {:>8.3} {:>8.3} {:>8.3} {:>9.3} {:>8}",
                k + 1,
                r.links_created,
                r.links_refined,
                r.links_looked,
                r.links,
                r.cluster_links,
                r.blocked_links,
                r.leaves,
                r.rays,
                r.gathers,
                r.residual,
                r.seconds_linking,
                r.seconds_refine,
                r.seconds_gather,
                r.seconds_push_pull,
                r.peak_memory_bytes
                    .map_or("?".to_string(), |b| format!("{:.1}", b as f64 / 1e6))
            );
        }
        return;
    }
    let measure = solution.solver.convergence_measure();
    for (k, value) in solution.convergence.iter().enumerate() {
        eprintln!("iteration {:6}  {measure} {value:.6e}", k + 1);
    }
}
