//! The per-object light report: one schema for every solver (the light model and every
//! radiosity solver), built from the [`Measurement`] of a solver and serialised as
//! JSON (and flattened to CSV by [`super::write`]).
//!
//! Definitions (per channel, linear Rec.709 RGB):
//! - `incident_power`: power arriving at the surface from both sides, W (watts of the scene's
//!   radiometric units).
//! - `absorbed_power`: the part of the incident power the surface absorbs, W.
//! - `emitted_power`: power the surface emits itself (both sides when two-sided), W.
//! - `reflected_power`: power leaving the surface by reflection or transmission, W.
//! - `irradiance` = incident power / area, W·m⁻² (a thin leaf lit from both sides has both
//!   sides summed; `area` is the one-sided area).
//! - `radiosity` = (emitted + reflected power) / area, W·m⁻².
//! - `illuminance_lux` = 683 lm/W × luminance Y of `irradiance`; it is lux only when lengths
//!   are metres (otherwise lm per squared scene unit).
//! - `luminous_flux_lm` = 683 lm/W × luminance Y of `incident_power`, lumens.
//! - `direct_power` (the light model, the matrix and progressive solvers, hierarchical
//!   radiosity, and every radiosity solver for the surfaces its final gather measured): the part of `incident_power` that came straight from a light or emitting
//!   surface, W; `direct_illuminance_lux` and `indirect_illuminance_lux`
//!   split `illuminance_lux` the same way.
//! - `incident_power_standard_error` (the light model, and the radiosity solvers for the
//!   surfaces their final gather measured anew, `--surface-gather`): the standard error of
//!   `incident_power`, W; `illuminance_standard_error_lux` is 683 × the luminance of the
//!   per-channel errors over the area (an upper bound of the error of the luminance).
//!
//! Sensors (`sensors`, when the scene has any) report the irradiance at their point on the
//! side their normal faces, W·m⁻², split into direct and indirect, and the same in lux; Monte
//! Carlo solvers add `standard_error_lux` (683 × the luminance of the per-channel errors).
//!
//! Y is the linear Rec.709 luminance 0.2126·R + 0.7152·G + 0.0722·B. Unbounded surfaces
//! (infinite planes) have no area: `area`, `irradiance`, `radiosity` and `illuminance_lux`
//! are then `null`.

use super::bands::{BandReport, RedFarRedReport, band_reports, red_far_red};
use crate::color::{LUMINOUS_EFFICACY, Rgb64};
use crate::measure::{
    BandMeasurement, Measurement, PowerBalance, SensorReading, StateMeasurement, Stats,
    SurfacePower, Totals,
};
use serde::{Deserialize, Serialize};

/// A complete report.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Report {
    /// Scene name.
    pub scene: String,
    /// Solver that produced it (`light-trace`, …).
    pub solver: String,
    /// Units of lengths and powers.
    pub units: Units,
    /// Run statistics.
    pub stats: Stats,
    /// One entry per object name (objects sharing a name are one entry), or per face of
    /// objects with `per_face = true`, in scene order.
    pub objects: Vec<ObjectReport>,
    /// Scene-wide power balance.
    pub totals: Totals,
    /// One entry per sensor of the scene, in scene order (absent when there is none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sensors: Vec<SensorReport>,
    /// Per wavelength band of the scene, in its order (absent for a scene in RGB only;
    /// `super::bands`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bands: Vec<BandReport>,
    /// The red : far-red ratio, when the scene has bands named red and far-red.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub red_far_red: Option<RedFarRedReport>,
    /// Each state of the scene's day alone, in order (absent without a day): the figures
    /// above are the mean over the states.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub states: Vec<StateReport>,
}

/// The figures of one state of a day, the state alone (its sun and sky at full strength):
/// objects and sensors as the report's, in the same order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StateReport {
    /// The state's clock time as the scene gives it.
    pub time: String,
    /// One entry per report object.
    pub objects: Vec<ObjectReport>,
    /// One entry per sensor (absent when there is none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sensors: Vec<SensorReport>,
}

