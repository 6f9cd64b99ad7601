//! `strahl solve`: compute the light on every object of a scene and report it per object
//! (or per face) as JSON or CSV.

use super::batch_file;
use super::choice::{choice, choice_among};
use super::limits::LimitArgs;
use super::merge::PartialFile;
use super::radiosity::{self, RadiosityArgs, SurfaceGatherArgs, method_error, print_convergence};
use super::run_measuring;
use super::tone::ToneArgs;
use anyhow::{Context, Result, bail};
use clap::Args;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use strahl::method::World;
use strahl::method::{
    AccelKind, Batch, LightTraceSettings, Method, MethodKind, SurfaceTraceSettings,
};
use strahl::report::{ExportFormat, ObjectReport, Report, ReportFormat, write_report};
use strahl::scene::Scene;

/// Options of the light-trace solver.
#[derive(Debug, Args)]
#[command(next_help_heading = "Light tracing (--solver light-trace)")]
pub struct LightTraceArgs {
    /// Photons to trace (at most 10¹²).
    #[arg(long, default_value_t = LightTraceSettings::default().photons, value_parser = clap::value_parser!(u64).range(1..=super::limits::MAX_PHOTONS))]
    pub photons: u64,
    /// Scattering events after which a photon is absorbed where it is.
    #[arg(long, default_value_t = LightTraceSettings::default().max_bounces)]
    pub max_bounces: u32,
}

/// Options of the surface-trace solver.
#[derive(Debug, Args)]
#[command(next_help_heading = "Surface tracing (--solver surface-trace)")]
pub struct SurfaceTraceArgs {
    /// Points on each reported surface (at least 2; and rays per sensor), each measured on
    /// both sides.
    #[arg(long, default_value_t = SurfaceTraceSettings::default().points, value_parser = clap::value_parser!(u32).range(2..))]
    pub points: u32,
    /// Add points, in rounds, to every surface whose incident power's standard error is
    /// above this share of it (e.g. 0.03), up to 2²⁰ points a surface; 0: --points on each.
    #[arg(long, default_value_t = 0.0)]
    pub standard_error: f64,
}

/// Arguments of `strahl solve`.
#[derive(Debug, Args)]
pub struct SolveArgs {
    /// Scene: a built-in name (see `strahl scenes`), a .toml scene file or a mesh file.
    pub scene: String,
    /// Which solver computes the light.
    #[arg(long, value_parser = choice_among(MethodKind::SURFACE_SOLVERS), default_value_t = MethodKind::LightTrace)]
    pub solver: MethodKind,
    /// Per-object report: .json (full report) or .csv (one row per object). Without it the
    /// JSON report goes to standard output.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Seed of all random numbers (same seed, same report, for any thread count).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Worker threads (0 = one per core).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Acceleration structure for ray queries.
    #[arg(long, value_parser = choice::<AccelKind>(), default_value_t = AccelKind::Bvh)]
    pub accel: AccelKind,
    /// No progress bar or summary.
    #[arg(short, long, conflicts_with = "verbose")]
    pub quiet: bool,
    /// Also print a per-object table (area, absorbed power, irradiance, illuminance).
    #[arg(short, long)]
    pub verbose: bool,
    /// Report every face of every object on its own (`object#face`), as `per_face = true` on
    /// every object of a scene file does.
    #[arg(long)]
    pub per_face: bool,
    /// Drop every material's specular, mirror and refracting lobes (their light is absorbed):
    /// the scene radiosity solves, for checking a radiosity solution against the light model.
    #[arg(long)]
    pub diffuse_only: bool,
    /// Trace only batch I of N of the photons (I from 0) and write its partial result to
    /// --partial instead of a report; `strahl merge` makes the report of all N, the same as
    /// one run gives (light model only; for job arrays and clusters).
    #[arg(long, requires = "partial", value_parser = clap::value_parser!(Batch))]
    pub batch: Option<Batch>,
    /// Where --batch writes its partial result (JSON).
    #[arg(long, requires = "batch", conflicts_with = "report")]
    pub partial: Option<PathBuf>,
    /// Light-trace options.
    #[command(flatten)]
    pub light_trace: LightTraceArgs,
    /// Surface-trace options.
    #[command(flatten)]
    pub surface_trace: SurfaceTraceArgs,
    /// Radiosity options.
    #[command(flatten)]
    pub radiosity: RadiosityArgs,
    /// The final gather at the reported surfaces.
    #[command(flatten)]
    #[command(
        next_help_heading = "Radiosity (--solver matrix|progressive|hierarchical|hierarchical-shooting)"
    )]
    pub gather: SurfaceGatherArgs,
    /// Colours of the exported mesh (`--export`).
    #[command(flatten)]
    #[command(next_help_heading = "Export colours (--export)")]
    pub tone: ToneArgs,
    /// Bounds on the work asked for.
    #[command(flatten)]
    pub limits: LimitArgs,
}

