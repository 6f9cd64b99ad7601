//! `strahl merge`: the report of a light-model run from the partial results of its batches
//! (`strahl solve … --batch I/N --partial FILE`, run anywhere: a job array, other machines),
//! the same as one `strahl solve` with the same settings gives, but for the seconds.

use super::outputs;
use super::radiosity::method_error;
use anyhow::{Context, Result, bail};
use clap::Args;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use strahl::method::{AccelKind, LightTracePartial, World};
use strahl::report::{Report, ReportFormat};

/// Arguments of `strahl merge`.
#[derive(Debug, Args)]
pub struct MergeArgs {
    /// The partial results of every batch of one run (`strahl solve --batch I/N --partial`).
    #[arg(required = true)]
    pub parts: Vec<PathBuf>,
    /// The report: .json or .csv. Without it the JSON report goes to standard output.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// No summary.
    #[arg(short, long)]
    pub quiet: bool,
}

/// A batch's partial result as `strahl solve --partial` writes it: how to open the scene
/// again, and the batch's tallies.
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

/// Runs `strahl merge`.
pub fn run(args: &MergeArgs) -> Result<()> {
    if let Some(path) = &args.report {
        ReportFormat::from_path(path).context("--report")?;
        outputs::check("", &[("--report", Some(path.as_path()))])?;
    }
    let files: Vec<PartialFile> = args.parts.iter().map(|p| read(p)).collect::<Result<_>>()?;
    let first = &files[0];
    for (file, path) in files.iter().zip(&args.parts) {
        if (&file.scene, file.per_face, file.diffuse_only)
            != (&first.scene, first.per_face, first.diffuse_only)
        {
            bail!(
                "{}: a batch of scene '{}'{}{}, not of '{}' like {}",
                path.display(),
                file.scene,
                if file.per_face { " --per-face" } else { "" },
                if file.diffuse_only {
                    " --diffuse-only"
                } else {
                    ""
                },
                first.scene,
                args.parts[0].display()
            );
        }
    }
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

/// A partial result file; errors name it.
fn read(path: &Path) -> Result<PartialFile> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    serde_json::from_str(&text).with_context(|| {
        format!(
            "{}: not a partial result of `strahl solve --batch I/N --partial`",
            path.display()
        )
    })
}
