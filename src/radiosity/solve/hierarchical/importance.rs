//! Importance (Smits, Arvo and Salesin 1992) for per-surface accuracy: how much an error in
//! the light a node receives matters to the figures the report gives, every reported
//! surface (object, or face with `per_face`) counted relative to its own power.
//!
//! The oracle's threshold `--error` is a share of all power emitted in the scene: a link may
//! bring its receiver that much power too much or too little. A dim face or a small leaf
//! receives little of the scene's power, so errors well within that threshold can be a large
//! part of its own (measured: +12 % on a Cornell-box block face with 0.5 % of the absorbed
//! power), and much of that error comes not from its own links but from the light of the
//! surfaces next to it (the floor in the block's shadow that the face sees).
//!
//! With `--surface-error ε`, a watt arriving on surface `S` has the direct importance
//! `w_S = 1/(ε·P_S)` (`P_S` the power `S` received in the last gather, both sides, luminance; at
//! least [`NEGLIGIBLE_SHARE`] of what all surfaces receive: a 2 × 2 cm measuring patch in a
//! room, a millionth of it or less, is held to its own power, and one that received nothing yet
//! — all its links blocked so far — is looked at again), and the importance of a watt arriving
//! at node `i` is `Γ_i = w_i + ρ_i·Σ_j F_ij^T Γ_j + τ_i·(the same for the other side)`: the
//! adjoint of the radiosity system, solved over the same links with the transport reversed (a
//! link's receiver passes `F·A_r/A_e·Γ_r` to its emitter) and the same push-pull. A link onto a
//! node of area `a` on a surface of area `A` is then also held to `Γ_r·δ ≤ √(a/A)` (`δ` the
//! uncertainty of the power it brings, W): the errors of the `A/a` nodes that cover a surface
//! add up like a random sum, `√(A/a)` times one of them, so each surface's error stays near the
//! share ε of its power, counting what it receives directly and through what its neighbours
//! reflect. (Holding each node to its area's share of ε, `a/A`, was as accurate at many times
//! the links; holding it to ε alone hardly changed a face's error: its error is the sum of many
//! small ones of one sign.) Cluster links carry no importance, but each is held to the smallest
//! threshold of the surfaces it brings light to: measuring patches far from the light they read
//! get it over cluster links. Before the first gather nothing is known, and the scene-wide
//! threshold alone applies.
//!
//! A measuring patch — a surface whose material scatters and emits nothing (black, passing
//! nothing through, untextured), such as a 2 × 2 cm quad placed to read the light — is held to
//! [`MEASURING_PATCH_ERROR`] even without `--surface-error` (its `ε_S`, the smaller where
//! both apply; surfaces without an error of their own weigh nothing): the light it receives
//! goes nowhere else, so its links and those of what it sees are all the budget costs.
//! Measured on `meters` (validate): the three patches from −100 % to +0.02 … +0.23 % at the
//! defaults, 0.006 → 0.010 s.

use super::links::Link;
use super::nodes::{Nodes, node, split_node};
use crate::measure::SurfaceTable;
use crate::radiosity::element::Side;
use crate::radiosity::mesh::{PatchId, PatchMesh};
use crate::world::World;

/// Surfaces receiving less than this share of the power all surfaces receive get the
/// importance of one at this share (a bound for the surfaces that receive nothing).
pub const NEGLIGIBLE_SHARE: f64 = 1e-9;

/// The relative error a surface that scatters and emits nothing (a measuring patch: black,
/// passing nothing through) is held to whatever `--surface-error` says, unless that is
/// smaller: the light it receives goes nowhere else, so refining its links changes no other
/// figure and costs only its own links and those of what it sees.
pub const MEASURING_PATCH_ERROR: f64 = 0.01;

/// Sweeps of the importance solve at most.
const MAX_SWEEPS: usize = 50;

/// The importance solve stops when a sweep changes it by at most this share.
const SWEEP_TOLERANCE: f64 = 1e-3;

/// The importance of the power each node receives, for the error budgets of the oracle.
#[derive(Clone, Debug)]
pub struct Importance {
    /// The relative error ε asked of every surface (0: none but the measuring patches').
    relative: f64,
    /// Per scene object: true when its material scatters and emits nothing (no lobe, no
    /// emission, no textures): its surface is a measuring patch.
    measures: Vec<bool>,
    /// The report's surfaces.
    table: SurfaceTable,
    /// Per node: the importance of a watt arriving there, 1/W (empty until known).
    per_node: Vec<f64>,
    /// Per surface: its area (one side), scene units².
    surface_area: Vec<f64>,
}

