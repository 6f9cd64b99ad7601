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
//! Two passes: a surface sees itself two reflections away (a block face over the floor
//! beside it), so one the solution has far off keeps a part of its own error. A first pass
//! to three times the error asked for finds such surfaces; where it finds none it goes on to the
//! error asked for, else a second pass measures anew over the solution with the surfaces it
//! found off brought to the first pass's level ([`Solution::with_irradiance`]). On the
//! Cornell box face by face under hierarchical shooting, whose solution has the tall block's
//! face toward the red wall 13 % high: worst face from 0.93–1.49 % to 0.77–0.88 % (seeds 0–3).
//!
//! Which surfaces: by default those that receive less than [`SurfaceGather::below_share`]
//! (2 %) of the light all surfaces receive but at least [`LEAST_SHARE`] (10⁻⁴; measuring
//! patches whatever their share), and at least [`INDIRECT_SHARE`] of theirs
//! otherwise than over light links (indirectly, or from emitting surfaces). The solution
//! holds every link to a share of the scene's power, so a surface with much of the light gets
//! it right within a fraction of a per cent (the Cornell box face by face: every face above
//! 1 % of the light within 0.43 %), while one with little light, most of it reflected to it
//! or sent by emitting surfaces, sums errors that can be several per cent of its own
//! (docs/VALIDATION.md).
//!
//! Each element's estimate carries the variance of its mean (the Sobol strata treated as
//! independent draws, which overstates it, on purpose: `Estimate::variance_of_mean`), so
//! each surface's power has a standard error. Deterministic: element `k` draws from stream
//! `k` of the seed (the second pass from streams after all elements'), whatever the threads.

use super::FinalGather;
use crate::color::Rgb64;
use crate::measure::SurfaceTable;
use crate::progress::{Cancel, ProgressListener};
use crate::radiosity::Side;
use crate::radiosity::solve::UNEVEN_RUN;
use crate::radiosity::solve::{GatheredIrradiance, RadiositySystem, Shading, Solution};
use crate::sampling::adaptive::{lit_channels, samples_for, worst_relative_error};
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

/// What the final gather at the reported surfaces measures, and how well.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceGather {
    /// The standard error each gathered surface's incident power is measured to, a share of
    /// it (0: no gather, the solution's own values are reported).
    pub error: f64,
    /// Only the surfaces that receive less than this share of the light all surfaces receive
    /// (luminance, by the solution) are gathered; the others keep the solution's values
    /// (1: every surface).
    pub below_share: f64,
}

impl SurfaceGather {
    /// A standard error of [`DEFAULT_ERROR`] for the surfaces below [`DEFAULT_BELOW_SHARE`].
    pub const DEFAULT: SurfaceGather = SurfaceGather {
        error: DEFAULT_ERROR,
        below_share: DEFAULT_BELOW_SHARE,
    };

    /// No gather: the solution's own values.
    pub const OFF: SurfaceGather = SurfaceGather {
        error: 0.0,
        below_share: DEFAULT_BELOW_SHARE,
    };

    /// Whether any surface is gathered.
    pub fn is_on(&self) -> bool {
        self.error > 0.0
    }
}

impl Default for SurfaceGather {
    /// [`SurfaceGather::DEFAULT`].
    fn default() -> Self {
        SurfaceGather::DEFAULT
    }
}

/// The default standard error of a gathered surface, a share of its incident power: three of
/// them, 1.5 %, bound what is left, and the stated error overstates the real one (over 8
/// seeds on the Cornell box face by face, the spread was 0.25–0.84 of it).
pub const DEFAULT_ERROR: f64 = 0.01;

/// The default share of all light below which a surface is gathered.
pub const DEFAULT_BELOW_SHARE: f64 = 0.02;

/// A surface below the share is gathered when at least this share of its light comes
/// otherwise than over light links, by the solution: light links are measured on grids of
/// points, right to a fraction of a per cent even on small surfaces (the leaves of
/// `canopy:300`, under sun and sky, within 1.2 %); reflected light and the light of emitting
/// surfaces come over links judged by the scene-wide threshold (the Cornell box's dim block
/// faces, 75–100 % indirect, up to 4.8 % off; RenderPark's louvred luminaire's vanes, lit
/// straight by its tube lamps, up to 6.8 %).
pub const INDIRECT_SHARE: f64 = 0.25;

