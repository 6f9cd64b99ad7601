//! Visibility between two patches (seed 000 §4.3, §4.4): the fraction of rays between
//! stratified, jittered points on both patches that reach the other patch unblocked.
//!
//! Each patch gets an `m × m` grid of strata with one jittered point per stratum; the points
//! of the two grids are paired by a random permutation, so every stratum of each patch sends
//! exactly one ray. The jitter and the pairing come from a generator seeded with
//! `(seed, lower patch id, higher patch id)`: the result is deterministic and symmetric.
//! Where links are kept between solves of a moving scene, the rays from points
//! ([`Visibility::from_points`], [`Visibility::look`]) are seeded by what the two patches
//! are instead (their corners and object, [`PatchMesh::patch_key`]), so that a pair casts
//! the same rays in every mesh of the scene ([`Visibility::seeded_by_geometry`]).
//!
//! The hierarchical solvers ask instead, per Gauss point of one patch, for the share of the
//! other patch it sees ([`Visibility::from_points`]): rays go to the part of that patch in
//! front of the point, spread by area, or by solid angle where that part is clipped or
//! close, each weighted by the form factor it stands for.
//!
//! Occluders: a shaft (Haines & Wallace) between the two patches — the convex hull of
//! their corners inside the union of their bounding boxes — discards the clusters of
//! primitives that cannot block any ray, and those that only touch it; when few primitives
//! survive, the rays test only those, otherwise the scene's BVH is used. Surfaces lying in
//! either patch's plane cannot block a ray leaving that plane and are skipped; a ray between
//! two faces of the same convex object is still blocked by its other faces.
//!
//! Rays are traced against the surfaces the patches lie on: curved analytic shapes are
//! replaced by the same polygon meshes the patches were cut from ([`World::faceted`]), so a
//! ray leaving a facet does not hit the true sphere it lies inside, and the inside of a
//! sphere sees only the inside.

use super::box_tree::BoxTree;
use super::clip::{Plane, SideCounts, clip_to_front};
use super::mesh::{Patch, PatchId, PatchMesh};
use super::shaft::{Bounds, Shaft};
use super::solid_angle::points_by_solid_angle;
use crate::accel::PrimitiveSet;
use crate::geometry::{Ray, offset_origin};

use crate::world::{GeometryError, World};
use glam::DVec3;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64Mcg;
use std::f64::consts::PI;
use std::fmt;
use std::str::FromStr;
use std::sync::Arc;

/// Rays per axis for each unit of `√A_max / d` in adaptive mode.
const ADAPTIVE_RAYS_PER_RATIO: f64 = 4.0;
/// Smallest adaptive grid per axis where the pair may be occluded (16 rays).
const ADAPTIVE_MIN_PER_AXIS: u32 = 4;
/// Largest adaptive grid per axis (64 rays).
const ADAPTIVE_MAX_PER_AXIS: u32 = 8;
/// Mixed into a pair's generator seed with the grid size of a [`Visibility::look`].
const LOOK_KEY: u64 = 0xD6E8_FEB8_6659_FD93;
/// Mixed into a pair's generator seed for the judging rays of [`Visibility::from_points`].
const JUDGE_KEY: u64 = 0x5A17_3C4E_91B2_D06F;
/// Judging rays per point of [`Visibility::from_points`]. Measured on the Cornell box
/// (hierarchical radiosity, one thread): 1 ray 7 % more rays in all and 9 % fewer links than
/// judging by the measuring rays, 2 rays 11 % more and 8 % fewer, 4 rays 27 % more and 7 %
/// fewer; the faces' errors the same within their spread over seeds.
const JUDGE_RAYS: u32 = 2;
/// Where the squared distances from a point to a patch's corners differ by more than this
/// factor, [`Visibility::from_points`] spreads its rays by solid angle rather than by area.
const SKEW: f64 = 4.0;
/// Rays per axis of the first probe of [`Visibility::from_points`].
const PROBE_PER_AXIS: u32 = 2;
/// Consecutive primitives of one object grouped under one bounding box for the shaft test.
const CLUSTER_SIZE: usize = 16;
/// Above this many surviving primitives the rays go through the scene's BVH.
const DIRECT_TEST_LIMIT: usize = 48;
/// Pairs with fewer rays than this skip the shaft (one or two BVH rays cost less than
/// building and testing the shaft).
const SHAFT_MIN_RAYS: u32 = 4;
/// Looks from a point with fewer rays than this skip the shaft: the few rays through the
/// scene's BVH cost less than the pyramid's test (measured on the Šibenik cathedral's
/// sensors, whose leaves mostly get 2 × 2 rays).
const POINT_SHAFT_MIN_RAYS: u32 = 16;

/// Most primitives a pair hands down to the pairs of its children ([`Blockers`]).
const INHERITED_BLOCKERS: usize = 8;

/// The primitives that may block the rays between two patches, as shaft culling found them
/// for a pair, handed down to the pairs of the patches' children: a child's rays run inside
/// the pair's convex hull, so nothing else can block them, and the children's pairs test
/// their own shafts against these alone instead of searching the scene. Unknown when the
/// pair had more than eight (`INHERITED_BLOCKERS`) or none was searched for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Blockers {
    prims: [u32; INHERITED_BLOCKERS],
    len: u8,
}

impl Blockers {
    /// Nothing known: the pairs below search the scene themselves.
    pub const UNKNOWN: Blockers = Blockers {
        prims: [0; INHERITED_BLOCKERS],
        len: u8::MAX,
    };

    /// The list `prims`, unknown when it is too long to hand down.
    pub(crate) fn of(prims: &[u32]) -> Blockers {
        if prims.len() > INHERITED_BLOCKERS {
            return Blockers::UNKNOWN;
        }
        let mut blockers = Blockers {
            prims: [0; INHERITED_BLOCKERS],
            len: prims.len() as u8,
        };
        blockers.prims[..prims.len()].copy_from_slice(prims);
        blockers
    }

    /// The primitives, when known.
    pub(crate) fn get(&self) -> Option<&[u32]> {
        self.prims.get(..usize::from(self.len))
    }
}

