//! Sensor readings of a radiosity solution: the irradiance at a point sensor gathered from
//! every leaf side of the solution and from every non-surface light,
//! `E = Σⱼ Bⱼ·F(x→j)·Vⱼ + Σ_lights E_light(x)`, with `F(x→j)` the exact point-to-polygon form
//! factor of the part of leaf side `j` in front of the sensor and `Vⱼ` its visible share
//! (rays spread by form factor, as many as the side's share of the sensor's unoccluded light
//! asks; none where shaft culling, run for the sides that get 16 rays or more, finds nothing
//! in the way). The direct part is what the leaves emit themselves plus the lights; the
//! indirect part what they reflect.

use super::solution::Solution;
use super::system::RadiositySystem;
use crate::color::Rgb64;
use crate::measure::SensorReading;
use crate::radiosity::element::Side;
use crate::radiosity::form_factor::point_to_side;
use crate::world::non_surface_irradiance;
use rayon::prelude::*;

/// Rays per edge of the jittered grid to a leaf side bringing a sensor a share `s` of its
/// light seen unoccluded: `⌈s·EDGE_RAYS_PER_SHARE⌉`, from [`FEWEST_EDGE_RAYS`] to
/// [`MOST_EDGE_RAYS`]. A shadow edge across an `m × m` grid misses about `1/m` of the leaf,
/// so a leaf misses at most `1/1600` of the sensor's light (`2 × 2` rays for leaves under
/// `1/800` of it, whose errors, of either sign, are each under half their share).
const EDGE_RAYS_PER_SHARE: f64 = 1600.0;
/// The fewest rays per grid edge.
const FEWEST_EDGE_RAYS: u32 = 2;
/// The most rays per grid edge (`16 × 16`: a shadow edge across the leaf costs well under
/// 1 % of it).
const MOST_EDGE_RAYS: u32 = 16;

impl Solution {
    /// The reading of every sensor of `system`'s scene (in scene order), in parallel over the
    /// sensors; deterministic.
    pub fn sensor_readings(&self, system: &RadiositySystem) -> Vec<SensorReading> {
        let world = system.world();
        let shadows = system.visibility().world();
        let radiosity = &self.display_radiosity(system);
        world
            .scene
            .sensors
            .par_iter()
            .enumerate()
            .map(|(index, sensor)| {
                let (x, n) = (sensor.position.as_dvec3(), sensor.normal.as_dvec3());
                // Every leaf side in front of the sensor, with its form factor from it.
                let seen: Vec<(usize, f64)> = system
                    .leaves
                    .iter()
                    .enumerate()
                    .flat_map(|(leaf, &patch)| {
                        let patch = system.mesh.patch(patch);
                        Side::BOTH.into_iter().filter_map(move |side| {
                            let element = RadiositySystem::element(leaf, side);
                            let f = point_to_side(x, n, patch, side);
                            (radiosity[element].max_channel() > 0.0 && f > 0.0)
                                .then_some((element, f))
                        })
                    })
                    .collect();
                let unoccluded: f64 = seen
                    .iter()
                    .map(|&(element, f)| f * radiosity[element].luminance())
                    .sum();
                let mut direct = non_surface_irradiance(shadows, sensor);
                let mut indirect = Rgb64::BLACK;
                let mut rays = 0;
                for (element, f) in seen {
                    let patch = system.patch(element);
                    let b = radiosity[element];
                    let share = f * b.luminance() / unoccluded;
                    let edge = ((share * EDGE_RAYS_PER_SHARE).ceil() as u32)
                        .clamp(FEWEST_EDGE_RAYS, MOST_EDGE_RAYS);
                    let key = (index as u64) << 32 | element as u64;
                    let (visible, cast) =
                        system
                            .visibility()
                            .share_from_point(x, n, patch, key, edge * edge);
                    rays += cast;
                    let emitted = system.emission[element];
                    direct += emitted * (f * visible);
                    indirect += (b - emitted).map(|c| c.max(0.0)) * (f * visible);
                }
                system.count_work(0, rays);
                SensorReading {
                    sensor: sensor.clone(),
                    direct,
                    indirect,
                    standard_error: None,
                }
            })
            .collect()
    }
}
