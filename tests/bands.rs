//! Wavelength bands against closed forms and against themselves: a black square under a sun
//! of a 5778 K black body receives, per band, the black body's share of the irradiance
//! (Planck's fractional function) and its photons (µmol per joule of the band's light); a
//! translucent leaf absorbs what its spectra, averaged over the band under that light, leave;
//! a band lit by two lights of different spectra holds the photons of each alone.
//!
//! The expected figures are computed here by other means than the library's: the fractions
//! by the series of the fractional function, spectral means by a midpoint sum at 0.01 nm.

use std::path::Path;
use std::sync::Arc;
use strahl::measure::{BandMeasurement, BandValues, ChannelErrors, GroupMeasurement, SensorBand};
use strahl::method::{
    AccelKind, Cancel, LightTraceSettings, Method, NoProgress, RadiositySettings, SolverKind,
    World, run_with_parts,
};
use strahl::report::{BandObjectReport, Report};
use strahl::scene::{BandGroup, BandQuantity, StandardSpectrum, load_str};

const H: f64 = 6.626_070_15e-34;
const C: f64 = 299_792_458.0;
const K: f64 = 1.380_649e-23;
const NA: f64 = 6.022_140_76e23;
const SUN_K: f64 = 5778.0;
/// The sun's total irradiance, W·m⁻².
const SUN: f64 = 1000.0;

/// The share of a black body's light at `kelvin` below `nm`: 15/π⁴ Σₙ e^{−nx}/n (x³ + 3x²/n
/// + 6x/n² + 6/n³), x = hc/λkT.
fn below(nm: f64, kelvin: f64) -> f64 {
    let x = H * C / (nm * 1e-9 * K * kelvin);
    let sum: f64 = (1..300)
        .map(|n| {
            let n = f64::from(n);
            (-n * x).exp() / n * (x.powi(3) + 3.0 * x * x / n + 6.0 * x / (n * n) + 6.0 / n.powi(3))
        })
        .sum();
    15.0 / std::f64::consts::PI.powi(4) * sum
}

/// Planck's spectral radiance at `nm` (any constant factor: only ratios are used).
fn planck(nm: f64, kelvin: f64) -> f64 {
    let m = nm * 1e-9;
    1.0 / m.powi(5) / (H * C / (m * K * kelvin)).exp_m1()
}

/// `∫ f(λ) dλ` over `[a, b]` nm by the midpoint rule at 0.01 nm.
fn midpoint(a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
    let n = ((b - a) / 0.01).round() as usize;
    let h = (b - a) / n as f64;
    (0..n).map(|i| f(a + (i as f64 + 0.5) * h) * h).sum()
}

/// µmol per joule of black-body light at `kelvin` within `[a, b]` nm.
fn photons_per_joule(a: f64, b: f64, kelvin: f64) -> f64 {
    let energy = midpoint(a, b, |l| planck(l, kelvin));
    let photons = midpoint(a, b, |l| planck(l, kelvin) * l * 1e-9 / (H * C * NA) * 1e6);
    photons / energy
}

const BANDS: &str = r#"
[[bands]]
name = "PAR"
from_nm = 400
to_nm = 700

[[bands]]
name = "red"
from_nm = 655
to_nm = 665

[[bands]]
name = "far-red"
from_nm = 725
to_nm = 735

[[bands]]
name = "NIR"
from_nm = 700
to_nm = 1100
"#;

/// A 1 m² square at y = 0 facing up with material `material` (a TOML table body), under the
/// sun straight from above, and `extra` TOML.
fn square(material: &str, extra: &str) -> String {
    format!(
        r#"{BANDS}
[materials.m]
{material}

[[objects]]
type = "quad"
name = "square"
material = "m"
vertices = [[0, 0, 1], [1, 0, 1], [1, 0, 0], [0, 0, 0]]

[[lights]]
type = "directional"
direction = [0, -1, 0]
irradiance = {SUN}
spectrum = {{ blackbody_k = {SUN_K} }}
{extra}"#
    )
}