impl SolveArgs {
    /// Checks the arguments that need no scene: the report and export formats, the solver's
    /// options and their limits.
    pub fn check(&self) -> Result<()> {
        let mut sensors = None;
        if let Some(path) = &self.report
            && ReportFormat::from_path(path).context("--report")? == ReportFormat::Csv
        {
            sensors = Some(strahl::report::sensors_csv_path(path));
        }
        super::outputs::check(
            &self.scene,
            &[
                ("--report", self.report.as_deref()),
                ("--report's sensor table", sensors.as_deref()),
                ("--export", self.radiosity.export.as_deref()),
            ],
        )?;
        if let Some(path) = &self.radiosity.export {
            ExportFormat::from_path(path).context("--export")?;
        }
        if self.batch.is_some() && self.solver != MethodKind::LightTrace {
            bail!("--batch splits the light model's photons: it needs --solver light-trace");
        }
        super::outputs::check(&self.scene, &[("--partial", self.partial.as_deref())])?;
        self.method()?;
        Ok(())
    }

    /// The method these arguments ask for, checked.
    pub fn method(&self) -> Result<Method> {
        let method = match self.solver {
            MethodKind::Radiosity(solver) => {
                let mut settings = self.radiosity.settings(solver, self.seed, &self.limits)?;
                settings.surface_gather = self.gather.settings();
                settings.check().map_err(|e| method_error(e.into()))?;
                Method::Radiosity(settings)
            }
            _ => {
                if self.gather.given() {
                    bail!(
                        "--surface-gather and --gather-below measure a radiosity solution's \
                         surfaces anew: they need --solver matrix, progressive, hierarchical or \
                         hierarchical-shooting"
                    );
                }
                if self.radiosity.export.is_some() {
                    bail!(
                        "--export writes a radiosity solution's mesh: it needs --solver matrix, \
                         progressive, hierarchical or hierarchical-shooting"
                    );
                }
                match self.solver {
                    MethodKind::SurfaceTrace => Method::SurfaceTrace(SurfaceTraceSettings {
                        points: self.surface_trace.points,
                        standard_error: self.surface_trace.standard_error,
                        seed: self.seed,
                    }),
                    _ => Method::LightTrace(LightTraceSettings {
                        photons: self.light_trace.photons,
                        seed: self.seed,
                        max_bounces: self.light_trace.max_bounces,
                    }),
                }
            }
        };
        method.check().map_err(|e| method_error(e.into()))?;
        Ok(method)
    }
}

