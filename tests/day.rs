//! A `day` light: the sun and a CIE sky at several clock times of one date and place, solved
//! at once as their mean. The lights are those of each state with 1/n of its irradiance, the
//! sun where NREL's algorithm puts it; an open black plate receives the mean over the states
//! of `DN·cos z + DH` (direct normal irradiance on the horizontal, plus the diffuse horizontal
//! irradiance), the light model within 3σ and 1 %, in one run of the photons one state takes.

use std::path::Path;
use std::sync::Arc;
use strahl::accel::AccelKind;
use strahl::light_model::LightTraceSettings;
use strahl::method::{Method, RadiositySettings, SolverKind, run, run_with_parts};
use strahl::progress::{Cancel, NoProgress};
use strahl::report::Report;
use strahl::scene::{
    DEFAULT_DELTA_T_S, LightKind, LocalTime, Observer, STANDARD_PRESSURE_MBAR,
    STANDARD_TEMPERATURE_C, SUNRISE_REFRACTION_DEG, load_str, sun_position,
};
use strahl::world::World;

/// Berlin on the summer solstice: a night state, morning, noon and afternoon.
const STATES: [(&str, f64, f64); 4] = [
    ("02:30", 0.0, 0.0),
    ("09:00", 500.0, 100.0),
    ("13:15", 800.0, 150.0),
    ("17:30", 300.0, 80.0),
];

fn scene_text() -> String {
    let states: Vec<String> = STATES
        .iter()
        .map(|(time, dn, dh)| {
            format!("  {{ time = \"{time}\", direct_normal = {dn}, diffuse_horizontal = {dh} }},")
        })
        .collect();
    format!(
        r#"
[materials.black]
diffuse = 0

[[objects]]
type = "parallelogram"
name = "plate"
material = "black"
origin = [-0.5, 0, 0.5]
edge_u = [1, 0, 0]
edge_v = [0, 0, -1]

[[lights]]
type = "day"
name = "solstice"
sky_type = 12
date = "2026-06-21"
utc_offset_hours = 2
latitude_deg = 52.52
longitude_deg = 13.40
states = [
{}
]
"#,
        states.join("\n")
    )
}

/// The unit direction toward the sun and the cosine of its zenith angle at `time` (HH:MM).
fn sun(time: &str) -> (glam::DVec3, f64) {
    let (hour, minute) = time.split_once(':').unwrap();
    let local = LocalTime {
        year: 2026,
        month: 6,
        day: 21,
        hour: hour.parse().unwrap(),
        minute: minute.parse().unwrap(),
        second: 0.0,
        utc_offset_hours: 2.0,
        delta_ut1_s: 0.0,
        delta_t_s: DEFAULT_DELTA_T_S,
    };
    let observer = Observer {
        latitude_deg: 52.52,
        longitude_deg: 13.40,
        elevation_m: 0.0,
        pressure_mbar: STANDARD_PRESSURE_MBAR,
        temperature_c: STANDARD_TEMPERATURE_C,
        refraction_deg: SUNRISE_REFRACTION_DEG,
    };
    let p = sun_position(&local, &observer);
    (p.direction(), p.zenith_deg.to_radians().cos())
}

#[test]
fn a_day_is_the_mean_of_its_states_suns_and_skies() {
    let scene = load_str(&scene_text(), "day.toml", Path::new(".")).unwrap();
    // The night state adds no light; the other three a sun and a sky each, at a quarter.
    assert_eq!(scene.lights.len(), 6);
    for (k, (time, dn, dh)) in STATES[1..].iter().enumerate() {
        let (toward, _) = sun(time);
        let sun_light = &scene.lights[2 * k];
        assert_eq!(
            sun_light.name.as_deref(),
            Some(&*format!("solstice {time} sun"))
        );
        let LightKind::Directional {
            direction,
            irradiance,
        } = sun_light.kind
        else {
            panic!("{sun_light:?}")
        };
        assert!((direction.as_dvec3() + toward).length() < 1e-6, "{time}");
        assert!((f64::from(irradiance.g) - dn / 4.0).abs() < 1e-4);
        let LightKind::CieSky {
            diffuse_horizontal, ..
        } = scene.lights[2 * k + 1].kind
        else {
            panic!()
        };
        assert!((f64::from(diffuse_horizontal.g) - dh / 4.0).abs() < 1e-4);
    }
    let expected: f64 = STATES
        .iter()
        .map(|(time, dn, dh)| {
            let (_, cos_z) = sun(time);
            if cos_z > 0.0 { dn * cos_z + dh } else { 0.0 }
        })
        .sum::<f64>()
        / STATES.len() as f64;
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let method = Method::LightTrace(LightTraceSettings {
        photons: 400_000,
        seed: 4,
        ..Default::default()
    });
    let outcome = run(&world, &method, &NoProgress, &Cancel::new()).unwrap();
    let report = Report::new("day", outcome.measurement.as_ref().unwrap());
    let plate = &report.objects[0];
    let (got, sigma) = (
        plate.incident_power.g,
        plate.incident_power_standard_error.unwrap().g,
    );
    assert!(
        (got - expected).abs() < 3.0 * sigma && (got - expected).abs() < 0.01 * expected,
        "{got} ± {sigma} vs {expected}"
    );
}

