//! A report's figures as columns for numpy (`strahl.Result`): the report's JSON read into the
//! library's typed [`Report`] here, each column handed over as little-endian `f64` bytes
//! (NaN where the report has no value). On the Helios field's report (160,001 rows, 93 MB)
//! Python's own `json.loads` and row-by-row columns took 5 s.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyByteArray, PyDict, PyList};
use strahl::method::Rgb64;
use strahl::report::{
    BandObjectReport, BandReport, BandSensorReport, ObjectReport, Report, StateReport,
};

/// `values` as little-endian `f64` bytes, for `numpy.frombuffer`.
fn column<'py>(py: Python<'py>, values: impl Iterator<Item = f64>) -> Bound<'py, PyByteArray> {
    let bytes: Vec<u8> = values.flat_map(f64::to_le_bytes).collect();
    PyByteArray::new(py, &bytes)
}

/// Three channels a row, NaN where the row has none.
fn rgb<'py, T>(
    py: Python<'py>,
    rows: &[T],
    value: impl Fn(&T) -> Option<Rgb64>,
) -> Bound<'py, PyByteArray> {
    let channels = |v: Option<Rgb64>| v.map_or([f64::NAN; 3], |c| c.to_array());
    column(py, rows.iter().flat_map(|r| channels(value(r))))
}

/// One number a row, NaN where the row has none.
fn scalar<'py, T>(
    py: Python<'py>,
    rows: &[T],
    value: impl Fn(&T) -> Option<f64>,
) -> Bound<'py, PyByteArray> {
    column(py, rows.iter().map(|r| value(r).unwrap_or(f64::NAN)))
}

/// The objects' (or faces') columns every table of rows shares: powers and irradiance.
fn object_columns<'py>(py: Python<'py>, objects: &[ObjectReport]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item(
        "incident_power",
        rgb(py, objects, |o| Some(o.incident_power)),
    )?;
    d.set_item(
        "absorbed_power",
        rgb(py, objects, |o| Some(o.absorbed_power)),
    )?;
    d.set_item("irradiance", rgb(py, objects, |o| o.irradiance))?;
    Ok(d)
}

/// One band's columns: per object and per sensor.
fn band_columns<'py>(py: Python<'py>, band: &BandReport) -> PyResult<Bound<'py, PyDict>> {
    let (o, s) = (&band.objects, &band.sensors);
    let d = PyDict::new(py);
    d.set_item("name", &band.name)?;
    d.set_item("from_nm", band.from_nm)?;
    d.set_item("to_nm", band.to_nm)?;
    d.set_item("incident_power", scalar(py, o, |r| Some(r.incident_power)))?;
    d.set_item("absorbed_power", scalar(py, o, |r| Some(r.absorbed_power)))?;
    d.set_item("irradiance", scalar(py, o, |r| r.irradiance))?;
    let umol = |r: &BandObjectReport| Some(r.incident_photons_umol_s);
    d.set_item("incident_photons_umol_s", scalar(py, o, umol))?;
    let absorbed = |r: &BandObjectReport| Some(r.absorbed_photons_umol_s);
    d.set_item("absorbed_photons_umol_s", scalar(py, o, absorbed))?;
    let ppfd = |r: &BandObjectReport| r.photon_irradiance_umol_m2_s;
    d.set_item("photon_irradiance_umol_m2_s", scalar(py, o, ppfd))?;
    let sigma = |r: &BandObjectReport| r.incident_power_standard_error;
    d.set_item("incident_power_standard_error", scalar(py, o, sigma))?;
    d.set_item("sensor_irradiance", scalar(py, s, |r| Some(r.irradiance)))?;
    let sensor_ppfd = |r: &BandSensorReport| Some(r.photon_irradiance_umol_m2_s);
    d.set_item(
        "sensor_photon_irradiance_umol_m2_s",
        scalar(py, s, sensor_ppfd),
    )?;
    Ok(d)
}

/// One state's columns.
fn state_columns<'py>(py: Python<'py>, state: &StateReport) -> PyResult<Bound<'py, PyDict>> {
    let d = object_columns(py, &state.objects)?;
    d.set_item("time", &state.time)?;
    Ok(d)
}

/// The report `json` (as `Scene.solve` returns it) as columns, read with the GIL released:
/// a dict of the objects' names and columns (`incident_power`, `absorbed_power`,
/// `irradiance`, `direct_power` and `incident_power_standard_error` three numbers a row;
/// `area`, `face`, `illuminance_lux`, `direct_illuminance_lux`, `indirect_illuminance_lux`
/// and `illuminance_standard_error_lux` one), `sensors` (names, `illuminance_lux`,
/// `irradiance`), `bands` and `states` (a dict each, in order) and `red_far_red` (or None).
#[pyfunction]
pub fn report_columns<'py>(py: Python<'py>, json: &str) -> PyResult<Bound<'py, PyDict>> {
    let report: Report = py
        .detach(|| serde_json::from_str(json))
        .map_err(|e| PyValueError::new_err(format!("not a strahl report: {e}")))?;
    let o = &report.objects;
    let d = object_columns(py, o)?;
    d.set_item("names", o.iter().map(|r| &r.name).collect::<Vec<_>>())?;
    d.set_item("face", scalar(py, o, |r| r.face.map(f64::from)))?;
    d.set_item("area", scalar(py, o, |r| r.area))?;
    d.set_item("direct_power", rgb(py, o, |r| r.direct_power))?;
    let sigma = |r: &ObjectReport| r.incident_power_standard_error;
    d.set_item("incident_power_standard_error", rgb(py, o, sigma))?;
    d.set_item("illuminance_lux", scalar(py, o, |r| r.illuminance_lux))?;
    d.set_item(
        "direct_illuminance_lux",
        scalar(py, o, |r| r.direct_illuminance_lux),
    )?;
    let indirect = |r: &ObjectReport| r.indirect_illuminance_lux;
    d.set_item("indirect_illuminance_lux", scalar(py, o, indirect))?;
    let lux_sigma = |r: &ObjectReport| r.illuminance_standard_error_lux;
    d.set_item("illuminance_standard_error_lux", scalar(py, o, lux_sigma))?;
    let s = &report.sensors;
    let sensors = PyDict::new(py);
    sensors.set_item("names", s.iter().map(|r| &r.name).collect::<Vec<_>>())?;
    sensors.set_item(
        "illuminance_lux",
        scalar(py, s, |r| Some(r.illuminance_lux)),
    )?;
    sensors.set_item("irradiance", rgb(py, s, |r| Some(r.irradiance)))?;
    d.set_item("sensors", sensors)?;
    let bands = PyList::empty(py);
    for band in &report.bands {
        bands.append(band_columns(py, band)?)?;
    }
    d.set_item("bands", bands)?;
    let states = PyList::empty(py);
    for state in &report.states {
        states.append(state_columns(py, state)?)?;
    }
    d.set_item("states", states)?;
    match &report.red_far_red {
        Some(ratio) => d.set_item(
            "red_far_red",
            column(py, ratio.objects.iter().map(|r| r.unwrap_or(f64::NAN))),
        )?,
        None => d.set_item("red_far_red", py.None())?,
    }
    Ok(d)
}