/// The report, bands included, of `method` on the scene in `text`.
fn solve(text: &str, method: &Method) -> Report {
    let scene = load_str(text, "bands.toml", Path::new(".")).unwrap();
    let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
    let (outcome, parts) = run_with_parts(&world, method, &NoProgress, &Cancel::new()).unwrap();
    let bands = parts.bands.unwrap();
    Report::new("bands", outcome.measurement.as_ref().unwrap()).with_bands(&bands)
}

fn matrix() -> Method {
    Method::Radiosity(RadiositySettings::new(SolverKind::Matrix))
}

/// A black square receives each band's share of the black body's light, and its photons.
#[test]
fn a_black_square_receives_the_black_bodys_share_of_every_band() {
    let report = solve(&square("diffuse = 0\none_sided = true", ""), &matrix());
    let expected = [
        (400.0, 700.0),
        (655.0, 665.0),
        (725.0, 735.0),
        (700.0, 1100.0),
    ];
    for (band, (a, b)) in report.bands.iter().zip(expected) {
        let share = below(b, SUN_K) - below(a, SUN_K);
        let power = SUN * share;
        let o = &band.objects[0];
        assert!(
            (o.incident_power / power - 1.0).abs() < 1e-6,
            "{}: {} vs {power}",
            band.name,
            o.incident_power
        );
        assert!((o.absorbed_power / power - 1.0).abs() < 1e-6);
        let photons = power * photons_per_joule(a, b, SUN_K);
        assert!(
            (o.photon_irradiance_umol_m2_s.unwrap() / photons - 1.0).abs() < 1e-6,
            "{}: {:?} vs {photons}",
            band.name,
            o.photon_irradiance_umol_m2_s
        );
    }
    // The PAR of this sun: 36.67 % of its light, 4.566 µmol per joule.
    let par = &report.bands[0].objects[0];
    assert!(
        (par.incident_power - 366.659_443).abs() < 1e-3,
        "{}",
        par.incident_power
    );
    assert!((par.photon_irradiance_umol_m2_s.unwrap() - 1674.200).abs() < 0.01);
    // R:FR of the photons, 1.0316 under a 5778 K body.
    let ratio = report.red_far_red.as_ref().unwrap().objects[0].unwrap();
    let expected = midpoint(655.0, 665.0, |l| planck(l, SUN_K) * l)
        / midpoint(725.0, 735.0, |l| planck(l, SUN_K) * l);
    assert!(
        (ratio / expected - 1.0).abs() < 1e-6,
        "{ratio} vs {expected}"
    );
}

/// A black square under the ASTM G173 direct sun receives the table's share of PAR and its
/// photons, computed here by hand from NREL's table (the trapezoids of the samples, 400–700 nm,
/// over those of 280–4000 nm; the photons by Simpson's rule on each piece, exact for a linear
/// spectrum times λ): 41.640 % of the light, 4.629 48 µmol per joule.
#[test]
fn a_black_square_receives_the_standard_suns_par() {
    let text = square("diffuse = 0\none_sided = true", "").replace(
        &format!("{{ blackbody_k = {SUN_K} }}"),
        "{ standard = \"astm-g173-direct\" }",
    );
    let report = solve(&text, &matrix());
    let par = &report.bands[0].objects[0];
    let power = SUN * 374.814_965 / 900.139_329_284;
    assert!(
        (par.incident_power / power - 1.0).abs() < 1e-6,
        "{} vs {power}",
        par.incident_power
    );
    let photons = power * 1_735.199_117_772 / 374.814_965;
    assert!(
        (par.photon_irradiance_umol_m2_s.unwrap() / photons - 1.0).abs() < 1e-6,
        "{:?} vs {photons}",
        par.photon_irradiance_umol_m2_s
    );
}

