//! The shape of an `[[objects]]` entry (every type but `mesh`), with its validation.

use super::error::SceneError;
use super::fields::Table;
use super::format::{ObjectEntry, ObjectType};
use crate::scene::tessellate::default_polygon_uvs;
use crate::scene::{PolygonMesh, Shape, polygon};
use glam::{Vec2, Vec3};
use std::sync::Arc;

/// A triangle or parallelogram spanned by edges `a` and `b` whose sine of the angle between
/// them is below this counts as degenerate.
const SINE_TOLERANCE: f32 = 1e-6;

/// The shape of `entry`, whose type is not `mesh`; its fields were already checked to belong
/// to the type.
pub(super) fn build_shape(t: &Table<'_>, e: &ObjectEntry) -> Result<Shape, SceneError> {
    let kind = *e.kind.get_ref();
    let why = format!("type {}", kind.name());
    let why = why.as_str();
    let shape = match kind {
        ObjectType::Triangle | ObjectType::Polygon | ObjectType::Quad => {
            return planar(t, e, kind);
        }
        ObjectType::Parallelogram => {
            let origin = t.required_vec3("origin", e.origin.as_ref(), why)?;
            let edge_u = t.required_vec3("edge_u", e.edge_u.as_ref(), why)?;
            let edge_v = t.required_vec3("edge_v", e.edge_v.as_ref(), why)?;
            if degenerate(edge_u, edge_v) {
                return Err(
                    t.table_error("parallelogram has zero area (edges are parallel or zero)")
                );
            }
            Shape::Parallelogram {
                origin,
                edge_u,
                edge_v,
            }
        }
        ObjectType::Mesh => return Err(t.table_error("a mesh has no analytic shape")),
        ObjectType::Sphere => Shape::Sphere {
            center: t.vec3("center", e.center.as_ref())?.unwrap_or(Vec3::ZERO),
            radius: positive(t, "radius", e, e.radius.as_ref(), why)?,
        },
        ObjectType::Box => {
            let min = t.required_vec3("min", e.min.as_ref(), why)?;
            let max = t.required_vec3("max", e.max.as_ref(), why)?;
            if !max.cmpgt(min).all() {
                let span = e.max.as_ref().map_or(t.span.clone(), |s| s.span());
                return Err(t.error(span, "max", "every coordinate of max must exceed min"));
            }
            Shape::Box { min, max }
        }
        ObjectType::Cylinder => Shape::Cylinder {
            base: t.required_vec3("base", e.base.as_ref(), why)?,
            top: t.required_vec3("top", e.top.as_ref(), why)?,
            radius: positive(t, "radius", e, e.radius.as_ref(), why)?,
            caps: e.caps.as_ref().is_none_or(|c| *c.get_ref()),
        },
        ObjectType::Cone => Shape::Cone {
            base: t.required_vec3("base", e.base.as_ref(), why)?,
            apex: t.required_vec3("apex", e.apex.as_ref(), why)?,
            radius: positive(t, "radius", e, e.radius.as_ref(), why)?,
            cap: e.cap.as_ref().is_none_or(|c| *c.get_ref()),
        },
        ObjectType::Frustum => {
            let top_radius = t.required_number("top_radius", e.top_radius.as_ref(), why)?;
            if top_radius < 0.0 {
                let span = e.top_radius.as_ref().map_or(t.span.clone(), |s| s.span());
                return Err(t.error(span, "top_radius", "radius must not be negative"));
            }
            Shape::Frustum {
                base: t.required_vec3("base", e.base.as_ref(), why)?,
                top: t.required_vec3("top", e.top.as_ref(), why)?,
                base_radius: positive(t, "base_radius", e, e.base_radius.as_ref(), why)?,
                top_radius,
                caps: e.caps.as_ref().is_none_or(|c| *c.get_ref()),
            }
        }
        ObjectType::Plane => {
            let normal = t.required_vec3("normal", e.normal.as_ref(), why)?;
            if normal.length_squared() == 0.0 {
                let span = e.normal.as_ref().map_or(t.span.clone(), |s| s.span());
                return Err(t.error(span, "normal", "normal is zero"));
            }
            Shape::Plane {
                point: t.vec3("point", e.point.as_ref())?.unwrap_or(Vec3::ZERO),
                normal,
            }
        }
    };
    let has_axis = matches!(
        kind,
        ObjectType::Cylinder | ObjectType::Cone | ObjectType::Frustum
    );
    if has_axis && shape.analytic().is_none() {
        return Err(t.table_error(format!(
            "degenerate {}: its axis has zero length",
            kind.name()
        )));
    }
    Ok(shape)
}

