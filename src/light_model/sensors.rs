//! Readings at point sensors in the light model. A sensor is a point: no photon can hit it,
//! so every place where light leaves a surface is connected to every sensor by a shadow ray
//! (next-event estimation toward the sensor):
//! - a photon leaving an emitting surface at `x` with power `Φ` (cosine-distributed about
//!   the emitting side's normal `n`) sends the radiant intensity `Φ·cos θₓ/π` toward the
//!   sensor — direct light;
//! - a photon of power `Φ` arriving at a surface along `ωᵢ` sends `Φ·f(ωᵢ, ω)·|cos θₓ|`
//!   toward it (`f` the material's non-delta scattering function: reflection toward a
//!   sensor on the photon's side, diffuse transmission toward one behind a translucent
//!   surface) — indirect light;
//!
//! and the sensor at distance `d`, seeing the point under `cos θₛ`, receives the irradiance
//! `I·cos θₛ/d²` when nothing lies between. Light reflected by ideal mirrors and glass cannot
//! be connected to a point and is not counted (a caustic on a sensor is not measured).
//! Point, Lambertian, spot and directional lights and the sky, whose photons start from a
//! single point or travel in a single direction, reach the sensor through
//! [`crate::world::non_surface_irradiance`] instead (exact for the first four, stratified
//! directions for the sky), which is what a connection from their photons would give.

use crate::color::Rgb64;
use crate::world::{SurfaceHit, SurfaceMaterial, World, non_surface_irradiance, sees_point};
use glam::Vec3;
use std::f64::consts::PI;

/// The irradiance (W·m⁻²) that every non-surface light of `world` sends to each sensor.
pub(super) fn delta_light_direct(world: &World) -> Vec<Rgb64> {
    world
        .scene
        .sensors
        .iter()
        .map(|s| non_surface_irradiance(world, s))
        .collect()
}

/// Adds to part `part` of each sensor's entry of `out` (W·m⁻²) the irradiance of a photon
/// of power `power` (W) leaving an emitting surface at `x` whose emitting side has the unit
/// normal `n`.
pub(super) fn connect_emission(
    world: &World,
    (x, n): (Vec3, Vec3),
    power: Rgb64,
    (out, part): (&mut [[Rgb64; 2]], usize),
) {
    connect(world, x, n, (out, part), |to_sensor| {
        power * (f64::from(n.dot(to_sensor)).max(0.0) / PI)
    });
}

/// Adds to part `part` of each sensor's entry of `out` (W·m⁻²) the irradiance of a photon
/// of power `power` (W) arriving along the unit direction `dir` at `hit`, reflected toward
/// the sensors by the non-delta part of the material there.
pub(super) fn connect_reflection(
    world: &World,
    (hit, dir): (&SurfaceHit, Vec3),
    power: Rgb64,
    (out, part): (&mut [[Rgb64; 2]], usize),
) {
    let m = SurfaceMaterial::at(&world.scene, hit);
    if m.is_black_from(hit.front_face) || !m.has_density() {
        return;
    }
    let side = if hit.front_face { 1.0 } else { -1.0 };
    // Sensors on the side the photon came from see it reflected; those behind a translucent
    // surface see it passed through.
    for &toward in m.hemispheres() {
        let (ng, ns) = (hit.ng * (side * toward), hit.ns * (side * toward));
        connect(world, hit.p, ng, (&mut *out, part), |to_sensor| {
            let cos = f64::from(ng.dot(to_sensor));
            if cos <= 0.0 {
                return Rgb64::BLACK;
            }
            power * m.eval(ns, to_sensor, -dir).to_f64() * cos
        });
    }
}

/// Adds to part `part` of each sensor's entry of `out` the irradiance `I·cos θₛ/d²` from the
/// surface point `x` (unit normal `n` of the side light leaves from), where `intensity(ω)` is
/// the radiant intensity (W·sr⁻¹) it sends along the unit direction `ω` toward the sensor,
/// when the way is free.
fn connect(
    world: &World,
    x: Vec3,
    n: Vec3,
    (out, part): (&mut [[Rgb64; 2]], usize),
    intensity: impl Fn(Vec3) -> Rgb64,
) {
    for (sensor, e) in world.scene.sensors.iter().zip(out.iter_mut()) {
        let d = sensor.position - x;
        let d2 = f64::from(d.length_squared());
        let to_sensor = d.normalize_or_zero();
        let cos_sensor = f64::from(-sensor.normal.dot(to_sensor));
        if d2 <= 0.0 || cos_sensor <= 0.0 || n.dot(to_sensor) <= 0.0 {
            continue;
        }
        let i = intensity(to_sensor);
        if i.max_channel() <= 0.0 || !sees_point(world, (x, n), (sensor.position, sensor.normal)) {
            continue;
        }
        e[part] += i * (cos_sensor / d2);
    }
}
