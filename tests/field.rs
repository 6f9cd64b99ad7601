//! A periodic field (a plot repeated without end in x and z) through the light model, against
//! Beer's law and closed forms.
//!
//! Beer's law: in a homogeneous canopy of leaf area index L whose leaves are placed
//! independently and face every way alike (spherical leaf angles, G = ½), the direct beam from
//! zenith angle θ reaches the ground with the fraction `exp(−G·L / cos θ)`, and the light of a
//! sky of uniform radiance with `2·∫₀¹ exp(−G·L/μ)·μ dμ`. With black leaves and a black
//! ground, the ground's incident power over what the light sends into the plot is that
//! fraction. The canopies here are the built-in field's (5 cm leaves, 3 m high, spherical
//! Fibonacci leaf angles) with 300,000 leaves: one plot of them is a draw of such a canopy
//! whose gap fraction differs from the expected one by about 0.3 % (measured over seeds), well
//! inside the 1 % the tests allow together with the photons' 3σ.

mod common;

use common::corner_leaf;
use glam::Vec3;
use std::sync::Arc;
use strahl::accel::AccelKind;
use strahl::color::Rgb;
use strahl::light_model::{LightTraceError, LightTraceSettings};
use strahl::measure::Film;
use strahl::method::{
    FinalGatherSettings, ImageSize, Method, MethodError, PathTraceSettings, RadiosityImageSettings,
    RadiositySettings, SensorTraceSettings, SolverKind, run,
};
use strahl::progress::{Cancel, NoProgress};
use strahl::report::Report;
use strahl::scene::builtin::field::{FieldSpec, field};
use strahl::scene::{
    CieSkyType, Light, LightKind, Material, Periodic, Scene, Sensor, Shape, load_str,
};
use strahl::validate::closed_forms::parallel_rectangle;
use strahl::world::{LightSet, World};

/// Leaves of the Beer's-law canopies.
const LEAVES: usize = 300_000;
/// Photons per light.
const PHOTONS: u64 = 1_000_000;

/// The field of `LEAVES` leaves at leaf area index `lai` with black leaves and ground.
fn black_field(lai: f32) -> Arc<World> {
    let mut scene = field(&FieldSpec {
        leaves: LEAVES,
        lai,
        ..FieldSpec::default()
    });
    for m in &mut scene.materials {
        *m = Material::diffuse(&m.name.clone(), Rgb::BLACK);
    }
    Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
}

/// The fraction of `light`'s power that the light model brings to the ground of `world` (its
/// lights replaced by `light`), and its standard error.
fn ground_fraction(world: &mut Arc<World>, light: LightKind) -> (f64, f64) {
    let w = Arc::get_mut(world).expect("one owner");
    w.scene.lights = vec![Light {
        name: None,
        kind: light.clone(),
    }];
    w.lights = LightSet::new(&w.scene, &w.geometry);
    let method = Method::LightTrace(LightTraceSettings {
        photons: PHOTONS,
        seed: 11,
        ..Default::default()
    });
    let outcome = run(world, &method, &NoProgress, &Cancel::new()).unwrap();
    let report = Report::new("field", outcome.measurement.as_ref().unwrap());
    let ground = report.objects.iter().find(|o| o.name == "ground").unwrap();
    let sent = f64::from(world.light_power(&light).g);
    let error = ground.incident_power_standard_error.unwrap().g;
    (ground.incident_power.g / sent, error / sent)
}

/// A sun of unit irradiance `zenith_degrees` from the zenith.
fn sun_at(zenith_degrees: f64) -> LightKind {
    let z = zenith_degrees.to_radians() as f32;
    LightKind::Directional {
        direction: -Vec3::new(z.sin(), z.cos(), 0.3 * z.sin()).normalize(),
        irradiance: Rgb::splat(1.0),
    }
}

/// `measured ± error` within 1 % of `expected` and within 3σ plus 0.5 % (the canopy's draw).
fn assert_close(what: &str, (measured, error): (f64, f64), expected: f64) {
    let off = (measured - expected).abs();
    assert!(
        off < 0.01 * expected && off < 3.0 * error + 0.005 * expected,
        "{what}: {measured:.5} ± {error:.5}, Beer's law {expected:.5} ({:+.2} %)",
        100.0 * (measured / expected - 1.0)
    );
}

