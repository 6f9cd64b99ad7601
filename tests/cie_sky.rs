//! The CIE standard skies and the sun by date and place, through every method.
//!
//! An open horizontal black plate under a CIE sky receives exactly the diffuse horizontal
//! irradiance: the light model within 3σ and 1 %, hierarchical and matrix radiosity within
//! 1 %, a sensor on it read by the direct tracer exactly and by the path tracer within 3σ.
//! Vertical sensors facing the sun and facing away read what an independent fine quadrature
//! of `CieSky::radiance` over their visible half of the upper hemisphere gives. A sun given by
//! date, time and place in a scene file points where `sun_position` says, and a sensor facing
//! it reads the directional light's irradiance.

use glam::{DVec3, Vec3};
use std::path::Path;
use std::sync::Arc;
use strahl::accel::AccelKind;
use strahl::color::{Rgb, Rgb64};
use strahl::light_model::LightTraceSettings;
use strahl::method::{Method, RadiositySettings, SensorTraceSettings, run};
use strahl::progress::{Cancel, NoProgress};
use strahl::radiosity::solve::SolverKind;
use strahl::report::Report;
use strahl::scene::{Light, LightKind, Material, Scene, Sensor, Shape};
use strahl::sky::{CieSky, CieSkyType, LocalTime, Observer, direction_from_angles, sun_position};
use strahl::world::World;

/// Diffuse horizontal irradiance, W·m⁻² (green; red and blue are scaled).
const DIFFUSE: f64 = 120.0;
/// The sun's azimuth, degrees clockwise from north.
const AZIMUTH: f64 = 150.0;

/// Sky types 1 (overcast), 7 (partly cloudy) and 12 (clear), sun at 30° and 60° elevation.
fn cases() -> Vec<(CieSkyType, f64)> {
    let types = [
        CieSkyType::OvercastSteep,
        CieSkyType::PartlyCloudyCircumsolar,
        CieSkyType::ClearLowTurbidity,
    ];
    types
        .iter()
        .flat_map(|&t| [30.0, 60.0].map(|elevation| (t, elevation)))
        .collect()
}

fn sun(elevation: f64) -> DVec3 {
    direction_from_angles(90.0 - elevation, AZIMUTH)
}

/// A black 1 m² horizontal plate at the origin under the CIE sky, with a sensor on it and
/// sensors at 3 m facing the sun's azimuth and facing away, horizontal normals.
fn plate_under(sky: CieSkyType, elevation: f64) -> Arc<World> {
    let mut scene = Scene::empty("plate under a CIE sky");
    let black = scene.add_material(Material::diffuse("black", Rgb::BLACK));
    scene.add_object(
        "plate",
        Shape::Parallelogram {
            origin: Vec3::new(-0.5, 0.0, 0.5),
            edge_u: Vec3::X,
            edge_v: Vec3::NEG_Z,
        },
        black,
    );
    scene.lights.push(Light {
        name: None,
        kind: LightKind::CieSky {
            sky,
            sun: sun(elevation).as_vec3(),
            diffuse_horizontal: Rgb::new(2.0, 1.0, 0.5) * DIFFUSE as f32,
        },
    });
    let toward = facing_sun(elevation);
    for (name, position, normal) in [
        ("up", Vec3::ZERO, Vec3::Y),
        ("toward", Vec3::new(3.0, 0.5, 0.0), toward),
        ("away", Vec3::new(3.0, 0.5, 0.0), -toward),
    ] {
        scene.sensors.push(Sensor {
            name: name.into(),
            position,
            normal,
        });
    }
    Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
}

/// The horizontal unit normal facing the sun's azimuth.
fn facing_sun(elevation: f64) -> Vec3 {
    let s = sun(elevation);
    Vec3::new(s.x as f32, 0.0, s.z as f32).normalize()
}

/// `∫ L(ω)·max(0, n·ω) dω` over the upper hemisphere (green channel) by a 600 × 1200 midpoint
/// rule in (θ, φ), independent of the library's quadrature.
fn quadrature(sky: CieSkyType, elevation: f64, normal: DVec3) -> f64 {
    let sky = CieSky::standard(sky, sun(elevation), DIFFUSE);
    let (rows, columns) = (600, 1200);
    let (dt, dp) = (
        std::f64::consts::FRAC_PI_2 / rows as f64,
        std::f64::consts::TAU / columns as f64,
    );
    let mut sum = 0.0;
    for i in 0..rows {
        let (sin, cos) = ((i as f64 + 0.5) * dt).sin_cos();
        for j in 0..columns {
            let phi = (j as f64 + 0.5) * dp;
            let d = DVec3::new(sin * phi.sin(), cos, -sin * phi.cos());
            sum += sky.radiance(d) * normal.dot(d).max(0.0) * sin;
        }
    }
    sum * dt * dp
}

