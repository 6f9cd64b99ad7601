//! Bounding-volume hierarchy built with the binned surface-area heuristic (SAH).
//!
//! Nodes are stored depth-first: an inner node's left child follows it directly and it
//! records the index of its right child. Traversal visits the nearer child first and skips
//! children whose box starts beyond the closest hit found so far. Unbounded primitives
//! (infinite planes) are kept outside the tree and tested by every ray.

use super::{AccelStats, Accelerator, PrimHit, PrimitiveSet, keep_closest};
use crate::geometry::{Aabb, Ray};
use glam::Vec3;

/// Build options of the BVH.
#[derive(Clone, Debug)]
pub struct BvhOptions {
    /// Leaves never hold more than this many primitives unless they cannot be split.
    pub max_leaf_size: usize,
    /// Number of bins per axis for the SAH sweep.
    pub bins: usize,
    /// Cost of visiting a node relative to one primitive test.
    pub traversal_cost: f32,
}

impl Default for BvhOptions {
    fn default() -> Self {
        BvhOptions {
            max_leaf_size: 8,
            bins: 16,
            traversal_cost: 1.0,
        }
    }
}

/// One node: its box, and either its children (`count == 0`, right child at `index`) or its
/// primitives (`count > 0`, references `index .. index + count`).
#[derive(Clone, Copy, Debug)]
#[repr(C)]
struct Node {
    min: Vec3,
    index: u32,
    max: Vec3,
    count: u32,
}

impl Node {
    /// Entry parameter of the ray into this node's box, if it enters before `t_max`.
    #[inline(always)]
    fn entry(&self, origin: Vec3, inv_dir: Vec3, t_max: f32) -> Option<f32> {
        let t0 = (self.min - origin) * inv_dir;
        let t1 = (self.max - origin) * inv_dir;
        let t_near = t0.min(t1).max_element().max(0.0);
        // Widened by a few ulps so rounding never loses a primitive touching the box face.
        let t_far = t0.max(t1).min_element() * ROBUST_FAR;
        (t_near <= t_far && t_near <= t_max).then_some(t_near)
    }
}

/// `1 + 2γ₃` (Pharr et al., PBR 3rd ed. §3.9.2): makes the slab test conservative.
const ROBUST_FAR: f32 = 1.0 + 2.0 * (3.0 * f32::EPSILON * 0.5) / (1.0 - 3.0 * f32::EPSILON * 0.5);

/// Traversal stack depth; the build keeps trees shallower than this.
const STACK_SIZE: usize = 64;

/// A SAH bounding-volume hierarchy.
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<Node>,
    refs: Vec<u32>,
    unbounded: Vec<u32>,
    max_depth: usize,
}

struct Builder<'a> {
    options: &'a BvhOptions,
    bounds: Vec<Aabb>,
    centroids: Vec<Vec3>,
    refs: Vec<u32>,
    nodes: Vec<Node>,
    max_depth: usize,
}

#[derive(Clone, Copy)]
struct Bin {
    bounds: Aabb,
    count: u32,
}

impl Bvh {
    /// Builds the hierarchy over `prims`.
    pub fn build<P: PrimitiveSet>(prims: &P, options: &BvhOptions) -> Self {
        let n = prims.len();
        let bounds: Vec<Aabb> = (0..n as u32).map(|i| prims.bounds(i)).collect();
        let (finite, unbounded): (Vec<u32>, Vec<u32>) = (0..n as u32).partition(|&i| {
            let b = &bounds[i as usize];
            !b.is_empty() && b.min.is_finite() && b.max.is_finite()
        });
        let centroids = bounds.iter().map(Aabb::center).collect();
        let mut builder = Builder {
            options,
            bounds,
            centroids,
            refs: finite,
            nodes: Vec::with_capacity(2 * n / options.max_leaf_size.max(1) + 1),
            max_depth: 0,
        };
        if !builder.refs.is_empty() {
            builder.build_node(0, builder.refs.len(), 0);
        }
        Bvh {
            nodes: builder.nodes,
            refs: builder.refs,
            unbounded,
            max_depth: builder.max_depth,
        }
    }

