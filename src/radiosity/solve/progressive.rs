//! Progressive refinement (seed 000 §5.2, seed 004): repeatedly shoot the leaf with the
//! largest unshot power `|ΔB|·A` (luminance) to every other leaf through one column of
//! couplings, `ΔH_i = F_ij V_ij s`, `B_i += ρ_i ΔH_i`, `ΔB_i += ρ_i ΔH_i`, `ΔB_j −= s`; a
//! translucent receiver also passes `τ_i ΔH_i` to the other side `ī` of its leaf
//! (`B_ī += τ_i ΔH_i`, `ΔB_ī += τ_i ΔH_i`).
//!
//! The shot `s` is the unshot radiosity `ΔB_j`, or with overshooting (negative radiosity)
//! `ΔB_j + (ρ_j + τ_j) × ambient`: the light the patch will still receive is sent ahead,
//! leaving a negative unshot amount that later shots correct (shooting just that amount, no
//! more light ahead); the fixed point is unchanged. The ambient term (Cohen et al. 1988) is
//! `R · Σ_k ΔB_k A_k / Σ_k A_k` with `R = 1 / (1 − ρ̄)` and `ρ̄` the area-averaged albedo
//! `ρ + τ`; it is kept in the solution for display.
//!
//! Columns already computed are cached up to [`COLUMN_CACHE_BYTES`]: a leaf shot again costs
//! no form factors.

use super::SolveError;
use super::solution::{Solution, power_fraction, source_power};
use super::solver_kind::SolverKind;
use super::steady_state::{Bounce, BounceWatch};
use super::system::{Couplings, RadiositySystem};
use super::unshot_progress::UnshotProgress;
use crate::choice::Choice;
use crate::color::Rgb64;
use crate::progress::{Cancel, ProgressListener};
use std::time::Instant;

/// Memory for cached coupling columns, bytes.
pub const COLUMN_CACHE_BYTES: usize = 512 << 20;

/// Settings of progressive refinement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShootingSettings {
    /// Stop when the unshot power is at most this fraction of the source power.
    pub tolerance: f64,
    /// Stop after this many shots at the latest.
    pub max_shots: u64,
    /// Shoot ahead the light a patch is still expected to receive (negative radiosity).
    pub overshoot: bool,
}

impl Default for ShootingSettings {
    /// Tolerance 1e-4, at most 1 000 000 shots, no overshooting.
    fn default() -> Self {
        ShootingSettings {
            tolerance: 1e-4,
            max_shots: 1_000_000,
            overshoot: false,
        }
    }
}

