//! After a move, which re-converges the light faster from the solution before: a gather
//! started from it (Gauss–Seidel) or shooting what it now lacks and has too much of
//! (negative shooting, seed 000 requirement 5.1: Southwell iteration on the residual)?
//!
//! On one flat radiosity system — the Cornell box on the matrix solver's default mesh, its
//! coupling matrix `F_ij V_ij` computed in full before and after the light moves 5 cm — four
//! ways solve the moved box until their error against its exact solution (Gauss–Seidel to
//! 10⁻¹³) is at most the target share of the power: Gauss–Seidel from the emission and from
//! the solution before, shooting from the emission (progressive refinement) and from the
//! solution before, shooting its residual `S + ρ·F·B_before − B_before`. Printed per move:
//! the couplings that changed, the sweeps or shots, the couplings visited in units of whole
//! sweeps, and the seconds. Shooting checks its error every 64 shots.
//!
//! Run: `cargo bench --bench move_convergence [-- TARGET]` (TARGET defaults to 1e-4); a
//! name given to `cargo bench -- NAME` that is not part of this one's skips it.

use glam::Vec3;
use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::Arc;
use std::time::Instant;
use strahl::accel::AccelKind;
use strahl::color::Rgb64;
use strahl::method::{RadiositySettings, SolverKind};
use strahl::radiosity::solve::RadiositySystem;
use strahl::scene::{Scene, builtin};
use strahl::world::World;

/// Shots between two looks at a shooting solve's error.
const SHOTS_PER_CHECK: usize = 64;

/// One row or column of the coupling matrix: element indices and `F_ij V_ij`.
type Line = (Vec<u32>, Vec<f64>);

/// The Cornell box's system on the matrix solver's default mesh.
fn system(scene: &Scene) -> RadiositySystem {
    let world = Arc::new(World::new(scene.clone(), AccelKind::Bvh).expect("the Cornell box"));
    let options = RadiositySettings::new(SolverKind::Matrix).system;
    RadiositySystem::new(&world, options).expect("the Cornell box meshes")
}

/// Every row of `system`'s coupling matrix, computed in parallel.
fn rows(system: &RadiositySystem) -> Vec<Line> {
    (0..system.len())
        .into_par_iter()
        .map(|i| {
            let row = system.row(i);
            (row.leaves, row.values)
        })
        .collect()
}

/// The columns of the matrix whose rows are `rows`.
fn columns(rows: &[Line]) -> Vec<Line> {
    let mut columns = vec![(Vec::new(), Vec::new()); rows.len()];
    for (i, (js, fs)) in rows.iter().enumerate() {
        for (&j, &f) in js.iter().zip(fs) {
            columns[j as usize].0.push(i as u32);
            columns[j as usize].1.push(f);
        }
    }
    columns
}

/// Entries that differ between two matrices given by rows (changed, gained or lost).
fn changed_entries(before: &[Line], after: &[Line]) -> usize {
    before
        .iter()
        .zip(after)
        .filter(|(b, a)| b != a)
        .map(|((bj, bf), (aj, af))| {
            let old: HashMap<u32, f64> = bj.iter().copied().zip(bf.iter().copied()).collect();
            let new: HashMap<u32, f64> = aj.iter().copied().zip(af.iter().copied()).collect();
            let changed = new.iter().filter(|(j, f)| old.get(j) != Some(f)).count();
            changed + old.keys().filter(|j| !new.contains_key(j)).count()
        })
        .sum()
}

/// `Σ A·Y(|v|)` over the elements, W.
fn power(system: &RadiositySystem, v: &[Rgb64]) -> f64 {
    v.iter()
        .zip(&system.area)
        .map(|(b, a)| b.map(f64::abs).luminance() * a)
        .sum()
}

/// The power of `b − exact` as a share of the power of `exact`.
fn error(system: &RadiositySystem, b: &[Rgb64], exact: &[Rgb64]) -> f64 {
    let d: Vec<Rgb64> = b.iter().zip(exact).map(|(&x, &y)| x - y).collect();
    power(system, &d) / power(system, exact)
}

/// `S_i + ρ_i Σ_j F_ij B_j` for element `i` (the Cornell box has no translucent surface).
fn gathered(system: &RadiositySystem, row: &Line, b: &[Rgb64], i: usize) -> Rgb64 {
    let (js, fs) = row;
    let h = js
        .iter()
        .zip(fs)
        .fold(Rgb64::BLACK, |h, (&j, &f)| h + b[j as usize] * f);
    system.source(i) + system.scattered(i, h, Rgb64::BLACK)
}

/// Gauss–Seidel sweeps from `b` until `done(b)`; the sweeps.
fn gauss_seidel(
    system: &RadiositySystem,
    rows: &[Line],
    b: &mut [Rgb64],
    done: impl Fn(&[Rgb64]) -> bool,
) -> usize {
    let mut sweeps = 0;
    while !done(b) {
        for (i, row) in rows.iter().enumerate() {
            b[i] = gathered(system, row, b, i);
        }
        sweeps += 1;
    }
    sweeps
}