/// Each state alone, as `run_with_parts` reports it: the open black plate receives the state's
/// `DN·cos z + DH` (none at night) — matrix radiosity to 10⁻⁴, the light model, tracing the
/// day and its four states along one set of photon paths, within 3σ, σ under 1 % — and the states'
/// mean is the day's figure (to 10⁻⁶ for the deterministic solver: the solve is linear in
/// the lights).
#[test]
fn each_state_of_a_day_is_reported_alone() {
    let scene = load_str(&scene_text(), "day.toml", Path::new(".")).unwrap();
    let day = scene.day.as_ref().unwrap();
    let times: Vec<&str> = day.states.iter().map(|s| s.time.as_str()).collect();
    assert_eq!(times, ["02:30", "09:00", "13:15", "17:30"]);
    assert!(day.states[0].lights.is_empty());
    assert_eq!(day.states[2].lights, [2, 3]);
    let expected: Vec<f64> = STATES
        .iter()
        .map(|(time, dn, dh)| {
            let (_, cos_z) = sun(time);
            if cos_z > 0.0 { dn * cos_z + dh } else { 0.0 }
        })
        .collect();
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let matrix = Method::Radiosity(RadiositySettings::new(SolverKind::Matrix));
    let photons = Method::LightTrace(LightTraceSettings {
        photons: 400_000,
        seed: 5,
        ..Default::default()
    });
    for method in [matrix, photons] {
        let (outcome, parts) =
            run_with_parts(&world, &method, &NoProgress, &Cancel::new()).unwrap();
        let report =
            Report::new("day", outcome.measurement.as_ref().unwrap()).with_states(&parts.states);
        assert_eq!(report.states.len(), 4);
        let mut sum = 0.0;
        for (state, expected) in report.states.iter().zip(&expected) {
            let plate = &state.objects[0];
            let got = plate.incident_power.g;
            sum += got;
            match plate.incident_power_standard_error {
                None => assert!(
                    (got - expected).abs() <= 1e-4 * expected,
                    "{}: {got} vs {expected}",
                    state.time
                ),
                Some(sigma) => assert!(
                    (got - expected).abs() <= 3.0 * sigma.g && sigma.g <= 0.01 * expected,
                    "{}: {got} ± {} vs {expected}",
                    state.time,
                    sigma.g
                ),
            }
        }
        let mean = report.objects[0].incident_power.g;
        if report.objects[0].incident_power_standard_error.is_none() {
            assert!((sum / 4.0 - mean).abs() < 1e-6 * mean, "{sum} vs {mean}");
        }
    }
}

#[test]
fn a_bad_day_is_refused_at_its_state_and_field() {
    let text = scene_text();
    let no_states = text.replace(&text[text.find("states = [").unwrap()..], "states = []\n");
    let e = load_str(&no_states, "day.toml", Path::new(".")).unwrap_err();
    assert!(
        e.to_string().contains("lights[0].states: a day needs"),
        "{e}"
    );
    let missing = text.replace(", direct_normal = 800,", ",");
    let e = load_str(&missing, "day.toml", Path::new(".")).unwrap_err();
    assert!(
        e.to_string()
            .contains("lights[0].states[2].direct_normal: missing field"),
        "{e}"
    );
    let bad_time = text.replace("\"17:30\"", "\"17:70\"");
    let e = load_str(&bad_time, "day.toml", Path::new(".")).unwrap_err();
    assert!(
        e.to_string()
            .contains("lights[0].states[3].time: expected a clock time"),
        "{e}"
    );
    let unknown = text.replace("direct_normal = 300", "direct = 300");
    assert!(load_str(&unknown, "day.toml", Path::new(".")).is_err());
}
