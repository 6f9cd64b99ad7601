//! Every shape as a polygon mesh: planar shapes exactly, curved analytic shapes approximated
//! with a chosen number of segments around their axis. Used where a shape must be a set of
//! flat faces: radiosity patches and emissive analytic shapes (sampled as area lights).

use super::{AnalyticKind, PolygonMesh, Shape};
use crate::geometry::frustum::UnitFrustum;
use glam::{Vec2, Vec3};
use std::borrow::Cow;
use std::f32::consts::PI;

impl Shape {
    /// This shape as a polygon mesh in object space, for the methods that light meshes in
    /// its place (radiosity patches, points spread over surfaces, emitters sampled by
    /// triangle). Planar shapes are exact (with default texture coordinates where none are
    /// given: the unit square for quads and parallelograms, `(0,0), (1,0), (0,1)` for
    /// triangles, the bounding rectangle in the polygon's plane otherwise). Curved shapes use
    /// `segments` divisions around their axis (at least 3), their facets pushed out from the
    /// axis (spheres: from the centre) until the mesh's area is the shape's in its canonical
    /// frame: a polyhedron with its corners on the surface would be smaller by 3 % at 16
    /// segments, and so would be the light it catches; one as large catches on average what
    /// the shape catches (a convex body's shadow, averaged over directions, is a quarter of its
    /// area). Boxes are exact. An infinite plane has no mesh (`Err`).
    pub fn to_mesh(&self, segments: u32) -> Result<Cow<'_, PolygonMesh>, String> {
        self.mesh(segments, Facets::AsLarge)
    }

    /// This shape as a polygon mesh in object space with the corners of a curved shape's
    /// facets on its surface (its area below the shape's by a share falling as 1/segments²);
    /// otherwise as [`Shape::to_mesh`].
    pub fn to_inscribed_mesh(&self, segments: u32) -> Result<Cow<'_, PolygonMesh>, String> {
        self.mesh(segments, Facets::Inscribed)
    }

    fn mesh(&self, segments: u32, facets: Facets) -> Result<Cow<'_, PolygonMesh>, String> {
        let segments = segments.max(3);
        Ok(match self {
            Shape::Mesh(m) => Cow::Borrowed(m.as_ref()),
            Shape::Triangle { vertices, uvs } => {
                let uvs = uvs.map_or_else(|| vec![Vec2::ZERO, Vec2::X, Vec2::Y], |u| u.to_vec());
                Cow::Owned(single_face(vertices.to_vec(), uvs))
            }
            Shape::Polygon { vertices, uvs } => {
                let uvs = uvs.clone().unwrap_or_else(|| default_polygon_uvs(vertices));
                Cow::Owned(single_face(vertices.clone(), uvs))
            }
            Shape::Parallelogram {
                origin,
                edge_u,
                edge_v,
            } => {
                let (o, u, v) = (*origin, *edge_u, *edge_v);
                Cow::Owned(single_face(
                    vec![o, o + u, o + u + v, o + v],
                    unit_square().to_vec(),
                ))
            }
            Shape::Plane { .. } => return Err("an infinite plane cannot be tessellated".into()),
            _ => {
                let (kind, placement) = self
                    .analytic()
                    .ok_or_else(|| format!("degenerate {}", self.kind_name()))?;
                let mut mesh = match kind {
                    AnalyticKind::Sphere => unit_sphere(segments, facets),
                    AnalyticKind::Cube => unit_cube(),
                    AnalyticKind::Frustum(f) => {
                        // Its radius over its height once placed: the side's share of the
                        // area depends on it.
                        let origin = placement.point(Vec3::ZERO);
                        let radius = placement.point(Vec3::X).distance(origin);
                        let aspect = radius / placement.point(Vec3::Z).distance(origin);
                        unit_frustum(segments, f, aspect, facets)
                    }
                    AnalyticKind::Plane => unreachable!("planes return early"),
                };
                for p in &mut mesh.positions {
                    *p = placement.point(*p);
                }
                if let Some(normals) = &mut mesh.normals {
                    for n in normals {
                        *n = placement.normal(*n).normalize_or_zero();
                    }
                }
                Cow::Owned(mesh)
            }
        })
    }
}

/// Where a curved shape's facets lie.
#[derive(Clone, Copy)]
enum Facets {
    /// Their corners on the surface.
    Inscribed,
    /// Pushed out until the mesh is as large as the surface.
    AsLarge,
}

fn unit_square() -> [Vec2; 4] {
    [Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y]
}

fn single_face(positions: Vec<Vec3>, uvs: Vec<Vec2>) -> PolygonMesh {
    let n = positions.len() as u32;
    PolygonMesh {
        positions,
        uvs: Some(uvs),
        indices: (0..n).collect(),
        face_sizes: vec![n],
        ..Default::default()
    }
}

