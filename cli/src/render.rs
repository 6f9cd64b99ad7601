//! `strahl render`: render an image of a scene.

use super::choice::{choice, choice_among};
use super::limits::{LimitArgs, finite};
use super::radiosity::{self, RadiosityDisplayArgs, method_error};
use super::tone::ToneArgs;
use super::{progress, run_method};
use anyhow::{Context, Result, bail};
use clap::Args;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;
use strahl::image::{self, FalseColor, MAX_ISOLINES, ToneMap, ToneMapping};
use strahl::method::{
    AccelKind, Antialias, AntialiasMode, Batch, DisplaySettings, FinalGatherSettings, ImageSize,
    LinkDisplay, Method, MethodKind, NoProgress, PathTraceSettings, Photometric,
    RadiosityImageSettings, RayTraceSettings, ShadowMode, SolvedRadiosity, World,
};

/// Arguments of `strahl render`.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// Scene: a built-in name (see `strahl scenes`), a .toml scene file or a mesh file.
    pub scene: String,
    /// Output image; the extension chooses the format (.png, .exr, .pfm).
    #[arg(
        short,
        long,
        required_unless_present = "partial",
        conflicts_with = "partial"
    )]
    pub output: Option<PathBuf>,
    /// pathtrace: render only batch I of N of the samples per pixel (I from 0) and write its
    /// partial result to --partial instead of an image; `strahl merge PARTS -o IMAGE` makes
    /// the image of all N, the same bit for bit as one render with the same settings.
    #[arg(long, requires = "partial", value_parser = clap::value_parser!(Batch))]
    pub batch: Option<Batch>,
    /// Where --batch writes its partial result (JSON: the exact per-pixel sums packed in
    /// base64).
    #[arg(long, requires = "batch")]
    pub partial: Option<PathBuf>,
    /// Rendering method.
    #[arg(long, value_parser = choice_among(MethodKind::IMAGES), default_value_t = MethodKind::RayTrace)]
    pub method: MethodKind,
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
    #[arg(long, default_value_t = RayTraceSettings::default().light_samples, value_parser = clap::value_parser!(u32).range(1..))]
    pub light_samples: u32,
    /// final-gather: rays per camera sample that gather the solution's reflected light
    /// (rounded up to a square).
    #[arg(long, default_value_t = FinalGatherSettings::default().gather_rays, value_parser = clap::value_parser!(u32).range(1..))]
    pub gather_rays: u32,
    /// raytrace: antialiasing method (pathtrace always jitters its samples over the pixel).
    #[arg(long, value_parser = choice::<AntialiasMode>(), default_value_t = Antialias::default().mode)]
    pub aa: AntialiasMode,
    /// Colour difference that makes adaptive antialiasing subdivide.
    #[arg(long, default_value_t = Antialias::default().threshold, value_parser = finite::<f32>)]
    pub aa_threshold: f32,
    /// Write an image of how often adaptive antialiasing subdivided each pixel.
    #[arg(long)]
    pub aa_map: Option<PathBuf>,
    /// Acceleration structure.
    #[arg(long, value_parser = choice::<AccelKind>(), default_value_t = AccelKind::Bvh)]
    pub accel: AccelKind,
    /// Shadows from all objects, or only self-shadowing by facing.
    #[arg(long, value_parser = choice::<ShadowMode>(), default_value_t = RayTraceSettings::default().shadows)]
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
    /// radiosity: write this quantity in false colour with its legend instead of the image
    /// (isolines with --isolines, the scale's ends with --range; -o must name a .png file).
    #[arg(long, value_parser = choice::<Photometric>())]
    pub false_color: Option<Photometric>,
    /// With --false-color: the values at the colour scale's low and high ends, `MIN,MAX` in
    /// lux or cd/m² (default: 0 to the largest value seen, rounded up to 1, 2, 2.5 or 5 × 10ⁿ).
    #[arg(long, value_parser = parse_range)]
    pub range: Option<(f32, f32)>,
    /// With --false-color: isolines at this many levels evenly spaced inside the range,
    /// each labelled in the legend.
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u32).range(0..=i64::from(MAX_ISOLINES)))]
    pub isolines: u32,
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
        if let Some(output) = &self.output {
            image::FileFormat::from_path(output).context("-o")?;
        }
        if self.batch.is_some() {
            if self.method != MethodKind::PathTrace {
                bail!(
                    "--batch splits the path tracer's samples per pixel: it needs --method \
                     pathtrace, not {}",
                    self.method
                );
            }
            if self.time_limit.is_some() {
                bail!(
                    "--time-limit with --batch would cut the batch short, and merging refuses it"
                );
            }
        }
        super::outputs::check(
            &self.scene,
            &[
                ("-o", self.output.as_deref()),
                ("--partial", self.partial.as_deref()),
                ("--aa-map", self.aa_map.as_deref()),
                ("--export", self.radiosity.solve.export.as_deref()),
            ],
        )?;
        if let Some(path) = &self.radiosity.solve.export {
            strahl::report::ExportFormat::from_path(path).context("--export")?;
        }
        match (self.false_color, self.output.as_deref()) {
            (Some(_), _) if self.method != MethodKind::RadiosityImage => bail!(
                "--false-color needs --method radiosity (the illuminance and luminance it shows \
                 come from the radiosity solution), not {}",
                self.method
            ),
            (Some(_), Some(output))
                if image::FileFormat::from_path(output)? != image::FileFormat::Png =>
            {
                bail!(
                    "-o {}: a false-colour image is written as PNG (its colours and legend are \
                     display colours, not radiance)",
                    output.display()
                )
            }
            (None, _) if self.range.is_some() || self.isolines > 0 => {
                bail!("--range and --isolines apply to --false-color only")
            }
            _ => {}
        }
        if let Some(map) = &self.aa_map {
            image::FileFormat::from_path(map).context("--aa-map")?;
            if self.aa != AntialiasMode::Adaptive {
                bail!("--aa-map needs --aa adaptive");
            }
        }
        if let (Some(solver), MethodKind::RayTrace | MethodKind::PathTrace) =
            (self.radiosity.solver, self.method)
        {
            bail!(
                "--solver {solver} applies to --method radiosity and final-gather only, not {}",
                self.method
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
        self.method()?;
        Ok(())
    }

    /// The method these arguments ask for, checked; the image size is the camera's where
    /// `--width` or `--height` is not given.
    pub fn method(&self) -> Result<Method> {
        let size = ImageSize {
            width: self.width,
            height: self.height,
        };
        let antialias = Antialias {
            mode: self.aa,
            samples_per_pixel: self.spp.unwrap_or(Antialias::default().samples_per_pixel),
            threshold: self.aa_threshold,
        };
        let method = match self.method {
            MethodKind::PathTrace => {
                if self.aa != AntialiasMode::Stochastic || self.aa_map.is_some() {
                    bail!("--aa and --aa-map apply to --method raytrace only");
                }
                if self.shadows != ShadowMode::On {
                    bail!("--shadows off applies to --method raytrace only");
                }
                let defaults = PathTraceSettings::default();
                Method::PathTrace(PathTraceSettings {
                    size,
                    max_depth: self.depth.unwrap_or(defaults.max_depth),
                    first_hit_paths: self.first_hit_paths.unwrap_or(defaults.first_hit_paths),
                    samples_per_pixel: self.spp.unwrap_or(defaults.samples_per_pixel),
                    time_limit: self.time_limit,
                    ..defaults
                })
            }
            MethodKind::RadiosityImage => Method::RadiosityImage(RadiosityImageSettings {
                size,
                radiosity: self
                    .radiosity
                    .settings("radiosity", self.seed, &self.limits)?,
                shading: self.radiosity.shading,
                wireframe: self.radiosity.wireframe,
                links: self.radiosity.links(),
                samples_per_pixel: antialias.samples_per_pixel,
            }),
            MethodKind::FinalGather => Method::FinalGather(FinalGatherSettings {
                size,
                radiosity: self
                    .radiosity
                    .settings("final-gather", self.seed, &self.limits)?,
                shading: self.radiosity.shading,
                light_samples: self.light_samples,
                gather_rays: self.gather_rays,
                antialias,
                ..FinalGatherSettings::default()
            }),
            _ => {
                if self.first_hit_paths.is_some() || self.time_limit.is_some() {
                    bail!("--first-hit-paths and --time-limit need --method pathtrace");
                }
                Method::RayTrace(RayTraceSettings {
                    size,
                    max_depth: self.depth.unwrap_or(RayTraceSettings::default().max_depth),
                    light_samples: self.light_samples,
                    shadows: self.shadows,
                    antialias,
                    ..RayTraceSettings::default()
                })
            }
        }
        .with_seed(self.seed);
        method.check().map_err(|e| method_error(e.into()))?;
        Ok(method)
    }
}

