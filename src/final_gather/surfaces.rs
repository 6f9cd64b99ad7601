//! The final gather at the reported surfaces: the irradiance of every element (side of a
//! leaf patch) measured anew once the solve is done, so that each reported surface's power
//! no longer rests on the links that brought it its light.
//!
//! Why: the hierarchical solvers hold each link to a share of the scene's power
//! (`--error`), and a leaf's radiosity is its mean; a surface that receives little — a block
//! face turned from the lamp, lit by the floor in the block's own shadow — sums many small
//! errors of one sign, and gathering it from the solved leaves alone keeps the floor's mean
//! over each leaf where the face sees the darkest part of it best (docs/VALIDATION.md).
//!
//! How: points spread over each reported surface's leaves (at least [`MIN_POINTS_PER_SIDE`]
//! per side of a leaf) and over each leaf by Owen-scrambled Sobol points, in rounds until the
//! surface's standard error is under the target ([`gather_surfaces`]); at each,
//! [`irradiance_sample`]: every light by a shadow ray (one point on each emitting surface,
//! weighed against the gather ray by multiple importance sampling), and one
//! cosine-distributed gather ray whose hit takes its own direct light by shadow rays and its
//! indirect light from the solution by one more gather ray ([`FinalGather`] with one light
//! sample and one gather ray). The solution's values enter
//! two reflections away from the reported surface, where their errors are weighed down by
//! two reflectances and averaged over many points. The rays are traced on the surfaces the
//! patches lie on (curved shapes as their facets).
//!
//! Each element's estimate carries the variance of its mean (the Sobol strata treated as
//! independent draws, which overstates it), so each surface's power has a standard error.
//! Deterministic: element `k` draws from stream `k` of the seed, whatever the threads.

use super::FinalGather;
use crate::color::Rgb64;
use crate::measure::SurfaceTable;
use crate::progress::{Cancel, ProgressListener};
use crate::radiosity::solve::{GatheredIrradiance, RadiositySystem, Shading, Solution};
use crate::sampling::{Moments, Sampler, SequenceKind};
use crate::trace::irradiance_sample;
use rayon::prelude::*;
use std::time::Instant;

/// Points per side of a leaf at least, so that each element's estimate has a variance.
pub const MIN_POINTS_PER_SIDE: u64 = 4;

/// Points per reported surface and side in the first round, spread by area.
pub const FIRST_POINTS: u64 = 1024;

/// Points per reported surface at most, both sides together (about 3 s of one core); a
/// surface that reaches it keeps the standard error it has.
pub const MAX_POINTS: u64 = 1 << 23;

/// Channels below this share of a surface's brightest channel do not hold its gather back.
const DIM_CHANNEL: f64 = 0.01;

