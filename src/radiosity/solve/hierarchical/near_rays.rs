//! The near field by rays: light between clusters too close to exchange it as points
//! (closer than the separation the cluster links ask for), carried by rays instead of by
//! links split down to pairs of root patches.
//!
//! In a furnished room (the conference room: 487,196 root patches, chairs and tables of
//! parts a few cm² large) neighbouring clusters are that close at every level of the tree:
//! splitting their links until the ends are separated makes links by the tens of millions
//! (docs/PERFORMANCE.md, *A building*). Here every root patch casts cosine-distributed rays
//! from both sides, once ([`RAYS_PER_SIDE`] a side per reference area, at least that many;
//! direction and origin from one scrambled Sobol point, origins over the whole patch), and
//! keeps the root patch, side and distance each meets first. A cluster link whose ends are
//! too close becomes a *near link* once the standard error of what its rays bring
//! ([`NearRays::error`]) is below the oracle's threshold; it brings each receiving node the
//! radiosity its rays meet on the emitting end (on the leaf under the point met) summed over
//! all the rays that leave the node: the irradiance `H = ∫ B cos θ dω/π` by cosine
//! sampling, visibility and all, unbiased. The links cover every pair of root patches once,
//! so a ray's light is counted by the near link whose ends hold its two patches, if there is
//! one, and by the other links otherwise. A receiving node is the deepest node of the
//! quadtree at least the reference area that holds the ray's origin, so that each gathers
//! over [`RAYS_PER_SIDE`] rays or more.
//!
//! What it costs: the rays once (17 bytes each), then per gather a sum over them. What it
//! gives up: the light of a near link is even over each receiving node, and a node's share
//! is a mean over a few tens of rays — right on average, not patch by patch.

use super::clusters::{ClusterTree, End};
use super::nodes::node;
use crate::accel::AccelKind;
use crate::color::Rgb64;
use crate::progress::{Cancel, ProgressListener};
use crate::radiosity::element::Side;
use crate::radiosity::mesh::{PatchId, PatchMesh};
use crate::radiosity::solve::patch_triangles::{PatchTriangles, side_ray};
use glam::DVec3;
use rayon::prelude::*;
use smallvec::SmallVec;
use std::sync::atomic::{AtomicBool, Ordering};

/// Scenes of at least this many root patches carry their near field by rays (the default
/// of [`super::HierarchicalSettings::near_rays_from`]): below it, splitting near links down
/// to pairs of root patches costs little, and the links are exact where rays are estimates.
pub const NEAR_RAYS_FROM: usize = 10_000;

/// The reference area, as a share of the area of all root patches (one side each): a root
/// patch of that area casts [`RAYS_PER_SIDE`] rays a side.
pub const REFERENCE_SHARE: f64 = 1e-4;

/// Rays cast from each side of a root patch of at most the reference area.
pub const RAYS_PER_SIDE: u32 = 16;

/// Rays from each side of a root patch at most.
const MAX_RAYS_PER_SIDE: u32 = 1 << 20;

/// A ray that met nothing.
const MISSED: u32 = u32::MAX;

/// The rays of the root patches and which of them near links carry.
pub struct NearRays {
    /// The area that gets [`RAYS_PER_SIDE`] rays a side (larger patches proportionally
    /// more), scene units².
    reference_area: f64,
    /// Per place in the cluster tree's member order: the index of its first ray (its front
    /// side's rays, then as many of its back side's), and at the end the number of rays.
    first_ray: Vec<u32>,
    /// Per ray: the place of the root patch met, shifted left by one, with the side met in
    /// the lowest bit ([`MISSED`] for none).
    hits: Vec<u32>,
    /// Per ray: how far it went, scene units.
    distances: Vec<f32>,
    /// Per ray: the node it meets, on the leaf of the quadtree that holds the point met
    /// ([`Self::locate`]; [`MISSED`] for none).
    met: Vec<u32>,
    /// Per ray: the node it leaves from (its side of the deepest node of the quadtree that
    /// holds its origin and is at least the reference area, [`Self::locate`]).
    origins: Vec<u32>,
    /// Per ray: whether a near link carries its light.
    carried: Vec<AtomicBool>,
    /// Per cluster of the tree: the brightest emission of a side of its members, W·m⁻²
    /// (luminance; emission does not change while solving).
    emitting: Vec<f64>,
    /// How many near links have been classified.
    classified: usize,
    /// The number of patches of the mesh when the rays were last located (the quadtrees
    /// only grow).
    located: usize,
}