/// 2·∫₀¹ exp(−G·L/μ)·μ dμ with G = ½: Simpson's rule on 2,000 intervals (the integrand is
/// smooth and vanishes at μ = 0).
fn uniform_sky_gap(lai: f64) -> f64 {
    let n = 2000;
    let f = |mu: f64| {
        if mu > 0.0 {
            (-0.5 * lai / mu).exp() * mu
        } else {
            0.0
        }
    };
    let sum: f64 = (0..=n)
        .map(|i| {
            let w = match i {
                0 => 1.0,
                i if i == n => 1.0,
                i if i % 2 == 1 => 4.0,
                _ => 2.0,
            };
            w * f(i as f64 / n as f64)
        })
        .sum();
    2.0 * sum / (3.0 * n as f64)
}

#[test]
fn the_sun_and_a_uniform_sky_reach_the_ground_as_beers_law_says() {
    for lai in [1.0, 2.0, 3.0] {
        let mut world = black_field(lai as f32);
        let zeniths: &[f64] = if lai == 1.0 {
            &[0.0, 30.0, 60.0]
        } else {
            &[0.0, 30.0]
        };
        for &zenith in zeniths {
            // The sun's direction as the scene holds it (in f32).
            let LightKind::Directional { direction, .. } = sun_at(zenith) else {
                unreachable!()
            };
            let beer = (-0.5 * lai / -f64::from(direction.y)).exp();
            let measured = ground_fraction(&mut world, sun_at(zenith));
            assert_close(&format!("LAI {lai}, sun {zenith}°"), measured, beer);
        }
        let sky = LightKind::CieSky {
            sky: CieSkyType::Uniform,
            sun: Vec3::Y,
            diffuse_horizontal: Rgb::splat(100.0),
        };
        let measured = ground_fraction(&mut world, sky);
        assert_close(&format!("LAI {lai}, sky"), measured, uniform_sky_gap(lai));
    }
}

#[test]
fn a_leaf_over_the_plots_corner_shades_as_much_as_one_inside_it() {
    let world = Arc::new(World::new(corner_leaf(), AccelKind::Bvh).unwrap());
    let method = Method::LightTrace(LightTraceSettings {
        photons: 400_000,
        seed: 5,
        ..Default::default()
    });
    let outcome = run(&world, &method, &NoProgress, &Cancel::new()).unwrap();
    let measurement = outcome.measurement.as_ref().unwrap();
    let report = Report::new("corner", measurement);
    let get = |name: &str| report.objects.iter().find(|o| o.name == name).unwrap();
    // The leaf's whole square catches 10 W (its four quarters through the four corners);
    // the ground the other 3 m² of the plot's 4: 30 W. Photons land on one or the other.
    let (leaf, ground) = (get("leaf"), get("ground"));
    let sigma = 40.0 * (0.25f64 * 0.75 / 400_000.0).sqrt();
    assert!(
        (leaf.incident_power.g - 10.0).abs() < 3.0 * sigma,
        "{:?}",
        leaf.incident_power
    );
    assert!((ground.incident_power.g - 30.0).abs() < 3.0 * sigma);
    let totals = measurement.power.totals();
    assert!((totals.emitted_power.g - 40.0).abs() < 1e-9, "{totals:?}");
    assert!((totals.absorbed_power.g - 40.0).abs() < 1e-9, "{totals:?}");
    // A uniform sky of radiance 1/π instead sends 4 W into the plot from above — 1 W onto the
    // leaf (the highest geometry), 3 W past it onto the ground — and 4 W from below onto the
    // ground's underside (the lowest geometry): leaf 1 W, ground 7 W.
    let mut scene = corner_leaf();
    scene.lights = vec![Light {
        name: None,
        kind: LightKind::Sky {
            radiance: Rgb::splat(std::f32::consts::FRAC_1_PI),
        },
    }];
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let outcome = run(&world, &method, &NoProgress, &Cancel::new()).unwrap();
    let report = Report::new("corner", outcome.measurement.as_ref().unwrap());
    let get = |name: &str| report.objects.iter().find(|o| o.name == name).unwrap();
    let sigma = 8.0 * (0.125f64 * 0.875 / 400_000.0).sqrt();
    let (leaf, ground) = (get("leaf"), get("ground"));
    assert!(
        (leaf.incident_power.g - 1.0).abs() < 3.0 * sigma,
        "{:?}",
        leaf.incident_power
    );
    assert!(
        (ground.incident_power.g - 7.0).abs() < 3.0 * sigma,
        "{:?}",
        ground.incident_power
    );
}

