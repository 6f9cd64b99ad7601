//! Bounding-volume hierarchy built with the binned surface-area heuristic (SAH).
//!
//! The tree is built binary (depth-first: an inner node's left child follows it, it records
//! its right child) and then collapsed into an 8-wide tree whose nodes hold the boxes of their
//! eight children side by side, so one SIMD slab test checks all eight (one AVX instruction
//! per step where the CPU has AVX). Leaves of plain triangles are packed into blocks of eight
//! tested at once. Traversal visits hit children nearest first and skips those starting
//! beyond the closest hit found so far.
//! Unbounded primitives (infinite planes) are kept outside the tree and tested by every ray.

use super::{AccelStats, Accelerator, PrimHit, PrimitiveSet, keep_closest};
use crate::geometry::{Aabb, Ray, Ray8, TRIANGLE_LANES, Triangle, Triangle8};
use glam::{Vec3, Vec4};
use rayon::prelude::*;
use wide::{CmpLe, f32x8};

/// Build options of the BVH.
#[derive(Clone, Debug)]
pub struct BvhOptions {
    /// Leaves never hold more than this many primitives unless they cannot be split.
    pub max_leaf_size: usize,
    /// Number of bins per axis for the SAH sweep.
    pub bins: usize,
    /// Cost of visiting a binary node of the SAH build relative to testing one block of
    /// eight triangles. The default 0.1 is small because the binary tree is collapsed into
    /// 8-wide nodes, one visit of which stands for three binary levels (measured best on the
    /// Cornell box and the 331k-triangle conference room).
    pub traversal_cost: f32,
}

impl Default for BvhOptions {
    fn default() -> Self {
        BvhOptions {
            max_leaf_size: 8,
            bins: 16,
            traversal_cost: 0.1,
        }
    }
}

/// One node: its box, and either its children (`count == 0`, right child at `index`) or its
/// primitives (`count > 0`, references `index .. index + count`). The index and count ride
/// in the unused fourth lanes of the corners so a node is two SIMD registers (32 bytes).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
struct BinaryNode {
    min: Vec4,
    max: Vec4,
}

impl BinaryNode {
    fn new(bounds: Aabb, index: u32, count: u32) -> Self {
        BinaryNode {
            min: bounds.min.extend(f32::from_bits(index)),
            max: bounds.max.extend(f32::from_bits(count)),
        }
    }

    #[inline(always)]
    fn index(&self) -> u32 {
        self.min.w.to_bits()
    }

    #[inline(always)]
    fn count(&self) -> u32 {
        self.max.w.to_bits()
    }

    fn bounds(&self) -> Aabb {
        Aabb::new(self.min.truncate(), self.max.truncate())
    }
}

/// `1 + 2γ₃` (Pharr et al., PBR 3rd ed. §3.9.2): makes the slab test conservative.
const ROBUST_FAR: f32 = 1.0 + 2.0 * (3.0 * f32::EPSILON * 0.5) / (1.0 - 3.0 * f32::EPSILON * 0.5);

/// Binary tree depth limit (leaves are forced beyond it); bounds the traversal stack.
const MAX_BINARY_DEPTH: usize = 64;
/// References under a node from which its two subtrees are built at once (a few
/// milliseconds of building each: `field`'s 320,002 triangles take about 80 ns a reference
/// and level on one thread).
const PARALLEL_BUILD: usize = 4096;
/// Children per wide node.
const WIDTH: usize = 8;
/// Traversal stack size: every wide node visited pushes at most `WIDTH − 1` entries more than
/// it pops, and wide trees are at most `MAX_BINARY_DEPTH` deep.
const STACK_SIZE: usize = (WIDTH - 1) * MAX_BINARY_DEPTH + WIDTH;
/// `count` of an unused child slot.
const EMPTY: u32 = u32::MAX;
/// Flag in a leaf's `count`: its primitives are plain triangles packed eight to a block, and
/// `child` is the first block.
const PACKED: u32 = 1 << 30;

