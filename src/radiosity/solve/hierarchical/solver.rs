//! The hierarchical solve: initial linking, then rounds of gathering, push-pull and
//! refinement until no link is refined (the steps of the module documentation).

use super::cluster_gather::GatherPlan;
use super::clusters::{ClusterLink, ClusterTree, End, Split};
use super::fine_gather::FineGather;
use super::importance::Importance;
use super::kept::KeptView;
use super::links::{LightLink, Link, Linker, Prior};
use super::near_rays::{NearRays, REFERENCE_SHARE};
use super::nodes::{Nodes, node, split_node};
use super::oracle::{Decision, Limits, decide, decide_light};
use super::{HierarchicalSettings, RefinePass};
use crate::choice::Choice;
use crate::color::Rgb64;
use crate::measure::{LitMesh, RoundSolution, peak_resident_bytes};
use crate::progress::{Cancel, ProgressListener};
use crate::radiosity::element::Side;
use crate::radiosity::light_links::exact_shadows;
use crate::radiosity::mesh::{PatchId, PatchMesh};
use crate::radiosity::solve::KeptLinks;
use crate::radiosity::solve::UNEVEN_RUN;
use crate::radiosity::solve::far_field::FarField;
use crate::radiosity::solve::steady_state::{Bounce, BounceWatch};
use crate::radiosity::solve::{
    LinkSegment, PhaseTimes, RadiositySystem, RoundStats, Solution, SolveError, SolverKind,
    SystemOptions,
};
use crate::radiosity::surface::is_textured;
use crate::radiosity::visibility::Visibility;
use crate::scene::LightKind;
use crate::world::World;
use glam::Vec3;
use rayon::prelude::*;
use std::ops::Range;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// Gathers per round at most (each is one bounce of light).
const MAX_GATHERS: u32 = 1000;

/// About the links per chunk of a parallel gather ([`Solver::gather_from`]); the chunks
/// depend on the link count alone, so that the sums do not depend on the number of threads
/// (fewer links are one chunk, in link order).
const GATHER_CHUNK: usize = 1 << 15;

/// Bytes the chunks' sums of one gather may hold together; and the cluster links' gathers
/// worked out for a round ([`GatherPlan`]).
const GATHER_BYTES: usize = 256 << 20;

/// Bytes a side of a [`GatherPlan`] takes: its node and its weight.
const PLANNED_SIDE_BYTES: usize = 12;

/// Cluster links a [`GatherPlan`] holds at most: a chunk's links are worked out in pieces of
/// this many, in parallel (links between large clusters cost more and come in runs).
const PLAN_PIECE: usize = 4096;

/// The cluster links' gathers worked out, per chunk of a gather its pieces in link order;
/// they hold while the cluster links stay as they are and the gather's chunks are `shape`.
struct GatherPlans {
    /// The gather's chunks (number, links per chunk) the plans follow.
    shape: (usize, usize),
    chunks: Vec<Vec<GatherPlan>>,
}

/// More chunks than this in a gather are rounded down to a multiple of it, so that threads
/// that divide it share them evenly (`canopy:3000`'s 9 chunks kept one of two threads
/// waiting for the ninth).
const GATHER_SHARES: usize = 4;

/// The chunks a gather over `links` links into `nodes` nodes is cut into: about one per
/// [`GATHER_CHUNK`] links (rounded to [`GATHER_SHARES`]), as many as [`GATHER_BYTES`]
/// allows (at least one). Depends on the problem alone, never on the thread count.
fn gather_chunks(links: usize, nodes: usize) -> usize {
    let by_memory = GATHER_BYTES / (nodes.max(1) * std::mem::size_of::<Rgb64>());
    let chunks = links.div_ceil(GATHER_CHUNK);
    let shared = if chunks > GATHER_SHARES {
        chunks - chunks % GATHER_SHARES
    } else {
        chunks
    };
    shared.min(by_memory).max(1)
}

/// What one pass of [`Solver::apply`] did.
#[derive(Clone, Copy, Debug, Default)]
struct Applied {
    /// Links created (not counting those computed anew).
    created: u64,
    /// Links refined.
    refined: u64,
    /// Blocked links computed anew with more rays.
    looked: u64,
}

/// The state of a solve (shared with hierarchical shooting, which uses the nodes, the light
/// links and the linker but keeps no patch links).
pub(super) struct Solver<'w, 'v> {
    pub(super) world: &'w Arc<World>,
    pub(super) mesh: PatchMesh,
    pub(super) nodes: Nodes,
    links: Vec<Link>,
    light_links: Vec<LightLink>,
    clusters: Option<ClusterTree>,
    cluster_links: Vec<ClusterLink>,
    /// The near field by rays, in scenes of many root patches.
    near: Option<NearRays>,
    /// Cluster links whose ends are too close for the cluster transport, carried by `near`
    /// (receiver, emitter).
    near_links: Vec<(End, End)>,
    /// What the endless field beyond the margin of an unrolled periodic world sends.
    pub(super) far: Option<FarField>,
    pub(super) linker: Linker<'v>,
    pub(super) limits: Limits,
    /// The chunks' sums of the last gather, kept for the next one.
    gather_sums: std::sync::Mutex<Vec<Vec<Rgb64>>>,
    /// The cluster links' gathers worked out ([`GatherPlans`]); dropped whenever the cluster
    /// links change.
    gather_plans: Option<GatherPlans>,
    /// How much the light each node receives matters to the reported surfaces.
    pub(super) importance: Importance,
    /// The emitters' pieces of the final gather, once refinement is done.
    fine: Option<FineGather>,
    pub(super) settings: HierarchicalSettings,
    /// The links kept from the solve before, and those this one makes (`kept.rs`).
    kept: Option<KeptView>,
}

/// The root patches of `world`'s scene meshed by `options`, and the visibility estimator
/// for links between their nodes (its rays seeded by what the patches are where
/// `by_geometry`, as links kept between solves need: [`Visibility::seeded_by_geometry`]).
pub(super) fn prepare(
    world: &Arc<World>,
    options: &SystemOptions,
    by_geometry: bool,
) -> Result<(PatchMesh, Arc<Visibility>), SolveError> {
    let mesh = PatchMesh::from_scene(&world.scene, &options.mesh)?;
    if mesh.roots.is_empty() {
        return Err(SolveError::NoPatches);
    }
    let visibility = Visibility::new(world, options.visibility, options.mesh.segments)?;
    let visibility = if by_geometry {
        visibility.seeded_by_geometry()
    } else {
        visibility
    };
    Ok((mesh, Arc::new(visibility)))
}

