//! A mesh object's `placements`: where copies of it stand, inline or from a CSV file, one
//! transform each, applied after the object's own `transform`.

use super::error::SceneError;
use super::fields::Table;
use super::number_rows::read_number_rows;
use crate::geometry::Transform;
use glam::{Mat4, Vec3, Vec4};
use std::path::Path;
use toml::{Spanned, Value};

/// What one placement may hold, for error messages.
const PLACEMENT_FORMS: &str = "a placement is x, y, z (a translation), x, y, z, degrees (and a \
     turn about the y axis first), x, y, z, degrees, scale (and a uniform scale before that), \
     or the 12 numbers of a 3 × 4 matrix, row by row";

/// The transforms of `placements` (inline rows, or the name of a CSV file of rows relative
/// to `base_dir`), each preceded by `own` (the object's `transform`).
pub(super) fn build_placements(
    t: &Table<'_>,
    placements: &Spanned<Value>,
    base_dir: &Path,
    own: &Transform,
) -> Result<Vec<Transform>, SceneError> {
    let error = |message: String| t.error(placements.span(), "placements", message);
    let rows: Vec<(String, Vec<f64>)> = match placements.get_ref() {
        Value::String(file) => {
            let path = base_dir.join(file);
            let rows = read_number_rows(&path, "placements", "numbers").map_err(error)?;
            let shown = path.display();
            rows.into_iter()
                .map(|(line, numbers)| (format!("{shown}:{line}"), numbers))
                .collect()
        }
        Value::Array(rows) => rows
            .iter()
            .enumerate()
            .map(|(i, row)| {
                let numbers = row.as_array().and_then(|r| {
                    r.iter()
                        .map(|x| x.as_float().or_else(|| x.as_integer().map(|i| i as f64)))
                        .collect::<Option<Vec<f64>>>()
                });
                numbers
                    .map(|n| (format!("placement {i}"), n))
                    .ok_or_else(|| error(format!("placement {i} is not a list of numbers")))
            })
            .collect::<Result<_, _>>()?,
        _ => {
            return Err(error(
                "placements are [[x, y, z], …] or the name of a CSV file of such rows".into(),
            ));
        }
    };
    if rows.is_empty() {
        return Err(error("placements must list at least one placement".into()));
    }
    rows.iter()
        .map(|(place, numbers)| {
            let placed = placement(numbers).map_err(|m| error(format!("{place}: {m}")))?;
            Ok(own.then(&placed))
        })
        .collect()
}

/// The transform of one row of numbers.
fn placement(n: &[f64]) -> Result<Transform, String> {
    if n.iter().any(|x| !x.is_finite()) {
        return Err("numbers must be finite".into());
    }
    let v = |i: usize| n[i] as f32;
    let matrix = match n.len() {
        3..=5 => {
            let scale = if n.len() == 5 { v(4) } else { 1.0 };
            let turn = if n.len() >= 4 { v(3).to_radians() } else { 0.0 };
            Mat4::from_translation(Vec3::new(v(0), v(1), v(2)))
                * Mat4::from_rotation_y(turn)
                * Mat4::from_scale(Vec3::splat(scale))
        }
        12 => Mat4::from_cols(
            Vec4::new(v(0), v(4), v(8), 0.0),
            Vec4::new(v(1), v(5), v(9), 0.0),
            Vec4::new(v(2), v(6), v(10), 0.0),
            Vec4::new(v(3), v(7), v(11), 1.0),
        ),
        _ => return Err(format!("{} numbers; {PLACEMENT_FORMS}", n.len())),
    };
    let det = matrix.determinant();
    if !(det.is_finite() && det.abs() >= 1e-20) {
        return Err("the placement is singular (a zero scale?)".into());
    }
    Transform::from_matrix(matrix).ok_or_else(|| "the placement is singular".to_string())
}