/// Unit square for quads, otherwise the polygon's bounding rectangle in its own plane.
pub(crate) fn default_polygon_uvs(vertices: &[Vec3]) -> Vec<Vec2> {
    if vertices.len() == 4 {
        return unit_square().to_vec();
    }
    let normal = polygon_normal(vertices);
    let s = (vertices[1] - vertices[0]).normalize_or_zero();
    let t = normal.cross(s);
    let coords: Vec<Vec2> = vertices
        .iter()
        .map(|p| Vec2::new((p - vertices[0]).dot(s), (p - vertices[0]).dot(t)))
        .collect();
    let lo = coords
        .iter()
        .fold(Vec2::splat(f32::INFINITY), |a, &c| a.min(c));
    let hi = coords
        .iter()
        .fold(Vec2::splat(f32::NEG_INFINITY), |a, &c| a.max(c));
    let size = (hi - lo).max(Vec2::splat(f32::MIN_POSITIVE));
    coords.iter().map(|&c| (c - lo) / size).collect()
}

/// Unit normal of a polygon by Newell's method (robust for slightly non-planar input).
pub fn polygon_normal(vertices: &[Vec3]) -> Vec3 {
    let n = vertices.len();
    (0..n)
        .map(|i| vertices[i].cross(vertices[(i + 1) % n]))
        .sum::<Vec3>()
        .normalize_or_zero()
}

/// Area of a planar polygon (half the length of the Newell vector).
pub fn polygon_area(vertices: &[Vec3]) -> f32 {
    let n = vertices.len();
    0.5 * (0..n)
        .map(|i| vertices[i].cross(vertices[(i + 1) % n]))
        .sum::<Vec3>()
        .length()
}

/// The unit sphere's mesh of `segments` around its axis and half as many rings; as large as
/// the sphere (4π) with `Facets::AsLarge`. Its normals are the sphere's at the corners.
fn unit_sphere(segments: u32, facets: Facets) -> PolygonMesh {
    let rings = (segments / 2).max(2);
    let mut mesh = PolygonMesh {
        normals: Some(Vec::new()),
        uvs: Some(Vec::new()),
        ..Default::default()
    };
    for ring in 0..=rings {
        let v = ring as f32 / rings as f32;
        let theta = PI * (1.0 - v);
        // sin(π) is 8.7·10⁻⁸ in single precision: the poles are set exactly, so the facets
        // around a pole meet in one point.
        let (sin_theta, cos_theta) = match ring {
            0 => (0.0, -1.0),
            r if r == rings => (0.0, 1.0),
            _ => theta.sin_cos(),
        };
        for seg in 0..=segments {
            let u = seg as f32 / segments as f32;
            // The seam's last column is the first one again (at the same point; u = 1).
            let phi = 2.0 * PI * ((seg % segments) as f32 / segments as f32 - 0.5);
            let p = Vec3::new(sin_theta * phi.cos(), cos_theta, sin_theta * phi.sin());
            mesh.positions.push(p);
            mesh.normals.as_mut().unwrap().push(p);
            mesh.uvs.as_mut().unwrap().push(Vec2::new(u, v));
        }
    }
    let row = segments + 1;
    for ring in 0..rings {
        for seg in 0..segments {
            let a = ring * row + seg;
            let (b, c, d) = (a + 1, a + row + 1, a + row);
            // Counter-clockwise seen from outside; degenerate pole quads become triangles.
            let face: Vec<u32> = if ring == 0 {
                vec![a, c, d]
            } else if ring == rings - 1 {
                vec![a, b, d]
            } else {
                vec![a, b, c, d]
            };
            let face: Vec<u32> = face.into_iter().rev().collect();
            mesh.face_sizes.push(face.len() as u32);
            mesh.indices.extend(face);
        }
    }
    if let Facets::AsLarge = facets {
        let scale = (4.0 * std::f64::consts::PI / mesh_area(&mesh)).sqrt() as f32;
        for p in &mut mesh.positions {
            *p *= scale;
        }
    }
    mesh
}

/// The area of `mesh`, in its own units.
fn mesh_area(mesh: &PolygonMesh) -> f64 {
    mesh.faces()
        .map(|face| {
            let corners: Vec<Vec3> = face.iter().map(|&i| mesh.positions[i as usize]).collect();
            f64::from(polygon_area(&corners))
        })
        .sum()
}