#[test]
fn a_translucent_field_conserves_energy() {
    let scene = field(&FieldSpec {
        leaves: 20_000,
        ..FieldSpec::default()
    });
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let method = Method::LightTrace(LightTraceSettings {
        photons: 200_000,
        seed: 2,
        ..Default::default()
    });
    let outcome = run(&world, &method, &NoProgress, &Cancel::new()).unwrap();
    let totals = outcome.measurement.as_ref().unwrap().power.totals();
    // What enters through the plot's top: 800 W·m⁻² on a surface facing the sun 30° from the
    // zenith, and 200 W·m⁻² of sky, over the plot.
    let plot = world.scene.periodic.unwrap();
    let sent = (800.0 * 30f64.to_radians().cos() + 200.0) * f64::from(plot.area());
    assert!(
        (totals.emitted_power.g / sent - 1.0).abs() < 5e-3,
        "{totals:?} vs {sent}"
    );
    let balance = totals.absorbed_power.g + totals.escaped_power.g;
    assert!(
        (balance / totals.emitted_power.g - 1.0).abs() < 1e-12,
        "{totals:?}"
    );
    // Leaves (ρ 0.1, τ 0.05) and soil (ρ 0.15) send back less than a fifth.
    let escaped = totals.escaped_power.g / totals.emitted_power.g;
    assert!(escaped > 0.02 && escaped < 0.2, "{escaped}");
}

/// The ray tracers read sensors of a periodic scene through every copy of the plot: sensors
/// on the corner-leaf plot's ground under a uniform sky (radiance 1) read the sun where no
/// copy of the leaf hides it, and `π·(1 − ΣF)` of sky, F the form factor from the sensor to
/// each copy of the leaf (Howell's closed form, summed over the copies within 40 periods).
/// A sensor's sky is a quadrature of 32 × 32 stratified directions, good to about 1 % over the
/// lattice's many edges: each of 16 sensors within 2.5 %, their mean within 0.5 %.
#[test]
fn sensors_under_the_copies_of_a_leaf_read_sun_and_sky_as_the_closed_form_says() {
    let mut scene = corner_leaf();
    scene.lights.push(Light {
        name: Some("sky".into()),
        kind: LightKind::Sky {
            radiance: Rgb::splat(1.0),
        },
    });
    let height = 0.001f32;
    let points: Vec<(f32, f32)> = (0..16)
        .map(|i| (0.1 + 0.5 * (i % 4) as f32, 0.15 + 0.5 * (i / 4) as f32))
        .collect();
    for (i, &(x, z)) in points.iter().enumerate() {
        scene.sensors.push(Sensor {
            name: format!("s{i}"),
            position: Vec3::new(x, height, z),
            normal: Vec3::Y,
        });
    }
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    for path_tracing in [false, true] {
        let method = Method::SensorTrace(SensorTraceSettings {
            samples: 1,
            paths: 1 << 12,
            path_tracing,
            seed: 3,
        });
        let outcome = run(&world, &method, &NoProgress, &Cancel::new()).unwrap();
        let mut sum = 0.0;
        for (reading, &(x, z)) in outcome.sensors().iter().zip(&points) {
            let under_leaf = |v: f32| !(0.5..1.5).contains(&v);
            let sun = if under_leaf(x) && under_leaf(z) {
                0.0
            } else {
                10.0
            };
            let (x, z, c) = (f64::from(x), f64::from(z), f64::from(1.0 - height));
            let mut blocked = 0.0;
            for i in -40..=40 {
                for k in -40..=40 {
                    let (cx, cz) = (f64::from(2 * i) - x, f64::from(2 * k) - z);
                    blocked += parallel_rectangle((cx - 0.5, cx + 0.5), (cz - 0.5, cz + 0.5), c);
                }
            }
            let sky = std::f64::consts::PI * (1.0 - blocked);
            // Black everywhere: nothing but sun and sky, and no noise.
            let off = (reading.irradiance().g - sun - sky) / sky;
            assert!(
                off.abs() < 0.025,
                "({x}, {z}), path tracing {path_tracing}: {off:+.4}"
            );
            sum += off;
        }
        let mean = sum / points.len() as f64;
        assert!(
            mean.abs() < 0.005,
            "path tracing {path_tracing}: mean {mean:+.4}"
        );
    }
}