/// By default a surface is gathered only when it receives at least this share of the light
/// all surfaces receive, or is a measuring patch (its material scatters and emits nothing,
/// [`crate::scene::Material::is_measuring`]): the floor of the per-surface contract
/// (docs/VALIDATION.md, *Per surface*). Without it a field of 160,000 leaves, each a
/// 160,000th of the light, gathered a quarter of them (about 25 minutes on two cores beside a
/// 50 s solve).
pub const LEAST_SHARE: f64 = 1e-4;

/// Where the near field's rays carried light, surfaces with at least this share of the light
/// all surfaces receive are measured to [`LARGE_SURFACE_ERROR`] of the error asked for.
pub const LARGE_SHARE: f64 = 0.01;

/// The share of the error asked for that large surfaces are measured to where the near
/// field's rays carried light: three of their standard errors within the error asked for.
pub const LARGE_SURFACE_ERROR: f64 = 1.0 / 3.0;

/// Measures the irradiance of every element of the surfaces `gather` selects anew from
/// `solution`, as the module describes, in rounds: [`FIRST_POINTS`] points per surface and
/// side spread by area; then, for each surface whose incident power's standard error is
/// still above its target share of it (in any channel but the very dim), as many more points
/// as the error says it needs (2 to 16 times as many, up to [`MAX_POINTS`]), divided between
/// its two sides by the spread of their points so far (the dark inside of a box gets none)
/// and over each side by area. In two passes (see the module): the first to
/// [`FIRST_PASS_ERROR`] times `gather.error`; when it finds a surface's solution value off,
/// the second measures anew over the solution corrected by it, else the first goes on to
/// `gather.error`. The other surfaces' elements keep the solution's values. Element `k`
/// draws the Sobol points of stream `k` of `seed` in order (stream `k` + the element count
/// in the second pass), so the result is the same whatever the threads. `None` when
/// cancelled.
pub fn gather_surfaces(
    system: &RadiositySystem,
    solution: &Solution,
    gather: SurfaceGather,
    seed: u64,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Option<GatheredIrradiance> {
    let start = Instant::now();
    let mut surfaces = Surfaces::new(system);
    surfaces.tighten_large(solution);
    let gathered = surfaces.selected(system, solution, gather.below_share);
    let (estimates, points, corrected) = if gathered.contains(&true) {
        let pass = Pass {
            surfaces: &surfaces,
            gathered: &gathered,
            progress,
            cancel,
        };
        pass.two(system, solution, (gather.error, seed))?
    } else {
        (vec![Estimate::default(); system.len()], 0, false)
    };
    // The surfaces not gathered keep the solution's values.
    let measured = |k: usize| gathered[surfaces.of[k]].then_some(&estimates[k]);
    let elements = 0..system.len();
    Some(GatheredIrradiance {
        irradiance: elements
            .clone()
            .map(|k| measured(k).map_or(solution.irradiance[k], |e| e.mean()))
            .collect(),
        direct: elements
            .clone()
            .map(|k| match measured(k) {
                Some(e) => Some(e.direct / e.moments.n as f64),
                None => solution.direct_irradiance.as_ref().map(|d| d[k]),
            })
            .collect(),
        variance: elements
            .map(|k| measured(k).map(|e| e.variance_of_mean()))
            .collect(),
        points,
        surfaces: gathered.iter().filter(|&&g| g).count(),
        corrected,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// The first pass measures each gathered surface to this many times the error asked for
/// (a ninth of the points): enough to find a solution value far off (hierarchical
/// shooting's 13 % on a block face of the Cornell box) and to correct it to a few per cent,
/// which then weigh two reflections away; and, when none is off, the start of the
/// measurement that goes on. At twice the error it found more, with no face of the Cornell
/// box nearer its reference, and cost `blocks:1000`'s gather 24 % more points.
pub const FIRST_PASS_ERROR: f64 = 3.0;

/// A surface's solution value counts as off when the first pass differs from it by more
/// than this many of its standard errors (and by more than the error asked for).
const SIGNIFICANT: f64 = 3.0;

/// What the passes of one gather share: the surfaces, which are gathered, and the progress
/// and cancel of the run.
struct Pass<'a> {
    surfaces: &'a Surfaces,
    gathered: &'a [bool],
    progress: &'a dyn ProgressListener,
    cancel: &'a Cancel,
}

impl Pass<'_> {
    /// The estimates of the gathered surfaces' elements to `target` of each surface's light,
    /// the points drawn in all, and whether the second pass ran. Why two: the gather reads
    /// the solution two reflections away, and a surface the solution has far off (13 % on a
    /// block face of the Cornell box under hierarchical shooting) sees itself there, over
    /// the floor beside it, and keeps a part of its own error (+1 % on that face). The first
    /// pass finds such surfaces; the second reads their values from the first. `None` when
    /// cancelled.
    fn two(
        &self,
        system: &RadiositySystem,
        solution: &Solution,
        (target, seed): (f64, u64),
    ) -> Option<(Vec<Estimate>, u64, bool)> {
        let integrator = FinalGather::over(system, solution, Shading::Flat, 1, 1);
        let mut first = vec![Estimate::default(); system.len()];
        let loose = (FIRST_PASS_ERROR * target, seed, 0);
        self.measure(system, &integrator, loose, &mut first)?;
        let points = |e: &[Estimate]| e.iter().map(|e| e.moments.n).sum::<u64>();
        let off = self.surfaces.off(&first, self.gathered, solution, target);
        if !off.contains(&true) {
            self.measure(system, &integrator, (target, seed, 0), &mut first)?;
            let n = points(&first);
            return Some((first, n, false));
        }
        let measured = self.surfaces.levelled(&first, solution, &off);
        let corrected = solution.with_irradiance(system, &measured);
        let integrator = FinalGather::over(system, &corrected, Shading::Flat, 1, 1);
        let mut second = vec![Estimate::default(); system.len()];
        let streams = system.len() as u64;
        self.measure(system, &integrator, (target, seed, streams), &mut second)?;
        let n = points(&first) + points(&second);
        Some((second, n, true))
    }

    /// Draws more points into `estimates` of the gathered surfaces' elements, in rounds until
    /// each surface's standard error is at most `target` of its light (see
    /// [`gather_surfaces`]), element `k` from stream `k + streams` of `seed`; the other
    /// elements' estimates stay empty. `None` when cancelled.
    fn measure(
        &self,
        system: &RadiositySystem,
        integrator: &FinalGather,
        (target, seed, streams): (f64, u64, u64),
        estimates: &mut [Estimate],
    ) -> Option<()> {
        let surfaces = self.surfaces;
        let mut active = self.gathered.to_vec();
        let mut wanted: Vec<u64> = (0..system.len())
            .map(|k| {
                let share = surfaces.side_share(system, k);
                ((FIRST_POINTS as f64 * share).ceil() as u64).max(MIN_POINTS_PER_SIDE)
            })
            .collect();
        while active.iter().any(|&a| a) {
            let round: Vec<usize> = (0..system.len())
                .filter(|&k| active[surfaces.of[k]] && estimates[k].moments.n < wanted[k])
                .collect();
            self.progress.start(round.len() as u64);
            let drawn: Vec<Option<Estimate>> = round
                .par_iter()
                .with_max_len(UNEVEN_RUN)
                .map(|&k| {
                    let more = (estimates[k], wanted[k]);
                    let stream = (k as u64 + streams, seed);
                    let estimate = draw(system, integrator, (k, stream), more, self.cancel);
                    self.progress.advance(1);
                    estimate
                })
                .collect();
            self.progress.finish();
            for (&k, estimate) in round.iter().zip(drawn) {
                estimates[k] = estimate?;
            }
            let short = surfaces.short_of(estimates, target, &mut active);
            surfaces.spread_points(system, estimates, &short, &mut wanted);
        }
        Some(())
    }
}

/// `estimate` of element `k` with its points up to `wanted`, drawn from `stream` of `seed`
/// (the surfaces the patches lie on, curved shapes as their facets); `None` when cancelled.
fn draw(
    system: &RadiositySystem,
    integrator: &FinalGather,
    (k, (stream, seed)): (usize, (u64, u64)),
    (mut estimate, wanted): (Estimate, u64),
    cancel: &Cancel,
) -> Option<Estimate> {
    if cancel.is_requested() {
        return None;
    }
    let world = system.visibility().world();
    let patch = system.patch(k);
    let normal = system.elements[k].side.normal(patch).as_vec3();
    for i in estimate.moments.n..wanted {
        let mut sampler = Sampler::new(SequenceKind::Sobol, seed, stream, i as u32);
        let [s, t] = sampler.next_2d().to_array().map(f64::from);
        let x = patch.point_at(s, t).as_vec3();
        let (direct, indirect) =
            irradiance_sample(world, integrator, (x, normal), true, &mut sampler);
        estimate.add(direct, indirect);
    }
    Some(estimate)
}

/// The reported surfaces of a system's elements.
struct Surfaces {
    /// How many.
    count: usize,
    /// Per element, its surface (an entry of the scene's `SurfaceTable`).
    of: Vec<usize>,
    /// Per element, what a W·m⁻² on it adds to its surface's incident power, m².
    weight: Vec<f64>,
    /// Per surface, the area of its leaves (one side), m².
    side_area: Vec<f64>,
    /// Per surface, the share of the error asked for that it is measured to (1, or
    /// [`LARGE_SURFACE_ERROR`] for the large surfaces of a solution with near links).
    error_share: Vec<f64>,
    /// Per surface, whether it is a copy around an unrolled periodic plot.
    copy: Vec<bool>,
    /// Per surface, whether it is a measuring patch.
    measuring: Vec<bool>,
}

impl Surfaces {
    fn new(system: &RadiositySystem) -> Self {
        let world = system.world();
        let table = SurfaceTable::new(&world.scene, &world.geometry);
        // The copies around an unrolled periodic plot are not reported: not gathered.
        let own = world.own_objects() as u32;
        let copy = table.surfaces().iter().map(|s| s.object >= own).collect();
        let scene = &world.scene;
        let measuring = table
            .surfaces()
            .iter()
            .map(|s| {
                let object = &scene.objects[s.object as usize];
                scene.materials[object.material as usize].is_measuring()
            })
            .collect();
        let of: Vec<usize> = (0..system.len())
            .map(|k| {
                let patch = system.patch(k);
                table.entry(patch.object, patch.face)
            })
            .collect();
        let mut side_area = vec![0.0; table.len()];
        for (k, &s) in of.iter().enumerate() {
            if system.elements[k].side == Side::Front {
                side_area[s] += system.area[k];
            }
        }
        Surfaces {
            count: table.len(),
            weight: (0..system.len())
                .map(|k| system.coverage[k] * system.area[k])
                .collect(),
            of,
            side_area,
            error_share: vec![1.0; table.len()],
            copy,
            measuring,
        }
    }

    /// Measures the surfaces that receive at least [`LARGE_SHARE`] of the light all surfaces
    /// receive by `solution` to [`LARGE_SURFACE_ERROR`] of the error asked for, when the near
    /// field's rays carried light in it: the surfaces a reader looks at first, which the rays
    /// leave off by a per cent or so (the conference room's ceiling, −1.5 % in the solution,
    /// −1.28 % gathered to a stated 0.5 %); they are few, and their points cost little beside
    /// those of the many small surfaces.
    fn tighten_large(&mut self, solution: &Solution) {
        if solution.near_links == 0 {
            return;
        }
        let incident = self.power(&solution.irradiance);
        let total = self.reported_total(incident.iter().map(|p| p.luminance()));
        for (share, p) in self.error_share.iter_mut().zip(&incident) {
            if p.luminance() >= LARGE_SHARE * total {
                *share = LARGE_SURFACE_ERROR;
            }
        }
    }

    /// Per surface, whether the gather measures it: every one when `share` is 1 or more,
    /// else those that receive less than `share` of the light all surfaces receive by
    /// `solution` (luminance; any share where the near field's rays carried light, which
    /// are right on average but not held to the error threshold surface by surface: the
    /// conference room's ceiling, 17 % of the light, −1.5 % in the solution), at least
    /// [`LEAST_SHARE`] of it unless a measuring patch, and at least
    /// [`INDIRECT_SHARE`] of theirs otherwise than over
    /// the light links of `system` (point, spot and directional lights and the sky, measured
    /// on grids of points): reflected, or straight from emitting surfaces, whose links are
    /// held to the scene-wide threshold like any other (RenderPark's louvred luminaire:
    /// vanes lit straight by its tube lamps −6.8 … +3.6 % in the solution). Solvers that
    /// keep no direct light apart have every surface below the share gathered.
    fn selected(&self, system: &RadiositySystem, solution: &Solution, share: f64) -> Vec<bool> {
        if share >= 1.0 {
            return self.copy.iter().map(|&copy| !copy).collect();
        }
        let incident: Vec<f64> = self
            .power(&solution.irradiance)
            .iter()
            .map(|p| p.luminance())
            .collect();
        let linked = self.power(&system.light_irradiance);
        let total = self.reported_total(incident.iter().copied());
        let apart = solution.direct_irradiance.is_some();
        let below = |p: f64| p < share * total || solution.near_links > 0;
        let held = |p: f64, measuring: bool| measuring || p >= LEAST_SHARE * total;
        incident
            .iter()
            .zip(linked)
            .zip(self.copy.iter().zip(&self.measuring))
            .map(|((&p, lit), (&copy, &measuring))| {
                !copy
                    && below(p)
                    && held(p, measuring)
                    && (!apart || p - lit.luminance() >= INDIRECT_SHARE * p)
            })
            .collect()
    }

    /// The sum of `per_surface` over the reported surfaces (not the copies).
    fn reported_total(&self, per_surface: impl Iterator<Item = f64>) -> f64 {
        per_surface
            .zip(&self.copy)
            .filter(|&(_, &copy)| !copy)
            .map(|(p, _)| p)
            .sum()
    }

    /// Element `k`'s share of its side of its surface, by area.
    fn side_share(&self, system: &RadiositySystem, k: usize) -> f64 {
        system.area[k] / self.side_area[self.of[k]]
    }

    /// Per surface still short of `target` (`active` ones only; the others are marked
    /// inactive): the channel furthest off, and the points the surface is to have in all.
    fn short_of(
        &self,
        estimates: &[Estimate],
        target: f64,
        active: &mut [bool],
    ) -> Vec<Option<(usize, u64)>> {
        let mut short = vec![None; self.count];
        for (s, &(sum, variance, points)) in self.totals(estimates).iter().enumerate() {
            if !active[s] {
                continue;
            }
            let (relative, channel) = worst_relative_error(sum, variance);
            let target = target * self.error_share[s];
            if relative <= target || points >= MAX_POINTS {
                active[s] = false;
                continue;
            }
            short[s] = Some((channel, samples_for(points, relative, target, MAX_POINTS)));
        }
        short
    }

    /// Per surface: its incident power for the irradiance `irradiance` per element, W.
    fn power(&self, irradiance: &[Rgb64]) -> Vec<Rgb64> {
        let mut power = vec![Rgb64::BLACK; self.count];
        for (k, &h) in irradiance.iter().enumerate() {
            power[self.of[k]] += h * self.weight[k];
        }
        power
    }

    /// Per surface: its incident power by `estimates` (W), the variance of that estimate
    /// (W²) and the points drawn.
    fn totals(&self, estimates: &[Estimate]) -> Vec<(Rgb64, Rgb64, u64)> {
        let mut power = vec![(Rgb64::BLACK, Rgb64::BLACK, 0); self.count];
        for (k, e) in estimates.iter().enumerate() {
            let (sum, variance, points) = &mut power[self.of[k]];
            *sum += e.mean() * self.weight[k];
            *variance += e.variance_of_mean() * (self.weight[k] * self.weight[k]);
            *points += e.moments.n;
        }
        power
    }

    /// Per element of the surfaces `off`, the solution's display irradiance scaled to the
    /// surface's incident power by `estimates` (per channel; the estimate's own mean where
    /// the solution has none): the surface's level from the first pass, its spread over
    /// the elements from the solution. Only the surfaces found off are replaced, and only
    /// in level: the first pass's values element by element, a few points each, would bring
    /// its noise back two reflections away, frozen into what the second pass reads. `None`
    /// for the other elements.
    fn levelled(
        &self,
        estimates: &[Estimate],
        solution: &Solution,
        off: &[bool],
    ) -> Vec<Option<Rgb64>> {
        let display = solution.display_irradiance();
        let solved = self.power(&display);
        let totals = self.totals(estimates);
        (0..display.len())
            .map(|k| {
                let s = self.of[k];
                off[s].then(|| {
                    let (measured, mean) = (totals[s].0.to_array(), estimates[k].mean());
                    let level = |c: usize| {
                        if solved[s][c] > 0.0 {
                            display[k][c] * measured[c] / solved[s][c]
                        } else {
                            mean[c]
                        }
                    };
                    Rgb64::new(level(0), level(1), level(2))
                })
            })
            .collect()
    }

    /// Per surface, whether the solution has it off, for the `gathered` ones: `estimates`
    /// differ from its incident power, in a channel not very dim, by more than
    /// [`SIGNIFICANT`] standard errors and by more than `target` (the error asked for) of it.
    fn off(
        &self,
        estimates: &[Estimate],
        gathered: &[bool],
        solution: &Solution,
        target: f64,
    ) -> Vec<bool> {
        let solved = self.power(&solution.display_irradiance());
        let totals = self.totals(estimates);
        (0..self.count)
            .map(|s| {
                let (sum, variance, _) = totals[s];
                gathered[s]
                    && lit_channels(sum).any(|c| {
                        let off = (sum[c] - solved[s][c]).abs();
                        off > SIGNIFICANT * variance[c].sqrt() && off > target * sum[c]
                    })
            })
            .collect()
    }

    /// Raises `wanted` so that each surface `short` of its target gets the points it is to
    /// have: between its sides by the summed spread of one point's estimate over their
    /// elements (each times its weight), in the surface's channel furthest off (Neyman's
    /// allocation between the two sides: the dark inside of a box gets none); within a side
    /// by area, as in the first round. Spreads per element would save more, but an element
    /// whose first points happened to miss a rare bright one would then get few and keep
    /// its low mean: a bias.
    fn spread_points(
        &self,
        system: &RadiositySystem,
        estimates: &[Estimate],
        short: &[Option<(usize, u64)>],
        wanted: &mut [u64],
    ) {
        let side = |k: usize| system.elements[k].side.index();
        let mut spread = vec![[0.0; 2]; self.count];
        for (k, e) in estimates.iter().enumerate() {
            if let Some((c, _)) = short[self.of[k]] {
                spread[self.of[k]][side(k)] += self.weight[k] * e.moments.spread()[c];
            }
        }
        for (k, wanted) in wanted.iter_mut().enumerate() {
            let s = self.of[k];
            let Some((_, points)) = short[s] else {
                continue;
            };
            let side_share = spread[s][side(k)] / (spread[s][0] + spread[s][1]);
            let share = self.side_share(system, k) * side_share;
            *wanted = (*wanted).max((points as f64 * share).ceil() as u64);
        }
    }
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

    /// The mean irradiance, W·m⁻².
    fn mean(&self) -> Rgb64 {
        self.moments.mean()
    }

    /// The variance of [`Self::mean`], (W·m⁻²)², the points taken as independent. That
    /// overstates it for Sobol points (the Cornell box's dim faces 1.5–4 times their real
    /// error), and is kept on purpose: measured from the spread of eight independently
    /// scrambled replicates instead, it came out nearer the real error on most faces, but the
    /// gather then stopped with a quarter fewer points and a face whose light comes partly
    /// along rare bright paths (the tall block's face toward the red wall, green and blue)
    /// came out 1.3 % low on each of four seeds: a heavy tail the replicates' means had not
    /// yet seen.
    fn variance_of_mean(&self) -> Rgb64 {
        self.moments.variance_of_mean()
    }
}
