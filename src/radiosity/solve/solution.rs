//! A radiosity solution: radiosity and irradiance per element (side of a leaf patch), the
//! convergence history
//! and the time spent per phase; and what it hands on — the power per reported surface, the
//! run's statistics and the lit mesh.
//!
//! Per element `i` with area `A_i`, irradiance `H_i`, emitted radiosity `E_i`, reflectance
//! `ρ_i`, translucency `τ_i` and the share `c_i` an alpha texture leaves in place (1 without
//! one), the surface power is: incident `c_i A_i H_i`, absorbed `(c_i − ρ_i − τ_i) A_i H_i`,
//! emitted `A_i E_i`, reflected (out of either side) `(ρ_i + τ_i) A_i H_i` (`E_i`, `ρ_i` and
//! `τ_i` already include `c_i`), summed per reported surface (of a periodic scene unrolled
//! for radiosity, its plot's own; not the copies around it). Scene-wide, the point,
//! spot and directional lights count with the power they send into the mesh
//! (`Σ A_i H_light,i`), and the escaped power is what is emitted but not absorbed by any
//! patch (light leaving an open scene, plus the small imbalance of the discretisation), at
//! least zero: where the form factors of a closed scene add up to a little more than one, the
//! patches absorb a little more than is emitted, and that shows in the absorbed power.

use super::interpolate::VertexWelding;
use super::lightmap;
use super::lookup::{RadiosityLookup, Shading};
use super::rounds::RoundStats;
use super::solver_kind::SolverKind;
use super::system::RadiositySystem;
use crate::color::Rgb64;
use crate::measure::{LitMesh, Measurement, Stats, SurfacePower, SurfaceTable};
use crate::radiosity::element::Side;
use glam::DVec3;
use glam::{Vec2, Vec3};

/// The irradiance of every element measured anew after a solve (the final gather at the
/// reported surfaces, `final_gather::gather_surfaces`), in element order; the elements of the
/// surfaces not gathered keep the solution's values.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GatheredIrradiance {
    /// Irradiance, W·m⁻².
    pub irradiance: Vec<Rgb64>,
    /// The part of `irradiance` straight from the lights and emitting surfaces, W·m⁻² (`None`
    /// where the solution's value is kept and the solver did not compute it).
    pub direct: Vec<Option<Rgb64>>,
    /// The variance of the estimate of `irradiance`, (W·m⁻²)² (`None` where the solution's
    /// value is kept).
    pub variance: Vec<Option<Rgb64>>,
    /// Points measured (each with its shadow rays and one gather ray), both passes.
    pub points: u64,
    /// Reported surfaces gathered.
    pub surfaces: usize,
    /// Whether the gather measured a second time over the solution corrected by its first
    /// pass (some surface's solution value was off by more than the gather's error).
    pub corrected: bool,
    /// Wall-clock seconds of the gather.
    pub seconds: f64,
}

/// Wall-clock seconds per phase of a solve.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PhaseTimes {
    /// Meshing, material averages and light links.
    pub setup: f64,
    /// Form factors and visibility (matrix assembly, or the columns of the shots).
    pub form_factors: f64,
    /// The iterations themselves (without form factors).
    pub iterations: f64,
}