/// A black square leaf of side `side` 1 m over the middle of a 1 m plot of grey ground
/// (ρ = 0.5), repeated without end, under a vertical sun of 100 W·m⁻².
fn leaf_over_grey_ground(side: f32) -> Arc<World> {
    let mut scene = Scene::empty("beyond");
    let black = scene.add_material(Material::diffuse("black", Rgb::BLACK));
    let grey = scene.add_material(Material::diffuse("grey", Rgb::splat(0.5)));
    let leaf = Shape::Parallelogram {
        origin: Vec3::new(0.5 - side / 2.0, 1.0, 0.5 - side / 2.0),
        edge_u: Vec3::X * side,
        edge_v: Vec3::Z * side,
    };
    scene.add_object("leaf", leaf, black);
    let ground = Shape::Parallelogram {
        origin: Vec3::ZERO,
        edge_u: Vec3::Z,
        edge_v: Vec3::X,
    };
    scene.add_object("ground", ground, grey);
    scene.periodic = Some(Periodic::new([0.0, 1.0], [0.0, 1.0]).unwrap());
    scene.lights.push(Light {
        name: Some("sun".into()),
        kind: LightKind::Directional {
            direction: -Vec3::Y,
            irradiance: Rgb::splat(100.0),
        },
    });
    Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
}

/// Asks `cancel` to stop when the phase `stop_at` starts, and records whether it did.
struct StopAt<'c> {
    cancel: &'c Cancel,
    stop_at: &'static str,
    seen: std::sync::atomic::AtomicBool,
}

impl strahl::progress::ProgressListener for StopAt<'_> {
    fn phase(&self, name: &str) {
        if name == self.stop_at {
            self.seen.store(true, std::sync::atomic::Ordering::Relaxed);
            self.cancel.request();
        }
    }
    fn start(&self, _: u64) {}
    fn advance(&self, _: u64) {}
    fn finish(&self) {}
}

/// Every radiosity solver says when it casts its far-field rays and, asked to stop then,
/// casts none and stops, reporting what it has as incomplete (the flat solvers' cast, part
/// of their system's setup, went on to the end before).
#[test]
fn every_radiosity_solver_stops_while_casting_its_far_field() {
    let world = leaf_over_grey_ground(0.05);
    for solver in [
        SolverKind::Hierarchical,
        SolverKind::HierarchicalShooting,
        SolverKind::Matrix,
        SolverKind::Progressive,
    ] {
        let cancel = Cancel::new();
        let listener = StopAt {
            cancel: &cancel,
            stop_at: "far-field rays",
            seen: false.into(),
        };
        let method = Method::Radiosity(RadiositySettings::new(solver));
        let outcome = run(&world, &method, &listener, &cancel).unwrap();
        assert!(listener.seen.into_inner(), "{solver:?}: no far-field phase");
        assert!(!outcome.complete, "{solver:?}: complete");
        let uncancelled = run(&world, &method, &NoProgress, &Cancel::new()).unwrap();
        let rays = |o: &strahl::method::Outcome| o.measurement.as_ref().unwrap().stats.rays;
        // The far field casts 16–1,024 rays a side, 2²¹ in all at most: at least 2,048 here.
        assert!(
            rays(&outcome) + 2048 <= rays(&uncancelled),
            "{solver:?}: {} rays stopped, {} not",
            rays(&outcome),
            rays(&uncancelled)
        );
    }
}