/// What the visibility rays from points of one patch to another found
/// ([`Visibility::from_points`]).
#[derive(Clone, Debug, PartialEq)]
pub struct PointShares {
    /// Per point, the visible share of the other patch as the form factor weighs it, in
    /// `[0, 1]`.
    pub shares: Vec<f64>,
    /// Rays cast.
    pub rays: u64,
    /// Whether any ray arrived unblocked.
    pub any_unblocked: bool,
    /// Whether any of the judging rays (asked for by `judge`: `JUDGE_RAYS` more per point,
    /// from a stream of their own) was blocked; false when none was asked for.
    pub judged_blocked: bool,
    /// What may block the rays of the pairs of the patches' children.
    pub blockers: Blockers,
}

/// One point's rays: their number and the form factor they stand for (each ray's
/// `cos θ·cos θ'/(π d²)` over its sampling density), all of them and those that arrived.
#[derive(Clone, Copy, Debug, Default)]
struct RaySums {
    rays: u32,
    total: f64,
    seen: f64,
}

/// What the rays of one grid between two patches found ([`Visibility::estimate`],
/// [`Visibility::look`]).
#[derive(Clone, Copy, Debug, Default)]
struct GridRays {
    /// Rays cast.
    cast: u64,
    /// Rays that arrived unblocked.
    arrived: u64,
    /// Sum over the rays of the point-to-point kernel `|cos θ·cos θ'|/d²` times both ends'
    /// area elements.
    kernel: f64,
    /// The same sum over the rays that arrived.
    kernel_arrived: f64,
}

impl GridRays {
    /// The share of the rays that arrived (0 when none was cast).
    fn share(&self) -> f64 {
        if self.cast == 0 {
            0.0
        } else {
            self.arrived as f64 / self.cast as f64
        }
    }

    /// The share of the form factor the rays that arrived stand for (the share of the rays
    /// where every ray stands for nothing).
    fn weighted_share(&self) -> f64 {
        if self.kernel > 0.0 {
            self.kernel_arrived / self.kernel
        } else {
            self.share()
        }
    }
}

/// How many visibility rays per patch pair (`--vis-rays N|adaptive`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VisRays {
    /// At least `N` rays: an `m × m` grid with `m = ⌈√N⌉`.
    Fixed(u32),
    /// `m = clamp(⌈4·√A_max / d⌉, 4, 8)` per axis, where `A_max` is the larger patch area
    /// and `d` the centroid distance (unchanged when the scene is scaled uniformly), for
    /// pairs that may be occluded; 8 × 8 where the first rays disagree or none arrives.
    Adaptive,
}

impl Default for VisRays {
    /// Adaptive.
    fn default() -> Self {
        VisRays::Adaptive
    }
}

impl fmt::Display for VisRays {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            VisRays::Fixed(n) => write!(f, "{n}"),
            VisRays::Adaptive => f.write_str("adaptive"),
        }
    }
}

impl FromStr for VisRays {
    type Err = String;

    /// `adaptive` or a positive ray count.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        if s.eq_ignore_ascii_case("adaptive") {
            return Ok(VisRays::Adaptive);
        }
        match s.parse::<u32>() {
            Ok(n) if n > 0 => Ok(VisRays::Fixed(n)),
            _ => Err(format!(
                "visibility rays '{s}': expected a positive count or 'adaptive'"
            )),
        }
    }
}

/// A visible fraction and what it cost.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VisibilityEstimate {
    /// The visible fraction in `[0, 1]`.
    pub visible: f64,
    /// Rays cast for it.
    pub rays: u64,
    /// True when nothing can block the pair (no candidate occluder): `visible` is exactly 1,
    /// and so it is for any parts of the two patches.
    pub unoccluded: bool,
}

impl VisibilityEstimate {
    /// A pair nothing can block: wholly visible, no rays cast.
    pub const UNOCCLUDED: VisibilityEstimate = VisibilityEstimate {
        visible: 1.0,
        rays: 0,
        unoccluded: true,
    };
}

/// Settings of the visibility test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VisibilityOptions {
    /// Ray count per pair.
    pub rays: VisRays,
    /// Cull occluders with the shaft before casting rays (off: every ray uses the BVH).
    pub shaft_culling: bool,
    /// Seed of the jitter and pairing.
    pub seed: u64,
}

impl Default for VisibilityOptions {
    /// Adaptive rays, shaft culling on, seed 0.
    fn default() -> Self {
        VisibilityOptions {
            rays: VisRays::Adaptive,
            shaft_culling: true,
            seed: 0,
        }
    }
}

/// Consecutive primitives of one object under one box.
#[derive(Clone, Debug)]
struct Cluster {
    bounds: Bounds,
    first: u32,
    end: u32,
}

/// Visibility queries against the surfaces of a patch mesh.
pub struct Visibility {
    world: Arc<World>,
    /// `world` with its curved shapes as polygon meshes, when it has any.
    faceted: Option<World>,
    clusters: Vec<Cluster>,
    /// A tree over the clusters' bounds, to find those a shaft may cross.
    cluster_tree: BoxTree,
    /// Bounding box of every primitive of the world rays are traced in.
    bounds: Vec<Bounds>,
    options: VisibilityOptions,
    /// Seed each pair's rays by what its patches are ([`PatchMesh::patch_key`]) rather
    /// than by their indices ([`Visibility::seeded_by_geometry`]).
    seeds_by_geometry: bool,
}

/// Where the occluders of one pair are looked for.
enum Occluders {
    /// Nothing can block: every ray arrives.
    None,
    /// Only these primitives.
    Listed(Vec<u32>),
    /// The whole scene through its BVH.
    Scene,
}

impl Occluders {
    /// The primitives `survivors` of a shaft: none, the listed ones, or (beyond
    /// [`DIRECT_TEST_LIMIT`]) the scene's BVH.
    fn of(survivors: Vec<u32>) -> Occluders {
        if survivors.is_empty() {
            Occluders::None
        } else if survivors.len() > DIRECT_TEST_LIMIT {
            Occluders::Scene
        } else {
            Occluders::Listed(survivors)
        }
    }
}