/// The reading of one point sensor.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SensorReport {
    /// Sensor name (`name[i,j]` for a point of a grid).
    pub name: String,
    /// Where it is, length units.
    pub position: [f32; 3],
    /// Unit normal of its receiving side.
    pub normal: [f32; 3],
    /// Irradiance on the receiving side, W·m⁻².
    pub irradiance: Rgb64,
    /// The part straight from lights and emitting surfaces, W·m⁻².
    pub direct_irradiance: Rgb64,
    /// The part reflected by surfaces on its way, W·m⁻².
    pub indirect_irradiance: Rgb64,
    /// 683 × luminance of `irradiance`, lux (when lengths are metres).
    pub illuminance_lux: f64,
    /// 683 × luminance of `direct_irradiance`, lux.
    pub direct_illuminance_lux: f64,
    /// 683 × luminance of `indirect_irradiance`, lux.
    pub indirect_illuminance_lux: f64,
    /// Standard error of `irradiance` per channel (Monte Carlo solvers), W·m⁻².
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub standard_error: Option<Rgb64>,
    /// 683 × luminance of `standard_error`, lux.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub standard_error_lux: Option<f64>,
}

impl SensorReport {
    /// The report of one sensor reading.
    pub fn new(reading: &SensorReading) -> Self {
        let lux = |e: Rgb64| LUMINOUS_EFFICACY * e.luminance();
        SensorReport {
            name: reading.sensor.name.clone(),
            position: reading.sensor.position.to_array(),
            normal: reading.sensor.normal.to_array(),
            irradiance: reading.irradiance(),
            direct_irradiance: reading.direct,
            indirect_irradiance: reading.indirect,
            illuminance_lux: lux(reading.irradiance()),
            direct_illuminance_lux: lux(reading.direct),
            indirect_illuminance_lux: lux(reading.indirect),
            standard_error: reading.standard_error,
            standard_error_lux: reading.standard_error.map(lux),
        }
    }
}

/// Units of the report's numbers.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Units {
    /// Unit of lengths (areas are its square).
    pub length: String,
    /// Unit of power.
    pub power: String,
}

impl Default for Units {
    /// Metres and watts.
    fn default() -> Self {
        Units {
            length: "m".to_string(),
            power: "W".to_string(),
        }
    }
}

/// The light report of one object (or one face of a per-face object).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ObjectReport {
    /// Object name (`object-<index>` when the scene gives none).
    pub name: String,
    /// Face index within the object for per-face entries; absent for whole objects.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub face: Option<u32>,
    /// One-sided surface area, squared length units; `null` when unbounded.
    pub area: Option<f64>,
    /// How many scene objects (faces, for per-face entries) share this entry's name and are
    /// reported together: areas and powers summed, densities area-weighted.
    pub parts: u32,
    /// Power arriving on either side, W.
    pub incident_power: Rgb64,
    /// Power absorbed, W.
    pub absorbed_power: Rgb64,
    /// Power emitted by the surface itself, W.
    pub emitted_power: Rgb64,
    /// Power reflected or transmitted, W.
    pub reflected_power: Rgb64,
    /// Incident power / area, W·m⁻².
    pub irradiance: Option<Rgb64>,
    /// (Emitted + reflected power) / area, W·m⁻².
    pub radiosity: Option<Rgb64>,
    /// 683 × luminance of `irradiance`, lux (when lengths are metres).
    pub illuminance_lux: Option<f64>,
    /// 683 × luminance of `incident_power`, lumens.
    pub luminous_flux_lm: f64,
    /// The part of `incident_power` straight from lights and emitting surfaces, W (the
    /// solvers that tell it apart: not hierarchical shooting).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direct_power: Option<Rgb64>,
    /// 683 × luminance of `direct_power` / area, lux.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direct_illuminance_lux: Option<f64>,
    /// 683 × luminance of (`incident_power` − `direct_power`) / area, lux.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub indirect_illuminance_lux: Option<f64>,
    /// Standard error of `incident_power` per channel (Monte Carlo solvers, and the surfaces
    /// a radiosity solver's final gather measured), W.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub incident_power_standard_error: Option<Rgb64>,
    /// 683 × luminance of `incident_power_standard_error` / area, lux.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub illuminance_standard_error_lux: Option<f64>,
}