impl Importance {
    /// Importance for the surfaces `world` reports at relative error `relative` (nothing
    /// known yet).
    pub fn new(world: &World, relative: f64) -> Self {
        let scene = &world.scene;
        let measures: Vec<bool> = scene
            .objects
            .iter()
            .map(|o| scene.materials[o.material as usize].is_measuring())
            .collect();
        let may_measure = measures.contains(&true);
        Importance {
            relative,
            measures,
            // Measuring the surfaces costs a pass over the geometry: only when asked for.
            table: if relative > 0.0 || may_measure {
                SurfaceTable::new(&world.scene, &world.geometry)
            } else {
                SurfaceTable::default()
            },
            per_node: Vec::new(),
            surface_area: Vec::new(),
        }
    }

    /// True when scene object `object` is a measuring patch (its material scatters and
    /// emits nothing).
    pub fn is_measuring_patch(&self, object: u32) -> bool {
        self.measures.get(object as usize).copied().unwrap_or(false)
    }

    /// The error threshold of a link onto `receiver` (a node of `mesh`), W: the scene-wide
    /// threshold `scene_error` (W), or `√(a/A)/Γ` when that is smaller (`Γ` holds the ε of the
    /// surfaces its light reaches). A node created since the last update takes the importance
    /// of its nearest known ancestor.
    pub fn error(&self, mesh: &PatchMesh, receiver: u32, scene_error: f64) -> f64 {
        if self.per_node.is_empty() {
            return scene_error;
        }
        let mut n = receiver as usize;
        while n >= self.per_node.len() {
            let (patch, side) = split_node(n);
            match mesh.patch(patch).parent {
                Some(parent) => n = node(parent, side),
                None => return scene_error,
            }
        }
        let gamma = self.per_node[n];
        let patch = mesh.patch(receiver / 2);
        let area = self.surface_area[self.table.entry(patch.object, patch.face)];
        if gamma > 0.0 && area > 0.0 {
            scene_error.min((patch.area / area).sqrt() / gamma)
        } else {
            scene_error
        }
    }

    /// The error threshold of a cluster link onto the root patches `members`, W: the
    /// smallest of [`Self::error`] over both sides of each (the scene-wide `scene_error`
    /// while no importance is known).
    pub fn error_for_members(
        &self,
        mesh: &PatchMesh,
        members: &[PatchId],
        scene_error: f64,
    ) -> f64 {
        if self.per_node.is_empty() {
            return scene_error;
        }
        members
            .iter()
            .flat_map(|&p| Side::BOTH.map(|side| node(p, side) as u32))
            .fold(scene_error, |least, n| {
                least.min(self.error(mesh, n, scene_error))
            })
    }

    /// Solves the importance on `mesh` for the irradiance the leaves received in the last
    /// gather (`nodes`) over the patch links `links`; nothing to do without a relative
    /// error or a measuring patch.
    pub fn update(&mut self, mesh: &PatchMesh, nodes: &Nodes, links: &[Link]) {
        if self.relative <= 0.0 && !self.measures.contains(&true) {
            return;
        }
        let Some(weight) = self.surface_weights(mesh, nodes) else {
            return;
        };
        let count = nodes.radiosity.len();
        let direct: Vec<f64> = (0..count)
            .map(|n| {
                let patch = mesh.patch(split_node(n).0);
                weight[self.table.entry(patch.object, patch.face)]
            })
            .collect();
        let mut gamma = self.warm_start(mesh, &direct);
        let mut leaving = vec![0.0; count];
        for _ in 0..MAX_SWEEPS {
            leaving.iter_mut().for_each(|l| *l = 0.0);
            for link in links.iter().filter(|l| !l.is_blocked()) {
                let (r, e) = (link.receiver as usize, link.emitter as usize);
                let (ar, ae) = (
                    mesh.patch(r as PatchId / 2).area,
                    mesh.patch(e as PatchId / 2).area,
                );
                leaving[e] += link.coupling * ar / ae * gamma[r];
            }
            let sweep = Sweep {
                mesh,
                nodes,
                direct: &direct,
                leaving: &leaving,
            };
            let (mut change, mut total) = (0.0, 0.0);
            for &root in &mesh.roots {
                let (c, t) = sweep.descend(root, [0.0; 2], &mut gamma);
                change += c;
                total += t;
            }
            if change <= SWEEP_TOLERANCE * total {
                break;
            }
        }
        self.per_node = gamma;
    }