/// Solves `system` by progressive refinement. `progress` advances on a log scale from the
/// first unshot fraction to the tolerance; `cancel` stops after the current shot and keeps
/// the state reached.
pub fn solve_progressive(
    system: &RadiositySystem,
    settings: &ShootingSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<Solution, SolveError> {
    let n = system.len();
    let mut solution = Solution::start(
        system,
        SolverKind::Progressive,
        SolverKind::Progressive.name(),
    );
    let mut unshot: Vec<Rgb64> = solution.radiosity.clone();
    let mut cache: Vec<Option<Couplings>> = vec![None; n];
    let mut cached_bytes = 0usize;
    let total_area = system.total_area();
    let mean_albedo = Rgb64::from(std::array::from_fn(|c| {
        (0..n)
            .map(|k| system.albedo(k)[c] * system.area[k])
            .sum::<f64>()
            / total_area
    }));
    let interreflection = mean_albedo.map(|r| 1.0 / (1.0 - r.min(0.999_999)));
    let mut bar = UnshotProgress::start(progress, settings.tolerance);
    let started = Instant::now();
    let mut form_factor_seconds = 0.0;
    let mut fraction = power_fraction(system, &unshot);
    solution.ambient = ambient(system, &unshot, total_area, interreflection);
    let mut bounces = BounceWatch::new(system.largest_albedo());
    let source = source_power(system).max(f64::MIN_POSITIVE);
    while fraction > settings.tolerance && (solution.iterations() as u64) < settings.max_shots {
        if cancel.is_requested() {
            solution.interrupted = true;
            break;
        }
        let j = brightest(system, &unshot);
        // Only light is sent ahead: a patch shooting back a negative unshot amount (light
        // sent ahead of it that it did not receive) shoots just that, so every shot of a
        // negative patch brings it to zero; overshooting it again would leave it where it
        // was and stall the solver on that patch.
        let overshoot = if settings.overshoot && unshot[j].luminance() > 0.0 {
            (system.albedo(j) * solution.ambient).map(|v| v.max(0.0))
        } else {
            Rgb64::BLACK
        };
        let shot = unshot[j] + overshoot;
        if cache[j].is_none() {
            let t = Instant::now();
            let column = system.column(j);
            form_factor_seconds += t.elapsed().as_secs_f64();
            if cached_bytes + column.bytes() <= COLUMN_CACHE_BYTES {
                cached_bytes += column.bytes();
                cache[j] = Some(column);
            } else {
                distribute(system, &column, shot, &mut solution, &mut unshot);
            }
        }
        if let Some(column) = &cache[j] {
            distribute(system, column, shot, &mut solution, &mut unshot);
        }
        unshot[j] -= shot;
        let before = fraction;
        fraction = power_fraction(system, &unshot);
        let sent = shot.map(f64::abs).luminance() * system.area[j];
        if let Bounce::Gaining(_) = bounces.shot(sent / source, before, fraction)? {
            break;
        }
        solution.ambient = ambient(system, &unshot, total_area, interreflection);
        solution.convergence.push(fraction);
        bar.reach(fraction);
    }
    bar.finish();
    solution.converged = fraction <= settings.tolerance;
    if !solution.interrupted {
        solution.direct_irradiance = Some(direct_from_emitters(system, &cache));
    }
    solution.seconds.form_factors = form_factor_seconds;
    solution.seconds.iterations = started.elapsed().as_secs_f64() - form_factor_seconds;
    Ok(solution)
}

/// Per element: the irradiance straight from the lights and the emitting elements,
/// `H_light,i + Σⱼ F_ij V_ij E_j` over the emitting elements `j`, W·m⁻², from the emitters'
/// columns in `cache` (they shoot first, so they are there unless the cache was full) or
/// computed again.
fn direct_from_emitters(system: &RadiositySystem, cache: &[Option<Couplings>]) -> Vec<Rgb64> {
    let mut direct = system.light_irradiance.clone();
    for j in (0..system.len()).filter(|&j| system.emission[j].max_channel() > 0.0) {
        let computed;
        let column = match &cache[j] {
            Some(column) => column,
            None => {
                computed = system.column(j);
                &computed
            }
        };
        for (&i, &f) in column.leaves.iter().zip(&column.values) {
            direct[i as usize] += system.emission[j] * f;
        }
    }
    direct
}

/// Adds a shot `s` from one leaf through its coupling column to every receiver.
fn distribute(
    system: &RadiositySystem,
    column: &Couplings,
    shot: Rgb64,
    solution: &mut Solution,
    unshot: &mut [Rgb64],
) {
    for (&i, &f) in column.leaves.iter().zip(&column.values) {
        let i = i as usize;
        let dh = shot * f;
        solution.irradiance[i] += dh;
        let reflected = system.reflectance[i] * dh;
        solution.radiosity[i] += reflected;
        unshot[i] += reflected;
        if !system.translucency[i].is_black() {
            let passed = system.translucency[i] * dh;
            let other = RadiositySystem::other_side(i);
            solution.radiosity[other] += passed;
            unshot[other] += passed;
        }
    }
}

/// The leaf with the largest unshot power `Y(|ΔB|)·A` (the first of equals).
fn brightest(system: &RadiositySystem, unshot: &[Rgb64]) -> usize {
    let mut best = (0, f64::NEG_INFINITY);
    for (k, d) in unshot.iter().enumerate() {
        let power = d.map(f64::abs).luminance() * system.area[k];
        if power > best.1 {
            best = (k, power);
        }
    }
    best.0
}

/// The ambient radiosity `R · Σ ΔB_k A_k / Σ A_k` per channel.
fn ambient(system: &RadiositySystem, unshot: &[Rgb64], total_area: f64, r: Rgb64) -> Rgb64 {
    Rgb64::from(std::array::from_fn(|c| {
        let sum: f64 = unshot.iter().zip(&system.area).map(|(d, a)| d[c] * a).sum();
        r[c] * sum / total_area
    }))
}