fn unit_cube() -> PolygonMesh {
    let mut mesh = PolygonMesh::default();
    let mut uvs = Vec::new();
    for axis in 0..3 {
        for side in 0..2 {
            let (ua, va) = ((axis + 1) % 3, (axis + 2) % 3);
            let corner = |u: f32, v: f32| {
                let mut p = Vec3::ZERO;
                p[axis] = side as f32;
                p[ua] = u;
                p[va] = v;
                p
            };
            let base = mesh.positions.len() as u32;
            let mut quad = [
                corner(0.0, 0.0),
                corner(1.0, 0.0),
                corner(1.0, 1.0),
                corner(0.0, 1.0),
            ];
            let mut quad_uvs = unit_square();
            // (u, v) axes are cyclic, so their cross product points along +axis; flip the low face.
            if side == 0 {
                quad.reverse();
                quad_uvs.reverse();
            }
            mesh.positions.extend(quad);
            uvs.extend(quad_uvs);
            mesh.indices.extend(base..base + 4);
            mesh.face_sizes.push(4);
        }
    }
    mesh.uvs = Some(uvs);
    mesh
}

/// The unit frustum's mesh of `segments` around its axis (z): its rings' radii 1 and
/// `top_radius` scaled by [`frustum_scale`] with `Facets::AsLarge` (for a frustum of
/// `aspect` = radius / height once placed).
fn unit_frustum(segments: u32, frustum: UnitFrustum, aspect: f32, facets: Facets) -> PolygonMesh {
    let UnitFrustum {
        top_radius,
        bottom_cap,
        top_cap,
    } = frustum;
    let scale = match facets {
        Facets::Inscribed => 1.0,
        Facets::AsLarge => frustum_scale(segments, frustum, aspect),
    };
    let mut mesh = PolygonMesh::default();
    let ring = |z: f32, r: f32| -> Vec<Vec3> {
        (0..segments)
            .map(|i| {
                let phi = 2.0 * PI * i as f32 / segments as f32;
                Vec3::new(scale * r * phi.cos(), scale * r * phi.sin(), z)
            })
            .collect()
    };
    let bottom = ring(0.0, 1.0);
    let top = ring(1.0, top_radius);
    mesh.positions.extend(&bottom);
    mesh.positions.extend(&top);
    let n = segments;
    for i in 0..n {
        let j = (i + 1) % n;
        if top_radius > 0.0 {
            mesh.indices.extend([i, j, n + j, n + i]);
            mesh.face_sizes.push(4);
        } else {
            mesh.indices.extend([i, j, n + i]);
            mesh.face_sizes.push(3);
        }
    }
    if bottom_cap {
        mesh.indices.extend((0..n).rev());
        mesh.face_sizes.push(n);
    }
    if top_cap && top_radius > 0.0 {
        mesh.indices.extend(n..2 * n);
        mesh.face_sizes.push(n);
    }
    mesh
}

