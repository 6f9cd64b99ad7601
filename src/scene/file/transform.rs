//! An object's `transform` list: steps applied to the object in the order written.

use super::error::SceneError;
use super::fields::Table;
use super::format::TransformStep;
use crate::geometry::Transform;
use glam::{Mat4, Vec3};
use toml::Spanned;

/// The object-to-world transform of `steps` (the first step is applied to the object first).
/// Errors name the step, e.g. `objects[1].transform[2]`.
pub(super) fn build_transform(
    table: &Table<'_>,
    steps: &Spanned<Vec<Spanned<TransformStep>>>,
) -> Result<Transform, SceneError> {
    let mut total = Transform::IDENTITY;
    for (i, step) in steps.get_ref().iter().enumerate() {
        let name = format!("transform[{i}]");
        let t = step_transform(step.get_ref()).map_err(|m| table.error(step.span(), &name, m))?;
        total = total.then(&t);
    }
    let det = total.to_world.determinant();
    if !total.to_world.is_finite()
        || !total.to_object.is_finite()
        || !det.is_finite()
        || det.abs() < 1e-20
    {
        return Err(table.error(
            steps.span(),
            "transform",
            "the steps combine to a singular transform",
        ));
    }
    Ok(total)
}

/// One step as a transform, or what is wrong with it.
fn step_transform(step: &TransformStep) -> Result<Transform, String> {
    match step {
        TransformStep::Translate(v) => {
            let v = finite(v.0)?;
            Ok(Transform::translate(v))
        }
        TransformStep::Rotate(r) => {
            let axis = finite(r.axis.0)?;
            if !r.degrees.is_finite() {
                return Err("rotation angle is not finite".into());
            }
            Transform::rotate(axis, r.degrees).ok_or_else(|| "rotation axis is zero".into())
        }
        TransformStep::Scale(s) => {
            let s = finite(s.0)?;
            Transform::scale(s).ok_or_else(|| "singular transform: a scale factor is zero".into())
        }
        TransformStep::Matrix(rows) => {
            let rows = rows.0.map(|row| row.0);
            if rows.iter().flatten().any(|x| !x.is_finite()) {
                return Err("matrix is not finite".into());
            }
            if rows[3] != [0.0, 0.0, 0.0, 1.0] {
                return Err("matrix is not affine: its last row must be [0, 0, 0, 1]".into());
            }
            let m = Mat4::from_cols_array_2d(&rows).transpose();
            Transform::from_matrix(m).ok_or_else(|| "singular matrix (determinant 0)".into())
        }
    }
}

fn finite(v: [f32; 3]) -> Result<Vec3, String> {
    let v = Vec3::from(v);
    if v.is_finite() {
        Ok(v)
    } else {
        Err("vector is not finite".into())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::file::format::Rotation;
    use crate::scene::file::value::{Exact, Triple};

    #[test]
    fn matrix_rows_are_row_major_and_validated() {
        let shift = TransformStep::Matrix(Exact([
            Exact([1.0, 0.0, 0.0, 5.0]),
            Exact([0.0, 1.0, 0.0, 0.0]),
            Exact([0.0, 0.0, 1.0, 0.0]),
            Exact([0.0, 0.0, 0.0, 1.0]),
        ]));
        let t = step_transform(&shift).unwrap();
        assert!((t.point(Vec3::ZERO) - Vec3::new(5.0, 0.0, 0.0)).length() < 1e-6);
        let singular = TransformStep::Matrix(Exact([
            Exact([1.0, 0.0, 0.0, 0.0]),
            Exact([2.0, 0.0, 0.0, 0.0]),
            Exact([0.0, 0.0, 1.0, 0.0]),
            Exact([0.0, 0.0, 0.0, 1.0]),
        ]));
        assert!(step_transform(&singular).unwrap_err().contains("singular"));
        let projective = TransformStep::Matrix(Exact([Exact([1.0, 0.0, 0.0, 0.0]); 4]));
        assert!(step_transform(&projective).unwrap_err().contains("affine"));
        assert!(step_transform(&TransformStep::Scale(Triple([1.0, 0.0, 1.0]))).is_err());
        let zero_axis = TransformStep::Rotate(Rotation {
            axis: Exact([0.0; 3]),
            degrees: 30.0,
        });
        assert!(step_transform(&zero_axis).is_err());
    }
}