impl NearRays {
    /// The near field, each root patch casting [`RAYS_PER_SIDE`] rays a side per
    /// `reference_area` scene units² (at least that many), with the brightest emission per
    /// cluster `emitting` ([`ClusterTree::brightest`] of the emission); no rays are cast
    /// until [`Self::cast`].
    pub fn new(reference_area: f64, emitting: Vec<f64>) -> Self {
        NearRays {
            reference_area,
            first_ray: Vec::new(),
            hits: Vec::new(),
            distances: Vec::new(),
            met: Vec::new(),
            origins: Vec::new(),
            carried: Vec::new(),
            emitting,
            classified: 0,
            located: 0,
        }
    }

    /// The brightest emission of a side of `end`'s members (luminance), W·m⁻², for the
    /// emission `emission` per node.
    pub fn emitting(&self, emission: &[Rgb64], end: End) -> f64 {
        ClusterTree::brightest_of(&self.emitting, emission, end)
    }

    /// How many near links [`Self::classify`] has been given: near links stay, so each is
    /// classified once.
    pub fn classified(&self) -> usize {
        self.classified
    }

    /// About the standard error of the power a near link brings (W, luminance), from an
    /// emitter of `emitter_area` scene units² (one side each) that sends `sent` W from both
    /// sides and whose brightest emitting side emits `emitted` W·m⁻², to a receiver of
    /// `receiver_area`: `n = N·F` of the receiver's `N` rays meet the emitter, each bringing
    /// `A·B/N`, so the error is `A·B·√F/√N = B·√(A·F·a/k)` for `k` ([`RAYS_PER_SIDE`]) rays
    /// per reference area `a`; `A·F` is taken at its largest, `2·A_e` (reciprocity, both sides
    /// of the emitter), and `B` as the emitter's mean radiosity plus its brightest emission:
    /// an estimate for the light it reflects, where the brightest side's radiosity instead
    /// kept links split that the rays carry better (the conference room: 230 s and 2.3 % of
    /// its light lost, against 64 s and 0.55 %; docs/PERFORMANCE.md), and a bound for what
    /// lamps send, whose light straight from them the links carry better (RenderPark's
    /// classroom: its largest surface −6.1 % with the mean alone).
    pub fn error(&self, receiver_area: f64, emitter_area: f64, sent: f64, emitted: f64) -> f64 {
        let radiosity = sent / (2.0 * emitter_area).max(f64::MIN_POSITIVE) + emitted;
        let seen = receiver_area.min(2.0 * emitter_area);
        radiosity * (seen * self.reference_area / f64::from(RAYS_PER_SIDE)).sqrt()
    }

    /// Rays per side of a patch of area `area`.
    fn rays_per_side(&self, area: f64) -> u32 {
        let scale = (area / self.reference_area)
            .ceil()
            .clamp(1.0, f64::from(MAX_RAYS_PER_SIDE));
        (RAYS_PER_SIDE * scale as u32).min(MAX_RAYS_PER_SIDE)
    }

