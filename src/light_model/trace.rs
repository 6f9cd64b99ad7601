//! A light-tracing run: photons from every source traced in parallel batches into fixed-point
//! tallies, merged into the power per reported surface.
//!
//! Groups. A run may trace several groups at once ([`trace_light_groups`]): worlds of one
//! geometry with other materials and lights (the band groups of a scene with wavelength
//! bands). Each photon then follows one path for all of them, carrying each group's power: its
//! source is drawn by the groups' summed power, and at every surface the lobe by the groups'
//! summed weighted power (`scatter.rs`), each group's power divided by the probability of what
//! was drawn, so every group's figures are unbiased and the path is traced once. A photon is
//! tallied only for the groups its source lights (a day's state: the state whose sun or sky
//! sent it; a band group: every one the light shines in), since it carries nothing for the
//! others along its whole path.

use super::scatter::scatter_photon;
use super::sensors::{connect_emission, connect_reflection, delta_light_direct};
use super::sources::PhotonSources;
use super::tally::{Fixed, FixedBalance, FixedSensor, Tally, add_fixed, add_fixed_saturating};
use crate::color::{Rgb, Rgb64};
use crate::geometry::spawn_ray;
use crate::measure::{Measurement, SensorReading, Stats, SurfacePower, SurfaceTable};
use crate::progress::{Cancel, ProgressListener};
use crate::sampling::{
    Batch, BatchPart, MergeError, NoSuchBatch, Sampler, SequenceKind, check_batches, from_fixed,
    to_fixed,
};
use crate::scene::Scene;
use crate::world::{SurfaceMaterial, World};
use rayon::prelude::*;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// Fixed-point units of the total emitted power (largest channel).
const FIXED_POINT_TOTAL: f64 = (1u64 << 62) as f64;
/// Fixed-point units of the square of the total emitted power (or of the reference
/// irradiance, for sensors): squares of one photon's share, about `1/N²`, keep six digits
/// at a billion photons, and one photon's square of a million times the reference still fits.
const FIXED_POINT_SQUARE: f64 = (1u128 << 80) as f64;
/// Photons per progress step are at least this many.
const MIN_BATCH: u64 = 4096;
/// Number of progress steps of a run (at most).
const BATCHES: u64 = 200;
/// Photons per progress step are at most this many, so that a stop request is answered
/// within a fraction of a second however many photons the run has.
const MAX_BATCH: u64 = 1 << 18;
/// Photons a thread takes at a time (about 0.06 ms of tracing in `canopy:3000`, 0.24 µs a
/// photon).
const PHOTON_RUN: u64 = 256;
/// Memory budget of the per-worker tallies, bytes.
const TALLY_BUDGET: usize = 256 << 20;

/// Settings of a light-tracing run.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
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

/// Why light tracing, or the merge of its batches, cannot run.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum LightTraceError {
    /// No light with positive power.
    #[error("the scene has no light with positive power")]
    NoLights,
    /// Zero photons asked for.
    #[error("at least one photon is needed")]
    NoPhotons,
    /// Groups that are not one geometry relit without emitting surfaces.
    #[error(
        "the groups of a light-tracing run must share one compiled geometry and light it by \
         lights, not emitting surfaces"
    )]
    UnsharedGroups,
    /// Sensors in a periodic scene: a sensor would have to see every copy of the plot.
    #[error(
        "sensors are not measured in a periodic scene yet: read the light on a small black \
         quad (a meter object) instead"
    )]
    PeriodicSensors,
    /// A batch that is not one of its count.
    #[error(transparent)]
    NoSuchBatch(#[from] NoSuchBatch),
    /// Batches that do not make one run.
    #[error(transparent)]
    Merge(#[from] MergeError),
}

/// What a batch of a run leaves for the merge ([`trace_light_batch`]): the scene's digest,
/// the settings, which batch, and the fixed-point tallies of its photons. Serializable, so
/// that batches run on other machines (a cluster's job array, Dask workers) come back as files
/// or bytes.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct LightTracePartial {
    /// [`crate::scene::Scene::digest`] of the scene traced, in hex.
    pub scene_digest: String,
    /// The run's settings (all its photons, not the batch's).
    pub settings: LightTraceSettings,
    /// Which batch.
    pub batch: Batch,
    /// Photons of the batch traced (fewer than its share when cancelled).
    pub photons_traced: u64,
    /// Seconds the batch took.
    pub seconds: f64,
    tally: Tally,
}

