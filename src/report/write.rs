//! Writing reports: JSON (the full schema) or CSV, chosen by the file extension.
//!
//! CSV has one row per report entry and these columns, arrays flattened per channel:
//! `name, face, area, parts, incident_power_{r,g,b}, absorbed_power_{r,g,b}, emitted_power_{r,g,b},
//! reflected_power_{r,g,b}, irradiance_{r,g,b}, radiosity_{r,g,b}, illuminance_lux,
//! luminous_flux_lm, direct_illuminance_lux, indirect_illuminance_lux,
//! illuminance_standard_error_lux`. Empty cells stand for absent values (no face; unbounded
//! area; no direct split or standard error from the solver). The scene name, solver, units,
//! statistics and totals are in the JSON form only.
//!
//! A scene with bands adds, per band, the columns `<band>_incident_power`,
//! `<band>_absorbed_power` (W), `<band>_irradiance` (W·m⁻²), `<band>_incident_photons_umol_s`,
//! `<band>_absorbed_photons_umol_s` and `<band>_photon_irradiance_umol_m2_s`, then
//! `red_far_red` where the scene has red and far-red bands.
//!
//! A scene with a day adds, per state, the columns `state_<time>_incident_power_{r,g,b}`,
//! `state_<time>_absorbed_power_{r,g,b}` (W), `state_<time>_irradiance_{r,g,b}` (W·m⁻²) and
//! `state_<time>_illuminance_lux`: each state alone at its full strength, as in the JSON form.
//!
//! When the scene has sensors, a second file next to it, named `<stem>.sensors.csv`, has one
//! row per sensor: `name, x, y, z, nx, ny, nz, illuminance_lux, direct_illuminance_lux,
//! indirect_illuminance_lux, standard_error_lux, irradiance_{r,g,b}` (irradiance in W·m⁻²),
//! and per band `<band>_irradiance` and `<band>_photon_irradiance_umol_m2_s`, then
//! `red_far_red`, then per state of a day `state_<time>_illuminance_lux` and
//! `state_<time>_irradiance_{r,g,b}`.

use super::schema::Report;
use crate::atomic_file::AtomicFile;
use crate::color::Rgb64;
use std::io::Write;
use std::path::Path;

/// Report file formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReportFormat {
    /// The full report as pretty-printed JSON.
    Json,
    /// One row per entry (objects only; sensors in a second file, see the module
    /// documentation).
    Csv,
}

/// Error while writing a report.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// The extension is neither `.json` nor `.csv`.
    #[error("'{path}': a report file must end in .json or .csv")]
    UnknownFormat {
        /// The path given.
        path: String,
    },
    /// The file could not be written.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The path given.
        path: String,
        /// The cause.
        source: std::io::Error,
    },
    /// CSV encoding failed.
    #[error("cannot write {path}: {source}")]
    Csv {
        /// The path given.
        path: String,
        /// The cause.
        source: csv::Error,
    },
}

impl ReportFormat {
    /// The format named by the extension of `path` (`.json` or `.csv`, any case).
    pub fn from_path(path: &Path) -> Result<Self, ReportError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("json") => Ok(ReportFormat::Json),
            Some("csv") => Ok(ReportFormat::Csv),
            _ => Err(ReportError::UnknownFormat {
                path: path.display().to_string(),
            }),
        }
    }
}

/// Writes `report` to `path` in the format its extension names.
pub fn write_report(report: &Report, path: &Path) -> Result<(), ReportError> {
    let format = ReportFormat::from_path(path)?;
    let name = || path.display().to_string();
    let io = |source| ReportError::Io {
        path: name(),
        source,
    };
    let mut out = AtomicFile::create(path).map_err(io)?;
    match format {
        ReportFormat::Json => {
            serde_json::to_writer_pretty(&mut out, report)
                .map_err(|e| io(std::io::Error::other(e)))?;
            writeln!(out).map_err(io)?;
        }
        ReportFormat::Csv => {
            write_csv(report, &mut out).map_err(|source| ReportError::Csv {
                path: name(),
                source,
            })?;
            if !report.sensors.is_empty() {
                // The sensor table is put in place first: a report never names rows that
                // are not there.
                let sensors_path = sensors_csv_path(path);
                let sensors_io = |source| ReportError::Io {
                    path: sensors_path.display().to_string(),
                    source,
                };
                let mut sensors = AtomicFile::create(&sensors_path).map_err(sensors_io)?;
                write_sensors_csv(report, &mut sensors).map_err(|source| ReportError::Csv {
                    path: sensors_path.display().to_string(),
                    source,
                })?;
                sensors.commit().map_err(sensors_io)?;
            }
        }
    }
    out.commit().map_err(io)
}