/// Runs `strahl solve`.
pub fn run(args: &SolveArgs) -> Result<()> {
    args.check()?;
    let scene = open_scene_with(
        &args.scene,
        args.per_face,
        args.diffuse_only,
        &args.limits.load_options(),
    )?;
    if scene.objects.is_empty() {
        bail!(
            "'{}' has no objects: there is nothing to take light",
            args.scene
        );
    }
    if !scene.has_light() {
        bail!(
            "'{}' has no light (no light source, no sky, no emitting material): there is nothing to solve",
            args.scene
        );
    }
    let name = scene.name.clone();
    let world = World::new(scene, args.accel).with_context(|| format!("scene '{}'", args.scene))?;
    if let Some(warning) = world.scale_warning().filter(|_| !args.quiet) {
        eprintln!("warning: {warning}");
    }
    let method = args.method()?;
    if method.radiosity().is_some() || method.kind() == MethodKind::SurfaceTrace {
        radiosity::warn_non_diffuse(&world.scene, method.kind());
    }
    let world = Arc::new(world);
    if let (Some(batch), Some(path)) = (args.batch, &args.partial) {
        return solve_batch(args, &world, &method, batch, path);
    }
    let (outcome, parts) = run_measuring(&world, &method, "solving", args.quiet)?;
    match &outcome.radiosity {
        Some(solved) => {
            radiosity::finish_solve(
                solved,
                args.radiosity.export.as_deref(),
                &args.tone.mapping(),
                args.quiet,
            )?;
            if args.verbose {
                print_convergence(&solved.solution);
            }
            let stats = outcome.measurement.as_ref().map(|m| &m.stats.extra);
            match stats.and_then(|s| {
                s.get("surface_gather_points")
                    .zip(s.get("seconds_surface_gather"))
            }) {
                Some((points, seconds)) if !args.quiet => eprintln!(
                    "final gather at the reported surfaces: {points} points, {:.2} s",
                    seconds.as_f64().unwrap_or(0.0)
                ),
                None if args.gather.settings().is_on() && !outcome.complete && !args.quiet => {
                    eprintln!(
                        "final gather interrupted: the report holds the solution's own values"
                    )
                }
                _ => {}
            }
        }
        None if !args.quiet => eprintln!(
            "{name}: {}{}",
            outcome.summary,
            match (outcome.complete, args.solver) {
                (true, _) => "",
                (false, MethodKind::SurfaceTrace) => {
                    " (interrupted: each surface reported from the points it had drawn)"
                }
                (false, _) => " (interrupted: report scaled to the full photon count)",
            }
        ),
        None => {}
    }
    let measured = outcome
        .measurement
        .context("the solver measured no surfaces")?;
    let mut report = Report::new(&name, &measured);
    report = report.with_states(&parts.states);
    match (&parts.bands, &world.scene.spectral) {
        (Some(bands), _) => report = report.with_bands(bands),
        (None, Some(spectral)) => eprintln!(
            "bands interrupted: the report holds the RGB figures only, none of the {} bands",
            spectral.bands.len()
        ),
        (None, None) => {}
    }
    if let Some((entry, field)) = report.first_non_finite() {
        anyhow::bail!(
            "the {} solution has a non-finite {field} for {entry}: a numerical failure, so no \
             report is written (please report the scene)",
            report.solver
        );
    }
    if !args.quiet {
        for o in report.objects.iter().filter(|o| o.area.is_none()) {
            eprintln!(
                "warning: '{}' is unbounded (an infinite plane): the power it receives is \
                 reported, its area, irradiance, radiosity and illuminance are not (null in \
                 JSON, empty in CSV)",
                o.name
            );
        }
        let t = &report.totals;
        eprintln!(
            "emitted {:.4} W, absorbed {:.4} W, escaped {:.4} W (luminance-weighted)",
            t.emitted_power.luminance(),
            t.absorbed_power.luminance(),
            t.escaped_power.luminance()
        );
    }
    if args.verbose {
        print_table(&report);
        if let Some(bytes) = strahl::method::peak_resident_bytes() {
            eprintln!(
                "peak memory {:.1} MiB (bound {})",
                bytes as f64 / f64::from(1 << 20),
                args.limits
                    .memory_bytes()
                    .map_or("none".to_string(), |b| format!("{} MiB", b >> 20))
            );
        }
    }
    deliver(&report, args.report.as_deref(), args.quiet)
}

