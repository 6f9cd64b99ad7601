//! The light on every reported surface by rays from points on it (`surface-trace`): the
//! gathering counterpart of the light model, and the way Helios' radiation model measures a
//! canopy leaf by leaf. Where the light model follows photons from the lights and counts
//! what each surface happens to catch — a small or shaded leaf few of them — this method
//! puts the same number of points on every surface, however small or dark, so every
//! surface's standard error is a share of its own light.
//!
//! The directional lights (the sun) first, exactly: each surface's lit share is cut out of it
//! once ([`ParallelShadows`]: the other triangles' shadows projected along the light), so
//! their light carries no noise and its shadow edges cost no points. Where that cannot be
//! done — placed meshes, alpha textures, a textured diffuse colour (its absorbed share varies
//! over the surface), a triangle under too many others (a field's ground) — the points take
//! them by shadow rays.
//!
//! At each point, on each side, one estimate of the irradiance ([`irradiance_sample`]):
//! point and spot lights (and directional ones left to rays) by a shadow ray each, emitting
//! surfaces by a point on them and the gather ray weighed by multiple importance sampling,
//! the sky where that cosine-distributed gather ray escapes (through a periodic plot's sides
//! too), and the light reflected toward the point from the surface it meets by the path
//! tracer ([`PathTracer`]) with Russian roulette from the first bounce on (a leaf reflecting
//! 10 % ends nine paths in ten at once, the survivors weighed up: no path goes on carrying a
//! hundredth of its light). What a side absorbs at the point is its irradiance times
//! `1 − ρ − τ` there (textures applied; the back of a one-sided material absorbs it all),
//! what it emits `π·Lₑ`.
//!
//! The sensors are read as the path tracer reads them ([`sensor_readings`], `points` rays
//! each), in the same scene as the surfaces.
//!
//! The scene is the one radiosity solves: materials keep their diffuse lobes (Lambertian
//! reflection and translucency; the rest of their light counts as absorbed, as radiosity
//! counts it) and analytic shapes are meshed ([`World::tessellated`], curved ones with
//! [`SEGMENTS`] segments), so that the method checks a radiosity solution surface by surface
//! — on periodic plots too, which radiosity does not model.
//!
//! Points: [`SurfaceTraceSettings::points`] on each reported surface, Owen-scrambled Sobol
//! points in two dimensions, the first choosing the triangle by area and, within its share,
//! going on across it (so a quad's two triangles hold one net of points). Each side of a
//! point draws its rays from a Sobol stream of its own, so that its gather direction is
//! always the first two dimensions there, stratified over the point's index (drawn from the
//! point's stream, the back's direction would fall on whatever dimension the front's path
//! left it: measured on the field's leaves, the sky's light then converged as plain random
//! sampling does). Points that an alpha texture cuts away count as nothing there. Each
//! surface's incident power carries the standard error of its mean (the points taken as
//! independent draws, which overstates it for Sobol points). With a standard error asked
//! for ([`SurfaceTraceSettings::standard_error`]), the surfaces still above it after the
//! first points go on, in rounds, along the same sequences: where a leaf is evenly lit few
//! points do, where a shadow's edge or the sky's gaps cross it it gets more. Deterministic:
//! surface `s` draws streams `3s`, `3s + 1` and `3s + 2` of the seed and decides on more
//! points by its own, whatever the threads.

use super::{PathTracer, SensorSettings, irradiance_sample, sensor_readings};
use crate::color::{Rgb, Rgb64};
use crate::measure::{Measurement, Stats, SurfacePower, SurfaceTable};
use crate::progress::{Cancel, ProgressListener};
use crate::sampling::adaptive::{samples_for, worst_relative_error};
use crate::sampling::warp::uniform_triangle;
use crate::sampling::{Moments, Sampler, SequenceKind};
use crate::scene::LightKind;
use crate::world::{
    GeometryError, ParallelShadows, SurfaceMaterial, SurfaceTriangle, World, emitted_toward,
};
use glam::{DVec3, Vec2};
use rayon::prelude::*;
use std::f64::consts::PI;
use std::time::Instant;

/// Points a surface draws between two looks at the cancel token (a few milliseconds).
pub const CANCEL_POINTS: u32 = 256;

/// Segments around the axis of a meshed curved shape (a sphere's, a cylinder's).
pub const SEGMENTS: u32 = 32;