    #[inline(always)]
    fn traverse<P: PrimitiveSet>(
        &self,
        prims: &P,
        ray: &Ray,
        t_max: f32,
        any: bool,
    ) -> Option<PrimHit> {
        let mut best: Option<PrimHit> = None;
        for &prim in &self.unbounded {
            let limit = best.map_or(t_max, |b| b.t);
            keep_closest(&mut best, prims.intersect(prim, ray, limit));
            if any && best.is_some() {
                return best;
            }
        }
        if self.nodes.is_empty() {
            return best;
        }
        let inv_dir = ray.dir.recip();
        let origin = ray.origin;
        let mut limit = best.map_or(t_max, |b| b.t);
        if self.nodes[0].entry(origin, inv_dir, limit).is_none() {
            return best;
        }
        let mut stack = [0u32; STACK_SIZE];
        let mut sp = 0usize;
        let mut current = 0usize;
        loop {
            let node = &self.nodes[current];
            if node.count > 0 {
                let first = node.index as usize;
                for &prim in &self.refs[first..first + node.count as usize] {
                    if let Some(hit) = prims.intersect(prim, ray, limit) {
                        if any {
                            return Some(hit);
                        }
                        if best.is_none_or(|b| hit.is_closer_than(&b)) {
                            best = Some(hit);
                            limit = hit.t;
                        }
                    }
                }
            } else {
                let left = current + 1;
                let right = node.index as usize;
                let t_left = self.nodes[left].entry(origin, inv_dir, limit);
                let t_right = self.nodes[right].entry(origin, inv_dir, limit);
                match (t_left, t_right) {
                    (Some(tl), Some(tr)) => {
                        let (near, far) = if tl <= tr { (left, right) } else { (right, left) };
                        stack[sp] = far as u32;
                        sp += 1;
                        current = near;
                        continue;
                    }
                    (Some(_), None) => {
                        current = left;
                        continue;
                    }
                    (None, Some(_)) => {
                        current = right;
                        continue;
                    }
                    (None, None) => {}
                }
            }
            if sp == 0 {
                return best;
            }
            sp -= 1;
            current = stack[sp] as usize;
        }
    }
}

