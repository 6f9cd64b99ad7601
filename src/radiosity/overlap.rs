//! Faces lying on other faces: root patches in one plane whose areas overlap (a floor
//! modelled twice, a decal on a wall, but also a box standing on a floor, its bottom on the
//! floor's face).
//!
//! The radiosity solvers light each such face fully — a ray from a point on one toward a
//! light leaves from just in front of it and meets nothing of the other — while a ray method
//! lights only the one a ray meets first: where both faces are lit on the same side, the
//! overlap receives its light twice in radiosity and reflects it twice, and the solution
//! makes light out of nothing there (the Šibenik cathedral: 1.2 % more light absorbed than
//! emitted). Where solids touch, the sides facing into them are dark and nothing is counted
//! twice; which case a pair is shows only in the solution (`Solution::light_counted_twice`),
//! not in the planes: faces' orientations in real models are not to be trusted. Which face
//! should have the light is not the solver's to decide; what it can do is say so.

use super::clip::{Plane, clip_to_front};
use super::mesh::{PatchId, PatchMesh};
use glam::DVec3;
use std::collections::HashMap;

/// Normals are compared to this many units (unit normals' components, rounded).
const NORMAL_STEP: f64 = 1e-4;

/// Planes are compared to this share of the scene's size.
const OFFSET_SHARE: f64 = 1e-6;

/// An overlap of less than this share of the smaller patch is a shared edge, not an overlap.
const NEGLIGIBLE: f64 = 1e-6;

/// Two root patches in one plane whose areas overlap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Overlap {
    /// One patch.
    pub first: PatchId,
    /// The other.
    pub second: PatchId,
    /// Whether their front sides face the same way (else opposite ways).
    pub same_facing: bool,
    /// The area they share, scene units².
    pub area: f64,
}

/// Every pair of root patches of `mesh` that overlap in the same plane (facing either way).
pub fn coplanar_overlaps(mesh: &PatchMesh) -> Vec<Overlap> {
    let size = mesh
        .roots
        .iter()
        .flat_map(|&r| {
            mesh.patch(r)
                .corners()
                .iter()
                .map(|c| c.abs().max_element())
        })
        .fold(0.0f64, f64::max)
        .max(f64::MIN_POSITIVE);
    let offset_step = OFFSET_SHARE * size;
    // Patches by their plane, the normal turned so that its largest component is positive
    // (faces facing opposite ways share a plane).
    let mut planes: HashMap<[i64; 4], Vec<PatchId>> = HashMap::new();
    for &r in &mesh.roots {
        let (normal, offset) = canonical_plane(mesh, r);
        planes
            .entry(plane_key(normal, offset, offset_step))
            .or_default()
            .push(r);
    }
    let mut found = Vec::new();
    let mut keys: Vec<&[i64; 4]> = planes.keys().collect();
    keys.sort_unstable();
    for key in keys {
        let patches = &planes[key];
        // The neighbouring offset too: a plane can round either way.
        let above = [key[0], key[1], key[2], key[3] + 1];
        let neighbours = planes.get(&above).map_or(&[][..], |v| v.as_slice());
        let candidates: Vec<PatchId> = patches.iter().chain(neighbours).copied().collect();
        overlaps_among(mesh, &candidates, patches.len(), &mut found);
    }
    found
}

/// The unit normal of root `r`'s plane turned so that its largest component is positive,
/// and the plane's offset along it.
fn canonical_plane(mesh: &PatchMesh, r: PatchId) -> (DVec3, f64) {
    let patch = mesh.patch(r);
    let n = patch.normal;
    let largest = if n.x.abs() >= n.y.abs() && n.x.abs() >= n.z.abs() {
        n.x
    } else if n.y.abs() >= n.z.abs() {
        n.y
    } else {
        n.z
    };
    let n = if largest < 0.0 { -n } else { n };
    (n, n.dot(patch.centroid))
}

/// The rounded plane `normal · x = offset`.
fn plane_key(normal: DVec3, offset: f64, offset_step: f64) -> [i64; 4] {
    let round = |x: f64, step: f64| (x / step).round() as i64;
    [
        round(normal.x, NORMAL_STEP),
        round(normal.y, NORMAL_STEP),
        round(normal.z, NORMAL_STEP),
        round(offset, offset_step),
    ]
}

