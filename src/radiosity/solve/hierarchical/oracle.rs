//! Oracles (seed 000 §6.6): does a link carry its light with a tolerable error, or must the
//! receiver or the emitter be refined?
//!
//! - **Lischinski** (§6.6.2, the default): the irradiance a link brings lies between
//!   `F_min·B_min` and `F_max·B_max` (the smallest and largest point form factor over the
//!   receiver, and the emitter's smallest and largest radiosity; `F_min = 0` when the pair is
//!   partly occluded, so shadow edges refine). The seed bounds the error by
//!   `B_max·(F_max − F_min)`, which misses a receiver that sees mostly a dark part of a
//!   bright emitter (a lamp's back under the ceiling); the width of the interval catches both.
//!   A link is refined when that width, times the receiver's area — the uncertainty of the
//!   power it brings — exceeds `--error` times all power emitted in the scene: scaling the
//!   scene or the lights changes neither the mesh nor the links, and the per-object powers a
//!   report gives are what the error controls. It is refined where the error comes from: the
//!   receiver when `(F_max − F_min)·B_max ≥ F_max·(B_max − B_min)` (the form factor varies
//!   more than the emitter's radiosity), else the emitter; a partly occluded link, or one
//!   whose emitter was never split (so its radiosity is known only as one value), splits the
//!   larger of the two, which localises the shadow or reveals the variation.
//! - **BFA** (§6.6.1): `B·F·A` (emitter radiosity, form factor, receiver area) against two
//!   thresholds, partial visibility always refines the receiver, touching pairs that need a
//!   support-plane split refine the receiver, and otherwise the side with the larger form
//!   factor (the larger patch as seen from the other) is refined. `B` and `F` are taken at
//!   their largest over the emitter and the receiver: with the link's mean form factor a
//!   coarse receiver kept next to an edge it shares with a small emitter mixes levels badly
//!   (measured in the furnace: 25 % too much light).
//!
//! A blocked link (no ray between its patches arrived, `links.rs`) could still bring
//! `A·F_max·B_max` through a gap its `n` rays missed; with `n` rays all blocked the visible
//! share is below `3/n` with 95 % confidence (the rule of three). So both oracles keep it
//! while `3/n` of that power is within the threshold, and otherwise look again with enough
//! rays for the bound to hold (at least twice as many, at most [`MAX_LOOK_RAYS`]).
//!
//! Light links are refined at the receiver when the power they bring varies over it by more
//! than the threshold. Cluster links (`clusters.rs`) are kept only while the largest power
//! they can bring at all is below it: their point-to-point exchange has no tighter bound. Decisions use luminance (Y), not the RGB mean (§7.3). Nothing smaller
//! than the minimum area is refined.

use super::links::{LightLink, Link};
use crate::radiosity::facing::needs_split;
use crate::radiosity::mesh::PatchMesh;

/// Which oracle decides refinement.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Oracle {
    /// Lischinski's error bound on the transported irradiance.
    #[default]
    Lischinski,
    /// The seed's B·F·A criterion.
    Bfa,
}

crate::choice::named_values!(Oracle {
    Oracle::Lischinski = "lischinski",
        "Error bound on the power a link brings, relative to all power emitted in the scene";
    Oracle::Bfa = "bfa", "The seed's B·F·A criterion (depends on the scene's size)";
});

/// The most rays a blocked link is looked at with (a 32 × 32 grid on each patch): a pair
/// still blocked then may hide at most about 0.3 % of what it could bring.
pub const MAX_LOOK_RAYS: u32 = 1024;

/// What to do with a link.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Decision {
    /// It transports its light well enough.
    Keep,
    /// Split the receiver and link its children.
    Receiver,
    /// Split the emitter and link its children.
    Emitter,
    /// A blocked link: compute it again, looking over both patches with this many rays.
    Look(u32),
}

/// The thresholds a decision compares with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// Largest tolerated uncertainty of the power a link brings its receiver, W (Lischinski,
    /// and light links).
    pub error: f64,
    /// Largest `B·F·A` not worth refining, W (BFA).
    pub bfa: f64,
    /// Nodes of this area or less are not split, scene units².
    pub min_area: f64,
}

impl Limits {
    /// These limits with the power error `error` (W) in place of theirs.
    pub fn with_error(self, error: f64) -> Self {
        Limits { error, ..self }
    }
}

/// Which nodes may still be split.
fn splittable(mesh: &PatchMesh, node: u32, limits: &Limits) -> bool {
    mesh.patch(node / 2).area > limits.min_area
}