/// The result of a radiosity solver, per element of its [`RadiositySystem`].
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// The solver that produced it.
    pub solver: SolverKind,
    /// The solver's name in reports: `matrix-jacobi`, `matrix-gauss-seidel`, `progressive`,
    /// `hierarchical`, `hierarchical-shooting`.
    pub solver_name: &'static str,
    /// Radiosity `B` per element (one side of a leaf), W·m⁻².
    pub radiosity: Vec<Rgb64>,
    /// Irradiance `H` gathered per element (light links included), W·m⁻².
    pub irradiance: Vec<Rgb64>,
    /// The part of `irradiance` straight from the lights and the emitting elements, W·m⁻²,
    /// when the solver computed it (not for hierarchical shooting or an interrupted solve).
    pub direct_irradiance: Option<Vec<Rgb64>>,
    /// Ambient radiosity estimate of the light not yet distributed (progressive refinement,
    /// seed 004), W·m⁻²; zero for the matrix solvers. Display adds `(ρ_i + τ_i) × ambient`.
    pub ambient: Rgb64,
    /// Per iteration (sweep or shot): the residual or unshot power as a fraction of the
    /// source power ([`power_fraction`]).
    pub convergence: Vec<f64>,
    /// True when the last convergence value is at or below the tolerance.
    pub converged: bool,
    /// True when Ctrl-C stopped the solve; the state reached is kept.
    pub interrupted: bool,
    /// Time per phase.
    pub seconds: PhaseTimes,
    /// Hierarchical solvers: what each round of refinement did (empty for flat solvers).
    pub rounds: Vec<RoundStats>,
    /// Hierarchical solvers: links at the end (0 for flat solvers).
    pub links: usize,
    /// Hierarchical radiosity: the links among them whose light the near field's rays carry
    /// (estimates, right on average over many patches, not held to the error threshold
    /// patch by patch like the other links; 0 for the other solvers).
    pub near_links: usize,
    /// Hierarchical radiosity: the patch links at the end, as segments between the centroids
    /// of their receiver and emitter, when `HierarchicalSettings::link_segments` asked for
    /// them (empty otherwise, and for the other solvers).
    pub link_segments: Vec<LinkSegment>,
}

/// A link drawn as a segment: from the centroid of the receiving node to that of the
/// emitting node (scene units), with the objects the two patches belong to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkSegment {
    /// Centroid of the receiving node (centre of a cluster).
    pub receiver: DVec3,
    /// Centroid of the emitting node (centre of a cluster).
    pub emitter: DVec3,
    /// Object index of the receiving patch (`None` for a cluster of patches).
    pub receiver_object: Option<u32>,
    /// Object index of the emitting patch (`None` for a cluster of patches or a light).
    pub emitter_object: Option<u32>,
    /// For a light link (a lamp, the sun or a sky lighting the receiver): the light's index
    /// in the scene's light list; the emitter end is then the lamp's position, or for the
    /// sun and the skies a point toward where their light comes from (the sun; the receiving
    /// side's normal for a sky) at the radius of the scene's bounding sphere.
    pub light: Option<u32>,
    /// The link's level in the patch hierarchy: the quadtree depth of the finer of its two
    /// patches (0: between root patches; `None` for a link with a cluster at an end).
    pub level: Option<u32>,
}

impl Solution {
    /// Iterations done (sweeps or shots).
    pub fn iterations(&self) -> usize {
        self.convergence.len()
    }