/// Runs `strahl render`.
pub fn run(args: &RenderArgs) -> Result<()> {
    args.check()?;
    let scene = strahl::scene::open(&args.scene, &args.limits.load_options())?;
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
    let method = match (args.method()?, args.false_color) {
        // False colour reads the solution itself: no image of it to render and drop.
        (Method::RadiosityImage(image), Some(_)) => Method::Radiosity(image.radiosity),
        (method, _) => method,
    };
    if method.radiosity().is_some() {
        radiosity::warn_non_diffuse(&world.scene, method.kind());
    }
    let world = Arc::new(world);
    if let (Some(batch), Some(path)) = (args.batch, &args.partial) {
        return super::render_batch::write(args, &world, &method, batch, path);
    }
    let output = args.output.as_deref().context("-o names no image")?;
    let start = Instant::now();
    let tone_mapping = args.tone.mapping();
    let outcome = run_method(&world, &method, "rendering", args.quiet)?;
    let seconds = start.elapsed().as_secs_f64();
    if let Some(solved) = &outcome.radiosity {
        radiosity::finish_solve(
            solved,
            args.radiosity.solve.export.as_deref(),
            &tone_mapping,
            args.quiet,
        )?;
    }
    match (args.false_color, &outcome.radiosity) {
        (Some(quantity), Some(solved)) => {
            save_false_color(args, &world, solved, quantity, (width, height), output)?
        }
        _ => {
            let film = outcome.image.context("the method made no image")?;
            image::save(&film, output, &tone_mapping)?;
        }
    }
    if let Some(map) = &args.aa_map {
        save_subdivision_map(&outcome.subdivisions, width, height, map)?;
    }
    if !args.quiet {
        eprintln!(
            "{} {}×{} in {seconds:.2} s, {}{}",
            output.display(),
            width,
            height,
            outcome.summary,
            if outcome.complete {
                ""
            } else {
                " (stopped early: partial image)"
            }
        );
    }
    Ok(())
}