/// The decision on `link` by `oracle`, its emitter's radiosity luminance lying in
/// `(b_min, b_max)` (W·m⁻²).
pub fn decide(
    oracle: Oracle,
    link: &Link,
    (b_min, b_max): (f64, f64),
    mesh: &PatchMesh,
    limits: &Limits,
) -> Decision {
    if link.blocked_rays > 0 {
        return decide_blocked(link, b_max, mesh, limits);
    }
    let can_receiver = splittable(mesh, link.receiver, limits);
    let can_emitter = splittable(mesh, link.emitter, limits);
    let prefer = |receiver_first: bool| match (receiver_first, can_receiver, can_emitter) {
        (true, true, _) | (false, true, false) => Decision::Receiver,
        (false, _, true) | (true, false, true) => Decision::Emitter,
        _ => Decision::Keep,
    };
    match oracle {
        Oracle::Lischinski => {
            let spread = link.f_max - link.f_min;
            let receiver_area = mesh.patch(link.receiver / 2).area;
            if receiver_area * (link.f_max * b_max - link.f_min * b_min) <= limits.error {
                return Decision::Keep;
            }
            let (r, e) = (mesh.patch(link.receiver / 2), mesh.patch(link.emitter / 2));
            if link.visible < 1.0 || e.children.is_none() {
                // A shadow edge crosses the pair, or the emitter's radiosity is known only as
                // one value (it was never split): splitting the larger side localises the
                // shadow or reveals the variation (the form-factor spread alone would always
                // pick the receiver).
                return prefer(r.area >= e.area);
            }
            prefer(spread * b_max >= link.f_max * (b_max - b_min))
        }
        Oracle::Bfa => {
            let receiver_area = mesh.patch(link.receiver / 2).area;
            let criterion = b_max * link.f_max * receiver_area;
            // Below a tenth of the threshold no refinement could be seen at all.
            if criterion < 0.1 * limits.bfa || link.visible <= 0.0 {
                return Decision::Keep;
            }
            if link.visible < 0.9 {
                return prefer(true);
            }
            let (r, e) = (mesh.patch(link.receiver / 2), mesh.patch(link.emitter / 2));
            if needs_split(e, r) {
                return prefer(true);
            }
            if criterion < limits.bfa {
                return Decision::Keep;
            }
            // F_er ≥ F_re exactly when the receiver is the larger patch (reciprocity).
            prefer(r.area >= e.area)
        }
    }
}

/// The decision on a blocked link (see the module documentation): keep it while the power
/// its rays may have missed, `A·F_max·B_max·3/n`, is within the threshold, else look again
/// with enough rays.
fn decide_blocked(link: &Link, b_max: f64, mesh: &PatchMesh, limits: &Limits) -> Decision {
    let stake = mesh.patch(link.receiver / 2).area * link.f_max * b_max;
    let rays = link.blocked_rays;
    if rays >= MAX_LOOK_RAYS || 3.0 * stake <= limits.error * f64::from(rays) {
        return Decision::Keep;
    }
    let needed = (3.0 * stake / limits.error)
        .ceil()
        .min(f64::from(MAX_LOOK_RAYS)) as u32;
    Decision::Look(needed.max(2 * rays).min(MAX_LOOK_RAYS))
}

/// The decision on a light link: the power it brings is uncertain (its irradiance varies over
/// the receiver, or a shadow edge crosses it) by more than the error threshold.
pub fn decide_light(link: &LightLink, mesh: &PatchMesh, limits: &Limits) -> Decision {
    let (e_min, e_max) = link.range;
    let area = mesh.patch(link.receiver / 2).area;
    if area * (e_max - e_min) > limits.error && splittable(mesh, link.receiver, limits) {
        Decision::Receiver
    } else {
        Decision::Keep
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::radiosity::mesh::MeshOptions;
    use crate::scene::{Material, Scene, Shape};
    use glam::Vec3;

    /// A blocked link between the two sides' fronts of two unit squares.
    fn blocked(rays: u32) -> (Link, PatchMesh) {
        let mut scene = Scene::empty("pair");
        let m = scene.add_material(Material::default());
        for (name, origin, u, v) in [
            ("bottom", Vec3::ZERO, Vec3::X, Vec3::Y),
            ("top", Vec3::Z, Vec3::Y, Vec3::X),
        ] {
            let shape = Shape::Parallelogram {
                origin,
                edge_u: u,
                edge_v: v,
            };
            scene.add_object(name, shape, m);
        }
        let mesh = PatchMesh::from_scene(&scene, &MeshOptions::default()).unwrap();
        let link = Link {
            receiver: 0,
            emitter: 2,
            coupling: 0.0,
            f_min: 0.0,
            f_max: 0.2,
            visible: 0.0,
            unoccluded: false,
            blockers: crate::radiosity::visibility::Blockers::UNKNOWN,
            blocked_rays: rays,
            shares: None,
            receiver_weights: [0.0; 4],
            receiver_shadow_pending: false,
        };
        (link, mesh)
    }

    #[test]
    fn a_blocked_link_is_looked_at_again_while_what_it_may_hide_matters() {
        let limits = Limits {
            error: 1e-3,
            bfa: 1e-3,
            min_area: 0.0,
        };
        for oracle in [Oracle::Lischinski, Oracle::Bfa] {
            // It could bring A·F_max·B_max = 0.2·B; 16 blocked rays may hide 3/16 of it.
            let (link, mesh) = blocked(16);
            let decide_at = |b: f64, link: &Link| decide(oracle, link, (0.0, b), &mesh, &limits);
            assert_eq!(decide_at(1e-3 * 16.0 / 3.0 / 0.2, &link), Decision::Keep);
            // Ten times brighter: 3·stake/ε = 160 rays are needed.
            assert_eq!(
                decide_at(1e-2 * 16.0 / 3.0 / 0.2, &link),
                Decision::Look(160)
            );
            // Just above the bound: at least twice the rays of the last look.
            assert_eq!(
                decide_at(1.01e-3 * 16.0 / 3.0 / 0.2, &link),
                Decision::Look(32)
            );
            // Very bright: as many as allowed; after a look with that many, kept.
            assert_eq!(decide_at(1e6, &link), Decision::Look(MAX_LOOK_RAYS));
            let (link, mesh) = blocked(MAX_LOOK_RAYS);
            assert_eq!(
                decide(oracle, &link, (0.0, 1e6), &mesh, &limits),
                Decision::Keep
            );
        }
    }
}
