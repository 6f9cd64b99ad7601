//! Radiosity interpolated to the corners of the leaf patches for smooth display (seed 001's
//! patch-to-vertex scheme): each vertex gets the area-weighted mean of the leaves that share
//! it, then every T-vertex (a corner of finer leaves lying on the edge of a coarser leaf) is
//! set to the linear interpolation along that coarser edge, coarsest edges first. Radiosity
//! interpolated linearly along every edge is then continuous across quadtree levels: no
//! cracks.
//!
//! Vertices are shared between leaves of the same object whose normals differ by less than
//! a crease angle of 45°: the facets of a tessellated sphere, cylinder or cone are shaded
//! smoothly across their edges (and T-vertices where a finer facet meets a coarser one are
//! fixed as on a plane), while a box's faces or a wall meeting the floor keep separate
//! values at their common corners. Different objects never share a vertex.
//!
//! The work is linear in the leaves: an edge is followed into its midpoints only while it is
//! longer than a few weld cells and its midpoint is a vertex other than its ends, so every
//! lookup along one edge either fails or finds a new vertex ([`SmoothCorners::midpoint_lookups`]
//! counts them). An edge shorter than the weld grid (a sliver of an imported mesh) has no
//! midpoint vertex of its own.

use crate::color::Rgb64;
use crate::radiosity::{Patch, PatchId, PatchMesh};
use glam::DVec3;
use std::collections::HashMap;

/// Relative size (to the scene's extent) of the grid vertices are welded on.
const WELD_RELATIVE: f64 = 1e-7;
/// Cosine of the crease angle (45°): leaves of one object meeting at a point share a vertex
/// there when their normals are closer than this.
const CREASE_COS: f64 = std::f64::consts::FRAC_1_SQRT_2;
/// Deepest chain of midpoints followed along one edge.
const MAX_EDGE_DEPTH: u32 = 24;
/// Shortest edge, in weld cells, whose midpoint may be a vertex of its own: the midpoint then
/// lies at least two cells from either end, farther than rounding to the grid moves a point
/// (√3/2 of a cell), so it never welds to an end.
const MIN_EDGE_CELLS: f64 = 4.0;

/// A weld cell of one object: object index and position on the weld grid.
type WeldCell = (u32, [i64; 3]);

/// Values at a leaf's corners, in corner order (the fourth unused for triangles).
pub type CornerValues = [Rgb64; 4];

/// The smooth corner values of a set of leaves and the work it took.
#[derive(Clone, Debug, PartialEq)]
pub struct SmoothCorners {
    /// Values at the corners of every leaf, in the order of the leaves given.
    pub corners: Vec<CornerValues>,
    /// Midpoints looked up along the leaves' edges: one per edge and two more per vertex
    /// found on an edge, so at most a small multiple of the corners.
    pub midpoint_lookups: u64,
}

/// Smooth corner values of every leaf `leaves[k]` from the per-leaf `values[k]` (flat
/// radiosity), as the module describes. For several sets of values over the same leaves,
/// [`VertexWelding`] finds the vertices once.
pub fn vertex_radiosity(mesh: &PatchMesh, leaves: &[PatchId], values: &[Rgb64]) -> SmoothCorners {
    let welding = VertexWelding::new(mesh, leaves);
    SmoothCorners {
        corners: welding.smooth(values),
        midpoint_lookups: welding.midpoint_lookups,
    }
}

/// The corners of a set of leaves as shared vertices, found once for any number of sets of
/// values over them ([`VertexWelding::smooth`]): the vertex at each corner, the leaves'
/// areas, and the T-vertices to set, in the order they are set.
#[derive(Clone, Debug)]
pub struct VertexWelding {
    /// Per leaf, the vertex at each corner and how many corners it has.
    corners: Vec<([usize; 4], usize)>,
    /// Per leaf, its area (scene units²).
    areas: Vec<f64>,
    /// Vertices in all.
    vertices: usize,
    /// Per T-vertex, in order: the vertex set to the mean of the two after it.
    fixes: Vec<[usize; 3]>,
    /// Midpoints looked up along the leaves' edges ([`SmoothCorners::midpoint_lookups`]).
    pub midpoint_lookups: u64,
}

impl VertexWelding {
    /// The vertices of `leaves` of `mesh`.
    pub fn new(mesh: &PatchMesh, leaves: &[PatchId]) -> VertexWelding {
        let patches: Vec<&Patch> = leaves.iter().map(|&id| mesh.patch(id)).collect();
        let extent = patches
            .iter()
            .flat_map(|p| p.corners().iter())
            .fold(0.0f64, |m, c| m.max(c.abs().max_element()));
        let weld = (extent * WELD_RELATIVE).max(f64::MIN_POSITIVE);
        let mut index = VertexIndex {
            weld,
            cells: HashMap::new(),
            count: 0,
        };
        // Each leaf's corner vertices, found once.
        let corners: Vec<([usize; 4], usize)> = patches
            .iter()
            .map(|p| {
                let mut ids = [0; 4];
                for (slot, &c) in ids.iter_mut().zip(p.corners()) {
                    *slot = index.find_or_insert(p, c);
                }
                (ids, p.corners().len())
            })
            .collect();
        let mut edge = EdgeWalk {
            min_length: MIN_EDGE_CELLS * weld,
            lookups: 0,
            fixes: Vec::new(),
        };
        let mut order: Vec<usize> = (0..patches.len()).collect();
        order.sort_by_key(|&k| patches[k].depth);
        for k in order {
            let patch = patches[k];
            let (c, n) = (patch.corners(), patch.corners().len());
            let lookup = |p: DVec3| index.find(patch, p);
            let ids = corners[k].0;
            for e in 0..n {
                let ends = (ids[e], ids[(e + 1) % n]);
                edge.fix(&lookup, (c[e], c[(e + 1) % n]), ends, MAX_EDGE_DEPTH);
            }
        }
        VertexWelding {
            corners,
            areas: patches.iter().map(|p| p.area).collect(),
            vertices: index.count,
            fixes: edge.fixes,
            midpoint_lookups: edge.lookups,
        }
    }