    /// The display radiosity looked up along rays by `shading`, with the texture detail of
    /// textured surfaces (what the display and the lightmaps show).
    pub(super) fn display_lookup<'s>(
        &self,
        system: &'s RadiositySystem,
        shading: Shading,
    ) -> RadiosityLookup<'s> {
        RadiosityLookup::new(system, self.display_radiosity(system), shading)
            .with_texture_detail(self.display_irradiance(), true)
    }

    /// The radiosity to display per element: `B_i + (ρ_i + τ_i) × ambient` (the ambient
    /// light arrives on both sides), W·m⁻².
    pub fn display_radiosity(&self, system: &RadiositySystem) -> Vec<Rgb64> {
        self.radiosity
            .iter()
            .enumerate()
            .map(|(k, &b)| b + system.albedo(k) * self.ambient)
            .collect()
    }

    /// The irradiance each element shows, W·m⁻²: its irradiance plus the ambient term
    /// (what [`Self::display_radiosity`] reflects).
    pub fn display_irradiance(&self) -> Vec<Rgb64> {
        self.irradiance.iter().map(|&h| h + self.ambient).collect()
    }

    /// The radiosity each element reflects, W·m⁻²: its display radiosity without its own
    /// emission (the light a final gather reads where its rays land).
    pub fn reflected_radiosity(&self, system: &RadiositySystem) -> Vec<Rgb64> {
        self.display_radiosity(system)
            .into_iter()
            .zip(&system.emission)
            .map(|(b, &e)| (b - e).map(|x| x.max(0.0)))
            .collect()
    }

    /// The solution with the display irradiance ([`Self::display_irradiance`]) of the
    /// elements `measured` gives replaced by it (W·m⁻²) and their radiosity following it
    /// (`E + ρ·H + τ·H` of the leaf's other side): what a final gather reads once some
    /// surfaces have been measured anew.
    pub fn with_irradiance(&self, system: &RadiositySystem, measured: &[Option<Rgb64>]) -> Self {
        let ambient = self.ambient;
        let display = |k: usize| measured[k].unwrap_or(self.irradiance[k] + ambient);
        let mut corrected = self.clone();
        for (k, m) in measured.iter().enumerate() {
            let Some(h) = *m else { continue };
            // The display adds the ambient term to both: take it off here.
            corrected.irradiance[k] = h - ambient;
            let other = display(RadiositySystem::other_side(k));
            corrected.radiosity[k] =
                system.emission[k] + system.scattered(k, h, other) - system.albedo(k) * ambient;
        }
        corrected
    }

    /// What the solution measured on `system`'s scene: its power per reported surface and
    /// its statistics, under the solver's name.
    pub fn measurement(&self, system: &RadiositySystem) -> Measurement {
        Measurement {
            solver: self.solver_name,
            power: self.surface_power(system, &self.irradiance, &|k| {
                self.direct_irradiance.as_ref().map(|d| d[k])
            }),
            sensors: self.sensor_readings(system),
            stats: self.stats(system),
        }
    }

    /// [`Self::measurement`] with the irradiance of every element measured anew after the
    /// solve (`gathered`): the power per reported surface from it, with the standard error of
    /// each gathered surface's incident power, and the gather's surfaces, rays and time in
    /// the statistics.
    pub fn measurement_with(
        &self,
        system: &RadiositySystem,
        gathered: &GatheredIrradiance,
    ) -> Measurement {
        let mut power = self.surface_power(system, &gathered.irradiance, &|k| gathered.direct[k]);
        let mut variances = vec![None; power.table().len()];
        let own = system.world().own_objects() as u32;
        for k in 0..system.len() {
            let patch = system.patch(k);
            if patch.object >= own {
                continue;
            }
            let weight = system.coverage[k] * system.area[k];
            let entry = &mut variances[power.table().entry(patch.object, patch.face)];
            if let Some(variance) = gathered.variance[k] {
                *entry = Some(entry.unwrap_or(Rgb64::BLACK) + variance * (weight * weight));
            }
        }
        power.set_standard_errors(
            variances
                .into_iter()
                .map(|v| v.map(|v| v.map(f64::sqrt)))
                .collect(),
        );
        let mut stats = self.stats(system);
        stats.insert("surface_gather_surfaces", gathered.surfaces);
        stats.insert("surface_gather_points", gathered.points);
        stats.insert("surface_gather_corrected", gathered.corrected);
        stats.insert("seconds_surface_gather", gathered.seconds);
        stats.seconds += gathered.seconds;
        Measurement {
            solver: self.solver_name,
            power,
            sensors: self.sensor_readings(system),
            stats,
        }
    }

    /// The power per reported surface of `system`'s scene, W, as the module describes, from
    /// the irradiance per element `irradiance` (and its direct part `direct(k)` where known),
    /// W·m⁻²; a surface has a direct part when all its elements have one.
    fn surface_power(
        &self,
        system: &RadiositySystem,
        irradiance: &[Rgb64],
        direct: &dyn Fn(usize) -> Option<Rgb64>,
    ) -> SurfacePower {
        // A periodic scene's plot: its own objects, not the copies around it.
        let world = system.world().plot_world();
        let own = world.scene.objects.len() as u32;
        let mut power = SurfacePower::new(SurfaceTable::new(&world.scene, &world.geometry));
        let mut direct_unknown = vec![false; power.table().len()];
        for (k, &h) in irradiance.iter().enumerate() {
            let patch = system.patch(k);
            if patch.object >= own {
                continue;
            }
            let entry = power.table().entry(patch.object, patch.face);
            direct_unknown[entry] |= direct(k).is_none();
            // What arrives on this side and is scattered back out of either side.
            let (a, e, r, c) = (
                system.area[k],
                system.emission[k],
                system.albedo(k),
                system.coverage[k],
            );
            let balance = power.balance_mut(entry);
            balance.incident += h * (c * a);
            if let Some(d) = direct(k) {
                balance.direct = Some(balance.direct.unwrap_or(Rgb64::BLACK) + d * (c * a));
            }
            balance.absorbed += (Rgb64::splat(c) - r) * a * h;
            balance.emitted += e * a;
            balance.reflected += r * a * h;
        }
        for (entry, &unknown) in direct_unknown.iter().enumerate() {
            if unknown {
                power.balance_mut(entry).direct = None;
            }
        }
        power.balance_with_lights(world.lights_power());
        power
    }

    /// The statistics of the solve: time per phase, rays, leaf patches and elements (their
    /// sides), form factors, iterations, the root patches lying on others in their plane
    /// lit on the same side, the area they overlap (scene units²) and the light counted
    /// twice there (W, luminance; [`Solution::light_counted_twice`]), the copies of a
    /// periodic plot's objects solved around it (where there are any)
    /// and the convergence history (at most [`CONVERGENCE_ROWS`] rows of `[iteration,
    /// value]`, spread evenly in the logarithm of the iteration number).
    fn stats(&self, system: &RadiositySystem) -> Stats {
        let s = &self.seconds;
        let mut stats = Stats {
            seconds: s.setup + s.form_factors + s.iterations,
            rays: system.visibility_ray_count(),
            ..Stats::default()
        };
        stats.insert("patches", system.leaves.len());
        stats.insert("elements", system.len());
        stats.insert("patch_nodes", system.mesh.len());
        stats.insert("form_factors", system.form_factor_count());
        stats.insert("visibility_rays", system.visibility_ray_count());
        stats.insert("iterations", self.iterations());
        stats.insert("converged", self.converged);
        stats.insert("interrupted", self.interrupted);
        stats.insert(
            "convergence",
            serde_json::json!(convergence_rows(&self.convergence)),
        );
        stats.insert("source_power", source_power(system));
        let world = system.world();
        let copies = world.scene.objects.len() - world.own_objects();
        if copies > 0 {
            // Copies of a periodic plot's objects solved around it (`World::unrolled`).
            stats.insert("periodic_copies", copies);
        }
        let twice = self.light_counted_twice(system);
        stats.insert("overlapping_patches", twice.patches);
        stats.insert("overlapping_area", twice.area);
        stats.insert("light_counted_twice", twice.power);
        stats.insert("seconds_setup", s.setup);
        stats.insert("seconds_form_factors", s.form_factors);
        stats.insert("seconds_iterations", s.iterations);
        if !self.rounds.is_empty() {
            stats.insert("links", self.links);
            stats.insert("rounds", serde_json::json!(self.rounds));
        }
        stats
    }

    /// The solution as a lit mesh: both sides of every leaf as polygons (the back with its
    /// corners reversed and its normal turned), with the smooth corner values
    /// ([`VertexWelding::smooth`]: display radiosity and irradiance, ambient term included) of
    /// that side; the
    /// polygons of textured materials also carry their texture coordinates and their place in
    /// their surface's lightmap (baked by `radiosity::solve::lightmap`) when `lightmaps`
    /// asks for them (a format that carries textures).
    pub fn lit_mesh(&self, system: &RadiositySystem, lightmaps: bool) -> LitMesh {
        let display = self.display_radiosity(system);
        let lightmaps = if lightmaps {
            lightmap::bake(system, &self.display_lookup(system, Shading::Smooth))
        } else {
            lightmap::Lightmaps::none(system)
        };
        let mut lit = LitMesh {
            surfaces: lightmaps.surfaces,
            ..LitMesh::default()
        };
        let irradiance = self.display_irradiance();
        // A periodic scene's plot alone, without the copies around it.
        let own = system.world().own_objects() as u32;
        // The vertices found once for both sides and both quantities.
        let welding = VertexWelding::new(&system.mesh, &system.leaves);
        for side in Side::BOTH {
            let smooth = |per_element: &[Rgb64]| {
                let values: Vec<Rgb64> = (0..system.leaves.len())
                    .map(|k| per_element[RadiositySystem::element(k, side)])
                    .collect();
                welding.smooth(&values)
            };
            let (corners, arriving) = rayon::join(|| smooth(&display), || smooth(&irradiance));
            for (k, values) in corners.iter().enumerate() {
                let patch = system.mesh.patch(system.leaves[k]);
                if patch.object >= own {
                    continue;
                }
                let n = patch.corners().len();
                let mut points: Vec<Vec3> = patch.corners().iter().map(|c| c.as_vec3()).collect();
                let mut values = values[..n].to_vec();
                let mut arrived = arriving[k][..n].to_vec();
                let mut texcoords: Vec<Vec2> = patch.uvs().iter().map(|uv| uv.as_vec2()).collect();
                let mapped = &lightmaps.corners[RadiositySystem::element(k, side)];
                let mut lightmap_texcoords =
                    mapped.as_ref().map_or(vec![Vec2::ZERO; n], |m| m.1.clone());
                if side == Side::Back {
                    points.reverse();
                    values.reverse();
                    arrived.reverse();
                    texcoords.reverse();
                    lightmap_texcoords.reverse();
                }
                lit.push_mapped_polygon(
                    patch.object,
                    &points,
                    side.normal(patch).as_vec3(),
                    (&values, &arrived),
                    (&texcoords, &lightmap_texcoords),
                    mapped.as_ref().map(|m| m.0),
                );
            }
        }
        lit
    }

    /// The initial state: radiosity = source term, irradiance = light-link irradiance.
    pub(super) fn start(
        system: &RadiositySystem,
        solver: SolverKind,
        solver_name: &'static str,
    ) -> Solution {
        Solution {
            solver,
            solver_name,
            radiosity: (0..system.len()).map(|k| system.source(k)).collect(),
            irradiance: system.light_irradiance.clone(),
            direct_irradiance: None,
            ambient: Rgb64::BLACK,
            convergence: Vec::new(),
            converged: false,
            interrupted: false,
            seconds: PhaseTimes {
                setup: system.setup_seconds,
                ..PhaseTimes::default()
            },
            rounds: Vec::new(),
            links: 0,
            near_links: 0,
            link_segments: Vec::new(),
        }
    }
}

