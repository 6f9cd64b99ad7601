//! Reading checked values out of one table of the scene file (a material, an object, a
//! light, the camera), with errors that name the table's path and the field.

use super::error::{SceneError, Source};
use super::value::{Coords, Triple};
use crate::color::Rgb;
use glam::Vec3;
use std::ops::Range;
use toml::Spanned;

pub(super) use crate::scene::MAX_COLOUR;

/// One table of the scene file: its path (`objects[2]`) and span.
#[derive(Clone, Debug)]
pub(super) struct Table<'a> {
    /// The scene text.
    pub src: Source<'a>,
    /// Dotted path of the table.
    pub path: String,
    /// Span of the table (its header or inline table).
    pub span: Range<usize>,
}

impl<'a> Table<'a> {
    /// A table at `path` spanning `span`.
    pub fn new(src: Source<'a>, path: impl Into<String>, span: Range<usize>) -> Self {
        Table {
            src,
            path: path.into(),
            span,
        }
    }

    /// The path of field `name` of this table (the table itself when `name` is empty).
    pub fn field(&self, name: &str) -> String {
        if name.is_empty() {
            self.path.clone()
        } else {
            format!("{}.{name}", self.path)
        }
    }

    /// An error about field `name` located at `span`.
    pub fn error(&self, span: Range<usize>, name: &str, message: impl ToString) -> SceneError {
        self.src.error(span, &self.field(name), message)
    }

    /// An error about the whole table, located at its header.
    pub fn table_error(&self, message: impl ToString) -> SceneError {
        self.src.error(self.span.clone(), &self.path, message)
    }

    /// The error for a missing required field `name`; `why` completes "required by …".
    pub fn missing(&self, name: &str, why: &str) -> SceneError {
        self.src.error(
            self.span.clone(),
            &self.field(name),
            format!("missing field (required by {why})"),
        )
    }

    /// A finite number, if given.
    pub fn number(&self, name: &str, v: Option<&Spanned<f32>>) -> Result<Option<f32>, SceneError> {
        match v {
            Some(s) if !s.get_ref().is_finite() => {
                Err(self.error(s.span(), name, "number is not finite"))
            }
            Some(s) => Ok(Some(*s.get_ref())),
            None => Ok(None),
        }
    }

    /// A finite number, required.
    pub fn required_number(
        &self,
        name: &str,
        v: Option<&Spanned<f32>>,
        why: &str,
    ) -> Result<f32, SceneError> {
        self.number(name, v)?.ok_or_else(|| self.missing(name, why))
    }

    /// A vector of finite numbers, if given.
    pub fn vec3(
        &self,
        name: &str,
        v: Option<&Spanned<Coords>>,
    ) -> Result<Option<Vec3>, SceneError> {
        match v {
            Some(s) => {
                let p = Vec3::from(s.get_ref().0);
                if p.is_finite() {
                    Ok(Some(p))
                } else {
                    Err(self.error(s.span(), name, "vector is not finite"))
                }
            }
            None => Ok(None),
        }
    }

    /// A vector of finite numbers, required.
    pub fn required_vec3(
        &self,
        name: &str,
        v: Option<&Spanned<Coords>>,
        why: &str,
    ) -> Result<Vec3, SceneError> {
        self.vec3(name, v)?.ok_or_else(|| self.missing(name, why))
    }

    /// A colour with every channel finite and ≥ 0, if given.
    pub fn rgb(&self, name: &str, v: Option<&Spanned<Triple>>) -> Result<Option<Rgb>, SceneError> {
        match v {
            Some(s) => {
                let c = Rgb::from(s.get_ref().0);
                if !c.is_finite() {
                    Err(self.error(s.span(), name, "colour is not finite"))
                } else if c.r < 0.0 || c.g < 0.0 || c.b < 0.0 {
                    Err(self.error(s.span(), name, "colour must not be negative"))
                } else if c.max_channel() > MAX_COLOUR {
                    Err(self.error(
                        s.span(),
                        name,
                        format!(
                            "colour {:e} is beyond {MAX_COLOUR:e}, where the renderers' 32-bit sums \
                             overflow: choose other units",
                            c.max_channel()
                        ),
                    ))
                } else {
                    Ok(Some(c))
                }
            }
            None => Ok(None),
        }
    }

    /// Rejects every field in `present` that is not in `allowed`; `kind` names the type.
    pub fn only_fields(
        &self,
        present: &[(&'static str, Range<usize>)],
        allowed: &[&str],
        kind: &str,
    ) -> Result<(), SceneError> {
        match present.iter().find(|(name, _)| !allowed.contains(name)) {
            Some((name, span)) => Err(self.error(
                span.clone(),
                name,
                format!(
                    "field does not apply to type {kind} (its fields: {})",
                    allowed.join(", ")
                ),
            )),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_table_and_field() {
        let src = Source {
            text: "[x]\nr = nan\n",
            file: "f.toml",
        };
        let t = Table::new(src, "objects[1]", 0..3);
        let nan = Spanned::new(8..11, f32::NAN);
        let e = t.number("radius", Some(&nan)).unwrap_err();
        assert_eq!(
            e.to_string(),
            "f.toml:2:5: objects[1].radius: number is not finite"
        );
        let e = t.missing("radius", "type sphere");
        assert_eq!(
            e.to_string(),
            "f.toml:1:1: objects[1].radius: missing field (required by type sphere)"
        );
        let neg = Spanned::new(8..11, Triple([0.1, -0.2, 0.0]));
        assert!(t.rgb("diffuse", Some(&neg)).is_err());
        let present = [("radius", 4..5)];
        assert!(t.only_fields(&present, &["min", "max"], "box").is_err());
        assert!(t.only_fields(&present, &["radius"], "sphere").is_ok());
    }
}
