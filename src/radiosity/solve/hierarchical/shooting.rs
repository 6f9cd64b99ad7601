//! Hierarchical shooting (seed 000 §5.3): progressive refinement whose receivers take the
//! light at the level of their quadtree an oracle allows.
//!
//! The lights are linked to the roots and their links refined as in hierarchical radiosity;
//! then, shot by shot, the root side with the most unshot power `Σ Y(|B − B_shot|)·A` over
//! its leaves sends its unshot radiosity to every root side. Each link of the shot is judged
//! by the oracle of hierarchical radiosity, with the shooter's unshot radiosity in place of
//! its radiosity: kept, or refined at the receiver or at the shooter's end — so a part of the
//! shooter that sends unevenly is split, and a receiver takes the shot at the level where
//! the power it brings is certain enough. What a node takes is pushed down to its leaves
//! (§5.3.2), where it becomes radiosity, and leaves whose texture makes the light they send
//! vary too much are split, before the next shooter is chosen. Shooting stops
//! when the unshot power is at most the tolerance times the source power, or after the most
//! shots allowed.
//!
//! The seed shoots from single elements and refines receivers only. With the many small
//! elements of a refined mesh each shooting on its own, every shot's error passes the oracle
//! and the errors add up with one sign: in a furnace the elements along the edges took 20 %
//! too much light (shots accepted at a coarse receiver spread evenly what mostly lands away
//! from the edge). Shooting from the root, refined where needed, keeps the shots few and
//! their links as fine as those of hierarchical radiosity.
//!
//! A measuring patch (a surface that scatters and emits nothing, `importance.rs`) takes each
//! shot within [`MEASURING_PATCH_ERROR`] of what it has received so far or of what the shot's
//! first link onto it brings, the larger (`Shots::limits_for`): the scene-wide threshold
//! would accept any error on a patch that receives a millionth of the light. Measured on
//! `meters`: −42 / −5 / +24 % → +0.17 / +0.13 / +0.49 %.
//!
//! Links are judged level by level: all links of one level are computed in parallel, in an
//! order that does not depend on the thread count.

use super::importance::MEASURING_PATCH_ERROR;
use super::links::{Link, Prior};
use super::nodes::{node, split_node};
use super::oracle::{Decision, Limits, decide};
use super::solver::{Solver, children, prepare};
use super::{HierarchicalSettings, RefinePass};
use crate::color::Rgb64;
use crate::progress::{Cancel, ProgressListener};
use crate::radiosity::solve::rounds::RoundStats;
use crate::radiosity::solve::steady_state::{Bounce, BounceWatch};
use crate::radiosity::solve::unshot_progress::UnshotProgress;
use crate::radiosity::solve::{
    PhaseTimes, RadiositySystem, ShootingSettings, Solution, SolveError, SolverKind, SystemOptions,
};
use crate::world::World;
use std::sync::Arc;
use std::time::Instant;

/// The least threshold a shot onto a measuring patch is held to, as a share of the
/// scene-wide one: a patch whose first shot brings almost nothing is not refined down to the
/// minimum area for it (the patches of `meters`, at 10⁻⁷ of the scene's power, need 10⁻⁵).
const LEAST_PATCH_THRESHOLD: f64 = 1e-6;

/// Links of a shot computed between two looks at cancellation: the first level of a shot
/// links the shooter with every root side (10⁶ of them in a furnished building).
const SHOT_CHUNK: usize = 1 << 14;

