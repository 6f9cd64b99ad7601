//! Links (seed 000 §6.2, §9.3.1): a receiver node gathers over a link the radiosity of an
//! emitter node, or the irradiance of a light that only sends.
//!
//! A patch link stores the transport coefficient: the area average over the smaller of the
//! two patches (its Gauss points, [`Patch::gauss_points`]) of the point form factor to the
//! other side times the share of it visible from the point ([`Visibility::from_points`]),
//! carried to the receiver by reciprocity when the emitter is the smaller, together with the
//! smallest and largest point form factor over the receiver's Gauss points, centroid and
//! corners (`F_min = 0` when the pair is partly occluded), which the oracles judge.
//!
//! A pair whose rays from the Gauss points are all blocked is looked at again with rays
//! between points spread over both patches ([`Visibility::look`]): the Gauss points of a
//! large node mostly in shadow may miss the gap through which it sees the other. A pair
//! seen there is linked with the share those rays found, for the oracle to refine; a pair
//! not seen is linked as *blocked*, carrying nothing, with the number of rays that found
//! nothing. The oracle looks again with more rays wherever the light such a pair could
//! bring, times the share those rays could have missed, exceeds the error threshold
//! ([`super::oracle`]): a blocked pair is never dropped on the word of a few rays.
//!
//! Once other links split its ends, a link kept at a coarse level still transports what the
//! finer level shows: it gathers the emitter's children's radiosities weighted by how much of
//! the transport leaves each child's quarter ([`Link::emitter_radiosity`]), and hands the
//! receiver's children the share the form factor at each gives them ([`Link::divide`]). With
//! the means alone, a bright part of an emitter that sees the receiver better than its dark
//! part (the shadow of the very light that makes it bright) loses light link after link.

use super::nodes::{node, split_node};
use crate::color::Rgb64;
use crate::radiosity::element::Side;
use crate::radiosity::facing::{Facing, facing};
use crate::radiosity::form_factor::{FactorList, points_to_side};
use crate::radiosity::light_links::{
    SKY_DIRECTIONS_PER_AXIS, exact_directional_arrival, light_arrival, shadow_at_edges,
};
use crate::radiosity::mesh::{Patch, PatchMesh};
use crate::radiosity::solve::UNEVEN_RUN;
use crate::radiosity::visibility::{Blockers, Visibility};
use crate::scene::LightKind;
use crate::world::point_irradiance;
use crate::world::{ParallelShadows, World};
use glam::DVec3;
use rayon::prelude::*;
use smallvec::SmallVec;
use std::sync::atomic::{AtomicU64, Ordering};

/// Visibility rays per Gauss point of the smaller patch where the pair may be occluded: the
/// first probe's 2 × 2 alone ([`Visibility::from_points`] adds rays only above four). 16 more
/// per point changed no Cornell-box figure beyond seed-to-seed noise: the oracle refines
/// partly occluded links until their share is small.
const RAYS_PER_POINT: u32 = 4;

/// How far the corner samples of a receiver are pulled towards its centroid (a share of the
/// way), so that a corner on an emitter's edge does not sit in the emitter's plane.
const CORNER_INSET: f64 = 1e-3;

/// How many times finer per axis the receiver points of a light link are where a shadow
/// edge crosses its receiver.
const PARTLY_SHADOWED_SAMPLES: u32 = 2;

/// Rays of the first look over both patches at a pair that no Gauss point sees (a 4 × 4
/// grid on each).
const FIRST_LOOK_RAYS: u32 = 16;

/// What is known of a pair's visibility before its link is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Prior {
    /// Nothing: its rays will tell.
    Unknown,
    /// It is part of a pair nothing can block: no rays are needed.
    Unoccluded,
    /// Its rays were all blocked so far: if the Gauss points see nothing again, look over
    /// both patches with this many rays; only these primitives can block it.
    Blocked(u32, Blockers),
    /// It is part of a pair only these primitives can block.
    Within(Blockers),
}

