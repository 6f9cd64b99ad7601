//! The seed's octree (seed 002 §4.5.2) with Glassner's 1984 cell generator.
//!
//! The root cell is a cube slightly larger than the bounds of all finite primitives. A cell
//! holding more than `max_objects_per_cell` primitives is split into eight equal children
//! until `max_depth` is reached; a primitive goes into every child its (slightly enlarged)
//! bounding box overlaps. A split that would more than quadruple the references is not made:
//! its primitives are about as large as the cell or larger, and splitting cannot separate
//! them. Unbounded primitives (infinite planes) stay outside the tree and are
//! tested by every ray.
//!
//! A ray walks the leaves it crosses in order: from the point where it leaves the current
//! leaf it steps one cell of the finest lattice (never larger than the smallest cell) past
//! the exit face and descends from the root to the leaf holding that point. Cell positions
//! are integers on that lattice, so faces shared by neighbours are the same numbers and the
//! walk cannot stall or go back. The walk stops once the closest hit lies before the current
//! leaf's exit; a few ulps of slack on both the primitive bounds and that test keep the
//! answer identical to testing every primitive.

use super::{AccelStats, Accelerator, PrimHit, PrimitiveSet, keep_closest};
use crate::geometry::{Aabb, Ray};
use glam::{UVec3, Vec3};
use std::ops::ControlFlow;

/// Build options of the octree.
#[derive(Clone, Debug)]
pub struct OctreeOptions {
    /// Cells holding more primitives than this are split.
    pub max_objects_per_cell: usize,
    /// Cells at this depth are never split (the root has depth 0). Values above 16 are
    /// treated as 16 (cells then span 2⁻¹⁶ of the root edge, near `f32` resolution).
    pub max_depth: usize,
}

impl Default for OctreeOptions {
    fn default() -> Self {
        OctreeOptions {
            max_objects_per_cell: 8,
            max_depth: 10,
        }
    }
}

/// Deepest level the octree subdivides to.
const MAX_DEPTH_LIMIT: usize = 16;

/// A split is refused when the children would hold more than this many times the parent's
/// references. Measured on a tessellated sphere over a floor, random triangles and a lattice
/// of walls: at 4 a ray tests as many primitives as with unrestricted splitting (within 2 %)
/// while storing 15–60 % fewer references; at 2 a ray tests up to twice as many.
const MAX_REFERENCE_GROWTH: usize = 4;

/// The root cube's edge exceeds the scene's largest extent by this fraction …
const ROOT_ENLARGEMENT: f32 = 1.0 / 256.0;
/// … plus this fraction of the largest coordinate magnitude (room for rounding).
const ROOT_PAD: f32 = 1.0 / 32_768.0;
/// Edge of the root cube when all primitives sit at the coordinate origin.
const MIN_ROOT_EDGE: f32 = 1e-20;

/// Primitive bounds are enlarged by this fraction of the largest coordinate magnitude
/// (64 ulps) …
const SLACK_MAGNITUDE: f32 = 1.0 / 131_072.0;
/// … plus this fraction of the root edge before they are sorted into cells.
const SLACK_EDGE: f32 = 1.0 / 1_048_576.0;

/// The walk stops only when the closest hit lies before `(1 − EXIT_MARGIN)` times the current
/// leaf's exit parameter, covering rounding in hit and exit parameters of distant rays.
const EXIT_MARGIN: f32 = 1.0 / 65_536.0;

/// Slots of the per-ray mailbox (a power of two).
const MAILBOX_SIZE: usize = 32;

/// `count` of an inner node.
const INNER: u32 = u32::MAX;

/// One cell: an inner node (`count == INNER`, its eight children at `index .. index + 8`,
/// child `i` taking the upper half of x, y, z when bit 0, 1, 2 of `i` is set) or a leaf
/// (primitive references `index .. index + count`).
#[derive(Clone, Copy, Debug)]
struct Node {
    index: u32,
    count: u32,
}

impl Node {
    const EMPTY_LEAF: Node = Node { index: 0, count: 0 };
}

/// The integer lattice of finest cells spanning the root cube. Cell faces are computed
/// from lattice coordinates alone, so build and walk see identical numbers.
#[derive(Clone, Copy, Debug)]
struct Lattice {
    /// Lower corner of the root cube (scene units).
    min: Vec3,
    /// Edge of a finest cell (scene units).
    unit: f32,
    /// `1 / unit`.
    inv_unit: f32,
    /// Number of subdivision levels: the root is `2^depth` finest cells wide.
    depth: u32,
}

impl Lattice {
    /// The lattice over a cube enclosing `scene` with margin, and the slack (scene units)
    /// added to primitive bounds; `None` when that cube is not representable in finite
    /// `f32` numbers.
    fn around(scene: &Aabb, depth: u32) -> Option<(Lattice, f32)> {
        let extent = scene.extent().max_element();
        let magnitude = scene.min.abs().max(scene.max.abs()).max_element();
        let edge = (extent * (1.0 + ROOT_ENLARGEMENT) + magnitude * ROOT_PAD).max(MIN_ROOT_EDGE);
        let min = scene.center() - Vec3::splat(0.5 * edge);
        let cells = (1u32 << depth) as f32;
        let lattice = Lattice {
            min,
            unit: edge / cells,
            inv_unit: cells / edge,
            depth,
        };
        let slack = magnitude * SLACK_MAGNITUDE + edge * SLACK_EDGE;
        let finite = edge.is_finite() && min.is_finite() && (min + Vec3::splat(edge)).is_finite();
        finite.then_some((lattice, slack))
    }