/// Where the sensor rows of a CSV report at `path` go: `<stem>.sensors.csv` beside it.
pub fn sensors_csv_path(path: &Path) -> std::path::PathBuf {
    let stem = path.file_stem().unwrap_or_default().to_string_lossy();
    path.with_file_name(format!("{stem}.sensors.csv"))
}

/// Writes one CSV row per sensor of `report` to `out`.
fn write_sensors_csv(report: &Report, out: impl Write) -> Result<(), csv::Error> {
    let mut w = csv::Writer::from_writer(out);
    w.write_record(
        [
            "name",
            "x",
            "y",
            "z",
            "nx",
            "ny",
            "nz",
            "illuminance_lux",
            "direct_illuminance_lux",
            "indirect_illuminance_lux",
            "standard_error_lux",
            "irradiance_r",
            "irradiance_g",
            "irradiance_b",
        ]
        .map(String::from)
        .into_iter()
        .chain(report.bands.iter().flat_map(|b| {
            [
                format!("{}_irradiance", b.name),
                format!("{}_photon_irradiance_umol_m2_s", b.name),
            ]
        }))
        .chain(
            report
                .red_far_red
                .as_ref()
                .map(|_| "red_far_red".to_string()),
        )
        .chain(report.states.iter().flat_map(|state| {
            [
                "illuminance_lux",
                "irradiance_r",
                "irradiance_g",
                "irradiance_b",
            ]
            .map(|c| format!("state_{}_{c}", state.time))
        })),
    )?;
    for (k, s) in report.sensors.iter().enumerate() {
        let mut row = vec![s.name.clone()];
        row.extend(s.position.iter().chain(&s.normal).map(|v| v.to_string()));
        row.extend(
            [
                s.illuminance_lux,
                s.direct_illuminance_lux,
                s.indirect_illuminance_lux,
            ]
            .map(|v| v.to_string()),
        );
        row.push(
            s.standard_error_lux
                .map(|v| v.to_string())
                .unwrap_or_default(),
        );
        row.extend(s.irradiance.to_array().map(|v| v.to_string()));
        for b in &report.bands {
            let f = &b.sensors[k];
            row.extend([f.irradiance, f.photon_irradiance_umol_m2_s].map(|v| v.to_string()));
        }
        if let Some(ratio) = &report.red_far_red {
            row.push(ratio.sensors[k].map(|v| v.to_string()).unwrap_or_default());
        }
        for state in &report.states {
            let s = &state.sensors[k];
            row.push(s.illuminance_lux.to_string());
            row.extend(s.irradiance.to_array().map(|v| v.to_string()));
        }
        w.write_record(&row)?;
    }
    w.flush()?;
    Ok(())
}

/// Column names of the CSV form of a report without bands.
pub(crate) fn csv_header() -> Vec<String> {
    let mut h = vec![
        "name".to_string(),
        "face".into(),
        "area".into(),
        "parts".into(),
    ];
    for q in [
        "incident_power",
        "absorbed_power",
        "emitted_power",
        "reflected_power",
        "irradiance",
        "radiosity",
    ] {
        for c in ["r", "g", "b"] {
            h.push(format!("{q}_{c}"));
        }
    }
    h.push("illuminance_lux".into());
    h.push("luminous_flux_lm".into());
    h.push("direct_illuminance_lux".into());
    h.push("indirect_illuminance_lux".into());
    h.push("illuminance_standard_error_lux".into());
    h
}

/// The columns each band adds to an object's row, after its name and an underscore.
const BAND_COLUMNS: [&str; 6] = [
    "incident_power",
    "absorbed_power",
    "irradiance",
    "incident_photons_umol_s",
    "absorbed_photons_umol_s",
    "photon_irradiance_umol_m2_s",
];

/// The columns each state of a day adds to an object's row, after `state_<time>_`.
const STATE_COLUMNS: [&str; 10] = [
    "incident_power_r",
    "incident_power_g",
    "incident_power_b",
    "absorbed_power_r",
    "absorbed_power_g",
    "absorbed_power_b",
    "irradiance_r",
    "irradiance_g",
    "irradiance_b",
    "illuminance_lux",
];