    /// The smooth values at the corners of every leaf from the per-leaf `values` (in the
    /// order of the leaves given to [`VertexWelding::new`]).
    pub fn smooth(&self, values: &[Rgb64]) -> Vec<CornerValues> {
        let mut sums = vec![(Rgb64::BLACK, 0.0); self.vertices];
        for ((ids, n), (&value, &area)) in self.corners.iter().zip(values.iter().zip(&self.areas)) {
            for &v in &ids[..*n] {
                let (sum, weight) = &mut sums[v];
                *sum += value * area;
                *weight += area;
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
        for &[m, a, b] in &self.fixes {
            vertex[m] = (vertex[a] + vertex[b]) * 0.5;
        }
        self.corners
            .iter()
            .map(|(ids, n)| {
                std::array::from_fn(|i| if i < *n { vertex[ids[i]] } else { Rgb64::BLACK })
            })
            .collect()
    }
}

/// The vertices by object and welded position, each with the normal of the first leaf that
/// made it (a handful per position at most: one per crease).
struct VertexIndex {
    /// Size of a weld cell, scene units.
    weld: f64,
    /// Vertices (normal, index) at each object's welded positions.
    cells: HashMap<WeldCell, Vec<(DVec3, usize)>>,
    /// Vertices made so far.
    count: usize,
}

impl VertexIndex {
    fn cell(&self, patch: &Patch, p: DVec3) -> WeldCell {
        let q = (p / self.weld).round();
        (patch.object, [q.x as i64, q.y as i64, q.z as i64])
    }

    /// The vertex `patch` shares at `p`, if there is one.
    fn find(&self, patch: &Patch, p: DVec3) -> Option<usize> {
        self.cells
            .get(&self.cell(patch, p))?
            .iter()
            .find(|(normal, _)| normal.dot(patch.normal) > CREASE_COS)
            .map(|&(_, v)| v)
    }

    /// The vertex `patch` shares at `p`, made (numbered next) when there is none yet.
    fn find_or_insert(&mut self, patch: &Patch, p: DVec3) -> usize {
        if let Some(v) = self.find(patch, p) {
            return v;
        }
        let cell = self.cell(patch, p);
        let v = self.count;
        self.cells.entry(cell).or_default().push((patch.normal, v));
        self.count += 1;
        v
    }
}

/// The walk along leaf edges that finds their T-vertices.
struct EdgeWalk {
    /// Shortest edge followed into its midpoint, scene units.
    min_length: f64,
    /// Midpoints looked up so far.
    lookups: u64,
    /// The T-vertices found, each with the ends of the edge it lies on, in the order found.
    fixes: Vec<[usize; 3]>,
}

impl EdgeWalk {
    /// Every vertex found at the midpoints along the edge `a`–`b` (recursively), to be set
    /// to the linear interpolation of the edge's end values: each midpoint is set to the
    /// mean of its edge's ends, before the two halves' midpoints.
    fn fix(
        &mut self,
        lookup: &impl Fn(DVec3) -> Option<usize>,
        (a, b): (DVec3, DVec3),
        (va, vb): (usize, usize),
        depth: u32,
    ) {
        if depth == 0 || a.distance(b) < self.min_length {
            return;
        }
        let m = (a + b) * 0.5;
        self.lookups += 1;
        let Some(vm) = lookup(m).filter(|&vm| vm != va && vm != vb) else {
            return;
        };
        self.fixes.push([vm, va, vb]);
        self.fix(lookup, (a, m), (va, vm), depth - 1);
        self.fix(lookup, (m, b), (vm, vb), depth - 1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    #[test]
    fn an_edge_shorter_than_the_weld_grid_is_not_followed() {
        // A sliver with an edge of 10⁻¹² (its midpoint welds to both ends) beside a square:
        // its edges cost one lookup each, not 2²⁴.
        let mut mesh = PatchMesh::default();
        let square = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        let sliver = [
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(2.0, 0.5, 0.0),
            DVec3::new(1.0, 1e-12, 0.0),
        ];
        for corners in [&square[..], &sliver[..]] {
            let patch = Patch::new(corners, &[DVec2::ZERO; 4][..corners.len()]).unwrap();
            mesh.patches.push(patch);
        }
        mesh.roots = vec![0, 1];
        let leaves = mesh.leaves();
        let values = [Rgb64::splat(1.0), Rgb64::splat(3.0)];
        let smooth = vertex_radiosity(&mesh, &leaves, &values);
        assert_eq!(
            smooth.midpoint_lookups, 6,
            "one per edge longer than the grid"
        );
        // The corner the two share, (1, 0) with (1, 10⁻¹²) welded to it, is their area-weighted
        // mean: the square's value up to the sliver's area of 5·10⁻¹³.
        let shared = smooth.corners[1][0][0];
        assert!(shared > 1.0 && shared - 1.0 < 1e-11, "{shared}");
        assert_eq!(smooth.corners[1][2][0], shared);
    }

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
        let corners = vertex_radiosity(&mesh, &leaves, &values).corners;
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
