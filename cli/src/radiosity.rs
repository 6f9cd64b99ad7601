//! The solvers a user picks (`--solver`), the radiosity options shared by `strahl solve` and
//! `strahl render --method radiosity`, and the radiosity solve and display they drive.

use super::choice::choice;
use super::limits::{LimitArgs, finite};
use super::{progress, with_threads};
use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use std::path::PathBuf;
use strahl::image::ToneMapping;
use strahl::measure::Film;
use strahl::progress::Cancel;
use strahl::radiosity::solve::hierarchical::{
    HierarchicalSettings, Oracle, RefinePass, solve_hierarchical, solve_hierarchical_shooting,
};
use strahl::radiosity::solve::{
    DisplaySettings, Iteration, LinkDisplay, MatrixSettings, RadiositySystem, Shading,
    ShootingSettings, Solution, SystemOptions, render_solution, solve_matrix, solve_progressive,
};
use strahl::radiosity::{
    FormFactorMethod, FormFactorOptions, MeshOptions, MeshSize, VisRays, VisibilityOptions,
};
use strahl::report::{ExportFormat, export_lit_mesh};
use strahl::world::World;

/// The light solvers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Solver {
    /// The light model: photons traced from all lights and the sky, Monte Carlo.
    LightTrace,
    /// Radiosity: full form-factor matrix, Jacobi or Gauss-Seidel.
    Matrix,
    /// Radiosity: progressive refinement (shoot the patch with the most unshot power).
    Progressive,
    /// Hierarchical radiosity: links between quadtree nodes, refined by an oracle.
    Hierarchical,
    /// Hierarchical shooting: progressive refinement, each root side's unshot light sent
    /// over links refined by an oracle.
    HierarchicalShooting,
}

/// How faces are prepared for linking (seed §6.3.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Linking {
    /// Every face as it is.
    Normal,
    /// Faces that others stand on are split at the standing faces' planes first.
    Asymmetric,
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
    #[arg(long, default_value_t = 16, value_parser = clap::value_parser!(u32).range(3..=1024))]
    pub segments: u32,
    /// Initial linking: `asymmetric` first splits faces at the planes of faces that stand on
    /// them (a box on the floor) and along the outline of faces hovering just in front of them
    /// (a sign on a wall), so no patch lies partly under a touching solid and no light leaks;
    /// `normal` meshes every face as it is.
    #[arg(long, value_enum, default_value_t = Linking::Asymmetric)]
    pub linking: Linking,
    /// Form-factor approximation.
    #[arg(long, value_parser = choice::<FormFactorMethod>(), default_value_t = FormFactorMethod::Analytic)]
    pub form_factor: FormFactorMethod,
    /// Points per axis on the smaller patch of a pair for the analytic form factor (1 = the
    /// centroid).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    pub receiver_samples: u32,
    /// Visibility rays per patch pair: a count or `adaptive`.
    #[arg(long, default_value = "adaptive")]
    pub vis_rays: VisRays,
    /// Test every visibility ray against the whole scene instead of culling by shafts.
    #[arg(long)]
    pub no_shaft_culling: bool,
    /// Receiver points per axis for the links from point (isotropic or Lambertian), spot and
    /// directional lights and the sky.
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..))]
    pub link_samples: u32,
    /// matrix: the iteration scheme.
    #[arg(long, value_parser = choice::<Iteration>(), default_value_t = Iteration::GaussSeidel)]
    pub iteration: Iteration,
    /// Stop when the residual (matrix) or the unshot power (progressive) is at most this
    /// fraction of the emitted power.
    #[arg(long, default_value_t = 1e-4, value_parser = finite::<f64>)]
    pub tolerance: f64,
    /// matrix: most sweeps.
    #[arg(long, default_value_t = 1000)]
    pub max_iterations: u32,
    /// progressive: most shots.
    #[arg(long, default_value_t = 1_000_000)]
    pub max_shots: u64,
    /// progressive: shoot ahead the light a patch will still receive (negative radiosity).
    #[arg(long)]
    pub overshoot: bool,
    /// hierarchical: the oracle that decides where links are refined.
    #[arg(long, value_parser = choice::<Oracle>(), default_value_t = Oracle::Lischinski)]
    pub oracle: Oracle,
    /// hierarchical: largest uncertainty of the power a link brings, as a share of all power emitted in the scene.
    #[arg(long, default_value_t = HierarchicalSettings::default().error, value_parser = finite::<f64>)]
    pub error: f64,
    /// hierarchical: nodes are not split below this fraction of the scene's surface area.
    #[arg(long, default_value_t = HierarchicalSettings::default().min_area, value_parser = finite::<f64>)]
    pub min_area: f64,
    /// hierarchical: which links a refinement pass judges.
    #[arg(long, value_parser = choice::<RefinePass>(), default_value_t = RefinePass::Original)]
    pub refine_pass: RefinePass,
    /// hierarchical: refinement rounds at most.
    #[arg(long, default_value_t = HierarchicalSettings::default().max_rounds)]
    pub max_rounds: u32,
    /// hierarchical: link every pair of root patches instead of grouping them into clusters.
    #[arg(long)]
    pub no_clustering: bool,
    /// Write the solution as a mesh with radiosity vertex colours (.glb, .gltf or .ply).
    #[arg(long)]
    pub export: Option<PathBuf>,
}

