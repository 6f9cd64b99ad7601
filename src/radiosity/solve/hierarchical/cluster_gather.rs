//! What the cluster links bring in a gather, their geometry worked out once for all the
//! gathers while the links stay as they are.
//!
//! A cluster link brings its receiver's members, side by side, `c·s·Σₑ wₑ·Bₑ`: the emitter's
//! member sides that face the receiver's centre, each weighed by `wₑ = A·cos θ/d²` (its own
//! distance and angle to that centre), the receiver's members that see the emitter, each by
//! `c = cos θ·v/d²` (its angle and distance from the emitter's centre, `v` the share of its
//! rays that arrive, in 255ths), and `s = d_c²/(255·π)` of the centres' distance `d_c` (the
//! irradiance at the receiver's centre spread to each member by `d_c²/d²`, which gets the
//! kernel `1/d²` right to first order in the ends' sizes). Between the gathers of a round
//! only the radiosity `B` changes, so [`GatherPlan`] holds the sides and their weights and a
//! gather is a sum and a scatter per link — the same sums, to the last bit, as working out
//! the geometry at every gather: each weight is computed by the same expression, and the
//! terms are added in the same order.

use super::clusters::{ClusterLink, ClusterTree};
use super::nodes::node;
use crate::color::Rgb64;
use crate::radiosity::mesh::PatchMesh;
use std::f64::consts::PI;

/// The gathers of a run of cluster links, worked out: per link that brings light, its
/// emitter's and receiver's sides with their weights (those with none left out).
#[derive(Clone, Debug, Default)]
pub struct GatherPlan {
    links: Vec<PlannedLink>,
    /// Per side, in link order (each link's emitter sides, then its receiver sides): its node.
    nodes: Vec<u32>,
    /// Per side, its weight: `wₑ` (m² per m², dimensionless over the distance squared) for
    /// an emitter side, `c` (per m², over 255) for a receiver side.
    weights: Vec<f64>,
}

/// One link of a [`GatherPlan`].
#[derive(Clone, Copy, Debug)]
struct PlannedLink {
    /// How many of the plan's sides are its emitter's, then its receiver's.
    emitters: u32,
    receivers: u32,
    /// `d_c²/255`, square scene units.
    scale: f64,
}

impl GatherPlan {
    /// The gathers of `links` (clusters of `tree` over the root patches of `mesh`) worked
    /// out, room made for `sides` sides ([`Self::sides_at_most`]); a link whose ends are not
    /// separated, or that no receiver member sees, brings nothing and is left out.
    pub fn new(tree: &ClusterTree, mesh: &PatchMesh, links: &[ClusterLink], sides: usize) -> Self {
        let mut plan = GatherPlan {
            links: Vec::with_capacity(links.len()),
            nodes: Vec::with_capacity(sides),
            weights: Vec::with_capacity(sides),
        };
        for link in links {
            plan.add(tree, mesh, link);
        }
        plan
    }

    /// The number of sides the gathers of `links` would hold at most (every member of both
    /// ends), without working them out.
    pub fn sides_at_most(tree: &ClusterTree, links: &[ClusterLink]) -> usize {
        (links.iter())
            .map(|l| tree.members(&l.emitter).len() + tree.members(&l.receiver).len())
            .sum()
    }

    fn add(&mut self, tree: &ClusterTree, mesh: &PatchMesh, link: &ClusterLink) {
        if !link.separated() || link.visible.iter().all(|&v| v == 0) {
            return;
        }
        let start = self.nodes.len();
        for &p in tree.members(&link.emitter) {
            let patch = mesh.patch(p);
            let to = link.receiver_centre - patch.centroid;
            let d2 = to.length_squared();
            let direction = to / d2.sqrt();
            let (side, cos) = tree.side_towards(patch, direction, link.receiver_centre);
            self.push(node(p, side), patch.area * cos / d2);
        }
        let emitters = self.nodes.len() - start;
        for (&p, &v) in tree.members(&link.receiver).iter().zip(&link.visible) {
            if v > 0 {
                let patch = mesh.patch(p);
                let from = patch.centroid - link.emitter_centre;
                let d2 = from.length_squared();
                let direction = -from / d2.sqrt();
                let (side, cos) = tree.side_towards(patch, direction, link.emitter_centre);
                self.push(node(p, side), cos * f64::from(v) / d2);
            }
        }
        self.links.push(PlannedLink {
            emitters: emitters as u32,
            receivers: (self.nodes.len() - start - emitters) as u32,
            scale: link.distance * link.distance / 255.0,
        });
    }

    /// A side with a weight (a side of weight zero adds nothing and is left out).
    fn push(&mut self, node: usize, weight: f64) {
        if weight != 0.0 {
            self.nodes.push(node as u32);
            self.weights.push(weight);
        }
    }

    /// Adds to `gathered` (per node, W·m⁻²) the irradiance the plan's links bring, given the
    /// radiosity per node (W·m⁻²).
    pub fn gather(&self, radiosity: &[Rgb64], gathered: &mut [Rgb64]) {
        let mut k = 0;
        for link in &self.links {
            let emitters = k..k + link.emitters as usize;
            let receivers = emitters.end..emitters.end + link.receivers as usize;
            k = receivers.end;
            let sent = (self.nodes[emitters.clone()].iter())
                .zip(&self.weights[emitters])
                .fold(Rgb64::BLACK, |sum, (&n, &w)| {
                    sum + radiosity[n as usize] * w
                });
            let at_centre = sent.map(|v| v / PI) * link.scale;
            for (&n, &w) in self.nodes[receivers.clone()]
                .iter()
                .zip(&self.weights[receivers])
            {
                gathered[n as usize] += at_centre * w;
            }
        }
    }
}