    /// Number of finest cells along each axis.
    fn cells(&self) -> u32 {
        1 << self.depth
    }

    /// Coordinate of lattice plane `k` on `axis`.
    #[inline(always)]
    fn face(&self, axis: usize, k: u32) -> f32 {
        self.min[axis] + k as f32 * self.unit
    }

    /// The box of the cell with lower lattice corner `lo` and edge `size` lattice units.
    fn cell_box(&self, lo: UVec3, size: u32) -> Aabb {
        let f = |k: UVec3| Vec3::from_array(std::array::from_fn(|a| self.face(a, k[a])));
        Aabb {
            min: f(lo),
            max: f(lo + size),
        }
    }

    /// The finest cell holding coordinate `x` on `axis`, clamped to the root. A point on a
    /// lattice plane belongs to the cell the direction component `d` moves into.
    #[inline(always)]
    fn locate(&self, axis: usize, x: f32, d: f32) -> u32 {
        let u = (x - self.min[axis]) * self.inv_unit;
        let k = if d < 0.0 { u.ceil() - 1.0 } else { u.floor() };
        // `as` maps NaN to 0 and saturates; the clamp keeps the cell inside the root.
        (k.max(0.0) as u32).min(self.cells() - 1)
    }
}

/// Primitives already tested by one ray, so that a primitive spanning several cells is
/// tested once: a direct-mapped cache, slot `prim mod MAILBOX_SIZE` holding the last
/// primitive of that slot tested.
struct Mailbox {
    ids: [u32; MAILBOX_SIZE],
}

impl Mailbox {
    fn new() -> Self {
        Mailbox {
            ids: [u32::MAX; MAILBOX_SIZE],
        }
    }

    /// True when `prim` is the last primitive of its slot tested (so it was tested already);
    /// otherwise records it and returns false.
    #[inline(always)]
    fn seen(&mut self, prim: u32) -> bool {
        let slot = &mut self.ids[prim as usize % MAILBOX_SIZE];
        let seen = *slot == prim;
        *slot = prim;
        seen
    }
}

/// The seed's octree: cubic cells split into eight, walked in ray order with Glassner's
/// cell generator.
#[derive(Clone, Debug)]
pub struct Octree {
    lattice: Lattice,
    /// Cells; node 0 is the root (absent when there is no finite primitive).
    nodes: Vec<Node>,
    /// Primitive references of all leaves.
    refs: Vec<u32>,
    /// Primitives with unbounded or non-finite bounds, tested by every ray.
    unbounded: Vec<u32>,
    primitives: usize,
    leaves: usize,
    max_depth: usize,
}

/// State of the recursive build.
struct Builder<'a> {
    options: &'a OctreeOptions,
    lattice: Lattice,
    /// Primitive bounds enlarged by the slack.
    bounds: Vec<Aabb>,
    nodes: Vec<Node>,
    refs: Vec<u32>,
    leaves: usize,
    max_depth: usize,
}

impl Octree {
    /// Builds the octree over `prims`.
    pub fn build<P: PrimitiveSet>(prims: &P, options: &OctreeOptions) -> Self {
        let n = prims.len() as u32;
        let bounds: Vec<Aabb> = (0..n).map(|i| prims.bounds(i)).collect();
        let (finite, mut unbounded): (Vec<u32>, Vec<u32>) = (0..n).partition(|&i| {
            let b = &bounds[i as usize];
            !b.is_empty() && b.min.is_finite() && b.max.is_finite()
        });
        let scene = finite
            .iter()
            .fold(Aabb::EMPTY, |s, &i| s.union(bounds[i as usize]));
        let depth = options.max_depth.min(MAX_DEPTH_LIMIT) as u32;
        let mut octree = Octree {
            lattice: Lattice {
                min: Vec3::ZERO,
                unit: 1.0,
                inv_unit: 1.0,
                depth: 0,
            },
            nodes: Vec::new(),
            refs: Vec::new(),
            unbounded: Vec::new(),
            primitives: n as usize,
            leaves: 0,
            max_depth: 0,
        };
        if finite.is_empty() {
            octree.unbounded = unbounded;
            return octree;
        }
        let Some((lattice, slack)) = Lattice::around(&scene, depth) else {
            // Coordinates too large for a cube in f32: every primitive is tested by every ray.
            unbounded.extend(finite);
            unbounded.sort_unstable();
            octree.unbounded = unbounded;
            return octree;
        };
        let pad = Vec3::splat(slack);
        let mut builder = Builder {
            options,
            lattice,
            bounds: bounds
                .iter()
                .map(|b| Aabb {
                    min: b.min - pad,
                    max: b.max + pad,
                })
                .collect(),
            nodes: vec![Node::EMPTY_LEAF],
            refs: Vec::with_capacity(finite.len()),
            leaves: 0,
            max_depth: 0,
        };
        builder.build_cell(0, finite, 0, UVec3::ZERO);
        Octree {
            lattice,
            nodes: builder.nodes,
            refs: builder.refs,
            unbounded,
            leaves: builder.leaves,
            max_depth: builder.max_depth,
            ..octree
        }
    }