fn measure(world: &Arc<World>, method: Method) -> strahl::method::Outcome {
    run(world, &method, &NoProgress, &Cancel::new()).unwrap()
}

/// Plate incident power (green) and its standard error, W, of a method's measurement.
fn plate_power(outcome: &strahl::method::Outcome) -> (f64, f64) {
    let report = Report::new("plate", outcome.measurement.as_ref().unwrap());
    let plate = report.objects.iter().find(|o| o.name == "plate").unwrap();
    let error = plate.incident_power_standard_error.map_or(0.0, |e| e.g);
    (plate.incident_power.g, error)
}

#[test]
fn the_light_model_gives_the_plate_the_diffuse_horizontal_irradiance() {
    for (sky, elevation) in cases() {
        let world = plate_under(sky, elevation);
        let method = Method::LightTrace(LightTraceSettings {
            photons: 400_000,
            seed: 7,
            ..Default::default()
        });
        let (power, error) = plate_power(&measure(&world, method));
        let deviation = (power - DIFFUSE).abs();
        eprintln!(
            "light model {sky:?} {elevation}°: {power:.4} ± {error:.4} W ({:+.3} %)",
            100.0 * (power / DIFFUSE - 1.0)
        );
        assert!(deviation < 3.0 * error && deviation < 0.01 * DIFFUSE);
    }
}

#[test]
fn radiosity_gives_the_plate_the_diffuse_horizontal_irradiance() {
    for solver in [SolverKind::Hierarchical, SolverKind::Matrix] {
        for (sky, elevation) in cases() {
            let world = plate_under(sky, elevation);
            let (power, _) = plate_power(&measure(
                &world,
                Method::Radiosity(RadiositySettings::new(solver)),
            ));
            eprintln!(
                "{solver:?} {sky:?} {elevation}°: {power:.6} W ({:+.2e})",
                power / DIFFUSE - 1.0
            );
            assert!((power - DIFFUSE).abs() < 0.01 * DIFFUSE);
        }
    }
}

/// A black 1 m² vertical plate facing the sun's azimuth, alone under the CIE sky, takes on its
/// two sides what a fine quadrature of the sky gives either normal, by radiosity: its light
/// links' points have one sky direction each, half of them under the horizon (where the sky is
/// black), and must not count as shadowed (they read 50 % too little before).
#[test]
fn radiosity_gives_a_vertical_plate_what_the_sky_sends_either_side() {
    for (sky, elevation) in cases() {
        let mut scene = plate_under(sky, elevation).scene.clone();
        let toward = facing_sun(elevation);
        let (u, _) = toward.any_orthonormal_pair();
        scene.objects[0].shape = Shape::Parallelogram {
            origin: -0.5 * (u + Vec3::Y),
            edge_u: u,
            edge_v: Vec3::Y,
        };
        let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
        let expected = quadrature(sky, elevation, toward.as_dvec3())
            + quadrature(sky, elevation, -toward.as_dvec3());
        let (power, _) = plate_power(&measure(
            &world,
            Method::Radiosity(RadiositySettings::default()),
        ));
        eprintln!(
            "vertical plate {sky:?} {elevation}°: {power:.4} W against {expected:.4} ({:+.2} %)",
            100.0 * (power / expected - 1.0)
        );
        assert!((power / expected - 1.0).abs() < 0.01);
    }
}

/// The sensors' readings (green) and standard errors by the direct or the path tracer.
fn sensors(world: &Arc<World>, path_tracing: bool) -> Vec<(f64, f64)> {
    let method = Method::SensorTrace(SensorTraceSettings {
        samples: 16,
        paths: 1 << 16,
        path_tracing,
        seed: 3,
    });
    measure(world, method)
        .sensor_readings
        .iter()
        .map(|r| {
            let e = r.standard_error.unwrap_or(Rgb64::BLACK).g;
            (r.irradiance().g, e)
        })
        .collect()
}

