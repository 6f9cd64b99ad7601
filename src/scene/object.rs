//! Scene objects: a shape, where it is (transform), what it is made of (material) and a name.

use super::{MaterialId, PolygonMesh};
use crate::geometry::Transform;
use crate::geometry::frustum::UnitFrustum;
use glam::{Mat4, Vec2, Vec3};
use std::sync::Arc;

/// One object of the scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    /// Name used in reports; `object-<index>` when absent.
    pub name: Option<String>,
    /// The geometry, in object space.
    pub shape: Shape,
    /// Object-to-world transform.
    pub transform: Transform,
    /// Material (for meshes: of the faces without a material of their own).
    pub material: MaterialId,
    /// Report every face of a mesh separately (for leaves in plant models).
    pub per_face: bool,
}

impl Object {
    /// The materials of its surface: a mesh's faces' own, or the object's.
    pub fn materials(&self) -> &[MaterialId] {
        match &self.shape {
            Shape::Mesh(mesh) => mesh.face_materials.as_deref(),
            _ => None,
        }
        .unwrap_or(std::slice::from_ref(&self.material))
    }
}

/// The geometric primitives. Planar ones (triangle, polygon, parallelogram, mesh) are traced
/// as triangles; the others are intersected analytically in their object space.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A single triangle, front side counter-clockwise.
    Triangle {
        /// The three corners.
        vertices: [Vec3; 3],
        /// Texture coordinates per corner; default `(0,0), (1,0), (0,1)`.
        uvs: Option<[Vec2; 3]>,
    },
    /// A planar convex polygon (quad, pentagon, …), front side counter-clockwise.
    Polygon {
        /// The corners in order.
        vertices: Vec<Vec3>,
        /// Texture coordinates per corner; quads default to the unit square.
        uvs: Option<Vec<Vec2>>,
    },
    /// The parallelogram `origin + s·edge_u + t·edge_v`, `s, t ∈ [0, 1]`, with `(u, v) = (s, t)`;
    /// its front side is the side `edge_u × edge_v` points to.
    Parallelogram {
        /// First corner.
        origin: Vec3,
        /// First edge.
        edge_u: Vec3,
        /// Second edge.
        edge_v: Vec3,
    },
    /// A polygon mesh.
    Mesh(Arc<PolygonMesh>),
    /// A sphere.
    Sphere {
        /// Centre.
        center: Vec3,
        /// Radius (> 0).
        radius: f32,
    },
    /// An axis-aligned box (before the transform).
    Box {
        /// Lower corner.
        min: Vec3,
        /// Upper corner.
        max: Vec3,
    },
    /// A cylinder from `base` to `top`.
    Cylinder {
        /// Centre of the bottom disc.
        base: Vec3,
        /// Centre of the top disc.
        top: Vec3,
        /// Radius (> 0).
        radius: f32,
        /// Whether the two discs close the cylinder.
        caps: bool,
    },
    /// A cone from a disc at `base` to the point `apex`.
    Cone {
        /// Centre of the base disc.
        base: Vec3,
        /// Tip of the cone.
        apex: Vec3,
        /// Base radius (> 0).
        radius: f32,
        /// Whether the base disc closes the cone.
        cap: bool,
    },
    /// A truncated cone (frustum) from `base` to `top`.
    Frustum {
        /// Centre of the bottom disc.
        base: Vec3,
        /// Centre of the top disc.
        top: Vec3,
        /// Radius at `base` (> 0).
        base_radius: f32,
        /// Radius at `top` (≥ 0).
        top_radius: f32,
        /// Whether the discs close the frustum.
        caps: bool,
    },
    /// An infinite plane through `point` with front-side normal `normal`.
    Plane {
        /// A point on the plane.
        point: Vec3,
        /// Normal of the front side.
        normal: Vec3,
    },
}

/// The analytic primitives, each in its canonical object space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AnalyticKind {
    /// Unit sphere at the origin.
    Sphere,
    /// Unit cube `[0, 1]³`.
    Cube,
    /// Unit frustum around the z axis (also cylinders and cones).
    Frustum(UnitFrustum),
    /// The plane `z = 0`.
    Plane,
}