/// A receiver node gathering an emitter node's radiosity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Link {
    /// Receiving node.
    pub receiver: u32,
    /// Emitting node.
    pub emitter: u32,
    /// `F·V`: area-averaged form factor times visible fraction.
    pub coupling: f64,
    /// Smallest point form factor over the receiver's sample points (0 when partly
    /// occluded).
    pub f_min: f64,
    /// Largest point form factor over the receiver's sample points.
    pub f_max: f64,
    /// Visible fraction.
    pub visible: f64,
    /// True when nothing can block the pair: its children's links need no visibility rays.
    pub unoccluded: bool,
    /// What may block the rays of its ends' children, where known.
    pub blockers: Blockers,
    /// The rays asked of the last look over both patches, when every ray between the pair
    /// was blocked (the link is blocked and carries nothing); 0 once any ray arrived.
    pub blocked_rays: u32,
    /// The share of the transport that leaves each quarter of the emitter (the quarters its
    /// children cover, in their order): gathering weighs the children's radiosities by it
    /// once the emitter is split. `None` until then where it would cost form factors of its
    /// own ([`Linker::complete_weights`] computes it when the emitter is split).
    pub shares: Option<[f32; 4]>,
    /// The point form factor times the visible share at the receiver's Gauss points, one
    /// per quarter its children cover (a triangle's middle child: their mean): how the light
    /// the link brings a split receiver divides among its children.
    pub receiver_weights: [f32; 4],
    /// True while `receiver_weights` still lack the visible shares: the pair is partly
    /// occluded and its transport was integrated over the emitter, so rays from the
    /// receiver's own Gauss points are cast once the receiver is split
    /// ([`Linker::complete_weights`]), not before they are needed.
    pub receiver_shadow_pending: bool,
}

impl Link {
    /// What is known of the visibility of its ends' children.
    pub fn prior_for_children(&self) -> Prior {
        if self.unoccluded {
            Prior::Unoccluded
        } else if self.blockers == Blockers::UNKNOWN {
            Prior::Unknown
        } else {
            Prior::Within(self.blockers)
        }
    }

    /// True when no ray between its ends arrived: it carries nothing.
    pub fn is_blocked(&self) -> bool {
        self.blocked_rays > 0
    }

    /// The radiosity the receiver sees, W·m⁻²: the emitter's children's radiosities weighted
    /// by the link's shares once the emitter is split (and its shares known), else the
    /// emitter's own.
    pub fn emitter_radiosity(&self, mesh: &PatchMesh, radiosity: &[Rgb64]) -> Rgb64 {
        let (patch, side) = split_node(self.emitter as usize);
        match (mesh.patch(patch).children, self.shares) {
            (Some(children), Some(shares)) => children
                .iter()
                .zip(shares)
                .map(|(&c, w)| radiosity[node(c, side)] * f64::from(w))
                .fold(Rgb64::BLACK, |sum, b| sum + b),
            _ => radiosity[self.emitter as usize],
        }
    }

    /// Where the mean irradiance `mean` (W·m⁻²) the link brings its receiver goes: to the
    /// receiver itself while it is a leaf; once split, to its children in proportion to the
    /// link's receiver weights (the point form factor in each child's quarter), the power
    /// unchanged — a child in the corner next to the emitter gets its share, not the mean.
    pub fn divide(&self, mesh: &PatchMesh, mean: Rgb64) -> Divided {
        let r = self.receiver as usize;
        let (patch, side) = split_node(r);
        let parent = mesh.patch(patch);
        let Some(children) = parent.children else {
            return Divided::Whole(r, mean);
        };
        let weights = self.receiver_weights.map(f64::from);
        let norm: f64 = children
            .iter()
            .zip(weights)
            .map(|(&c, w)| mesh.patch(c).area / parent.area * w)
            .sum();
        if norm <= 0.0 {
            return Divided::Whole(r, mean);
        }
        Divided::Quarters(std::array::from_fn(|k| {
            (node(children[k], side), mean * (weights[k] / norm))
        }))
    }
}