/// Measures the irradiance of every element of `system` anew from `solution`, as the module
/// describes, in rounds: [`FIRST_POINTS`] points per reported surface and side spread by
/// area; then, for each surface whose incident power's standard error is still above
/// `target` of it (in any channel but the very dim), as many more points as the error says
/// it needs (2 to 16 times as many, up to [`MAX_POINTS`]), divided between its two sides by
/// the spread of their points so far (the dark inside of a box gets none) and over each side
/// by area. Element `k` draws the Sobol points of
/// stream `k` of `seed` in order, so the result is the same whatever the threads. `None`
/// when cancelled.
pub fn gather_surfaces(
    system: &RadiositySystem,
    solution: &Solution,
    target: f64,
    seed: u64,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Option<GatheredIrradiance> {
    let start = Instant::now();
    let world = system.visibility().world();
    let integrator = FinalGather::over(system, solution, Shading::Flat, 1, 1);
    let table = SurfaceTable::new(&system.world().scene, &system.world().geometry);
    let surface_of: Vec<usize> = (0..system.len())
        .map(|k| {
            let patch = system.patch(k);
            table.entry(patch.object, patch.face)
        })
        .collect();
    // What a W·m⁻² on each element adds to its surface's incident power, m².
    let weight: Vec<f64> = (0..system.len())
        .map(|k| system.coverage[k] * system.area[k])
        .collect();
    let mut side_area = vec![0.0; table.len()];
    for &leaf in &system.leaves {
        let patch = system.mesh.patch(leaf);
        side_area[table.entry(patch.object, patch.face)] += patch.area;
    }
    let mut wanted: Vec<u64> = (0..system.len())
        .map(|k| {
            let share = system.area[k] / side_area[surface_of[k]];
            ((FIRST_POINTS as f64 * share).ceil() as u64).max(MIN_POINTS_PER_SIDE)
        })
        .collect();
    let mut estimates = vec![Estimate::default(); system.len()];
    let mut active = vec![true; table.len()];
    loop {
        let round: Vec<usize> = (0..system.len())
            .filter(|&k| active[surface_of[k]] && estimates[k].moments.n < wanted[k])
            .collect();
        progress.start(round.len() as u64);
        let drawn: Vec<Option<Estimate>> = round
            .par_iter()
            .map(|&k| {
                if cancel.is_requested() {
                    return None;
                }
                let mut estimate = estimates[k];
                let patch = system.patch(k);
                let normal = system.elements[k].side.normal(patch).as_vec3();
                for i in estimate.moments.n..wanted[k] {
                    let mut sampler = Sampler::new(SequenceKind::Sobol, seed, k as u64, i as u32);
                    let [s, t] = sampler.next_2d().to_array().map(f64::from);
                    let x = patch.point_at(s, t).as_vec3();
                    let (direct, indirect) =
                        irradiance_sample(world, &integrator, (x, normal), &mut sampler);
                    estimate.add(direct, indirect);
                }
                progress.advance(1);
                Some(estimate)
            })
            .collect();
        progress.finish();
        for (&k, estimate) in round.iter().zip(drawn) {
            estimates[k] = estimate?;
        }
        // Each surface's incident power, the variance of its estimate and its points.
        let mut power = vec![(Rgb64::BLACK, Rgb64::BLACK, 0); table.len()];
        for (k, e) in estimates.iter().enumerate() {
            let (sum, variance, points) = &mut power[surface_of[k]];
            *sum += e.moments.mean() * weight[k];
            *variance += e.moments.variance_of_mean() * (weight[k] * weight[k]);
            *points += e.moments.n;
        }
        // The surfaces still short of the target: the channel furthest off, and the points
        // the surface is to have in all.
        let mut short = vec![None; table.len()];
        for (s, &(sum, variance, points)) in power.iter().enumerate() {
            if !active[s] {
                continue;
            }
            let brightest = sum.max_channel();
            let (relative, channel) = (0..3)
                .filter(|&c| sum[c] > DIM_CHANNEL * brightest)
                .map(|c| (variance[c].sqrt() / sum[c], c))
                .fold((0.0, 0), |a, b| if b.0 > a.0 { b } else { a });
            if relative <= target || points >= MAX_POINTS {
                active[s] = false;
                continue;
            }
            // The error falls as one over the root of the points: as many more as it says,
            // a tenth over lest the next round fall just short, in a power of two.
            let doublings = (1.1 * (relative / target).powi(2))
                .log2()
                .ceil()
                .clamp(1.0, 4.0);
            short[s] = Some((channel, (points << doublings as u32).min(MAX_POINTS)));
        }
        if !active.iter().any(|&a| a) {
            break;
        }
        // The points each side of a surface short of the target is to have: by the summed
        // spread of one point's estimate over its elements (each times its area), in the
        // surface's channel furthest off (Neyman's allocation between the two sides: the
        // dark inside of a box gets none); within a side by area, as in the first round.
        // Spreads per element would save more, but an element whose first points happened to
        // miss a rare bright one would then get few and keep its low mean: a bias.
        let mut spread = vec![[0.0; 2]; table.len()];
        for (k, e) in estimates.iter().enumerate() {
            if let Some((c, _)) = short[surface_of[k]] {
                spread[surface_of[k]][k % 2] += weight[k] * e.moments.spread()[c];
            }
        }
        for k in 0..system.len() {
            let s = surface_of[k];
            let Some((_, points)) = short[s] else {
                continue;
            };
            let side_share = spread[s][k % 2] / (spread[s][0] + spread[s][1]);
            let share = system.area[k] / side_area[s] * side_share;
            wanted[k] = wanted[k].max((points as f64 * share).ceil() as u64);
        }
    }
    Some(GatheredIrradiance {
        irradiance: estimates.iter().map(|e| e.moments.mean()).collect(),
        direct: estimates
            .iter()
            .map(|e| e.direct / e.moments.n as f64)
            .collect(),
        variance: estimates
            .iter()
            .map(|e| e.moments.variance_of_mean())
            .collect(),
        points: estimates.iter().map(|e| e.moments.n).sum(),
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// One element's samples: their moments and the sum of their direct part, W·m⁻².
#[derive(Clone, Copy, Default)]
struct Estimate {
    moments: Moments,
    direct: Rgb64,
}

impl Estimate {
    fn add(&mut self, direct: Rgb64, indirect: Rgb64) {
        self.moments.add(direct + indirect);
        self.direct += direct;
    }
}