/// Largest number of rows of the convergence history in the statistics.
pub const CONVERGENCE_ROWS: usize = 64;

/// At most [`CONVERGENCE_ROWS`] rows `[iteration, value]` of `history` (iterations counted
/// from 1), spread evenly in the logarithm of the iteration number; the last iteration is
/// always kept.
fn convergence_rows(history: &[f64]) -> Vec<(usize, f64)> {
    let n = history.len();
    let mut rows: Vec<usize> = if n <= CONVERGENCE_ROWS {
        (1..=n).collect()
    } else {
        let step = (n as f64).ln() / (CONVERGENCE_ROWS - 1) as f64;
        (0..CONVERGENCE_ROWS)
            .map(|k| ((k as f64 * step).exp().round() as usize).clamp(1, n))
            .collect()
    };
    rows.dedup();
    rows.into_iter().map(|i| (i, history[i - 1])).collect()
}

/// `Σ_i A_i Y(|d_i|) / Σ_i A_i Y(S_i)`: a per-leaf radiosity change or unshot radiosity `d`
/// as a fraction of the source power (Y = luminance, `S` the source term). 0 when the scene
/// has no source.
pub fn power_fraction(system: &RadiositySystem, d: &[Rgb64]) -> f64 {
    let source = source_power(system);
    if source <= 0.0 {
        return 0.0;
    }
    let change: f64 = d
        .iter()
        .zip(&system.area)
        .map(|(v, a)| a * v.map(f64::abs).luminance())
        .sum();
    change / source
}

/// Luminance of the source power `Σ_i A_i S_i`, W.
pub fn source_power(system: &RadiositySystem) -> f64 {
    (0..system.len())
        .map(|k| system.area[k] * system.source(k).luminance())
        .sum()
}