/// Radiosity takes the light the endless field reflects from beyond the plot: a black 5 cm
/// leaf 1 m over the middle of a 1 m plot of grey ground (ρ = 0.5) under a vertical sun of
/// 100 W·m⁻² sees the ground, of radiosity 50 W·m⁻² but in the shadows of the leaf and its
/// copies, under its whole lower hemisphere, three quarters of it beyond the plot. Its
/// underside receives `50·A·(1 − Σ F)`, the sum over the shadows below it and below its copies
/// of the form factor from its centre (closed form per shadow); every radiosity solver at its
/// default margin (none: all of the field beyond the plot comes by its far-field rays),
/// without the final gather at the surfaces, within 1 % (measured +0.49 % by the hierarchical
/// solvers, −0.15 % by matrix and progressive), the ground its sun less the leaf's shadow
/// within 0.2 % (the flat solvers' light links resolve the 5 cm shadow on their 8 × 8 points
/// of a ground patch: −0.14 %). Without the far field the underside took 24 % of its light,
/// and 88 % with a 1.5 m margin of copies.
#[test]
fn radiosity_takes_the_light_the_field_reflects_from_beyond_the_plot() {
    let side = 0.05;
    let world = leaf_over_grey_ground(side);
    let h = f64::from(side) / 2.0;
    let shadows: f64 = (-100..=100)
        .flat_map(|i| (-100..=100).map(move |k| (f64::from(i), f64::from(k))))
        .map(|(i, k)| parallel_rectangle((i - h, i + h), (k - h, k + h), 1.0))
        .sum();
    let area = f64::from(side * side);
    let underside = 50.0 * area * (1.0 - shadows);
    for solver in [
        SolverKind::Hierarchical,
        SolverKind::HierarchicalShooting,
        SolverKind::Matrix,
        SolverKind::Progressive,
    ] {
        let settings = RadiositySettings::new(solver).without_surface_gather();
        let method = Method::Radiosity(settings);
        let outcome = run(&world, &method, &NoProgress, &Cancel::new()).unwrap();
        let report = Report::new("beyond", outcome.measurement.as_ref().unwrap());
        let got = report.objects[0].incident_power.g - 100.0 * area;
        assert!(
            (got / underside - 1.0).abs() < 0.01,
            "{solver:?}: the leaf's underside {got} W vs {underside} W (shadows {shadows})"
        );
        let ground = report.objects[1].incident_power.g;
        assert!(
            (ground / (100.0 * (1.0 - area)) - 1.0).abs() < 2e-3,
            "{solver:?}: {ground}"
        );
    }
}

