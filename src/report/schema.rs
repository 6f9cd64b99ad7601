//! The per-object light report: one schema for every solver (light tracing now, radiosity
//! later), serialised as JSON (and flattened to CSV by [`super::write`]).
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
//!
//! Y is the linear Rec.709 luminance 0.2126·R + 0.7152·G + 0.0722·B. Unbounded surfaces
//! (infinite planes) have no area: `area`, `irradiance`, `radiosity` and `illuminance_lux`
//! are then `null`.

use crate::color::LUMINOUS_EFFICACY;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// An RGB power or power density in `f64`, channels `[r, g, b]`.
pub type Rgb64 = [f64; 3];

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
    /// One entry per object, or per face of objects with `per_face = true`, in scene order.
    pub objects: Vec<ObjectReport>,
    /// Scene-wide power balance.
    pub totals: Totals,
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

/// Run statistics: wall-clock seconds, rays traced, and solver-specific counts.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Stats {
    /// Wall-clock seconds of the solve (without scene loading).
    pub seconds: f64,
    /// Rays traced (closest-hit queries).
    pub rays: u64,
    /// Solver-specific counts, written next to `seconds` and `rays`.
    #[serde(flatten)]
    pub extra: BTreeMap<String, serde_json::Value>,
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
}

/// Scene-wide power balance, W.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Totals {
    /// Power emitted by all lights and emissive surfaces.
    pub emitted_power: Rgb64,
    /// Power absorbed by all surfaces.
    pub absorbed_power: Rgb64,
    /// Power that left the scene (zero in a closed scene).
    pub escaped_power: Rgb64,
}

/// Linear Rec.709 luminance Y of an `f64` RGB triple (same unit as the triple).
pub fn luminance(c: Rgb64) -> f64 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

impl ObjectReport {
    /// The entry for a surface called `name` (`face` for per-face entries) of one-sided area
    /// `area` (squared length units; infinite or NaN for unbounded surfaces) with the given
    /// powers in W; the densities and photometric values are derived as the module states.
    pub fn new(name: String, face: Option<u32>, area: f64, powers: &PowerBalance) -> Self {
        let bounded = area.is_finite() && area > 0.0;
        let per_area = |v: Rgb64| bounded.then(|| v.map(|c| c / area));
        let irradiance = per_area(powers.incident);
        let leaving = add(powers.emitted, powers.reflected);
        ObjectReport {
            name,
            face,
            area: (area.is_finite() && area >= 0.0).then_some(area),
            incident_power: powers.incident,
            absorbed_power: powers.absorbed,
            emitted_power: powers.emitted,
            reflected_power: powers.reflected,
            irradiance,
            radiosity: per_area(leaving),
            illuminance_lux: irradiance.map(|e| LUMINOUS_EFFICACY * luminance(e)),
            luminous_flux_lm: LUMINOUS_EFFICACY * luminance(powers.incident),
        }
    }
}

/// The power balance of one surface, W per channel.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PowerBalance {
    /// Power arriving on either side.
    pub incident: Rgb64,
    /// Power absorbed.
    pub absorbed: Rgb64,
    /// Power emitted by the surface itself.
    pub emitted: Rgb64,
    /// Power reflected or transmitted.
    pub reflected: Rgb64,
}

/// Channel-wise sum.
pub fn add(a: Rgb64, b: Rgb64) -> Rgb64 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derived_values_follow_the_definitions() {
        let p = PowerBalance {
            incident: [2.0, 4.0, 6.0],
            absorbed: [1.0, 1.0, 1.0],
            emitted: [0.5, 0.0, 0.0],
            reflected: [1.0, 3.0, 5.0],
        };
        let r = ObjectReport::new("leaf".into(), None, 2.0, &p);
        assert_eq!(r.irradiance, Some([1.0, 2.0, 3.0]));
        assert_eq!(r.radiosity, Some([0.75, 1.5, 2.5]));
        let y = 0.2126 + 0.7152 * 2.0 + 0.0722 * 3.0;
        assert!((r.illuminance_lux.unwrap() - 683.0 * y).abs() < 1e-9);
        assert!((r.luminous_flux_lm - 683.0 * 2.0 * y).abs() < 1e-9);
        let unbounded = ObjectReport::new("ground".into(), None, f64::INFINITY, &p);
        assert_eq!(unbounded.area, None);
        assert_eq!(unbounded.irradiance, None);
        assert_eq!(unbounded.illuminance_lux, None);
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
                1.0,
                &PowerBalance::default(),
            )],
            totals: Totals::default(),
        };
        let text = serde_json::to_string(&report).unwrap();
        assert!(text.contains("\"stats\":{\"seconds\":1.5,\"rays\":10,\"photons\":7}"));
        assert!(text.contains("\"face\":3"));
        let back: Report = serde_json::from_str(&text).unwrap();
        assert_eq!(back, report);
    }
}