/// An 8-wide node: the boxes of up to eight children as structure-of-arrays lanes.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct WideNode {
    min_x: f32x8,
    min_y: f32x8,
    min_z: f32x8,
    max_x: f32x8,
    max_y: f32x8,
    max_z: f32x8,
    /// Per child: wide-node index (inner child) or first reference (leaf child).
    child: [u32; WIDTH],
    /// Per child: 0 for an inner node, the number of references for a leaf, `EMPTY` unused.
    count: [u32; WIDTH],
}

impl WideNode {
    /// A node with eight unused slots. An unused slot's box lies at +∞ on every axis, so no
    /// ray with a finite parameter limit ever enters it and traversal needs no check.
    fn empty() -> Self {
        let inf = f32x8::splat(f32::INFINITY);
        WideNode {
            min_x: inf,
            min_y: inf,
            min_z: inf,
            max_x: inf,
            max_y: inf,
            max_z: inf,
            child: [0; WIDTH],
            count: [EMPTY; WIDTH],
        }
    }

    fn set_bounds(&mut self, slot: usize, b: &Aabb) {
        let set = |lanes: &mut f32x8, v: f32| {
            let mut a = lanes.to_array();
            a[slot] = v;
            *lanes = f32x8::new(a);
        };
        set(&mut self.min_x, b.min.x);
        set(&mut self.min_y, b.min.y);
        set(&mut self.min_z, b.min.z);
        set(&mut self.max_x, b.max.x);
        set(&mut self.max_y, b.max.y);
        set(&mut self.max_z, b.max.z);
    }
}

/// A ray prepared for 8-wide slab tests and triangle blocks.
struct WideRay {
    origin: [f32x8; 3],
    inv_dir: [f32x8; 3],
    lanes: Ray8,
}

impl WideRay {
    fn new(ray: &Ray) -> Self {
        WideRay {
            origin: ray.origin.to_array().map(f32x8::splat),
            inv_dir: glam::Vec3A::from(ray.dir)
                .recip()
                .to_array()
                .map(f32x8::splat),
            lanes: Ray8::new(ray),
        }
    }

    /// Entry parameters into the eight child boxes and the mask of those entered before
    /// `t_max`.
    #[inline(always)]
    fn test(&self, n: &WideNode, t_max: f32) -> ([f32; WIDTH], u32) {
        let t0x = (n.min_x - self.origin[0]) * self.inv_dir[0];
        let t1x = (n.max_x - self.origin[0]) * self.inv_dir[0];
        let t0y = (n.min_y - self.origin[1]) * self.inv_dir[1];
        let t1y = (n.max_y - self.origin[1]) * self.inv_dir[1];
        let t0z = (n.min_z - self.origin[2]) * self.inv_dir[2];
        let t1z = (n.max_z - self.origin[2]) * self.inv_dir[2];
        // `fast_min`/`fast_max` are the plain SIMD min/max: a NaN (0·∞ for a ray in a slab
        // plane) yields the second operand, so it never widens the interval.
        let near = t0x
            .fast_min(t1x)
            .fast_max(t0y.fast_min(t1y))
            .fast_max(t0z.fast_min(t1z))
            .fast_max(f32x8::ZERO);
        // Widened by a few ulps so rounding never loses a primitive touching a box face.
        let far = t0x
            .fast_max(t1x)
            .fast_min(t0y.fast_max(t1y))
            .fast_min(t0z.fast_max(t1z))
            * f32x8::splat(ROBUST_FAR);
        let mask = near.cmp_le(far) & near.cmp_le(f32x8::splat(t_max));
        (near.to_array(), mask.move_mask() as u32)
    }
}

/// A SAH bounding-volume hierarchy.
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<WideNode>,
    refs: Vec<u32>,
    /// Leaves of plain triangles, eight per block, with the primitive index of each lane
    /// (`u32::MAX` for padding).
    blocks: Vec<(Triangle8, [u32; TRIANGLE_LANES])>,
    unbounded: Vec<u32>,
    max_depth: usize,
}