/// Writes the CSV form of `report` to `out`.
fn write_csv(report: &Report, out: &mut impl Write) -> Result<(), csv::Error> {
    let mut w = csv::Writer::from_writer(out);
    let mut header = csv_header();
    for b in &report.bands {
        header.extend(BAND_COLUMNS.map(|c| format!("{}_{c}", b.name)));
    }
    if report.red_far_red.is_some() {
        header.push("red_far_red".into());
    }
    for state in &report.states {
        header.extend(STATE_COLUMNS.map(|c| format!("state_{}_{c}", state.time)));
    }
    w.write_record(header)?;
    let num = |v: f64| v.to_string();
    let opt = |v: Option<f64>| v.map(num).unwrap_or_default();
    let rgb = |row: &mut Vec<String>, v: Option<Rgb64>| match v {
        Some(c) => row.extend(c.to_array().map(num)),
        None => row.extend([String::new(), String::new(), String::new()]),
    };
    for (e, o) in report.objects.iter().enumerate() {
        let mut row = vec![
            o.name.clone(),
            o.face.map(|f| f.to_string()).unwrap_or_default(),
            opt(o.area),
            o.parts.to_string(),
        ];
        for v in [
            o.incident_power,
            o.absorbed_power,
            o.emitted_power,
            o.reflected_power,
        ] {
            rgb(&mut row, Some(v));
        }
        rgb(&mut row, o.irradiance);
        rgb(&mut row, o.radiosity);
        row.push(opt(o.illuminance_lux));
        row.push(num(o.luminous_flux_lm));
        row.push(opt(o.direct_illuminance_lux));
        row.push(opt(o.indirect_illuminance_lux));
        row.push(opt(o.illuminance_standard_error_lux));
        for b in &report.bands {
            let f = &b.objects[e];
            row.extend([
                num(f.incident_power),
                num(f.absorbed_power),
                opt(f.irradiance),
            ]);
            row.extend([
                num(f.incident_photons_umol_s),
                num(f.absorbed_photons_umol_s),
                opt(f.photon_irradiance_umol_m2_s),
            ]);
        }
        if let Some(ratio) = &report.red_far_red {
            row.push(opt(ratio.objects[e]));
        }
        for state in &report.states {
            let o = &state.objects[e];
            rgb(&mut row, Some(o.incident_power));
            rgb(&mut row, Some(o.absorbed_power));
            rgb(&mut row, o.irradiance);
            row.push(opt(o.illuminance_lux));
        }
        w.write_record(&row)?;
    }
    w.flush()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::schema::{ObjectReport, Units};
    use super::*;
    use crate::measure::{PowerBalance, Stats, Totals};

    fn sample() -> Report {
        let p = PowerBalance {
            incident: Rgb64::new(1.0, 2.0, 3.0),
            ..PowerBalance::default()
        };
        Report {
            scene: "s".into(),
            solver: "light-trace".into(),
            units: Units::default(),
            stats: Stats::default(),
            objects: vec![
                ObjectReport::new("leaf, big".into(), Some(1), (0.5, 1), &p, None),
                ObjectReport::new("ground".into(), None, (f64::INFINITY, 1), &p, None),
            ],
            totals: Totals::default(),
            sensors: Vec::new(),
            bands: Vec::new(),
            red_far_red: None,
            states: Vec::new(),
        }
    }

    #[test]
    fn csv_has_one_row_per_entry_and_flattened_columns() {
        let mut buf = Vec::new();
        write_csv(&sample(), &mut buf).unwrap();
        let text = String::from_utf8(buf).unwrap();
        let mut reader = csv::Reader::from_reader(text.as_bytes());
        let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
        assert_eq!(header, csv_header());
        assert_eq!(header.len(), 27);
        let rows: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
        assert_eq!(rows.len(), 2);
        assert_eq!(&rows[0][0], "leaf, big");
        assert_eq!(&rows[0][1], "1");
        assert_eq!(&rows[0][2], "0.5");
        assert_eq!(&rows[0][3], "1");
        assert_eq!(&rows[0][16], "2"); // irradiance_r = 1 / 0.5
        assert_eq!(&rows[1][2], "");
        assert_eq!(&rows[1][16], "");
    }

    #[test]
    fn format_follows_the_extension() {
        assert_eq!(
            ReportFormat::from_path(Path::new("a/OUT.CSV")).unwrap(),
            ReportFormat::Csv
        );
        assert_eq!(
            ReportFormat::from_path(Path::new("o.json")).unwrap(),
            ReportFormat::Json
        );
        assert!(ReportFormat::from_path(Path::new("o.txt")).is_err());
    }
}