impl ObjectReport {
    /// The entry for a surface called `name` (`face` for per-face entries) of one-sided area
    /// `area` (squared length units; infinite or NaN for unbounded surfaces) with the given
    /// powers in W; the densities and photometric values are derived as the module states.
    pub fn new(
        name: String,
        face: Option<u32>,
        (area, parts): (f64, u32),
        powers: &PowerBalance,
        standard_error: Option<Rgb64>,
    ) -> Self {
        let bounded = area.is_finite() && area > 0.0;
        let per_area = |v: Rgb64| bounded.then(|| v.map(|c| c / area));
        let lux = |v: Rgb64| per_area(v).map(|e| LUMINOUS_EFFICACY * e.luminance());
        let irradiance = per_area(powers.incident);
        let leaving = powers.emitted + powers.reflected;
        ObjectReport {
            name,
            face,
            area: (area.is_finite() && area >= 0.0).then_some(area),
            parts,
            incident_power: powers.incident,
            absorbed_power: powers.absorbed,
            emitted_power: powers.emitted,
            reflected_power: powers.reflected,
            irradiance,
            radiosity: per_area(leaving),
            illuminance_lux: irradiance.map(|e| LUMINOUS_EFFICACY * e.luminance()),
            luminous_flux_lm: LUMINOUS_EFFICACY * powers.incident.luminance(),
            direct_power: powers.direct,
            direct_illuminance_lux: powers.direct.and_then(lux),
            indirect_illuminance_lux: powers.direct.and_then(|d| lux(powers.incident - d)),
            incident_power_standard_error: standard_error,
            illuminance_standard_error_lux: standard_error.and_then(lux),
        }
    }
}

/// One report entry per surface of `power`'s table.
fn objects_of(power: &SurfacePower) -> Vec<ObjectReport> {
    power
        .table()
        .surfaces()
        .iter()
        .enumerate()
        .map(|(e, s)| {
            ObjectReport::new(
                s.name.clone(),
                s.face,
                (s.area, s.parts),
                power.balance(e),
                power.standard_error(e),
            )
        })
        .collect()
}

impl Report {
    /// The report of scene `scene` from what a solver measured on it, in metres and watts.
    pub fn new(scene: &str, measured: &Measurement) -> Self {
        let power = &measured.power;
        let objects = objects_of(power);
        Report {
            scene: scene.to_string(),
            solver: measured.solver.to_string(),
            units: Units::default(),
            stats: measured.stats.clone(),
            objects,
            totals: power.totals(),
            sensors: measured.sensors.iter().map(SensorReport::new).collect(),
            bands: Vec::new(),
            red_far_red: None,
            states: Vec::new(),
        }
    }

    /// This report with the figures of each state of the scene's day (measured on the same
    /// scene by the same method).
    pub fn with_states(mut self, states: &[StateMeasurement]) -> Report {
        self.states = states
            .iter()
            .map(|state| StateReport {
                time: state.time.clone(),
                objects: state.power.as_ref().map_or_else(Vec::new, objects_of),
                sensors: state.sensors.iter().map(SensorReport::new).collect(),
            })
            .collect();
        self
    }

    /// This report with the figures of `bands` (measured on the same scene by the same
    /// method): a band per entry of `bands`, and the red : far-red ratio where bands named
    /// `red` and `far-red` (or `far_red`, any case) exist.
    pub fn with_bands(mut self, bands: &BandMeasurement) -> Report {
        let objects: Vec<_> = self
            .objects
            .iter()
            .map(|o| (o.name.as_str(), o.face, o.area))
            .collect();
        let sensors: Vec<&str> = self.sensors.iter().map(|s| s.name.as_str()).collect();
        let reports = band_reports(bands, &objects, &sensors);
        self.red_far_red = red_far_red(&reports);
        self.bands = reports;
        self
    }