/// Builds the binary hierarchy over `refs`, the primitive references from `offset` on in the
/// whole list, in depth-first order (a node's left child right after it). Subtrees of at
/// least [`PARALLEL_BUILD`] references are built by builders of their own on the rayon pool
/// and appended in order: the same nodes, to the last bit, for any thread count.
struct Builder<'a> {
    options: &'a BvhOptions,
    bounds: &'a [Aabb],
    centroids: &'a [Vec3],
    refs: &'a mut [u32],
    offset: usize,
    nodes: Vec<BinaryNode>,
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
        let bounds: Vec<Aabb> = (0..n as u32)
            .into_par_iter()
            .map(|i| prims.bounds(i))
            .collect();
        let (finite, unbounded): (Vec<u32>, Vec<u32>) = (0..n as u32).partition(|&i| {
            let b = &bounds[i as usize];
            !b.is_empty() && b.min.is_finite() && b.max.is_finite()
        });
        let centroids: Vec<Vec3> = bounds.par_iter().map(Aabb::center).collect();
        let mut refs = finite;
        let mut nodes = Vec::new();
        let mut max_depth = 0;
        if !refs.is_empty() {
            let count = refs.len();
            let mut builder = Builder {
                options,
                bounds: &bounds,
                centroids: &centroids,
                refs: &mut refs,
                offset: 0,
                nodes: Vec::with_capacity(2 * n / options.max_leaf_size.max(1) + 1),
                max_depth: 0,
            };
            builder.build_node(0, count, 0);
            collapse(&builder.nodes, 0, 0, &mut nodes, &mut max_depth);
        }
        let blocks = pack_plain_triangles(prims, &mut nodes, &refs);
        Bvh {
            nodes,
            refs,
            blocks,
            unbounded,
            max_depth,
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
        let wide_ray = WideRay::new(ray);
        // A finite limit keeps rays out of unused child slots (see `WideNode::empty`).
        let mut limit = best.map_or(t_max, |b| b.t).min(f32::MAX);
        // Children waiting: (child, count, entry parameter); uninitialised beyond `sp`.
        let mut stack = [std::mem::MaybeUninit::<Entry>::uninit(); STACK_SIZE];
        let mut sp = 0usize;
        let mut current: Entry = (0, 0, 0.0);
        loop {
            let (child, count, _) = current;
            if count & PACKED != 0 {
                let n = (count & !PACKED) as usize;
                let first = child as usize;
                for (block, lanes) in &self.blocks[first..first + n.div_ceil(TRIANGLE_LANES)] {
                    let hits = block.intersect(&wide_ray.lanes, limit);
                    let mut mask = hits.mask;
                    while mask != 0 {
                        let lane = mask.trailing_zeros() as usize;
                        mask &= mask - 1;
                        let Some((t, b1, b2)) = hits.lane(lane, limit) else {
                            continue;
                        };
                        let hit = PrimHit {
                            t,
                            prim: lanes[lane],
                            local: [b1, b2],
                            part: 0,
                        };
                        if any {
                            return Some(hit);
                        }
                        if best.is_none_or(|b| hit.is_closer_than(&b)) {
                            best = Some(hit);
                            limit = hit.t;
                        }
                    }
                }
            } else if count > 0 {
                let first = child as usize;
                for &prim in &self.refs[first..first + count as usize] {
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
                let node = &self.nodes[child as usize];
                let (near, mut mask) = wide_ray.test(node, limit);
                let entry = |slot: usize| (node.child[slot], node.count[slot], near[slot]);
                match mask.count_ones() {
                    0 => {}
                    1 => {
                        current = entry(mask.trailing_zeros() as usize);
                        continue;
                    }
                    _ if any => {
                        // Any hit ends the search, so the order does not matter: no sorting.
                        current = entry(mask.trailing_zeros() as usize);
                        mask &= mask - 1;
                        while mask != 0 {
                            stack[sp].write(entry(mask.trailing_zeros() as usize));
                            sp += 1;
                            mask &= mask - 1;
                        }
                        continue;
                    }
                    2 => {
                        let a = entry(mask.trailing_zeros() as usize);
                        let b = entry(31 - mask.leading_zeros() as usize);
                        let (near_child, far_child) = if b.2 < a.2 { (b, a) } else { (a, b) };
                        stack[sp].write(far_child);
                        sp += 1;
                        current = near_child;
                        continue;
                    }
                    _ => {
                        // Three or more children: sort farthest first, visit the nearest.
                        let mut hits = [(0u32, 0u32, 0f32); WIDTH];
                        let mut n = 0;
                        while mask != 0 {
                            let e = entry(mask.trailing_zeros() as usize);
                            mask &= mask - 1;
                            let mut k = n;
                            while k > 0 && hits[k - 1].2 < e.2 {
                                hits[k] = hits[k - 1];
                                k -= 1;
                            }
                            hits[k] = e;
                            n += 1;
                        }
                        for &e in &hits[..n - 1] {
                            stack[sp].write(e);
                            sp += 1;
                        }
                        current = hits[n - 1];
                        continue;
                    }
                }
            }
            // Pop the nearest waiting child that still starts before the closest hit.
            loop {
                if sp == 0 {
                    return best;
                }
                sp -= 1;
                // SAFETY: every slot below `sp` was written before `sp` moved past it.
                let entry = unsafe { stack[sp].assume_init() };
                if entry.2 <= limit {
                    current = entry;
                    break;
                }
            }
        }
    }
}