    /// Marks the rays that the near links `links` (receiver, emitter), the ones made since
    /// the last call, carry.
    pub fn classify(&mut self, mesh: &PatchMesh, tree: &ClusterTree, links: &[(End, End)]) {
        self.classified += links.len();
        if self.located != mesh.len() {
            self.locate(mesh, tree);
            self.located = mesh.len();
        }
        // Each receiver's rays looked at once, against the emitters of all its new links
        // (disjoint ranges of places: the links cover each pair once).
        let mut by_receiver: Vec<(End, std::ops::Range<u32>)> =
            links.iter().map(|&(r, e)| (r, tree.range(e))).collect();
        by_receiver
            .sort_unstable_by_key(|(r, e)| (tree.range(*r).start, tree.range(*r).end, e.start));
        let groups: Vec<&[(End, std::ops::Range<u32>)]> =
            by_receiver.chunk_by(|a, b| a.0 == b.0).collect();
        let (hits, carried, first_ray) = (&self.hits, &self.carried, &self.first_ray);
        groups.par_iter().for_each(|group| {
            let receivers = tree.range(group[0].0);
            let rays = first_ray[receivers.start as usize] as usize
                ..first_ray[receivers.end as usize] as usize;
            for k in rays {
                let hit = hits[k];
                if hit == MISSED {
                    continue;
                }
                let place = hit >> 1;
                // The last emitter starting at or before the place met.
                let at = group.partition_point(|(_, e)| e.start <= place);
                if at > 0 && group[at - 1].1.contains(&place) {
                    carried[k].store(true, Ordering::Relaxed);
                }
            }
        });
    }

    /// Casts the rays of every root patch (`progress` counts the root patches); returns how
    /// many. Once `cancel` is requested the root patches left cast nothing: their rays count
    /// as met nothing, and bring nothing.
    pub fn cast(
        &mut self,
        mesh: &PatchMesh,
        tree: &ClusterTree,
        progress: &dyn ProgressListener,
        cancel: &Cancel,
    ) -> u64 {
        let members = tree.all_members();
        let mut first_ray = Vec::with_capacity(members.len() + 1);
        let mut total = 0u32;
        for &p in members {
            first_ray.push(total);
            total += 2 * self.rays_per_side(mesh.patch(p).area);
        }
        first_ray.push(total);
        let triangles = PatchTriangles::new(mesh, members);
        let accel = AccelKind::Bvh.build(&triangles);
        let (triangles, accel) = (&triangles, &accel);
        progress.start(members.len() as u64);
        let cast: Vec<(u32, f32)> = members
            .par_iter()
            .enumerate()
            .flat_map_iter(|(place, &p)| {
                let patch = mesh.patch(p);
                let per_side = (first_ray[place + 1] - first_ray[place]) / 2;
                let stopped = cancel.is_requested();
                progress.advance(1);
                (0..2 * per_side).map(move |k| {
                    if stopped {
                        return (MISSED, 0.0);
                    }
                    let ray = side_ray(patch, place, k, per_side);
                    match accel.closest_hit(triangles, &ray, f32::INFINITY) {
                        Some(hit) => {
                            let place = triangles.owners[hit.prim as usize].0;
                            let met = mesh.patch(members[place as usize]);
                            let side = Side::hit_by(met, ray.dir.as_dvec3());
                            ((place << 1) | side.index() as u32, hit.t)
                        }
                        None => (MISSED, 0.0),
                    }
                })
            })
            .collect();
        (self.hits, self.distances) = cast.into_iter().unzip();
        self.carried = (0..self.hits.len())
            .map(|_| AtomicBool::new(false))
            .collect();
        self.first_ray = first_ray;
        u64::from(total)
    }

