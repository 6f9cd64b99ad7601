//! `strahl validate`: the analytic validation suite — scenes with closed-form answers run
//! through every method, a table of expected and computed figures, a non-zero exit when any
//! check fails.

use super::choice::choice_among;
use super::progress;
use anyhow::{Context, Result, bail};
use clap::Args;
use std::path::PathBuf;
use strahl::method::MethodKind;
use strahl::validate::{Effort, Row, STANDARD_ERRORS, SUITE, TOLERANCE, run_suite};

/// Arguments of `strahl validate`.
#[derive(Debug, Args)]
pub struct ValidateArgs {
    /// Fewer photons and samples and the quicker cases (well under a minute).
    #[arg(long)]
    pub quick: bool,
    /// Only these methods (comma-separated; default: all).
    #[arg(long, value_delimiter = ',', value_parser = choice_among(SUITE))]
    pub method: Vec<MethodKind>,
    /// Also write the table as JSON.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Photons of the light model (default 10⁶ with --quick, else 8·10⁶; at most 10¹²).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=super::limits::MAX_PHOTONS))]
    pub photons: Option<u64>,
    /// Points per emitting surface and rays per sensor of the ray tracers (default 2¹⁸ with
    /// --quick, else 2²⁰; at most 2²⁴).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=i64::from(super::limits::MAX_VALIDATE_SAMPLES)))]
    pub samples: Option<u32>,
    /// Points per surface of the surface tracer (default 2¹⁶ with --quick, else 2¹⁸; 2 to
    /// 2²⁴).
    #[arg(long, value_parser = clap::value_parser!(u32).range(2..=i64::from(super::limits::MAX_VALIDATE_SAMPLES)))]
    pub points: Option<u32>,
    /// Error threshold of hierarchical radiosity and hierarchical shooting, relative to all
    /// power emitted in the scene (10⁻⁸ to 1).
    #[arg(long)]
    pub error: Option<f64>,
    /// Radiosity solvers: the final gather at the reported surfaces, as in `strahl solve`.
    #[command(flatten)]
    pub gather: super::radiosity::SurfaceGatherArgs,
    /// Seed of all random numbers.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Worker threads (0 = one per core).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// The memory bound.
    #[command(flatten)]
    pub memory: super::limits::MemoryArgs,
}

/// Runs `strahl validate`.
pub fn run(args: &ValidateArgs) -> Result<()> {
    let methods = if args.method.is_empty() {
        SUITE.to_vec()
    } else {
        args.method.clone()
    };
    let base = if args.quick {
        Effort::QUICK
    } else {
        Effort::FULL
    };
    let effort = Effort {
        photons: args.photons.unwrap_or(base.photons),
        samples: args.samples.unwrap_or(base.samples),
        points: args.points.unwrap_or(base.points),
        error: args.error.unwrap_or(base.error),
        surface_gather: args.gather.settings(),
        ..base
    };
    if !(effort.error.is_finite() && effort.error > 0.0) {
        bail!("--error must be a positive number (got {})", effort.error);
    }
    super::outputs::check("", &[("--report", args.report.as_deref())])?;
    println!(
        "{:16} {:18} {:21} {:>12} {:>12} {:>9} {:>9} {:>5} {:>7}",
        "case", "quantity", "method", "expected", "computed", "error", "±3σ", "pass", "time"
    );
    let cancel = progress::cancel_flag();
    let rows = run_suite(&methods, effort, args.seed, cancel, |r| {
        println!("{}", line(r))
    })?;
    let failed = rows.iter().filter(|r| !r.pass).count();
    println!(
        "{} checks, {} passed, {failed} failed (tolerance {:.0} %, plus {STANDARD_ERRORS} \
         standard errors of a recorded reference; and within {STANDARD_ERRORS} standard errors \
         for Monte Carlo methods)",
        rows.len(),
        rows.len() - failed,
        TOLERANCE * 100.0
    );
    if let Some(path) = &args.report {
        let text = serde_json::to_string_pretty(&rows)?;
        strahl::atomic_file::write(path, (text + "\n").as_bytes())
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    if progress::interrupted() {
        return Ok(());
    }
    if failed > 0 {
        bail!("{failed} validation checks failed");
    }
    Ok(())
}

/// One table line.
fn line(r: &Row) -> String {
    let sigma = r.standard_error.map_or("-".to_string(), |s| {
        format!("{:.3}%", 100.0 * STANDARD_ERRORS * s / r.expected.abs())
    });
    format!(
        "{:16} {:18} {:21} {:>12.4} {:>12.4} {:>8.3}% {:>9} {:>5} {:>6.2}s",
        r.case,
        r.quantity,
        r.method,
        r.expected,
        r.computed,
        100.0 * r.relative_error,
        sigma,
        if r.pass { "ok" } else { "FAIL" },
        r.seconds
    )
}