/// How many points `surface-trace` puts on each surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceTraceSettings {
    /// Points on each reported surface (each measured on both sides), at least 2 (for a
    /// standard error); the first round's when `standard_error` is set.
    pub points: u32,
    /// When positive, the standard error each surface's incident power is measured to, a
    /// share of it: a surface above it after `points` gets more, in rounds, up to
    /// `MAX_POINTS` (2²⁰; 0: `points` on every surface).
    pub standard_error: f64,
    /// Seed of all random numbers.
    pub seed: u64,
}

impl Default for SurfaceTraceSettings {
    /// 1,024 points per surface, no target, seed 0.
    fn default() -> Self {
        SurfaceTraceSettings {
            points: 1024,
            standard_error: 0.0,
            seed: 0,
        }
    }
}

/// Points a surface gets at most when a standard error is asked for; one that reaches it
/// keeps the error it has.
pub const MAX_POINTS: u32 = 1 << 20;

/// The sums one surface's points gather, per point (W·m⁻², both sides together).
#[derive(Clone, Copy, Default)]
struct SurfaceSums {
    /// Incident irradiance, with its moments.
    incident: Moments,
    /// Its direct part.
    direct: Rgb64,
    /// Its indirect part, with its moments.
    indirect: Moments,
    /// Absorbed.
    absorbed: Rgb64,
    /// Emitted exitance.
    emitted: Rgb64,
}

/// Measures every reported surface of `world`'s scene as the module describes, and its
/// sensors as the path tracer reads them (`points` rays each, in the same scene), and whether
/// it completed; an error when a shape cannot be meshed (an infinite plane). When `cancel`
/// stops it (within `CANCEL_POINTS` points), each surface keeps the points it had drawn, and
/// one without any reports nothing, without a standard error; the sensors are not read; the
/// statistics say `complete: false` and how many points were drawn.
pub fn trace_surfaces(
    world: &World,
    settings: &SurfaceTraceSettings,
    progress: &dyn ProgressListener,
    cancel: &Cancel,
) -> Result<(Measurement, bool), GeometryError> {
    let start = Instant::now();
    let meshed = world.tessellated(SEGMENTS)?;
    let meshed = meshed.as_ref().unwrap_or(world);
    let diffuse = meshed.diffuse()?;
    let world = diffuse.as_ref().unwrap_or(meshed);
    let table = SurfaceTable::new(&world.scene, &world.geometry);
    let mut triangles: Vec<Vec<SurfaceTriangle>> = vec![Vec::new(); table.len()];
    world.geometry.for_each_surface_triangle(|t| {
        if t.area > 0.0 {
            triangles[table.entry(t.object, t.face)].push(t);
        }
    });
    let exact = exact_directional(world, &triangles, cancel);
    let mut tracer = PathTracer::new(world, u32::MAX, 1);
    tracer.roulette_start = 1;
    let mut sums = vec![SurfaceSums::default(); table.len()];
    let mut wanted = vec![settings.points; table.len()];
    // In rounds: every surface to `points`, then those still above the error asked for to
    // as many more as their error says (each surface's own points decide: the same for any
    // thread count).
    loop {
        let round: Vec<usize> = (0..sums.len())
            .filter(|&s| !triangles[s].is_empty() && sums[s].incident.n < u64::from(wanted[s]))
            .collect();
        if round.is_empty() || cancel.is_requested() {
            break;
        }
        progress.start(round.len() as u64);
        let drawn: Vec<SurfaceSums> = round
            .par_iter()
            .map(|&s| {
                let points = (sums[s], wanted[s]);
                let more = measure_surface(
                    world,
                    (&tracer, exact[s].is_none()),
                    &triangles[s],
                    (s as u64, settings),
                    points,
                    cancel,
                );
                progress.advance(1);
                more
            })
            .collect();
        progress.finish();
        for (&s, more) in round.iter().zip(drawn) {
            sums[s] = more;
            // A surface stopped short keeps its count wanted: the run is then incomplete.
            if sums[s].incident.n >= u64::from(wanted[s]) {
                let known = exact[s].map_or(Rgb64::BLACK, |e| e.incident / area(&triangles[s]));
                wanted[s] = points_wanted(&sums[s], known, settings.standard_error);
            }
        }
    }
    let mut power = SurfacePower::new(table);
    let mut errors = Vec::with_capacity(sums.len());
    let (mut total_variance, mut indirect_variance) = (Rgb64::BLACK, Rgb64::BLACK);
    for (s, (sums, triangles)) in sums.iter().zip(&triangles).enumerate() {
        let area = area(triangles);
        let n = sums.incident.n.max(1) as f64;
        // A surface without points reports nothing, what is known exactly included.
        let known = exact[s].filter(|_| sums.incident.n > 0).unwrap_or_default();
        let balance = power.balance_mut(s);
        balance.incident = sums.incident.mean() * area + known.incident;
        balance.direct = Some(sums.direct * (area / n) + known.incident);
        balance.absorbed = sums.absorbed * (area / n) + known.absorbed;
        balance.emitted = sums.emitted * (area / n);
        balance.reflected = balance.incident - balance.absorbed;
        let variance = sums.incident.variance_of_mean() * (area * area);
        total_variance += variance;
        indirect_variance += sums.indirect.variance_of_mean() * (area * area);
        // A surface without points (stopped before it, or without area) has no estimate.
        errors.push((sums.incident.n > 0).then(|| variance.map(f64::sqrt)));
    }
    power.set_standard_errors(errors);
    power.set_total_standard_errors(
        total_variance.map(f64::sqrt),
        indirect_variance.map(f64::sqrt),
    );
    power.balance_with_lights(world.lights_power());
    let points: u64 = sums.iter().map(|s| s.incident.n).sum();
    // A surface without area (every triangle degenerate) has no points to draw.
    let complete = (0..sums.len())
        .all(|s| triangles[s].is_empty() || sums[s].incident.n >= u64::from(wanted[s]));
    let sensors = if complete {
        let rays = SensorSettings {
            samples: settings.points,
            paths: settings.points,
            seed: settings.seed,
        };
        sensor_readings(world, Some(&tracer), &rays)
    } else {
        Vec::new()
    };
    let mut stats = Stats {
        seconds: start.elapsed().as_secs_f64(),
        // The gather rays, one per side of each point; the paths continuing from where
        // they meet a surface, the shadow rays and the sensors' rays are not counted.
        rays: 2 * points,
        ..Stats::default()
    };
    stats.insert("points", points);
    // The surfaces whose directional light was cut out exactly rather than sampled.
    let exact = exact.iter().filter(|e| e.is_some()).count() as u64;
    stats.insert("exact_directional_surfaces", exact);
    stats.insert("complete", complete);
    let measurement = Measurement {
        solver: "surface-trace",
        power,
        sensors,
        stats,
    };
    Ok((measurement, complete))
}