    /// The leaf holding lattice cell `c`: its node and depth.
    #[inline(always)]
    fn descend(&self, c: UVec3) -> (Node, u32) {
        let mut node = self.nodes[0];
        let mut depth = 0;
        while node.count == INNER {
            let shift = self.lattice.depth - 1 - depth;
            let bit = |a: usize| ((c[a] >> shift) & 1) as usize;
            let child = bit(0) | (bit(1) << 1) | (bit(2) << 2);
            node = self.nodes[node.index as usize + child];
            depth += 1;
        }
        (node, depth)
    }

    /// Parameter where `ray` enters the root cube (0 when it starts inside), if it meets it.
    fn root_entry(&self, ray: &Ray) -> Option<f32> {
        let edge = self.lattice.cells();
        let (mut t_in, mut t_out) = (0.0f32, f32::INFINITY);
        for a in 0..3 {
            let (lo, hi) = (self.lattice.face(a, 0), self.lattice.face(a, edge));
            let (o, d) = (ray.origin[a], ray.dir[a]);
            if d == 0.0 {
                if o < lo || o > hi {
                    return None;
                }
            } else {
                let (near, far) = if d > 0.0 { (lo, hi) } else { (hi, lo) };
                t_in = t_in.max((near - o) / d);
                t_out = t_out.min((far - o) / d);
            }
        }
        (t_in <= t_out).then_some(t_in)
    }

    /// Calls `visit` with the primitive references of every leaf `ray` crosses, in ray
    /// order. `visit` returns the current hit limit (`Continue`) or ends the walk (`Break`);
    /// the walk also ends once the limit lies before the next leaf.
    fn walk(
        &self,
        ray: &Ray,
        mut limit: f32,
        mut visit: impl FnMut(&[u32]) -> ControlFlow<(), f32>,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        if !(ray.origin.is_finite() && ray.dir.is_finite()) {
            // No cell order exists for such a ray: all references form one cell.
            let _ = visit(&self.refs);
            return;
        }
        let Some(t_enter) = self.root_entry(ray) else {
            return;
        };
        let lattice = &self.lattice;
        let (origin, dir) = (ray.origin, ray.dir);
        let inv_dir = dir.recip();
        let start = ray.at(t_enter);
        let mut c = UVec3::from_array(std::array::from_fn(|a| lattice.locate(a, start[a], dir[a])));
        let mut t_cell = t_enter;
        loop {
            if limit < t_cell * (1.0 - EXIT_MARGIN) {
                return;
            }
            let (leaf, depth) = self.descend(c);
            let first = leaf.index as usize;
            match visit(&self.refs[first..first + leaf.count as usize]) {
                ControlFlow::Continue(l) => limit = l,
                ControlFlow::Break(()) => return,
            }
            // The leaf's lattice box and the parameters of its three exit faces.
            let size = 1u32 << (lattice.depth - depth);
            let lo = c & UVec3::splat(!(size - 1));
            let hi = lo + size;
            let t_face: [f32; 3] = std::array::from_fn(|a| {
                if dir[a] > 0.0 {
                    (lattice.face(a, hi[a]) - origin[a]) * inv_dir[a]
                } else if dir[a] < 0.0 {
                    (lattice.face(a, lo[a]) - origin[a]) * inv_dir[a]
                } else {
                    f32::INFINITY
                }
            });
            let t_exit = t_face[0].min(t_face[1]).min(t_face[2]);
            if t_exit.is_nan() || t_exit == f32::INFINITY {
                // The ray stays in this leaf (zero or vanishing direction).
                return;
            }
            // Glassner's step: just past the exit face(s), at the exit point elsewhere. The
            // probe never moves against the ray on any axis, so the walk always progresses.
            let t_next = t_exit.max(t_cell);
            let exit_point = ray.at(t_next);
            for a in 0..3 {
                let d = dir[a];
                if t_face[a] <= t_exit {
                    if d > 0.0 {
                        if hi[a] == lattice.cells() {
                            return;
                        }
                        c[a] = hi[a];
                    } else {
                        if lo[a] == 0 {
                            return;
                        }
                        c[a] = lo[a] - 1;
                    }
                } else if d > 0.0 {
                    c[a] = lattice.locate(a, exit_point[a], d).max(c[a]).min(hi[a] - 1);
                } else if d < 0.0 {
                    c[a] = lattice.locate(a, exit_point[a], d).min(c[a]).max(lo[a]);
                }
            }
            t_cell = t_next;
        }
    }
}

