//! A building without large files: `building:30` (30 furnished offices, 33,240 triangles,
//! enough for the near field by rays) solved by hierarchical radiosity at its defaults,
//! surface by surface and sensor by sensor against the light model.

use std::sync::Arc;
use strahl::light_model::LightTraceSettings;
use strahl::method::{
    AccelKind, Cancel, Method, NoProgress, Outcome, RadiositySettings, SolverKind, World, run,
};
use strahl::report::Report;
use strahl::scene::builtin;

/// `method` run on `building:30`.
fn solve(method: &Method) -> Outcome {
    let scene = builtin::load("building:30").unwrap().unwrap();
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    run(&world, method, &NoProgress, &Cancel::new()).unwrap()
}

#[test]
fn thirty_offices_by_hierarchical_radiosity_agree_with_the_light_model_surface_by_surface() {
    let radiosity = solve(&Method::Radiosity(RadiositySettings::new(
        SolverKind::Hierarchical,
    )));
    let light_model = solve(&Method::LightTrace(LightTraceSettings {
        photons: 4_000_000,
        ..LightTraceSettings::default()
    }));
    let solved = radiosity.radiosity.as_ref().unwrap();
    // The scene is large enough for the near field's rays, and they carry light.
    assert!(solved.system.mesh.roots.len() >= 10_000);
    assert!(solved.solution.near_links > 0);
    // Furniture stands on the floors and desk tops on their legs: faces overlap, but where
    // solids touch nothing is lit twice.
    let twice = solved.solution.light_counted_twice(&solved.system);
    assert!(
        twice.patches > 0 && twice.power < 1e-4 * twice.received,
        "{twice:?}"
    );
    let report = |o: &Outcome| Report::new("building", o.measurement.as_ref().unwrap());
    let (radiosity_report, reference) = (report(&radiosity), report(&light_model));
    assert_eq!(radiosity_report.objects.len(), 6);
    // Each surface within 1 % plus three of the reference's standard errors (measured:
    // −0.71 … +0.56 %, the reference's σ 0.08–0.23 % at 2·10⁶ photons).
    for (r, l) in radiosity_report.objects.iter().zip(&reference.objects) {
        let (got, expected) = (r.incident_power[1], l.incident_power[1]);
        let sigma = l.incident_power_standard_error.unwrap()[1] / expected;
        let deviation = got / expected - 1.0;
        assert!(
            deviation.abs() < 0.01 + 3.0 * sigma,
            "{}: {:+.2} % (σ {:.2} %)",
            r.name,
            100.0 * deviation,
            100.0 * sigma
        );
    }
    // Each office's sensor, 0.75 m above its floor (measured: −0.40 … +0.13 %).
    let sensors = &radiosity.measurement.as_ref().unwrap().sensors;
    let reference_sensors = &light_model.measurement.as_ref().unwrap().sensors;
    assert_eq!(sensors.len(), 30);
    for (r, l) in sensors.iter().zip(reference_sensors) {
        let (got, expected) = (r.irradiance()[1], l.irradiance()[1]);
        let sigma = l.standard_error.unwrap()[1] / expected;
        let deviation = got / expected - 1.0;
        assert!(
            deviation.abs() < 0.01 + 3.0 * sigma,
            "{}: {:+.2} % (σ {:.2} %)",
            r.sensor.name,
            100.0 * deviation,
            100.0 * sigma
        );
    }
}