    /// The importance the solve starts from: the last update's, a node created since taking
    /// its parent's (the children of a split node share its light), and the direct importance
    /// before the first update. Started from the last solution, a few sweeps settle what the
    /// refinement changed (from the direct importance alone it took up to 50).
    fn warm_start(&self, mesh: &PatchMesh, direct: &[f64]) -> Vec<f64> {
        if self.per_node.is_empty() {
            return direct.to_vec();
        }
        let mut gamma = self.per_node.clone();
        // Patches are numbered after their parents: a parent's value is set before its
        // children's.
        let known = gamma.len();
        for (n, &own) in direct.iter().enumerate().skip(known) {
            let (patch, side) = split_node(n);
            gamma.push(match mesh.patch(patch).parent {
                Some(parent) => gamma[node(parent, side)],
                None => own,
            });
        }
        gamma
    }

    /// Per surface, the direct importance `1/(ε_S·P_S)` of a watt arriving there, 1/W (`ε_S`
    /// the surface's relative error: the one asked of every surface, or for a measuring
    /// patch at most [`MEASURING_PATCH_ERROR`]; 0 where no error is asked of it); `None`
    /// while no surface receives anything or none is held to an error.
    fn surface_weights(&mut self, mesh: &PatchMesh, nodes: &Nodes) -> Option<Vec<f64>> {
        let mut power = vec![0.0; self.table.len()];
        let mut measures = vec![true; self.table.len()];
        self.surface_area = vec![0.0; self.table.len()];
        for leaf in mesh.leaves() {
            let patch = mesh.patch(leaf);
            let h: f64 = Side::BOTH
                .iter()
                .map(|&side| nodes.irradiance[node(leaf, side)].luminance())
                .sum();
            let surface = self.table.entry(patch.object, patch.face);
            power[surface] += h * patch.area;
            self.surface_area[surface] += patch.area;
            measures[surface] &= self.measures[patch.object as usize];
        }
        let floor = NEGLIGIBLE_SHARE * power.iter().sum::<f64>();
        let relative = |s: usize| match (measures[s], self.relative > 0.0) {
            (true, true) => self.relative.min(MEASURING_PATCH_ERROR),
            (true, false) => MEASURING_PATCH_ERROR,
            (false, _) => self.relative,
        };
        let weights: Vec<f64> = (0..power.len())
            .map(|s| {
                let e = relative(s);
                if e > 0.0 {
                    1.0 / (e * power[s].max(floor))
                } else {
                    0.0
                }
            })
            .collect();
        (floor > 0.0 && weights.iter().any(|&w| w > 0.0)).then_some(weights)
    }
}

/// One sweep of the importance push-pull.
struct Sweep<'a> {
    mesh: &'a PatchMesh,
    nodes: &'a Nodes,
    /// Per node, the direct importance of its surface, 1/W.
    direct: &'a [f64],
    /// Per node, the importance of a watt leaving it, gathered over its links, 1/W.
    leaving: &'a [f64],
}

impl Sweep<'_> {
    /// Sets the importance below `patch`, whose sides' ancestors pass down `above` (the
    /// importance of a watt leaving them), as the radiosity push-pull does: at a leaf
    /// `Γ = w + ρ·L + τ·L̄`, at an inner node the area mean of its children. Returns the
    /// area-weighted change and total of its leaves.
    fn descend(&self, patch: PatchId, above: [f64; 2], gamma: &mut [f64]) -> (f64, f64) {
        let nodes = Side::BOTH.map(|side| node(patch, side));
        let out = [0, 1].map(|s| above[s] + self.leaving[nodes[s]]);
        let p = self.mesh.patch(patch);
        match p.children {
            None => {
                let (mut change, mut total) = (0.0, 0.0);
                for s in 0..2 {
                    let n = nodes[s];
                    let rho = self.nodes.reflectance[n].luminance();
                    let tau = self.nodes.translucency[n].luminance();
                    let g = self.direct[n] + rho * out[s] + tau * out[1 - s];
                    change += (g - gamma[n]).abs() * p.area;
                    total += g * p.area;
                    gamma[n] = g;
                }
                (change, total)
            }
            Some(children) => {
                let (mut change, mut total) = (0.0, 0.0);
                let mut sum = [0.0; 2];
                for child in children {
                    let (c, t) = self.descend(child, out, gamma);
                    change += c;
                    total += t;
                    let area = self.mesh.patch(child).area;
                    for (s, side) in Side::BOTH.into_iter().enumerate() {
                        sum[s] += gamma[node(child, side)] * area;
                    }
                }
                for s in 0..2 {
                    gamma[nodes[s]] = sum[s] / p.area;
                }
                (change, total)
            }
        }
    }
}