/// Packs every leaf whose primitives are all plain triangles into eight-wide blocks and marks
/// it `PACKED`; returns the blocks.
fn pack_plain_triangles<P: PrimitiveSet>(
    prims: &P,
    nodes: &mut [WideNode],
    refs: &[u32],
) -> Vec<(Triangle8, [u32; TRIANGLE_LANES])> {
    let mut blocks = Vec::new();
    for node in nodes.iter_mut() {
        for slot in 0..WIDTH {
            let count = node.count[slot];
            if count == 0 || count == EMPTY {
                continue;
            }
            let first = node.child[slot] as usize;
            let leaf = &refs[first..first + count as usize];
            let Some(tris) = leaf
                .iter()
                .map(|&p| prims.plain_triangle(p))
                .collect::<Option<Vec<Triangle>>>()
            else {
                continue;
            };
            node.child[slot] = blocks.len() as u32;
            node.count[slot] = count | PACKED;
            let chunks = tris.chunks(TRIANGLE_LANES).zip(leaf.chunks(TRIANGLE_LANES));
            for (chunk, ids) in chunks {
                let mut lanes = [u32::MAX; TRIANGLE_LANES];
                lanes[..ids.len()].copy_from_slice(ids);
                blocks.push((Triangle8::new(chunk), lanes));
            }
        }
    }
    blocks
}

/// A child waiting for traversal: (wide node or first reference, reference count (0 for an
/// inner node), ray parameter where the ray enters its box).
type Entry = (u32, u32, f32);

/// Turns the binary subtree at `node` into wide nodes appended to `wide`; returns the index
/// of its wide root. Each wide node takes the binary children of `node` and keeps opening the
/// largest inner one until it has eight children.
fn collapse(
    binary: &[BinaryNode],
    node: usize,
    depth: usize,
    wide: &mut Vec<WideNode>,
    max_depth: &mut usize,
) -> u32 {
    *max_depth = (*max_depth).max(depth);
    let mut kids: Vec<usize> = if binary[node].count() > 0 {
        vec![node]
    } else {
        vec![node + 1, binary[node].index() as usize]
    };
    while kids.len() < WIDTH {
        let largest_inner = kids
            .iter()
            .enumerate()
            .filter(|&(_, &k)| binary[k].count() == 0)
            .max_by(|a, b| {
                let area = |k: usize| binary[k].bounds().surface_area();
                area(*a.1).total_cmp(&area(*b.1))
            })
            .map(|(pos, _)| pos);
        let Some(pos) = largest_inner else { break };
        let k = kids.swap_remove(pos);
        kids.push(k + 1);
        kids.push(binary[k].index() as usize);
    }
    let me = wide.len();
    wide.push(WideNode::empty());
    for (slot, &k) in kids.iter().enumerate() {
        let (child, count) = if binary[k].count() > 0 {
            (binary[k].index(), binary[k].count())
        } else {
            (collapse(binary, k, depth + 1, wide, max_depth), 0)
        };
        let n = &mut wide[me];
        n.set_bounds(slot, &binary[k].bounds());
        n.child[slot] = child;
        n.count[slot] = count;
    }
    me as u32
}