/// Solves `world`'s scene by hierarchical radiosity: the mesh (roots, contact splits and any
/// initial subdivision) and the visibility and light-link settings come from `options`.
/// `progress` names the phases (`meshing`, `linking lights`, `far-field rays` for a periodic
/// plot, `linking`, `near-field rays` and `linking clusters` where the near field is cast,
/// `solving`) and counts the pairs of
/// root side and light linked, the root patches that cast their rays and the rounds, whose
/// number it estimates as refinement settles; `cancel` stops after the current gather or
/// refinement pass (or within the linking of lights or the ray cast) and keeps the state
/// reached. Returns the system on the final leaves and its solution.
pub fn solve_hierarchical(
    world: &Arc<World>,
    options: SystemOptions,
    settings: &HierarchicalSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<(RadiositySystem, Solution), SolveError> {
    solve_hierarchical_keeping(world, options, settings, progress, cancel, None)
}

/// [`solve_hierarchical`], taking the patch links `kept` from the solve before where
/// nothing moved between their ends and keeping this solve's for the next (`kept.rs`): the
/// same solution, bit for bit, as this solve with no links kept, in less time. Its rays are
/// seeded by what the patches are, not by their indices ([`Visibility::seeded_by_geometry`]):
/// as accurate as [`solve_hierarchical`]'s solution, not the same bit for bit.
pub fn solve_hierarchical_keeping(
    world: &Arc<World>,
    options: SystemOptions,
    settings: &HierarchicalSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
    mut kept: Option<&mut KeptLinks>,
) -> Result<(RadiositySystem, Solution), SolveError> {
    let start = Instant::now();
    progress.phase("meshing");
    progress.start(0);
    let (mesh, visibility) = prepare(world, &options, kept.is_some())?;
    let mut solver = Solver::new(world, mesh, &visibility, &options, settings);
    if let Some(kept) = kept.as_deref_mut() {
        kept.last_matrix = false;
        let view = (kept.patch_links).begin(&world.scene, &options, &solver.mesh, &visibility);
        solver.kept = Some(view);
    }
    progress.finish();
    let setup = start.elapsed().as_secs_f64();
    let mut rounds: Vec<RoundStats> = Vec::new();
    let mut times = PhaseTimes {
        setup,
        ..PhaseTimes::default()
    };
    let t = Instant::now();
    // The lights first: the cluster links are judged by the radiosity the direct light
    // gives, not by the emission alone (zero on every surface a point light or the sky lights).
    progress.phase("linking lights");
    solver.link_root_lights(progress, cancel);
    progress.finish();
    solver.nodes.push_pull(&solver.mesh);
    solver.cast_far_field(progress, cancel);
    solver.link_root_pairs(progress, cancel);
    let mut round = RoundStats {
        seconds_linking: t.elapsed().as_secs_f64(),
        ..RoundStats::default()
    };
    progress.finish();
    progress.phase("solving");
    progress.start(u64::from(settings.max_rounds.min(FIRST_ROUNDS_GUESS)));
    let mut converged = false;
    let mut interrupted = false;
    let mut refined_before = 0;
    for _ in 0..settings.max_rounds {
        solver.gather_to_convergence(&mut round, cancel)?;
        let t = Instant::now();
        solver
            .importance
            .update(&solver.mesh, &solver.nodes, &solver.links);
        round.seconds_refine += t.elapsed().as_secs_f64();
        round.links = solver.link_count() as u64;
        round.cluster_links = solver.cluster_links.len() as u64;
        round.blocked_links = solver.links.iter().filter(|l| l.is_blocked()).count() as u64;
        round.leaves = solver.mesh.leaves().len() as u64;
        round.rays = solver.linker.rays.load(Ordering::Relaxed);
        round.peak_memory_bytes = peak_resident_bytes();
        if progress.wants_rounds() {
            progress.round(&solver.round_solution(rounds.len() + 1, &round));
        }
        rounds.push(round);
        progress.advance(1);
        if cancel.is_requested() {
            interrupted = true;
            break;
        }
        round = RoundStats::default();
        if !solver.refine(&mut round, cancel) {
            converged = rounds
                .last()
                .is_some_and(|r| r.residual <= settings.tolerance);
            break;
        }
        let left = rounds_left(refined_before, round.links_refined);
        let total = (rounds.len() as u64 + left).min(u64::from(settings.max_rounds));
        progress.estimate(total);
        refined_before = round.links_refined;
    }
    if settings.fine_gather
        && !interrupted
        && let Some(last) = rounds.last_mut()
    {
        solver.fine_gather(last, cancel)?;
        interrupted = cancel.is_requested();
        converged &= last.residual <= settings.tolerance;
    }
    progress.finish();
    for r in &rounds {
        times.form_factors += r.seconds_linking + r.seconds_refine;
        times.iterations += r.seconds_gather + r.seconds_push_pull;
    }
    let convergence = rounds.iter().map(|r| r.residual).collect();
    let kind = SolverKind::Hierarchical;
    if let (Some(kept), Some(view)) = (kept, solver.kept.take()) {
        kept.patch_links.end(view);
    }
    solver.into_solution(
        Arc::clone(&visibility),
        kind,
        options,
        times,
        convergence,
        converged,
        interrupted,
        rounds,
    )
}

/// Pairs of root side and light linked between two looks at progress and cancellation.
const LIGHT_LINK_CHUNK: usize = 1 << 14;

/// The rounds a solve is first thought to take, until refinement shows how fast it
/// settles ([`rounds_left`]).
const FIRST_ROUNDS_GUESS: u32 = 8;

/// About how many more rounds a solve takes after a refinement pass that refined `last`
/// links where the pass before refined `before`: the round this pass prepared, and as many
/// more as the links refined take to fall below one at the rate they fell (halving each
/// pass when they did not fall, or on the first pass).
fn rounds_left(before: u64, last: u64) -> u64 {
    if last == 0 {
        return 1;
    }
    let fall = if before > last {
        before as f64 / last as f64
    } else {
        2.0
    };
    1 + ((last as f64).ln() / fall.ln()).ceil() as u64
}

impl<'w: 'v, 'v> Solver<'w, 'v> {
    /// A solver on the root patches `mesh` with no links yet; its limits are set.
    pub(super) fn new(
        world: &'w Arc<World>,
        mesh: PatchMesh,
        visibility: &'v Visibility,
        options: &SystemOptions,
        settings: &HierarchicalSettings,
    ) -> Self {
        let mut solver = Solver {
            world,
            nodes: Nodes::new(&world.scene, &mesh),
            links: Vec::new(),
            light_links: Vec::new(),
            clusters: None,
            cluster_links: Vec::new(),
            near: None,
            near_links: Vec::new(),
            far: None,
            linker: Linker {
                world,
                visibility,
                link_samples: options.link_samples,
                exact_shadows: exact_shadows(world, visibility),
                rays: AtomicU64::new(0),
                form_factors: AtomicU64::new(0),
            },
            limits: Limits {
                error: 0.0,
                bfa: 0.0,
                min_area: 0.0,
            },
            gather_sums: std::sync::Mutex::new(Vec::new()),
            gather_plans: None,
            importance: Importance::new(world, settings.surface_error),
            fine: None,
            settings: *settings,
            mesh,
            kept: None,
        };
        solver.limits = solver.limits();
        solver
    }

    /// The solution after round `number` (its statistics `round`): every side of every leaf
    /// lit flat by its radiosity and irradiance, for an observer.
    fn round_solution(&self, number: usize, round: &RoundStats) -> RoundSolution {
        let mut mesh = LitMesh::default();
        for leaf in self.mesh.leaves() {
            let patch = self.mesh.patch(leaf);
            for side in Side::BOTH {
                let mut corners: Vec<Vec3> = patch.corners().iter().map(|c| c.as_vec3()).collect();
                if side == Side::Back {
                    corners.reverse();
                }
                let n = node(leaf, side);
                let radiosity = vec![self.nodes.radiosity[n]; corners.len()];
                let irradiance = vec![self.nodes.irradiance[n]; corners.len()];
                mesh.push_polygon(
                    patch.object,
                    &corners,
                    side.normal(patch).as_vec3(),
                    (&radiosity, &irradiance),
                );
            }
        }
        RoundSolution {
            round: number,
            links: round.links,
            leaves: round.leaves,
            change: round.residual,
            mesh,
        }
    }

    /// Both sides of every root patch, as nodes.
    pub(super) fn root_nodes(&self) -> Vec<usize> {
        self.mesh
            .roots
            .iter()
            .flat_map(|&r| Side::BOTH.map(|s| node(r, s)))
            .collect()
    }

    /// In an unrolled periodic world, casts the rays that bring the root sides what the
    /// field beyond the margin sends (`far_field.rs`).
    pub(super) fn cast_far_field(&mut self, progress: &dyn ProgressListener, cancel: &Cancel) {
        let roots = &self.mesh.roots;
        let node_of = |k: usize, side: Side| node(roots[k], side) as u32;
        let cast = FarField::cast(self.world, &self.mesh, roots, node_of, progress, cancel);
        if let Some((far, rays)) = cast {
            self.linker.rays.fetch_add(rays, Ordering::Relaxed);
            self.far = Some(far);
        }
    }

    /// Links every pair of root sides that face and see each other (seed §6.3); with
    /// clustering, links the root cluster with itself and refines that link until every
    /// cluster link is either certain enough or replaced by links between root sides.
    fn link_root_pairs(&mut self, progress: &dyn ProgressListener, cancel: &Cancel) {
        progress.phase("linking");
        progress.start(0);
        if self.settings.clustering {
            self.clusters = ClusterTree::new(&self.world.scene, &self.mesh);
            if let Some(tree) = &self.clusters
                && self.mesh.roots.len() >= self.settings.near_rays_from
            {
                let area: f64 = self
                    .mesh
                    .roots
                    .iter()
                    .map(|&r| self.mesh.patch(r).area)
                    .sum();
                let emitting = tree.brightest(&self.nodes.emission);
                let mut near = NearRays::new(REFERENCE_SHARE * area, emitting);
                progress.phase("near-field rays");
                let rays = near.cast(&self.mesh, tree, progress, cancel);
                progress.finish();
                self.linker.rays.fetch_add(rays, Ordering::Relaxed);
                self.near = Some(near);
                progress.phase("linking clusters");
                progress.start(0);
            }
        }
        if let Some(tree) = &self.clusters {
            let root = tree.root();
            self.cluster_links = vec![tree.link(&self.mesh, root, root)];
            self.gather_plans = None;
            self.refine_clusters(cancel);
            return;
        }
        let roots = self.root_nodes();
        let pairs: Vec<(usize, usize, Prior)> = roots
            .iter()
            .flat_map(|&r| roots.iter().map(move |&e| (r, e, Prior::Unknown)))
            .collect();
        self.links = self.create_links(&pairs);
    }

    /// Patch, cluster, near and light links.
    fn link_count(&self) -> usize {
        self.links.len() + self.cluster_links.len() + self.near_links.len() + self.light_links.len()
    }

    /// Refines cluster links until every one left brings at most the error threshold's
    /// power; links between two root patches become links between their sides. Whatever the
    /// refine pass, new cluster links are judged at once: judging one costs a sum over its
    /// members, and a link between large clusters reaches the level it needs only after
    /// many splits. Stops early when `cancel` is requested. Returns the links created and
    /// refined.
    fn refine_clusters(&mut self, cancel: &Cancel) -> (u64, u64) {
        let Some(tree) = &self.clusters else {
            return (0, 0);
        };
        let (mut created, mut refined) = (0, 0);
        // The links before this index were kept earlier in this call: neither the radiosity
        // nor the patches change while it runs, so they would be kept again.
        let mut judged = 0;
        let sent = tree.sent(&self.mesh, &self.nodes.radiosity);
        while !cancel.is_requested() {
            let (mesh, b, error) = (&self.mesh, &self.nodes.radiosity, self.limits.error);
            let importance = &self.importance;
            // Judged and split in parallel: what replaces each link refined, in link order.
            let near = self.near.as_ref();
            let splits: Vec<Verdict> = self.cluster_links[judged..]
                .par_iter()
                .with_max_len(UNEVEN_RUN)
                .map(|l| {
                    let members = tree.members(&l.receiver);
                    let threshold = importance.error_for_members(mesh, members, error);
                    let sends = ClusterTree::sent_of(&sent, mesh, b, l.emitter);
                    let verdict = match near {
                        // Ends too close for the cluster transport: rays, if their error
                        // is small enough.
                        Some(near) if !l.separated() => {
                            let error = near.error(
                                tree.area(mesh, l.receiver),
                                tree.area(mesh, l.emitter),
                                sends,
                                near.emitting(&self.nodes.emission, l.emitter),
                            );
                            (error <= threshold).then_some(Verdict::Near)
                        }
                        // The bound from the clusters' sums first: when it passes, no sum
                        // over the members.
                        _ if tree.loose_power_bound(mesh, l, sends) <= threshold => {
                            Some(Verdict::Keep)
                        }
                        _ if tree.power_bound(mesh, l, b) > threshold => None,
                        _ => Some(Verdict::Keep),
                    };
                    verdict.unwrap_or_else(|| Verdict::Split(tree.split(mesh, l)))
                })
                .collect();
            let count = splits
                .iter()
                .filter(|s| !matches!(s, Verdict::Keep))
                .count() as u64;
            if count == 0 {
                break;
            }
            // The cluster links change: their gathers worked out before no longer hold.
            self.gather_plans = None;
            // What replaces the links refined, gathered in parallel in link order.
            let replaced: Vec<Replacements> = splits
                .par_iter()
                .zip(&self.cluster_links[judged..])
                .fold(Replacements::default, |mut r, (split, link)| {
                    r.add(tree, split, link);
                    r
                })
                .collect();
            let (mut ends, mut pairs) = (Vec::new(), Vec::new());
            for r in replaced {
                ends.extend(r.ends);
                pairs.extend(r.pairs);
                self.near_links.extend(r.near);
            }
            // The links kept close up behind those judged before.
            close_up(&mut self.cluster_links, judged, &splits);
            refined += count;
            judged = self.cluster_links.len();
            // Written in place, in parallel: 2.6·10⁵ links collected first and
            // then moved took 20 ms on one thread (canopy:3000).
            self.cluster_links.par_extend(
                ends.par_iter()
                    .with_max_len(UNEVEN_RUN)
                    .map(|&(r, e)| tree.link(mesh, r, e)),
            );
            let patch_links = self.create_links(&pairs);
            created += (ends.len() + patch_links.len()) as u64;
            self.links.extend(patch_links);
        }
        // The links kept look at what lies between their ends (those split at once never
        // needed to); stopped, the links not looked at bring nothing.
        if cancel.is_requested() {
            return (created, refined);
        }
        let (mesh, visibility) = (&self.mesh, self.linker.visibility);
        let rays: u64 = self
            .cluster_links
            .par_iter_mut()
            .with_max_len(UNEVEN_RUN)
            .map(|link| {
                let mut rays = 0;
                tree.see(mesh, visibility, link, &self.nodes.radiosity, &mut rays);
                rays
            })
            .sum();
        self.linker.rays.fetch_add(rays, Ordering::Relaxed);
        if let Some(near) = &mut self.near {
            near.classify(mesh, tree, &self.near_links[near.classified()..]);
        }
        (created, refined)
    }

    /// Links every root side with every light that reaches it (`progress` counts the pairs
    /// of root side and light); once `cancel` is requested the pairs left get no link.
    pub(super) fn link_root_lights(&mut self, progress: &dyn ProgressListener, cancel: &Cancel) {
        let roots = self.root_nodes();
        let lights = self.world.scene.lights.len() as u32;
        let pairs: Vec<(usize, u32)> = (0..lights)
            .flat_map(|l| roots.iter().map(move |&r| (r, l)))
            .collect();
        progress.start(pairs.len() as u64);
        let mut links = Vec::new();
        for chunk in pairs.chunks(LIGHT_LINK_CHUNK) {
            if cancel.is_requested() {
                break;
            }
            links.extend(self.create_light_links(chunk));
            progress.advance(chunk.len() as u64);
        }
        self.light_links = links;
        self.sum_light_links();
    }

    /// The links of `pairs` (receiver, emitter, what is known of their visibility), in
    /// order, computed in parallel.
    pub(super) fn create_links(&self, pairs: &[(usize, usize, Prior)]) -> Vec<Link> {
        let (mesh, linker) = (&self.mesh, &self.linker);
        let Some(kept) = &self.kept else {
            return pairs
                .par_iter()
                .with_max_len(UNEVEN_RUN)
                .filter_map(|&(r, e, prior)| linker.link(mesh, r, e, prior))
                .collect();
        };
        // The two sides of one patch never link: nothing to keep.
        let made: Vec<_> = pairs
            .par_iter()
            .with_max_len(UNEVEN_RUN)
            .filter(|&&(r, e, _)| split_node(r).0 != split_node(e).0)
            .map(|&(r, e, prior)| kept.link(mesh, (r, e, prior), || linker.link(mesh, r, e, prior)))
            .collect();
        let (links, made): (Vec<Option<Link>>, Vec<_>) = made.into_iter().unzip();
        kept.keep(made.into_iter().flatten().collect());
        links.into_iter().flatten().collect()
    }

    /// The light links of `pairs` (receiver, light), in order, computed in parallel.
    fn create_light_links(&self, pairs: &[(usize, u32)]) -> Vec<LightLink> {
        let (mesh, linker) = (&self.mesh, &self.linker);
        pairs
            .par_iter()
            .with_max_len(UNEVEN_RUN)
            .filter_map(|&(r, l)| linker.light_link(mesh, r, l))
            .collect()
    }

    /// The nodes' light irradiance from the light links.
    fn sum_light_links(&mut self) {
        self.nodes.lit.iter_mut().for_each(|h| *h = Rgb64::BLACK);
        for l in &self.light_links {
            self.nodes.lit[l.receiver as usize] += l.irradiance;
        }
    }

    /// The thresholds: the error relative to all power emitted in the scene (surfaces and
    /// lights), the minimum area relative to the scene's one-sided surface area. Both are
    /// unchanged when the scene is scaled or its lights made brighter.
    fn limits(&self) -> Limits {
        let roots = &self.mesh.roots;
        let area: f64 = roots.iter().map(|&r| self.mesh.patch(r).area).sum();
        let surfaces: f64 = roots
            .iter()
            .flat_map(|&r| Side::BOTH.map(|s| (r, s)))
            .map(|(r, s)| self.nodes.emission[node(r, s)].luminance() * self.mesh.patch(r).area)
            .sum();
        let lights: f64 = self
            .world
            .scene
            .lights
            .iter()
            .map(|l| self.world.light_power(&l.kind).to_f64().luminance())
            .sum();
        let power = surfaces + lights;
        Limits {
            error: self.settings.error * power,
            bfa: self.settings.error * power,
            min_area: self.settings.min_area * area,
        }
    }

    /// Gathers and push-pulls until a gather changes the radiosity by at most the tolerance,
    /// or until the gathers stop losing light (`steady_state.rs`: an error where a surface
    /// reflects all of it).
    fn gather_to_convergence(
        &mut self,
        round: &mut RoundStats,
        cancel: &Cancel,
    ) -> Result<(), SolveError> {
        let mut bounces = BounceWatch::new(self.nodes.largest_albedo());
        let t = Instant::now();
        self.plan_gathers();
        round.seconds_gather += t.elapsed().as_secs_f64();
        for _ in 0..MAX_GATHERS {
            let t = Instant::now();
            self.gather();
            round.seconds_gather += t.elapsed().as_secs_f64();
            let t = Instant::now();
            let (change, source) = self.nodes.push_pull(&self.mesh);
            round.seconds_push_pull += t.elapsed().as_secs_f64();
            round.gathers += 1;
            round.residual = if source > 0.0 { change / source } else { 0.0 };
            if round.residual <= self.settings.tolerance || cancel.is_requested() {
                break;
            }
            // Light gained by links too coarse: the refinement that follows splits them.
            if let Bounce::Gaining(_) = bounces.gathered(change, source)? {
                break;
            }
        }
        Ok(())
    }

    /// Once refinement is done: every link whose emitter is split gathers from the
    /// emitter's pieces from now on ([`FineGather`]), until the radiosity settles again; the
    /// time counts in `round`, the last round (the pieces' form factors as refinement).
    fn fine_gather(&mut self, round: &mut RoundStats, cancel: &Cancel) -> Result<(), SolveError> {
        let t = Instant::now();
        self.fine = Some(FineGather::new(
            &self.mesh,
            &self.nodes,
            &self.links,
            &self.linker.form_factors,
        ));
        round.seconds_refine += t.elapsed().as_secs_f64();
        self.gather_to_convergence(round, cancel)
    }

    /// Works out the cluster links' gathers ([`GatherPlans`]) unless those worked out before
    /// still hold; none without clusters, or when they would hold more than
    /// [`GATHER_BYTES`] (each gather then works them out as it goes).
    fn plan_gathers(&mut self) {
        let shape = self.gather_chunking(self.nodes.radiosity.len());
        if self.gather_plans.as_ref().is_some_and(|p| p.shape == shape) {
            return;
        }
        self.gather_plans = None;
        let Some(tree) = &self.clusters else {
            return;
        };
        // Each chunk's cluster links in pieces, worked out in parallel, in order.
        let (chunks, chunk) = shape;
        let pieces: Vec<(usize, Range<usize>)> = (0..chunks)
            .flat_map(|k| {
                let range = self.chunk_ranges(k, chunk).1;
                (range.start..range.end)
                    .step_by(PLAN_PIECE)
                    .map(move |start| (k, start..(start + PLAN_PIECE).min(range.end)))
            })
            .collect();
        let sides: Vec<usize> = (pieces.par_iter())
            .map(|(_, range)| GatherPlan::sides_at_most(tree, &self.cluster_links[range.clone()]))
            .collect();
        if sides.iter().sum::<usize>() * PLANNED_SIDE_BYTES > GATHER_BYTES {
            return;
        }
        let planned: Vec<GatherPlan> = (pieces.par_iter().zip(&sides))
            .with_max_len(1)
            .map(|((_, range), &sides)| {
                GatherPlan::new(tree, &self.mesh, &self.cluster_links[range.clone()], sides)
            })
            .collect();
        let mut plans = GatherPlans {
            shape,
            chunks: vec![Vec::new(); chunks],
        };
        for ((k, _), plan) in pieces.into_iter().zip(planned) {
            plans.chunks[k].push(plan);
        }
        self.gather_plans = Some(plans);
    }

    /// How many chunks a gather into `nodes` nodes is cut into, and the links per chunk.
    fn gather_chunking(&self, nodes: usize) -> (usize, usize) {
        let links = self.links.len() + self.cluster_links.len();
        let chunks = gather_chunks(links, nodes);
        (chunks, links.div_ceil(chunks).max(1))
    }

    /// The links of chunk `k` of a gather cut into chunks of `chunk` links
    /// ([`Self::gather_chunking`]): its patch links and its cluster links (each as a range of
    /// its own list).
    fn chunk_ranges(&self, k: usize, chunk: usize) -> (Range<usize>, Range<usize>) {
        let patch_links = self.links.len();
        let total = patch_links + self.cluster_links.len();
        let (start, end) = (k * chunk, ((k + 1) * chunk).min(total));
        (
            start.min(patch_links)..end.min(patch_links),
            start.max(patch_links) - patch_links..end.max(patch_links) - patch_links,
        )
    }

    /// Every node gathers `Σ F·V·B` over its links (seed §6.7).
    fn gather(&mut self) {
        let mut gathered = std::mem::take(&mut self.nodes.gathered);
        self.gather_from(&self.nodes.radiosity, &mut gathered);
        self.nodes.gathered = gathered;
    }

    /// Into `gathered` (cleared first), per node: `Σ F·V·B` over its links and the cluster
    /// links, for the radiosity `b` per node. The links (patch links, then cluster links) are
    /// cut into [`gather_chunks`] equal chunks gathered in parallel, each into a sum of its
    /// own, and the chunks' sums are added in their order: the same sums, to the last bit,
    /// for any number of threads.
    fn gather_from(&self, b: &[Rgb64], gathered: &mut Vec<Rgb64>) {
        let nodes = b.len();
        let (chunks, chunk) = self.gather_chunking(nodes);
        let mut sums = self.gather_sums.lock().unwrap_or_else(|e| e.into_inner());
        sums.resize_with(chunks, Vec::new);
        sums.par_iter_mut().enumerate().for_each(|(k, sum)| {
            sum.clear();
            sum.resize(nodes, Rgb64::BLACK);
            let (patch_range, cluster_range) = self.chunk_ranges(k, chunk);
            for (k, link) in self.links[patch_range.clone()]
                .iter()
                .enumerate()
                .filter(|(_, l)| !l.is_blocked())
            {
                let pieces = self
                    .fine
                    .as_ref()
                    .and_then(|f| f.emitter_radiosity(patch_range.start + k, b));
                let h =
                    pieces.unwrap_or_else(|| link.emitter_radiosity(&self.mesh, b)) * link.coupling;
                for (n, h) in link.divide(&self.mesh, h) {
                    sum[n] += h;
                }
            }
            let plans = (self.gather_plans.as_ref()).filter(|p| p.shape == (chunks, chunk));
            match (plans, &self.clusters) {
                (Some(plans), _) => plans.chunks[k].iter().for_each(|p| p.gather(b, sum)),
                (None, Some(tree)) => {
                    let links = &self.cluster_links[cluster_range];
                    let sides = GatherPlan::sides_at_most(tree, links);
                    GatherPlan::new(tree, &self.mesh, links, sides).gather(b, sum);
                }
                (None, None) => {}
            }
        });
        let sums = &sums[..chunks];
        gathered.clear();
        gathered.resize(nodes, Rgb64::BLACK);
        gathered.par_iter_mut().enumerate().for_each(|(n, g)| {
            *g = sums[1..]
                .iter()
                .fold(sums[0][n], |total, sum| total + sum[n]);
        });
        if let (Some(near), Some(tree)) = (&self.near, &self.clusters) {
            near.gather(tree, b, gathered);
        }
        if let Some(far) = &self.far {
            far.gather(b, gathered);
        }
    }

    /// Per node, at the leaves: the irradiance straight from the emitting surfaces and the
    /// lights (one gather of the emitted radiosity alone over the final links, pushed down
    /// with the light links), W·m⁻².
    fn direct_irradiance(&self) -> Vec<Rgb64> {
        let mut gathered = Vec::new();
        if self.nodes.emission.iter().any(|&e| e != Rgb64::BLACK) {
            self.gather_from(&self.nodes.emission, &mut gathered);
        } else {
            // Lit by lights alone (the canopy's sun and sky): the gather would bring nothing.
            gathered.resize(self.nodes.emission.len(), Rgb64::BLACK);
        }
        self.nodes.push_down(&self.mesh, &gathered)
    }

    /// One refinement pass (seed §6.4); true when a link was refined.
    pub(super) fn refine(&mut self, round: &mut RoundStats, cancel: &Cancel) -> bool {
        let mut refined_any = false;
        loop {
            let t = Instant::now();
            let (oracle, limits) = (self.settings.oracle, self.limits);
            let (nodes, mesh, importance) = (&self.nodes, &self.mesh, &self.importance);
            let limits_for =
                |receiver: u32| limits.with_error(importance.error(mesh, receiver, limits.error));
            let decisions: Vec<Decision> = self
                .links
                .par_iter()
                .map(|l| {
                    let range = nodes.range[l.emitter as usize];
                    decide(oracle, l, range, mesh, &limits_for(l.receiver))
                })
                .collect();
            let light_decisions: Vec<Decision> = self
                .light_links
                .par_iter()
                .map(|l| decide_light(l, mesh, &limits_for(l.receiver)))
                .collect();
            round.seconds_refine += t.elapsed().as_secs_f64();
            let t = Instant::now();
            let applied = self.apply(&decisions, &light_decisions);
            let refined = applied.refined + self.refine_textures();
            let (created_clusters, refined_clusters) = self.refine_clusters(cancel);
            self.linker.complete_weights(&self.mesh, &mut self.links);
            let (created, refined) = (
                applied.created + created_clusters,
                refined + refined_clusters,
            );
            round.seconds_linking += t.elapsed().as_secs_f64();
            round.links_created += created;
            round.links_refined += refined;
            round.links_looked += applied.looked;
            refined_any |= refined + applied.looked > 0;
            if refined + applied.looked == 0
                || self.settings.refine_pass == RefinePass::Original
                || cancel.is_requested()
            {
                return refined_any;
            }
        }
    }

    /// Splits every leaf whose textures make the light it sends vary across it by more than
    /// the error threshold, `A·Y(ΔE + Δρ·H) > error` for either side (`ΔE`, `Δρ` the
    /// spreads of [`Nodes::spread`], `H` the leaf's irradiance), down to the minimum area.
    /// The children are judged at once with the irradiance they take from their parent,
    /// which makes their radiosity `E + ρ·H` until the next gather or shot. Returns the
    /// leaves split.
    pub(super) fn refine_textures(&mut self) -> u64 {
        let scene = &self.world.scene;
        let mut pending: Vec<PatchId> = self
            .mesh
            .leaves()
            .into_iter()
            .filter(|&l| is_textured(scene, self.mesh.patch(l).material))
            .collect();
        let mut split = 0;
        while let Some(leaf) = pending.pop() {
            let patch = self.mesh.patch(leaf);
            let varies = Side::BOTH.into_iter().any(|side| {
                let n = node(leaf, side);
                let (de, dr) = self.nodes.spread[n];
                patch.area * (de + dr * self.nodes.irradiance[n].luminance()) > self.limits.error
            });
            if !varies || patch.area <= self.limits.min_area {
                continue;
            }
            let children = self.mesh.subdivide(leaf);
            self.nodes.grow(scene, &self.mesh);
            let nodes = &mut self.nodes;
            for (c, side) in children
                .into_iter()
                .flat_map(|c| Side::BOTH.map(|s| (c, s)))
            {
                let (n, other) = (node(c, side), node(c, side.other()));
                let b = nodes.emission[n]
                    + nodes.scattered(n, nodes.irradiance[n], nodes.irradiance[other]);
                nodes.radiosity[n] = b;
                nodes.range[n] = (b.luminance(), b.luminance());
            }
            pending.extend(children);
            split += 1;
        }
        split
    }

    /// Replaces every link with a refining decision by links to the children of its receiver
    /// or emitter (splitting those nodes), and every blocked link the oracle looks at again
    /// by its link computed anew; returns the links created, refined and looked at again.
    fn apply(&mut self, decisions: &[Decision], light_decisions: &[Decision]) -> Applied {
        // Refined links are removed in place (the kept keep their order), so no round copies
        // the whole link list.
        let mut pairs: Vec<(usize, usize, Prior)> = Vec::new();
        let mut applied = Applied::default();
        let mesh = &mut self.mesh;
        let mut decision = decisions.iter();
        self.links.retain(|link| {
            let (r, e) = (link.receiver as usize, link.emitter as usize);
            match decision.next() {
                Some(Decision::Receiver) => {
                    applied.refined += 1;
                    for child in children(mesh, r) {
                        pairs.push((child, e, link.prior_for_children()));
                    }
                    false
                }
                Some(Decision::Emitter) => {
                    applied.refined += 1;
                    for child in children(mesh, e) {
                        pairs.push((r, child, link.prior_for_children()));
                    }
                    false
                }
                Some(&Decision::Look(rays)) => {
                    applied.looked += 1;
                    pairs.push((r, e, Prior::Blocked(rays, link.blockers)));
                    false
                }
                Some(Decision::Keep) | None => true,
            }
        });
        let mut light_pairs: Vec<(usize, u32)> = Vec::new();
        let mut decision = light_decisions.iter();
        self.light_links.retain(|link| {
            if decision.next().is_none_or(|d| *d == Decision::Keep) {
                return true;
            }
            applied.refined += 1;
            for child in children(mesh, link.receiver as usize) {
                light_pairs.push((child, link.light));
            }
            false
        });
        self.nodes.grow(&self.world.scene, &self.mesh);
        let created = self.create_links(&pairs);
        let created_lights = self.create_light_links(&light_pairs);
        applied.created =
            ((created.len() + created_lights.len()) as u64).saturating_sub(applied.looked);
        self.links.extend(created);
        self.light_links.extend(created_lights);
        self.sum_light_links();
        applied
    }

    /// Every link not blocked as a segment between the centres of its ends, and every light
    /// link that carries light from the receiver's centre toward its light (for the display
    /// of links).
    fn link_segments(&self) -> Vec<LinkSegment> {
        let mut link_segments: Vec<LinkSegment> = self
            .links
            .par_iter()
            .filter(|l| !l.is_blocked())
            .map(|l| {
                let r = self.mesh.patch(split_node(l.receiver as usize).0);
                let e = self.mesh.patch(split_node(l.emitter as usize).0);
                LinkSegment {
                    receiver: r.centroid,
                    emitter: e.centroid,
                    receiver_object: Some(r.object),
                    emitter_object: Some(e.object),
                    light: None,
                    level: Some(r.depth.max(e.depth)),
                }
            })
            .collect();
        let world = self.linker.world;
        let reach = f64::from(world.geometry.bounding_sphere().1);
        link_segments.par_extend(
            self.light_links
                .par_iter()
                .filter(|l| l.irradiance != Rgb64::BLACK)
                .map(|l| {
                    let (patch, side) = split_node(l.receiver as usize);
                    let r = self.mesh.patch(patch);
                    let emitter = match &world.scene.lights[l.light as usize].kind {
                        LightKind::Point { position, .. }
                        | LightKind::Lambertian { position, .. }
                        | LightKind::Spot { position, .. } => position.as_dvec3(),
                        LightKind::Directional { direction, .. } => {
                            r.centroid - reach * direction.as_dvec3()
                        }
                        LightKind::Sky { .. } | LightKind::CieSky { .. } => {
                            r.centroid + reach * side.normal(r)
                        }
                    };
                    LinkSegment {
                        receiver: r.centroid,
                        emitter,
                        receiver_object: Some(r.object),
                        emitter_object: None,
                        light: Some(l.light),
                        level: Some(r.depth),
                    }
                }),
        );
        if let Some(tree) = &self.clusters {
            let end = |end: End| match end {
                End::Patch(p) => (self.mesh.patch(p).centroid, Some(self.mesh.patch(p).object)),
                End::Cluster(_) => (tree.ball(&self.mesh, end).0, None),
            };
            link_segments.par_extend(self.cluster_links.par_iter().map(|l| {
                let ((receiver, receiver_object), (emitter, emitter_object)) =
                    (end(l.receiver), end(l.emitter));
                LinkSegment {
                    receiver,
                    emitter,
                    receiver_object,
                    emitter_object,
                    light: None,
                    // A cluster link between two root patches is a link between roots.
                    level: (receiver_object.is_some() && emitter_object.is_some()).then_some(0),
                }
            }));
        }
        link_segments
    }

    /// The system on the final leaves (with `visibility`, the estimator the solver used)
    /// and the solution on it, by solver `kind`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn into_solution(
        self,
        visibility: Arc<Visibility>,
        kind: SolverKind,
        options: SystemOptions,
        seconds: PhaseTimes,
        convergence: Vec<f64>,
        converged: bool,
        interrupted: bool,
        rounds: Vec<RoundStats>,
    ) -> Result<(RadiositySystem, Solution), SolveError> {
        let leaves = self.mesh.leaves();
        let per_element = |values: &Vec<Rgb64>| -> Vec<Rgb64> {
            leaves
                .iter()
                .flat_map(|&l| Side::BOTH.map(|s| values[node(l, s)]))
                .collect()
        };
        let radiosity = per_element(&self.nodes.radiosity);
        let irradiance = per_element(&self.nodes.irradiance);
        // Only hierarchical radiosity tells direct from indirect light apart.
        let direct_irradiance =
            (kind == SolverKind::Hierarchical).then(|| per_element(&self.direct_irradiance()));
        let lit = per_element(&self.nodes.lit_total);
        let (links, near_links) = (self.link_count(), self.near_links.len());
        let link_segments = if self.settings.link_segments {
            self.link_segments()
        } else {
            Vec::new()
        };
        let form_factors = self.linker.form_factors.load(Ordering::Relaxed);
        let rays = self.linker.rays.load(Ordering::Relaxed);
        let Solver {
            world,
            mesh,
            links: patch_links,
            cluster_links,
            gather_sums,
            ..
        } = self;
        // Freeing 10⁵–10⁶ links takes several milliseconds, most of it giving their memory
        // back to the system: a job of the thread pool does it while this thread goes on
        // to the system and the report (on one thread, once the thread is free).
        rayon::spawn(move || drop((patch_links, cluster_links, gather_sums)));
        let system = RadiositySystem::from_mesh(world, mesh, options, Some(lit), Some(visibility));
        let system = system?;
        system.count_work(form_factors, rays);
        let solution = Solution {
            solver: kind,
            solver_name: kind.name(),
            radiosity,
            irradiance,
            direct_irradiance,
            ambient: Rgb64::BLACK,
            convergence,
            converged,
            interrupted,
            seconds,
            rounds,
            links,
            near_links,
            link_segments,
        };
        Ok((system, solution))
    }
}

