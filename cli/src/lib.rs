//! The `strahl` command line: `render`, `solve`, `validate`, `scenes`, `info`, `bench` and
//! `view`. The only part of strahl that knows the argument parser and HTTP; everything it
//! runs is in the library.

mod batch_file;
mod bench;
mod choice;
mod info;
mod limits;
mod merge;
mod outputs;
mod progress;
mod radiosity;
mod render;
mod render_batch;
mod solve;
mod tone;
mod validate;
mod view;

use clap::{Parser, Subcommand};

/// strahl — global illumination by radiosity and ray tracing.
#[derive(Debug, Parser)]
#[command(name = "strahl", version, about, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render an image of a scene.
    Render(render::RenderArgs),
    /// Compute the light on every object and write a per-object report.
    Solve(solve::SolveArgs),
    /// Merge the partial results of a light-model run's batches (`solve --batch I/N
    /// --partial FILE`) into its report, or of a render's (`render --batch I/N --partial
    /// FILE`) into its image.
    Merge(merge::MergeArgs),
    /// Run the analytic validation suite (closed-form cases through every method).
    Validate(validate::ValidateArgs),
    /// List the built-in scenes.
    Scenes,
    /// Validate a scene and print its statistics.
    Info(info::InfoArgs),
    /// Measure ray-query speed of an accelerator (prints one JSON line).
    Bench(bench::BenchArgs),
    /// Solve a scene by radiosity and show it in the browser: orbit, read the lux anywhere.
    View(view::ViewArgs),
}

/// Runs the command line with the process arguments; returns the process exit code.
pub fn main() -> std::process::ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Render(args) => {
            progress::watch_memory(args.limits.memory_bytes());
            with_threads(args.threads, || render::run(&args)).and_then(|done| done)
        }
        Command::Solve(args) => {
            progress::watch_memory(args.limits.memory_bytes());
            with_threads(args.threads, || solve::run(&args)).and_then(|done| done)
        }
        Command::Merge(args) => merge::run(&args),
        Command::Validate(args) => {
            progress::watch_memory(args.memory.bytes());
            with_threads(args.threads, || validate::run(&args)).and_then(|done| done)
        }
        Command::Scenes => {
            let list: String = strahl::scene::builtin::names()
                .iter()
                .map(|(name, description)| format!("{name:18} {description}\n"))
                .collect();
            print_text(&list).map_err(anyhow::Error::from)
        }
        Command::Info(args) => {
            progress::watch_memory(args.memory.bytes());
            info::run(&args)
        }
        Command::Bench(args) => {
            progress::watch_memory(args.memory.bytes());
            with_threads(args.threads, || bench::run(&args)).and_then(|done| done)
        }
        Command::View(args) => {
            progress::watch_memory(args.limits.memory_bytes());
            view::run(&args)
        }
    };
    if let Some(bytes) = progress::over_memory() {
        progress::report_over_memory(bytes, result.is_ok());
        return std::process::ExitCode::FAILURE;
    }
    match result {
        // Stopped by Ctrl-C, the partial image or report written: the shell's code for it.
        Ok(()) if progress::interrupted() => std::process::ExitCode::from(130),
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", describe(&e));
            std::process::ExitCode::FAILURE
        }
    }
}

/// `e` and its causes, joined by `: `, leaving out a cause the message before already
/// quotes (the library's errors name their operating-system cause in their own words).
fn describe(e: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in e.chain().map(ToString::to_string) {
        if text.is_empty() {
            text = cause;
        } else if !text.contains(&cause) {
            text = format!("{text}: {cause}");
        }
    }
    text
}

/// Threads per core at most: more never speed anything up, and results do not depend on the
/// count (`--threads 100000` spent minutes starting threads before).
const THREADS_PER_CORE: usize = 4;

/// `threads`, or [`THREADS_PER_CORE`] per core where it asks for more (with a warning).
fn useful_threads(threads: usize) -> usize {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let most = THREADS_PER_CORE * cores;
    if threads > most {
        eprintln!(
            "warning: --threads {threads} is more than {THREADS_PER_CORE} per core; using {most} \
             (results do not depend on the count)"
        );
        most
    } else {
        threads
    }
}

/// Runs `method` on `world` with a progress bar labelled `label` (none when `quiet`);
/// Ctrl-C stops it, keeping what it has.
fn run_method(
    world: &std::sync::Arc<strahl::method::World>,
    method: &strahl::method::Method,
    label: &str,
    quiet: bool,
) -> anyhow::Result<strahl::method::Outcome> {
    let bar = progress::Bar::new(label, quiet);
    let cancel = progress::cancel_flag();
    strahl::method::run(world, method, &bar, cancel).map_err(radiosity::method_error)
}

/// [`run_method`] and the scene's parts: its wavelength bands' figures and its day's states
/// ([`strahl::method::run_with_parts`]).
fn run_measuring(
    world: &std::sync::Arc<strahl::method::World>,
    method: &strahl::method::Method,
    label: &str,
    quiet: bool,
) -> anyhow::Result<(strahl::method::Outcome, strahl::method::Parts)> {
    let bar = progress::Bar::new(label, quiet);
    let cancel = progress::cancel_flag();
    strahl::method::run_with_parts(world, method, &bar, cancel).map_err(radiosity::method_error)
}

/// Runs `f` on a rayon pool of its own of `threads` threads (0 = one per core), at most
/// [`THREADS_PER_CORE`] per core ([`useful_threads`]). A command runs whole on its pool, the
/// scene's acceleration structure included (`--threads 1` means one thread throughout);
/// the viewer's renderer, which works while the solver does, on one of its own for each
/// pass (the solver keeps one: [`thread_pool`]).
fn with_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> anyhow::Result<T> {
    Ok(thread_pool(threads)?.install(f))
}

/// A rayon pool of `threads` threads (0 = one per core), at most [`THREADS_PER_CORE`] per
/// core ([`useful_threads`]).
fn thread_pool(threads: usize) -> anyhow::Result<rayon::ThreadPool> {
    let threads = useful_threads(threads);
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| anyhow::anyhow!("cannot start {threads} threads: {e}"))
}

/// Writes `text` to standard output; a reader that stops reading early (`strahl info … |
/// head`) is no error (`println!` would panic there).
fn print_text(text: &str) -> std::io::Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        written => written,
    }
}
