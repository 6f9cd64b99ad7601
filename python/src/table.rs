//! A report's tables read column by column for numpy (`strahl.Result`): the JSON parsed once
//! here, each column handed over as little-endian `f64` bytes. On the Helios field's report
//! (160,001 rows, 93 MB) Python's own `json.loads` and row-by-row columns took 5 s.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyByteArray;
use serde_json::Value;

/// A report (`strahl solve --report` JSON), parsed.
#[pyclass(frozen, module = "strahl._strahl")]
pub struct ReportTable {
    report: Value,
}

impl ReportTable {
    /// The array at JSON pointer `rows` (empty where there is none).
    fn rows_at(&self, rows: &str) -> &[Value] {
        self.report
            .pointer(rows)
            .and_then(Value::as_array)
            .map_or(&[], Vec::as_slice)
    }
}

/// Field `key` of `row`, or the row itself for an empty key.
fn field<'v>(row: &'v Value, key: &str) -> &'v Value {
    if key.is_empty() {
        row
    } else {
        row.get(key).unwrap_or(&Value::Null)
    }
}

#[pymethods]
impl ReportTable {
    /// Parses the report `json` (the GIL released meanwhile).
    #[new]
    fn new(py: Python<'_>, json: &str) -> PyResult<Self> {
        let report = py
            .detach(|| serde_json::from_str(json))
            .map_err(|e| PyValueError::new_err(format!("not a strahl report: {e}")))?;
        Ok(ReportTable { report })
    }

    /// Whether the report has a value at JSON pointer `pointer` (`/red_far_red`).
    fn has(&self, pointer: &str) -> bool {
        self.report.pointer(pointer).is_some_and(|v| !v.is_null())
    }

    /// How many rows the array at JSON pointer `rows` holds (0 where there is none).
    fn rows(&self, rows: &str) -> usize {
        self.rows_at(rows).len()
    }

    /// Field `key` of every row of the array at `rows` (`""`: the rows themselves), `width`
    /// numbers a row — a number, or an array of `width` numbers — NaN where it is null or
    /// absent; as little-endian `f64` bytes, row after row.
    fn numbers<'py>(
        &self,
        py: Python<'py>,
        rows: &str,
        key: &str,
        width: usize,
    ) -> PyResult<Bound<'py, PyByteArray>> {
        let rows = self.rows_at(rows);
        let mut bytes = Vec::with_capacity(rows.len() * width * 8);
        for (k, row) in rows.iter().enumerate() {
            let value = field(row, key);
            let numbers: Vec<f64> = match value {
                Value::Null => vec![f64::NAN; width],
                Value::Number(n) if width == 1 => n.as_f64().into_iter().collect(),
                Value::Array(items) if items.len() == width => {
                    items.iter().filter_map(Value::as_f64).collect()
                }
                _ => Vec::new(),
            };
            if numbers.len() != width {
                return Err(PyValueError::new_err(format!(
                    "row {k}: '{key}' is {value}, not {width} number(s)"
                )));
            }
            bytes.extend(numbers.iter().flat_map(|v| v.to_le_bytes()));
        }
        Ok(PyByteArray::new(py, &bytes))
    }

    /// Field `key` of every row of the array at `rows`, a string each.
    fn strings(&self, rows: &str, key: &str) -> PyResult<Vec<String>> {
        self.rows_at(rows)
            .iter()
            .enumerate()
            .map(|(k, row)| match field(row, key) {
                Value::String(s) => Ok(s.clone()),
                other => Err(PyValueError::new_err(format!(
                    "row {k}: '{key}' is {other}, not a string"
                ))),
            })
            .collect()
    }
}