/// A day's suns take its `spectrum` and its skies its `sky_spectrum`; an unknown standard
/// spectrum is refused at its field, naming the ones strahl knows.
#[test]
fn a_days_sun_and_sky_take_their_own_spectra() {
    let day = r#"
[[lights]]
type = "day"
name = "june"
date = "2026-06-21"
utc_offset_hours = 2
latitude_deg = 52.5
longitude_deg = 13.4
sky_type = 12
spectrum = { standard = "astm-g173-direct" }
sky_spectrum = { standard = "astm-g173-diffuse" }
states = [
  { time = "10:00", direct_normal = 700, diffuse_horizontal = 120 },
  { time = "14:00", direct_normal = 650, diffuse_horizontal = 130 },
]
"#;
    let text = format!("{BANDS}\n{day}");
    let scene = load_str(&text, "bands.toml", Path::new(".")).unwrap();
    let spectral = scene.spectral.as_ref().unwrap();
    assert_eq!(scene.lights.len(), 4);
    for (light, spectrum) in scene.lights.iter().zip(&spectral.lights) {
        let name = light.name.as_deref().unwrap();
        let expected = if name.ends_with("sky") {
            StandardSpectrum::AstmG173Diffuse
        } else {
            StandardSpectrum::AstmG173Direct
        };
        assert_eq!(spectrum, &expected.spectrum(), "{name}");
    }
    let unknown = text.replace("astm-g173-diffuse", "astm-g173-sky");
    let message = load_str(&unknown, "bands.toml", Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("lights[0].sky_spectrum: unknown standard spectrum \"astm-g173-sky\"")
            && message.contains("astm-g173-diffuse"),
        "{message}"
    );
}

/// The light model agrees within its standard errors.
#[test]
fn the_light_model_measures_the_same_bands() {
    let photons = Method::LightTrace(LightTraceSettings {
        photons: 200_000,
        ..LightTraceSettings::default()
    });
    let text = square("diffuse = 0\none_sided = true", "");
    let (exact, traced) = (solve(&text, &matrix()), solve(&text, &photons));
    for (e, t) in exact.bands.iter().zip(&traced.bands) {
        let (e, t) = (&e.objects[0], &t.objects[0]);
        let sigma = t.incident_power_standard_error.unwrap();
        assert!(sigma > 0.0 && sigma < 0.01 * e.incident_power, "{sigma}");
        assert!((t.incident_power - e.incident_power).abs() < 4.0 * sigma);
    }
}

/// A leaf's band values are its spectra's means over the band weighted by the light, so a
/// leaf alone absorbs `(1 − ρ_b − τ_b)` of a band's light.
#[test]
fn a_leaf_absorbs_what_its_band_averaged_spectra_leave() {
    let leaf = r#"diffuse_spectrum = [[400, 0.05], [550, 0.15], [700, 0.05], [750, 0.45], [1100, 0.45]]
translucency_spectrum = [[400, 0.02], [700, 0.04], [750, 0.40], [1100, 0.40]]"#;
    let report = solve(&square(leaf, ""), &matrix());
    let linear = |points: &[(f64, f64)], l: f64| {
        let i = points
            .iter()
            .rposition(|p| p.0 <= l)
            .unwrap()
            .min(points.len() - 2);
        let ((x0, y0), (x1, y1)) = (points[i], points[i + 1]);
        y0 + (y1 - y0) * (l - x0) / (x1 - x0)
    };
    let rho = [
        (400.0, 0.05),
        (550.0, 0.15),
        (700.0, 0.05),
        (750.0, 0.45),
        (1100.0, 0.45),
    ];
    let tau = [(400.0, 0.02), (700.0, 0.04), (750.0, 0.40), (1100.0, 0.40)];
    for band in &report.bands {
        let (a, b) = (band.from_nm, band.to_nm);
        let light = midpoint(a, b, |l| planck(l, SUN_K));
        let mean = |s: &[(f64, f64)]| midpoint(a, b, |l| planck(l, SUN_K) * linear(s, l)) / light;
        let o = &band.objects[0];
        let expected = 1.0 - mean(&rho) - mean(&tau);
        assert!(
            (o.absorbed_power / o.incident_power - expected).abs() < 1e-5,
            "{}: {} vs {expected}",
            band.name,
            o.absorbed_power / o.incident_power
        );
    }
}