/// Radiosity solves a periodic scene on the plot and copies of it in a margin around it, its
/// light links traced through the endless field: the corner-leaf plot's black leaf catches
/// 10 W of the sun (all four quarters of it, through the plot's four corners) and the ground
/// the other 30 W, and sensors on the ground read the sun but under the leaf's copies; under a
/// uniform sky of radiance 1/π, 1 W and 7 W (3 W from above past the leaf, 4 W onto its
/// underside from below). The light links measure shadows on grids of points: each within
/// 0.5 %.
#[test]
fn radiosity_shades_a_plot_through_its_corner_as_the_closed_form_says() {
    for (light, leaf, ground) in [
        (corner_leaf().lights[0].kind.clone(), 10.0, 30.0),
        (
            LightKind::Sky {
                radiance: Rgb::splat(std::f32::consts::FRAC_1_PI),
            },
            1.0,
            7.0,
        ),
    ] {
        let mut scene = corner_leaf();
        let sun = matches!(light, LightKind::Directional { .. });
        scene.lights = vec![Light {
            name: None,
            kind: light,
        }];
        // Under the sun, sensors on the ground read 10 W·m⁻² but under a copy of the leaf.
        let sensors = [
            (1.0, 1.0, 10.0),
            (1.0, 0.25, 10.0),
            (0.25, 0.25, 0.0),
            (1.75, 0.25, 0.0),
        ];
        if sun {
            for &(x, z, _) in &sensors {
                scene.sensors.push(Sensor {
                    name: format!("({x}, {z})"),
                    position: Vec3::new(x, 0.0, z),
                    normal: Vec3::Y,
                });
            }
        }
        let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
        let radiosity = Method::Radiosity(RadiositySettings::default());
        let outcome = run(&world, &radiosity, &NoProgress, &Cancel::new()).unwrap();
        assert_eq!(outcome.sensors().len(), if sun { sensors.len() } else { 0 });
        for (reading, &(x, z, expected)) in outcome.sensors().iter().zip(&sensors) {
            let got = reading.irradiance().g;
            assert!(
                (got - expected).abs() < 1e-9,
                "({x}, {z}): {got} vs {expected}"
            );
        }
        let measurement = outcome.measurement.as_ref().unwrap();
        let report = Report::new("corner", measurement);
        // The plot's own objects only, not the copies around it.
        let names: Vec<&str> = report.objects.iter().map(|o| o.name.as_str()).collect();
        assert_eq!(names, ["leaf", "ground"]);
        for (name, expected) in [("leaf", leaf), ("ground", ground)] {
            let got = report.objects.iter().find(|o| o.name == name).unwrap();
            let off = got.incident_power.g / expected - 1.0;
            assert!(
                off.abs() < 5e-3,
                "{name}: {:?} vs {expected}",
                got.incident_power
            );
        }
        let totals = measurement.power.totals();
        assert!(
            (totals.emitted_power.g - (leaf + ground)).abs() < 1e-6,
            "{totals:?}"
        );
    }
}

/// A curved shape over the plot's corner: a black sphere of radius 0.5 centred over the corner
/// under the vertical sun, solved by radiosity on its facets. The light the plot takes in (40 W)
/// lands on the sphere's four quarters or on the ground, the shadow of each facet missing from
/// the ground what the facet catches (within 0.1 %), and the sphere catches the sun on its
/// disc, π·0.5²·10 W, less what its facets' outline lacks (within 2 %).
#[test]
fn radiosity_shades_a_plot_by_a_sphere_over_its_corner_as_its_facets_do() {
    let mut scene = corner_leaf();
    scene.objects[0].shape = Shape::Sphere {
        center: Vec3::new(0.0, 1.0, 0.0),
        radius: 0.5,
    };
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let radiosity = Method::Radiosity(RadiositySettings::default());
    let outcome = run(&world, &radiosity, &NoProgress, &Cancel::new()).unwrap();
    let report = Report::new("corner", outcome.measurement.as_ref().unwrap());
    let get = |name: &str| {
        report
            .objects
            .iter()
            .find(|o| o.name == name)
            .unwrap()
            .incident_power
            .g
    };
    let (sphere, ground) = (get("leaf"), get("ground"));
    assert!((sphere + ground - 40.0).abs() < 0.04, "{sphere} + {ground}");
    let disc = std::f64::consts::PI * 0.25 * 10.0;
    assert!((sphere / disc - 1.0).abs() < 0.02, "{sphere} vs {disc}");
}

/// A periodic field of grey spheres (radius 0.25 on a 1 m plot, centred on its corner) over
/// grey ground under a sun and a uniform sky, seen from above so that no sky is in view.
const SPHERES: &str = r#"
[camera]
position = [2.2, 1.6, 2.2]
look_at = [0.5, 0.0, 0.5]

[periodic]
x = [0.0, 1.0]
z = [0.0, 1.0]

[materials.grey]
diffuse = 0.5

[materials.ground]
diffuse = 0.3

[[objects]]
type = "sphere"
name = "ball"
material = "grey"
center = [0.0, 0.3, 0.0]
radius = 0.25

[[objects]]
type = "quad"
name = "ground"
material = "ground"
vertices = [[0, 0, 1], [1, 0, 1], [1, 0, 0], [0, 0, 0]]