impl Visibility {
    /// Prepares visibility queries on the surfaces of `world`'s patch mesh, whose curved
    /// shapes have `segments` segments around the axis.
    pub fn new(
        world: &Arc<World>,
        options: VisibilityOptions,
        segments: u32,
    ) -> Result<Visibility, GeometryError> {
        let faceted = world.faceted(segments)?;
        let geometry = &faceted.as_ref().unwrap_or(world).geometry;
        let mut clusters: Vec<Cluster> = Vec::new();
        let mut bounds_of = Vec::with_capacity(geometry.len());
        for prim in 0..geometry.len() as u32 {
            let b = PrimitiveSet::bounds(geometry.as_ref(), prim);
            let bounds = Bounds {
                min: b.min.as_dvec3(),
                max: b.max.as_dvec3(),
            };
            bounds_of.push(bounds);
            let object = geometry.owner(prim).0;
            match clusters.last_mut() {
                Some(c)
                    if geometry.owner(c.first).0 == object
                        && ((c.end - c.first) as usize) < CLUSTER_SIZE =>
                {
                    c.bounds = c.bounds.union(bounds);
                    c.end = prim + 1;
                }
                _ => clusters.push(Cluster {
                    bounds,
                    first: prim,
                    end: prim + 1,
                }),
            }
        }
        let cluster_bounds: Vec<Bounds> = clusters.iter().map(|c| c.bounds).collect();
        Ok(Visibility {
            world: Arc::clone(world),
            faceted,
            cluster_tree: BoxTree::new(&cluster_bounds),
            clusters,
            bounds: bounds_of,
            options,
            seeds_by_geometry: false,
        })
    }

    /// This estimator with the rays of [`Visibility::estimate`], [`Visibility::from_points`]
    /// and [`Visibility::look`] seeded by what the two patches are ([`PatchMesh::patch_key`])
    /// rather than by their indices: a pair casts the same rays in every mesh of the scene,
    /// whatever indices its patches have there (a mesh made again after an object moved
    /// numbers its patches anew), which keeping links between solves rests on
    /// (`radiosity::solve::hierarchical::kept`). Another seeding than the default's: the
    /// solutions are as accurate, not the same bit for bit.
    pub fn seeded_by_geometry(mut self) -> Visibility {
        self.seeds_by_geometry = true;
        self
    }

    /// A 64-bit hash of what primitive `prim` of the world the rays are traced in is — its
    /// object, its bounds and a triangle's corners, bit for bit — the same whatever index
    /// it has in a world built again (whose accelerator orders the primitives anew).
    pub fn primitive_key(&self, prim: u32) -> u64 {
        let geometry = &self.world().geometry;
        let b = &self.bounds[prim as usize];
        let corners = geometry
            .triangle(prim)
            .map(|t| t.vertices().map(|v| v.as_dvec3()))
            .into_iter()
            .flatten();
        let words = std::iter::once(u64::from(geometry.owner(prim).0)).chain(
            [b.min, b.max]
                .into_iter()
                .chain(corners)
                .flat_map(|p| p.to_array().map(f64::to_bits)),
        );
        words.fold(0x1319_8A2E_0370_7344, |h, w| crate::sampling::hash64(h ^ w))
    }

    /// How many primitives the world the rays are traced in has.
    pub fn primitive_count(&self) -> u32 {
        self.bounds.len() as u32
    }

    /// The generator seed of the rays from patch `a` to patch `b` of `mesh` in
    /// [`Visibility::estimate`], [`Visibility::from_points`] and [`Visibility::look`]: from the patches' indices, or
    /// from what they are ([`Visibility::seeded_by_geometry`]).
    fn pair_seed(&self, mesh: &PatchMesh, a: PatchId, b: PatchId) -> u64 {
        if self.seeds_by_geometry {
            let pair =
                crate::sampling::hash64(mesh.patch_key(a) ^ mesh.patch_key(b).rotate_left(17));
            crate::sampling::hash64(self.options.seed ^ pair)
        } else {
            pair_key(self.options.seed, a, b)
        }
    }

    /// The world the rays are traced in: the scene with curved shapes as the polygon meshes
    /// the patches lie on.
    pub fn world(&self) -> &World {
        self.faceted.as_ref().unwrap_or(&self.world)
    }

    /// The options in use.
    pub fn options(&self) -> &VisibilityOptions {
        &self.options
    }

    /// Rays per axis for the pair's first estimate (`m`; `m²` rays are cast).
    pub fn rays_per_axis(&self, a: &Patch, b: &Patch) -> u32 {
        match self.options.rays {
            VisRays::Fixed(n) => (n as f64).sqrt().ceil().max(1.0) as u32,
            VisRays::Adaptive => {
                let d = a.centroid.distance(b.centroid);
                let size = a.area.max(b.area).sqrt();
                if d <= 0.0 {
                    return ADAPTIVE_MAX_PER_AXIS;
                }
                let m = (ADAPTIVE_RAYS_PER_RATIO * size / d).ceil();
                m.clamp(ADAPTIVE_MIN_PER_AXIS as f64, ADAPTIVE_MAX_PER_AXIS as f64) as u32
            }
        }
    }

    /// The visible fraction in `[0, 1]` between patches `a` and `b` of `mesh`: 1 when nothing
    /// blocks, 0 when everything does. Symmetric in `a` and `b` and deterministic for a
    /// fixed seed.
    pub fn between(&self, mesh: &PatchMesh, a: PatchId, b: PatchId) -> f64 {
        self.estimate(mesh, a, b).visible
    }

    /// [`Self::between`] with the number of rays it cast. Pairs with no possible occluder cast
    /// none. In adaptive mode a pair that may be occluded casts at least 4 × 4 rays (2 × 2
    /// missed too many partial occluders: +1.25 % on a wall seen past a box at 0.25 m
    /// patches, 0.20 % with 4 × 4), and when not all of them arrive (a shadow edge crosses
    /// the pair, or it may be wholly occluded) it is estimated again with the largest grid:
    /// rays go where the visibility changes, not merely where patches are close.
    pub fn estimate(&self, mesh: &PatchMesh, a: PatchId, b: PatchId) -> VisibilityEstimate {
        let (lo, hi) = (a.min(b), a.max(b));
        let (p, q) = (mesh.patch(lo), mesh.patch(hi));
        let adaptive = self.options.rays == VisRays::Adaptive;
        let mut m = self.rays_per_axis(p, q);
        let occluders = if m * m < SHAFT_MIN_RAYS && !adaptive {
            Occluders::Scene
        } else {
            self.occluders(p, q)
        };
        if matches!(occluders, Occluders::None) {
            return VisibilityEstimate::UNOCCLUDED;
        }
        let mut rng = Pcg64Mcg::seed_from_u64(self.pair_seed(mesh, lo, hi));
        let mut rays = 0;
        loop {
            let grid = self.grid_rays(p, q, m, None, &occluders, &mut rng);
            rays += grid.cast;
            // Mixed answers (a shadow edge crosses the pair) or none arriving (the pair would
            // not be linked at all) are settled with the largest grid.
            let settle = grid.arrived < grid.cast;
            if adaptive && settle && m < ADAPTIVE_MAX_PER_AXIS {
                m = ADAPTIVE_MAX_PER_AXIS;
                continue;
            }
            return VisibilityEstimate {
                visible: grid.share(),
                rays,
                unoccluded: false,
            };
        }
    }

