//! The viewer's solver, on a thread of its own: solves the scene as it is now (with every
//! move asked for so far) — a quick, coarser preview first where the solver has one, then
//! the solve asked for — and publishes each solution as a [`Snapshot`]. A move during a solve
//! stops it within a work unit and starts over from the moved scene; the progress of the
//! running solve is readable at any time.

use super::super::{progress, radiosity, thread_pool};
use super::snapshot::{Snapshot, Stage};
use anyhow::{Context, Result};
use glam::Vec3;
use serde::Serialize;
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::{Duration, Instant};
use strahl::method::{
    AccelKind, Cancel, KeptLinks, Method, ProgressListener, RoundSolution, Shading, SolverKind,
    SurfaceGather, World,
};
use strahl::report::Report;
use strahl::scene::{MoveError, Scene};

/// How much larger the preview's error threshold is than the final solve's.
const PREVIEW_COARSER: f64 = 16.0;

/// The least time between two solutions shown from rounds of a solve under way: a round
/// sooner after the last one shown is not shown (each costs the page a download and a
/// redraw, on the cores the solve runs on).
const ROUND_INTERVAL: Duration = Duration::from_millis(250);

/// What the solver is doing, for `/api/status`.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Status {
    /// The latest solution's version (0: none yet).
    pub version: u64,
    /// The version whose mesh, lightmaps and links it shows (an earlier one when only its
    /// report is new).
    pub mesh_version: u64,
    /// Its stage.
    pub stage: Option<Stage>,
    /// Moves asked for so far.
    pub moves: u64,
    /// Moves the latest solution was solved with.
    pub solved_moves: u64,
    /// Whether a solve runs.
    pub solving: bool,
    /// Its phase, work units done and in all (0: not known).
    pub phase: String,
    pub done: u64,
    pub total: u64,
    /// Why the last solve failed, if it did.
    pub error: Option<String>,
    /// Seconds from the last move to its preview, to its final solve (shown with the
    /// solution's own report while the final gather at the reported surfaces runs; absent
    /// when there is none) and to its final solution being served (absent until served).
    pub preview_seconds: Option<f64>,
    pub solved_seconds: Option<f64>,
    pub final_seconds: Option<f64>,
    /// Links the latest solve took from the solve before (where nothing moved between their
    /// ends) and computed: patch links (hierarchical) or couplings between two elements
    /// (matrix).
    pub links_kept: u64,
    pub links_computed: u64,
}

/// How a move places what it moves (scene units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Move {
    /// By this offset.
    By(Vec3),
    /// So that its position (`Scene::position_of`: an object's centre, a light's place) is
    /// this point.
    To(Vec3),
}

/// The solver's state, shared with the requests.
struct State {
    /// The scene with every move so far.
    scene: Scene,
    /// The latest solution, or solution between rounds.
    snapshot: Option<Arc<Snapshot>>,
    /// The latest whole solution (what picks read).
    readable: Option<Arc<Snapshot>>,
    /// When a solution was last shown.
    shown_at: Instant,
    /// Stops the running solve.
    cancel: Arc<Cancel>,
    /// When the last move came.
    moved_at: Option<Instant>,
    /// The moves the running (or last) solve started from.
    started_moves: Option<u64>,
    shutdown: bool,
    status: Status,
}

/// The solver and its latest solution.
pub struct Solving {
    /// The final solve.
    method: Method,
    /// The threads every solve and gather runs on (one pool for the viewer's life: a pool
    /// started for each stage cost the preview after a move about 5 ms of the Cornell box's 30).
    pool: rayon::ThreadPool,
    shading: Shading,
    quiet: bool,
    /// Where to export the first final solution.
    export: Option<PathBuf>,
    state: Mutex<State>,
    /// Wakes the solver thread: a move, or the end.
    work: Condvar,
    /// Wakes the requests waiting for news: a solution, a failure, the end.
    news: Condvar,
    /// Work units of the running phase done and in all (atomic: every worker thread adds).
    done: AtomicU64,
    total: AtomicU64,
    /// The patch links of the last solve, for the next (only the solver thread takes it).
    kept: Mutex<KeptLinks>,
}

