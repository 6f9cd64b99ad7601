//! A tree over axis-aligned boxes for "which boxes meet this one" — the faces near a face in
//! the contact splits (`contact.rs`) — or "which boxes may a shaft cross" — the clusters of
//! primitives that may block the rays between two patches (`visibility.rs`). Built by median
//! splits of the boxes' centres along the longest axis of their bounds, [`LEAF_SIZE`] boxes at most per leaf; a query visits the
//! nodes whose bounds meet the query box. Building takes `O(n log n)`, a query `O(log n + k)`
//! for `k` boxes found, whatever the sizes of the boxes (a grid of one cell size, which this
//! replaced, made every query of a face much larger than the cells visit all faces).

use super::shaft::Bounds;

/// Boxes per leaf at most.
const LEAF_SIZE: usize = 8;

/// One node: its bounds and either two children or a range of `order`.
#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Bounds,
    /// Inner node: index of the first child (the second follows it); leaf: start in `order`.
    first: u32,
    /// Leaf: number of boxes; 0 for an inner node.
    count: u32,
}

/// The tree (see the module documentation).
#[derive(Clone, Debug, Default)]
pub struct BoxTree {
    nodes: Vec<Node>,
    /// Box indices, leaf by leaf.
    order: Vec<u32>,
    /// The boxes.
    boxes: Vec<Bounds>,
    /// Boxes with a non-finite coordinate: found by every query.
    unbounded: Vec<u32>,
}

impl BoxTree {
    /// The tree over `boxes` (indices into it are what queries return).
    pub fn new(boxes: &[Bounds]) -> Self {
        let (mut order, unbounded): (Vec<u32>, Vec<u32>) =
            (0..boxes.len() as u32).partition(|&i| finite(&boxes[i as usize]));
        let mut tree = BoxTree {
            nodes: Vec::with_capacity(2 * order.len() / LEAF_SIZE + 1),
            order: Vec::new(),
            boxes: boxes.to_vec(),
            unbounded,
        };
        if !order.is_empty() {
            tree.nodes.push(Node {
                bounds: Bounds::from_points([]),
                first: 0,
                count: 0,
            });
            tree.build(0, boxes, &mut order, 0);
        }
        tree.order = order;
        tree
    }

    /// Fills node `node` with the boxes `items` (which start at `offset` in the final order).
    fn build(&mut self, node: usize, boxes: &[Bounds], items: &mut [u32], offset: usize) {
        let bounds = items
            .iter()
            .fold(Bounds::from_points([]), |b, &i| b.union(boxes[i as usize]));
        if items.len() <= LEAF_SIZE {
            self.nodes[node] = Node {
                bounds,
                first: offset as u32,
                count: items.len() as u32,
            };
            return;
        }
        let axis = (bounds.max - bounds.min).max_position();
        let centre = |i: &u32| {
            let b = boxes[*i as usize];
            b.min[axis] + b.max[axis]
        };
        let half = items.len() / 2;
        items.select_nth_unstable_by(half, |a, b| centre(a).total_cmp(&centre(b)));
        let first = self.nodes.len();
        let empty = Node {
            bounds,
            first: 0,
            count: 0,
        };
        self.nodes.extend([empty, empty]);
        self.nodes[node] = Node {
            bounds,
            first: first as u32,
            count: 0,
        };
        let (left, right) = items.split_at_mut(half);
        self.build(first, boxes, left, offset);
        self.build(first + 1, boxes, right, offset + half);
    }

    /// Indices of the boxes that meet `query` (touching counts), each once, ascending.
    pub fn meeting(&self, query: &Bounds) -> Vec<usize> {
        self.find(|b| b.overlaps(query))
    }

    /// Indices of the boxes that `keep` accepts, each once, ascending, for a `keep` that
    /// refuses every box inside a box it refuses (a box meets a query, a shaft may cross a
    /// box): whole subtrees whose bounds it refuses are skipped. Boxes with a non-finite
    /// coordinate are always found.
    pub fn find(&self, keep: impl Fn(&Bounds) -> bool) -> Vec<usize> {
        let mut found: Vec<usize> = self.unbounded.iter().map(|&i| i as usize).collect();
        let mut stack = Vec::new();
        if !self.nodes.is_empty() {
            stack.push(0);
        }
        while let Some(n) = stack.pop() {
            let node = self.nodes[n];
            if !keep(&node.bounds) {
                continue;
            }
            if node.count == 0 {
                stack.extend([node.first as usize, node.first as usize + 1]);
            } else {
                let range = node.first as usize..(node.first + node.count) as usize;
                found.extend(
                    self.order[range]
                        .iter()
                        .map(|&i| i as usize)
                        .filter(|&i| keep(&self.boxes[i])),
                );
            }
        }
        found.sort_unstable();
        found
    }
}

/// Whether every coordinate of `b` is finite.
fn finite(b: &Bounds) -> bool {
    b.min.is_finite() && b.max.is_finite()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn finds_exactly_the_boxes_a_query_meets() {
        // Boxes of very different sizes, as faces of a building are: a brute-force check.
        let mut boxes = Vec::new();
        let mut seed = 12345u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for k in 0..500 {
            let size = if k % 50 == 0 {
                5.0
            } else {
                0.01 + 0.1 * next()
            };
            let lo = DVec3::new(next(), next(), next()) * 10.0;
            let extent = DVec3::new(next(), next(), next()) * size;
            boxes.push(Bounds {
                min: lo,
                max: lo + extent,
            });
        }
        boxes.push(Bounds {
            min: DVec3::NEG_INFINITY,
            max: DVec3::INFINITY,
        });
        let tree = BoxTree::new(&boxes);
        for q in 0..200 {
            let lo = DVec3::new(next(), next(), next()) * 10.0;
            let query = Bounds {
                min: lo,
                max: lo + DVec3::splat(if q % 10 == 0 { 4.0 } else { 0.3 }),
            };
            let expected: Vec<usize> = (0..boxes.len())
                .filter(|&i| !finite(&boxes[i]) || boxes[i].overlaps(&query))
                .collect();
            assert_eq!(tree.meeting(&query), expected);
        }
        assert!(
            BoxTree::new(&[])
                .meeting(&Bounds {
                    min: DVec3::ZERO,
                    max: DVec3::ONE
                })
                .is_empty()
        );
    }
}