    /// The visible share of the form factor between the sides of patches `a` and `b` whose
    /// unit normals are `normal_a` and `normal_b`, from at least `rays` rays between
    /// stratified, jittered points spread over both (an `m × m` grid on each, paired at
    /// random; each ray weighted by the point-to-point kernel it stands for, and standing
    /// for nothing unless each end lies in front of the other's side), whatever the
    /// `--vis-rays` option: 0 exactly when no ray arrived. The rays start anywhere on `a`, near its
    /// edges too: a pair whose Gauss points see nothing of each other may still see itself
    /// through a gap ([`Visibility::from_points`] looks from the Gauss points only). Looks
    /// with different ray counts cast different rays; deterministic for a fixed seed.
    /// `blockers` are what may block the pair, where known (as [`Visibility::from_points`]
    /// found them for it).
    pub fn look(
        &self,
        mesh: &PatchMesh,
        (a, normal_a): (PatchId, DVec3),
        (b, normal_b): (PatchId, DVec3),
        rays: u32,
        blockers: Blockers,
    ) -> VisibilityEstimate {
        let (p, q) = (mesh.patch(a), mesh.patch(b));
        let occluders = match blockers.get() {
            Some(prims) => Occluders::of(prims.to_vec()),
            None => self.occluders(p, q),
        };
        if matches!(occluders, Occluders::None) {
            return VisibilityEstimate::UNOCCLUDED;
        }
        let m = (rays as f64).sqrt().ceil().max(1.0) as u32;
        let key = self.pair_seed(mesh, a, b) ^ u64::from(m).wrapping_mul(LOOK_KEY);
        let mut rng = Pcg64Mcg::seed_from_u64(key);
        let sides = Some((normal_a, normal_b));
        let grid = self.grid_rays(p, q, m, sides, &occluders, &mut rng);
        let visible = if grid.arrived > 0 {
            grid.weighted_share()
        } else {
            0.0
        };
        VisibilityEstimate {
            visible,
            rays: grid.cast,
            unoccluded: false,
        }
    }

    /// Casts one ray per stratum of an `m × m` jittered grid on `p` to one of `q`'s, the
    /// strata paired by a random permutation. With `sides` (the unit normals of the sides of
    /// `p` and `q` that see each other), only pairs of points each in front of the other's
    /// side are joined by a ray; without, every pair is, whichever side it leaves from.
    fn grid_rays(
        &self,
        p: &Patch,
        q: &Patch,
        m: u32,
        sides: Option<(DVec3, DVec3)>,
        occluders: &Occluders,
        rng: &mut Pcg64Mcg,
    ) -> GridRays {
        let from = jittered_points(p, m, rng);
        let mut to = jittered_points(q, m, rng);
        for i in (1..to.len()).rev() {
            let j = rng.random_range(0..=i);
            to.swap(i, j);
        }
        let mut rays = GridRays::default();
        for (&(x, ax), &(y, ay)) in from.iter().zip(&to) {
            let d = y - x;
            let d2 = d.length_squared();
            let cosines = match sides {
                Some((np, nq)) => np.dot(d).max(0.0) * (-nq.dot(d)).max(0.0),
                None => (p.normal.dot(d) * q.normal.dot(d)).abs(),
            };
            if sides.is_some() && cosines <= 0.0 {
                continue;
            }
            let kernel = cosines / (d2 * d2) * ax * ay;
            // Points that coincide (patches touching there) stand for nothing.
            let kernel = if kernel.is_finite() { kernel } else { 0.0 };
            rays.cast += 1;
            rays.kernel += kernel;
            if !self.blocked(x, p.normal, y, q.normal, occluders) {
                rays.arrived += 1;
                rays.kernel_arrived += kernel;
            }
        }
        rays
    }