#[test]
fn sensors_read_the_sky_as_a_fine_quadrature_does_by_both_tracers() {
    for (sky, elevation) in cases() {
        let world = plate_under(sky, elevation);
        let toward = facing_sun(elevation).as_dvec3();
        let expected = [
            DIFFUSE,
            quadrature(sky, elevation, toward),
            quadrature(sky, elevation, -toward),
        ];
        let (direct, path) = (sensors(&world, false), sensors(&world, true));
        for (k, name) in ["up", "toward", "away"].iter().enumerate() {
            let ((d, _), (p, pe)) = (direct[k], path[k]);
            eprintln!(
                "{sky:?} {elevation}° {name}: quadrature {:.4}, direct {d:.4}, path {p:.4} ± {pe:.4}",
                expected[k]
            );
            // The library's 90 × 180 quadrature against 600 × 1200 points.
            assert!((d - expected[k]).abs() < 2e-3 * expected[k]);
            // Both read the sky at a sensor by the same stratified directions
            // (`non_surface_irradiance`): σ is 0 here and the readings exact.
            assert!((p - expected[k]).abs() <= 3.0 * pe + 2e-3 * expected[k]);
            assert!(pe < 0.02 * expected[k]);
        }
    }
}

/// NREL's example (Reda & Andreas 2004, table A5.1).
fn nrel() -> (LocalTime, Observer) {
    (
        LocalTime {
            year: 2003,
            month: 10,
            day: 17,
            hour: 12,
            minute: 30,
            second: 30.0,
            utc_offset_hours: -7.0,
            delta_ut1_s: 0.0,
            delta_t_s: 67.0,
        },
        Observer {
            latitude_deg: 39.742476,
            longitude_deg: -105.1786,
            elevation_m: 1830.14,
            pressure_mbar: 820.0,
            temperature_c: 11.0,
            refraction_deg: 0.5667,
        },
    )
}

#[test]
fn a_sun_by_date_and_place_points_where_the_algorithm_says_and_lights_a_plate_facing_it() {
    let (time, observer) = nrel();
    let toward = sun_position(&time, &observer).direction();
    let text = format!(
        r#"
[[objects]]
type = "parallelogram"
material = "black"
origin = [0, -1, 0]
edge_u = [1, 0, 0]
edge_v = [0, 0, -1]

[materials.black]
diffuse = [0, 0, 0]

[[lights]]
type = "directional"
irradiance = [500, 500, 500]
date = "2003-10-17"
time = "12:30:30"
utc_offset_hours = -7
latitude_deg = 39.742476
longitude_deg = -105.1786
elevation_m = 1830.14
pressure_mbar = 820
temperature_c = 11
delta_t_s = 67

[[lights]]
type = "cie_sky"
sky_type = 12
diffuse_horizontal = [0, 0, 0]
date = "2003-10-17"
time = "12:30:30"
utc_offset_hours = -7
latitude_deg = 39.742476
longitude_deg = -105.1786
elevation_m = 1830.14
pressure_mbar = 820
temperature_c = 11
delta_t_s = 67

[[sensors]]
name = "facing"
position = [5, 0, 0]
normal = [{}, {}, {}]
"#,
        toward.x, toward.y, toward.z
    );
    let scene = strahl::scene::load_str(&text, "nrel.toml", Path::new(".")).unwrap();
    let LightKind::Directional { direction, .. } = scene.lights[0].kind else {
        panic!("a directional light");
    };
    let LightKind::CieSky { sun, .. } = scene.lights[1].kind else {
        panic!("a CIE sky");
    };
    for d in [-direction, sun] {
        let angle = d.as_dvec3().angle_between(toward).to_degrees();
        assert!(angle < 1e-4, "{angle}°");
    }
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let (e, _) = sensors(&world, false)[0];
    assert!((e - 500.0).abs() < 1e-3, "{e}");
}

#[test]
fn a_sun_below_the_horizon_is_refused_at_its_time() {
    let text = r#"
[[lights]]
type = "directional"
irradiance = [500, 500, 500]
date = "2003-10-17"
time = "23:30"
utc_offset_hours = -7
latitude_deg = 39.7
longitude_deg = -105.2
"#;
    let error = strahl::scene::load_str(text, "night.toml", Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("night.toml:6") && error.contains("lights[0].time"),
        "{error}"
    );
    assert!(error.contains("below the horizon"), "{error}");
}