impl Solving {
    /// A solver of `scene` by `method` (radiosity) on `threads` threads (0: one per core),
    /// its solutions read by `shading`; the first final solution is exported to `export`.
    pub fn new(
        scene: Scene,
        method: Method,
        threads: usize,
        shading: Shading,
        quiet: bool,
        export: Option<PathBuf>,
    ) -> Result<Self> {
        Ok(Solving {
            method,
            pool: thread_pool(threads)?,
            shading,
            quiet,
            export,
            state: Mutex::new(State {
                scene,
                snapshot: None,
                readable: None,
                shown_at: Instant::now(),
                cancel: Arc::new(Cancel::new()),
                moved_at: None,
                started_moves: None,
                shutdown: false,
                status: Status::default(),
            }),
            work: Condvar::new(),
            news: Condvar::new(),
            done: AtomicU64::new(0),
            total: AtomicU64::new(0),
            kept: Mutex::new(KeptLinks::new()),
        })
    }

    fn lock(&self) -> MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The latest solution (or solution between rounds), if any.
    pub fn snapshot(&self) -> Option<Arc<Snapshot>> {
        self.lock().snapshot.clone()
    }

    /// The scene as it is now, with the number of moves it includes.
    pub fn scene(&self) -> (Scene, u64) {
        let state = self.lock();
        (state.scene.clone(), state.status.moves)
    }

    /// The latest whole solution, if any.
    pub fn readable(&self) -> Option<Arc<Snapshot>> {
        self.lock().readable.clone()
    }

    /// The final solution of the scene as it is now (every move solved), if it is there
    /// (its report may still be being gathered: the light is the same).
    pub fn final_solution(&self) -> Option<Arc<Snapshot>> {
        let state = self.lock();
        let status = &state.status;
        let last = matches!(status.stage, Some(Stage::Solved | Stage::Final));
        let current = last && status.solved_moves == status.moves;
        state.readable.clone().filter(|_| current)
    }

    /// Shows `snapshot` (made as version `version` of `stage` after `moves` moves), unless
    /// a move came since.
    fn publish(&self, snapshot: Arc<Snapshot>, version: u64, stage: Stage, moves: u64) {
        let mut state = self.lock();
        if state.status.moves != moves {
            return;
        }
        let since_move = state.moved_at.map(|t| t.elapsed().as_secs_f64());
        let status = &mut state.status;
        status.version = version;
        status.mesh_version = snapshot.mesh_version();
        status.stage = Some(stage);
        status.solved_moves = moves;
        status.error = None;
        match stage {
            Stage::Round => {}
            Stage::Preview => status.preview_seconds = since_move,
            Stage::Solved => status.solved_seconds = since_move,
            Stage::Final => status.final_seconds = since_move,
        }
        if snapshot.readable() {
            state.readable = Some(Arc::clone(&snapshot));
        }
        state.snapshot = Some(snapshot);
        state.shown_at = Instant::now();
        self.news.notify_all();
    }

    /// The next version to show.
    fn next_version(&self) -> u64 {
        self.lock().status.version + 1
    }

    /// The status and the latest solution (or solution between rounds) now, or — when the
    /// latest solution is `version` and nothing changes — after at most `wait`; the two read
    /// together (the solution is the status's version).
    pub fn news_after(
        &self,
        version: Option<u64>,
        wait: Duration,
    ) -> (Status, Option<Arc<Snapshot>>) {
        let until = Instant::now() + wait;
        let mut state = self.lock();
        while version == Some(state.status.version) && !state.shutdown {
            let left = until.saturating_duration_since(Instant::now());
            if left.is_zero() || progress::cancel_flag().is_requested() {
                break;
            }
            // Short waits: Ctrl-C is seen within one.
            let slice = left.min(Duration::from_millis(200));
            state = self
                .news
                .wait_timeout(state, slice)
                .unwrap_or_else(|e| e.into_inner())
                .0;
        }
        let mut status = state.status.clone();
        status.done = self.done.load(Ordering::Relaxed);
        status.total = self.total.load(Ordering::Relaxed);
        (status, state.snapshot.clone())
    }

    /// Moves the object or light `name` as `how` says and starts solving the moved scene
    /// (stopping a solve under way). Returns the moves asked for so far.
    pub fn move_named(&self, name: &str, how: Move) -> Result<u64, MoveError> {
        let mut state = self.lock();
        match how {
            Move::By(by) => state.scene.move_named(name, by)?,
            Move::To(to) => state.scene.move_named_to(name, to)?,
        };
        state.status.moves += 1;
        state.moved_at = Some(Instant::now());
        state.status.preview_seconds = None;
        state.status.solved_seconds = None;
        state.status.final_seconds = None;
        state.cancel.request();
        self.work.notify_all();
        Ok(state.status.moves)
    }