[[lights]]
type = "directional"
direction = [-0.4, -0.8, -0.3]
irradiance = 100

[[lights]]
type = "sky"
radiance = 5
"#;

/// The radiosity images of a periodic field show the endless field as the path tracer does:
/// the radiosity solution looked up where camera rays meet the field (the patch under the
/// point met in any plot), and the final gather over it; the mean of each image against the
/// path tracer's (64 paths a pixel) within 3 % and 1 % — the leaves of the test field
/// (measured +0.16 % and +0.17 %) and a field of spheres, whose facets pass inside and outside
/// the spheres the periodic world meets (measured −2.2 %, the radiosity of flat facets shown
/// on a sphere, and +0.16 %). No pixel of the spheres'
/// radiosity image is black: before the search for the facet under the point met reached
/// before and past it, every facet showed a black spot where it bulges out, and the rims
/// black specks where the rays passed outside the facets.
#[test]
fn radiosity_images_show_the_endless_field_as_the_path_tracer_does() {
    let spheres = load_str(SPHERES, "spheres.toml", std::path::Path::new(".")).unwrap();
    let spheres = Arc::new(World::new(spheres, AccelKind::Bvh).unwrap());
    let size = ImageSize {
        width: Some(64),
        height: Some(48),
    };
    for world in [low_field(), spheres] {
        let image = |method: Method| {
            let outcome = run(&world, &method, &NoProgress, &Cancel::new()).unwrap();
            outcome.image.expect("an image")
        };
        let mean = |film: &Film| film.mean().to_f64().luminance();
        let path_traced = mean(&image(Method::PathTrace(PathTraceSettings {
            size,
            samples_per_pixel: 64,
            ..PathTraceSettings::default()
        })));
        let radiosity = image(Method::RadiosityImage(RadiosityImageSettings {
            size,
            ..RadiosityImageSettings::default()
        }));
        let gathered = mean(&image(Method::FinalGather(FinalGatherSettings {
            size,
            ..FinalGatherSettings::default()
        })));
        let name = &world.scene.name;
        let dark = radiosity
            .pixels()
            .iter()
            .filter(|p| p.to_f64().luminance() < 0.01 * mean(&radiosity))
            .count();
        let radiosity = mean(&radiosity);
        assert!(
            (radiosity / path_traced - 1.0).abs() < 0.03,
            "{name}: {radiosity} vs {path_traced}"
        );
        assert!(
            (gathered / path_traced - 1.0).abs() < 0.01,
            "{name}: {gathered} vs {path_traced}"
        );
        assert_eq!(dark, 0, "{name}: black pixels in the radiosity image");
    }
}

#[test]
fn lamps_under_the_ray_tracers_and_radiosity_and_the_light_models_sensors_are_refused() {
    let world = Arc::new(World::new(corner_leaf(), AccelKind::Bvh).unwrap());
    // The path tracer renders a field under sun and sky, but not one lit by a lamp (it would
    // miss the lamp's copies).
    let path_trace = Method::PathTrace(PathTraceSettings {
        size: ImageSize {
            width: Some(8),
            height: Some(8),
        },
        samples_per_pixel: 1,
        ..PathTraceSettings::default()
    });
    assert!(run(&world, &path_trace, &NoProgress, &Cancel::new()).is_ok());
    let mut lamp = corner_leaf();
    lamp.lights.push(Light {
        name: None,
        kind: LightKind::Point {
            position: Vec3::new(1.0, 2.0, 1.0),
            intensity: Rgb::splat(1.0),
        },
    });
    let lamp = Arc::new(World::new(lamp, AccelKind::Bvh).unwrap());
    let error = run(&lamp, &path_trace, &NoProgress, &Cancel::new())
        .err()
        .expect("refused");
    assert!(matches!(error, MethodError::PeriodicLamps(_)), "{error}");
    let radiosity = Method::Radiosity(RadiositySettings::default());
    let error = run(&lamp, &radiosity, &NoProgress, &Cancel::new())
        .err()
        .expect("refused");
    assert!(matches!(error, MethodError::PeriodicLamps(_)), "{error}");
    // The light model takes the lamp (its copies light every plot) but not sensors.
    let light_trace = Method::LightTrace(LightTraceSettings::default());
    assert!(run(&lamp, &light_trace, &NoProgress, &Cancel::new()).is_ok());
    let mut scene = corner_leaf();
    scene.sensors.push(Sensor {
        name: "meter".into(),
        position: Vec3::new(1.0, 0.5, 1.0),
        normal: Vec3::Y,
    });
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let error = run(&world, &light_trace, &NoProgress, &Cancel::new())
        .err()
        .expect("refused");
    assert!(matches!(
        error,
        MethodError::LightTrace(LightTraceError::PeriodicSensors)
    ));
}