/// Bands on a curved shape: a black sphere of radius 0.5 under the 5778 K sun receives each
/// band's share of `E·π·r²` by the light model, within four standard errors; hierarchical
/// radiosity gives each band its share of its own (grey) RGB figure to 10⁻⁶, and that figure
/// is `E·π·r²` within 1 % (the patches of the meshed sphere, a polyhedron as large as the
/// sphere, cast a shadow as large within that; measured: +0.65 %; one with its corners on
/// the sphere cast one 2.6 % smaller).
#[test]
fn a_black_sphere_receives_each_bands_share_of_its_shadow() {
    let text = square("diffuse = 0", "").replace(
        r#"type = "quad"
name = "square"
material = "m"
vertices = [[0, 0, 1], [1, 0, 1], [1, 0, 0], [0, 0, 0]]"#,
        r#"type = "sphere"
name = "ball"
material = "m"
center = [0, 0, 0]
radius = 0.5"#,
    );
    let cross_section = std::f64::consts::PI * 0.25;
    let photons = Method::LightTrace(LightTraceSettings {
        photons: 200_000,
        ..LightTraceSettings::default()
    });
    let hierarchical = Method::Radiosity(RadiositySettings::new(SolverKind::Hierarchical));
    for (method, name) in [(photons, "light model"), (hierarchical, "hierarchical")] {
        let report = solve(&text, &method);
        for band in &report.bands {
            let share = below(band.to_nm, SUN_K) - below(band.from_nm, SUN_K);
            let o = &band.objects[0];
            let (expected, allowed) = if name == "light model" {
                let sigma = o.incident_power_standard_error.unwrap();
                (SUN * cross_section * share, 4.0 * sigma)
            } else {
                let rgb = report.objects[0].incident_power.g;
                let shadow = SUN * cross_section;
                assert!((rgb / shadow - 1.0).abs() < 0.01, "{rgb} vs {shadow}");
                (rgb * share, 1e-6 * rgb * share)
            };
            assert!(
                (o.incident_power - expected).abs() <= allowed,
                "{name}, {}: {} vs {expected} (± {allowed})",
                band.name,
                o.incident_power
            );
        }
    }
}

/// Two lights of different spectra in one band: its photon flux is carried on its own and
/// equals the sum of each light's alone (the solve is linear in the lights).
/// A band's power and photon flux under lights of two and of three spectra are the sums of
/// each light's alone: two photon classes are carried as each class's power, three as the
/// power and the photon flux of all (each light's strength converted by its own spectrum).
#[test]
fn photons_of_lights_with_different_spectra_add_up() {
    let lamp = |intensity: f64, spectrum: &str| {
        format!(
            r#"
[[lights]]
type = "point"
position = [0.5, 2, 0.5]
intensity = {intensity}
spectrum = {spectrum}"#
        )
    };
    let flat = "[[400, 1], [700, 1]]";
    let warm = "{ blackbody_k = 3000 }";
    let black = "diffuse = 0\none_sided = true";
    let no_sun = |text: String| text.replace(&format!("irradiance = {SUN}"), "irradiance = 0");
    // Without the warm lamp, and with it.
    for three in [false, true] {
        let warm_lamp = if three { 30.0 } else { 0.0 };
        let scene = |sun: bool, flat_lamp: f64, warm_lamp: f64| {
            let mut lamps = lamp(flat_lamp, flat);
            if three {
                lamps += &lamp(warm_lamp, warm);
            }
            let text = square(black, &lamps);
            if sun { text } else { no_sun(text) }
        };
        let quantities: Vec<BandQuantity> =
            load_str(&scene(true, 50.0, warm_lamp), "b.toml", Path::new("."))
                .unwrap()
                .band_groups()
                .unwrap()
                .iter()
                .flat_map(|g| {
                    g.channels
                        .iter()
                        .filter(|c| c.band == 0)
                        .map(|c| c.quantity)
                })
                .collect();
        let classes = if three {
            vec![BandQuantity::Power, BandQuantity::Photons]
        } else {
            vec![BandQuantity::ClassPower(0), BandQuantity::ClassPower(1)]
        };
        assert_eq!(quantities, classes);
        let all = solve(&scene(true, 50.0, warm_lamp), &matrix());
        let alone = [
            solve(&scene(true, 0.0, 0.0), &matrix()),
            solve(&scene(false, 50.0, 0.0), &matrix()),
            solve(&scene(false, 0.0, warm_lamp), &matrix()),
        ];
        for (b, all) in all.bands.iter().enumerate() {
            let sum = |f: fn(&BandObjectReport) -> f64| -> f64 {
                alone.iter().map(|r| f(&r.bands[b].objects[0])).sum()
            };
            let o = &all.objects[0];
            let photons = sum(|o| o.incident_photons_umol_s);
            assert!(
                (o.incident_photons_umol_s / photons - 1.0).abs() < 1e-6,
                "{}",
                all.name
            );
            let power = sum(|o| o.incident_power);
            assert!(
                (o.incident_power / power - 1.0).abs() < 1e-6,
                "{}",
                all.name
            );
        }
        // The flat lamp's spectrum: 550 nm on average in PAR, so 4.5977 µmol per joule.
        let l = &alone[1].bands[0].objects[0];
        let factor = l.incident_photons_umol_s / l.incident_power;
        assert!((factor - 550.0 / 119.626_566).abs() < 1e-5, "{factor}");
    }
}

