//! The surfaces a report lists: one per object, or one per face for objects with
//! `per_face = true`, with their areas, and the map from a hit's object and face to its entry.
//! Objects that share a name are one entry (scenes often split a wall or a plant organ into
//! parts): their areas and powers add up, so the irradiance is their area-weighted mean.

use crate::scene::Scene;
use crate::world::SceneGeometry;
use std::collections::HashMap;

/// Segments of the coarser of the two tessellations that measure curved analytic shapes.
const AREA_SEGMENTS: u32 = 64;

/// One reported surface.
#[derive(Clone, Debug, PartialEq)]
pub struct ReportSurface {
    /// Object name (`object-<index>` when the scene gives none).
    pub name: String,
    /// Index of the entry's first scene object.
    pub object: u32,
    /// Face index for per-face entries, `None` for whole objects.
    pub face: Option<u32>,
    /// One-sided area in squared scene units, summed over the parts; infinite for unbounded
    /// shapes (planes).
    pub area: f64,
    /// Number of scene objects (or of their faces, for per-face entries) in the entry.
    pub parts: u32,
}

/// The report entries of a scene and the map from (object, face) to entry.
#[derive(Clone, Debug, Default)]
pub struct SurfaceTable {
    surfaces: Vec<ReportSurface>,
    /// Per object: where its entries start in `slots`.
    first: Vec<u32>,
    /// Per object: number of its slots (faces when per-face, else 1).
    count: Vec<u32>,
    /// The entry of every object's whole or face, objects in scene order.
    slots: Vec<u32>,
}

impl SurfaceTable {
    /// The entries of `scene` as flattened into `geometry`. Areas of triangulated objects are
    /// the sums of their world-space triangles (faces are the mesh's polygons, not its
    /// triangles); areas of analytic shapes are measured on a fine tessellation with the
    /// object transform applied; infinite planes have infinite area.
    pub fn new(scene: &Scene, geometry: &SceneGeometry) -> Self {
        let objects = scene.objects.len();
        // Per object, triangle area per face (grown as faces appear).
        let mut face_areas: Vec<Vec<f64>> = vec![Vec::new(); objects];
        geometry.for_each_surface_triangle(|t| {
            let (areas, face) = (&mut face_areas[t.object as usize], t.face as usize);
            if areas.len() <= face {
                areas.resize(face + 1, 0.0);
            }
            areas[face] += t.area;
        });
        let mut table = SurfaceTable::default();
        let mut by_name: HashMap<(String, Option<u32>), u32> = HashMap::new();
        for (index, object) in scene.objects.iter().enumerate() {
            let name = scene.object_name(index);
            let areas = &face_areas[index];
            table.first.push(table.slots.len() as u32);
            let whole_area = if areas.is_empty() {
                analytic_area(scene, index)
            } else {
                areas.iter().sum()
            };
            let mut add = |face: Option<u32>, area: f64| {
                let surfaces = &mut table.surfaces;
                let entry = *by_name.entry((name.clone(), face)).or_insert_with(|| {
                    surfaces.push(ReportSurface {
                        name: name.clone(),
                        object: index as u32,
                        face,
                        area: 0.0,
                        parts: 0,
                    });
                    (surfaces.len() - 1) as u32
                });
                let surface = &mut surfaces[entry as usize];
                surface.area += area;
                surface.parts += 1;
                table.slots.push(entry);
            };
            if object.per_face && areas.len() > 1 {
                for (face, &area) in areas.iter().enumerate() {
                    add(Some(face as u32), area);
                }
                table.count.push(areas.len() as u32);
            } else {
                add(object.per_face.then_some(0), whole_area);
                table.count.push(1);
            }
        }
        table
    }

    /// All entries, in the scene order of their first object (faces of one object
    /// consecutive).
    pub fn surfaces(&self) -> &[ReportSurface] {
        &self.surfaces
    }

    /// Number of entries.
    pub fn len(&self) -> usize {
        self.surfaces.len()
    }

    /// True when the scene has no objects.
    pub fn is_empty(&self) -> bool {
        self.surfaces.is_empty()
    }

    /// The entry of face `face` of object `object` (the object's only entry unless it is
    /// reported per face). `object` must be a scene object index.
    pub fn entry(&self, object: u32, face: u32) -> usize {
        let o = object as usize;
        let face = face.min(self.count[o] - 1);
        self.slots[(self.first[o] + face) as usize] as usize
    }
}

