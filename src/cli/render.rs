//! `strahl render`: render an image of a scene.

use super::{progress, source, with_threads};
use crate::accel::AccelKind;
use crate::color::Rgb;
use crate::image::{self, Film, ToneMap, ToneMapping};
use crate::trace::antialias::AntialiasMode;
use crate::trace::direct::ShadowMode;
use crate::trace::render::{RenderSettings, render};
use crate::trace::sampler::SequenceKind;
use crate::trace::{StandardRayTracer, World};
use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Rendering methods.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Method {
    /// The standard (Whitted-style) ray tracer: direct light, ideal reflection and refraction.
    Raytrace,
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
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height in pixels (default: the scene camera's).
    #[arg(long)]
    pub height: Option<u32>,
    /// Camera samples per pixel for stochastic antialiasing (rounded up to a square).
    #[arg(long, default_value_t = 4)]
    pub spp: u32,
    /// Reflection/refraction recursion depth (0 turns reflections and refractions off).
    #[arg(long, default_value_t = 6)]
    pub depth: u32,
    /// Shadow rays per area light and for the sky at every shading point.
    #[arg(long, default_value_t = 16)]
    pub light_samples: u32,
    /// Antialiasing method.
    #[arg(long, value_enum, default_value_t = AntialiasMode::Stochastic)]
    pub aa: AntialiasMode,
    /// Colour difference that makes adaptive antialiasing subdivide.
    #[arg(long, default_value_t = 0.05)]
    pub aa_threshold: f32,
    /// Write an image of how often adaptive antialiasing subdivided each pixel.
    #[arg(long)]
    pub aa_map: Option<PathBuf>,
    /// Acceleration structure.
    #[arg(long, value_enum, default_value_t = AccelKind::Bvh)]
    pub accel: AccelKind,
    /// Shadows from all objects, or only self-shadowing by facing.
    #[arg(long, value_enum, default_value_t = ShadowMode::On)]
    pub shadows: ShadowMode,
    /// Tone mapping for 8-bit output.
    #[arg(long, value_enum, default_value_t = ToneMap::Auto)]
    pub tonemap: ToneMap,
    /// Exposure in stops applied before tone mapping.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub exposure: f32,
    /// Worker threads (0 = one per core).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Seed of all random numbers (same seed, same image, for any thread count).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// No progress bar or summary.
    #[arg(short, long)]
    pub quiet: bool,
}

/// Runs `strahl render`.
pub fn run(args: &RenderArgs) -> Result<()> {
    image::FileFormat::from_path(&args.output)?;
    if let Some(map) = &args.aa_map {
        image::FileFormat::from_path(map)?;
        if args.aa != AntialiasMode::Adaptive {
            bail!("--aa-map needs --aa adaptive");
        }
    }
    let scene = source::load(&args.scene)?;
    let width = args.width.unwrap_or(scene.camera.width);
    let height = args.height.unwrap_or(scene.camera.height);
    if width == 0 || height == 0 {
        bail!("the image size must be at least 1×1 (got {width}×{height})");
    }
    let world = World::new(scene, args.accel).with_context(|| format!("scene '{}'", args.scene))?;
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
    let settings = RenderSettings {
        width,
        height,
        antialias: args.aa,
        samples_per_pixel: args.spp,
        adaptive_threshold: args.aa_threshold,
        seed: args.seed,
        sequence: SequenceKind::Random,
    };
    let integrator = StandardRayTracer {
        max_depth: args.depth,
        light_samples: args.light_samples,
        shadows: args.shadows,
    };
    let cancel = progress::cancel_flag();
    let bar = progress::Bar::new("rendering", args.quiet);
    let start = Instant::now();
    let output = with_threads(args.threads, || {
        render(&world, &integrator, &settings, &bar, &cancel)
    })?
    .context("the camera is degenerate")?;
    let seconds = start.elapsed().as_secs_f64();
    let tone_mapping = ToneMapping {
        operator: args.tonemap,
        exposure_ev: args.exposure,
    };
    image::save(&output.film, &args.output, &tone_mapping)?;
    if let Some(map) = &args.aa_map {
        save_subdivision_map(&output.subdivisions, width, height, map)?;
    }
    if !args.quiet {
        eprintln!(
            "{} {}×{} in {seconds:.2} s, {} camera samples{}",
            args.output.display(),
            width,
            height,
            output.samples_traced,
            if output.complete {
                ""
            } else {
                " (interrupted: partial image)"
            }
        );
    }
    Ok(())
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