/// Solves `world`'s scene by hierarchical shooting: the oracle, error and minimum area come
/// from `settings`, the tolerance and the most shots from `shooting` (overshooting is not
/// used). `progress` names the phases (`meshing`, `linking lights`, `far-field rays` for a
/// periodic plot, `linking`, `shooting`)
/// and advances on a log scale of the unshot power while shooting; `cancel` stops within
/// the current shot (which is then dropped, its shooter's light left unshot) and keeps the
/// state the shots before reached.
pub fn solve_hierarchical_shooting(
    world: &Arc<World>,
    options: SystemOptions,
    settings: &HierarchicalSettings,
    shooting: &ShootingSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<(RadiositySystem, Solution), SolveError> {
    let start = Instant::now();
    progress.phase("meshing");
    progress.start(0);
    let (mesh, visibility) = prepare(world, &options, false)?;
    let light_settings = HierarchicalSettings {
        refine_pass: RefinePass::All,
        ..*settings
    };
    let mut solver = Solver::new(world, mesh, &visibility, &options, &light_settings);
    progress.phase("linking lights");
    solver.link_root_lights(progress, cancel);
    progress.finish();
    solver.cast_far_field(progress, cancel);
    progress.phase("linking");
    progress.start(0);
    solver.refine(&mut RoundStats::default(), cancel);
    progress.finish();
    let (_, source) = solver.nodes.push_pull(&solver.mesh);
    let mut times = PhaseTimes {
        setup: start.elapsed().as_secs_f64(),
        ..PhaseTimes::default()
    };
    let mut shots = Shots::new(&solver);
    let mut convergence = Vec::new();
    progress.phase("shooting");
    let mut bar = UnshotProgress::start(progress, shooting.tolerance);
    let mut interrupted = false;
    let source = source.max(f64::MIN_POSITIVE);
    let (mut shooter, mut unshot) = shots.unshot_power(&solver);
    let mut fraction = unshot / source;
    let mut bounces = BounceWatch::new(solver.nodes.largest_albedo());
    while fraction > shooting.tolerance && (convergence.len() as u64) < shooting.max_shots {
        if cancel.is_requested() {
            interrupted = true;
            break;
        }
        let t = Instant::now();
        let sent = shots.unshot_below(&solver, shooter);
        let Some(received) = shots.shot_from(&mut solver, shooter, cancel) else {
            interrupted = true;
            break;
        };
        times.form_factors += t.elapsed().as_secs_f64();
        let t = Instant::now();
        for (receiver, irradiance) in received {
            push(&mut solver, receiver, irradiance);
        }
        solver.refine_textures();
        shots.grow(&solver);
        let (next, after) = shots.unshot_power(&solver);
        times.iterations += t.elapsed().as_secs_f64();
        let bounce = bounces.shot(sent, unshot, after)?;
        (shooter, unshot, fraction) = (next, after, after / source);
        convergence.push(fraction);
        bar.reach(fraction);
        if let Bounce::Gaining(_) = bounce {
            break;
        }
    }
    bar.finish();
    // Every leaf already holds what was pushed to it; this makes the inner nodes' means and
    // the light share of the irradiance consistent for the report.
    solver.nodes.push_pull(&solver.mesh);
    let converged = fraction <= shooting.tolerance;
    let kind = SolverKind::HierarchicalShooting;
    solver.into_solution(
        Arc::clone(&visibility),
        kind,
        options,
        times,
        convergence,
        converged,
        interrupted,
        Vec::new(),
    )
}

/// The shooting state: what each node has shot, and the unshot radiosity of the current
/// shooter's nodes.
struct Shots {
    /// Radiosity each node had when it (or the root side above it) last shot, W·m⁻²; a
    /// child starts with its parent's.
    shot: Vec<Rgb64>,
    /// The current shooter's unshot radiosity `B − B_shot` (area mean over the leaves
    /// below), W·m⁻²; other nodes hold what they held when they last shot or were created.
    unshot: Vec<Rgb64>,
    /// The luminance range of `unshot` over the leaves below each node, W·m⁻².
    range: Vec<(f64, f64)>,
    /// Per scene object, the luminance of the power it has received so far, W.
    measured: Vec<f64>,
}

impl Shots {
    /// Nothing shot yet.
    fn new(solver: &Solver) -> Self {
        let n = solver.nodes.radiosity.len();
        Shots {
            shot: vec![Rgb64::BLACK; n],
            unshot: vec![Rgb64::BLACK; n],
            range: vec![(0.0, 0.0); n],
            measured: vec![0.0; solver.world.scene.objects.len()],
        }
    }

    /// The root side with the most unshot power `Σ Y(|B − B_shot|)·A` over its leaves (the
    /// first of equals), and the total unshot power over all leaves, W.
    fn unshot_power(&self, solver: &Solver) -> (usize, f64) {
        let mut best = (0, f64::NEG_INFINITY);
        let mut total = 0.0;
        for root in solver.root_nodes() {
            let power = self.unshot_below(solver, root);
            total += power;
            if power > best.1 {
                best = (root, power);
            }
        }
        (best.0, total)
    }

    /// The unshot power of the leaves below node `n`, W.
    fn unshot_below(&self, solver: &Solver, n: usize) -> f64 {
        let (patch, side) = split_node(n);
        let mesh = &solver.mesh;
        match mesh.patch(patch).children {
            None => {
                let b = solver.nodes.radiosity[n];
                (b - self.shot[n]).map(f64::abs).luminance() * mesh.patch(patch).area
            }
            Some(children) => children
                .iter()
                .map(|&c| self.unshot_below(solver, node(c, side)))
                .sum(),
        }
    }

    /// One shot from root side `shooter`: takes its unshot radiosity and sends it to every
    /// root side ([`Shots::shoot`]). Returns the nodes that took light and the irradiance each
    /// took, W·m⁻², already added to what they gathered; `None` when `cancel` was requested
    /// before the shot was complete, with nothing of it kept (the shooter's light stays
    /// unshot): a shot over a large scene links the shooter with every root side and may take
    /// far longer than a second.
    fn shot_from(
        &mut self,
        solver: &mut Solver,
        shooter: usize,
        cancel: &Cancel,
    ) -> Option<Vec<(usize, Rgb64)>> {
        let before: Vec<(usize, Rgb64)> = leaf_nodes(solver, shooter)
            .map(|n| (n, self.shot[n]))
            .collect();
        self.take_unshot(solver, shooter);
        let measured = self.measured.clone();
        let received = self.shoot(solver, shooter, cancel);
        match &received {
            Some(received) => {
                for &(n, irradiance) in received {
                    solver.nodes.gathered[n] += irradiance;
                }
            }
            None => {
                for (n, shot) in before {
                    self.shot[n] = shot;
                }
                self.measured = measured;
            }
        }
        received
    }

    /// Takes the unshot radiosity of every node below `n` (the area mean over its leaves,
    /// and their range) and marks its leaves as shot.
    fn take_unshot(&mut self, solver: &Solver, n: usize) {
        let (patch, side) = split_node(n);
        let mesh = &solver.mesh;
        match mesh.patch(patch).children {
            None => {
                let b = solver.nodes.radiosity[n];
                let unshot = b - self.shot[n];
                let y = unshot.luminance();
                self.unshot[n] = unshot;
                self.range[n] = (y, y);
                self.shot[n] = b;
            }
            Some(children) => {
                let mut sum = Rgb64::BLACK;
                let mut range = (f64::INFINITY, f64::NEG_INFINITY);
                for c in children {
                    let c_node = node(c, side);
                    self.take_unshot(solver, c_node);
                    sum += self.unshot[c_node] * mesh.patch(c).area;
                    let r = self.range[c_node];
                    range = (range.0.min(r.0), range.1.max(r.1));
                }
                self.unshot[n] = sum.map(|v| v / mesh.patch(patch).area);
                self.range[n] = range;
            }
        }
    }

    /// Gives the nodes created since the last call their parent's state.
    fn grow(&mut self, solver: &Solver) {
        while self.shot.len() < solver.nodes.radiosity.len() {
            let (patch, side) = split_node(self.shot.len());
            let parent = solver.mesh.patch(patch).parent.map(|p| node(p, side));
            let (shot, unshot, range) = match parent {
                Some(p) => (self.shot[p], self.unshot[p], self.range[p]),
                None => (Rgb64::BLACK, Rgb64::BLACK, (0.0, 0.0)),
            };
            self.shot.push(shot);
            self.unshot.push(unshot);
            self.range.push(range);
        }
    }

    /// The limits `link` is judged by: the scene-wide ones, but a link onto a measuring
    /// patch (`importance.rs`) is held to [`MEASURING_PATCH_ERROR`] of what the patch has
    /// received so far or of what this shot's first link onto it brings, the larger: each
    /// shot's light reaches the patch within that share of its own. `thresholds` holds, per
    /// scene object, the threshold of the current shot once its first link is judged.
    fn limits_for(
        &self,
        solver: &Solver,
        link: &Link,
        limits: Limits,
        thresholds: &mut [Option<f64>],
    ) -> Limits {
        let receiver = solver.mesh.patch(split_node(link.receiver as usize).0);
        let object = receiver.object as usize;
        if !solver.importance.is_measuring_patch(receiver.object) || link.is_blocked() {
            return limits;
        }
        let threshold = *thresholds[object].get_or_insert_with(|| {
            let brought = receiver.area
                * link.coupling
                * link
                    .emitter_radiosity(&solver.mesh, &self.unshot)
                    .luminance();
            MEASURING_PATCH_ERROR * brought.max(self.measured[object])
        });
        let threshold = threshold.max(LEAST_PATCH_THRESHOLD * limits.error);
        limits.with_error(limits.error.min(threshold))
    }

    /// Sends the unshot radiosity taken from root side `shooter` to every root side, each
    /// link refined at either end until the oracle keeps it (nodes split on the way).
    /// Returns the nodes that took light and the irradiance each took, W·m⁻², not yet added
    /// to what they gathered; `None` once `cancel` is requested (looked at every
    /// [`SHOT_CHUNK`] links).
    fn shoot(
        &mut self,
        solver: &mut Solver,
        shooter: usize,
        cancel: &Cancel,
    ) -> Option<Vec<(usize, Rgb64)>> {
        let mut received = Vec::new();
        let mut thresholds = vec![None; self.measured.len()];
        let mut frontier: Vec<(usize, usize, Prior)> = solver
            .root_nodes()
            .into_iter()
            .map(|r| (r, shooter, Prior::Unknown))
            .collect();
        while !frontier.is_empty() {
            let mut links = Vec::with_capacity(frontier.len());
            for chunk in frontier.chunks(SHOT_CHUNK) {
                if cancel.is_requested() {
                    return None;
                }
                links.extend(solver.create_links(chunk));
            }
            let (oracle, limits) = (solver.settings.oracle, solver.limits);
            let mut next = Vec::new();
            let mut kept = Vec::new();
            for link in links {
                let (r, e) = (link.receiver as usize, link.emitter as usize);
                let limits = self.limits_for(solver, &link, limits, &mut thresholds);
                match decide(oracle, &link, self.range[e], &solver.mesh, &limits) {
                    Decision::Keep => kept.push(link),
                    Decision::Receiver => {
                        let prior = link.prior_for_children();
                        next.extend(children(&mut solver.mesh, r).map(|c| (c, e, prior)))
                    }
                    Decision::Emitter => {
                        let prior = link.prior_for_children();
                        next.extend(children(&mut solver.mesh, e).map(|c| (r, c, prior)))
                    }
                    Decision::Look(rays) => next.push((r, e, Prior::Blocked(rays, link.blockers))),
                }
            }
            solver.nodes.grow(&solver.world.scene, &solver.mesh);
            self.grow(solver);
            // Taken after the splits of this level, which may have split a kept link's
            // receiver (through its other side) or emitter.
            solver.linker.complete_weights(&solver.mesh, &mut kept);
            for link in kept {
                let sent = link.emitter_radiosity(&solver.mesh, &self.unshot) * link.coupling;
                for (n, irradiance) in link.divide(&solver.mesh, sent) {
                    self.receive(solver, (n, irradiance), &mut received);
                }
            }
            frontier = next;
        }
        // What the shooter sends the root sides that see it beyond the margin of a periodic
        // plot (`far_field.rs`), from its mean over the root side.
        if let Some(far) = &solver.far {
            let unshot = self.unshot[shooter];
            for &(receiver, share) in far.sent_by(shooter) {
                self.receive(solver, (receiver as usize, unshot * share), &mut received);
            }
        }
        Some(received)
    }

    /// Node `n` takes `irradiance` (W·m⁻²) of the shot: noted in `received`, and counted in
    /// what its object has received.
    fn receive(
        &mut self,
        solver: &Solver,
        (n, irradiance): (usize, Rgb64),
        received: &mut Vec<(usize, Rgb64)>,
    ) {
        received.push((n, irradiance));
        let patch = solver.mesh.patch(split_node(n).0);
        if let Some(measured) = self.measured.get_mut(patch.object as usize) {
            *measured += irradiance.luminance() * patch.area;
        }
    }
}

/// The leaf nodes below node `n` (its side).
fn leaf_nodes(solver: &Solver, n: usize) -> impl Iterator<Item = usize> {
    let (patch, side) = split_node(n);
    let leaves = solver.mesh.leaves_under(patch);
    leaves.into_iter().map(move |leaf| node(leaf, side))
}

/// The push (§5.3.2): irradiance `h` taken at node `n` reaches every leaf below it, where it
/// adds `ρ·h` to the radiosity of its side and `τ·h` to that of the other side.
fn push(solver: &mut Solver, n: usize, h: Rgb64) {
    let (patch, side) = split_node(n);
    let nodes = &mut solver.nodes;
    for leaf in solver.mesh.leaves_under(patch) {
        let (l, other) = (node(leaf, side), node(leaf, side.other()));
        nodes.irradiance[l] += h;
        nodes.radiosity[l] += nodes.reflectance[l] * h;
        nodes.radiosity[other] += nodes.translucency[other] * h;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::AccelKind;
    use crate::scene::builtin;

    #[test]
    fn a_shot_stopped_before_it_is_complete_leaves_nothing_of_itself() {
        let scene = builtin::load("cornell").unwrap().unwrap();
        let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
        let options = SystemOptions::default();
        let (mesh, visibility) = prepare(&world, &options, false).unwrap();
        let settings = HierarchicalSettings::default();
        let mut solver = Solver::new(&world, mesh, &visibility, &options, &settings);
        solver.link_root_lights(&crate::progress::NoProgress, &Cancel::new());
        solver.refine(&mut RoundStats::default(), &Cancel::new());
        solver.nodes.push_pull(&solver.mesh);
        let mut shots = Shots::new(&solver);
        let (shooter, unshot) = shots.unshot_power(&solver);
        assert!(unshot > 0.0);

        let stopped = Cancel::new();
        stopped.request();
        let (shot, measured) = (shots.shot.clone(), shots.measured.clone());
        let gathered = solver.nodes.gathered.clone();
        assert!(shots.shot_from(&mut solver, shooter, &stopped).is_none());
        assert_eq!(shots.shot[..shot.len()], shot[..]);
        assert_eq!(shots.measured, measured);
        assert_eq!(solver.nodes.gathered[..gathered.len()], gathered[..]);
        assert!(
            solver.nodes.gathered[gathered.len()..]
                .iter()
                .all(|&h| h == Rgb64::BLACK)
        );
        assert_eq!(shots.unshot_power(&solver), (shooter, unshot));

        // Not stopped, the same shot sends everything: the shooter has nothing left unshot.
        let received = shots
            .shot_from(&mut solver, shooter, &Cancel::new())
            .unwrap();
        assert!(!received.is_empty());
        assert_eq!(shots.unshot_below(&solver, shooter), 0.0);
        assert!(shots.measured.iter().sum::<f64>() > measured.iter().sum::<f64>());
    }
}