/// The points a surface with `sums` is to have in all for a standard error of `target` of
/// its incident power (in its lit channels), `known` W·m⁻² of its irradiance being known
/// exactly: as many as it has when it is there (or has [`MAX_POINTS`], or `target` is 0, or
/// it receives nothing), else as many more as [`samples_for`] says.
fn points_wanted(sums: &SurfaceSums, known: Rgb64, target: f64) -> u32 {
    let n = sums.incident.n;
    let variance = sums.incident.variance_of_mean();
    let (relative, _) = worst_relative_error(sums.incident.mean() + known, variance);
    if target <= 0.0 || relative <= target || n >= u64::from(MAX_POINTS) {
        return n as u32;
    }
    samples_for(n, relative, target, u64::from(MAX_POINTS)) as u32
}

/// The area of a surface made of `triangles`, square scene units.
fn area(triangles: &[SurfaceTriangle]) -> f64 {
    triangles.iter().map(|t| t.area).sum()
}

/// What the directional lights send to one surface, known exactly, W.
#[derive(Clone, Copy, Default)]
struct KnownLight {
    /// Incident on both sides together.
    incident: Rgb64,
    /// Absorbed of it.
    absorbed: Rgb64,
}

/// What the directional lights send to each surface (made of `triangles[s]`), known exactly
/// where their shadows can be cut out of it ([`ParallelShadows`]): `None` for a surface
/// left to shadow rays at its points — every surface when the scene has no directional
/// light or a world the shadows cannot take, and those with a textured diffuse colour (their
/// absorbed share varies over them) or with too many shadows over them.
fn exact_directional(
    world: &World,
    triangles: &[Vec<SurfaceTriangle>],
    cancel: &Cancel,
) -> Vec<Option<KnownLight>> {
    let lights: Option<Vec<(ParallelShadows, Rgb64, DVec3)>> = (world.lights.delta.iter())
        .filter_map(|light| match *light {
            LightKind::Directional {
                direction,
                irradiance,
            } => Some((direction.as_dvec3(), irradiance.to_f64())),
            _ => None,
        })
        .map(|(direction, irradiance)| {
            let shadows = ParallelShadows::new(world, direction)?;
            Some((shadows, irradiance, -direction.normalize_or_zero()))
        })
        .collect();
    let lights = lights.filter(|l| !l.is_empty());
    let Some(lights) = lights else {
        return vec![None; triangles.len()];
    };
    let scene = &world.scene;
    triangles
        .par_iter()
        .map(|triangles| {
            if cancel.is_requested() {
                return None;
            }
            let mut known = KnownLight::default();
            for t in triangles {
                let hit = world.geometry.surface_point(t, 1.0 / 3.0, 1.0 / 3.0);
                if scene.materials[hit.material as usize]
                    .diffuse_texture
                    .is_some()
                {
                    return None;
                }
                let material = SurfaceMaterial::at(scene, &hit);
                for (shadows, irradiance, toward) in &lights {
                    let cos = hit.ng.as_dvec3().dot(*toward);
                    let front = cos > 0.0;
                    let share = shadows.lit_share(t.prim)?;
                    let e = *irradiance * (cos.abs() * share * t.area);
                    let scattered = if material.is_black_from(front) {
                        Rgb::BLACK
                    } else {
                        material.diffuse + material.translucency
                    };
                    known.incident += e;
                    known.absorbed += (Rgb64::WHITE - scattered.to_f64()) * e;
                }
            }
            Some(known)
        })
        .collect()
}

