//! A light-tracing run: photons from every source traced in parallel batches into fixed-point
//! tallies, merged into the power per reported surface.

use super::scatter::scatter_photon;
use super::sources::PhotonSources;
use super::tally::{Fixed, FixedBalance, Tally, add_fixed};
use crate::color::{Rgb, Rgb64};
use crate::geometry::spawn_ray;
use crate::measure::{Measurement, Stats, SurfacePower, SurfaceTable};
use crate::progress::{Cancel, ProgressListener};
use crate::sampling::{Sampler, SequenceKind};
use crate::world::World;
use rayon::prelude::*;
use std::time::Instant;

/// Fixed-point units of the total emitted power (largest channel).
const FIXED_POINT_TOTAL: f64 = (1u64 << 62) as f64;
/// Photons per progress step are at least this many.
const MIN_BATCH: u64 = 4096;
/// Number of progress steps of a run (at most).
const BATCHES: u64 = 200;
/// Photons per progress step are at most this many, so that a stop request is answered
/// within a fraction of a second however many photons the run has.
const MAX_BATCH: u64 = 1 << 18;
/// Memory budget of the per-worker tallies, bytes.
const TALLY_BUDGET: usize = 256 << 20;

/// Settings of a light-tracing run.
#[derive(Clone, Debug)]
pub struct LightTraceSettings {
    /// Photons to trace.
    pub photons: u64,
    /// Seed of all random numbers.
    pub seed: u64,
    /// Scattering events after which a photon is absorbed where it is.
    pub max_bounces: u32,
}

impl Default for LightTraceSettings {
    /// One million photons, seed 0, at most 1000 bounces.
    fn default() -> Self {
        LightTraceSettings {
            photons: 1_000_000,
            seed: 0,
            max_bounces: 1000,
        }
    }
}

/// Why light tracing cannot run.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum LightTraceError {
    /// No light with positive power.
    #[error("the scene has no light with positive power")]
    NoLights,
    /// Zero photons asked for.
    #[error("at least one photon is needed")]
    NoPhotons,
}

/// The result of a light-tracing run.
#[derive(Clone, Debug)]
pub struct LightTraceOutput {
    /// Per-surface and scene-wide power, W, scaled to the full photon count when the run was
    /// cancelled early.
    pub power: SurfacePower,
    /// Photons asked for.
    pub photons: u64,
    /// Photons traced (less than `photons` when cancelled).
    pub photons_traced: u64,
    /// Closest-hit ray queries.
    pub rays: u64,
    /// Photons that left the scene.
    pub escaped_photons: u64,
    /// Photons stopped by the bounce limit.
    pub truncated_paths: u64,
    /// Sources that received no photon (too little power for the photon count).
    pub unsampled_sources: usize,
    /// Number of photon sources.
    pub sources: usize,
    /// Wall-clock seconds of the run.
    pub seconds: f64,
    /// The settings used.
    pub settings: LightTraceSettings,
}

impl LightTraceOutput {
    /// The solver's name in reports.
    pub const SOLVER: &'static str = "light-trace";

    /// True when every photon asked for was traced.
    pub fn complete(&self) -> bool {
        self.photons_traced == self.photons
    }

    /// What this run measured: the power per reported surface and [`Self::stats`].
    pub fn measurement(&self) -> Measurement {
        Measurement {
            solver: Self::SOLVER,
            power: self.power.clone(),
            stats: self.stats(),
        }
    }

    /// The statistics of this run: time, rays, photons and sources.
    pub fn stats(&self) -> Stats {
        let mut stats = Stats {
            seconds: self.seconds,
            rays: self.rays,
            ..Stats::default()
        };
        stats.insert("photons", self.photons);
        stats.insert("photons_traced", self.photons_traced);
        stats.insert("complete", self.complete());
        stats.insert("seed", self.settings.seed);
        stats.insert("max_bounces", self.settings.max_bounces);
        stats.insert("escaped_photons", self.escaped_photons);
        stats.insert("truncated_paths", self.truncated_paths);
        stats.insert("sources", self.sources);
        stats.insert("unsampled_sources", self.unsampled_sources);
        stats
    }
}

/// Everything a worker needs to trace photon `i`.
struct Tracer<'a> {
    world: &'a World,
    sources: PhotonSources,
    /// Cumulative power fractions of the sources (last = 1).
    cdf: Vec<f64>,
    /// Photons per source over the whole run.
    counts: Vec<u64>,
    table: &'a SurfaceTable,
    /// Fixed-point units per watt.
    scale: f64,
    settings: LightTraceSettings,
}

/// Magnitude below which a fixed-point value fits an `i64` (2⁶² with room to spare).
const FITS_I64: f64 = 9.0e18;

/// `x` rounded to the nearest integer, as `round() as i128` does; through `i64` (one machine
/// instruction instead of a library call) whenever the value fits, which a photon's power
/// almost always does.
#[inline]
fn to_fixed(x: f64) -> i128 {
    let r = x.round();
    if r.abs() < FITS_I64 {
        r as i64 as i128
    } else {
        r as i128
    }
}