impl Builder<'_> {
    fn bounds_of(&self, start: usize, end: usize) -> (Aabb, Aabb) {
        self.refs[start..end].iter().fold((Aabb::EMPTY, Aabb::EMPTY), |(b, c), &r| {
            (
                b.union(self.bounds[r as usize]),
                c.grow(self.centroids[r as usize]),
            )
        })
    }

    fn push_leaf(&mut self, node: usize, bounds: Aabb, start: usize, end: usize) {
        self.nodes[node] = Node {
            min: bounds.min,
            index: start as u32,
            max: bounds.max,
            count: (end - start) as u32,
        };
    }

    /// Builds the subtree over `refs[start..end]` and returns its node index.
    fn build_node(&mut self, start: usize, end: usize, depth: usize) -> usize {
        let node = self.nodes.len();
        self.nodes.push(Node {
            min: Vec3::ZERO,
            index: 0,
            max: Vec3::ZERO,
            count: 0,
        });
        self.max_depth = self.max_depth.max(depth);
        let (bounds, centroid_bounds) = self.bounds_of(start, end);
        let count = end - start;
        if count <= 1 || depth + 2 >= STACK_SIZE {
            self.push_leaf(node, bounds, start, end);
            return node;
        }
        let mid = match self.find_split(start, end, &bounds, &centroid_bounds) {
            Some(mid) => mid,
            None if count <= self.options.max_leaf_size => {
                self.push_leaf(node, bounds, start, end);
                return node;
            }
            None => match self.median_split(start, end, &centroid_bounds) {
                Some(mid) => mid,
                None => {
                    // All centroids coincide: nothing separates these primitives.
                    self.push_leaf(node, bounds, start, end);
                    return node;
                }
            },
        };
        self.build_node(start, mid, depth + 1);
        let right = self.build_node(mid, end, depth + 1);
        self.nodes[node] = Node {
            min: bounds.min,
            index: right as u32,
            max: bounds.max,
            count: 0,
        };
        node
    }

    /// Binned SAH: partitions `refs[start..end]` and returns the split point, or `None` when
    /// a leaf is cheaper (only if the leaf is small enough) or no split separates anything.
    fn find_split(
        &mut self,
        start: usize,
        end: usize,
        bounds: &Aabb,
        centroid_bounds: &Aabb,
    ) -> Option<usize> {
        let nbins = self.options.bins.max(2);
        let extent = centroid_bounds.extent();
        let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, split bin)
        for axis in 0..3 {
            if extent[axis] <= 0.0 {
                continue;
            }
            let scale = nbins as f32 / extent[axis];
            let lo = centroid_bounds.min[axis];
            let mut bins = vec![
                Bin {
                    bounds: Aabb::EMPTY,
                    count: 0
                };
                nbins
            ];
            for &r in &self.refs[start..end] {
                let b = (((self.centroids[r as usize][axis] - lo) * scale) as usize).min(nbins - 1);
                bins[b].count += 1;
                bins[b].bounds = bins[b].bounds.union(self.bounds[r as usize]);
            }
            // Sweep from the right to collect right-side areas and counts.
            let mut right_area = vec![0.0f32; nbins];
            let mut right_count = vec![0u32; nbins];
            let (mut acc_b, mut acc_n) = (Aabb::EMPTY, 0u32);
            for i in (1..nbins).rev() {
                acc_b = acc_b.union(bins[i].bounds);
                acc_n += bins[i].count;
                right_area[i] = acc_b.surface_area();
                right_count[i] = acc_n;
            }
            let (mut left_b, mut left_n) = (Aabb::EMPTY, 0u32);
            for split in 1..nbins {
                left_b = left_b.union(bins[split - 1].bounds);
                left_n += bins[split - 1].count;
                if left_n == 0 || right_count[split] == 0 {
                    continue;
                }
                let cost = left_b.surface_area() * left_n as f32
                    + right_area[split] * right_count[split] as f32;
                if best.is_none_or(|(c, _, _)| cost < c) {
                    best = Some((cost, axis, split));
                }
            }
        }
        let (cost, axis, split) = best?;
        let count = (end - start) as f32;
        let area = bounds.surface_area().max(f32::MIN_POSITIVE);
        let split_cost = self.options.traversal_cost + cost / area;
        if split_cost >= count && end - start <= self.options.max_leaf_size {
            return None;
        }
        let lo = centroid_bounds.min[axis];
        let scale = nbins as f32 / extent[axis];
        let centroids = &self.centroids;
        let mid = partition(&mut self.refs[start..end], |r| {
            (((centroids[r as usize][axis] - lo) * scale) as usize).min(nbins - 1) < split
        });
        (mid > 0 && mid < end - start).then_some(start + mid)
    }

    /// Splits at the median centroid along the widest centroid axis.
    fn median_split(&mut self, start: usize, end: usize, centroid_bounds: &Aabb) -> Option<usize> {
        let axis = centroid_bounds.longest_axis();
        if centroid_bounds.extent()[axis] <= 0.0 {
            return None;
        }
        let mid = (end - start) / 2;
        let centroids = &self.centroids;
        self.refs[start..end].select_nth_unstable_by(mid, |&a, &b| {
            centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis])
        });
        Some(start + mid)
    }
}

/// Moves the elements satisfying `pred` to the front; returns how many there are.
fn partition(v: &mut [u32], pred: impl Fn(u32) -> bool) -> usize {
    let mut first = 0;
    for i in 0..v.len() {
        if pred(v[i]) {
            v.swap(first, i);
            first += 1;
        }
    }
    first
}

impl<P: PrimitiveSet> Accelerator<P> for Bvh {
    fn closest_hit(&self, prims: &P, ray: &Ray, t_max: f32) -> Option<PrimHit> {
        self.traverse(prims, ray, t_max, false)
    }

    fn any_hit(&self, prims: &P, ray: &Ray, t_max: f32) -> bool {
        self.traverse(prims, ray, t_max, true).is_some()
    }

    fn stats(&self) -> AccelStats {
        AccelStats {
            kind: "bvh",
            primitives: self.refs.len() + self.unbounded.len(),
            nodes: self.nodes.len(),
            leaves: self.nodes.iter().filter(|n| n.count > 0).count(),
            max_depth: self.max_depth,
            references: self.refs.len() + self.unbounded.len(),
        }
    }
}