impl Builder<'_> {
    /// Fills node `node`: the cell with lower lattice corner `lo` at `depth`, overlapped by
    /// the bounds of `items`.
    fn build_cell(&mut self, node: usize, items: Vec<u32>, depth: u32, lo: UVec3) {
        if items.len() > self.options.max_objects_per_cell && depth < self.lattice.depth {
            let half = 1u32 << (self.lattice.depth - depth - 1);
            let corner = |i: usize| {
                lo + UVec3::new(i as u32 & 1, (i as u32 >> 1) & 1, (i as u32 >> 2) & 1) * half
            };
            let children: [Vec<u32>; 8] = std::array::from_fn(|i| {
                let cell = self.lattice.cell_box(corner(i), half);
                items
                    .iter()
                    .copied()
                    .filter(|&p| self.bounds[p as usize].overlaps(&cell))
                    .collect()
            });
            let references: usize = children.iter().map(Vec::len).sum();
            if references <= MAX_REFERENCE_GROWTH * items.len() {
                drop(items);
                let first = self.nodes.len();
                self.nodes[node] = Node {
                    index: first as u32,
                    count: INNER,
                };
                self.nodes.extend([Node::EMPTY_LEAF; 8]);
                for (i, child) in children.into_iter().enumerate() {
                    self.build_cell(first + i, child, depth + 1, corner(i));
                }
                return;
            }
        }
        self.nodes[node] = Node {
            index: self.refs.len() as u32,
            count: items.len() as u32,
        };
        self.refs.extend(items);
        self.leaves += 1;
        self.max_depth = self.max_depth.max(depth as usize);
    }
}

impl<P: PrimitiveSet> Accelerator<P> for Octree {
    fn closest_hit(&self, prims: &P, ray: &Ray, t_max: f32) -> Option<PrimHit> {
        let mut best: Option<PrimHit> = None;
        for &prim in &self.unbounded {
            let limit = best.map_or(t_max, |b| b.t);
            keep_closest(&mut best, prims.intersect(prim, ray, limit));
        }
        let mut mailbox = Mailbox::new();
        self.walk(ray, best.map_or(t_max, |b| b.t), |cell| {
            for &prim in cell {
                if !mailbox.seen(prim) {
                    let limit = best.map_or(t_max, |b| b.t);
                    keep_closest(&mut best, prims.intersect(prim, ray, limit));
                }
            }
            ControlFlow::Continue(best.map_or(t_max, |b| b.t))
        });
        best
    }

    fn any_hit(&self, prims: &P, ray: &Ray, t_max: f32) -> bool {
        if self
            .unbounded
            .iter()
            .any(|&prim| prims.intersect(prim, ray, t_max).is_some())
        {
            return true;
        }
        let mut hit = false;
        let mut mailbox = Mailbox::new();
        self.walk(ray, t_max, |cell| {
            hit = cell
                .iter()
                .any(|&prim| !mailbox.seen(prim) && prims.intersect(prim, ray, t_max).is_some());
            if hit {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(t_max)
            }
        });
        hit
    }