impl Shape {
    /// For analytic shapes: the canonical primitive and the map from its canonical space to
    /// this shape's object space. `None` for planar shapes or degenerate parameters.
    pub fn analytic(&self) -> Option<(AnalyticKind, Transform)> {
        match *self {
            Shape::Sphere { center, radius } => Some((
                AnalyticKind::Sphere,
                Transform::from_matrix(
                    Mat4::from_translation(center) * Mat4::from_scale(Vec3::splat(radius)),
                )?,
            )),
            Shape::Box { min, max } => Some((
                AnalyticKind::Cube,
                Transform::from_matrix(Mat4::from_translation(min) * Mat4::from_scale(max - min))?,
            )),
            Shape::Cylinder {
                base,
                top,
                radius,
                caps,
            } => frustum(base, top, radius, radius, caps, caps),
            Shape::Cone {
                base,
                apex,
                radius,
                cap,
            } => frustum(base, apex, radius, 0.0, cap, false),
            Shape::Frustum {
                base,
                top,
                base_radius,
                top_radius,
                caps,
            } => frustum(base, top, base_radius, top_radius, caps, caps),
            Shape::Plane { point, normal } => {
                let n = normal.try_normalize()?;
                let (s, t) = n.any_orthonormal_pair();
                let m = Mat4::from_cols(
                    s.extend(0.0),
                    t.extend(0.0),
                    n.extend(0.0),
                    point.extend(1.0),
                );
                Some((AnalyticKind::Plane, Transform::from_matrix(m)?))
            }
            _ => None,
        }
    }

    /// True for shapes intersected analytically (sphere, box, cylinder, cone, frustum, plane).
    pub fn is_analytic(&self) -> bool {
        !matches!(
            self,
            Shape::Triangle { .. }
                | Shape::Polygon { .. }
                | Shape::Parallelogram { .. }
                | Shape::Mesh(_)
        )
    }

    /// True for curved analytic shapes (sphere, cylinder, cone, frustum), whose polygon
    /// meshes only approximate them.
    pub fn is_curved(&self) -> bool {
        matches!(
            self,
            Shape::Sphere { .. }
                | Shape::Cylinder { .. }
                | Shape::Cone { .. }
                | Shape::Frustum { .. }
        )
    }

    /// Short name of the shape kind.
    pub fn kind_name(&self) -> &'static str {
        match self {
            Shape::Triangle { .. } => "triangle",
            Shape::Polygon { .. } => "polygon",
            Shape::Parallelogram { .. } => "parallelogram",
            Shape::Mesh(_) => "mesh",
            Shape::Sphere { .. } => "sphere",
            Shape::Box { .. } => "box",
            Shape::Cylinder { .. } => "cylinder",
            Shape::Cone { .. } => "cone",
            Shape::Frustum { .. } => "frustum",
            Shape::Plane { .. } => "plane",
        }
    }
}

/// The map from the unit frustum to the frustum from `base` to `top` with radii `r0`, `r1`.
fn frustum(
    base: Vec3,
    top: Vec3,
    r0: f32,
    r1: f32,
    bottom_cap: bool,
    top_cap: bool,
) -> Option<(AnalyticKind, Transform)> {
    let axis = top - base;
    let w = axis.try_normalize()?;
    if r0.is_nan() || r0 <= 0.0 || r1.is_nan() || r1 < 0.0 {
        return None;
    }
    let (u, v) = w.any_orthonormal_pair();
    let m = Mat4::from_cols(
        (u * r0).extend(0.0),
        (v * r0).extend(0.0),
        axis.extend(0.0),
        base.extend(1.0),
    );
    let unit = UnitFrustum {
        top_radius: r1 / r0,
        bottom_cap,
        top_cap,
    };
    Some((AnalyticKind::Frustum(unit), Transform::from_matrix(m)?))
}
