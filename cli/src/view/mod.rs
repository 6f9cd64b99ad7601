//! `strahl view`: solves a scene by radiosity and serves the solution to a browser on this
//! machine — the mesh lit by the solution (orbit, pan, zoom, wireframe, exposure) and the
//! illuminance anywhere on it, with the object's report row, by a click.

mod rendering;
mod server;
mod snapshot;
mod solving;

use super::choice::{choice, choice_among};
use super::limits::LimitArgs;
use super::progress;
use super::radiosity::{self, RadiosityArgs, SurfaceGatherArgs, method_error};
use anyhow::{Context, Result};
use clap::Args;
use rendering::Rendering;
use solving::Solving;
use std::io::Write;
use std::net::IpAddr;
use std::time::Duration;
use strahl::method::{AccelKind, Method, MethodKind, Shading, SolverKind, World};

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
        // The page shows the hierarchical solvers' links.
        settings.hierarchical.link_segments = true;
        settings.check().map_err(|e| method_error(e.into()))?;
        Ok(Method::Radiosity(settings))
    }
}

/// The viewer's two workers: the solver and the renderer of views.
pub struct Viewer {
    solving: Solving,
    rendering: Rendering,
}

/// Requests served at once (a page holds one while it waits for the next solution).
const WORKERS: usize = 8;

/// How long a worker waits for a request before it looks at Ctrl-C again.
const POLL: Duration = Duration::from_millis(200);

/// Runs `strahl view`: prints the address, serves at once (the page shows the solve's
/// progress), solves on a thread of its own — again after every move — until Ctrl-C.
pub fn run(args: &ViewArgs) -> Result<()> {
    let method = args.method()?;
    let scene = strahl::scene::open(&args.scene, &args.limits.load_options())?;
    // Checked here, so that a scene that cannot be compiled fails before anything is served.
    World::new(scene.clone(), AccelKind::Bvh).with_context(|| format!("scene '{}'", args.scene))?;
    radiosity::warn_non_diffuse(&scene, MethodKind::RadiosityImage);
    let server = match server::listen(args.bind, args.port) {
        Ok(listener) => tiny_http::Server::from_listener(listener, None),
        Err(e) => Err(e.into()),
    }
    .map_err(|e| {
        anyhow::anyhow!(
            "cannot listen on {}:{}: {e} (--port 0 picks a free port)",
            args.bind,
            args.port
        )
    })?;
    let address = server
        .server_addr()
        .to_ip()
        .context("the server has no IP address")?;
    let viewer = Viewer {
        solving: Solving::new(
            scene,
            method,
            args.threads,
            args.shading,
            args.quiet,
            args.radiosity.export.clone(),
        )?,
        rendering: Rendering::new(args.threads),
    };
    println!("strahl view: http://{address}/ (Ctrl-C stops)");
    std::io::stdout().flush()?;
    let cancel = progress::cancel_flag();
    std::thread::scope(|scope| {
        scope.spawn(|| viewer.solving.run());
        scope.spawn(|| viewer.rendering.run());
        let workers: Vec<_> = (0..WORKERS)
            .map(|_| {
                scope.spawn(|| {
                    while !cancel.is_requested() {
                        match server.recv_timeout(POLL) {
                            Ok(Some(request)) => server::answer(request, &viewer),
                            Ok(None) => {}
                            Err(e) => {
                                eprintln!("warning: a request could not be read: {e}");
                            }
                        }
                    }
                })
            })
            .collect();
        for worker in workers {
            let _ = worker.join();
        }
        viewer.solving.shut_down();
        viewer.rendering.shut_down();
    });
    Ok(())
}