/// A required number that must be > 0.
fn positive(
    t: &Table<'_>,
    name: &str,
    e: &ObjectEntry,
    v: Option<&toml::Spanned<f32>>,
    why: &str,
) -> Result<f32, SceneError> {
    let r = t.required_number(name, v, why)?;
    if r > 0.0 {
        Ok(r)
    } else {
        let span = v.map_or(e.kind.span(), |s| s.span());
        Err(t.error(span, name, format!("{name} must be > 0, got {r}")))
    }
}

/// True when the edges `a`, `b` span (almost) no area.
fn degenerate(a: Vec3, b: Vec3) -> bool {
    let sine_area = a.cross(b).length();
    sine_area.is_nan() || sine_area <= SINE_TOLERANCE * a.length() * b.length()
}

/// Triangles, polygons and quads from `vertices` and optional `uvs`.
fn planar(t: &Table<'_>, e: &ObjectEntry, kind: ObjectType) -> Result<Shape, SceneError> {
    let why = format!("type {}", kind.name());
    let Some(spanned) = e.vertices.as_ref() else {
        return Err(t.missing("vertices", &why));
    };
    let vertices: Vec<Vec3> = spanned.get_ref().iter().map(|v| Vec3::from(v.0)).collect();
    let span = spanned.span();
    if vertices.iter().any(|v| !v.is_finite()) {
        return Err(t.error(span, "vertices", "a vertex is not finite"));
    }
    let expected = match kind {
        ObjectType::Triangle => Some(3),
        ObjectType::Quad => Some(4),
        _ => None,
    };
    if let Some(n) = expected.filter(|&n| n != vertices.len()) {
        return Err(t.error(
            span,
            "vertices",
            format!(
                "a {} needs {n} vertices, got {}",
                kind.name(),
                vertices.len()
            ),
        ));
    }
    let shape = polygon::classify(&vertices).map_err(|m| t.error(span.clone(), "vertices", m))?;
    if let polygon::Shape::NonPlanar {
        corner,
        distance,
        relative,
    } = shape
    {
        eprintln!(
            "warning: {}",
            t.error(
                span.clone(),
                "vertices",
                format!(
                    "the {} is not planar (vertex {corner} is {distance:.3e} from its plane, \
                     {:.1e} of its size; tolerance {:.0e}): split into triangles",
                    kind.name(),
                    relative,
                    polygon::PLANARITY_TOLERANCE
                )
            )
        );
    }
    let uvs: Option<Vec<Vec2>> = match e.uvs.as_ref() {
        Some(u) => {
            let uvs: Vec<Vec2> = u.get_ref().iter().map(|p| Vec2::from(p.0)).collect();
            if uvs.len() != vertices.len() {
                return Err(t.error(
                    u.span(),
                    "uvs",
                    format!(
                        "{} texture coordinates for {} vertices",
                        uvs.len(),
                        vertices.len()
                    ),
                ));
            }
            if uvs.iter().any(|p| !p.is_finite()) {
                return Err(t.error(u.span(), "uvs", "a texture coordinate is not finite"));
            }
            Some(uvs)
        }
        None => None,
    };
    Ok(match (kind, shape) {
        (ObjectType::Triangle, _) => Shape::Triangle {
            vertices: [vertices[0], vertices[1], vertices[2]],
            uvs: uvs.map(|u| [u[0], u[1], u[2]]),
        },
        (_, polygon::Shape::Convex) => Shape::Polygon { vertices, uvs },
        // Concave or bent: the same polygon as triangles.
        _ => {
            let triangles = polygon::triangulate(&vertices);
            let uvs = uvs.unwrap_or_else(|| default_polygon_uvs(&vertices));
            Shape::Mesh(Arc::new(PolygonMesh {
                indices: triangles.iter().flatten().map(|&i| i as u32).collect(),
                face_sizes: vec![3; triangles.len()],
                positions: vertices,
                uvs: Some(uvs),
                ..PolygonMesh::default()
            }))
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degenerate_edges_are_detected_relative_to_their_length() {
        assert!(degenerate(Vec3::X, Vec3::X * 3.0));
        assert!(degenerate(Vec3::ZERO, Vec3::Y));
        assert!(!degenerate(Vec3::X * 1e-3, Vec3::Y * 1e-3));
    }
}