/// The factor on the unit frustum's radii that makes its mesh of `segments` as large as the
/// frustum once placed with `aspect` = radius / height: its side (a band of trapezoids, or
/// triangles for a cone) and its caps, in closed form in units of its height, solved by
/// bisection (the mesh's area grows with the factor; at 1 it is below the frustum's, at 2
/// above it for any count of segments from 3).
fn frustum_scale(segments: u32, frustum: UnitFrustum, aspect: f32) -> f32 {
    use std::f64::consts::PI;
    let n = f64::from(segments);
    let (a, t) = (f64::from(aspect), f64::from(frustum.top_radius));
    let caps = f64::from(u8::from(frustum.bottom_cap)) + if frustum.top_cap { t * t } else { 0.0 };
    let exact = PI * a * (1.0 + t) * (1.0 + (a * (1.0 - t)).powi(2)).sqrt() + PI * a * a * caps;
    let (half_angle_sin, half_angle_cos) = (PI / n).sin_cos();
    let area = |k: f64| {
        let polygons = caps * (k * a).powi(2) * n * half_angle_sin * half_angle_cos;
        let slant = (1.0 + (k * a * half_angle_cos * (1.0 - t)).powi(2)).sqrt();
        polygons + n * k * a * (1.0 + t) * half_angle_sin * slant
    };
    let (mut low, mut high) = (1.0, 2.0);
    for _ in 0..60 {
        let k = 0.5 * (low + high);
        if area(k) < exact {
            low = k;
        } else {
            high = k;
        }
    }
    (0.5 * (low + high)) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    fn outward(mesh: &PolygonMesh, inside: Vec3) -> bool {
        mesh.faces().all(|f| {
            let verts: Vec<Vec3> = f.iter().map(|&i| mesh.positions[i as usize]).collect();
            let c = verts.iter().sum::<Vec3>() / verts.len() as f32;
            polygon_normal(&verts).dot(c - inside) > 0.0
        })
    }

    fn total_area(mesh: &PolygonMesh) -> f32 {
        mesh.faces()
            .map(|f| {
                let v: Vec<Vec3> = f.iter().map(|&i| mesh.positions[i as usize]).collect();
                polygon_area(&v)
            })
            .sum()
    }

    #[test]
    fn box_is_exact_and_outward() {
        let shape = Shape::Box {
            min: Vec3::ZERO,
            max: Vec3::new(1.0, 2.0, 3.0),
        };
        let mesh = shape.to_mesh(8).unwrap();
        assert_eq!(mesh.face_count(), 6);
        assert!((total_area(&mesh) - 22.0).abs() < 1e-5);
        assert!(outward(&mesh, Vec3::new(0.5, 1.0, 1.5)));
    }

    #[test]
    fn a_sphere_closes_at_its_poles_and_its_seam() {
        // Facets meeting at a pole share it exactly (sin π is not 0 in single precision), and
        // the seam's last column lies on its first: no sliver for the radiosity mesh to cut.
        let sphere = Shape::Sphere {
            center: Vec3::new(0.3, 1.7, -0.2),
            radius: 0.4,
        };
        let segments = 16;
        let m = sphere.to_mesh(segments).unwrap();
        let row = segments as usize + 1;
        let rings = m.positions.len() / row;
        for ring in [0, rings - 1] {
            let pole = &m.positions[ring * row..(ring + 1) * row];
            assert!(pole.iter().all(|&p| p == pole[0]), "{pole:?}");
        }
        for ring in 0..rings {
            assert_eq!(m.positions[ring * row], m.positions[ring * row + row - 1]);
        }
    }

    /// Curved shapes with their closed-form areas and a point inside each.
    fn curved_shapes() -> [(Shape, f32, Vec3); 4] {
        let sqrt2 = 2f32.sqrt();
        [
            (
                Shape::Sphere {
                    center: Vec3::ONE,
                    radius: 2.0,
                },
                16.0 * PI,
                Vec3::ONE,
            ),
            (
                Shape::Cylinder {
                    base: Vec3::ZERO,
                    top: Vec3::Y * 2.0,
                    radius: 0.5,
                    caps: true,
                },
                2.0 * PI * 0.5 * 2.0 + 2.0 * PI * 0.25,
                Vec3::Y,
            ),
            (
                Shape::Cone {
                    base: Vec3::ZERO,
                    apex: Vec3::Y,
                    radius: 1.0,
                    cap: true,
                },
                PI * sqrt2 + PI,
                Vec3::Y * 0.25,
            ),
            (
                Shape::Frustum {
                    base: Vec3::ZERO,
                    top: Vec3::Y,
                    base_radius: 1.0,
                    top_radius: 0.5,
                    caps: false,
                },
                PI * 1.5 * (1.25f32).sqrt(),
                Vec3::Y * 0.5,
            ),
        ]
    }

    #[test]
    fn curved_shapes_are_as_large_as_their_surface_and_face_outward() {
        for (shape, exact, inside) in curved_shapes() {
            for segments in [3, 7, 16, 64] {
                let m = shape.to_mesh(segments).unwrap();
                assert!(outward(&m, inside), "{shape:?}");
                let area = total_area(&m);
                assert!(
                    (area / exact - 1.0).abs() < 1e-5,
                    "{shape:?} at {segments}: {area}"
                );
            }
        }
    }

    #[test]
    fn inscribed_meshes_have_their_corners_on_the_surface_and_converge_to_its_area() {
        for (shape, exact, inside) in curved_shapes() {
            let coarse = total_area(&shape.to_inscribed_mesh(16).unwrap());
            let m = shape.to_inscribed_mesh(128).unwrap();
            assert!(outward(&m, inside));
            let fine = total_area(&m);
            assert!(coarse < fine && fine < exact, "{shape:?}");
            assert!((fine / exact - 1.0).abs() < 1e-3, "{shape:?}: {fine}");
        }
        let sphere = Shape::Sphere {
            center: Vec3::ONE,
            radius: 2.0,
        };
        let m = sphere.to_inscribed_mesh(16).unwrap();
        assert!(
            m.positions
                .iter()
                .all(|p| (p.distance(Vec3::ONE) - 2.0).abs() < 1e-5)
        );
    }

    #[test]
    fn planar_shapes_keep_their_corners_and_get_default_uvs() {
        let quad = Shape::Parallelogram {
            origin: Vec3::ZERO,
            edge_u: Vec3::X,
            edge_v: Vec3::Z * 2.0,
        };
        let m = quad.to_mesh(3).unwrap();
        assert_eq!(m.positions[2], Vec3::new(1.0, 0.0, 2.0));
        assert_eq!(m.uvs.as_ref().unwrap()[2], Vec2::ONE);
        assert!(
            Shape::Plane {
                point: Vec3::ZERO,
                normal: Vec3::Y
            }
            .to_mesh(8)
            .is_err()
        );
    }
}