    /// Stops the running solve and the solver thread.
    pub fn shut_down(&self) {
        let mut state = self.lock();
        state.shutdown = true;
        state.cancel.request();
        self.work.notify_all();
        self.news.notify_all();
    }

    /// The solver thread: solves whenever the scene has moves not yet solved (the first time
    /// at once), until [`Solving::shut_down`].
    pub fn run(&self) {
        let mut first = true;
        loop {
            let (scene, moves, cancel) = {
                let mut state = self.lock();
                while !state.shutdown && state.started_moves == Some(state.status.moves) {
                    state = self.work.wait(state).unwrap_or_else(|e| e.into_inner());
                }
                if state.shutdown {
                    return;
                }
                state.cancel = Arc::new(Cancel::new());
                state.started_moves = Some(state.status.moves);
                state.status.solving = true;
                // The first round shown comes an interval after the solve starts: a quick
                // solve shows its preview first.
                state.shown_at = Instant::now();
                (
                    state.scene.clone(),
                    state.status.moves,
                    state.cancel.clone(),
                )
            };
            let solved = self.solve(scene, moves, &cancel, first);
            let mut state = self.lock();
            state.status.solving = false;
            match solved {
                Ok(()) => first = false,
                Err(e) => state.status.error = Some(format!("{e:#}")),
            }
            self.news.notify_all();
        }
    }

    /// The stages of a solve: a preview where the solver refines by an error threshold, then
    /// the solve asked for — without its final gather at the reported surfaces, when it has
    /// one, which then follows over the solution shown (see [`Solving::gathered`]).
    fn stages(&self) -> Vec<(Stage, Method)> {
        let mut stages = Vec::new();
        match &self.method {
            Method::Radiosity(settings) => {
                if settings.solver == SolverKind::Hierarchical {
                    let mut preview = *settings;
                    preview.hierarchical.error *= PREVIEW_COARSER;
                    preview.surface_gather = SurfaceGather::OFF;
                    stages.push((Stage::Preview, Method::Radiosity(preview)));
                }
                if settings.surface_gather.is_on() {
                    let solved = settings.without_surface_gather();
                    stages.push((Stage::Solved, Method::Radiosity(solved)));
                } else {
                    stages.push((Stage::Final, self.method.clone()));
                }
            }
            _ => stages.push((Stage::Final, self.method.clone())),
        }
        stages
    }

    /// Solves `scene` (after `moves` moves) stage by stage, publishing each solution, until
    /// done or `cancel`led. The first solve shows a bar on the terminal and exports.
    fn solve(&self, scene: Scene, moves: u64, cancel: &Cancel, first: bool) -> Result<()> {
        let name = scene.name.clone();
        let world = Arc::new(World::new(scene, AccelKind::Bvh).context("the moved scene")?);
        let bar = progress::Bar::new("solving", self.quiet || !first);
        for (stage, method) in self.stages() {
            let observer = Observer {
                solving: self,
                bar: &bar,
                scene: &world.scene,
                moves,
            };
            // Links kept from the solve before wherever the moves did not reach them (and the
            // matrix solver's solution to start from): the same solution as without, within
            // the matrix solver's tolerance, in less time (`method::run_keeping`).
            let mut kept =
                std::mem::take(&mut *self.kept.lock().unwrap_or_else(|e| e.into_inner()));
            let outcome = self.pool.install(|| {
                strahl::method::run_keeping(&world, &method, &observer, cancel, &mut kept)
            });
            let links = (kept.reused(), kept.computed());
            *self.kept.lock().unwrap_or_else(|e| e.into_inner()) = kept;
            let outcome = outcome.map_err(radiosity::method_error)?;
            if cancel.is_requested() {
                return Ok(());
            }
            let solved = outcome.radiosity.context("the solver made no solution")?;
            let measured = outcome
                .measurement
                .as_ref()
                .context("the solver measured no surfaces")?;
            if first && stage != Stage::Preview {
                radiosity::finish_solve(
                    &solved,
                    self.export.as_deref(),
                    &Default::default(),
                    self.quiet,
                )?;
            }
            let report = Report::new(&name, measured);
            let version = self.next_version();
            let snapshot = Snapshot::new(version, moves, stage, solved, &report, self.shading)?;
            let snapshot = Arc::new(snapshot);
            // The counts first: a page that sees the solution reads its counts with it.
            {
                let status = &mut self.lock().status;
                (status.links_kept, status.links_computed) = links;
            }
            if stage == Stage::Solved {
                self.gathered(snapshot, version, &name, &observer, cancel)?;
            } else {
                self.publish(snapshot, version, stage, moves);
            }
            // The links kept merged once the solution is out (on the Cornell box about 10 ms
            // after the final solve).
            self.kept.lock().unwrap_or_else(|e| e.into_inner()).settle();
        }
        Ok(())
    }