/// Writes `report` to `path` (JSON or CSV by its extension), or prints it as JSON to
/// standard output without one (a reader that stops early is no error).
pub fn deliver(report: &Report, path: Option<&Path>, quiet: bool) -> Result<()> {
    match path {
        Some(path) => {
            write_report(report, path)?;
            if !quiet {
                eprintln!("report: {}", path.display());
            }
        }
        None => {
            let mut out = std::io::BufWriter::new(std::io::stdout().lock());
            let written = serde_json::to_writer_pretty(&mut out, report)
                .map_err(std::io::Error::from)
                .and_then(|()| writeln!(out))
                .and_then(|()| out.flush());
            match written {
                // The reader stopped reading (`strahl solve … | head`): nothing is lost.
                Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {}
                written => written?,
            }
        }
    }
    Ok(())
}

/// The scene `name` (a built-in name or a file), every face reported on its own with
/// `per_face`, without its non-diffuse lobes with `diffuse_only`.
pub fn open_scene(name: &str, per_face: bool, diffuse_only: bool) -> Result<Scene> {
    open_scene_with(name, per_face, diffuse_only, &Default::default())
}

/// [`open_scene`] within the bounds of `load`.
fn open_scene_with(
    name: &str,
    per_face: bool,
    diffuse_only: bool,
    load: &strahl::scene::LoadOptions,
) -> Result<Scene> {
    let mut scene = strahl::scene::open(name, load)?;
    if per_face {
        for object in &mut scene.objects {
            object.per_face = true;
        }
    }
    if diffuse_only {
        scene.keep_diffuse_lobes();
    }
    Ok(scene)
}

/// Traces batch `batch` of the light model's run and writes its partial result to `path`.
fn solve_batch(
    args: &SolveArgs,
    world: &World,
    method: &Method,
    batch: Batch,
    path: &Path,
) -> Result<()> {
    let partial = batch_file::run_whole("photons", args.quiet, |bar, cancel| {
        strahl::method::run_batch(world, method, batch, bar, cancel)
    })?;
    let file = PartialFile {
        scene: args.scene.clone(),
        per_face: args.per_face,
        diffuse_only: args.diffuse_only,
        partial,
    };
    batch_file::write(path, &file)?;
    if !args.quiet {
        eprintln!(
            "batch {batch}: {} photons in {:.2} s → {}",
            file.partial.photons_traced,
            file.partial.seconds,
            path.display()
        );
    }
    Ok(())
}

/// Prints one line per report entry, then one per sensor, to standard error.
fn print_table(report: &Report) {
    eprintln!(
        "{:24} {:>10} {:>12} {:>12} {:>12} {:>12}",
        "object", "area", "absorbed W", "E W/m²", "lux", "±1σ lux"
    );
    for o in &report.objects {
        eprintln!("{}", table_row(o));
    }
    if report.sensors.is_empty() {
        return;
    }
    eprintln!(
        "{:24} {:>12} {:>12} {:>12} {:>12}",
        "sensor", "lux", "direct lux", "indirect lux", "±1σ lux"
    );
    for s in &report.sensors {
        let sigma = s
            .standard_error_lux
            .map_or("-".to_string(), |e| format!("{e:.4}"));
        eprintln!(
            "{:24} {:>12.4} {:>12.4} {:>12.4} {:>12}",
            s.name, s.illuminance_lux, s.direct_illuminance_lux, s.indirect_illuminance_lux, sigma
        );
    }
}

/// One table line: name (with face), area, luminance of absorbed power and irradiance, lux.
fn table_row(o: &ObjectReport) -> String {
    let name = match o.face {
        Some(f) => format!("{}[{f}]", o.name),
        None => o.name.clone(),
    };
    let opt = |v: Option<f64>| v.map_or("-".to_string(), |x| format!("{x:.4}"));
    format!(
        "{name:24} {:>10} {:>12.5} {:>12} {:>12} {:>12}",
        opt(o.area),
        o.absorbed_power.luminance(),
        opt(o.irradiance.map(|e| e.luminance())),
        opt(o.illuminance_lux),
        opt(o.illuminance_standard_error_lux)
    )
}