/// Writes `quantity` over `solved` through the scene camera at `width × height` in false
/// colour with its legend to `output`, the solution looked up as the image was (shading,
/// rays per pixel).
fn save_false_color(
    args: &RenderArgs,
    world: &World,
    solved: &SolvedRadiosity,
    quantity: Photometric,
    (width, height): (u32, u32),
    output: &Path,
) -> Result<()> {
    let settings = DisplaySettings {
        width,
        height,
        shading: args.radiosity.shading,
        wireframe: false,
        samples_per_axis: (args
            .spp
            .unwrap_or(RadiosityImageSettings::default().samples_per_pixel)
            as f64)
            .sqrt()
            .ceil() as u32,
        links: LinkDisplay::None,
    };
    let values = solved
        .value_image(
            &world.scene.camera,
            &settings,
            quantity,
            &NoProgress,
            progress::cancel_flag(),
        )
        .context("the scene camera is degenerate")?;
    let false_color = FalseColor {
        range: args.range,
        isolines: args.isolines,
    };
    image::save_false_color(&values, &false_color, output)?;
    Ok(())
}

/// `MIN,MAX`: two finite numbers, MIN below MAX.
fn parse_range(text: &str) -> Result<(f32, f32), String> {
    let parse = |s: &str| {
        s.trim()
            .parse::<f32>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| format!("'{s}' is not a finite number"))
    };
    let (low, high) = text
        .split_once(',')
        .ok_or_else(|| format!("expected MIN,MAX (e.g. 0,500), got '{text}'"))?;
    let (low, high) = (parse(low)?, parse(high)?);
    if low >= high {
        return Err(format!("MIN must lie below MAX (got {low},{high})"));
    }
    Ok((low, high))
}

/// Writes the subdivision counts as a grey image: black = never subdivided, white = the
/// most-subdivided pixel.
fn save_subdivision_map(counts: &[u32], width: u32, height: u32, path: &Path) -> Result<()> {
    let film = image::count_map(counts, width, height).context("subdivision map size")?;
    let linear = ToneMapping {
        operator: ToneMap::Linear,
        exposure_ev: 0.0,
    };
    image::save(&film, path, &linear)?;
    Ok(())
}