    /// The visible share of patch `b` seen from each of `points` (points of patch `a` whose
    /// receiving side has the unit normal `normal`) as the form factor weighs it: the form
    /// factor the unblocked rays stand for over that of all rays, each ray standing for its
    /// `cos θ·cos θ'/(π d²)` over its sampling density. From each point a first probe of
    /// 2 × 2 rays to jittered strata of the part of `b` in front of it (by area, or by solid
    /// angle where that part is clipped or close), joined by `per_point` more rays from every point
    /// when any of those is blocked and `per_point` exceeds the probe's four. `None` when
    /// nothing can block the pair (every share is 1). The occluders are searched for among
    /// `inherited` when known (those of a pair of the patches' ancestors), else in the whole
    /// scene; what was found comes back for the pairs of the patches' children.
    /// With `judge`, a few more rays from every point, from a stream of their own, say whether
    /// the pair is partly hidden (`judged_blocked`): a decision taken on the
    /// rays that measure the shares would keep the pairs whose rays happened to miss an
    /// occluder and refine the others, and shadows would come out too small.
    /// Deterministic for a fixed seed.
    pub fn from_points(
        &self,
        mesh: &PatchMesh,
        (a, points, normal): (PatchId, &[DVec3], DVec3),
        b: PatchId,
        (per_point, judge): (u32, bool),
        inherited: Blockers,
    ) -> Option<PointShares> {
        let (p, q) = (mesh.patch(a), mesh.patch(b));
        let occluders = match inherited.get() {
            Some(prims) => self.within(p, q, prims),
            None => self.occluders(p, q),
        };
        let blockers = match &occluders {
            Occluders::None => return None,
            Occluders::Listed(prims) => Blockers::of(prims),
            Occluders::Scene => Blockers::UNKNOWN,
        };
        let mut rng = Pcg64Mcg::seed_from_u64(self.pair_seed(mesh, a, b) ^ 0x9e37);
        let mut sums = vec![RaySums::default(); points.len()];
        let mut any_unblocked = false;
        // Casts an m × m jittered grid on `b` from every point; true when any ray is blocked.
        let mut cast = |m: u32, sums: &mut [RaySums]| {
            let mut any_blocked = false;
            for (&x, sum) in points.iter().zip(sums.iter_mut()) {
                for (y, element) in self.targets(q, x, normal, m, &mut rng) {
                    let d = y - x;
                    let d2 = d.length_squared();
                    // cos θ·cos θ'/d², and the form factor a ray stands for.
                    let weight = normal.dot(d).max(0.0) * q.normal.dot(d).abs() / (d2 * d2);
                    let factor = weight * element / PI;
                    // A target on the point itself (patches touching there) stands for
                    // nothing.
                    let factor = if factor.is_finite() { factor } else { 0.0 };
                    sum.total += factor;
                    sum.rays += 1;
                    if self.blocked(x, p.normal, y, q.normal, &occluders) {
                        any_blocked = true;
                    } else {
                        any_unblocked = true;
                        sum.seen += factor;
                    }
                }
            }
            any_blocked
        };
        let probe = PROBE_PER_AXIS * PROBE_PER_AXIS;
        if cast(PROBE_PER_AXIS, &mut sums) && per_point > probe {
            cast((per_point as f64).sqrt().ceil() as u32, &mut sums);
        }
        let mut rays = sums.iter().map(|s| u64::from(s.rays)).sum();
        let judged_blocked = judge && {
            let rng = Pcg64Mcg::seed_from_u64(self.pair_seed(mesh, a, b) ^ JUDGE_KEY);
            let (blocked, judging) = self.judge(p, q, (points, normal), &occluders, rng);
            rays += judging;
            blocked
        };
        let shares = sums
            .iter()
            .map(|sum| {
                if sum.total > 0.0 {
                    sum.seen / sum.total
                } else if sum.rays == 0 {
                    // No part of `b` in front of the point: it has nothing to lose.
                    1.0
                } else {
                    0.0
                }
            })
            .collect();
        Some(PointShares {
            shares,
            rays,
            any_unblocked,
            judged_blocked,
            blockers,
        })
    }

    /// Whether any of [`JUDGE_RAYS`] rays from each of `points` (on `p`, receiving side
    /// `normal`) to a jittered point of `q` drawn from `rng` is blocked, and the rays cast:
    /// rounds of one ray per point, stopping at the first blocked.
    fn judge(
        &self,
        p: &Patch,
        q: &Patch,
        (points, normal): (&[DVec3], DVec3),
        occluders: &Occluders,
        mut rng: Pcg64Mcg,
    ) -> (bool, u64) {
        let mut rays = 0;
        for _ in 0..JUDGE_RAYS {
            for &x in points {
                for (y, _) in self.targets(q, x, normal, 1, &mut rng) {
                    rays += 1;
                    if self.blocked(x, p.normal, y, q.normal, occluders) {
                        return (true, rays);
                    }
                }
            }
        }
        (false, rays)
    }

    /// The visible share of patch `q` seen from the free point `x` (a sensor: unit normal
    /// `normal`, on no patch) as the form factor weighs it, and the rays cast: 1 without a
    /// ray when nothing crosses the pyramid from `x` over `q` (shaft culling), else the share
    /// of `rays` rays to jittered strata of the part of `q` in front of `x` (spread as
    /// [`Self::from_points`] spreads them). The jitter comes from `key`: deterministic.
    pub fn share_from_point(
        &self,
        x: DVec3,
        normal: DVec3,
        q: &Patch,
        key: u64,
        rays: u32,
    ) -> (f64, u64) {
        let occluders = if rays < POINT_SHAFT_MIN_RAYS {
            Occluders::Scene
        } else {
            self.point_occluders(x, q)
        };
        if matches!(occluders, Occluders::None) {
            return (1.0, 0);
        }
        let mut rng = Pcg64Mcg::seed_from_u64(pair_key(self.options.seed, 0, 0) ^ key);
        let mut sum = RaySums::default();
        let m = (rays as f64).sqrt().ceil() as u32;
        for (y, element) in self.targets(q, x, normal, m, &mut rng) {
            let d = y - x;
            let d2 = d.length_squared();
            let factor = normal.dot(d).max(0.0) * q.normal.dot(d).abs() / (d2 * d2) * element;
            let factor = if factor.is_finite() { factor } else { 0.0 };
            sum.total += factor;
            sum.rays += 1;
            if !self.blocked(x, normal, y, q.normal, &occluders) {
                sum.seen += factor;
            }
        }
        let share = if sum.total > 0.0 {
            sum.seen / sum.total
        } else {
            0.0
        };
        (share, u64::from(sum.rays))
    }

    /// The ray targets on patch `q` from point `x` (receiving normal `normal`), each with
    /// the area it stands for (the inverse of its sampling density, scene units²): an
    /// `m × m` jittered grid over the part of `q` in front of `x` — over its area where `q`
    /// lies wholly in front and its corners' squared distances differ at most [`SKEW`]
    /// times; otherwise over the solid angle that part subtends (points behind `x` would
    /// stand for nothing, and the few near ones of a close patch for most of the form
    /// factor). Empty when no part of `q` lies in front of `x`.
    fn targets(
        &self,
        q: &Patch,
        x: DVec3,
        normal: DVec3,
        m: u32,
        rng: &mut Pcg64Mcg,
    ) -> Vec<(DVec3, f64)> {
        let plane = Plane::new(x, normal);
        let sides = SideCounts::of(&plane, q.corners());
        if sides.front == 0 {
            return Vec::new();
        }
        let straddles = sides.back > 0;
        if straddles || distance_varies(q, x) {
            let front = clip_to_front(&plane, q.corners());
            if let Some((targets, omega)) =
                points_by_solid_angle(&front, q.normal, x, m, || (rng.random(), rng.random()))
            {
                // The area per ray: d²·Ω/cos θ' = d³·Ω/|n'·d|.
                return targets
                    .into_iter()
                    .map(|y| {
                        let d = y - x;
                        let d2 = d.length_squared();
                        (y, d2 * d2.sqrt() * omega / q.normal.dot(d).abs())
                    })
                    .collect();
            }
        }
        jittered_points(q, m, rng)
    }

