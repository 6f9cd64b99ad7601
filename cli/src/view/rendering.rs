//! Renders the viewer's current view by path tracing or by final gathering over the final
//! solution, on a thread of its own: pass after pass, each of [`SAMPLES_PER_PASS`] paths (or
//! [`GATHER_SAMPLES_PER_PASS`] final gathers of [`GATHER_RAYS`] rays) per pixel with a seed of
//! its own, the running mean of the passes served as a PNG after each, so that the page shows
//! the image as it refines. A new render (or a move) stops the one under way.
//!
//! Renders and moves are ordered by the scene's move count: a move stops a render of a scene
//! with fewer moves, and a render asked for a scene with fewer moves than one already seen is
//! refused (its scene was taken before a move that has stopped renders since).

use super::super::with_threads;
use super::snapshot::Snapshot;
use anyhow::{Context, Result};
use serde::Serialize;
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use strahl::image::{ToneMap, ToneMapping, encode_png};
use strahl::method::{
    AccelKind, Cancel, Film, FinalGatherSettings, ImageSize, Method, NoProgress, PathTraceSettings,
    World,
};
use strahl::scene::{Camera, Scene};

/// Paths per pixel of one pass of the path tracer.
pub const SAMPLES_PER_PASS: u32 = 4;

/// Camera samples per pixel of one pass of the final gather: each costs [`GATHER_RAYS`]
/// gather rays and the shadow rays of [`FinalGatherSettings::default`], so that the first
/// image comes soon (measured on the Cornell box at 512 × 512 on two cores: a pass 0.8 s,
/// against 9.7 s for 4 samples of 64 gather rays and 0.35 s for the path tracer's 4 paths).
pub const GATHER_SAMPLES_PER_PASS: u32 = 1;

/// Gather rays per camera sample of the final gather (a pass's image is noisier than one of
/// the default 64, the mean of the passes the same).
pub const GATHER_RAYS: u32 = 16;

/// Passes of a render: it stops at `MAX_PASSES` times a pass's samples per pixel.
pub const MAX_PASSES: u32 = 256;

/// Most pixels a render may have (a 4K view).
pub const MAX_PIXELS: u32 = 3840 * 2160;

/// What the renderer is doing, for `GET /api/render`.
#[derive(Clone, Debug, Default, Serialize)]
pub struct RenderStatus {
    /// Counts the renders asked for (0: none yet).
    pub render: u64,
    /// Passes in the image served, and paths per pixel.
    pub passes: u32,
    pub samples_per_pixel: u32,
    /// Whether passes are being added.
    pub running: bool,
    /// Why the render failed, if it did.
    pub error: Option<String>,
}

/// What a render shows: a scene, path-traced, or a final solution of the scene as it is
/// now, final-gathered.
pub enum Source {
    /// The scene, every move included.
    PathTrace(Box<Scene>),
    /// A final solution (a snapshot whose solution is whole).
    FinalGather(Arc<Snapshot>),
}

/// Why a render was not started.
#[derive(Debug)]
pub enum Refused {
    /// The size asked for is none or too large.
    Size(String),
    /// The scene moved after the render's source was taken.
    Moved,
}

/// A render asked for: `source` seen through `camera` at its size.
struct Job {
    source: Source,
    camera: Camera,
}

struct State {
    job: Option<Job>,
    /// The mean of the passes so far, as a PNG.
    png: Option<Arc<Vec<u8>>>,
    cancel: Arc<Cancel>,
    status: RenderStatus,
    /// The most moves of a scene rendered or stopped for.
    moves: u64,
    shutdown: bool,
}

/// The renderer and its latest image.
pub struct Rendering {
    threads: usize,
    state: Mutex<State>,
    work: Condvar,
}

impl Rendering {
    /// A renderer on `threads` threads (0: one per core).
    pub fn new(threads: usize) -> Self {
        Rendering {
            threads,
            state: Mutex::new(State {
                job: None,
                png: None,
                cancel: Arc::new(Cancel::new()),
                status: RenderStatus::default(),
                moves: 0,
                shutdown: false,
            }),
            work: Condvar::new(),
        }
    }

    fn lock(&self) -> MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Starts rendering `source` (the scene after `moves` moves) through `camera`
    /// (`width × height` pixels), stopping the render under way. Returns the render's number.
    pub fn start(&self, source: Source, camera: Camera, moves: u64) -> Result<u64, Refused> {
        let pixels = u64::from(camera.width) * u64::from(camera.height);
        if camera.width == 0 || camera.height == 0 || pixels > u64::from(MAX_PIXELS) {
            return Err(Refused::Size(format!(
                "a render is 1 to {MAX_PIXELS} pixels ({} × {} asked for)",
                camera.width, camera.height
            )));
        }
        let mut state = self.lock();
        if moves < state.moves {
            return Err(Refused::Moved);
        }
        state.moves = moves;
        state.cancel.request();
        state.job = Some(Job { source, camera });
        state.png = None;
        state.status = RenderStatus {
            render: state.status.render + 1,
            running: true,
            ..RenderStatus::default()
        };
        self.work.notify_all();
        Ok(state.status.render)
    }

    /// Stops the render under way if it shows the scene with fewer than `moves` moves (a
    /// move makes its image stale); renders of such a scene asked for later are refused.
    pub fn stop(&self, moves: u64) {
        let mut state = self.lock();
        if moves > state.moves {
            state.moves = moves;
            state.cancel.request();
            state.job = None;
        }
    }