/// `q as f64`, through `i64` whenever it fits (the same rounding, without a library call).
#[inline]
fn from_fixed(q: i128) -> f64 {
    match i64::try_from(q) {
        Ok(v) => v as f64,
        Err(_) => q as f64,
    }
}

/// Radical inverse in base 2 of `i`, in `[0, 1)`.
fn radical_inverse(i: u64) -> f64 {
    i.reverse_bits() as f64 * (1.0 / 18_446_744_073_709_551_616.0)
}

impl Tracer<'_> {
    fn source_of(&self, photon: u64) -> usize {
        let u = radical_inverse(photon);
        self.cdf
            .partition_point(|&c| c <= u)
            .min(self.cdf.len() - 1)
    }

    fn quantize(&self, p: Rgb64) -> Fixed {
        p.to_array().map(|c| to_fixed(c * self.scale))
    }

    fn watts(&self, q: Fixed) -> Rgb64 {
        Rgb64::from(q.map(|c| from_fixed(c) / self.scale))
    }

    fn trace_photon(&self, index: u64, tally: &mut Tally) {
        let world = self.world;
        let mut sampler = Sampler::new(SequenceKind::Random, self.settings.seed, index, 0);
        let source = self.source_of(index);
        let photon = self.sources.emit(world, source, &mut sampler);
        let count = self.counts[source] as f64;
        let share = photon.power.to_f64().map(|c| c / count);
        let emitted = self.quantize(share);
        let mut q = self.quantize(share.map(|c| c * photon.carried));
        match photon.surface {
            Some((object, face)) => {
                let e = self.table.entry(object, face);
                add_fixed(&mut tally.entries[e].emitted, emitted);
            }
            None => add_fixed(&mut tally.light_emission, emitted),
        }
        add_fixed(&mut tally.escaped, [0, 1, 2].map(|c| emitted[c] - q[c]));
        let mut ray = photon.ray;
        let mut bounces = 0;
        loop {
            tally.rays += 1;
            let Some(hit) = world.intersect(&ray) else {
                add_fixed(&mut tally.escaped, q);
                tally.escaped_photons += 1;
                return;
            };
            let entry = &mut tally.entries[self.table.entry(hit.object, hit.face)];
            add_fixed(&mut entry.incident, q);
            let scattered = if bounces < self.settings.max_bounces {
                scatter_photon(&world.scene, &hit, ray.dir, self.watts(q), &mut sampler)
            } else {
                tally.truncated_paths += 1;
                None
            };
            let out = scattered.map(|s| (s.dir, self.quantize(s.power)));
            match out {
                Some((dir, q_out)) if q_out != [0; 3] => {
                    add_fixed(&mut entry.absorbed, [0, 1, 2].map(|c| q[c] - q_out[c]));
                    add_fixed(&mut entry.reflected, q_out);
                    q = q_out;
                    ray = spawn_ray(hit.p, hit.ng, dir);
                    bounces += 1;
                }
                _ => {
                    add_fixed(&mut entry.absorbed, q);
                    return;
                }
            }
        }
    }
}

/// Photons per source for a run of `photons`: how many photon indices fall in each source's
/// interval of the cumulative power (photon `i` goes to the first source whose cumulative
/// power exceeds its radical inverse, the last one if none does), counted without visiting
/// every photon (see [`photons_below`]).
fn photons_per_source(cdf: &[f64], photons: u64) -> Vec<u64> {
    let mut counts = Vec::with_capacity(cdf.len());
    let mut before = 0;
    for &c in &cdf[..cdf.len() - 1] {
        let below = photons_below(c, photons);
        counts.push(below - before);
        before = below;
    }
    counts.push(photons - before);
    counts
}

/// How many of the photons `0..n` have a radical inverse (as [`radical_inverse`] rounds it)
/// below `c`. The indices split into aligned blocks `a..a + 2ᵐ`, one per set bit of `n`;
/// within a block the reversed bits are `j·2⁶⁴⁻ᵐ + reverse(a)` for every `j < 2ᵐ`, increasing
/// with `j`, so the photons below `c` are a prefix of the `j`s, found by bisection. 64 · 64
/// steps at most, for any `n`.
fn photons_below(c: f64, n: u64) -> u64 {
    let mut count = 0;
    let mut start = 0u64;
    for m in (0..64).rev() {
        if (n >> m) & 1 == 0 {
            continue;
        }
        let low = start.reverse_bits();
        let below = |j: u64| {
            let bits = if m == 0 { low } else { (j << (64 - m)) | low };
            bits as f64 * (1.0 / 18_446_744_073_709_551_616.0) < c
        };
        let (mut lo, mut hi) = (0u64, 1u64 << m);
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            if below(mid) {
                lo = mid + 1;
            } else {
                hi = mid;
            }
        }
        count += lo;
        start += 1 << m;
    }
    count
}