/// Adds to `found` the overlapping pairs among `candidates` (one plane) with at least one
/// of the first `own` (pairs within the neighbouring plane are that plane's).
fn overlaps_among(mesh: &PatchMesh, candidates: &[PatchId], own: usize, found: &mut Vec<Overlap>) {
    if candidates.len() < 2 {
        return;
    }
    let normal = canonical_plane(mesh, candidates[0]).0;
    let (u, v) = normal.any_orthonormal_pair();
    // Bounds in the plane, swept along u.
    let bounds: Vec<[f64; 4]> = candidates
        .iter()
        .map(|&p| {
            let corners = mesh.patch(p).corners();
            let us = corners.iter().map(|c| c.dot(u));
            let vs = corners.iter().map(|c| c.dot(v));
            [
                us.clone().fold(f64::INFINITY, f64::min),
                us.fold(f64::NEG_INFINITY, f64::max),
                vs.clone().fold(f64::INFINITY, f64::min),
                vs.fold(f64::NEG_INFINITY, f64::max),
            ]
        })
        .collect();
    let mut order: Vec<usize> = (0..candidates.len()).collect();
    order.sort_by(|&a, &b| bounds[a][0].total_cmp(&bounds[b][0]));
    for (i, &a) in order.iter().enumerate() {
        for &b in &order[i + 1..] {
            if bounds[b][0] >= bounds[a][1] {
                break;
            }
            let (p, q) = (candidates[a], candidates[b]);
            if (a >= own && b >= own)
                || bounds[b][2] >= bounds[a][3]
                || bounds[a][2] >= bounds[b][3]
            {
                continue;
            }
            let area = overlap_area(mesh, p, q);
            let (pp, qp) = (mesh.patch(p), mesh.patch(q));
            if area > NEGLIGIBLE * pp.area.min(qp.area) {
                found.push(Overlap {
                    first: p,
                    second: q,
                    same_facing: pp.normal.dot(qp.normal) > 0.0,
                    area,
                });
            }
        }
    }
}

/// The area of the part of root `p` that lies within root `q` (both convex, in one plane),
/// scene units².
fn overlap_area(mesh: &PatchMesh, p: PatchId, q: PatchId) -> f64 {
    let (p, q) = (mesh.patch(p), mesh.patch(q));
    let corners = q.corners();
    // Inward from each edge is normal × edge for corners winding counter-clockwise.
    let mut part: Vec<DVec3> = p.corners().to_vec();
    for (k, &a) in corners.iter().enumerate() {
        let b = corners[(k + 1) % corners.len()];
        let inward = q.normal.cross(b - a).normalize_or_zero();
        part = clip_to_front(&Plane::new(a, inward), &part).into_owned();
        if part.len() < 3 {
            return 0.0;
        }
    }
    let twice: DVec3 = (1..part.len() - 1)
        .map(|k| (part[k] - part[0]).cross(part[k + 1] - part[0]))
        .sum();
    0.5 * twice.length()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;
    use crate::radiosity::mesh::MeshOptions;
    use crate::scene::{Material, Scene, Shape};
    use glam::Vec3;

    /// A scene of the squares `(origin, edge_u, edge_v)`.
    fn squares(shapes: &[(Vec3, Vec3, Vec3)]) -> PatchMesh {
        let mut scene = Scene::empty("overlaps");
        let grey = scene.add_material(Material::diffuse("grey", Rgb::splat(0.5)));
        for (k, &(origin, edge_u, edge_v)) in shapes.iter().enumerate() {
            scene.add_object(
                &format!("square {k}"),
                Shape::Parallelogram {
                    origin,
                    edge_u,
                    edge_v,
                },
                grey,
            );
        }
        let options = MeshOptions {
            contact_splits: false,
            ..MeshOptions::default()
        };
        PatchMesh::from_scene(&scene, &options).unwrap()
    }

    /// The area of every overlap found, and whether each pair faces the same way.
    fn found(mesh: &PatchMesh) -> Vec<(f64, bool)> {
        coplanar_overlaps(mesh)
            .iter()
            .map(|o| (o.area, o.same_facing))
            .collect()
    }

    #[test]
    fn a_square_half_on_another_overlaps_by_half_its_area() {
        let mesh = squares(&[
            (Vec3::ZERO, Vec3::X, Vec3::Z),
            (Vec3::new(0.5, 0.0, 0.0), Vec3::X, Vec3::Z),
        ]);
        let found = found(&mesh);
        assert_eq!(found.len(), 1);
        assert!((found[0].0 - 0.5).abs() < 1e-12 && found[0].1, "{found:?}");
    }

    #[test]
    fn a_square_facing_down_onto_a_larger_one_overlaps_facing_the_other_way() {
        // The foot of a box standing on a floor.
        let mesh = squares(&[
            (Vec3::ZERO, Vec3::X, Vec3::Z),
            (Vec3::new(0.25, 0.0, 0.25), Vec3::Z * 0.5, Vec3::X * 0.5),
        ]);
        let found = found(&mesh);
        assert_eq!(found.len(), 1);
        assert!(
            (found[0].0 - 0.25).abs() < 1e-12 && !found[0].1,
            "{found:?}"
        );
    }

    #[test]
    fn neighbours_sharing_an_edge_and_parallel_faces_apart_do_not() {
        let mesh = squares(&[
            (Vec3::ZERO, Vec3::X, Vec3::Z),
            (Vec3::new(1.0, 0.0, 0.0), Vec3::X, Vec3::Z),
            (Vec3::new(0.0, 1e-3, 0.0), Vec3::X, Vec3::Z),
        ]);
        assert!(coplanar_overlaps(&mesh).is_empty());
    }
}
