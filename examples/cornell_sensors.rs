//! Illuminance along a line across the Cornell box's floor (z = 0.5 m, in front of the tall
//! block, through the blocks' shadows), read by sensors with the path tracer, the light model
//! and hierarchical radiosity at their defaults. Prints CSV: x (m), then each method's
//! illuminance (lux of the box's radiometric units: 683 × luminance) and, for the Monte Carlo
//! methods, its standard error. `scripts/validation-figures.py` plots it.
//!
//! Run: `cargo run --release --example cornell_sensors [SENSORS]` (default 26).

use glam::Vec3;
use std::sync::Arc;
use strahl::accel::AccelKind;
use strahl::color::Rgb64;
use strahl::light_model::LightTraceSettings;
use strahl::measure::SensorReading;
use strahl::method::{Method, MethodKind, SensorTraceSettings, run};
use strahl::progress::{Cancel, NoProgress};
use strahl::radiosity::solve::SolverKind;
use strahl::scene::{Sensor, builtin};
use strahl::world::World;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let count: u32 = match std::env::args().nth(1) {
        Some(n) => n.parse()?,
        None => 26,
    };
    let mut scene = builtin::load("cornell").ok_or("no built-in cornell")??;
    for k in 0..count {
        let x = 0.02 + 0.51 * (k as f32 + 0.5) / count as f32;
        scene.sensors.push(Sensor {
            name: format!("x={x:.3}"),
            position: Vec3::new(x, 0.0, 0.5),
            normal: Vec3::Y,
        });
    }
    let world = Arc::new(World::new(scene, AccelKind::Bvh)?);
    let sensors = |method: &Method| -> Result<Vec<SensorReading>, Box<dyn std::error::Error>> {
        Ok(run(&world, method, &NoProgress, &Cancel::new())?
            .sensors()
            .to_vec())
    };
    let paths = sensors(&Method::SensorTrace(SensorTraceSettings {
        samples: 1 << 16,
        paths: 1 << 16,
        path_tracing: true,
        seed: 1,
    }))?;
    let light = sensors(&Method::LightTrace(LightTraceSettings {
        photons: 10_000_000,
        seed: 1,
        ..LightTraceSettings::default()
    }))?;
    let radiosity = sensors(&MethodKind::Radiosity(SolverKind::Hierarchical).with_defaults())?;
    let lux = |e: Rgb64| 683.0 * e.luminance();
    let error = |r: &SensorReading| r.standard_error.map_or(0.0, lux);
    println!("x,pathtrace,pathtrace_se,light_trace,light_trace_se,hierarchical");
    for ((p, l), h) in paths.iter().zip(&light).zip(&radiosity) {
        println!(
            "{},{},{},{},{},{}",
            p.sensor.position.x,
            lux(p.irradiance()),
            error(p),
            lux(l.irradiance()),
            error(l),
            lux(h.irradiance())
        );
    }
    Ok(())
}