    /// Whether the segment between surface points `x` (normal `nx`) and `y` (normal `ny`) is
    /// blocked by anything in the scene (both ends moved off their surfaces first).
    pub fn segment_blocked(&self, x: DVec3, nx: DVec3, y: DVec3, ny: DVec3) -> bool {
        self.blocked(x, nx, y, ny, &Occluders::Scene)
    }

    /// The primitives that may block rays between `a` and `b` after shaft culling, or `None`
    /// when shaft culling is off. Primitives in either patch's plane are left out.
    pub fn candidates(&self, a: &Patch, b: &Patch) -> Option<Vec<u32>> {
        self.options
            .shaft_culling
            .then(|| self.shaft_survivors(a, b))
    }

    fn shaft_survivors(&self, a: &Patch, b: &Patch) -> Vec<u32> {
        let shaft = Shaft::between_polygons(a.corners(), b.corners());
        self.survivors(&shaft, &[a.plane(), b.plane()])
    }

    /// The primitives that may cross `shaft`, less those lying in one of `planes`.
    fn survivors(&self, shaft: &Shaft, planes: &[Plane]) -> Vec<u32> {
        self.cluster_tree
            .find(|b| shaft.may_intersect(b))
            .into_iter()
            .flat_map(|c| self.clusters[c].first..self.clusters[c].end)
            .filter(|&prim| self.may_cross(shaft, planes, prim))
            .collect()
    }

    /// Whether primitive `prim` may cross `shaft` and lies in none of `planes`.
    fn may_cross(&self, shaft: &Shaft, planes: &[Plane], prim: u32) -> bool {
        if !shaft.may_intersect(&self.bounds[prim as usize]) {
            return false;
        }
        let Some(triangle) = self.world().geometry.triangle(prim) else {
            return true;
        };
        let corners = triangle.vertices().map(|v| v.as_dvec3());
        shaft.may_intersect_points(&corners)
            && !planes.iter().any(|plane| {
                let s = SideCounts::of(plane, &corners);
                s.front == 0 && s.back == 0
            })
    }

    /// What may block rays from the free point `x` to patch `q`: the primitives crossing
    /// the pyramid from `x` over `q` (all of the scene without shaft culling).
    fn point_occluders(&self, x: DVec3, q: &Patch) -> Occluders {
        if !self.options.shaft_culling {
            return Occluders::Scene;
        }
        let shaft = Shaft::between_polygons(&[x], q.corners());
        Occluders::of(self.survivors(&shaft, &[q.plane()]))
    }

    /// What may block rays between `a` and `b` of the primitives `inherited` (those of a
    /// pair of their ancestors, in neither patch's plane): the ones that may cross the
    /// pair's shaft.
    fn within(&self, a: &Patch, b: &Patch, inherited: &[u32]) -> Occluders {
        let shaft = Shaft::between_polygons(a.corners(), b.corners());
        Occluders::of(
            inherited
                .iter()
                .copied()
                .filter(|&prim| self.may_cross(&shaft, &[], prim))
                .collect(),
        )
    }

    fn occluders(&self, a: &Patch, b: &Patch) -> Occluders {
        if !self.options.shaft_culling {
            return Occluders::Scene;
        }
        Occluders::of(self.shaft_survivors(a, b))
    }

    /// Whether the segment between surface points `x` (normal `nx`) and `y` (normal `ny`) is
    /// blocked; both ends are moved off their surfaces first.
    fn blocked(&self, x: DVec3, nx: DVec3, y: DVec3, ny: DVec3, occluders: &Occluders) -> bool {
        let (xf, yf) = (x.as_vec3(), y.as_vec3());
        let start = offset_origin(xf, nx.as_vec3(), yf - xf);
        let end = offset_origin(yf, ny.as_vec3(), xf - yf);
        let d = end - start;
        let length = d.length();
        if length.is_nan() || length <= 0.0 {
            return false;
        }
        let ray = Ray::new(start, d / length);
        match occluders {
            Occluders::None => false,
            Occluders::Listed(prims) => prims.iter().any(|&prim| {
                self.world()
                    .geometry
                    .intersect(prim, &ray, length)
                    .is_some()
            }),
            Occluders::Scene => self.world().occluded(&ray, length),
        }
    }
}

/// Whether the squared distance from `x` to the corners of `patch` varies by more than
/// [`SKEW`] times.
fn distance_varies(patch: &Patch, x: DVec3) -> bool {
    let (near, far) = patch
        .corners()
        .iter()
        .map(|c| c.distance_squared(x))
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), d| {
            (lo.min(d), hi.max(d))
        });
    far > SKEW * near
}

/// One jittered point per stratum of an `m × m` grid over `patch`, with its area element
/// ([`Patch::area_element`]).
fn jittered_points(patch: &Patch, m: u32, rng: &mut Pcg64Mcg) -> Vec<(DVec3, f64)> {
    let step = 1.0 / m as f64;
    let mut points = Vec::with_capacity((m * m) as usize);
    for i in 0..m {
        for j in 0..m {
            let s = (i as f64 + rng.random::<f64>()) * step;
            let t = (j as f64 + rng.random::<f64>()) * step;
            points.push((patch.point_at(s, t), patch.area_element(s, t)));
        }
    }
    points
}