/// Options of the radiosity display.
#[derive(Debug, Args)]
#[command(next_help_heading = "Radiosity (--method radiosity|final-gather)")]
pub struct RadiosityDisplayArgs {
    /// The radiosity solver [default: hierarchical, it refines where the light needs it].
    #[arg(long, value_enum)]
    pub solver: Option<Solver>,
    /// Flat patches or radiosity interpolated to the vertices.
    #[arg(long, value_parser = choice::<Shading>(), default_value_t = Shading::Smooth)]
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
    /// The solver asked for, hierarchical when none was.
    pub fn solver(&self) -> Solver {
        self.solver.unwrap_or(Solver::Hierarchical)
    }
}

impl RadiosityArgs {
    /// The system options for `solver`, with visibility jitter seeded by `seed`.
    pub fn system_options(
        &self,
        solver: Solver,
        seed: u64,
        limits: &LimitArgs,
    ) -> Result<SystemOptions> {
        let squared = |n: u32| u64::from(n) * u64::from(n);
        limits.check_samples("--receiver-samples²", squared(self.receiver_samples))?;
        limits.check_samples("--link-samples²", squared(self.link_samples))?;
        if !(self.tolerance.is_finite() && self.tolerance >= 0.0) {
            bail!(
                "--tolerance must be a non-negative number (got {})",
                self.tolerance
            );
        }
        if !(self.error.is_finite() && self.error > 0.0) {
            bail!("--error must be a positive number (got {})", self.error);
        }
        if !(self.min_area.is_finite() && self.min_area > 0.0 && self.min_area < 1.0) {
            bail!(
                "--min-area must lie between 0 and 1 (got {})",
                self.min_area
            );
        }
        Ok(SystemOptions {
            mesh: MeshOptions {
                segments: self.segments,
                size: self.mesh_size.unwrap_or(match solver {
                    Solver::Hierarchical | Solver::HierarchicalShooting => MeshSize::Levels(0),
                    _ => MeshSize::Levels(3),
                }),
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
        })
    }
}

/// How a radiosity run is carried out.
pub struct RunOptions<'a> {
    /// Seed of the visibility jitter.
    pub seed: u64,
    /// Worker threads (0 = one per core).
    pub threads: usize,
    /// No progress bars or summary.
    pub quiet: bool,
    /// Colours of the exported mesh (`--export`).
    pub tone_mapping: &'a ToneMapping,
    /// Bounds on the mesh and the sample counts.
    pub limits: &'a LimitArgs,
}

/// Meshes and solves `world` with the radiosity `solver`, with progress bars unless quiet;
/// Ctrl-C keeps the state reached. Writes `--export`.
pub fn solve<'w>(
    world: &'w World,
    args: &RadiosityArgs,
    solver: Solver,
    run: &RunOptions,
) -> Result<(RadiositySystem<'w>, Solution)> {
    let options = args.system_options(solver, run.seed, run.limits)?;
    let non_diffuse = strahl::radiosity::surface::non_diffuse_materials(&world.scene);
    if !non_diffuse.is_empty() {
        let names: Vec<String> = non_diffuse.iter().map(|n| format!("'{n}'")).collect();
        let (materials, verbs) = if names.len() == 1 {
            ("material", "reflects specularly or transmits")
        } else {
            ("materials", "reflect specularly or transmit")
        };
        eprintln!(
            "warning: radiosity reflects light diffusely only: the light that {materials} {} \
             {verbs} is counted as absorbed (the light model, --solver light-trace, and the \
             path tracer follow it)",
            names.join(", ")
        );
    }
    let cancel = progress::cancel_flag();
    let (system, solution) = with_threads(run.threads, || -> Result<_> {
        let hierarchical = HierarchicalSettings {
            oracle: args.oracle,
            error: args.error,
            min_area: args.min_area,
            refine_pass: args.refine_pass,
            tolerance: args.tolerance,
            max_rounds: args.max_rounds,
            clustering: !args.no_clustering,
        };
        let shooting = ShootingSettings {
            tolerance: args.tolerance,
            max_shots: args.max_shots,
            overshoot: args.overshoot,
        };
        match solver {
            Solver::Hierarchical => {
                let bar = progress::Bar::new("refining", run.quiet);
                return Ok(solve_hierarchical(
                    world,
                    options,
                    &hierarchical,
                    &bar,
                    cancel,
                )?);
            }
            Solver::HierarchicalShooting => {
                let bar = progress::Bar::new("shooting", run.quiet);
                return Ok(solve_hierarchical_shooting(
                    world,
                    options,
                    &hierarchical,
                    &shooting,
                    &bar,
                    cancel,
                )?);
            }
            _ => {}
        }
        let system = RadiositySystem::new(world, options)?;
        let solution = match solver {
            Solver::Matrix => {
                let settings = MatrixSettings {
                    iteration: args.iteration,
                    tolerance: args.tolerance,
                    max_iterations: args.max_iterations,
                };
                let bar = progress::Bar::new("form factors", run.quiet);
                solve_matrix(&system, &settings, &bar, cancel)?
            }
            Solver::Progressive => {
                let bar = progress::Bar::new("shooting", run.quiet);
                solve_progressive(&system, &shooting, &bar, cancel)?
            }
            Solver::Hierarchical | Solver::HierarchicalShooting | Solver::LightTrace => {
                bail!("{solver:?} is not a flat radiosity solver")
            }
        };
        Ok((system, solution))
    })??;
    if !run.quiet {
        print_summary(&system, &solution);
    }
    if let Some(path) = &args.export {
        let textures = &system.world().scene.textures;
        let lightmaps = ExportFormat::from_path(path)?.carries_lightmaps();
        export_lit_mesh(
            &solution.lit_mesh(&system, lightmaps),
            textures,
            run.tone_mapping,
            path,
        )?;
        if !run.quiet {
            eprintln!("export: {}", path.display());
        }
    }
    Ok((system, solution))
}

