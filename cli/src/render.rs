//! `strahl render`: render an image of a scene.

use super::choice::choice;
use super::limits::{LimitArgs, finite};
use super::radiosity::{self, RadiosityDisplayArgs, RunOptions, Solver};
use super::tone::ToneArgs;
use super::{progress, source, with_threads};
use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use strahl::accel::AccelKind;
use strahl::color::Rgb;
use strahl::final_gather::FinalGather;
use strahl::image::{self, ToneMap, ToneMapping};
use strahl::measure::Film;
use strahl::progress::Cancel;
use strahl::radiosity::solve::RadiosityLookup;
use strahl::sampling::SequenceKind;
use strahl::trace::{
    AntialiasMode, Integrator, PathTracer, ProgressiveSettings, RenderOutput, RenderSettings,
    ShadowMode, StandardRayTracer, render, render_progressive,
};
use strahl::world::World;

/// Rendering methods.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Method {
    /// The standard (Whitted-style) ray tracer: direct light, ideal reflection and refraction.
    Raytrace,
    /// Unbiased Monte Carlo path tracing with next-event estimation and multiple importance
    /// sampling, rendered in progressive passes.
    Pathtrace,
    /// Radiosity on the patch mesh, shown flat or smooth (`--solver`, `--shading`).
    Radiosity,
    /// Direct light ray-traced with exact shadows at each pixel, indirect light gathered from
    /// the radiosity solution (`--solver`, `--gather-rays`).
    FinalGather,
}

/// Arguments of `strahl render`.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// Scene: a built-in name (see `strahl scenes`), a .toml scene file or a mesh file.
    pub scene: String,
    /// Output image; the extension chooses the format (.png, .exr, .pfm).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Rendering method.
    #[arg(long, value_enum, default_value_t = Method::Raytrace)]
    pub method: Method,
    /// Image width in pixels (default: the scene camera's).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    pub width: Option<u32>,
    /// Image height in pixels (default: the scene camera's).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    pub height: Option<u32>,
    /// Samples per pixel: camera samples for stochastic antialiasing with raytrace (rounded up
    /// to a square; default 4), paths per pixel with pathtrace (default 64).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    pub spp: Option<u32>,
    /// raytrace: reflection/refraction recursion depth (0 turns them off; default 6).
    /// pathtrace: maximum scattering events per path (1 = direct light only; default
    /// unbounded, paths ended by Russian roulette from bounce 5).
    #[arg(long)]
    pub depth: Option<u32>,
    /// pathtrace: paths branching from the first hit of each camera ray.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    pub first_hit_paths: Option<u32>,
    /// pathtrace: stop after the last pass of samples that fits in this many seconds.
    #[arg(long, value_parser = finite::<f64>)]
    pub time_limit: Option<f64>,
    /// raytrace, final-gather: shadow rays per area light and for the sky at every shading
    /// point.
    #[arg(long, default_value_t = 16, value_parser = clap::value_parser!(u32).range(1..))]
    pub light_samples: u32,
    /// final-gather: rays per camera sample that gather the solution's reflected light
    /// (rounded up to a square).
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(1..))]
    pub gather_rays: u32,
    /// raytrace: antialiasing method (pathtrace always jitters its samples over the pixel).
    #[arg(long, value_parser = choice::<AntialiasMode>(), default_value_t = AntialiasMode::Stochastic)]
    pub aa: AntialiasMode,
    /// Colour difference that makes adaptive antialiasing subdivide.
    #[arg(long, default_value_t = 0.05, value_parser = finite::<f32>)]
    pub aa_threshold: f32,
    /// Write an image of how often adaptive antialiasing subdivided each pixel.
    #[arg(long)]
    pub aa_map: Option<PathBuf>,
    /// Acceleration structure.
    #[arg(long, value_parser = choice::<AccelKind>(), default_value_t = AccelKind::Bvh)]
    pub accel: AccelKind,
    /// Shadows from all objects, or only self-shadowing by facing.
    #[arg(long, value_parser = choice::<ShadowMode>(), default_value_t = ShadowMode::On)]
    pub shadows: ShadowMode,
    /// Tone mapping.
    #[command(flatten)]
    pub tone: ToneArgs,
    /// Worker threads (0 = one per core).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Seed of all random numbers (same seed, same image, for any thread count).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// No progress bar or summary.
    #[arg(short, long)]
    pub quiet: bool,
    /// Radiosity options.
    #[command(flatten)]
    pub radiosity: RadiosityDisplayArgs,
    /// Bounds on the work asked for.
    #[command(flatten)]
    pub limits: LimitArgs,
}

