//! The report's figures per wavelength band, for scenes with `[[bands]]`: per band, every
//! object's (and sensor's) power in W and W·m⁻² and its photon flux in µmol·s⁻¹ and
//! µmol·m⁻²·s⁻¹ (PPFD in the PAR band); and the red : far-red ratio of the photon
//! irradiance where the scene has bands named `red` and `far-red`.
//!
//! The objects and sensors of a band are those of the report, in the same order.

use crate::measure::{BandFigures, BandMeasurement, SensorBand};
use serde::{Deserialize, Serialize};

/// One band's figures.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BandReport {
    /// The band's name.
    pub name: String,
    /// Shortest wavelength, nm.
    pub from_nm: f64,
    /// Longest wavelength, nm.
    pub to_nm: f64,
    /// One entry per report object, in the same order.
    pub objects: Vec<BandObjectReport>,
    /// One entry per sensor, in the same order (absent when there is none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sensors: Vec<BandSensorReport>,
}

/// One object's light in one band.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BandObjectReport {
    /// Object name, as in the report's objects.
    pub name: String,
    /// Face index for per-face entries.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub face: Option<u32>,
    /// Power arriving on either side, W.
    pub incident_power: f64,
    /// Power absorbed, W.
    pub absorbed_power: f64,
    /// Incident power / area, W·m⁻² (`null` when unbounded).
    pub irradiance: Option<f64>,
    /// Photon flux arriving, µmol·s⁻¹.
    pub incident_photons_umol_s: f64,
    /// Photon flux absorbed, µmol·s⁻¹.
    pub absorbed_photons_umol_s: f64,
    /// Incident photon flux / area, µmol·m⁻²·s⁻¹ (PPFD in the PAR band).
    pub photon_irradiance_umol_m2_s: Option<f64>,
    /// The part of `incident_power` straight from the lights, W (solvers that tell it apart).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direct_power: Option<f64>,
    /// Standard error of `incident_power`, W (Monte Carlo solvers).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub incident_power_standard_error: Option<f64>,
    /// Standard error of `photon_irradiance_umol_m2_s`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub photon_irradiance_standard_error: Option<f64>,
}

/// One sensor's light in one band.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BandSensorReport {
    /// Sensor name, as in the report's sensors.
    pub name: String,
    /// Irradiance on its side, W·m⁻².
    pub irradiance: f64,
    /// The part straight from the lights, W·m⁻².
    pub direct_irradiance: f64,
    /// Photon irradiance, µmol·m⁻²·s⁻¹ (PPFD in the PAR band).
    pub photon_irradiance_umol_m2_s: f64,
    /// Standard error of `irradiance` (Monte Carlo solvers).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub standard_error: Option<f64>,
    /// Standard error of `photon_irradiance_umol_m2_s`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub photon_standard_error: Option<f64>,
}

/// The red : far-red ratio of the photon irradiance per object and sensor (`null` where
/// the far-red light is zero).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RedFarRedReport {
    /// The name of the band taken as red.
    pub red: String,
    /// The name of the band taken as far red.
    pub far_red: String,
    /// Per report object, in the same order.
    pub objects: Vec<Option<f64>>,
    /// Per sensor, in the same order.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sensors: Vec<Option<f64>>,
}

/// Where a report entry is: its name, face (per-face entries) and one-sided area (`None`
/// when unbounded).
pub(super) type EntryPlace<'a> = (&'a str, Option<u32>, Option<f64>);

/// The band reports of `bands` for the report entries `objects` and the sensors named
/// `sensors`, in their order.
pub(super) fn band_reports(
    bands: &BandMeasurement,
    objects: &[EntryPlace<'_>],
    sensors: &[&str],
) -> Vec<BandReport> {
    bands
        .bands
        .iter()
        .map(|b| band_report(b, objects, sensors))
        .collect()
}

fn band_report(figures: &BandFigures, objects: &[EntryPlace<'_>], sensors: &[&str]) -> BandReport {
    let objects = objects
        .iter()
        .enumerate()
        .map(|(e, &(name, face, area))| {
            let power = figures.power.get(e).copied().unwrap_or_default();
            let photons = figures.photons.get(e).copied().unwrap_or_default();
            let per_area = |v: f64| area.filter(|&a| a > 0.0).map(|a| v / a);
            BandObjectReport {
                name: name.to_string(),
                face,
                incident_power: power.incident,
                absorbed_power: power.absorbed,
                irradiance: per_area(power.incident),
                incident_photons_umol_s: photons.incident,
                absorbed_photons_umol_s: photons.absorbed,
                photon_irradiance_umol_m2_s: per_area(photons.incident),
                direct_power: power.direct,
                incident_power_standard_error: power.incident_standard_error,
                photon_irradiance_standard_error: photons
                    .incident_standard_error
                    .and_then(per_area),
            }
        })
        .collect();
    let sensors = sensors
        .iter()
        .enumerate()
        .map(|(k, name)| {
            let power = figures.sensor_power.get(k).copied().unwrap_or_default();
            let photons: SensorBand = figures.sensor_photons.get(k).copied().unwrap_or_default();
            BandSensorReport {
                name: name.to_string(),
                irradiance: power.irradiance,
                direct_irradiance: power.direct,
                photon_irradiance_umol_m2_s: photons.irradiance,
                standard_error: power.standard_error,
                photon_standard_error: photons.standard_error,
            }
        })
        .collect();
    BandReport {
        name: figures.band.name.clone(),
        from_nm: figures.band.from_nm,
        to_nm: figures.band.to_nm,
        objects,
        sensors,
    }
}

/// The red : far-red ratio of `bands`' photon irradiance, when bands called red and far red
/// are among them.
pub(super) fn red_far_red(bands: &[BandReport]) -> Option<RedFarRedReport> {
    let named = |names: &[&str]| {
        bands
            .iter()
            .find(|b| names.iter().any(|n| b.name.eq_ignore_ascii_case(n)))
    };
    let red = named(&["red"])?;
    let far = named(&["far-red", "far_red"])?;
    let ratio = |r: f64, f: f64| (f > 0.0).then(|| r / f);
    Some(RedFarRedReport {
        red: red.name.clone(),
        far_red: far.name.clone(),
        objects: red
            .objects
            .iter()
            .zip(&far.objects)
            .map(|(r, f)| ratio(r.incident_photons_umol_s, f.incident_photons_umol_s))
            .collect(),
        sensors: red
            .sensors
            .iter()
            .zip(&far.sensors)
            .map(|(r, f)| ratio(r.photon_irradiance_umol_m2_s, f.photon_irradiance_umol_m2_s))
            .collect(),
    })
}

/// The first non-finite band figure as `(entry, field)`, or `None`.
pub(super) fn first_non_finite(bands: &[BandReport]) -> Option<(String, &'static str)> {
    for b in bands {
        for o in &b.objects {
            let values = [
                Some(o.incident_power),
                Some(o.absorbed_power),
                o.irradiance,
                Some(o.incident_photons_umol_s),
                Some(o.absorbed_photons_umol_s),
                o.photon_irradiance_umol_m2_s,
            ];
            if values.iter().flatten().any(|v| !v.is_finite()) {
                return Some((format!("{} in band {}", o.name, b.name), "band figures"));
            }
        }
        for s in &b.sensors {
            if ![s.irradiance, s.photon_irradiance_umol_m2_s]
                .iter()
                .all(|v| v.is_finite())
            {
                return Some((format!("{} in band {}", s.name, b.name), "band irradiance"));
            }
        }
    }
    None
}