/// Irradiance a link brings, by node (see [`Link::divide`]).
pub enum Divided {
    /// All of it to one node.
    Whole(usize, Rgb64),
    /// To the four children of the receiver.
    Quarters([(usize, Rgb64); 4]),
}

impl IntoIterator for Divided {
    type Item = (usize, Rgb64);
    type IntoIter = std::iter::Take<std::array::IntoIter<(usize, Rgb64), 4>>;

    fn into_iter(self) -> Self::IntoIter {
        match self {
            Divided::Whole(n, h) => [(n, h); 4].into_iter().take(1),
            Divided::Quarters(q) => q.into_iter().take(4),
        }
    }
}

/// The shares of the transport from the quarters of `emitter` (side `es`) to `receiver`
/// (side `rs`): the weighted point form factor from each of the emitter's Gauss points (see
/// [`quarter_values`] for the quarter each lies in) to the receiver. Visibility is not known
/// from that side and is taken as even.
fn emitter_shares(emitter: &Patch, es: Side, receiver: &Patch, rs: Side) -> [f32; 4] {
    let factors = points_to_side(emitter.gauss_points(), es.normal(emitter), receiver, rs);
    let weights = emitter.gauss_weights();
    quadrant_shares(emitter, |i| weights[i] * factors[i])
}

/// Shares in proportion to `weight(i)` of Gauss point `i` of `patch` (see
/// [`quarter_values`]); even shares when every weight is zero.
fn quadrant_shares(patch: &Patch, weight: impl Fn(usize) -> f64) -> [f32; 4] {
    let w = quarter_values(patch, weight);
    let total: f32 = w.iter().sum();
    if total > 0.0 {
        w.map(|x| x / total)
    } else {
        [0.25; 4]
    }
}

/// `value(i)` at Gauss point `i` of `patch`, which lies in the quarter of child `i`: one per
/// child of a quad; a triangle's three lie in its corner children, and its middle child gets
/// their mean. Negative values count as zero.
fn quarter_values(patch: &Patch, value: impl Fn(usize) -> f64) -> [f32; 4] {
    let v: [f64; 4] = if patch.is_triangle() {
        let corners: [f64; 3] = std::array::from_fn(|i| value(i).max(0.0));
        let middle = corners.iter().sum::<f64>() / 3.0;
        [corners[0], corners[1], corners[2], middle]
    } else {
        std::array::from_fn(|i| value(i).max(0.0))
    };
    v.map(|x| x as f32)
}

/// A receiver node gathering the irradiance of a light that only sends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightLink {
    /// Receiving node.
    pub receiver: u32,
    /// Index of the light in the scene's light list.
    pub light: u32,
    /// Mean irradiance over the receiver, W·m⁻².
    pub irradiance: Rgb64,
    /// Smallest and largest irradiance luminance at the receiver's sample points.
    pub range: (f64, f64),
}

/// What creating links needs.
pub struct Linker<'a> {
    /// The scene's world.
    pub world: &'a World,
    /// The visibility estimator.
    pub visibility: &'a Visibility,
    /// Receiver points per axis of the light links' mean irradiance.
    pub link_samples: u32,
    /// Per light of the scene, its shadows cut out exactly, for directional lights where
    /// the world allows ([`ParallelShadows`]); the other light links are measured by rays.
    pub exact_shadows: Vec<Option<ParallelShadows>>,
    /// Rays cast so far.
    pub rays: AtomicU64,
    /// Form factors evaluated so far (point form factors).
    pub form_factors: AtomicU64,
}