/// Prints one line on the solve.
fn print_summary(system: &RadiositySystem, solution: &Solution) {
    let last = solution.convergence.last().copied().unwrap_or(0.0);
    eprintln!(
        "{}: {} patches ({} sides), {} form factors, {} iterations, {} {last:.3e}{}; \
         {:.2} s setup, {:.2} s form factors, {:.2} s iterations",
        solution.solver.name(),
        system.leaves.len(),
        system.len(),
        system.form_factor_count(),
        solution.iterations(),
        solution.solver.convergence_measure(),
        if solution.interrupted {
            " (interrupted)"
        } else if !solution.converged {
            " (not converged)"
        } else {
            ""
        },
        solution.seconds.setup,
        solution.seconds.form_factors,
        solution.seconds.iterations,
    );
}

/// Prints the convergence history to standard error: one line per iteration, or for a
/// hierarchical solver one line per round of refinement.
pub fn print_convergence(solution: &Solution) {
    if !solution.rounds.is_empty() {
        eprintln!(
            "{:>5} {:>9} {:>9} {:>7} {:>9} {:>9} {:>8} {:>8} {:>10} {:>7} {:>10} {:>8} {:>8} {:>8} {:>8}",
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
            "peak MB"
        );
        for (k, r) in solution.rounds.iter().enumerate() {
            eprintln!(
                "{:>5} {:>9} {:>9} {:>7} {:>9} {:>9} {:>8} {:>8} {:>10} {:>7} {:>10.3e} {:>8.3} {:>8.3} {:>8.3} {:>8}",
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
                r.seconds_gather + r.seconds_push_pull,
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

/// A radiosity solution shown through the camera.
pub struct RadiosityImage {
    /// Linear radiance per pixel.
    pub film: Film,
    /// One phrase on the solve.
    pub summary: String,
    /// False when Ctrl-C stopped the solve or the display.
    pub complete: bool,
}

/// Solves `world` as `display` asks and renders the solution through the scene camera at
/// `width × height` with `samples_per_pixel` camera rays (rounded up to a square).
pub fn render(
    world: &World,
    display: &RadiosityDisplayArgs,
    run: &RunOptions,
    (width, height): (u32, u32),
    samples_per_pixel: u32,
    bar: &progress::Bar,
    cancel: &Cancel,
) -> Result<RadiosityImage> {
    if display.solver() == Solver::LightTrace {
        bail!("--method radiosity needs --solver matrix, progressive or hierarchical");
    }
    let links = match display.links.as_deref() {
        None => LinkDisplay::None,
        Some(_) if display.solver() != Solver::Hierarchical => {
            bail!("--links needs --solver hierarchical (the other solvers keep no links)")
        }
        Some("") => LinkDisplay::All,
        Some(name) => {
            let objects = &world.scene.objects;
            let index = objects
                .iter()
                .position(|o| o.name.as_deref() == Some(name))
                .with_context(|| {
                    let names: Vec<&str> =
                        objects.iter().filter_map(|o| o.name.as_deref()).collect();
                    format!(
                        "--links: no object named '{name}' (objects: {})",
                        names.join(", ")
                    )
                })?;
            LinkDisplay::Object(index as u32)
        }
    };
    let (system, solution) = solve(world, &display.solve, display.solver(), run)?;
    let settings = DisplaySettings {
        links,
        width,
        height,
        shading: display.shading,
        wireframe: display.wireframe,
        samples_per_axis: (samples_per_pixel.max(1) as f64).sqrt().ceil() as u32,
    };
    let camera = &world.scene.camera;
    let film = with_threads(run.threads, || {
        render_solution(&system, &solution, camera, &settings, bar, cancel)
    })?
    .context("the camera is degenerate")?;
    Ok(RadiosityImage {
        film,
        summary: format!(
            "{} patches by {} ({} iterations)",
            system.leaves.len(),
            solution.solver.name(),
            solution.iterations()
        ),
        complete: !solution.interrupted && !cancel.is_requested(),
    })
}
