//! `strahl render --method radiosity`: solve radiosity on the patch mesh, then show it
//! through the camera, flat or smooth, with an optional wireframe.

use super::progress;
use super::radiosity::{self, RadiosityArgs, RadiositySolver};
use super::render::RenderArgs;
use crate::image::{Film, ToneMapping};
use crate::radiosity::solve::{DisplaySettings, Shading, render_solution};
use crate::trace::World;
use anyhow::{Context, Result};
use clap::Args;
use std::sync::atomic::AtomicBool;

/// Options of the radiosity display.
#[derive(Debug, Args)]
#[command(next_help_heading = "Radiosity display (--method radiosity)")]
pub struct RadiosityDisplayArgs {
    /// The radiosity solver.
    #[arg(long, value_enum, default_value_t = RadiositySolver::Progressive)]
    pub solver: RadiositySolver,
    /// Flat patches or radiosity interpolated to the vertices.
    #[arg(long, value_enum, default_value_t = Shading::Smooth)]
    pub shading: Shading,
    /// Draw the patch edges.
    #[arg(long)]
    pub wireframe: bool,
    /// Solver options.
    #[command(flatten)]
    pub solve: RadiosityArgs,
}

/// The displayed solution.
pub struct RadiosityImage {
    /// Linear radiance per pixel.
    pub film: Film,
    /// One phrase on the solve.
    pub summary: String,
    /// False when Ctrl-C stopped the solve or the display.
    pub complete: bool,
}

/// Solves and renders `world` at `width × height`; `--spp` camera rays per pixel (rounded up
/// to a square, default 4).
pub fn render(
    args: &RenderArgs,
    world: &World,
    width: u32,
    height: u32,
    bar: &progress::Bar,
    cancel: &AtomicBool,
) -> Result<RadiosityImage> {
    let display = &args.radiosity;
    let tone_mapping = ToneMapping {
        operator: args.tonemap,
        exposure_ev: args.exposure,
    };
    let (system, solution) = radiosity::solve(
        world,
        &display.solve,
        display.solver,
        args.seed,
        args.threads,
        args.quiet,
        &tone_mapping,
    )?;
    let settings = DisplaySettings {
        width,
        height,
        shading: display.shading,
        wireframe: display.wireframe,
        samples_per_axis: (args.spp.unwrap_or(4).max(1) as f64).sqrt().ceil() as u32,
    };
    let camera = &world.scene.camera;
    let film = super::with_threads(args.threads, || {
        render_solution(&system, &solution, camera, &settings, bar, cancel)
    })?
    .context("the camera is degenerate")?;
    Ok(RadiosityImage {
        film,
        summary: format!(
            "{} patches by {} ({} iterations)",
            system.len(),
            solution.solver,
            solution.iterations()
        ),
        complete: !solution.interrupted && !cancel.load(std::sync::atomic::Ordering::Relaxed),
    })
}