/// What a scene with bands may not hold is refused at the file's line and field.
#[test]
fn bad_band_scenes_are_refused_with_their_place() {
    let load = |text: &str| {
        load_str(text, "bands.toml", Path::new("."))
            .unwrap_err()
            .to_string()
    };
    let no_spectrum = square("diffuse = 0.5", "").replace("spectrum = { blackbody_k = 5778 }", "");
    assert!(
        load(&no_spectrum).contains("lights[0].spectrum: missing field"),
        "{}",
        load(&no_spectrum)
    );
    let coloured = square("diffuse = [0.5, 0.2, 0.1]", "");
    assert!(
        load(&coloured).contains("diffuse is not grey"),
        "{}",
        load(&coloured)
    );
    let short = square("diffuse_spectrum = [[400, 0.5], [700, 0.5]]", "");
    assert!(
        load(&short).contains("covers 400–700 nm, not all of band \"far-red\""),
        "{}",
        load(&short)
    );
    let bright = square(
        "diffuse_spectrum = [[400, 0.9], [1100, 0.9]]\ntranslucency = 0.2",
        "",
    );
    assert!(
        load(&bright).contains("reflects more than it receives"),
        "{}",
        load(&bright)
    );
    let bad_band = square("diffuse = 0.5", "").replacen("to_nm = 700", "to_nm = 300", 1);
    assert!(
        load(&bad_band).contains("bands[0].to_nm: must be greater than from_nm"),
        "{}",
        load(&bad_band)
    );
    // A band without bound would be integrated in pieces without end.
    let endless = square("diffuse = 0.5", "").replacen("to_nm = 1100", "to_nm = 1e12", 1);
    assert!(
        load(&endless).contains("bands[3].to_nm: a wavelength must be a positive number of nm"),
        "{}",
        load(&endless)
    );
    let csv = std::env::temp_dir().join("strahl-bands-bad.csv");
    std::fs::write(&csv, "nm,value\n400,0.1\n500,oops\n").unwrap();
    let from_csv = square(
        &format!("diffuse_spectrum = {:?}", csv.display().to_string()),
        "",
    );
    assert!(
        load(&from_csv).contains("strahl-bands-bad.csv:3: expected two numbers"),
        "{}",
        load(&from_csv)
    );
    // Spectra without bands.
    let text = "[materials.m]\ndiffuse_spectrum = [[400, 0.5], [700, 0.5]]\n";
    assert!(
        load(text).contains("materials.m.diffuse_spectrum: a spectrum needs [[bands]]"),
        "{}",
        load(text)
    );
}

