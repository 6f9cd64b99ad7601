//! Hierarchical shooting (seed 000 §5.3): progressive refinement whose receivers take the
//! light at the level of their quadtree an oracle allows.
//!
//! The lights are linked to the roots and their links refined as in hierarchical radiosity;
//! then, shot by shot, the leaf side with the most unshot power `Y(|B − B_shot|)·A` sends its
//! unshot radiosity to every root side. A receiver takes the shot at a node when the power it
//! brings there is certain enough — `A·(F_max − F_min)·Y(ΔB) ≤ ε·Φ` (Lischinski) or
//! `A·F_max·Y(ΔB) < ε·Φ` (BFA) — or the node is at the minimum area; otherwise the node is
//! split and its children try. What a node takes is pushed down to its leaves (§5.3.2), where
//! it becomes radiosity, before the next shooter is chosen. Shooting stops when the unshot
//! power is at most the tolerance times the source power, or after the most shots allowed.
//!
//! Receivers are judged level by level: all links of one level are computed in parallel, in
//! an order that does not depend on the thread count.

use super::nodes::{node, split_node};
use super::oracle::accepts_shot;
use super::solver::{RoundStats, Solver, children, prepare};
use super::{HierarchicalSettings, RefinePass};
use crate::color::Rgb64;
use crate::progress::{Cancel, ProgressListener};
use crate::radiosity::element::Side;
use crate::radiosity::solve::unshot_progress::UnshotProgress;
use crate::radiosity::solve::{
    PhaseTimes, RadiositySystem, ShootingSettings, Solution, SolveError, SolverKind, SystemOptions,
};
use crate::world::World;
use std::time::Instant;

/// Solves `world`'s scene by hierarchical shooting: the oracle, error and minimum area come
/// from `settings`, the tolerance and the most shots from `shooting` (overshooting is not
/// used). `progress` advances on a log scale of the unshot power; `cancel` stops after the
/// current shot and keeps the state reached.
pub fn solve_hierarchical_shooting<'w>(
    world: &'w World,
    options: SystemOptions,
    settings: &HierarchicalSettings,
    shooting: &ShootingSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<(RadiositySystem<'w>, Solution), SolveError> {
    let start = Instant::now();
    let (mesh, visibility) = prepare(world, &options)?;
    let light_settings = HierarchicalSettings {
        refine_pass: RefinePass::All,
        ..*settings
    };
    let mut solver = Solver::new(world, mesh, &visibility, &options, &light_settings);
    solver.link_root_lights();
    solver.refine(&mut RoundStats::default(), cancel);
    let (_, source) = solver.nodes.push_pull(&solver.mesh);
    let mut times = PhaseTimes {
        setup: start.elapsed().as_secs_f64(),
        ..PhaseTimes::default()
    };
    let mut shot = vec![Rgb64::BLACK; solver.nodes.radiosity.len()];
    let mut convergence = Vec::new();
    let mut bar = UnshotProgress::start(progress, shooting.tolerance);
    let mut interrupted = false;
    let source = source.max(f64::MIN_POSITIVE);
    let mut leaves = leaf_sides(&solver);
    let mut leaves_of = shot.len();
    let (mut shooter, unshot) = unshot_power(&solver, &leaves, &shot);
    let mut fraction = unshot / source;
    while fraction > shooting.tolerance && (convergence.len() as u64) < shooting.max_shots {
        if cancel.is_requested() {
            interrupted = true;
            break;
        }
        let sent = solver.nodes.radiosity[shooter] - shot[shooter];
        shot[shooter] = solver.nodes.radiosity[shooter];
        let t = Instant::now();
        let received = shoot(&mut solver, &mut shot, shooter, sent);
        times.form_factors += t.elapsed().as_secs_f64();
        let t = Instant::now();
        for (receiver, irradiance) in received {
            push(&mut solver, receiver, irradiance);
        }
        if shot.len() != leaves_of {
            (leaves, leaves_of) = (leaf_sides(&solver), shot.len());
        }
        let (next, unshot) = unshot_power(&solver, &leaves, &shot);
        times.iterations += t.elapsed().as_secs_f64();
        (shooter, fraction) = (next, unshot / source);
        convergence.push(fraction);
        bar.reach(fraction);
    }
    bar.finish();
    // Every leaf already holds what was pushed to it; this makes the inner nodes' means and
    // the light share of the irradiance consistent for the report.
    solver.nodes.push_pull(&solver.mesh);
    let converged = fraction <= shooting.tolerance;
    let kind = SolverKind::HierarchicalShooting(settings.oracle);
    solver.into_solution(
        kind,
        options,
        times,
        convergence,
        converged,
        interrupted,
        Vec::new(),
    )
}

