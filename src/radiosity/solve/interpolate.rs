//! Radiosity interpolated to the corners of the leaf patches for smooth display (seed 001's
//! patch-to-vertex scheme): each vertex gets the area-weighted mean of the leaves that share
//! it, then every T-vertex (a corner of finer leaves lying on the edge of a coarser leaf) is
//! set to the linear interpolation along that coarser edge, coarsest edges first. Radiosity
//! interpolated linearly along every edge is then continuous across quadtree levels: no
//! cracks.
//!
//! Vertices are shared only between leaves of the same object lying in the same plane
//! (coplanar faces of one object count as one surface); corners between different surfaces
//! (a wall meeting the floor) keep separate values.

use crate::color::Rgb64;
use crate::radiosity::{Patch, PatchId, PatchMesh};
use glam::DVec3;
use std::collections::HashMap;

/// Relative size (to the scene's extent) of the grid vertices are welded on.
const WELD_RELATIVE: f64 = 1e-7;
/// Normals are compared after rounding to this many steps per unit.
const NORMAL_STEPS: f64 = 1e4;
/// Deepest chain of midpoints followed along one edge.
const MAX_EDGE_DEPTH: u32 = 24;

/// Values at a leaf's corners, in corner order (the fourth unused for triangles).
pub type CornerValues = [Rgb64; 4];

/// Vertex key: surface group and welded position.
type VertexKey = (u32, [i64; 3]);

/// Smooth corner values of every leaf `leaves[k]` from the per-leaf `values[k]` (flat
/// radiosity), as the module describes.
pub fn vertex_radiosity(
    mesh: &PatchMesh,
    leaves: &[PatchId],
    values: &[Rgb64],
) -> Vec<CornerValues> {
    let patches: Vec<&Patch> = leaves.iter().map(|&id| mesh.patch(id)).collect();
    let extent = patches
        .iter()
        .flat_map(|p| p.corners().iter())
        .fold(0.0f64, |m, c| m.max(c.abs().max_element()));
    let weld = (extent * WELD_RELATIVE).max(f64::MIN_POSITIVE);
    let mut groups: HashMap<(u32, [i64; 3]), u32> = HashMap::new();
    let group_of: Vec<u32> = patches
        .iter()
        .map(|p| {
            let n = (p.normal * NORMAL_STEPS).round();
            let key = (p.object, [n.x as i64, n.y as i64, n.z as i64]);
            let next = groups.len() as u32;
            *groups.entry(key).or_insert(next)
        })
        .collect();
    let key = |group: u32, p: DVec3| -> VertexKey {
        let q = (p / weld).round();
        (group, [q.x as i64, q.y as i64, q.z as i64])
    };
    let mut index: HashMap<VertexKey, usize> = HashMap::new();
    let mut sums: Vec<(Rgb64, f64)> = Vec::new();
    for (k, p) in patches.iter().enumerate() {
        for &c in p.corners() {
            let v = *index.entry(key(group_of[k], c)).or_insert_with(|| {
                sums.push((Rgb64::BLACK, 0.0));
                sums.len() - 1
            });
            let (sum, weight) = &mut sums[v];
            *sum += values[k] * p.area;
            *weight += p.area;
        }
    }
    let mut vertex: Vec<Rgb64> = sums
        .iter()
        .map(|(s, w)| {
            if *w > 0.0 {
                s.map(|x| x / w)
            } else {
                Rgb64::BLACK
            }
        })
        .collect();
    let mut order: Vec<usize> = (0..patches.len()).collect();
    order.sort_by_key(|&k| patches[k].depth);
    for k in order {
        let c = patches[k].corners();
        for e in 0..c.len() {
            let (a, b) = (c[e], c[(e + 1) % c.len()]);
            let ends = (index[&key(group_of[k], a)], index[&key(group_of[k], b)]);
            let lookup = |p: DVec3| index.get(&key(group_of[k], p)).copied();
            fix_edge(&lookup, &mut vertex, (a, b), ends, MAX_EDGE_DEPTH);
        }
    }
    patches
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let mut out = [Rgb64::BLACK; 4];
            for (slot, &c) in out.iter_mut().zip(p.corners()) {
                *slot = vertex[index[&key(group_of[k], c)]];
            }
            out
        })
        .collect()
}

/// Sets every vertex found at the midpoints along the edge `a`–`b` (recursively) to the
/// linear interpolation of the edge's end values.
fn fix_edge(
    lookup: &impl Fn(DVec3) -> Option<usize>,
    vertex: &mut [Rgb64],
    (a, b): (DVec3, DVec3),
    (va, vb): (usize, usize),
    depth: u32,
) {
    if depth == 0 {
        return;
    }
    let m = (a + b) * 0.5;
    let Some(vm) = lookup(m) else {
        return;
    };
    vertex[vm] = (vertex[va] + vertex[vb]) * 0.5;
    fix_edge(lookup, vertex, (a, m), (va, vm), depth - 1);
    fix_edge(lookup, vertex, (m, b), (vm, vb), depth - 1);
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    #[test]
    fn t_vertex_takes_the_coarse_edge_interpolation() {
        // Two unit squares side by side; the right one split once. The left square's right
        // edge has the T-vertex (1, 0.5).
        let square = |x: f64| {
            Patch::new(
                &[
                    DVec3::new(x, 0.0, 0.0),
                    DVec3::new(x + 1.0, 0.0, 0.0),
                    DVec3::new(x + 1.0, 1.0, 0.0),
                    DVec3::new(x, 1.0, 0.0),
                ],
                &[DVec2::ZERO; 4],
            )
            .unwrap()
        };
        let mut mesh = PatchMesh::default();
        mesh.patches.push(square(0.0));
        mesh.patches.push(square(1.0));
        mesh.roots = vec![0, 1];
        mesh.subdivide(1);
        let leaves = mesh.leaves();
        assert_eq!(leaves.len(), 5);
        // Left square 1, right children 2, 4, 6, 8 (any distinct values).
        let values: Vec<Rgb64> = (0..5).map(|k| Rgb64::splat((1 + 2 * k) as f64)).collect();
        let corners = vertex_radiosity(&mesh, &leaves, &values);
        let at = |p: DVec3| {
            leaves.iter().enumerate().find_map(|(k, &id)| {
                let i = mesh.patch(id).corners().iter().position(|&c| c == p)?;
                Some(corners[k][i][0])
            })
        };
        let (bottom, top) = (
            at(DVec3::new(1.0, 0.0, 0.0)).unwrap(),
            at(DVec3::new(1.0, 1.0, 0.0)).unwrap(),
        );
        let t = at(DVec3::new(1.0, 0.5, 0.0)).unwrap();
        assert!(
            (t - 0.5 * (bottom + top)).abs() < 1e-12,
            "{t} vs {bottom}, {top}"
        );
        // A shared corner is the area-weighted mean: (1, 0) touches the left square (area 1,
        // value 1) and the bottom-left child (area 1/4).
        let child = values[leaves
            .iter()
            .position(|&id| {
                mesh.patch(id)
                    .corners()
                    .contains(&DVec3::new(1.0, 0.0, 0.0))
                    && id != 0
            })
            .unwrap()][0];
        assert!((bottom - (1.0 + 0.25 * child) / 1.25).abs() < 1e-12);
    }
}