/// Traces `settings.photons` photons through `world` on the current rayon pool. Progress is
/// reported in photons; when `cancel` is requested the run stops after the current batch and
/// the result is scaled to the full photon count.
pub fn trace_light(
    world: &World,
    settings: &LightTraceSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<LightTraceOutput, LightTraceError> {
    let start = Instant::now();
    if settings.photons == 0 {
        return Err(LightTraceError::NoPhotons);
    }
    let sources = PhotonSources::new(world);
    if sources.sources.is_empty() {
        return Err(LightTraceError::NoLights);
    }
    let weights: Vec<f64> = sources
        .sources
        .iter()
        .map(|s| s.power.to_f64().to_array().iter().sum())
        .collect();
    let total: f64 = weights.iter().sum();
    let mut cdf: Vec<f64> = weights
        .iter()
        .scan(0.0, |acc, w| {
            *acc += w / total;
            Some(*acc)
        })
        .collect();
    if let Some(last) = cdf.last_mut() {
        *last = 1.0;
    }
    let counts = photons_per_source(&cdf, settings.photons);
    let largest_channel = sources
        .sources
        .iter()
        .map(|s| s.power)
        .sum::<Rgb>()
        .max_channel() as f64;
    let table = SurfaceTable::new(&world.scene, &world.geometry);
    let tracer = Tracer {
        world,
        cdf,
        counts,
        table: &table,
        scale: FIXED_POINT_TOTAL / largest_channel,
        settings: settings.clone(),
        sources,
    };
    let workers = rayon::current_num_threads().max(1) * 4;
    let per_tally = table.len().max(1) * std::mem::size_of::<FixedBalance>();
    let slots = workers.min(TALLY_BUDGET / per_tally).max(1);
    let mut tallies = vec![Tally::new(table.len()); slots];
    let batch = settings
        .photons
        .div_ceil(BATCHES)
        .clamp(MIN_BATCH, MAX_BATCH);
    progress.start(settings.photons);
    let mut done = 0u64;
    while done < settings.photons && !cancel.is_requested() {
        let end = (done + batch).min(settings.photons);
        let span = end - done;
        tallies
            .par_iter_mut()
            .enumerate()
            .for_each(|(slot, tally)| {
                let from = done + span * slot as u64 / slots as u64;
                let to = done + span * (slot as u64 + 1) / slots as u64;
                for i in from..to {
                    tracer.trace_photon(i, tally);
                }
            });
        progress.advance(span);
        done = end;
    }
    progress.finish();
    let mut sum = Tally::new(table.len());
    for t in &tallies {
        sum.merge(t);
    }
    let mut power = SurfacePower::new(table.clone());
    for (e, b) in sum.entries.iter().enumerate() {
        let out = power.balance_mut(e);
        out.incident = tracer.watts(b.incident);
        out.absorbed = tracer.watts(b.absorbed);
        out.emitted = tracer.watts(b.emitted);
        out.reflected = tracer.watts(b.reflected);
    }
    power.add_light_emission(tracer.watts(sum.light_emission));
    power.add_escaped(tracer.watts(sum.escaped));
    if done > 0 && done < settings.photons {
        power.scale(settings.photons as f64 / done as f64);
    }
    Ok(LightTraceOutput {
        power,
        photons: settings.photons,
        photons_traced: done,
        rays: sum.rays,
        escaped_photons: sum.escaped_photons,
        truncated_paths: sum.truncated_paths,
        unsampled_sources: tracer.counts.iter().filter(|&&c| c == 0).count(),
        sources: tracer.counts.len(),
        seconds: start.elapsed().as_secs_f64(),
        settings: settings.clone(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn photons_per_source_counts_as_visiting_every_photon_does() {
        let cdfs: [&[f64]; 4] = [
            &[1.0],
            &[0.5, 1.0],
            &[0.1234567, 0.1234568, 0.75, 1.0],
            &[1e-9, 0.3333333333333333, 0.9999999999, 1.0],
        ];
        for cdf in cdfs {
            for n in [1u64, 2, 3, 1000, 4096, 65_537, 1_000_003] {
                let mut brute = vec![0u64; cdf.len()];
                for i in 0..n {
                    let u = radical_inverse(i);
                    brute[cdf.partition_point(|&x| x <= u).min(cdf.len() - 1)] += 1;
                }
                assert_eq!(photons_per_source(cdf, n), brute, "{cdf:?} {n}");
            }
        }
        // Any count, at once: a hundred billion photons split by their share.
        let counts = photons_per_source(&[0.25, 1.0], 100_000_000_000);
        assert_eq!(counts, vec![25_000_000_000, 75_000_000_000]);
    }

    #[test]
    fn fixed_point_conversions_match_the_wide_ones() {
        let mut x = 0.37f64;
        for _ in 0..2000 {
            for v in [x, -x, x + 0.5, (x * 1e3).floor() + 0.5] {
                assert_eq!(to_fixed(v), v.round() as i128, "{v}");
                let q = v.round() as i128;
                assert_eq!(from_fixed(q).to_bits(), (q as f64).to_bits(), "{q}");
            }
            x *= 1.037;
        }
        assert!(x > 1e30, "the values cover more than i64's range");
    }
}
