//! `strahl view`: solves a scene by radiosity and serves the solution to a browser on this
//! machine — the mesh lit by the solution (orbit, pan, zoom, wireframe, exposure) and the
//! illuminance anywhere on it, with the object's report row, by a click.

mod server;

use super::choice::{choice, choice_among};
use super::limits::LimitArgs;
use super::radiosity::{self, RadiosityArgs, SurfaceGatherArgs, method_error};
use super::{progress, run_method};
use anyhow::{Context, Result};
use clap::Args;
use server::ViewState;
use std::io::Write;
use std::net::IpAddr;
use std::sync::Arc;
use std::time::Duration;
use strahl::method::{AccelKind, Method, MethodKind, Shading, SolverKind, World};
use strahl::report::Report;

/// Arguments of `strahl view`.
#[derive(Debug, Args)]
pub struct ViewArgs {
    /// Scene: a built-in name (see `strahl scenes`), a .toml scene file or a mesh file.
    pub scene: String,
    /// The radiosity solver [default: hierarchical].
    #[arg(long, value_parser = choice_among(MethodKind::SURFACE_SOLVERS))]
    pub solver: Option<MethodKind>,
    /// How the solution is shown and read across a patch.
    #[arg(long, value_parser = choice::<Shading>(), default_value_t = Shading::default())]
    pub shading: Shading,
    /// Address to listen on: 127.0.0.1 serves this machine only; 0.0.0.0 every network it
    /// is on (anyone who reaches it sees the scene).
    #[arg(long, default_value = "127.0.0.1")]
    pub bind: IpAddr,
    /// Port to listen on (0: any free one; the address is printed).
    #[arg(long, default_value_t = 8000)]
    pub port: u16,
    /// Seed of all random numbers.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Worker threads of the solve (0 = one per core).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// No progress bar or summary (the address is still printed).
    #[arg(short, long)]
    pub quiet: bool,
    /// Radiosity options.
    #[command(flatten)]
    pub radiosity: RadiosityArgs,
    /// The final gather at the reported surfaces.
    #[command(flatten)]
    pub gather: SurfaceGatherArgs,
    /// Bounds on the work asked for.
    #[command(flatten)]
    pub limits: LimitArgs,
}

impl ViewArgs {
    /// The solve these arguments ask for, checked.
    fn method(&self) -> Result<Method> {
        let solver = match self.solver {
            None => SolverKind::Hierarchical,
            Some(MethodKind::Radiosity(solver)) => solver,
            Some(other) => anyhow::bail!(
                "--solver {other}: the viewer shows a radiosity solution (matrix, progressive, \
                 hierarchical or hierarchical-shooting)"
            ),
        };
        let mut settings = self.radiosity.settings(solver, self.seed, &self.limits)?;
        settings.surface_gather = self.gather.settings();
        settings.check().map_err(|e| method_error(e.into()))?;
        Ok(Method::Radiosity(settings))
    }
}

/// Requests served at once.
const WORKERS: usize = 4;

/// How long a worker waits for a request before it looks at Ctrl-C again.
const POLL: Duration = Duration::from_millis(200);

/// Runs `strahl view`: solves, prints the address, serves until Ctrl-C.
pub fn run(args: &ViewArgs) -> Result<()> {
    let method = args.method()?;
    let scene = strahl::scene::open(&args.scene, &args.limits.load_options())?;
    let name = scene.name.clone();
    let world =
        World::new(scene, AccelKind::Bvh).with_context(|| format!("scene '{}'", args.scene))?;
    radiosity::warn_non_diffuse(&world.scene);
    let world = Arc::new(world);
    // Listening first: a port in use is refused before minutes of solving.
    let server = tiny_http::Server::http((args.bind, args.port)).map_err(|e| {
        anyhow::anyhow!(
            "cannot listen on {}:{}: {e} (--port 0 picks a free port)",
            args.bind,
            args.port
        )
    })?;
    let outcome = run_method(&world, &method, "solving", args.quiet, args.threads)?;
    if progress::interrupted() {
        return Ok(());
    }
    let solved = outcome
        .radiosity
        .as_ref()
        .context("the solver made no solution")?;
    radiosity::finish_solve(
        solved,
        args.radiosity.export.as_deref(),
        &Default::default(),
        args.quiet,
    )?;
    let measured = outcome
        .measurement
        .as_ref()
        .context("the solver measured no surfaces")?;
    let report = Report::new(&name, measured);
    let state = ViewState::new(solved, &report, args.shading)?;
    let address = server
        .server_addr()
        .to_ip()
        .context("the server has no IP address")?;
    println!("strahl view: http://{address}/ (Ctrl-C stops)");
    std::io::stdout().flush()?;
    let cancel = progress::cancel_flag();
    std::thread::scope(|scope| {
        for _ in 0..WORKERS {
            scope.spawn(|| {
                while !cancel.is_requested() {
                    match server.recv_timeout(POLL) {
                        Ok(Some(request)) => server::answer(request, &state),
                        Ok(None) => {}
                        Err(e) => {
                            eprintln!("warning: a request could not be read: {e}");
                        }
                    }
                }
            });
        }
    });
    Ok(())
}
