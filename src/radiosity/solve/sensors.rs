//! Sensor readings of a radiosity solution: the irradiance at a point sensor gathered from
//! every leaf side of the solution and from every non-surface light,
//! `E = Σⱼ Bⱼ·F(x→j)·Vⱼ + Σ_lights E_light(x)`, with `F(x→j)` the exact point-to-polygon form
//! factor of the part of leaf side `j` in front of the sensor and `Vⱼ` its visible share
//! (rays spread by form factor, none where shaft culling finds nothing in the way). The direct part is
//! what the leaves emit themselves plus the lights; the indirect part what they reflect.

use super::solution::Solution;
use super::system::RadiositySystem;
use crate::color::Rgb64;
use crate::measure::SensorReading;
use crate::radiosity::element::Side;
use crate::radiosity::form_factor::point_to_side;
use crate::world::non_surface_irradiance;
use rayon::prelude::*;

/// Visibility rays from a sensor to a leaf side that something may hide (16 × 16: a shadow
/// edge across the leaf costs well under 1 % of it).
const RAYS_PER_LEAF: u32 = 256;
impl Solution {
    /// The reading of every sensor of `system`'s scene (in scene order), in parallel over the
    /// sensors; deterministic.
    pub fn sensor_readings(&self, system: &RadiositySystem) -> Vec<SensorReading> {
        let world = system.world();
        let shadows = system.visibility().world();
        let radiosity = self.display_radiosity(system);
        world
            .scene
            .sensors
            .par_iter()
            .enumerate()
            .map(|(index, sensor)| {
                let (x, n) = (sensor.position.as_dvec3(), sensor.normal.as_dvec3());
                let mut direct = non_surface_irradiance(shadows, sensor);
                let mut indirect = Rgb64::BLACK;
                let mut rays = 0;
                for (leaf, &patch) in system.leaves.iter().enumerate() {
                    let patch = system.mesh.patch(patch);
                    for side in Side::BOTH {
                        let element = RadiositySystem::element(leaf, side);
                        let b = radiosity[element];
                        if b.max_channel() <= 0.0 {
                            continue;
                        }
                        let f = point_to_side(x, n, patch, side);
                        if f <= 0.0 {
                            continue;
                        }
                        let key = (index as u64) << 32 | element as u64;
                        let (share, cast) =
                            system
                                .visibility()
                                .share_from_point(x, n, patch, key, RAYS_PER_LEAF);
                        rays += cast;
                        let emitted = system.emission[element];
                        direct += emitted * (f * share);
                        indirect += (b - emitted).map(|c| c.max(0.0)) * (f * share);
                    }
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