impl RenderArgs {
    /// Checks the arguments that need no scene: output formats, the method's options, the
    /// sample counts, an explicit image size and the radiosity options against their limits.
    pub fn check(&self) -> Result<()> {
        image::FileFormat::from_path(&self.output)?;
        if let Some(map) = &self.aa_map {
            image::FileFormat::from_path(map)?;
            if self.aa != AntialiasMode::Adaptive {
                bail!("--aa-map needs --aa adaptive");
            }
        }
        if let (Some(solver), Method::Raytrace | Method::Pathtrace) =
            (self.radiosity.solver, self.method)
        {
            bail!(
                "--solver {} applies to --method radiosity and final-gather only, not {}",
                solver
                    .to_possible_value()
                    .map_or("?".into(), |v| v.get_name().to_string()),
                self.method
                    .to_possible_value()
                    .map_or("?".into(), |v| v.get_name().to_string())
            );
        }
        for (flag, count) in [
            ("--spp", self.spp),
            ("--first-hit-paths", self.first_hit_paths),
            ("--light-samples", Some(self.light_samples)),
            ("--gather-rays", Some(self.gather_rays)),
        ] {
            self.limits
                .check_samples(flag, count.map_or(0, u64::from))?;
        }
        if let (Some(width), Some(height)) = (self.width, self.height) {
            self.limits.check_image(width, height)?;
        }
        if let Method::Radiosity | Method::FinalGather = self.method {
            self.radiosity.solve.system_options(
                self.radiosity.solver(),
                self.seed,
                &self.limits,
            )?;
        }
        Ok(())
    }
}

/// Runs `strahl render`.
pub fn run(args: &RenderArgs) -> Result<()> {
    args.check()?;
    let scene = source::load(&args.scene, &args.limits.load_options())?;
    if scene.objects.is_empty() && scene.lights.is_empty() {
        bail!(
            "'{}' is empty (no objects, no lights): there is nothing to render",
            args.scene
        );
    }
    if !scene.has_light() && !args.quiet {
        eprintln!(
            "warning: '{}' has no light (no light source, no sky, no emitting material): the image will be black",
            args.scene
        );
    }
    let width = args.width.unwrap_or(scene.camera.width);
    let height = args.height.unwrap_or(scene.camera.height);
    if width == 0 || height == 0 {
        bail!("the image size must be at least 1×1 (got {width}×{height})");
    }
    args.limits.check_image(width, height)?;
    let world = World::new(scene, args.accel).with_context(|| format!("scene '{}'", args.scene))?;
    if let Some(warning) = world.scale_warning().filter(|_| !args.quiet) {
        eprintln!("warning: {warning}");
    }
    if let Some(object) = world.enclosing_object(world.scene.camera.position)
        && !args.quiet
    {
        eprintln!(
            "warning: the camera is inside '{}' (every view ray meets its inside): the image \
             shows it from within",
            world.scene.object_name(object as usize)
        );
    }
    if world
        .scene
        .camera
        .with_resolution(width, height)
        .rays()
        .is_none()
    {
        bail!(
            "the camera of '{}' is degenerate (look_at equals position, up parallel to the view, or fov outside 0–180°)",
            args.scene
        );
    }
    let cancel = progress::cancel_flag();
    let bar = progress::Bar::new("rendering", args.quiet);
    let start = Instant::now();
    let tone_mapping = args.tone.mapping();
    let output = match args.method {
        Method::Raytrace => render_standard(args, &world, width, height, &bar, cancel)?,
        Method::Pathtrace => render_path_traced(args, &world, width, height, &bar, cancel)?,
        Method::FinalGather => {
            let run = RunOptions {
                seed: args.seed,
                threads: args.threads,
                quiet: args.quiet,
                tone_mapping: &tone_mapping,
                limits: &args.limits,
            };
            render_final_gather(args, &world, width, height, &run, &bar, cancel)?
        }
        Method::Radiosity => {
            let run = RunOptions {
                seed: args.seed,
                threads: args.threads,
                quiet: args.quiet,
                tone_mapping: &tone_mapping,
                limits: &args.limits,
            };
            let spp = args.spp.unwrap_or(4);
            let out = radiosity::render(
                &world,
                &args.radiosity,
                &run,
                (width, height),
                spp,
                &bar,
                cancel,
            )?;
            Rendered {
                film: out.film,
                subdivisions: Vec::new(),
                summary: out.summary,
                complete: out.complete,
            }
        }
    };
    let seconds = start.elapsed().as_secs_f64();
    image::save(&output.film, &args.output, &tone_mapping)?;
    if let Some(map) = &args.aa_map {
        save_subdivision_map(&output.subdivisions, width, height, map)?;
    }
    if !args.quiet {
        eprintln!(
            "{} {}×{} in {seconds:.2} s, {}{}",
            args.output.display(),
            width,
            height,
            output.summary,
            if output.complete {
                ""
            } else {
                " (stopped early: partial image)"
            }
        );
    }
    Ok(())
}

/// What either rendering method produced.
struct Rendered {
    film: Film,
    /// Adaptive antialiasing subdivisions per pixel (raytrace only).
    subdivisions: Vec<u32>,
    /// One phrase on the samples taken.
    summary: String,
    complete: bool,
}