/// The nodes of the children of node `n`'s patch (same side), splitting it if needed.
pub(super) fn children(mesh: &mut PatchMesh, n: usize) -> [usize; 4] {
    let (patch, side) = split_node(n);
    let ids: [PatchId; 4] = mesh.subdivide(patch);
    ids.map(|c| node(c, side))
}

/// Keeps the links of `links[from..]` whose verdict (in `verdicts`, one per link from
/// `from` on) is [`Verdict::Keep`]: the last ones kept are copied into the places of the
/// first ones not, in parallel, and the rest cut off. Which link goes where depends on the
/// verdicts alone. Keeping the links' order moved every link after the first one refined
/// (2.6·10⁵ links to drop one in the canopy's second round), and moving them on one thread
/// was the longest serial step of cluster refinement.
fn close_up(links: &mut Vec<ClusterLink>, from: usize, verdicts: &[Verdict]) {
    let keep = |i: usize| matches!(verdicts[i], Verdict::Keep);
    let kept = (0..verdicts.len()).filter(|&i| keep(i)).count();
    // The gaps among the first `kept` places, and as many links kept beyond them, last first.
    let gaps: Vec<usize> = (0..kept).filter(|&i| !keep(i)).collect();
    let movers: Vec<usize> = (kept..verdicts.len()).rev().filter(|&i| keep(i)).collect();
    let (front, back) = links[from..].split_at_mut(kept);
    let back = &*back;
    front
        .par_chunks_mut(CLOSE_UP_RUN)
        .enumerate()
        .for_each(|(chunk_index, chunk)| {
            let start = chunk_index * CLOSE_UP_RUN;
            let first = gaps.partition_point(|&g| g < start);
            for (&gap, &mover) in gaps[first..].iter().zip(&movers[first..]) {
                if gap >= start + chunk.len() {
                    break;
                }
                chunk[gap - start].clone_from(&back[mover - kept]);
            }
        });
    links.truncate(from + kept);
}

