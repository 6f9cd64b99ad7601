//! Embedding strahl in a program: a room built in code (no file), solved by hierarchical
//! radiosity and by the light model, the power each object absorbs and a sensor's
//! illuminance read from both, and a path-traced image rendered to memory — all through
//! the library's method API ([`strahl::method`]). The light model runs on a thread of its
//! own while radiosity solves: results are owned values that cross threads.
//!
//! Run: `cargo run --release --example embed`.

use glam::Vec3;
use std::sync::Arc;
use strahl::accel::AccelKind;
use strahl::color::Rgb;
use strahl::light_model::LightTraceSettings;
use strahl::method::{ImageSize, Method, MethodKind, Outcome, PathTraceSettings, run};
use strahl::progress::{Cancel, NoProgress};
use strahl::radiosity::solve::SolverKind;
use strahl::report::Report;
use strahl::scene::{Material, Scene, Sensor, Shape};
use strahl::world::World;

/// A 4 m × 4 m grey floor lit by a 1 m² lamp 2 m above it (radiance 20 W·sr⁻¹·m⁻²,
/// facing down), a red box standing on the floor, a sensor on the floor beside the box.
fn room() -> Scene {
    let mut scene = Scene::empty("room");
    let material = |name: &str, diffuse: Rgb, emission: Rgb| Material {
        name: name.to_string(),
        diffuse,
        emission,
        ..Material::default()
    };
    let grey = scene.add_material(material("grey", Rgb::splat(0.5), Rgb::BLACK));
    let red = scene.add_material(material("red", Rgb::new(0.6, 0.1, 0.1), Rgb::BLACK));
    let lamp = scene.add_material(material("lamp", Rgb::BLACK, Rgb::splat(20.0)));
    // A parallelogram's front side is the side edge_u × edge_v points to.
    let floor = Shape::Parallelogram {
        origin: Vec3::new(-2.0, 0.0, -2.0),
        edge_u: Vec3::new(0.0, 0.0, 4.0),
        edge_v: Vec3::new(4.0, 0.0, 0.0),
    };
    let panel = Shape::Parallelogram {
        origin: Vec3::new(-0.5, 2.0, -0.5),
        edge_u: Vec3::new(1.0, 0.0, 0.0),
        edge_v: Vec3::new(0.0, 0.0, 1.0),
    };
    let block = Shape::Box {
        min: Vec3::new(-1.2, 0.0, -0.4),
        max: Vec3::new(-0.6, 0.6, 0.2),
    };
    scene.add_object("floor", floor, grey);
    scene.add_object("lamp", panel, lamp);
    scene.add_object("box", block, red);
    scene.sensors.push(Sensor {
        name: "meter".to_string(),
        position: Vec3::new(0.8, 0.0, 0.5),
        normal: Vec3::Y,
    });
    scene.camera.position = Vec3::new(0.0, 1.6, 4.5);
    scene.camera.look_at = Vec3::new(0.0, 0.3, 0.0);
    scene.camera.fov_degrees = 50.0;
    scene
}

/// Prints the power each object absorbs and the sensor's illuminance; returns the report.
fn print(outcome: &Outcome) -> Result<Report, Box<dyn std::error::Error>> {
    let measured = outcome.measurement.as_ref().ok_or("no surfaces measured")?;
    let report = Report::new("room", measured);
    for object in &report.objects {
        println!(
            "{:>14} {:6}: absorbed {:7.3} W",
            report.solver,
            object.name,
            object.absorbed_power.luminance()
        );
    }
    for sensor in &report.sensors {
        println!(
            "{:>14} {:6}: {:7.2} lux",
            report.solver, sensor.name, sensor.illuminance_lux
        );
    }
    Ok(report)
}

/// The luminance of the power `object` absorbs, W.
fn absorbed(report: &Report, object: &str) -> f64 {
    report
        .objects
        .iter()
        .find(|o| o.name == object)
        .map_or(f64::NAN, |o| o.absorbed_power.luminance())
}

/// Relative difference of `a` from `b`.
fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let world = Arc::new(World::new(room(), AccelKind::Bvh)?);

    // The light model on a thread of its own; a Cancel shared with it could stop it early.
    let cancel = Arc::new(Cancel::new());
    let photons = Method::LightTrace(LightTraceSettings {
        photons: 200_000,
        ..LightTraceSettings::default()
    });
    let light_model = {
        let (world, cancel) = (Arc::clone(&world), Arc::clone(&cancel));
        std::thread::spawn(move || run(&world, &photons, &NoProgress, &cancel))
    };

    let mut hierarchical = MethodKind::Radiosity(SolverKind::Hierarchical).with_defaults();
    if let Method::Radiosity(settings) = &mut hierarchical {
        settings.hierarchical.error = 1e-3;
    }
    let radiosity = print(&run(&world, &hierarchical, &NoProgress, &Cancel::new())?)?;
    let light_model = light_model
        .join()
        .map_err(|_| "the light model panicked")??;
    let light_model = print(&light_model)?;
    // Two independent methods agree on the lit surfaces and the sensor (the light model's
    // standard error at 2·10⁵ photons is below 0.5 % for these).
    for object in ["floor", "box"] {
        let difference = relative(absorbed(&radiosity, object), absorbed(&light_model, object));
        assert!(difference < 0.03, "{object}: {difference}");
    }
    let lux = |r: &Report| r.sensors[0].illuminance_lux;
    assert!(relative(lux(&radiosity), lux(&light_model)) < 0.03);

    let image = Method::PathTrace(PathTraceSettings {
        size: ImageSize {
            width: Some(48),
            height: Some(32),
        },
        samples_per_pixel: 16,
        ..PathTraceSettings::default()
    });
    let rendered = run(&world, &image, &NoProgress, &Cancel::new())?;
    let film = rendered.image.ok_or("no image rendered")?;
    let mean =
        film.pixels().iter().map(|p| p.luminance()).sum::<f32>() / film.pixels().len() as f32;
    println!(
        "path tracer: {}×{} image, mean luminance {mean:.4} W·sr⁻¹·m⁻² ({})",
        film.width(),
        film.height(),
        rendered.summary
    );
    assert!(mean > 0.0, "the lit room renders black");
    Ok(())
}