    fn stats(&self) -> AccelStats {
        AccelStats {
            kind: "octree",
            primitives: self.primitives,
            nodes: self.nodes.len(),
            leaves: self.leaves,
            max_depth: self.max_depth,
            references: self.refs.len() + self.unbounded.len(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::Naive;
    use crate::geometry::Triangle;
    use rand::{RngExt, SeedableRng};
    use rand_pcg::Pcg64Mcg;
    use std::sync::atomic::{AtomicU32, Ordering};

    /// Triangles followed by infinite planes `y = height`; counts intersection tests.
    struct Soup {
        triangles: Vec<Triangle>,
        planes: Vec<f32>,
        tests: Vec<AtomicU32>,
    }

    impl Soup {
        fn new(triangles: Vec<Triangle>, planes: Vec<f32>) -> Self {
            let tests = (0..triangles.len() + planes.len())
                .map(|_| AtomicU32::new(0))
                .collect();
            Soup {
                triangles,
                planes,
                tests,
            }
        }

        fn tests_of(&self, prim: usize) -> u32 {
            self.tests[prim].load(Ordering::Relaxed)
        }

        fn total_tests(&self) -> u32 {
            (0..self.tests.len()).map(|i| self.tests_of(i)).sum()
        }

        fn reset_counts(&self) {
            self.tests
                .iter()
                .for_each(|c| c.store(0, Ordering::Relaxed));
        }
    }

    impl PrimitiveSet for Soup {
        fn len(&self) -> usize {
            self.triangles.len() + self.planes.len()
        }

        fn bounds(&self, prim: u32) -> Aabb {
            match self.triangles.get(prim as usize) {
                Some(t) => Aabb::from_points(t.vertices()),
                None => Aabb {
                    min: Vec3::NEG_INFINITY,
                    max: Vec3::INFINITY,
                },
            }
        }

        fn intersect(&self, prim: u32, ray: &Ray, t_max: f32) -> Option<PrimHit> {
            self.tests[prim as usize].fetch_add(1, Ordering::Relaxed);
            let i = prim as usize;
            if let Some(tri) = self.triangles.get(i) {
                let (t, b1, b2) = tri.intersect(ray, t_max)?;
                return Some(PrimHit {
                    t,
                    prim,
                    local: [b1, b2],
                    part: 0,
                });
            }
            let height = self.planes[i - self.triangles.len()];
            let t = (height - ray.origin.y) / ray.dir.y;
            (t > 0.0 && t <= t_max).then_some(PrimHit {
                t,
                prim,
                local: [0.0; 2],
                part: 0,
            })
        }
    }

    fn random_vec(rng: &mut Pcg64Mcg, lo: f32, hi: f32) -> Vec3 {
        Vec3::new(
            rng.random_range(lo..hi),
            rng.random_range(lo..hi),
            rng.random_range(lo..hi),
        )
    }

    fn random_dir(rng: &mut Pcg64Mcg) -> Vec3 {
        loop {
            let v = random_vec(rng, -1.0, 1.0);
            let l = v.length();
            if l > 0.1 && l <= 1.0 {
                return v / l;
            }
        }
    }

    /// `n` triangles of edge up to `size` with centres uniform in `[-1, 1]³`.
    fn small_triangles(rng: &mut Pcg64Mcg, n: usize, size: f32) -> Vec<Triangle> {
        (0..n)
            .map(|_| {
                let c = random_vec(rng, -1.0, 1.0);
                let mut v = || c + random_vec(rng, -0.5 * size, 0.5 * size);
                Triangle::new(v(), v(), v())
            })
            .collect()
    }

    /// Rays with origins inside `[-1, 1]³` (random directions), on a sphere of radius 3 and
    /// 300 aimed at the box, and a few with finite `t_max`.
    fn mixed_rays(rng: &mut Pcg64Mcg, n: usize) -> Vec<(Ray, f32)> {
        (0..n)
            .map(|i| {
                let ray = match i % 3 {
                    0 => Ray::new(random_vec(rng, -1.0, 1.0), random_dir(rng)),
                    k => {
                        let origin = random_dir(rng) * if k == 1 { 3.0 } else { 300.0 };
                        let target = random_vec(rng, -1.0, 1.0);
                        Ray::new(origin, (target - origin).normalize())
                    }
                };
                let t_max = if i % 5 == 0 {
                    rng.random_range(0.0..4.0)
                } else {
                    f32::INFINITY
                };
                (ray, t_max)
            })
            .collect()
    }

    /// Asserts that the octree answers every query exactly like the naive loop; returns the
    /// number of rays that hit something.
    fn assert_agrees(soup: &Soup, options: &OctreeOptions, rays: &[(Ray, f32)]) -> usize {
        let octree = Octree::build(soup, options);
        let naive = Naive::build(soup);
        let mut hits = 0;
        for (i, (ray, t_max)) in rays.iter().enumerate() {
            let expected = naive.closest_hit(soup, ray, *t_max);
            let got = octree.closest_hit(soup, ray, *t_max);
            assert_eq!(
                got, expected,
                "closest hit of ray {i}: {ray:?}, t_max {t_max}"
            );
            let any = octree.any_hit(soup, ray, *t_max);
            assert_eq!(any, expected.is_some(), "any hit of ray {i}: {ray:?}");
            hits += usize::from(expected.is_some());
        }
        hits
    }

    /// Depth and reference count of every leaf.
    fn leaves(octree: &Octree) -> Vec<(usize, usize)> {
        fn visit(o: &Octree, node: usize, depth: usize, out: &mut Vec<(usize, usize)>) {
            let n = o.nodes[node];
            if n.count == INNER {
                (0..8).for_each(|i| visit(o, n.index as usize + i, depth + 1, out));
            } else {
                out.push((depth, n.count as usize));
            }
        }
        let mut out = Vec::new();
        if !octree.nodes.is_empty() {
            visit(octree, 0, 0, &mut out);
        }
        out
    }

    #[test]
    fn agrees_with_naive_on_random_small_triangles() {
        let mut rng = Pcg64Mcg::seed_from_u64(1);
        let soup = Soup::new(small_triangles(&mut rng, 3000, 0.1), Vec::new());
        let rays = mixed_rays(&mut rng, 6000);
        let hits = assert_agrees(&soup, &OctreeOptions::default(), &rays);
        // Over a quarter of the rays hit: the comparison covers hits and misses alike.
        assert!((1500..4500).contains(&hits), "{hits} hits");
        let deep = OctreeOptions {
            max_objects_per_cell: 1,
            max_depth: 16,
        };
        assert_eq!(assert_agrees(&soup, &deep, &rays), hits);
    }

    #[test]
    fn agrees_with_naive_with_an_unbounded_plane() {
        let mut rng = Pcg64Mcg::seed_from_u64(2);
        let soup = Soup::new(small_triangles(&mut rng, 1000, 0.2), vec![-0.5]);
        let rays = mixed_rays(&mut rng, 3000);
        let hits = assert_agrees(&soup, &OctreeOptions::default(), &rays);
        assert!(hits > 1500, "{hits} hits");
        let stats =
            <Octree as Accelerator<Soup>>::stats(&Octree::build(&soup, &Default::default()));
        assert_eq!(stats.primitives, 1001);
        assert!(stats.references > 1001);
    }

    /// Unit squares (two triangles each) covering the planes `x, y, z ∈ {0, 3, 6}` inside
    /// `[0, 6]³`: coplanar, touching and crossing triangles.
    fn lattice_walls() -> Vec<Triangle> {
        let mut triangles = Vec::new();
        for axis in 0..3 {
            for level in [0.0, 3.0, 6.0] {
                for i in 0..6 {
                    for j in 0..6 {
                        let p = |u: f32, v: f32| {
                            let mut c = [0.0; 3];
                            c[axis] = level;
                            c[(axis + 1) % 3] = u;
                            c[(axis + 2) % 3] = v;
                            Vec3::from_array(c)
                        };
                        let (u, v) = (i as f32, j as f32);
                        triangles.push(Triangle::new(p(u, v), p(u + 1.0, v), p(u + 1.0, v + 1.0)));
                        triangles.push(Triangle::new(p(u, v), p(u + 1.0, v + 1.0), p(u, v + 1.0)));
                    }
                }
            }
        }
        triangles
    }

    #[test]
    fn agrees_with_naive_on_a_dense_grid_with_axis_rays() {
        let mut rng = Pcg64Mcg::seed_from_u64(3);
        let soup = Soup::new(lattice_walls(), Vec::new());
        let dirs = [
            Vec3::X,
            -Vec3::X,
            Vec3::Y,
            -Vec3::Y,
            Vec3::Z,
            -Vec3::Z,
            Vec3::new(1.0, 1.0, 0.0).normalize(),
            Vec3::new(-1.0, 1.0, 1.0).normalize(),
        ];
        // Origins on the grid lines, on half and quarter steps, inside and outside the walls.
        let steps = [0.0, 0.25, 0.5, 1.0];
        let rays: Vec<(Ray, f32)> = (0..6000)
            .map(|_| {
                let mut coord =
                    || rng.random_range(-2i32..8) as f32 + steps[rng.random_range(0..4)];
                let origin = Vec3::new(coord(), coord(), coord());
                (
                    Ray::new(origin, dirs[rng.random_range(0..dirs.len())]),
                    f32::INFINITY,
                )
            })
            .collect();
        let small = OctreeOptions {
            max_objects_per_cell: 2,
            max_depth: 8,
        };
        for options in [OctreeOptions::default(), small] {
            let hits = assert_agrees(&soup, &options, &rays);
            assert!(hits > 1500, "{hits} hits");
        }
    }

    #[test]
    fn agrees_with_naive_on_degenerate_scenes() {
        let mut rng = Pcg64Mcg::seed_from_u64(4);
        let rays = mixed_rays(&mut rng, 2000);
        let point = Vec3::new(0.3, -0.2, 0.7);
        // All primitives at one point: nothing can be hit, the build stays tiny.
        let collapsed = Soup::new(vec![Triangle::new(point, point, point); 50], Vec::new());
        assert_eq!(
            assert_agrees(&collapsed, &OctreeOptions::default(), &rays),
            0
        );
        let stats =
            <Octree as Accelerator<Soup>>::stats(&Octree::build(&collapsed, &Default::default()));
        assert!(stats.nodes <= 1 + 8 * 10, "{stats:?}");
        // A fan of triangles meeting at one point.
        let fan: Vec<Triangle> = (0..64)
            .map(|_| {
                Triangle::new(
                    point,
                    point + random_vec(&mut rng, -0.8, 0.8),
                    point + random_vec(&mut rng, -0.8, 0.8),
                )
            })
            .collect();
        let fan = Soup::new(fan, Vec::new());
        assert!(assert_agrees(&fan, &OctreeOptions::default(), &rays) > 300);
        // A single primitive.
        let single = Soup::new(
            vec![Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y)],
            Vec::new(),
        );
        let down = (
            Ray::new(Vec3::new(0.25, 0.25, 1.0), -Vec3::Z),
            f32::INFINITY,
        );
        assert_eq!(
            assert_agrees(&single, &OctreeOptions::default(), &[down]),
            1
        );
        assert!(assert_agrees(&single, &OctreeOptions::default(), &rays) > 10);
        let stats =
            <Octree as Accelerator<Soup>>::stats(&Octree::build(&single, &Default::default()));
        assert_eq!((stats.nodes, stats.leaves, stats.references), (1, 1, 1));
        // The empty set.
        let empty = Soup::new(Vec::new(), Vec::new());
        assert_eq!(assert_agrees(&empty, &OctreeOptions::default(), &rays), 0);
        let stats =
            <Octree as Accelerator<Soup>>::stats(&Octree::build(&empty, &Default::default()));
        assert_eq!(
            stats,
            AccelStats {
                kind: "octree",
                ..Default::default()
            }
        );
    }

    #[test]
    fn respects_max_depth_and_max_objects_per_cell() {
        let mut rng = Pcg64Mcg::seed_from_u64(5);
        // Triangles small against the cells, so every split separates them.
        let soup = Soup::new(small_triangles(&mut rng, 2000, 0.002), Vec::new());
        for (max_objects_per_cell, max_depth) in [(4, 5), (1, 7), (8, 10), (100, 3)] {
            let options = OctreeOptions {
                max_objects_per_cell,
                max_depth,
            };
            let octree = Octree::build(&soup, &options);
            let leaves = leaves(&octree);
            let stats = <Octree as Accelerator<Soup>>::stats(&octree);
            assert_eq!(stats.kind, "octree");
            assert_eq!(stats.leaves, leaves.len());
            assert_eq!(stats.nodes, 1 + 8 * (leaves.len() - 1) / 7);
            assert_eq!(stats.references, leaves.iter().map(|l| l.1).sum::<usize>());
            assert!(stats.references >= 2000);
            assert_eq!(stats.max_depth, leaves.iter().map(|l| l.0).max().unwrap());
            assert!(stats.max_depth <= max_depth, "{stats:?}");
            for &(depth, count) in &leaves {
                assert!(
                    depth == max_depth || count <= max_objects_per_cell,
                    "{depth} {count}"
                );
            }
        }
        // With one object per cell, 2000 primitives need the full depth.
        let deep = Octree::build(
            &soup,
            &OctreeOptions {
                max_objects_per_cell: 1,
                max_depth: 6,
            },
        );
        assert_eq!(deep.max_depth, 6);
        let flat = Octree::build(
            &soup,
            &OctreeOptions {
                max_objects_per_cell: 1,
                max_depth: 0,
            },
        );
        assert_eq!((flat.nodes.len(), flat.refs.len()), (1, 2000));
    }

    #[test]
    fn refuses_splits_that_cannot_separate_primitives() {
        let mut rng = Pcg64Mcg::seed_from_u64(6);
        // Twenty triangles whose bounds all span the whole scene.
        let big: Vec<Triangle> = (0..20)
            .map(|_| {
                let a = random_vec(&mut rng, -0.1, 0.1);
                Triangle::new(
                    Vec3::splat(-1.0) + a,
                    Vec3::new(1.0, -1.0, 1.0) - a,
                    Vec3::ONE + a,
                )
            })
            .collect();
        let soup = Soup::new(big, Vec::new());
        let options = OctreeOptions {
            max_objects_per_cell: 1,
            max_depth: 10,
        };
        let octree = Octree::build(&soup, &options);
        assert!(octree.nodes.len() <= 9, "{} nodes", octree.nodes.len());
        let rays = mixed_rays(&mut rng, 1000);
        assert!(assert_agrees(&soup, &options, &rays) > 100);
    }

    #[test]
    fn agrees_with_naive_on_triangles_within_ulps_of_cell_faces() {
        let mut rng = Pcg64Mcg::seed_from_u64(7);
        // Two specks fix the scene bounds, hence the lattice, whatever the other triangles.
        let speck = |p: Vec3| Triangle::new(p, p, p);
        let mut triangles = vec![speck(Vec3::splat(-1.5)), speck(Vec3::splat(1.5))];
        let scene = Aabb::new(Vec3::splat(-1.5), Vec3::splat(1.5));
        let (lattice, _) = Lattice::around(&scene, MAX_DEPTH_LIMIT as u32).unwrap();
        // Overlapping, nearly axis-aligned triangles whose vertices lie up to 3, 48 or 768
        // ulps either side of faces of the depth-3 cells, so neighbouring cells hold near-ties.
        for _ in 0..600 {
            let axis = rng.random_range(0..3);
            let face = lattice.face(axis, rng.random_range(1..8) << (MAX_DEPTH_LIMIT - 3));
            let ulp = f32::EPSILON * face.abs().max(f32::EPSILON);
            let centre = random_vec(&mut rng, -1.0, 1.0);
            let spread = [1.0, 16.0, 256.0][rng.random_range(0..3)] * ulp;
            let mut vertex = || {
                let mut v = centre + random_vec(&mut rng, -0.4, 0.4);
                v[axis] = face + rng.random_range(-3i32..=3) as f32 * spread;
                v
            };
            triangles.push(Triangle::new(vertex(), vertex(), vertex()));
        }
        let soup = Soup::new(triangles, Vec::new());
        let rays = mixed_rays(&mut rng, 6000);
        for max_depth in [3, 6] {
            let options = OctreeOptions {
                max_objects_per_cell: 2,
                max_depth,
            };
            let hits = assert_agrees(&soup, &options, &rays);
            assert!(hits > 3000, "{hits} hits");
        }
    }

    #[test]
    fn agrees_with_naive_on_extreme_rays_and_coordinates() {
        let mut rng = Pcg64Mcg::seed_from_u64(8);
        let soup = Soup::new(small_triangles(&mut rng, 500, 0.3), Vec::new());
        let odd_dirs = [
            Vec3::ZERO,
            Vec3::new(f32::NAN, 0.0, 1.0),
            Vec3::new(1.0, 1e-40, -1e-40),
            Vec3::new(-1e-30, 1.0, 1e-38),
            Vec3::new(0.0, -0.0, -1.0),
        ];
        let rays: Vec<(Ray, f32)> = (0..2000)
            .map(|i| {
                let origin = random_vec(&mut rng, -1.5, 1.5);
                (
                    Ray::new(origin, odd_dirs[i % odd_dirs.len()]),
                    f32::INFINITY,
                )
            })
            .collect();
        let hits = assert_agrees(&soup, &OctreeOptions::default(), &rays);
        assert!(hits > 100, "{hits} hits");
        // Coordinates near the largest f32: no finite root cube, every primitive is tested.
        let huge = 1.7e38;
        let far = Soup::new(
            vec![
                Triangle::new(
                    Vec3::new(-huge, -1.0, 0.0),
                    Vec3::new(huge, -1.0, 0.0),
                    Vec3::Y,
                ),
                Triangle::new(
                    Vec3::new(-1.0, -1.0, 1.0),
                    Vec3::new(1.0, -1.0, 1.0),
                    Vec3::Y,
                ),
            ],
            Vec::new(),
        );
        let octree = Octree::build(&far, &OctreeOptions::default());
        let stats = <Octree as Accelerator<Soup>>::stats(&octree);
        assert_eq!((stats.nodes, stats.references), (0, 2));
        let rays: Vec<(Ray, f32)> = (0..200)
            .map(|_| {
                let origin = Vec3::new(0.0, 0.0, -2.0);
                let target = random_vec(&mut rng, -1.0, 1.0).with_z(1.0);
                (
                    Ray::new(origin, (target - origin).normalize()),
                    f32::INFINITY,
                )
            })
            .collect();
        assert!(assert_agrees(&far, &OctreeOptions::default(), &rays) > 20);
    }

    /// Two triangles forming the square of half-edge `r` at `x`, facing along x.
    fn square(x: f32, r: f32) -> [Triangle; 2] {
        let p = |y: f32, z: f32| Vec3::new(x, y, z);
        [
            Triangle::new(p(-r, -r), p(r, -r), p(r, r)),
            Triangle::new(p(-r, -r), p(r, r), p(-r, r)),
        ]
    }

    #[test]
    fn walk_stops_at_the_first_hit() {
        // A row of 200 small squares along +x, 0.1 apart.
        let triangles: Vec<Triangle> = (0..200)
            .flat_map(|i| square(i as f32 * 0.1, 0.02))
            .collect();
        let soup = Soup::new(triangles, Vec::new());
        let octree = Octree::build(&soup, &OctreeOptions::default());
        // From between squares 100 and 101 towards square 101 (triangles 202 and 203, whose
        // shared diagonal the ray hits: the tie goes to 202).
        let ray = Ray::new(Vec3::new(10.05, 0.0, 0.0), Vec3::X);
        let hit = octree.closest_hit(&soup, &ray, f32::INFINITY).unwrap();
        assert_eq!(hit.prim, 202);
        assert!((hit.t - 0.05).abs() < 1e-5, "{hit:?}");
        assert!(soup.total_tests() <= 16, "{} tests", soup.total_tests());
        // From outside the root, along the row from its start.
        soup.reset_counts();
        let ray = Ray::new(Vec3::new(-5.0, -0.01, 0.01), Vec3::X);
        let hit = octree.closest_hit(&soup, &ray, f32::INFINITY).unwrap();
        assert_eq!(hit.prim, 1);
        assert!((hit.t - 5.0).abs() < 1e-5, "{hit:?}");
        assert!(soup.total_tests() <= 16, "{} tests", soup.total_tests());
    }

    #[test]
    fn mailbox_tests_a_primitive_spanning_many_cells_once() {
        // Twelve small squares along +x and a long sliver beside them.
        let mut triangles: Vec<Triangle> =
            (0..12).flat_map(|i| square(i as f32 * 0.1, 0.02)).collect();
        triangles.push(Triangle::new(
            Vec3::new(-0.05, 0.01, 0.03),
            Vec3::new(1.2, 0.01, 0.03),
            Vec3::new(1.2, 0.01, 0.05),
        ));
        let sliver = triangles.len() as u32 - 1;
        let soup = Soup::new(triangles, Vec::new());
        let options = OctreeOptions {
            max_objects_per_cell: 1,
            max_depth: 8,
        };
        let octree = Octree::build(&soup, &options);
        let cells_with_sliver = octree.refs.iter().filter(|&&r| r == sliver).count();
        assert!(cells_with_sliver >= 8, "{cells_with_sliver} cells");
        // Through the gap between the squares and the sliver.
        let ray = Ray::new(Vec3::new(-1.0, 0.0, 0.025), Vec3::X);
        assert_eq!(octree.closest_hit(&soup, &ray, f32::INFINITY), None);
        assert_eq!(soup.tests_of(sliver as usize), 1);
        assert!(!octree.any_hit(&soup, &ray, f32::INFINITY));
        assert_eq!(soup.tests_of(sliver as usize), 2);
    }
}