    /// The final gather at the reported surfaces over `solved`, the final solve with its
    /// solution's own report (version `version`, stage [`Stage::Solved`]), and the solution
    /// shown with the gathered report as the final one; `progress` hears the gather. When
    /// the gather takes longer than [`ROUND_INTERVAL`], the solve is shown while it runs (on
    /// `blocks:216` the gather takes most of a move's time; on the Cornell box, a few
    /// hundredths of a second, showing the solve first would only make the page draw it
    /// twice).
    fn gathered(
        &self,
        solved: Arc<Snapshot>,
        version: u64,
        name: &str,
        progress: &Observer,
        cancel: &Cancel,
    ) -> Result<()> {
        let Method::Radiosity(settings) = &self.method else {
            return Ok(());
        };
        let solution = solved
            .solved()
            .context("the solve made no whole solution")?;
        progress.phase("gathering");
        let seed = settings.system.visibility.seed;
        let gathered = std::thread::scope(|scope| {
            let (done, finished) = std::sync::mpsc::channel();
            scope.spawn(move || {
                let gathered = self.pool.install(|| {
                    solution.gathered_measurement(settings.surface_gather, seed, progress, cancel)
                });
                // The receiver waits until this is sent: it cannot be gone.
                let _ = done.send(gathered);
            });
            if let Ok(gathered) = finished.recv_timeout(ROUND_INTERVAL) {
                return Ok(gathered);
            }
            self.publish(Arc::clone(&solved), version, Stage::Solved, solved.moves());
            finished.recv().context("the final gather stopped")
        })?;
        let Some((measurement, phrase)) = gathered.filter(|_| !cancel.is_requested()) else {
            return Ok(());
        };
        let report = Report::new(name, &measurement);
        let version = self.next_version();
        let snapshot = solved.with_report(version, &report, solution.summary() + &phrase)?;
        self.publish(Arc::new(snapshot), version, Stage::Final, solved.moves());
        Ok(())
    }
}

/// Hands a solve's progress to the status (and the terminal's bar), and its solutions
/// between rounds to the page.
struct Observer<'a> {
    solving: &'a Solving,
    bar: &'a progress::Bar,
    /// The scene solved, after `moves` moves.
    scene: &'a Scene,
    moves: u64,
}

impl ProgressListener for Observer<'_> {
    fn phase(&self, name: &str) {
        self.bar.phase(name);
        self.solving.lock().status.phase = name.to_string();
        self.solving.done.store(0, Ordering::Relaxed);
        self.solving.total.store(0, Ordering::Relaxed);
    }
    fn start(&self, total: u64) {
        self.bar.start(total);
        self.solving.done.store(0, Ordering::Relaxed);
        self.solving.total.store(total, Ordering::Relaxed);
    }
    fn estimate(&self, total: u64) {
        self.bar.estimate(total);
        self.solving.total.store(total, Ordering::Relaxed);
    }
    fn advance(&self, units: u64) {
        self.bar.advance(units);
        self.solving.done.fetch_add(units, Ordering::Relaxed);
    }
    fn finish(&self) {
        self.bar.finish();
    }
    fn wants_rounds(&self) -> bool {
        self.solving.lock().shown_at.elapsed() >= ROUND_INTERVAL
    }
    fn round(&self, solution: &RoundSolution) {
        let version = self.solving.next_version();
        let made = Snapshot::round(version, self.moves, self.scene, solution);
        match made {
            Ok(snapshot) => {
                self.solving
                    .publish(Arc::new(snapshot), version, Stage::Round, self.moves)
            }
            Err(e) => self.solving.lock().status.error = Some(format!("{e:#}")),
        }
    }
}
