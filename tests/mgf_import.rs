//! MGF import against the built-in Cornell box: `tests/data/cornell.mgf`, which
//! `scripts/cornell-mgf.py` writes from the built-in `cornell` scene, opens with the same
//! objects, areas (within 10⁻⁴ relative), reflectances and emitted radiance (within the
//! script's colour round trip, 10⁻⁶ relative), and the light model at a fixed seed finds every
//! object absorbing the same power in both scenes within 1 %.

use std::collections::BTreeMap;
use std::sync::Arc;
use strahl::color::Rgb;
use strahl::method::{AccelKind, Cancel, LightTraceSettings, Method, NoProgress, World, run};
use strahl::report::Report;
use strahl::scene::{LoadOptions, Scene, builtin, open, polygon_area};

/// Relative tolerance of the areas.
const AREA_TOLERANCE: f64 = 1e-4;

/// Relative tolerance of the colours: the round trip `scripts/cornell-mgf.py --check` states.
const COLOR_TOLERANCE: f32 = 1e-6;

/// Photons per light-model run. One run's standard error is 0.08–0.5 % per object (the light
/// fixture's the largest); at the same seed the two runs follow the same photons through the
/// same faces (the MGF gives the published vertices to their 0.1 mm) and agree to about
/// 10⁻⁵, far within the 1 %.
const PHOTONS: u64 = 4_000_000;

fn scenes() -> (Scene, Scene) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/cornell.mgf");
    let mgf = open(path, &LoadOptions::default()).unwrap();
    let built_in = builtin::load("cornell").unwrap().unwrap();
    (mgf, built_in)
}

/// Per object: its area (m²), reflectance and emitted radiance.
fn objects(scene: &Scene) -> BTreeMap<String, (f64, Rgb, Rgb)> {
    scene
        .objects
        .iter()
        .enumerate()
        .map(|(i, o)| {
            let mesh = o.shape.to_mesh(3).unwrap();
            let area = mesh
                .faces()
                .map(|f| {
                    let corners: Vec<_> = f.iter().map(|&k| mesh.positions[k as usize]).collect();
                    f64::from(polygon_area(&corners))
                })
                .sum();
            let material = &scene.materials[o.material as usize];
            (
                scene.object_name(i),
                (area, material.diffuse, material.emission),
            )
        })
        .collect()
}

/// The luminous efficacy `scripts/cornell-mgf.py` writes the lamp's emittance at (RenderPark's,
/// lm/W): strahl reads lumens at 683 lm/W, so the file's lamp is 183.07/683 of the built-in
/// one's radiance, and every power in proportion.
const FILE_EFFICACY: f64 = 183.07;

/// What strahl reads of the file per W of the built-in scene.
fn file_scale() -> f64 {
    FILE_EFFICACY / strahl::color::LUMINOUS_EFFICACY
}

fn close(got: Rgb, want: Rgb) -> bool {
    (0..3).all(|c| (got[c] - want[c]).abs() <= COLOR_TOLERANCE * want[c].abs())
}

#[test]
fn the_cornell_mgf_opens_as_the_built_in_box() {
    let (mgf, built_in) = scenes();
    let names = |s: &Scene| {
        (0..s.objects.len())
            .map(|i| s.object_name(i))
            .collect::<Vec<_>>()
    };
    assert_eq!(names(&mgf), names(&built_in));
    let (got, want) = (objects(&mgf), objects(&built_in));
    for (name, (area, diffuse, emission)) in &want {
        let (a, d, e) = got[name];
        assert!(
            (a - area).abs() <= AREA_TOLERANCE * area,
            "{name}: area {a} vs {area}"
        );
        assert!(
            close(d, *diffuse),
            "{name}: reflectance {d:?} vs {diffuse:?}"
        );
        let emission = *emission * file_scale() as f32;
        assert!(close(e, emission), "{name}: emission {e:?} vs {emission:?}");
    }
    // One-sided surfaces, each material once.
    assert_eq!(mgf.materials.len(), 4);
    assert!(mgf.materials.iter().all(|m| m.one_sided && !m.two_sided));
}

/// Per object: the absorbed power (W per channel) the light model finds, and the relative
/// standard error of its incident power.
fn absorbed(scene: Scene) -> BTreeMap<String, ([f64; 3], [f64; 3])> {
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let method = Method::LightTrace(LightTraceSettings {
        photons: PHOTONS,
        seed: 11,
        ..LightTraceSettings::default()
    });
    let outcome = run(&world, &method, &NoProgress, &Cancel::new()).unwrap();
    let report = Report::new("cornell", outcome.measurement.as_ref().unwrap());
    report
        .objects
        .iter()
        .map(|o| {
            let incident = o.incident_power.to_array();
            let error = o.incident_power_standard_error.unwrap().to_array();
            let relative = std::array::from_fn(|c| error[c] / incident[c]);
            (o.name.clone(), (o.absorbed_power.to_array(), relative))
        })
        .collect()
}

#[test]
fn the_light_model_finds_the_same_absorbed_power_in_both() {
    let (mgf, built_in) = scenes();
    let (got, want) = (absorbed(mgf), absorbed(built_in));
    assert_eq!(got.len(), want.len());
    for (name, (power, relative_error)) in &want {
        let (p, e) = got[name];
        for c in 0..3 {
            let deviation = p[c] / (power[c] * file_scale()) - 1.0;
            assert!(
                deviation.abs() < 0.01,
                "{name} channel {c}: {} W vs {} W ({:+.3} %, standard errors {:.3} % and {:.3} %)",
                p[c],
                power[c],
                100.0 * deviation,
                100.0 * e[c],
                100.0 * relative_error[c]
            );
        }
    }
}