/// Renders with the standard ray tracer.
fn render_standard(
    args: &RenderArgs,
    world: &World,
    width: u32,
    height: u32,
    bar: &progress::Bar,
    cancel: &Cancel,
) -> Result<Rendered> {
    if args.first_hit_paths.is_some() || args.time_limit.is_some() {
        bail!("--first-hit-paths and --time-limit need --method pathtrace");
    }
    let integrator = StandardRayTracer {
        max_depth: args.depth.unwrap_or(6),
        light_samples: args.light_samples,
        shadows: args.shadows,
    };
    let output = render_tiles(args, world, width, height, &integrator, bar, cancel)?;
    Ok(Rendered {
        film: output.film,
        subdivisions: output.subdivisions,
        summary: format!("{} camera samples", output.samples_traced),
        complete: output.complete,
    })
}

/// Renders `integrator` in tiles at `width × height` with the antialiasing, samples and seed
/// of `args`.
fn render_tiles(
    args: &RenderArgs,
    world: &World,
    width: u32,
    height: u32,
    integrator: &dyn Integrator,
    bar: &progress::Bar,
    cancel: &Cancel,
) -> Result<RenderOutput> {
    let settings = RenderSettings {
        width,
        height,
        antialias: args.aa,
        samples_per_pixel: args.spp.unwrap_or(4),
        adaptive_threshold: args.aa_threshold,
        seed: args.seed,
        sequence: SequenceKind::Random,
    };
    with_threads(args.threads, || {
        render(world, integrator, &settings, bar, cancel)
    })?
    .context("the camera is degenerate")
}

/// Solves the scene by radiosity and renders it by final gathering.
fn render_final_gather(
    args: &RenderArgs,
    world: &World,
    width: u32,
    height: u32,
    run: &RunOptions,
    bar: &progress::Bar,
    cancel: &Cancel,
) -> Result<Rendered> {
    if args.gather_rays == 0 {
        bail!("--gather-rays must be at least 1");
    }
    if args.radiosity.solver() == Solver::LightTrace {
        bail!("--method final-gather needs --solver matrix, progressive or hierarchical");
    }
    let (system, solution) =
        radiosity::solve(world, &args.radiosity.solve, args.radiosity.solver(), run)?;
    let integrator = FinalGather {
        reflected: RadiosityLookup::new(
            &system,
            solution.reflected_radiosity(&system),
            args.radiosity.shading,
        )
        .with_texture_detail(solution.display_irradiance(), false),
        light_samples: args.light_samples,
        gather_rays: args.gather_rays,
    };
    let output = render_tiles(args, world, width, height, &integrator, bar, cancel)?;
    Ok(Rendered {
        film: output.film,
        subdivisions: output.subdivisions,
        summary: format!(
            "{} camera samples, indirect light from {} patches by {}",
            output.samples_traced,
            system.leaves.len(),
            solution.solver.name()
        ),
        complete: output.complete && !solution.interrupted,
    })
}

/// Renders with the path tracer in progressive passes.
fn render_path_traced(
    args: &RenderArgs,
    world: &World,
    width: u32,
    height: u32,
    bar: &progress::Bar,
    cancel: &Cancel,
) -> Result<Rendered> {
    if args.aa != AntialiasMode::Stochastic || args.aa_map.is_some() {
        bail!("--aa and --aa-map apply to --method raytrace only");
    }
    if args.shadows != ShadowMode::On {
        bail!("--shadows off applies to --method raytrace only");
    }
    let time_limit = match args.time_limit {
        Some(s) if s.is_finite() && s > 0.0 => Some(Duration::from_secs_f64(s)),
        Some(s) => bail!("--time-limit must be a positive number of seconds (got {s})"),
        None => None,
    };
    let spp = args.spp.unwrap_or(64);
    if spp == 0 {
        bail!("--spp must be at least 1 for pathtrace");
    }
    let first_hit_paths = args.first_hit_paths.unwrap_or(1);
    if first_hit_paths == 0 {
        bail!("--first-hit-paths must be at least 1");
    }
    let integrator = PathTracer::new(world, args.depth.unwrap_or(u32::MAX), first_hit_paths);
    let settings = ProgressiveSettings {
        width,
        height,
        samples_per_pixel: spp,
        seed: args.seed,
        time_limit,
    };
    let output = with_threads(args.threads, || {
        render_progressive(world, &integrator, &settings, bar, cancel)
    })?
    .context("the camera is degenerate")?;
    Ok(Rendered {
        film: output.film,
        subdivisions: Vec::new(),
        summary: format!(
            "{} paths per pixel in {} passes",
            output.samples_per_pixel, output.passes
        ),
        complete: output.complete,
    })
}

/// Writes the subdivision counts as a grey image: black = never subdivided, white = the
/// most-subdivided pixel.
fn save_subdivision_map(counts: &[u32], width: u32, height: u32, path: &Path) -> Result<()> {
    let max = counts.iter().copied().max().unwrap_or(0).max(1) as f32;
    let pixels = counts.iter().map(|&c| Rgb::splat(c as f32 / max)).collect();
    let film = Film::from_pixels(width, height, pixels).context("subdivision map size")?;
    let linear = ToneMapping {
        operator: ToneMap::Linear,
        exposure_ev: 0.0,
    };
    image::save(&film, path, &linear)?;
    Ok(())
}