/// The light model traces the scene and its band groups along the same photons: each band's
/// power and photon flux agree with those read from the light model run on each band group's
/// scene alone (other photons), surface by surface and at a sensor, within four standard
/// errors of the difference — a translucent leaf over a grey ground, whose albedos differ by
/// band, so that the paths are drawn by one group's weights for all. Under a sun and a sky
/// of different spectra a band is two channels, the sun's power and the sky's, so each
/// photon carries light for about half the groups.
#[test]
fn one_set_of_photon_paths_serves_every_band() {
    let leaf = r#"diffuse_spectrum = [[400, 0.05], [550, 0.15], [700, 0.05], [750, 0.45], [1100, 0.45]]
translucency_spectrum = [[400, 0.02], [700, 0.04], [750, 0.40], [1100, 0.40]]"#;
    let extra = r#"
[materials.ground]
diffuse = 0.3

[[objects]]
type = "quad"
name = "ground"
material = "ground"
vertices = [[-2, -1, 3], [3, -1, 3], [3, -1, -2], [-2, -1, -2]]

[[lights]]
type = "sky"
radiance = 50
spectrum = { blackbody_k = 9000 }

[[sensors]]
name = "under"
position = [0.5, -0.5, 0.5]
normal = [0, 1, 0]
"#;
    let text = square(leaf, extra);
    let photons = |seed| {
        Method::LightTrace(LightTraceSettings {
            photons: 400_000,
            seed,
            ..LightTraceSettings::default()
        })
    };
    let scene = load_str(&text, "bands.toml", Path::new(".")).unwrap();
    let spectral = scene.spectral.clone().unwrap();
    let world = Arc::new(World::new(scene.clone(), AccelKind::Bvh).unwrap());
    let (_, parts) = run_with_parts(&world, &photons(1), &NoProgress, &Cancel::new()).unwrap();
    let shared = parts.bands.unwrap();
    let groups = scene.band_groups().unwrap();
    // Two photon classes in every band: each class's power a channel, the sun's side by side.
    assert_eq!(groups.len(), 3);
    let lit_by = |g: &BandGroup| {
        let mut lights: Vec<usize> = g
            .channels
            .iter()
            .flat_map(|c| match c.quantity {
                BandQuantity::ClassPower(k) => spectral.photon_classes(c.band)[k].lights.clone(),
                q => panic!("{q:?}"),
            })
            .collect();
        lights.dedup();
        lights
    };
    let lit: Vec<Vec<usize>> = groups.iter().map(lit_by).collect();
    assert_eq!(lit, [vec![0], vec![0, 1], vec![1]]);
    let alone: Vec<_> = groups
        .iter()
        .map(|group| {
            let world = Arc::new(World::new(group.scene.clone(), AccelKind::Bvh).unwrap());
            let (outcome, _) =
                run_with_parts(&world, &photons(2), &NoProgress, &Cancel::new()).unwrap();
            outcome.measurement.unwrap()
        })
        .collect();
    let measured: Vec<GroupMeasurement<'_>> = groups
        .iter()
        .zip(&alone)
        .map(|(group, m)| GroupMeasurement {
            channels: &group.channels,
            power: Some(&m.power),
            sensors: &m.sensors,
        })
        .collect();
    let alone = BandMeasurement::new(&spectral, &measured, ChannelErrors::Independent);
    let agree = |what: &str, (value, sigma): (f64, f64), (other, other_sigma): (f64, f64)| {
        let both = (sigma * sigma + other_sigma * other_sigma).sqrt();
        assert!(
            (value - other).abs() < 4.0 * both && both < 0.03 * other,
            "{what}: {value} vs {other} (σ {both})"
        );
    };
    for (s, a) in shared.bands.iter().zip(&alone.bands) {
        let name = &s.band.name;
        for (quantity, shared, alone) in
            [("W", &s.power, &a.power), ("µmol", &s.photons, &a.photons)]
        {
            for (e, (s, a)) in shared.iter().zip(alone).enumerate() {
                let figure = |v: &BandValues| (v.incident, v.incident_standard_error.unwrap());
                agree(
                    &format!("{name} {quantity} surface {e}"),
                    figure(s),
                    figure(a),
                );
            }
        }
        for (quantity, shared, alone) in [
            ("W", &s.sensor_power, &a.sensor_power),
            ("µmol", &s.sensor_photons, &a.sensor_photons),
        ] {
            let figure = |v: &SensorBand| (v.irradiance, v.standard_error.unwrap());
            agree(
                &format!("{name} {quantity} sensor"),
                figure(&shared[0]),
                figure(&alone[0]),
            );
        }
    }
}