/// The places [`close_up`] looks at in one task.
const CLOSE_UP_RUN: usize = 1 << 12;

/// The links, patch pairs and near-field pairs that replace the cluster links refined in
/// a run of judged links, in link order.
#[derive(Default)]
struct Replacements {
    /// The ends of the new cluster links.
    ends: Vec<(End, End)>,
    /// The side pairs (receiver, emitter) of the new patch links.
    pairs: Vec<(usize, usize, Prior)>,
    /// The ends left to the near field's rays.
    near: Vec<(End, End)>,
}

impl Replacements {
    /// Adds what replaces `link` by its verdict `split`.
    fn add(&mut self, tree: &ClusterTree, split: &Verdict, link: &ClusterLink) {
        match split {
            Verdict::Keep => {}
            Verdict::Near => self.near.push((link.receiver, link.emitter)),
            &Verdict::Split(Split::Patches(r, e)) => self.pairs.extend(
                Side::BOTH
                    .into_iter()
                    .flat_map(|rs| Side::BOTH.map(|es| (node(r, rs), node(e, es), Prior::Unknown))),
            ),
            Verdict::Split(split) => tree.split_ends(link, split, &mut self.ends),
        }
    }
}

/// What judging a cluster link decides.
enum Verdict {
    /// It brings its light well enough as it is.
    Keep,
    /// Its ends are too close for the cluster transport: the near field's rays carry it.
    Near,
    /// It is replaced.
    Split(Split),
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use smallvec::SmallVec;