/// `sums` of the surface made of `triangles` with its points up to `wanted`, drawn from
/// streams `3·stream`… of the seed (point `i` from index `i` of each); fewer when `cancel`
/// is set. Its points take the directional lights by shadow rays when `directional`.
fn measure_surface(
    world: &World,
    (tracer, directional): (&PathTracer, bool),
    triangles: &[SurfaceTriangle],
    (stream, settings): (u64, &SurfaceTraceSettings),
    (mut sums, wanted): (SurfaceSums, u32),
    cancel: &Cancel,
) -> SurfaceSums {
    let mut cdf = Vec::with_capacity(triangles.len());
    let mut area = 0.0;
    for t in triangles {
        area += t.area;
        cdf.push(area);
    }
    let scene = &world.scene;
    for i in sums.incident.n as u32..wanted {
        if i % CANCEL_POINTS == 0 && cancel.is_requested() {
            break;
        }
        // The point from its own stream, each side's rays from theirs: every side's gather
        // direction is then the first two dimensions of a Sobol sequence, however many
        // numbers the other side's path used (see the module).
        let mut sampler = Sampler::new(SequenceKind::Sobol, settings.seed, 3 * stream, i);
        let u = sampler.next_2d();
        let pick = f64::from(u.x) * area;
        let k = cdf.partition_point(|&c| c <= pick).min(triangles.len() - 1);
        let below = if k == 0 { 0.0 } else { cdf[k - 1] };
        let across = ((pick - below) / triangles[k].area).clamp(0.0, 1.0) as f32;
        let (b1, b2) = uniform_triangle(Vec2::new(across, u.y));
        let hit = world.geometry.surface_point(&triangles[k], b1, b2);
        if !world.geometry.is_present(hit.material, hit.uv) {
            sums.incident.add(Rgb64::BLACK);
            sums.indirect.add(Rgb64::BLACK);
            continue;
        }
        let material = SurfaceMaterial::at(scene, &hit);
        let m = &scene.materials[hit.material as usize];
        let (mut incident, mut incident_indirect) = (Rgb64::BLACK, Rgb64::BLACK);
        for (side, front) in [true, false].into_iter().enumerate() {
            let normal = if front { hit.ng } else { -hit.ng };
            let stream = 3 * stream + 1 + side as u64;
            let mut sampler = Sampler::new(SequenceKind::Sobol, settings.seed, stream, i);
            let (direct, indirect) =
                irradiance_sample(world, tracer, (hit.p, normal), directional, &mut sampler);
            let scattered = if material.is_black_from(front) {
                Rgb::BLACK
            } else {
                material.diffuse + material.translucency
            };
            let e = direct + indirect;
            incident += e;
            incident_indirect += indirect;
            sums.direct += direct;
            sums.absorbed += (Rgb64::WHITE - scattered.to_f64()) * e;
            sums.emitted += emitted_toward(scene, m, hit.uv, front).to_f64() * PI;
        }
        sums.incident.add(incident);
        sums.indirect.add(incident_indirect);
    }
    sums
}