    /// Finds the leaf each ray meets and the node it leaves from, for the patches as the
    /// quadtrees now split them.
    fn locate(&mut self, mesh: &PatchMesh, tree: &ClusterTree) {
        let members = tree.all_members();
        let (first_ray, hits, distances) = (&self.first_ray, &self.hits, &self.distances);
        let reference_area = self.reference_area;
        (self.met, self.origins) = (0..members.len())
            .into_par_iter()
            .flat_map_iter(|place| {
                let root = members[place];
                let patch = mesh.patch(root);
                let (first, end) = (first_ray[place], first_ray[place + 1]);
                let per_side = (end - first) / 2;
                (first..end).map(move |k| {
                    let side = Side::BOTH[((k - first) / per_side) as usize];
                    let split = patch
                        .children
                        .is_some_and(|_| patch.area >= 2.0 * reference_area);
                    let ray = split.then(|| side_ray(patch, place, k - first, per_side));
                    let origin = match &ray {
                        Some(ray) => {
                            let at = ray.origin.as_dvec3();
                            node(node_at(mesh, root, at, reference_area), side) as u32
                        }
                        None => node(root, side) as u32,
                    };
                    let hit = hits[k as usize];
                    if hit == MISSED {
                        return (MISSED, origin);
                    }
                    let (met, met_side) =
                        (members[(hit >> 1) as usize], Side::BOTH[(hit & 1) as usize]);
                    if mesh.patch(met).children.is_none() {
                        return (node(met, met_side) as u32, origin);
                    }
                    let ray = ray.unwrap_or_else(|| side_ray(patch, place, k - first, per_side));
                    let point = (ray.origin + ray.dir * distances[k as usize]).as_dvec3();
                    (
                        node(node_at(mesh, met, point, 0.0), met_side) as u32,
                        origin,
                    )
                })
            })
            .unzip();
    }

    /// Adds to `gathered` (per node) the irradiance the near links bring each member side,
    /// for the radiosity `radiosity` per node, W·m⁻².
    pub fn gather(&self, tree: &ClusterTree, radiosity: &[Rgb64], gathered: &mut [Rgb64]) {
        // Not located yet (stopped before the first near links were classified): no ray is
        // carried.
        if self.origins.is_empty() {
            return;
        }
        let members = tree.all_members();
        // Per root: the nodes its rays leave from, with the sum of what their carried rays
        // meet and how many rays leave from each.
        // Most roots are not split below the reference area: their two sides' sums stay inline.
        let sums: Vec<SmallVec<[(u32, Rgb64, u32); 2]>> = (0..members.len())
            .into_par_iter()
            .map(|place| {
                let rays = self.first_ray[place] as usize..self.first_ray[place + 1] as usize;
                let mut sums: SmallVec<[(u32, Rgb64, u32); 2]> = SmallVec::new();
                for k in rays {
                    let origin = self.origins[k];
                    let at = match sums.iter().position(|s| s.0 == origin) {
                        Some(at) => at,
                        None => {
                            sums.push((origin, Rgb64::BLACK, 0));
                            sums.len() - 1
                        }
                    };
                    sums[at].2 += 1;
                    if self.carried[k].load(Ordering::Relaxed) {
                        sums[at].1 += radiosity[self.met[k] as usize];
                    }
                }
                sums
            })
            .collect();
        for (origin, sum, rays) in sums.into_iter().flatten() {
            if sum != Rgb64::BLACK {
                gathered[origin as usize] += sum * (1.0 / f64::from(rays));
            }
        }
    }
}

/// The deepest node below `patch` of at least `area` scene units² that holds `point` (a
/// point of its plane): at each level the child the point lies deepest inside.
fn node_at(mesh: &PatchMesh, patch: PatchId, point: DVec3, area: f64) -> PatchId {
    let mut at = patch;
    while let Some(children) = mesh.patch(at).children
        && mesh.patch(children[0]).area >= area
    {
        let inside = |c: PatchId| {
            let child = mesh.patch(c);
            let corners = child.corners();
            (0..corners.len())
                .map(|i| {
                    let (a, b) = (corners[i], corners[(i + 1) % corners.len()]);
                    child.normal.cross(b - a).dot(point - a)
                        / (b - a).length().max(f64::MIN_POSITIVE)
                })
                .fold(f64::INFINITY, f64::min)
        };
        at = children
            .into_iter()
            .max_by(|&a, &b| inside(a).total_cmp(&inside(b)))
            .expect("four children");
    }
    at
}