    /// A cluster link told apart by its distance, `id`.
    fn link(id: usize) -> ClusterLink {
        ClusterLink {
            receiver: End::Patch(0),
            emitter: End::Patch(1),
            receiver_centre: DVec3::ZERO,
            emitter_centre: DVec3::ZERO,
            direction: DVec3::Y,
            receiver_radius: 0.0,
            emitter_radius: 0.0,
            distance: id as f64,
            visible: SmallVec::new(),
            seen: false,
        }
    }

    /// The ids of `links`.
    fn ids(links: &[ClusterLink]) -> Vec<usize> {
        links.iter().map(|l| l.distance as usize).collect()
    }

    #[test]
    fn planned_gathers_equal_gathers_that_work_the_links_out_as_they_go() {
        // A canopy of 300 leaves: about 2·10⁴ cluster links, so a chunk holds several pieces.
        let scene = crate::scene::builtin::canopy::scene(300);
        let world = Arc::new(World::new(scene, crate::accel::AccelKind::default()).unwrap());
        let (options, settings) = (SystemOptions::default(), HierarchicalSettings::default());
        let (mesh, visibility) = prepare(&world, &options, false).unwrap();
        let mut solver = Solver::new(&world, mesh, &visibility, &options, &settings);
        let (progress, cancel) = (crate::progress::NoProgress, Cancel::new());
        solver.link_root_lights(&progress, &cancel);
        solver.nodes.push_pull(&solver.mesh);
        solver.link_root_pairs(&progress, &cancel);
        assert!(solver.cluster_links.len() > 2 * PLAN_PIECE);
        fn same_either_way<'w: 'v, 'v>(solver: &mut Solver<'w, 'v>) {
            let b = solver.nodes.radiosity.clone();
            let (mut as_they_go, mut planned) = (Vec::new(), Vec::new());
            let kept = solver.gather_plans.take();
            solver.gather_from(&b, &mut as_they_go);
            solver.gather_plans = kept;
            solver.plan_gathers();
            let plans = solver.gather_plans.as_ref().unwrap();
            assert!(plans.chunks.iter().map(Vec::len).sum::<usize>() > 2);
            solver.gather_from(&b, &mut planned);
            assert_eq!(as_they_go, planned);
            assert!(planned.iter().filter(|h| h.max_channel() > 0.0).count() > 100);
        }
        same_either_way(&mut solver);
        // Links refined after a gather: the plans made before are dropped, not used.
        solver
            .gather_to_convergence(&mut RoundStats::default(), &cancel)
            .unwrap();
        let links = solver.cluster_links.len();
        solver.limits.error *= 0.5;
        solver.refine_clusters(&cancel);
        assert_ne!(solver.cluster_links.len(), links);
        assert!(solver.gather_plans.is_none());
        same_either_way(&mut solver);
    }

    #[test]
    fn closing_up_keeps_every_link_kept_once_and_moves_only_into_gaps() {
        // Ten thousand links judged after five kept before; every third one refined, so the
        // gaps spread over several of the parallel runs.
        let (from, judged) = (5, 10_000);
        let verdicts: Vec<Verdict> = (0..judged)
            .map(|i| match i % 3 {
                1 => Verdict::Near,
                _ => Verdict::Keep,
            })
            .collect();
        let mut links: Vec<ClusterLink> = (0..from + judged).map(link).collect();
        close_up(&mut links, from, &verdicts);
        let ids = ids(&links);
        assert_eq!(ids[..from], [0, 1, 2, 3, 4]);
        let mut kept = ids[from..].to_vec();
        kept.sort_unstable();
        let expected: Vec<usize> = (0..judged)
            .filter(|i| i % 3 != 1)
            .map(|i| from + i)
            .collect();
        assert_eq!(kept, expected);
        // A link kept stays where it was unless it moved into a gap; the gaps are filled
        // by the last links kept, last first.
        let gaps: Vec<usize> = (0..kept.len()).filter(|i| i % 3 == 1).collect();
        for (place, &id) in ids.iter().enumerate().skip(from) {
            if gaps.binary_search(&(place - from)).is_err() {
                assert_eq!(id, place);
            }
        }
        let movers: Vec<usize> = (kept.len()..judged).rev().filter(|i| i % 3 != 1).collect();
        assert_eq!(ids[from + gaps[0]], from + movers[0]);
    }

    #[test]
    fn closing_up_with_none_kept_or_none_refined() {
        let mut links: Vec<ClusterLink> = (0..8).map(link).collect();
        close_up(&mut links, 2, &[const { Verdict::Keep }; 6]);
        assert_eq!(ids(&links), (0..8).collect::<Vec<_>>());
        close_up(
            &mut links,
            3,
            &(0..5).map(|_| Verdict::Near).collect::<Vec<_>>(),
        );
        assert_eq!(ids(&links), [0, 1, 2]);
    }
}