/// Area of an object the geometry holds as an analytic shape (not as triangles): the
/// tessellated area at n and 2n segments extrapolated to infinitely many (Richardson; the
/// tessellation error falls as 1/n², so the extrapolated error is O(1/n⁴)). Exact for boxes.
fn analytic_area(scene: &Scene, index: usize) -> f64 {
    let coarse = tessellated_area(scene, index, AREA_SEGMENTS);
    let fine = tessellated_area(scene, index, 2 * AREA_SEGMENTS);
    if coarse.is_finite() {
        (4.0 * fine - coarse) / 3.0
    } else {
        coarse
    }
}

/// Area of object `index` tessellated with `segments` (world space).
fn tessellated_area(scene: &Scene, index: usize, segments: u32) -> f64 {
    let object = &scene.objects[index];
    match object.shape.to_inscribed_mesh(segments) {
        Err(_) if matches!(object.shape, crate::scene::Shape::Plane { .. }) => f64::INFINITY,
        Err(_) => 0.0,
        Ok(mesh) => {
            let world: Vec<glam::Vec3> = mesh
                .positions
                .iter()
                .map(|&p| object.transform.point(p))
                .collect();
            mesh.faces()
                .map(|face| {
                    let vertices: Vec<glam::Vec3> =
                        face.iter().map(|&i| world[i as usize]).collect();
                    crate::scene::polygon_area(&vertices) as f64
                })
                .sum()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Transform;
    use crate::scene::{Material, PolygonMesh, Shape};
    use glam::Vec3;
    use std::sync::Arc;

    #[test]
    fn areas_and_entries_per_object_and_per_face() {
        let mut scene = Scene::empty("t");
        let m = scene.add_material(Material::default());
        // Two unit quads as one mesh, reported per face.
        let mesh = PolygonMesh::from_triangles(
            vec![
                Vec3::ZERO,
                Vec3::X,
                Vec3::new(1.0, 0.0, -1.0),
                Vec3::new(0.0, 0.0, -1.0),
                Vec3::new(2.0, 0.0, 0.0),
                Vec3::new(2.0, 0.0, -1.0),
            ],
            &[[0, 1, 2], [0, 2, 3], [1, 4, 5]],
        );
        scene.add_object("leaves", Shape::Mesh(Arc::new(mesh)), m);
        scene.objects[0].per_face = true;
        scene.add_object(
            "ball",
            Shape::Sphere {
                center: Vec3::new(0.0, 5.0, 0.0),
                radius: 2.0,
            },
            m,
        );
        scene.objects[1].transform = Transform::scale(Vec3::splat(0.5)).unwrap();
        scene.objects.push(crate::scene::Object {
            name: None,
            shape: Shape::Plane {
                point: Vec3::ZERO,
                normal: Vec3::Y,
            },
            transform: Default::default(),
            material: m,
            per_face: false,
        });
        let geometry = SceneGeometry::new(&scene).unwrap();
        let table = SurfaceTable::new(&scene, &geometry);
        let s = table.surfaces();
        assert_eq!(s.len(), 5);
        assert_eq!((s[0].face, s[2].face), (Some(0), Some(2)));
        assert!((s[0].area - 0.5).abs() < 1e-6 && (s[2].area - 0.5).abs() < 1e-6);
        // Sphere of radius 2 scaled by 0.5: 4π·1².
        let sphere = 4.0 * std::f64::consts::PI;
        assert!((s[3].area - sphere).abs() / sphere < 1e-5, "{}", s[3].area);
        assert_eq!(s[4].name, "object-2");
        assert!(s[4].area.is_infinite());
        assert_eq!(table.entry(0, 2), 2);
        assert_eq!(table.entry(1, 0), 3);
        assert_eq!(table.entry(2, 0), 4);
    }

    #[test]
    fn objects_that_share_a_name_are_one_entry() {
        let mut scene = Scene::empty("t");
        let m = scene.add_material(Material::default());
        let quad = |x: f32, width: f32| Shape::Parallelogram {
            origin: Vec3::new(x, 0.0, 0.0),
            edge_u: Vec3::X * width,
            edge_v: Vec3::Y,
        };
        scene.add_object("wall", quad(0.0, 1.0), m);
        scene.add_object("door", quad(5.0, 0.5), m);
        scene.add_object("wall", quad(1.0, 2.0), m);
        let geometry = SceneGeometry::new(&scene).unwrap();
        let table = SurfaceTable::new(&scene, &geometry);
        let s = table.surfaces();
        assert_eq!(s.len(), 2);
        assert_eq!((s[0].name.as_str(), s[0].parts), ("wall", 2));
        assert!((s[0].area - 3.0).abs() < 1e-6);
        assert_eq!((s[1].name.as_str(), s[1].parts), ("door", 1));
        assert_eq!(table.entry(0, 0), 0);
        assert_eq!(table.entry(1, 0), 1);
        assert_eq!(table.entry(2, 0), 0);
    }
}
