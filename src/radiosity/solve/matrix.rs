//! The full-matrix solver (seed 000 §5.1, seed 001): all couplings `F_ij V_ij` are assembled
//! (rows in parallel), then `B = S + ρ ⊙ (F B) + τ ⊙ (F̄ B)` (`F̄` the rows of the other
//! sides) is iterated by Jacobi or Gauss-Seidel sweeps
//! until the change of one sweep, as a fraction of the source power ([`power_fraction`]),
//! falls to the tolerance. Starting from `B = S`, a Jacobi sweep's change is exactly the
//! light not yet reflected, so the measure matches the progressive solver's unshot power.
//! Solved again after objects moved ([`solve_matrix_keeping`]), it takes the couplings no
//! move reached and starts from the solution before (`kept_couplings.rs`).

use super::SolveError;
use super::kept::KeptLinks;
use super::solution::{Solution, power_fraction};
use super::solver_kind::SolverKind;
use super::steady_state::{Bounce, BounceWatch};
use super::system::{Couplings, RadiositySystem};
use crate::color::Rgb64;
use crate::progress::{Cancel, ProgressListener};
use rayon::prelude::*;
use std::time::Instant;

/// Largest `patches²` the matrix solver accepts. Of the four side pairs of two patches
/// usually one couples (each lies in front of one side of the other), so about `patches²`
/// couplings are stored, 12 bytes each.
pub const MAX_MATRIX_ENTRIES: u64 = 200_000_000;

/// The iteration scheme (`--iteration`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Iteration {
    /// Every sweep uses only the previous sweep's radiosities.
    Jacobi,
    /// Every update uses the newest radiosities (converges in fewer sweeps).
    #[default]
    GaussSeidel,
}

crate::choice::named_values!(Iteration {
    Iteration::Jacobi = "jacobi", "Every sweep uses only the previous sweep's radiosities";
    Iteration::GaussSeidel = "gauss-seidel", "Every update uses the newest radiosities";
});

/// Settings of the matrix solver.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MatrixSettings {
    /// Jacobi or Gauss-Seidel.
    pub iteration: Iteration,
    /// Stop when a sweep changes radiosity by at most this fraction of the source power.
    pub tolerance: f64,
    /// Stop after this many sweeps at the latest.
    pub max_iterations: u32,
}

impl Default for MatrixSettings {
    /// Gauss-Seidel to 1e-4, at most 1000 sweeps.
    fn default() -> Self {
        MatrixSettings {
            iteration: Iteration::GaussSeidel,
            tolerance: 1e-4,
            max_iterations: 1000,
        }
    }
}

