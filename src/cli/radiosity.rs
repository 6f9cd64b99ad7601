//! Radiosity options shared by `strahl solve --solver matrix|progressive` and
//! `strahl render --method radiosity`, and the solve they drive.

use super::{progress, with_threads};
use crate::image::ToneMapping;
use crate::radiosity::solve::{
    Iteration, MatrixSettings, RadiositySystem, ShootingSettings, Solution, SystemOptions,
    export_solution, solve_matrix, solve_progressive,
};
use crate::radiosity::{
    FormFactorMethod, FormFactorOptions, MeshOptions, MeshSize, VisRays, VisibilityOptions,
};
use crate::trace::World;
use anyhow::{Result, bail};
use clap::{Args, ValueEnum};
use std::path::PathBuf;

/// The radiosity solvers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum RadiositySolver {
    /// Full form-factor matrix, Jacobi or Gauss-Seidel sweeps.
    Matrix,
    /// Progressive refinement: shoot the patch with the most unshot power.
    #[default]
    Progressive,
}

/// Options of the radiosity solvers.
#[derive(Debug, Args)]
#[command(next_help_heading = "Radiosity (--solver matrix|progressive)")]
pub struct RadiosityArgs {
    /// Initial patch size: `levels:N` (2ᴺ × 2ᴺ patches per face) or the longest patch edge
    /// in scene units.
    #[arg(long, default_value = "levels:3")]
    pub mesh_size: MeshSize,
    /// Segments around the axis when curved shapes are meshed.
    #[arg(long, default_value_t = 16)]
    pub segments: u32,
    /// Form-factor approximation.
    #[arg(long, value_enum, default_value_t = FormFactorMethod::Analytic)]
    pub form_factor: FormFactorMethod,
    /// Receiver points per axis for the analytic form factor (1 = the centroid).
    #[arg(long, default_value_t = 1)]
    pub receiver_samples: u32,
    /// Visibility rays per patch pair: a count or `adaptive`.
    #[arg(long, default_value = "adaptive")]
    pub vis_rays: VisRays,
    /// Test every visibility ray against the whole scene instead of culling by shafts.
    #[arg(long)]
    pub no_shaft_culling: bool,
    /// Receiver points per axis for the links from point, spot and directional lights.
    #[arg(long, default_value_t = 2)]
    pub link_samples: u32,
    /// matrix: the iteration scheme.
    #[arg(long, value_enum, default_value_t = Iteration::GaussSeidel)]
    pub iteration: Iteration,
    /// Stop when the residual (matrix) or the unshot power (progressive) is at most this
    /// fraction of the emitted power.
    #[arg(long, default_value_t = 1e-4)]
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
    /// Write the solution as a mesh with radiosity vertex colours (.glb, .gltf or .ply).
    #[arg(long)]
    pub export: Option<PathBuf>,
}

impl RadiosityArgs {
    /// The system options, with visibility jitter seeded by `seed`.
    pub fn system_options(&self, seed: u64) -> Result<SystemOptions> {
        if !(self.tolerance.is_finite() && self.tolerance >= 0.0) {
            bail!(
                "--tolerance must be a non-negative number (got {})",
                self.tolerance
            );
        }
        Ok(SystemOptions {
            mesh: MeshOptions {
                segments: self.segments,
                size: self.mesh_size,
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

/// Meshes and solves `world` with `solver` on `threads` threads (0 = one per core), with
/// progress bars unless `quiet`; Ctrl-C keeps the state reached. Writes `--export` with
/// `tone_mapping`.
pub fn solve<'w>(
    world: &'w World,
    args: &RadiosityArgs,
    solver: RadiositySolver,
    seed: u64,
    threads: usize,
    quiet: bool,
    tone_mapping: &ToneMapping,
) -> Result<(RadiositySystem<'w>, Solution)> {
    let options = args.system_options(seed)?;
    let cancel = progress::cancel_flag();
    let (system, solution) = with_threads(threads, || -> Result<_> {
        let system = RadiositySystem::new(world, options)?;
        let solution = match solver {
            RadiositySolver::Matrix => {
                let settings = MatrixSettings {
                    iteration: args.iteration,
                    tolerance: args.tolerance,
                    max_iterations: args.max_iterations,
                };
                let bar = progress::Bar::new("form factors", quiet);
                solve_matrix(&system, &settings, &bar, &cancel)?
            }
            RadiositySolver::Progressive => {
                let settings = ShootingSettings {
                    tolerance: args.tolerance,
                    max_shots: args.max_shots,
                    overshoot: args.overshoot,
                };
                let bar = progress::Bar::new("shooting", quiet);
                solve_progressive(&system, &settings, &bar, &cancel)?
            }
        };
        Ok((system, solution))
    })??;
    if !quiet {
        let last = solution.convergence.last().copied().unwrap_or(0.0);
        eprintln!(
            "{}: {} patches, {} form factors, {} iterations, residual {last:.3e}{}; \
             {:.2} s setup, {:.2} s form factors, {:.2} s iterations",
            solution.solver,
            system.len(),
            system.form_factor_count(),
            solution.iterations(),
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
        if system.unlinked_sky_lights > 0 {
            eprintln!(
                "warning: {} sky light(s) are not linked into the radiosity mesh",
                system.unlinked_sky_lights
            );
        }
    }
    if let Some(path) = &args.export {
        export_solution(&system, &solution, tone_mapping, path)?;
        if !quiet {
            eprintln!("export: {}", path.display());
        }
    }
    Ok((system, solution))
}

/// Prints the convergence history, one line per iteration, to standard error.
pub fn print_convergence(solution: &Solution) {
    let unit = if solution.solver == "progressive" {
        "unshot"
    } else {
        "residual"
    };
    for (k, value) in solution.convergence.iter().enumerate() {
        eprintln!("iteration {:6}  {unit} {value:.6e}", k + 1);
    }
}