impl Builder<'_> {
    fn bounds_of(&self, start: usize, end: usize) -> (Aabb, Aabb) {
        self.refs[start..end]
            .iter()
            .fold((Aabb::EMPTY, Aabb::EMPTY), |(b, c), &r| {
                (
                    b.union(self.bounds[r as usize]),
                    c.grow(self.centroids[r as usize]),
                )
            })
    }

    fn push_leaf(&mut self, node: usize, bounds: Aabb, start: usize, end: usize) {
        let first = self.offset + start;
        self.nodes[node] = BinaryNode::new(bounds, first as u32, (end - start) as u32);
    }

    /// The subtrees over `refs[start..mid]` and `refs[mid..end]` (at `depth`), each by a
    /// builder of its own, both at once; appends their nodes, left then right, and returns
    /// the right one's index.
    fn build_both(&mut self, start: usize, mid: usize, end: usize, depth: usize) -> usize {
        let (options, bounds, centroids) = (self.options, self.bounds, self.centroids);
        let (left, right) = self.refs[start..end].split_at_mut(mid - start);
        let [mut left, mut right] = [(left, start), (right, mid)].map(|(refs, at)| Builder {
            options,
            bounds,
            centroids,
            refs,
            offset: self.offset + at,
            nodes: Vec::new(),
            max_depth: 0,
        });
        rayon::join(
            || left.build_node(0, mid - start, depth),
            || right.build_node(0, end - mid, depth),
        );
        let [left, right] = [left, right].map(|b| (b.nodes, b.max_depth));
        self.append(left);
        self.append(right)
    }

    /// Appends the `nodes` of a subtree `depth` deep, their children's indices moved to
    /// where they land; returns where its root landed.
    fn append(&mut self, (nodes, depth): (Vec<BinaryNode>, usize)) -> usize {
        let base = self.nodes.len();
        self.nodes.extend(nodes.iter().map(|n| {
            if n.count() == 0 {
                BinaryNode::new(n.bounds(), n.index() + base as u32, 0)
            } else {
                *n
            }
        }));
        self.max_depth = self.max_depth.max(depth);
        base
    }

    /// Builds the subtree over `refs[start..end]` and returns its node index.
    fn build_node(&mut self, start: usize, end: usize, depth: usize) -> usize {
        let node = self.nodes.len();
        self.nodes
            .push(BinaryNode::new(Aabb::new(Vec3::ZERO, Vec3::ZERO), 0, 0));
        self.max_depth = self.max_depth.max(depth);
        let (bounds, centroid_bounds) = self.bounds_of(start, end);
        let count = end - start;
        if count <= 1 || depth + 1 >= MAX_BINARY_DEPTH {
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
        let right = if count >= PARALLEL_BUILD {
            self.build_both(start, mid, end, depth + 1)
        } else {
            self.build_node(start, mid, depth + 1);
            self.build_node(mid, end, depth + 1)
        };
        self.nodes[node] = BinaryNode::new(bounds, right as u32, 0);
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
                let cost = left_b.surface_area() * leaf_cost(left_n as usize)
                    + right_area[split] * leaf_cost(right_count[split] as usize);
                if best.is_none_or(|(c, _, _)| cost < c) {
                    best = Some((cost, axis, split));
                }
            }
        }
        let (cost, axis, split) = best?;
        let area = bounds.surface_area().max(f32::MIN_POSITIVE);
        let split_cost = self.options.traversal_cost + cost / area;
        if split_cost >= leaf_cost(end - start) && end - start <= self.options.max_leaf_size {
            return None;
        }
        let lo = centroid_bounds.min[axis];
        let scale = nbins as f32 / extent[axis];
        let centroids = &self.centroids;
        let mid = super::partition(&mut self.refs[start..end], |r| {
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

/// SAH cost of testing a leaf of `n` primitives, relative to visiting a node: triangles are
/// tested eight at a time.
fn leaf_cost(n: usize) -> f32 {
    n.div_ceil(TRIANGLE_LANES) as f32
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
            leaves: self
                .nodes
                .iter()
                .flat_map(|n| n.count)
                .filter(|&c| c > 0 && c != EMPTY)
                .count(),
            max_depth: self.max_depth,
            references: self.refs.len() + self.unbounded.len(),
        }
    }
}
