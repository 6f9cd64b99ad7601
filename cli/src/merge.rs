//! `strahl merge`: one run's output from the partial results of its batches, run anywhere (a
//! job array, other machines) — the report of a light-model run (`strahl solve … --batch I/N
//! --partial FILE`, written with `--report`) or the image of a path-traced render (`strahl
//! render … --batch I/N --partial FILE`, written with `-o`), the same as the single run with
//! the same settings gives, but for the seconds.

use super::outputs;
use super::radiosity::method_error;
use super::render_batch::{self, RenderPartialFile};
use super::tone::ToneArgs;
use anyhow::{Context, Result, bail};
use clap::Args;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use strahl::image::FileFormat;
use strahl::method::{AccelKind, LightTracePartial, World};
use strahl::report::{Report, ReportFormat};

/// Arguments of `strahl merge`.
#[derive(Debug, Args)]
pub struct MergeArgs {
    /// The partial results of every batch of one run (`strahl solve --batch I/N --partial`
    /// or `strahl render --batch I/N --partial`).
    #[arg(required = true)]
    pub parts: Vec<PathBuf>,
    /// The report of a light-model run: .json or .csv. Without it the JSON report goes to
    /// standard output.
    #[arg(long, conflicts_with = "output")]
    pub report: Option<PathBuf>,
    /// The image of a render; the extension chooses the format (.png, .exr, .pfm).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Tone mapping of a PNG image, as `strahl render` takes it.
    #[command(flatten)]
    pub tone: ToneArgs,
    /// No summary.
    #[arg(short, long)]
    pub quiet: bool,
}

/// A light-model batch's partial result as `strahl solve --partial` writes it: how to open
/// the scene again, and the batch's tallies.
#[derive(Serialize, Deserialize)]
pub struct PartialFile {
    /// The scene as `solve` was given it (a built-in name or a file path).
    pub scene: String,
    /// `--per-face` and `--diffuse-only`, which change the scene solved.
    pub per_face: bool,
    pub diffuse_only: bool,
    /// The batch.
    pub partial: LightTracePartial,
}

/// A partial result file of either kind, told apart by its fields.
enum AnyPartial {
    /// Of `strahl solve --batch` (boxed: its tallies' fixed part is large).
    Light(Box<PartialFile>),
    /// Of `strahl render --batch`.
    Render(RenderPartialFile),
}

/// Runs `strahl merge`.
pub fn run(args: &MergeArgs) -> Result<()> {
    if let Some(path) = &args.report {
        ReportFormat::from_path(path).context("--report")?;
    }
    if let Some(path) = &args.output {
        FileFormat::from_path(path).context("-o")?;
    }
    outputs::check(
        "",
        &[
            ("--report", args.report.as_deref()),
            ("-o", args.output.as_deref()),
        ],
    )?;
    let (mut light, mut render) = (Vec::new(), Vec::new());
    for path in &args.parts {
        match read(path)? {
            AnyPartial::Light(file) => light.push((path, *file)),
            AnyPartial::Render(file) => render.push((path, file)),
        }
    }
    match (light.first(), render.first()) {
        (Some((light, _)), Some((render, _))) => bail!(
            "{} is a render's batch (strahl render --batch), {} a light-model run's (strahl \
             solve --batch): they do not merge",
            render.display(),
            light.display()
        ),
        (None, _) => {
            let Some(output) = &args.output else {
                bail!("these are a render's batches: name the image with -o IMAGE");
            };
            same_scene(
                render
                    .iter()
                    .map(|(path, f)| (*path, format!("'{}'", f.scene))),
            )?;
            let scene = render[0].1.scene.clone();
            let files = render.into_iter().map(|(_, f)| f).collect();
            render_batch::merge(&scene, files, output, &args.tone.mapping(), args.quiet)
        }
        (Some(_), None) => {
            if args.output.is_some() {
                bail!(
                    "these are a light-model run's batches: name the report with --report, not -o"
                );
            }
            same_scene(light.iter().map(|(path, f)| {
                let options = [
                    (f.per_face, " --per-face"),
                    (f.diffuse_only, " --diffuse-only"),
                ];
                let flags: String = options.iter().filter(|o| o.0).map(|o| o.1).collect();
                (*path, format!("'{}'{flags}", f.scene))
            }))?;
            merge_light(args, light.into_iter().map(|(_, f)| f).collect())
        }
    }
}

/// Refuses parts (each with the scene it names, options that change it included) of
/// different scenes.
fn same_scene<'a>(parts: impl Iterator<Item = (&'a PathBuf, String)>) -> Result<()> {
    let mut parts = parts.peekable();
    let Some((first_path, first)) = parts.peek().cloned() else {
        return Ok(());
    };
    for (path, scene) in parts {
        if scene != first {
            bail!(
                "{}: a batch of scene {scene}, not of {first} like {}",
                path.display(),
                first_path.display()
            );
        }
    }
    Ok(())
}

/// The light-model report of the batches `files` (of one scene), written as `--report` asks.
fn merge_light(args: &MergeArgs, files: Vec<PartialFile>) -> Result<()> {
    let first = &files[0];
    let scene = super::solve::open_scene(&first.scene, first.per_face, first.diffuse_only)?;
    let name = scene.name.clone();
    let world =
        World::new(scene, AccelKind::Bvh).with_context(|| format!("scene '{}'", first.scene))?;
    let partials: Vec<LightTracePartial> = files.into_iter().map(|f| f.partial).collect();
    let outcome = strahl::method::merge_batches(&world, &partials).map_err(method_error)?;
    if !args.quiet {
        eprintln!(
            "{name}: {} (merged from {} batches)",
            outcome.summary,
            partials.len()
        );
    }
    let measured = outcome
        .measurement
        .context("the merge measured no surfaces")?;
    let report = Report::new(&name, &measured);
    super::solve::deliver(&report, args.report.as_deref(), args.quiet)
}

/// The field that tells a render's partial result from a light-model run's.
#[derive(Deserialize)]
struct Kind {
    render: Option<serde::de::IgnoredAny>,
}

/// A partial result file, a render's where it has a `render` field; errors name it.
fn read(path: &Path) -> Result<AnyPartial> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    let not_partial = || {
        format!(
            "{}: not a partial result of `strahl solve --batch I/N --partial` or `strahl \
             render --batch I/N --partial`",
            path.display()
        )
    };
    // Typed from the text: through `serde_json::Value` the tallies' 128-bit integers would
    // lose digits.
    let kind: Kind = serde_json::from_str(&text).with_context(not_partial)?;
    Ok(match kind.render {
        Some(_) => AnyPartial::Render(serde_json::from_str(&text).with_context(not_partial)?),
        None => AnyPartial::Light(serde_json::from_str(&text).with_context(not_partial)?),
    })
}