    /// The first non-finite figure, as `(entry, field)` (`entry` is an object's name or
    /// `totals`), or `None` when every figure is finite. A non-finite figure is a numerical
    /// failure, never a result: callers refuse to write such a report.
    pub fn first_non_finite(&self) -> Option<(String, &'static str)> {
        let finite = |c: &Rgb64| c.to_array().iter().all(|v| v.is_finite());
        for o in &self.objects {
            let fields = [
                ("incident_power", Some(o.incident_power)),
                ("absorbed_power", Some(o.absorbed_power)),
                ("emitted_power", Some(o.emitted_power)),
                ("reflected_power", Some(o.reflected_power)),
                ("irradiance", o.irradiance),
                ("radiosity", o.radiosity),
            ];
            for (field, value) in fields {
                if value.is_some_and(|v| !finite(&v)) {
                    return Some((o.name.clone(), field));
                }
            }
            if !o.luminous_flux_lm.is_finite() || o.illuminance_lux.is_some_and(|v| !v.is_finite())
            {
                return Some((o.name.clone(), "illuminance_lux"));
            }
        }
        for s in &self.sensors {
            if !finite(&s.irradiance) || !s.illuminance_lux.is_finite() {
                return Some((s.name.clone(), "sensor irradiance"));
            }
        }
        if let Some(found) = super::bands::first_non_finite(&self.bands) {
            return Some(found);
        }
        let t = &self.totals;
        [
            ("emitted_power", t.emitted_power),
            ("absorbed_power", t.absorbed_power),
            ("escaped_power", t.escaped_power),
        ]
        .into_iter()
        .find(|(_, v)| !finite(v))
        .map(|(field, _)| ("totals".to_string(), field))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derived_values_follow_the_definitions() {
        let p = PowerBalance {
            incident: Rgb64::new(2.0, 4.0, 6.0),
            direct: Some(Rgb64::new(1.0, 1.0, 1.0)),
            absorbed: Rgb64::new(1.0, 1.0, 1.0),
            emitted: Rgb64::new(0.5, 0.0, 0.0),
            reflected: Rgb64::new(1.0, 3.0, 5.0),
        };
        let r = ObjectReport::new("leaf".into(), None, (2.0, 1), &p, None);
        assert_eq!(r.irradiance, Some(Rgb64::new(1.0, 2.0, 3.0)));
        assert_eq!(r.radiosity, Some(Rgb64::new(0.75, 1.5, 2.5)));
        let y = 0.2126 + 0.7152 * 2.0 + 0.0722 * 3.0;
        assert!((r.illuminance_lux.unwrap() - 683.0 * y).abs() < 1e-9);
        assert!((r.luminous_flux_lm - 683.0 * 2.0 * y).abs() < 1e-9);
        let y1 = 1.0 / 2.0;
        assert!((r.direct_illuminance_lux.unwrap() - 683.0 * y1).abs() < 1e-9);
        assert!((r.indirect_illuminance_lux.unwrap() - 683.0 * (y - y1)).abs() < 1e-9);
        let unbounded = ObjectReport::new("ground".into(), None, (f64::INFINITY, 1), &p, None);
        assert_eq!(unbounded.area, None);
        assert_eq!(unbounded.irradiance, None);
        assert_eq!(unbounded.illuminance_lux, None);
    }

    #[test]
    fn non_finite_figures_are_found_by_entry_and_field() {
        let fine = PowerBalance::default();
        let mut report = Report {
            scene: "s".into(),
            solver: "matrix".into(),
            units: Units::default(),
            stats: Stats::default(),
            objects: vec![ObjectReport::new("a".into(), None, (1.0, 1), &fine, None)],
            totals: Totals::default(),
            sensors: Vec::new(),
            bands: Vec::new(),
            red_far_red: None,
            states: Vec::new(),
        };
        assert_eq!(report.first_non_finite(), None);
        report.totals.escaped_power = Rgb64::new(0.0, f64::NEG_INFINITY, 0.0);
        assert_eq!(
            report.first_non_finite(),
            Some(("totals".to_string(), "escaped_power"))
        );
        let broken = PowerBalance {
            absorbed: Rgb64::new(f64::NAN, 0.0, 0.0),
            ..PowerBalance::default()
        };
        report
            .objects
            .push(ObjectReport::new("b".into(), None, (1.0, 1), &broken, None));
        assert_eq!(
            report.first_non_finite(),
            Some(("b".to_string(), "absorbed_power"))
        );
    }

    #[test]
    fn json_round_trip_keeps_stats_flat() {
        let mut stats = Stats {
            seconds: 1.5,
            rays: 10,
            ..Stats::default()
        };
        stats.extra.insert("photons".into(), 7.into());
        let report = Report {
            scene: "s".into(),
            solver: "light-trace".into(),
            units: Units::default(),
            stats,
            objects: vec![ObjectReport::new(
                "a".into(),
                Some(3),
                (1.0, 1),
                &PowerBalance::default(),
                None,
            )],
            totals: Totals::default(),
            sensors: Vec::new(),
            bands: Vec::new(),
            red_far_red: None,
            states: Vec::new(),
        };
        let text = serde_json::to_string(&report).unwrap();
        assert!(text.contains("\"stats\":{\"seconds\":1.5,\"rays\":10,\"photons\":7}"));
        assert!(text.contains("\"face\":3"));
        let back: Report = serde_json::from_str(&text).unwrap();
        assert_eq!(back, report);
    }
}