/// Every leaf side as its node and area, root by root.
fn leaf_sides(solver: &Solver) -> Vec<(usize, f64)> {
    let mesh = &solver.mesh;
    mesh.leaves()
        .into_iter()
        .flat_map(|l| Side::BOTH.map(|s| (node(l, s), mesh.patch(l).area)))
        .collect()
}

/// The leaf side of `leaves` (nodes and areas) with the most unshot power (the first of
/// equals) and the total unshot power `Σ Y(|B − B_shot|)·A` over them, W.
fn unshot_power(solver: &Solver, leaves: &[(usize, f64)], shot: &[Rgb64]) -> (usize, f64) {
    let mut best = (0, f64::NEG_INFINITY);
    let mut total = 0.0;
    for &(n, area) in leaves {
        let power = (solver.nodes.radiosity[n] - shot[n])
            .map(f64::abs)
            .luminance()
            * area;
        total += power;
        if power > best.1 {
            best = (n, power);
        }
    }
    (best.0, total)
}

/// Sends radiosity `sent` from leaf side `shooter` to every root side, each taking it at the
/// level the oracle allows (nodes split on the way; their children start with their shot
/// radiosity). Returns the nodes that took it and the irradiance each took, W·m⁻².
fn shoot(
    solver: &mut Solver,
    shot: &mut Vec<Rgb64>,
    shooter: usize,
    sent: Rgb64,
) -> Vec<(usize, Rgb64)> {
    let mut received = Vec::new();
    let y = sent.map(f64::abs).luminance();
    let mut frontier: Vec<(usize, usize, bool)> = solver
        .root_nodes()
        .into_iter()
        .map(|r| (r, shooter, false))
        .collect();
    while !frontier.is_empty() {
        let links = solver.create_links(&frontier);
        let mut next = Vec::new();
        let mut accepted = Vec::new();
        for link in links {
            if accepts_shot(
                solver.settings.oracle,
                &link,
                y,
                &solver.mesh,
                &solver.limits,
            ) {
                accepted.push(link);
                continue;
            }
            for child in children(&mut solver.mesh, link.receiver as usize) {
                next.push((child, shooter, link.unoccluded));
            }
        }
        solver.nodes.grow(&solver.world.scene, &solver.mesh);
        while shot.len() < solver.nodes.radiosity.len() {
            let (patch, side) = split_node(shot.len());
            let parent = solver.mesh.patch(patch).parent.map(|p| node(p, side));
            shot.push(parent.map_or(Rgb64::BLACK, |p| shot[p]));
        }
        // Taken after the splits of this level, which may have split an accepted receiver
        // (through its other side).
        for link in accepted {
            for (n, irradiance) in link.divide(&solver.mesh, sent * link.coupling) {
                solver.nodes.gathered[n] += irradiance;
                received.push((n, irradiance));
            }
        }
        frontier = next;
    }
    received
}

/// The push (§5.3.2): irradiance `h` taken at node `n` reaches every leaf below it, where it
/// adds `ρ·h` to the radiosity.
fn push(solver: &mut Solver, n: usize, h: Rgb64) {
    let (patch, side) = split_node(n);
    let nodes = &mut solver.nodes;
    for leaf in solver.mesh.leaves_under(patch) {
        let l = node(leaf, side);
        nodes.irradiance[l] += h;
        nodes.radiosity[l] += nodes.reflectance[l] * h;
    }
}