/// A field low enough for the tests (1,000 leaves 1 m high at leaf area index 1: a plot
/// 1.58 m wide), under the built-in field's sun and CIE sky.
fn low_field() -> Arc<World> {
    let scene = field(&FieldSpec {
        leaves: 1000,
        height: 1.0,
        ..FieldSpec::default()
    });
    Arc::new(World::new(scene, AccelKind::Bvh).unwrap())
}

/// One reported surface's name, incident power, direct part of it (W, green) and the standard
/// error of the incident power (0 where not given).
type SurfaceRow = (String, f64, f64, f64);

/// What `method` measures on `world`, surface by surface; its energy balance checked.
fn surface_powers(world: &Arc<World>, method: &Method) -> Vec<SurfaceRow> {
    let outcome = run(world, method, &NoProgress, &Cancel::new()).unwrap();
    let power = &outcome.measurement.as_ref().unwrap().power;
    let totals = power.totals();
    let balance = totals.absorbed_power.g + totals.escaped_power.g;
    assert!(
        (balance / totals.emitted_power.g - 1.0).abs() < 1e-9,
        "{totals:?}"
    );
    (0..power.table().len())
        .map(|e| {
            let b = power.balance(e);
            let sigma = power.standard_error(e).map_or(0.0, |s| s.g);
            let name = power.table().surfaces()[e].name.clone();
            (name, b.incident.g, b.direct.expect("direct part").g, sigma)
        })
        .collect()
}

/// Hierarchical radiosity at its defaults on a periodic field against the light model
/// (4·10⁶ photons), the ground and all leaves together: the direct light (its light links,
/// traced through the endless field) within 0.5 % plus three standard errors (measured
/// +0.06 % and −0.07 %); all the light within 0.5 % (ground +0.08 %, leaves −0.25 %), what the
/// field beyond the plot reflects brought by the far-field rays (with a margin of copies and
/// no far field the leaves were −1.0 %).
#[test]
fn radiosity_lights_a_periodic_field_as_the_light_model_does() {
    let world = low_field();
    let light_model = Method::LightTrace(LightTraceSettings {
        photons: 4_000_000,
        seed: 4,
        ..Default::default()
    });
    let reference = surface_powers(&world, &light_model);
    let radiosity = surface_powers(&world, &Method::Radiosity(RadiositySettings::default()));
    let sum = |rows: &[SurfaceRow], ground: bool, part: fn(&SurfaceRow) -> f64| {
        rows.iter()
            .filter(|r| (r.0 == "ground") == ground)
            .map(part)
            .sum::<f64>()
    };
    for (ground, what) in [(true, "ground"), (false, "leaves")] {
        // Independent standard errors, surface by surface.
        let sigma = sum(&reference, ground, |r| r.3 * r.3).sqrt();
        let (got, expected) = (
            sum(&radiosity, ground, |r| r.1),
            sum(&reference, ground, |r| r.1),
        );
        assert!(
            (got - expected).abs() < 5e-3 * expected + 3.0 * sigma,
            "{what}: incident {got} vs {expected} ± {sigma}"
        );
        let (got, expected) = (
            sum(&radiosity, ground, |r| r.2),
            sum(&reference, ground, |r| r.2),
        );
        assert!(
            (got - expected).abs() < 5e-3 * expected + 3.0 * sigma,
            "{what}: direct {got} vs {expected} ± {sigma}"
        );
    }
}