/// The result of a light-tracing run.
#[derive(Clone, Debug)]
pub struct LightTraceOutput {
    /// Per-surface and scene-wide power, W, scaled to the full photon count when the run was
    /// cancelled early, with the standard error of every surface's incident power.
    pub power: SurfacePower,
    /// One reading per sensor of the scene (irradiance, W·m⁻², with its standard error),
    /// scaled like `power`.
    pub sensors: Vec<SensorReading>,
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
            sensors: self.sensors.clone(),
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

/// One group a run traces: a world's materials and lights (on the run's geometry) with the
/// fixed-point scale of its tally.
struct Group<'a> {
    world: &'a World,
    /// Each source's power in this group, W per channel; `None` for a run of one group, whose
    /// photons carry their source's own power.
    powers: GroupPowers,
    /// Fixed-point units per watt.
    scale: f64,
    /// The largest channel of the group's total source power, W (1 when it has none).
    largest_channel: f64,
    /// The reference irradiance of sensor tallies, W·m⁻²: the total power over the square
    /// of the bounding sphere's radius.
    sensor_reference: f64,
}

impl Group<'_> {
    fn quantize(&self, p: Rgb64) -> Fixed {
        p.to_array().map(|c| to_fixed(c * self.scale))
    }

    /// Share of the total emitted power (largest channel) per watt.
    fn share_per_watt(&self) -> f64 {
        self.scale / FIXED_POINT_TOTAL
    }

    fn watts(&self, q: Fixed) -> Rgb64 {
        Rgb64::from(q.map(|c| from_fixed(c) / self.scale))
    }
}

/// Everything a worker needs to trace photon `i`.
struct Tracer<'a> {
    /// The first group's world: the geometry every group shares, and the sources' shapes.
    world: &'a World,
    /// The sources photons are drawn from (for several groups, with their summed power).
    sources: PhotonSources,
    groups: Vec<Group<'a>>,
    /// The groups' scenes, in order, for scattering.
    scenes: Vec<&'a Scene>,
    /// Cumulative power fractions of the sources (last = 1).
    cdf: Vec<f64>,
    /// Photons per source over the whole run.
    counts: Vec<u64>,
    table: &'a SurfaceTable,
    settings: LightTraceSettings,
}

/// A worker's tallies (one per group) and the scratch space of the photon it traces.
#[derive(Clone)]
struct Worker {
    tallies: Vec<Tally>,
    /// Per group, the current photon's hits: report entry and incident power as a share of
    /// the group's total emitted power (largest channel).
    hits: Vec<Vec<(usize, [f64; 3])>>,
    /// Per group, the current photon's irradiance at each sensor, direct and indirect, W·m⁻².
    sensor_light: Vec<Vec<[Rgb64; 2]>>,
    /// The groups the current photon carries light for (all, for one group).
    active: Vec<usize>,
    /// Per active group, the photon's power in fixed point, and what goes on after a hit.
    q: Vec<Fixed>,
    q_out: Vec<Fixed>,
    /// Per active group, the photon's power at a hit, W.
    powers: Vec<Rgb64>,
    /// Per active group, the power the photon carries, W, when there are several groups (one
    /// group reads it back from its fixed-point tally units, as a run of one world always has).
    carried: Vec<Rgb64>,
    /// Per active group, the material at a hit (scratch space of scattering).
    materials: Vec<SurfaceMaterial>,
}

impl Worker {
    fn new(groups: usize, entries: usize, sensors: usize) -> Self {
        Worker {
            tallies: vec![Tally::new(entries, sensors); groups],
            hits: vec![Vec::new(); groups],
            sensor_light: vec![vec![[Rgb64::BLACK; 2]; sensors]; groups],
            active: Vec::with_capacity(groups),
            q: Vec::with_capacity(groups),
            q_out: Vec::with_capacity(groups),
            powers: Vec::with_capacity(groups),
            carried: Vec::with_capacity(groups),
            materials: Vec::with_capacity(groups),
        }
    }
}