/// Assembles the coupling matrix of `system` and iterates it. `progress` counts assembled
/// rows, then sweeps; `cancel` stops either phase and keeps the state reached (an interrupted
/// assembly leaves the radiosity at the source term).
pub fn solve_matrix(
    system: &RadiositySystem,
    settings: &MatrixSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<Solution, SolveError> {
    solve_matrix_keeping(system, settings, progress, cancel, None)
}

/// [`solve_matrix`], taking the couplings `kept` from the solve before where no move
/// reached them and starting the iteration from its solution; keeps this solve's for the
/// next (`kept_couplings.rs`). `system` is to be built with its rays seeded by geometry
/// ([`RadiositySystem::with_progress_by_geometry`]), or the couplings kept differ from
/// those computed in the last bits.
pub fn solve_matrix_keeping(
    system: &RadiositySystem,
    settings: &MatrixSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
    kept: Option<&mut KeptLinks>,
) -> Result<Solution, SolveError> {
    let n = system.len();
    let patches = system.leaves.len();
    if (patches as u64) * (patches as u64) > MAX_MATRIX_ENTRIES {
        return Err(SolveError::MatrixTooLarge {
            patches,
            limit: MAX_MATRIX_ENTRIES,
        });
    }
    let mut solution =
        Solution::start(system, SolverKind::Matrix, settings.iteration.solver_name());
    let kept = kept.map(|kept| {
        kept.last_matrix = true;
        let view = kept.couplings.begin(system);
        (kept, view)
    });
    let start = Instant::now();
    progress.start(n as u64);
    let view = kept.as_ref().map(|(_, view)| view);
    let rows: Vec<Option<Couplings>> = (0..n)
        .into_par_iter()
        .map_init(
            || view.map_or_else(Vec::new, |view| view.scratch()),
            |scratch, i| {
                (!cancel.is_requested()).then(|| {
                    let row = match view {
                        Some(view) => view.row(system, i, scratch),
                        None => system.row(i),
                    };
                    progress.advance(1);
                    row
                })
            },
        )
        .collect();
    progress.finish();
    solution.seconds.form_factors = start.elapsed().as_secs_f64();
    let Some(rows) = rows.into_iter().collect::<Option<Vec<Couplings>>>() else {
        solution.interrupted = true;
        if let Some((kept, view)) = kept {
            kept.couplings.end(view, None);
        }
        return Ok(solution);
    };
    if let Some(view) = view {
        solution.radiosity = view.start(system);
    }
    let start = Instant::now();
    progress.start(settings.max_iterations as u64);
    let source: Vec<Rgb64> = (0..n).map(|k| system.source(k)).collect();
    let b = &mut solution.radiosity;
    let mut bounces = BounceWatch::new(system.largest_albedo());
    for _ in 0..settings.max_iterations {
        if cancel.is_requested() {
            solution.interrupted = true;
            break;
        }
        let change = match settings.iteration {
            Iteration::Jacobi => jacobi_sweep(system, &rows, &source, b),
            Iteration::GaussSeidel => gauss_seidel_sweep(system, &rows, &source, b),
        };
        let residual = power_fraction(system, &change);
        solution.convergence.push(residual);
        progress.advance(1);
        if residual <= settings.tolerance {
            solution.converged = true;
            break;
        }
        if let Bounce::Gaining(_) = bounces.gathered(residual, 1.0)? {
            break;
        }
    }
    progress.finish();
    solution.irradiance = (0..n)
        .into_par_iter()
        .map(|i| system.light_irradiance[i] + gather(&rows[i], b))
        .collect();
    solution.direct_irradiance = Some(
        (0..n)
            .into_par_iter()
            .map(|i| system.light_irradiance[i] + gather(&rows[i], &system.emission))
            .collect(),
    );
    solution.seconds.iterations = start.elapsed().as_secs_f64();
    if let Some((kept, view)) = kept {
        kept.couplings
            .end(view, Some((rows, solution.radiosity.clone())));
    }
    Ok(solution)
}

/// `Σ_j F_ij V_ij B_j` over one row, W·m⁻².
fn gather(row: &Couplings, b: &[Rgb64]) -> Rgb64 {
    let mut sum = Rgb64::BLACK;
    for (&j, &f) in row.leaves.iter().zip(&row.values) {
        sum += b[j as usize] * f;
    }
    sum
}

/// `S_i + ρ_i Σ_j F_ij B_j + τ_i Σ_j F_īj B_j` for element `i` (`ī` the other side of its
/// leaf, gathered only when the element is translucent).
fn update(
    system: &RadiositySystem,
    rows: &[Couplings],
    source: &[Rgb64],
    b: &[Rgb64],
    i: usize,
) -> Rgb64 {
    let own = gather(&rows[i], b);
    let other = if system.translucency[i].is_black() {
        Rgb64::BLACK
    } else {
        gather(&rows[RadiositySystem::other_side(i)], b)
    };
    source[i] + system.scattered(i, own, other)
}

/// One Jacobi sweep (rows in parallel); returns the change per element.
fn jacobi_sweep(
    system: &RadiositySystem,
    rows: &[Couplings],
    source: &[Rgb64],
    b: &mut Vec<Rgb64>,
) -> Vec<Rgb64> {
    let next: Vec<Rgb64> = (0..b.len())
        .into_par_iter()
        .map(|i| update(system, rows, source, b, i))
        .collect();
    let change = next.iter().zip(b.iter()).map(|(&x, &y)| x - y).collect();
    *b = next;
    change
}

/// One Gauss-Seidel sweep in element order, in place; returns the change per element.
fn gauss_seidel_sweep(
    system: &RadiositySystem,
    rows: &[Couplings],
    source: &[Rgb64],
    b: &mut [Rgb64],
) -> Vec<Rgb64> {
    (0..b.len())
        .map(|i| {
            let next = update(system, rows, source, b, i);
            let old = std::mem::replace(&mut b[i], next);
            next - old
        })
        .collect()
}

impl Iteration {
    /// The matrix solver's name in reports with this scheme: `matrix-jacobi` or
    /// `matrix-gauss-seidel`.
    pub fn solver_name(self) -> &'static str {
        match self {
            Iteration::Jacobi => "matrix-jacobi",
            Iteration::GaussSeidel => "matrix-gauss-seidel",
        }
    }
}