impl Linker<'_> {
    /// The link from `emitter` to `receiver` (node indices of `mesh`), `None` when they do
    /// not face each other or are sides of one patch; a blocked link (see the module
    /// documentation) when no ray between them arrives. `prior` is what is known of the
    /// pair's visibility.
    pub fn link(
        &self,
        mesh: &PatchMesh,
        receiver: usize,
        emitter: usize,
        prior: Prior,
    ) -> Option<Link> {
        let ((rp, rs), (ep, es)) = (split_node(receiver), split_node(emitter));
        if rp == ep {
            return None;
        }
        let (r, e) = (mesh.patch(rp), mesh.patch(ep));
        if facing(r, rs, e, es) == Facing::Away {
            return None;
        }
        let normal = rs.normal(r);
        // The range over the receiver: its Gauss points, centroid and corners (pulled in a
        // little from the edge an emitter may touch).
        let range_points: SmallVec<[DVec3; 9]> = r
            .gauss_points()
            .iter()
            .copied()
            .chain([r.centroid])
            .chain(
                r.corners()
                    .iter()
                    .map(|&c| c + (r.centroid - c) * CORNER_INSET),
            )
            .collect();
        let factors = points_to_side(&range_points, normal, e, es);
        // The transport is integrated over the smaller patch (its Gauss points, each with the
        // share of the other patch it sees) and carried over by reciprocity,
        // A_r·F_re = A_e·F_er: point samples of a small emitter from a large receiver would
        // be far off wherever a sample lies next to it.
        let (from, from_patch, from_side, to, to_patch, to_side, scale) = if r.area <= e.area {
            (r, rp, rs, e, ep, es, 1.0)
        } else {
            (e, ep, es, r, rp, rs, e.area / r.area)
        };
        let from_normal = from_side.normal(from);
        let (points, weights) = (from.gauss_points(), from.gauss_weights());
        // The receiver's Gauss points lead its range points: their factors are known.
        let point_factors: FactorList = if scale == 1.0 {
            SmallVec::from_slice(&factors[..points.len()])
        } else {
            points_to_side(points, from_normal, to, to_side)
        };
        // The unoccluded mean over the receiver, `scale · Σ w F`, is at most the maximum: it
        // holds the range up where the receiver's samples all miss a small, close emitter.
        let mean = scale
            * weights
                .iter()
                .zip(&point_factors)
                .map(|(w, f)| w * f)
                .sum::<f64>();
        let f_max = factors.iter().copied().fold(mean, f64::max);
        if f_max <= 0.0 {
            return None;
        }
        let inherited = match prior {
            Prior::Within(blockers) | Prior::Blocked(_, blockers) => blockers,
            Prior::Unknown | Prior::Unoccluded => Blockers::UNKNOWN,
        };
        let seen = if prior == Prior::Unoccluded {
            None
        } else {
            self.visibility.from_points(
                mesh,
                (from_patch, points, from_normal),
                to_patch,
                (RAYS_PER_POINT, true),
                inherited,
            )
        };
        let blockers = seen.as_ref().map_or(Blockers::UNKNOWN, |s| s.blockers);
        // Partly hidden or not is judged by rays of their own, not by those that measure the
        // visible share: judged by those, the pairs whose rays happened to miss an occluder
        // would be kept whole and the others refined, and shadows would come out too small
        // (docs/VALIDATION.md, *Per surface*).
        let partial = seen.as_ref().is_some_and(|s| s.judged_blocked);
        self.form_factors.fetch_add(
            (range_points.len() + points.len()) as u64,
            Ordering::Relaxed,
        );
        let any_unblocked = seen.as_ref().is_none_or(|s| s.any_unblocked);
        let seen = seen.map(|s| {
            self.rays.fetch_add(s.rays, Ordering::Relaxed);
            s.shares
        });
        let visible_at = |i: usize| seen.as_ref().map_or(1.0, |v| v[i]);
        let mut coupling: f64 = scale
            * weights
                .iter()
                .enumerate()
                .map(|(i, w)| w * point_factors[i] * visible_at(i))
                .sum::<f64>();
        let mut visible: f64 = weights
            .iter()
            .enumerate()
            .map(|(i, w)| w * visible_at(i))
            .sum();
        let mut blocked_rays = 0;
        if !any_unblocked {
            // No ray from a Gauss point arrived: look over both patches, near their edges
            // too, before calling the pair blocked.
            let rays = match prior {
                Prior::Blocked(rays, _) => rays,
                Prior::Unknown | Prior::Unoccluded | Prior::Within(_) => FIRST_LOOK_RAYS,
            };
            let to_normal = to_side.normal(to);
            let look = self.visibility.look(
                mesh,
                (from_patch, from_normal),
                (to_patch, to_normal),
                rays,
                blockers,
            );
            self.rays.fetch_add(look.rays, Ordering::Relaxed);
            if look.visible > 0.0 {
                (coupling, visible) = (mean * look.visible, look.visible);
            } else {
                blocked_rays = rays;
            }
        }
        // Integrated over the emitter, the shares come with the transport; over the
        // receiver, they need form factors of their own, computed once the emitter is split.
        let shares = if scale != 1.0 {
            Some(quadrant_shares(e, |i| {
                weights[i] * point_factors[i] * visible_at(i)
            }))
        } else if e.children.is_some() {
            self.form_factors
                .fetch_add(e.gauss_points().len() as u64, Ordering::Relaxed);
            Some(emitter_shares(e, es, r, rs))
        } else {
            None
        };
        let receiver_visible = |i: usize| if scale == 1.0 { visible_at(i) } else { 1.0 };
        let receiver_weights = quarter_values(r, |i| factors[i] * receiver_visible(i));
        // Integrated over the emitter, a partly occluded pair says nothing of where on the
        // receiver the shadow falls; a penumbra on a coarse receiver would be spread evenly
        // over its children (measured: floor leaves beside the Cornell blocks 2–3× too
        // bright, the block faces that see them 8–13 % too bright).
        let receiver_shadow_pending = scale != 1.0 && partial && blocked_rays == 0;
        let f_min = if partial {
            0.0
        } else {
            factors.iter().copied().fold(f64::INFINITY, f64::min)
        };
        Some(Link {
            receiver: receiver as u32,
            emitter: emitter as u32,
            coupling: coupling.min(1.0),
            f_min,
            f_max,
            visible,
            unoccluded: seen.is_none(),
            blockers,
            blocked_rays,
            shares,
            receiver_weights,
            receiver_shadow_pending,
        })
    }

    /// Completes, in parallel, what the links in `links` need once their ends are split:
    /// the emitter shares of a link whose emitter has been split since it was made, and the
    /// visible shares in the receiver weights of a partly occluded link whose receiver has
    /// (see [`Link::receiver_shadow_pending`]).
    pub fn complete_weights(&self, mesh: &PatchMesh, links: &mut [Link]) {
        self.complete_shares(mesh, links);
        let rays: u64 = links
            .par_iter_mut()
            .with_max_len(UNEVEN_RUN)
            .filter(|l| {
                l.receiver_shadow_pending
                    && mesh
                        .patch(split_node(l.receiver as usize).0)
                        .children
                        .is_some()
            })
            .map(|l| {
                l.receiver_shadow_pending = false;
                let ((rp, rs), (ep, _)) = (
                    split_node(l.receiver as usize),
                    split_node(l.emitter as usize),
                );
                let receiver = mesh.patch(rp);
                let points = receiver.gauss_points();
                let Some(seen) = self.visibility.from_points(
                    mesh,
                    (rp, points, rs.normal(receiver)),
                    ep,
                    (RAYS_PER_POINT, false),
                    l.blockers,
                ) else {
                    return 0;
                };
                // A quad's weights are its Gauss points' factors; a triangle's fourth, the
                // middle child's, is recomputed from the other three.
                let factors = l.receiver_weights;
                l.receiver_weights =
                    quarter_values(receiver, |i| f64::from(factors[i]) * seen.shares[i]);
                seen.rays
            })
            .sum();
        self.rays.fetch_add(rays, Ordering::Relaxed);
    }

    /// Computes the emitter shares of every link in `links` whose emitter has been split
    /// since the link was made, in parallel.
    fn complete_shares(&self, mesh: &PatchMesh, links: &mut [Link]) {
        let evaluated: u64 = links
            .par_iter_mut()
            .with_max_len(UNEVEN_RUN)
            .filter(|l| {
                l.shares.is_none()
                    && mesh
                        .patch(split_node(l.emitter as usize).0)
                        .children
                        .is_some()
            })
            .map(|l| {
                let ((rp, rs), (ep, es)) = (
                    split_node(l.receiver as usize),
                    split_node(l.emitter as usize),
                );
                let emitter = mesh.patch(ep);
                l.shares = Some(emitter_shares(emitter, es, mesh.patch(rp), rs));
                emitter.gauss_points().len() as u64
            })
            .sum();
        self.form_factors.fetch_add(evaluated, Ordering::Relaxed);
    }

    /// The link from light `light` (an index into the scene's lights) to `receiver`, `None`
    /// when the light sends it nothing.
    pub fn light_link(&self, mesh: &PatchMesh, receiver: usize, light: u32) -> Option<LightLink> {
        let (rp, rs) = split_node(receiver);
        let patch = mesh.patch(rp);
        let kind: &LightKind = &self.world.scene.lights[light as usize].kind;
        let exact = self.exact_shadows[light as usize]
            .as_ref()
            .and_then(|shadows| exact_directional_arrival(shadows, kind, patch, rs));
        if let Some(arrival) = exact {
            // No points to look at: the patch is lit all over, or in part, or not at all.
            let (lit, unshadowed) = (
                arrival.irradiance.luminance(),
                arrival.unshadowed.luminance(),
            );
            let range = if arrival.partly_shadowed {
                (0.0, unshadowed)
            } else {
                (lit, lit)
            };
            // A share strictly inside (0, 1) brings light: only a dark patch has no link.
            return (lit > 0.0).then_some(LightLink {
                receiver: receiver as u32,
                light,
                irradiance: arrival.irradiance,
                range,
            });
        }
        let shadows = self.visibility.world();
        let mut arrival = light_arrival(shadows, kind, patch, rs, self.link_samples);
        // Every point lit: a shadow may still lie along an edge, between the rows.
        let edge_shadow = !arrival.partly_shadowed
            && arrival.irradiance.luminance() > 0.0
            && shadow_at_edges(shadows, kind, patch, rs);
        if arrival.partly_shadowed || edge_shadow {
            // The grid of points misses a shadow edge by up to half a row: where one crosses,
            // the lit share is measured again on a grid twice as fine (canopy:300, leaf by
            // leaf against the light model: RMS 1.5 → 1.2 %, the worst 4.9 → 3.2 %; four times
            // as fine changed nothing more).
            arrival = light_arrival(
                shadows,
                kind,
                patch,
                rs,
                PARTLY_SHADOWED_SAMPLES * self.link_samples,
            );
            arrival.partly_shadowed = true;
        }
        let irradiance = arrival.irradiance;
        let normal = rs.normal(patch);
        let mut range = (f64::INFINITY, 0.0f64);
        let points = patch.gauss_points();
        for &p in points.iter().chain([&patch.centroid]) {
            let y = point_irradiance(shadows, kind, p, normal, SKY_DIRECTIONS_PER_AXIS).luminance();
            range = (range.0.min(y), range.1.max(y));
        }
        if arrival.partly_shadowed {
            // A shadow edge crosses the patch, maybe between the range's points (a leaf's
            // shadow on another, the sun through a gap): part of it gets nothing, part all.
            range = (0.0, range.1.max(arrival.unshadowed.luminance()));
        }
        self.rays
            .fetch_add(points.len() as u64 + 1, Ordering::Relaxed);
        (range.1 > 0.0 || irradiance.luminance() > 0.0).then_some(LightLink {
            receiver: receiver as u32,
            light,
            irradiance,
            range,
        })
    }
}
