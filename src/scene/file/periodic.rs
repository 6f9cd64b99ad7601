//! The `[periodic]` table: the plot a periodic scene repeats in x and z.

use super::error::SceneError;
use super::fields::Table;
use super::format::PeriodicEntry;
use crate::scene::Periodic;
use toml::Spanned;

/// The plot of `e`: both ranges required, finite, each from a lower to a higher value.
pub(super) fn build_periodic(t: &Table<'_>, e: &PeriodicEntry) -> Result<Periodic, SceneError> {
    let range = |name: &str, v: Option<&Spanned<[f32; 2]>>| {
        let v = v.ok_or_else(|| t.missing(name, "a periodic plot"))?;
        let [lo, hi] = *v.get_ref();
        if lo.is_finite() && hi.is_finite() && lo < hi {
            Ok([lo, hi])
        } else {
            Err(t.error(
                v.span(),
                name,
                format!("must be [low, high] with low below high (got [{lo}, {hi}])"),
            ))
        }
    };
    let x = range("x", e.x.as_ref())?;
    let z = range("z", e.z.as_ref())?;
    Periodic::new(x, z).map_err(|m| t.table_error(m))
}

#[cfg(test)]
mod tests {
    use crate::scene::{Periodic, load_str};
    use std::path::Path;

    #[test]
    fn a_plot_is_read_and_a_bad_range_is_located() {
        let text = "[periodic]\nx = [0, 20]\nz = [-5, 5]\n";
        let scene = load_str(text, "field.toml", Path::new(".")).unwrap();
        assert_eq!(
            scene.periodic,
            Some(Periodic::new([0.0, 20.0], [-5.0, 5.0]).unwrap())
        );
        let text = "[periodic]\nx = [0, 20]\nz = [5, 5]\n";
        let e = load_str(text, "field.toml", Path::new(".")).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("field.toml:3:5: periodic.z: must be"),
            "{e}"
        );
        let text = "[periodic]\nx = [0, 20]\n";
        let e = load_str(text, "field.toml", Path::new(".")).unwrap_err();
        assert!(e.to_string().contains("periodic.z: missing field"), "{e}");
    }
}