/// A well-mixed generator seed from the user seed and an ordered patch pair (SplitMix64
/// finaliser).
fn pair_key(seed: u64, lo: PatchId, hi: PatchId) -> u64 {
    let mut z = seed ^ ((lo as u64) << 32 | hi as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::AccelKind;
    use crate::radiosity::form_factor::point_to_polygon;
    use crate::radiosity::mesh::MeshOptions;
    use crate::scene::{Material, Scene, Shape};
    use glam::Vec3;

    /// Two unit squares facing each other at z = 0 and z = 1 (scaled by `scale`), and an
    /// optional blocker plate at z = 0.5 covering `x ∈ [x0, x1]`, `y ∈ [-1, 2]`.
    fn pair_scene(blocker: Option<(f32, f32)>, scale: f32) -> Scene {
        let mut scene = Scene::empty("pair");
        let m = scene.add_material(Material::default());
        let s = scale;
        scene.add_object(
            "bottom",
            Shape::Parallelogram {
                origin: Vec3::ZERO,
                edge_u: Vec3::X * s,
                edge_v: Vec3::Y * s,
            },
            m,
        );
        scene.add_object(
            "top",
            Shape::Parallelogram {
                origin: Vec3::Z * s,
                edge_u: Vec3::Y * s,
                edge_v: Vec3::X * s,
            },
            m,
        );
        if let Some((x0, x1)) = blocker {
            scene.add_object(
                "blocker",
                Shape::Parallelogram {
                    origin: Vec3::new(x0, -1.0, 0.5) * s,
                    edge_u: Vec3::X * (x1 - x0) * s,
                    edge_v: Vec3::Y * 3.0 * s,
                },
                m,
            );
        }
        scene
    }

    fn visibility_of(scene: Scene, options: VisibilityOptions) -> f64 {
        let mesh = PatchMesh::from_scene(&scene, &MeshOptions::default()).unwrap();
        let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
        let vis = Visibility::new(&world, options, 16).unwrap();
        let v = vis.between(&mesh, 0, 1);
        assert_eq!(v, vis.between(&mesh, 1, 0), "symmetric");
        v
    }

    fn fixed(n: u32, shaft_culling: bool) -> VisibilityOptions {
        VisibilityOptions {
            rays: VisRays::Fixed(n),
            shaft_culling,
            seed: 7,
        }
    }

    #[test]
    fn unblocked_blocked_and_half_blocked_pairs() {
        for culling in [true, false] {
            assert_eq!(
                visibility_of(pair_scene(None, 1.0), fixed(64, culling)),
                1.0
            );
            assert_eq!(
                visibility_of(pair_scene(Some((-1.0, 2.0)), 1.0), fixed(64, culling)),
                0.0
            );
            // The plate covers x < 0.5 at mid-height: a ray from x₀ to x₁ is blocked when
            // (x₀ + x₁)/2 < 0.5, which is half of the pairs by symmetry.
            let half = visibility_of(pair_scene(Some((-1.0, 0.5)), 1.0), fixed(1024, culling));
            assert!((half - 0.5).abs() < 0.03, "{half}");
        }
    }

    #[test]
    fn a_look_weighs_by_the_form_factor_and_keeps_to_the_sides() {
        let look = |blocker, (na, nb): (DVec3, DVec3), rays| {
            let scene = pair_scene(blocker, 1.0);
            let mesh = PatchMesh::from_scene(&scene, &MeshOptions::default()).unwrap();
            let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
            let vis = Visibility::new(&world, fixed(4, true), 16).unwrap();
            vis.look(&mesh, (0, na), (1, nb), rays, Blockers::UNKNOWN)
        };
        let facing = (DVec3::Z, DVec3::NEG_Z);
        assert_eq!(look(None, facing, 64), VisibilityEstimate::UNOCCLUDED);
        // Half the pairs are blocked, by symmetry also half the form factor.
        let half = look(Some((-1.0, 0.5)), facing, 1024);
        assert_eq!(half.rays, 1024);
        assert!((half.visible - 0.5).abs() < 0.03, "{half:?}");
        let none = look(Some((-1.0, 2.0)), facing, 64);
        assert_eq!((none.visible, none.rays), (0.0, 64));
        // From the back of the lower square nothing of the upper one is in front: no ray
        // stands for anything, and the share is 0 however the plate lies.
        let back = look(Some((-1.0, 0.5)), (DVec3::NEG_Z, DVec3::NEG_Z), 64);
        assert_eq!((back.visible, back.rays), (0.0, 0));
    }

    #[test]
    fn scaling_the_scene_by_1000_changes_nothing() {
        for rays in [VisRays::Fixed(256), VisRays::Adaptive] {
            let options = VisibilityOptions {
                rays,
                ..fixed(0, true)
            };
            let small = visibility_of(pair_scene(Some((-1.0, 0.5)), 1.0), options);
            let large = visibility_of(pair_scene(Some((-1.0, 0.5)), 1000.0), options);
            assert_eq!(small, large, "{rays}");
        }
    }

    #[test]
    fn adaptive_ray_count_depends_on_size_over_distance_only() {
        let build = |scale: f32| {
            let scene = pair_scene(None, scale);
            PatchMesh::from_scene(&scene, &MeshOptions::default()).unwrap()
        };
        let world = Arc::new(World::new(pair_scene(None, 1.0), AccelKind::Bvh).unwrap());
        let vis = Visibility::new(&world, VisibilityOptions::default(), 16).unwrap();
        let (small, large) = (build(1.0), build(1000.0));
        let m_small = vis.rays_per_axis(small.patch(0), small.patch(1));
        let m_large = vis.rays_per_axis(large.patch(0), large.patch(1));
        assert_eq!(m_small, 4, "⌈4·√1 / 1⌉");
        assert_eq!(m_small, m_large);
    }

    /// The mean over seeds of the visible share from a point near a corner of a unit square
    /// (0.2 and 0.1 from its edges), of a parallel unit square `height` above it behind a plate at half height
    /// that covers `x < 0.5` (rays to `x < 0.8` of the upper square are blocked, the near
    /// part), the standard error of that mean, and the exact share from the analytic form
    /// factors.
    fn mean_share_under_a_plate(height: f64, seeds: u64) -> (f64, f64, f64) {
        let h = height as f32;
        let mut scene = Scene::empty("plate");
        let m = scene.add_material(Material::default());
        let square = |origin: Vec3, u: Vec3, v: Vec3| Shape::Parallelogram {
            origin,
            edge_u: u,
            edge_v: v,
        };
        scene.add_object("bottom", square(Vec3::ZERO, Vec3::X, Vec3::Y), m);
        scene.add_object("top", square(Vec3::Z * h, Vec3::Y, Vec3::X), m);
        let plate = square(Vec3::new(-1.0, -1.0, h / 2.0), Vec3::X * 1.5, Vec3::Y * 3.0);
        scene.add_object("plate", plate, m);
        // Patches 0 and 1 are the whole squares (the plate hovering over them would cut
        // them out otherwise).
        let options = MeshOptions {
            contact_splits: false,
            ..MeshOptions::default()
        };
        let mesh = PatchMesh::from_scene(&scene, &options).unwrap();
        let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
        let x = DVec3::new(0.2, 0.1, 0.0);
        let top = mesh.patch(1).corners().to_vec();
        let seen: Vec<DVec3> = top
            .iter()
            .map(|c| DVec3::new(c.x.max(0.8), c.y, c.z))
            .collect();
        let exact = point_to_polygon(x, DVec3::Z, &seen) / point_to_polygon(x, DVec3::Z, &top);
        let shares: Vec<f64> = (0..seeds)
            .map(|seed| {
                let options = VisibilityOptions {
                    seed,
                    ..fixed(4, true)
                };
                let vis = Visibility::new(&world, options, 16).unwrap();
                let found = vis
                    .from_points(&mesh, (0, &[x], DVec3::Z), 1, (4, false), Blockers::UNKNOWN)
                    .unwrap();
                found.shares[0]
            })
            .collect();
        let n = seeds as f64;
        let mean = shares.iter().sum::<f64>() / n;
        let variance = shares.iter().map(|s| (s - mean).powi(2)).sum::<f64>() / (n - 1.0);
        (mean, (variance / n).sqrt(), exact)
    }

    #[test]
    fn the_judging_rays_come_apart_from_the_measuring_ones() {
        // A blocker across the middle between the squares: the judging rays see it, and
        // asking for them leaves the measuring rays, and so the shares, as they were.
        let scene = pair_scene(Some((0.3, 0.7)), 1.0);
        let mesh = PatchMesh::from_scene(&scene, &MeshOptions::default()).unwrap();
        let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
        let vis = Visibility::new(&world, fixed(16, true), 16).unwrap();
        let points = mesh.patch(0).gauss_points().to_vec();
        let look = |judge: bool| {
            vis.from_points(
                &mesh,
                (0, &points, DVec3::Z),
                1,
                (16, judge),
                Blockers::UNKNOWN,
            )
            .unwrap()
        };
        let (judged, plain) = (look(true), look(false));
        assert!(judged.judged_blocked);
        assert!(!plain.judged_blocked);
        assert_eq!(judged.shares, plain.shares);
        assert!(plain.shares.iter().any(|&v| v < 1.0));
        let judging = judged.rays - plain.rays;
        assert!((1..=u64::from(JUDGE_RAYS) * points.len() as u64).contains(&judging));
    }

    #[test]
    fn children_looking_through_their_parents_blockers_see_what_they_would_see_alone() {
        // The blocker covers x ∈ [0.8, 1.2] half-way between the squares; the bottom
        // square's children look at the top one through the blockers the whole pair handed
        // down.
        let scene = pair_scene(Some((0.8, 1.2)), 1.0);
        let options = MeshOptions {
            contact_splits: false,
            ..MeshOptions::default()
        };
        let mut mesh = PatchMesh::from_scene(&scene, &options).unwrap();
        let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
        let vis = Visibility::new(&world, fixed(16, true), 16).unwrap();
        let points_of = |mesh: &PatchMesh, p: PatchId| mesh.patch(p).gauss_points().to_vec();
        let parent = vis
            .from_points(
                &mesh,
                (0, &points_of(&mesh, 0), DVec3::Z),
                1,
                (16, false),
                Blockers::UNKNOWN,
            )
            .unwrap();
        assert_eq!(
            parent.blockers.get().map(<[u32]>::len),
            Some(2),
            "the plate's triangles"
        );
        let mut unoccluded = 0;
        for child in mesh.subdivide(0) {
            let points = points_of(&mesh, child);
            let alone = vis.from_points(
                &mesh,
                (child, &points, DVec3::Z),
                1,
                (16, false),
                Blockers::UNKNOWN,
            );
            let handed = vis.from_points(
                &mesh,
                (child, &points, DVec3::Z),
                1,
                (16, false),
                parent.blockers,
            );
            assert_eq!(
                alone.as_ref().map(|a| &a.shares),
                handed.as_ref().map(|h| &h.shares)
            );
            assert_eq!(
                alone.as_ref().map(|a| a.rays),
                handed.as_ref().map(|h| h.rays)
            );
            unoccluded += usize::from(handed.is_none());
        }
        // Half-way up, the shafts of the children at x < 0.5 reach x = 0.75 only.
        assert_eq!(unoccluded, 2);
    }

    #[test]
    fn four_rays_estimate_the_share_behind_a_near_blocker_with_a_small_bias() {
        // The ratio of seen to cast ray weights is biased for four rays. Far (rays by area;
        // the corners' squared distances differ 2.3-fold) it is 0.0051 ± 0.0009 high here
        // (4 %, over 20,000 seeds; 0.0065 with the rays seeded by what the patches are);
        // near (by solid angle; they differ 17-fold) 0.0027 ± 0.0003 high (0.0018), where by
        // area it was 0.0094 high (twice the share): the rays to the near, blocked part
        // weighed far more than the rest. The oracle refines partly blocked links until
        // what remains is small. Held to a bias bound plus three standard errors of the
        // mean over the seeds.
        for (height, bias) in [(1.0, 0.006), (0.2, 0.003)] {
            let (mean, se, exact) = mean_share_under_a_plate(height, 20_000);
            assert!(
                (mean - exact).abs() < bias + 3.0 * se,
                "height {height}: mean share {mean} ± {se} vs exact {exact}"
            );
        }
    }

    #[test]
    fn shaft_keeps_the_blocker_and_drops_the_patches_own_planes() {
        let scene = pair_scene(Some((2.5, 3.0)), 1.0);
        let mesh = PatchMesh::from_scene(&scene, &MeshOptions::default()).unwrap();
        let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
        let vis = Visibility::new(&world, VisibilityOptions::default(), 16).unwrap();
        // The plate at x ∈ [2.5, 3] is outside the shaft between the squares.
        let survivors = vis.candidates(mesh.patch(0), mesh.patch(1)).unwrap();
        assert!(survivors.is_empty(), "{survivors:?}");
        let scene = pair_scene(Some((0.2, 0.3)), 1.0);
        let world = Arc::new(World::new(scene, AccelKind::Bvh).unwrap());
        let vis = Visibility::new(&world, VisibilityOptions::default(), 16).unwrap();
        let survivors = vis.candidates(mesh.patch(0), mesh.patch(1)).unwrap();
        let owners: Vec<u32> = survivors
            .iter()
            .map(|&p| world.geometry.owner(p).0)
            .collect();
        assert!(
            !owners.is_empty() && owners.iter().all(|&o| o == 2),
            "{owners:?}"
        );
    }

    #[test]
    fn vis_rays_parse() {
        assert_eq!("adaptive".parse(), Ok(VisRays::Adaptive));
        assert_eq!("16".parse(), Ok(VisRays::Fixed(16)));
        assert!("0".parse::<VisRays>().is_err());
    }
}