/// Southwell iteration: the element with the most unshot power `A·Y(|r|)` shoots `r`
/// through its column, until `done(b)`; the shots and the couplings visited.
fn shoot(
    system: &RadiositySystem,
    columns: &[Line],
    b: &mut [Rgb64],
    unshot: &mut [Rgb64],
    done: impl Fn(&[Rgb64]) -> bool,
) -> (usize, u64) {
    let (mut shots, mut visited) = (0, 0u64);
    while shots % SHOTS_PER_CHECK != 0 || !done(b) {
        let j = (0..unshot.len())
            .max_by(|&x, &y| {
                let p = |k: usize| unshot[k].map(f64::abs).luminance() * system.area[k];
                p(x).total_cmp(&p(y))
            })
            .unwrap_or(0);
        let sent = std::mem::replace(&mut unshot[j], Rgb64::BLACK);
        let (is, fs) = &columns[j];
        for (&i, &f) in is.iter().zip(fs) {
            let reflected = system.reflectance[i as usize] * (sent * f);
            b[i as usize] += reflected;
            unshot[i as usize] += reflected;
        }
        visited += is.len() as u64;
        shots += 1;
    }
    (shots, visited)
}

/// Gauss–Seidel from `b` until a sweep changes the power by at most 10⁻¹³ of it.
fn solve_exactly(system: &RadiositySystem, rows: &[Line], b: &mut [Rgb64]) {
    loop {
        let mut change = 0.0;
        for (i, row) in rows.iter().enumerate() {
            let new = gathered(system, row, b, i);
            change += (new - b[i]).map(f64::abs).luminance() * system.area[i];
            b[i] = new;
        }
        if change <= 1e-13 * power(system, b) {
            return;
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    // `cargo bench -- NAME` passes NAME to every bench: run only when it names this one.
    let filtered = args
        .iter()
        .filter(|a| !a.starts_with('-') && a.parse::<f64>().is_err())
        .any(|a| !"move_convergence".contains(a.as_str()));
    if filtered {
        return;
    }
    let target: f64 = args.iter().find_map(|a| a.parse().ok()).unwrap_or(1e-4);
    let mut scene = builtin::load("cornell")
        .expect("built-in scene")
        .expect("valid scene");
    let before = system(&scene);
    let mut rows_before = rows(&before);
    let mut solution: Vec<Rgb64> = (0..before.len()).map(|k| before.source(k)).collect();
    solve_exactly(&before, &rows_before, &mut solution);
    println!(
        "Cornell box, {} elements; target error {target:e} of the power",
        before.len()
    );
    for step in 0..2 {
        let dx = if step == 0 { 0.05 } else { -0.05 };
        scene
            .move_named("light", Vec3::new(dx, 0.0, 0.02))
            .expect("the light");
        let after = system(&scene);
        let rows_after = rows(&after);
        let columns_after = columns(&rows_after);
        let entries: u64 = rows_after.iter().map(|r| r.0.len() as u64).sum();
        let mut moved_exact = solution.clone();
        solve_exactly(&after, &rows_after, &mut moved_exact);
        let done = |b: &[Rgb64]| error(&after, b, &moved_exact) <= target;
        println!(
            "light moved {dx:+} m in x, 0.02 m in z: {} of {entries} couplings changed; \
             the solution before is {:.2} % off",
            changed_entries(&rows_before, &rows_after),
            100.0 * error(&after, &solution, &moved_exact)
        );
        let emission: Vec<Rgb64> = (0..after.len()).map(|k| after.source(k)).collect();
        for (name, start) in [
            ("from the emission", &emission),
            ("from the solution before", &solution),
        ] {
            let mut b = start.clone();
            let t = Instant::now();
            let sweeps = gauss_seidel(&after, &rows_after, &mut b, done);
            println!(
                "  gather (Gauss–Seidel) {name}: {sweeps} sweeps, {:.4} s",
                t.elapsed().as_secs_f64()
            );
        }
        let mut b = emission.clone();
        let mut unshot = emission.clone();
        let t = Instant::now();
        let (shots, visited) = shoot(&after, &columns_after, &mut b, &mut unshot, done);
        println!(
            "  shooting from the emission: {shots} shots, {:.2} sweeps of couplings, {:.4} s",
            visited as f64 / entries as f64,
            t.elapsed().as_secs_f64()
        );
        let t = Instant::now();
        let mut unshot: Vec<Rgb64> = (0..after.len())
            .map(|i| gathered(&after, &rows_after[i], &solution, i) - solution[i])
            .collect();
        let mut b: Vec<Rgb64> = solution.iter().zip(&unshot).map(|(&s, &r)| s + r).collect();
        let (shots, visited) = shoot(&after, &columns_after, &mut b, &mut unshot, done);
        println!(
            "  negative shooting from the solution before: {shots} shots, {:.2} sweeps of \
             couplings (and one for the residual), {:.4} s",
            visited as f64 / entries as f64,
            t.elapsed().as_secs_f64()
        );
        solution = moved_exact;
        rows_before = rows_after;
    }
}