/// `x²` of a share `x` (of the total power or the reference irradiance) in the fixed-point
/// units of squares.
#[inline]
fn square(x: f64) -> i128 {
    to_fixed(x * x * FIXED_POINT_SQUARE)
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

    fn trace_photon(&self, index: u64, worker: &mut Worker) {
        let world = self.world;
        let mut sampler = Sampler::new(SequenceKind::Random, self.settings.seed, index, 0);
        let source = self.source_of(index);
        let photon = self.sources.emit(world, source, &mut sampler);
        let count = self.counts[source] as f64;
        let sensing = !world.scene.sensors.is_empty();
        let single = self.groups.len() == 1;
        // What the photon carries of its source's power (1 but for a CIE sky's weighted
        // draws, and the same in every channel), for the groups' shares.
        let weight = if single {
            1.0
        } else {
            photon.power.max_channel() / self.sources.sources[source].power.max_channel()
        };
        // The groups the photon brings light to (of several, those its source lights): a
        // group it carries nothing for stays so along the whole path and is left alone.
        worker.active.clear();
        worker.q.clear();
        worker.carried.clear();
        for (g, group) in self.groups.iter().enumerate() {
            let power = match &group.powers {
                None => photon.power,
                Some(powers) => powers[source] * weight,
            };
            if !single && power.max_channel() <= 0.0 {
                continue;
            }
            let share = power.to_f64().map(|c| c / count);
            let emitted = group.quantize(share);
            let carried = share.map(|c| c * photon.carried);
            // Most photons carry all of their share (no aiming): the same units again.
            let q = if photon.carried == 1.0 {
                emitted
            } else {
                group.quantize(carried)
            };
            let tally = &mut worker.tallies[g];
            match photon.surface {
                Some((object, face)) => {
                    let e = self.table.entry(object, face);
                    add_fixed(&mut tally.entries[e].emitted, emitted);
                    if sensing && let Some(n) = photon.normal {
                        let light = (&mut worker.sensor_light[g][..], 0);
                        connect_emission(
                            group.world,
                            (photon.ray.origin, n),
                            group.watts(q),
                            light,
                        );
                    }
                }
                None => add_fixed(&mut tally.light_emission, emitted),
            }
            if q != emitted {
                add_fixed(&mut tally.escaped, [0, 1, 2].map(|c| emitted[c] - q[c]));
            }
            worker.active.push(g);
            worker.q.push(q);
            worker.carried.push(carried);
            worker.hits[g].clear();
        }
        // The active groups' scenes, for scattering.
        let some_scenes: Vec<&Scene>;
        let scenes = if worker.active.len() == self.groups.len() {
            &self.scenes[..]
        } else {
            some_scenes = worker.active.iter().map(|&g| self.scenes[g]).collect();
            &some_scenes[..]
        };
        let mut ray = photon.ray;
        let mut bounces = 0;
        loop {
            worker.tallies[0].rays += 1;
            let Some(hit) = world.intersect(&ray) else {
                for (&g, q) in worker.active.iter().zip(&worker.q) {
                    add_fixed(&mut worker.tallies[g].escaped, *q);
                }
                worker.tallies[0].escaped_photons += 1;
                break;
            };
            let entry_index = self.table.entry(hit.object, hit.face);
            worker.powers.clear();
            for (k, &g) in worker.active.iter().enumerate() {
                let group = &self.groups[g];
                let q = worker.q[k];
                let power = if single {
                    group.watts(q)
                } else {
                    worker.carried[k]
                };
                worker.hits[g].push((
                    entry_index,
                    power.to_array().map(|c| c * group.share_per_watt()),
                ));
                let entry = &mut worker.tallies[g].entries[entry_index];
                add_fixed(&mut entry.incident, q);
                if bounces == 0 {
                    add_fixed(&mut entry.direct, q);
                }
                if sensing {
                    let light = (&mut worker.sensor_light[g][..], 1);
                    connect_reflection(group.world, (&hit, ray.dir), power, light);
                }
                worker.powers.push(power);
            }
            let scattered = if bounces < self.settings.max_bounces {
                let (powers, materials) = (&mut worker.powers, &mut worker.materials);
                scatter_photon(scenes, &hit, ray.dir, powers, materials, &mut sampler)
            } else {
                worker.tallies[0].truncated_paths += 1;
                None
            };
            worker.q_out.clear();
            if scattered.is_some() {
                let out = worker.active.iter().zip(&worker.powers);
                worker
                    .q_out
                    .extend(out.map(|(&g, &p)| self.groups[g].quantize(p)));
            }
            match scattered {
                Some(dir) if worker.q_out.iter().any(|q| *q != [0; 3]) => {
                    for (k, &g) in worker.active.iter().enumerate() {
                        let entry = &mut worker.tallies[g].entries[entry_index];
                        let (q, q_out) = (worker.q[k], worker.q_out[k]);
                        add_fixed(&mut entry.absorbed, [0, 1, 2].map(|c| q[c] - q_out[c]));
                        add_fixed(&mut entry.reflected, q_out);
                    }
                    std::mem::swap(&mut worker.q, &mut worker.q_out);
                    if !single {
                        worker.carried.copy_from_slice(&worker.powers);
                    }
                    ray = spawn_ray(hit.p, hit.ng, dir);
                    bounces += 1;
                }
                _ => {
                    for (&g, q) in worker.active.iter().zip(&worker.q) {
                        add_fixed(&mut worker.tallies[g].entries[entry_index].absorbed, *q);
                    }
                    break;
                }
            }
        }
        for k in 0..worker.active.len() {
            self.add_squares(worker.active[k], worker);
        }
    }

    /// Adds the squares of what the photon just traced brought to each surface it hit (its
    /// hits summed per surface) and to each sensor in group `g`, and moves its sensor light
    /// into the group's tally.
    fn add_squares(&self, g: usize, worker: &mut Worker) {
        let group = &self.groups[g];
        let tally = &mut worker.tallies[g];
        let hits = &mut worker.hits[g];
        let add = |a: [f64; 3], b: [f64; 3]| [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
        match hits[..] {
            // Nothing hit: nothing to add (squares of zero).
            [] => {}
            // One hit, the common case: its square is the whole path's and its surface's, and
            // the indirect part is zero — the sums below, without them.
            [(entry, x)] => {
                let squares = x.map(square);
                add_fixed_saturating(&mut tally.total_squares[0], squares);
                add_fixed_saturating(&mut tally.entries[entry].incident_squares, squares);
            }
            _ => {
                let all = hits.iter().fold([0.0; 3], |a, &(_, x)| add(a, x));
                let first = hits[0].1;
                let indirect = [0, 1, 2].map(|c| all[c] - first[c]);
                for (squares, total) in tally.total_squares.iter_mut().zip([all, indirect]) {
                    add_fixed_saturating(squares, total.map(square));
                }
                // Per surface: the photon's hits summed (in hit order, so the same for any
                // thread).
                hits.sort_by_key(|&(entry, _)| entry);
                for run in hits.chunk_by(|a, b| a.0 == b.0) {
                    let total = run.iter().fold([0.0; 3], |a, &(_, x)| add(a, x));
                    add_fixed_saturating(
                        &mut tally.entries[run[0].0].incident_squares,
                        total.map(square),
                    );
                }
            }
        }
        let sensor_scale = FIXED_POINT_TOTAL / group.sensor_reference;
        for (light, fixed) in worker.sensor_light[g].iter_mut().zip(&mut tally.sensors) {
            let [direct, indirect] = *light;
            if direct.max_channel() <= 0.0 && indirect.max_channel() <= 0.0 {
                continue;
            }
            add_fixed(
                &mut fixed.direct,
                direct.to_array().map(|c| to_fixed(c * sensor_scale)),
            );
            add_fixed(
                &mut fixed.indirect,
                indirect.to_array().map(|c| to_fixed(c * sensor_scale)),
            );
            let squares = (direct + indirect)
                .to_array()
                .map(|c| square(c / group.sensor_reference));
            add_fixed_saturating(&mut fixed.squares, squares);
            *light = [Rgb64::BLACK; 2];
        }
    }

    /// The reading of sensor `k` from its tally in group `group` over `traced` photons: the
    /// photons' direct and indirect irradiance, the direct irradiance `delta` of the
    /// non-surface lights added, and the standard error; everything of the photons multiplied
    /// by `factor` (to scale a partial run to its full size).
    fn sensor_reading(
        &self,
        group: &Group<'_>,
        k: usize,
        fixed: &FixedSensor,
        delta: Rgb64,
        traced: u64,
        factor: f64,
    ) -> SensorReading {
        let per_unit = group.sensor_reference / FIXED_POINT_TOTAL;
        let irradiance = |q: Fixed| Rgb64::from(q.map(|c| from_fixed(c) * per_unit));
        let (direct, indirect) = (irradiance(fixed.direct), irradiance(fixed.indirect));
        let sum = direct + indirect;
        let squares = Rgb64::from(fixed.squares.map(|c| {
            from_fixed(c) / FIXED_POINT_SQUARE * group.sensor_reference * group.sensor_reference
        }));
        SensorReading {
            sensor: group.world.scene.sensors[k].clone(),
            direct: delta + direct * factor,
            indirect: indirect * factor,
            standard_error: Some(standard_error(sum, squares, traced) * factor),
        }
    }
}

/// The standard error of a sum `sum` of `n` independent terms whose squares sum to
/// `squares`: `√(Σx² − S²/n)`, per channel.
fn standard_error(sum: Rgb64, squares: Rgb64, n: u64) -> Rgb64 {
    let n = n.max(1) as f64;
    Rgb64::from([0, 1, 2].map(|c| {
        (squares.to_array()[c] - sum.to_array()[c].powi(2) / n)
            .max(0.0)
            .sqrt()
    }))
}

/// Each source's power in one group, W per channel (`None`: the sources' own).
type GroupPowers = Option<Vec<Rgb>>;

/// The sources of several groups' worlds: each world's sources, dark ones kept so that the
/// lists align (the same lights in the same order), summed into the sources photons are drawn
/// from, those with no power in any group left out; and each group's power per source kept.
/// Refuses worlds that do not share one geometry, or that have emitting surfaces (whose
/// photons' power is not their source's times one number).
fn grouped_sources(
    worlds: &[&World],
) -> Result<(PhotonSources, Vec<GroupPowers>), LightTraceError> {
    let shared = worlds
        .iter()
        .all(|w| Arc::ptr_eq(&w.geometry, &worlds[0].geometry) && w.lights.area.is_empty());
    if !shared {
        return Err(LightTraceError::UnsharedGroups);
    }
    let all: Vec<PhotonSources> = worlds.iter().map(|w| PhotonSources::all(w)).collect();
    let n = all[0].sources.len();
    if all.iter().any(|s| s.sources.len() != n) {
        return Err(LightTraceError::UnsharedGroups);
    }
    let summed = |i: usize| all.iter().map(|s| s.sources[i].power).sum::<Rgb>();
    let kept: Vec<usize> = (0..n)
        .filter(|&i| summed(i).is_finite() && summed(i).max_channel() > 0.0)
        .collect();
    let mut sources = all[0].clone();
    sources.sources = kept
        .iter()
        .map(|&i| {
            let mut source = all[0].sources[i].clone();
            source.power = summed(i);
            source
        })
        .collect();
    let powers = all
        .iter()
        .map(|s| Some(kept.iter().map(|&i| s.sources[i].power).collect()))
        .collect();
    Ok((sources, powers))
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
    let mut outputs = trace_light_groups(&[world], settings, progress, cancel)?;
    Ok(outputs.remove(0))
}

/// Traces `settings.photons` photons through the groups `worlds` at once: worlds of one
/// geometry (made by [`World::relit`]) with other materials and lights, and no emitting
/// surfaces when there are several. Each photon follows one path for every group (see the
/// module's documentation); one output per group, in order, each with the run's rays and
/// photon counts. One world gives exactly [`trace_light`]'s output.
pub fn trace_light_groups(
    worlds: &[&World],
    settings: &LightTraceSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<Vec<LightTraceOutput>, LightTraceError> {
    let start = Instant::now();
    let world = worlds.first().ok_or(LightTraceError::UnsharedGroups)?;
    let table = SurfaceTable::new(&world.scene, &world.geometry);
    let tracer = Tracer::new(worlds, settings, &table)?;
    let (tallies, done) = tracer.trace(0..settings.photons, progress, cancel);
    let seconds = start.elapsed().as_secs_f64();
    Ok((0..worlds.len())
        .map(|g| tracer.output(g, &tallies, done, seconds))
        .collect())
}

/// Traces batch `batch.index` of `batch.count` of the photons of `settings` (the photons
/// `index·N/count .. (index + 1)·N/count` of the N asked for, each exactly as a whole run
/// traces it) and keeps their fixed-point tallies, for [`merge_light_batches`].
pub fn trace_light_batch(
    world: &World,
    settings: &LightTraceSettings,
    batch: Batch,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<LightTracePartial, LightTraceError> {
    let photons = batch.share(settings.photons)?;
    let start = Instant::now();
    let table = SurfaceTable::new(&world.scene, &world.geometry);
    let tracer = Tracer::new(&[world], settings, &table)?;
    let (mut tallies, traced) = tracer.trace(photons, progress, cancel);
    let tally = tallies.remove(0);
    Ok(LightTracePartial {
        scene_digest: format!("{:016x}", world.scene.digest()),
        settings: settings.clone(),
        batch,
        photons_traced: traced,
        seconds: start.elapsed().as_secs_f64(),
        tally,
    })
}

/// The output of one run of all the photons, from the `partials` of its batches: their
/// tallies added (integers: in any order the same sums), so the output is the one a single
/// run with the same settings gives, bit for bit, but for the seconds (the batches' sum).
/// Refuses batches of another scene, other settings, or not each batch exactly once
/// ([`check_batches`]).
pub fn merge_light_batches(
    world: &World,
    partials: &[LightTracePartial],
) -> Result<LightTraceOutput, LightTraceError> {
    let digest = format!("{:016x}", world.scene.digest());
    check_batches(
        &digest,
        partials.iter().map(|p| BatchPart {
            scene_digest: &p.scene_digest,
            settings: &p.settings,
            batch: p.batch,
            done: p.photons_traced,
            total: p.settings.photons,
        }),
    )?;
    let first = &partials[0];
    let table = SurfaceTable::new(&world.scene, &world.geometry);
    let tracer = Tracer::new(&[world], &first.settings, &table)?;
    let mut sum = Tally::new(table.len(), world.scene.sensors.len());
    for p in partials {
        if p.tally.entries.len() != sum.entries.len() || p.tally.sensors.len() != sum.sensors.len()
        {
            return Err(MergeError::Damaged(p.batch).into());
        }
        sum.merge(&p.tally);
    }
    let traced = partials.iter().map(|p| p.photons_traced).sum();
    let seconds = partials.iter().map(|p| p.seconds).sum();
    Ok(tracer.output(0, &[sum], traced, seconds))
}

impl<'a> Tracer<'a> {
    /// The tracer of `settings` on the groups `worlds` (one or more), tallying into `table`'s
    /// entries.
    fn new(
        worlds: &[&'a World],
        settings: &LightTraceSettings,
        table: &'a SurfaceTable,
    ) -> Result<Self, LightTraceError> {
        if settings.photons == 0 {
            return Err(LightTraceError::NoPhotons);
        }
        let world = worlds[0];
        if world.field().is_some() && !world.scene.sensors.is_empty() {
            return Err(LightTraceError::PeriodicSensors);
        }
        let (sources, group_powers) = if worlds.len() == 1 {
            (PhotonSources::new(world), vec![None])
        } else {
            grouped_sources(worlds)?
        };
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
        let radius = f64::from(world.entry_sphere().1);
        let groups = worlds
            .iter()
            .zip(group_powers)
            .map(|(&world, powers)| {
                let total: Rgb = match &powers {
                    None => sources.sources.iter().map(|s| s.power).sum(),
                    Some(p) => p.iter().copied().sum(),
                };
                let largest = match total.max_channel() as f64 {
                    l if l > 0.0 && l.is_finite() => l,
                    _ => 1.0,
                };
                Group {
                    world,
                    powers,
                    scale: FIXED_POINT_TOTAL / largest,
                    largest_channel: largest,
                    sensor_reference: largest / (radius * radius),
                }
            })
            .collect();
        Ok(Tracer {
            world,
            cdf,
            counts,
            table,
            scenes: worlds.iter().map(|w| &w.scene).collect(),
            groups,
            settings: settings.clone(),
            sources,
        })
    }

    /// Traces the photons `photons` on the current rayon pool; returns their tally and how
    /// many were traced (fewer when `cancel` stopped it).
    ///
    /// A tally per thread; the threads take the photons of each progress step in runs of
    /// [`PHOTON_RUN`] as they come free (photons differ in cost, so equal shares would leave
    /// one thread waiting for the other). Which thread traces a photon does not change the
    /// sums: every photon is traced from its own index, and the tallies are integers.
    fn trace(
        &self,
        photons: std::ops::Range<u64>,
        progress: &dyn ProgressListener,
        cancel: &Cancel,
    ) -> (Vec<Tally>, u64) {
        let workers = rayon::current_num_threads().max(1);
        let sensors = self.world.scene.sensors.len();
        let groups = self.groups.len();
        let per_tally = self.table.len().max(1) * std::mem::size_of::<FixedBalance>()
            + sensors * std::mem::size_of::<FixedSensor>();
        let slots = workers.min(TALLY_BUDGET / (per_tally * groups)).max(1);
        let mut workers = vec![Worker::new(groups, self.table.len(), sensors); slots];
        let asked = photons.end - photons.start;
        let batch = asked.div_ceil(BATCHES).clamp(MIN_BATCH, MAX_BATCH);
        progress.start(asked);
        let mut done = photons.start;
        while done < photons.end && !cancel.is_requested() {
            let end = (done + batch).min(photons.end);
            let next = AtomicU64::new(done);
            workers.par_iter_mut().for_each(|worker| {
                loop {
                    let from = next.fetch_add(PHOTON_RUN, Ordering::Relaxed);
                    if from >= end {
                        break;
                    }
                    for i in from..(from + PHOTON_RUN).min(end) {
                        self.trace_photon(i, worker);
                    }
                }
            });
            progress.advance(end - done);
            done = end;
        }
        progress.finish();
        let mut sums = vec![Tally::new(self.table.len(), sensors); groups];
        for w in &workers {
            for (sum, tally) in sums.iter_mut().zip(&w.tallies) {
                sum.merge(tally);
            }
        }
        (sums, done - photons.start)
    }

    /// The output of group `g` of the run whose photons, `done` of them, left the groups'
    /// tallies `sums` (the run's counts in the first), in `seconds`; scaled to the photons
    /// asked for when fewer were traced.
    fn output(&self, g: usize, sums: &[Tally], done: u64, seconds: f64) -> LightTraceOutput {
        let settings = &self.settings;
        let (group, sum, counted) = (&self.groups[g], &sums[g], &sums[0]);
        let largest_channel = group.largest_channel;
        let mut power = SurfacePower::new(self.table.clone());
        let mut errors = Vec::with_capacity(self.table.len());
        for (e, b) in sum.entries.iter().enumerate() {
            let out = power.balance_mut(e);
            out.incident = group.watts(b.incident);
            out.direct = Some(group.watts(b.direct));
            out.absorbed = group.watts(b.absorbed);
            out.emitted = group.watts(b.emitted);
            out.reflected = group.watts(b.reflected);
            let squares =
                Rgb64::from(b.incident_squares.map(|c| {
                    from_fixed(c) / FIXED_POINT_SQUARE * largest_channel * largest_channel
                }));
            errors.push(Some(standard_error(out.incident, squares, done)));
        }
        power.set_standard_errors(errors);
        let totals = sum.entries.iter().fold([[0i128; 3]; 2], |mut t, b| {
            add_fixed(&mut t[0], b.incident);
            add_fixed(&mut t[1], [0, 1, 2].map(|c| b.incident[c] - b.direct[c]));
            t
        });
        let [incident_error, indirect_error] = [0, 1].map(|k| {
            let squares =
                Rgb64::from(sum.total_squares[k].map(|c| {
                    from_fixed(c) / FIXED_POINT_SQUARE * largest_channel * largest_channel
                }));
            standard_error(group.watts(totals[k]), squares, done)
        });
        power.set_total_standard_errors(incident_error, indirect_error);
        power.add_light_emission(group.watts(sum.light_emission));
        power.add_escaped(group.watts(sum.escaped));
        let factor = if done > 0 && done < settings.photons {
            settings.photons as f64 / done as f64
        } else {
            1.0
        };
        power.scale(factor);
        let delta = delta_light_direct(group.world);
        let sensors = sum
            .sensors
            .iter()
            .zip(delta)
            .enumerate()
            .map(|(k, (fixed, delta))| self.sensor_reading(group, k, fixed, delta, done, factor))
            .collect();
        LightTraceOutput {
            power,
            sensors,
            photons: settings.photons,
            photons_traced: done,
            rays: counted.rays,
            escaped_photons: counted.escaped_photons,
            truncated_paths: counted.truncated_paths,
            unsampled_sources: self.counts.iter().filter(|&&c| c == 0).count(),
            sources: self.counts.len(),
            seconds,
            settings: settings.clone(),
        }
    }
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
}