    /// The status now.
    pub fn status(&self) -> RenderStatus {
        self.lock().status.clone()
    }

    /// The latest image, a PNG.
    pub fn png(&self) -> Option<Arc<Vec<u8>>> {
        self.lock().png.clone()
    }

    /// Stops the render under way and the renderer's thread.
    pub fn shut_down(&self) {
        let mut state = self.lock();
        state.shutdown = true;
        state.cancel.request();
        self.work.notify_all();
    }

    /// The renderer's thread: renders each job asked for until [`Rendering::shut_down`].
    pub fn run(&self) {
        loop {
            let (job, cancel, render) = {
                let mut state = self.lock();
                while !state.shutdown && state.job.is_none() {
                    state = self.work.wait(state).unwrap_or_else(|e| e.into_inner());
                }
                let Some(job) = state.job.take().filter(|_| !state.shutdown) else {
                    return;
                };
                state.cancel = Arc::new(Cancel::new());
                (job, Arc::clone(&state.cancel), state.status.render)
            };
            let rendered = self.render(job, &cancel, render);
            let mut state = self.lock();
            if state.status.render == render {
                state.status.running = false;
                if let Err(e) = rendered {
                    state.status.error = Some(format!("{e:#}"));
                }
            }
        }
    }

    /// Renders `job` (render number `render`) pass after pass until done or `cancel`led.
    fn render(&self, job: Job, cancel: &Cancel, render: u64) -> Result<()> {
        match job.source {
            Source::FinalGather(snapshot) => {
                let solved = snapshot
                    .solved()
                    .context("the solution is not a whole one")?;
                let gather = FinalGatherSettings::default();
                let view = solved
                    .final_gather_view(
                        &job.camera,
                        gather.shading,
                        gather.light_samples,
                        GATHER_RAYS,
                    )
                    .context("the view")?;
                self.passes(render, cancel, GATHER_SAMPLES_PER_PASS, |pass| {
                    let seed = u64::from(pass);
                    with_threads(self.threads, || {
                        view.render(GATHER_SAMPLES_PER_PASS, seed, cancel)
                    })
                })
            }
            Source::PathTrace(mut scene) => {
                scene.camera = job.camera.clone();
                let world = Arc::new(World::new(*scene, AccelKind::Bvh).context("the view")?);
                self.passes(render, cancel, SAMPLES_PER_PASS, |pass| {
                    let method = Method::PathTrace(PathTraceSettings {
                        size: ImageSize {
                            width: Some(job.camera.width),
                            height: Some(job.camera.height),
                        },
                        seed: u64::from(pass),
                        samples_per_pixel: SAMPLES_PER_PASS,
                        ..PathTraceSettings::default()
                    });
                    let outcome = with_threads(self.threads, || {
                        strahl::method::run(&world, &method, &NoProgress, cancel)
                    })?
                    .map_err(|e| anyhow::anyhow!("{e}"))?;
                    Ok(outcome.image.filter(|_| outcome.complete))
                })
            }
        }
    }

    /// Renders passes of `samples` camera samples per pixel by `pass` (its image, `None`
    /// when stopped) until [`MAX_PASSES`] or `cancel`, serving the running mean after each.
    fn passes(
        &self,
        render: u64,
        cancel: &Cancel,
        samples: u32,
        pass_image: impl Fn(u32) -> Result<Option<Film>>,
    ) -> Result<()> {
        let mut mean: Option<Film> = None;
        for pass in 0..MAX_PASSES {
            let Some(film) = pass_image(pass)?.filter(|_| !cancel.is_requested()) else {
                return Ok(());
            };
            let count = pass as f32 + 1.0;
            let mean = match &mut mean {
                Some(mean) => {
                    for (m, p) in mean.pixels_mut().iter_mut().zip(film.pixels()) {
                        *m += (*p - *m) / count;
                    }
                    mean
                }
                None => mean.insert(film),
            };
            let tone = ToneMapping {
                operator: ToneMap::Auto,
                exposure_ev: 0.0,
            };
            let png = Arc::new(encode_png(mean, &tone)?);
            let mut state = self.lock();
            if state.status.render != render {
                return Ok(());
            }
            state.png = Some(png);
            state.status.passes = pass + 1;
            state.status.samples_per_pixel = (pass + 1) * samples;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn asked(rendering: &Rendering, moves: u64) -> Result<u64, Refused> {
        let scene = strahl::scene::open("cornell", &Default::default()).unwrap();
        let camera = scene.camera.clone();
        rendering.start(Source::PathTrace(Box::new(scene)), camera, moves)
    }

    #[test]
    fn a_render_of_the_scene_before_a_move_is_refused_and_one_after_it_is_not_stopped() {
        let rendering = Rendering::new(1);
        assert_eq!(asked(&rendering, 0).unwrap(), 1);
        // The move stops the render of the scene without it...
        rendering.stop(1);
        assert!(rendering.lock().job.is_none());
        assert!(rendering.lock().cancel.is_requested());
        // ...and a render asked with the scene taken before the move is refused.
        assert!(matches!(asked(&rendering, 0), Err(Refused::Moved)));
        // The scene taken after the move renders, and the move's own stop, coming after
        // that render was asked for, leaves it running.
        assert_eq!(asked(&rendering, 2).unwrap(), 2);
        rendering.stop(2);
        assert!(rendering.lock().job.is_some());
        assert_eq!(rendering.status().render, 2);
    }
}
