//! Links kept from one hierarchical solve of a scene for the next solve of the same scene
//! after objects moved (the viewer's moves, seed 000 requirement 5.1): a link whose ends
//! did not move and between which nothing moved is what it was, and is taken instead of
//! computed again.
//!
//! A link is a function of its ends' geometry and sides, of what was known of the pair's
//! visibility when it was made ([`Prior`]), and of the surfaces its rays could meet — those
//! inside the shaft between its ends ([`Shaft`]); a solve that keeps links seeds its rays
//! by what the ends are, not by their indices in the mesh, which a mesh made again numbers
//! anew ([`Visibility::seeded_by_geometry`]). So a kept link is taken when its ends are the
//! same patches (bit for bit: [`PatchMesh::patch_key`]) and the shaft between them meets
//! neither where a moved object was nor where it is now: a solve that keeps links gives,
//! bit for bit, what the same solve with no links kept gives (`tests/kept_links.rs`), in
//! less time. (Not what a solve that keeps none gives: its rays are seeded by the indices.
//! Both are as accurate.) Anything but a move — a
//! changed shape, material, mesh or visibility setting, an object more or less — and nothing
//! is kept.
//!
//! A link names what may block its ends' children by the primitives' indices, which a
//! world built again orders anew; kept, it names them by what they are
//! ([`Visibility::primitive_key`]).
//!
//! Kept: the patch links as made (before the oracle looks again at a blocked pair, or the
//! emitter's pieces weigh it once it is split). Made anew every time: the cluster links, the light links,
//! everything the oracle decides, the gathers.
//!
//! [`Visibility::primitive_key`]: crate::radiosity::visibility::Visibility::primitive_key

use super::links::{Link, Prior};
use super::nodes::split_node;
use crate::radiosity::mesh::PatchMesh;
use crate::radiosity::shaft::Bounds;
use crate::radiosity::solve::SystemOptions;
use crate::radiosity::solve::moves::{Basis, reaches};
use crate::radiosity::visibility::{Blockers, Visibility};
use crate::scene::Scene;
// The links' and primitives' keys are hashes of geometry already (`PatchMesh::patch_key`,
// `Visibility::primitive_key`): a fast hasher does (the standard SipHash took the Cornell
// box's final solve after a move 8 % longer, its lookups and the merge).
use rustc_hash::FxHashMap;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

/// Blockers named by what the primitives are ([`Visibility::primitive_key`]), in the order
/// of those keys; `None` where they are not known.
type StableBlockers = Option<([u64; 8], u8)>;

/// What a link is made from: its ends as what they are (geometry key and side), what was
/// known of the pair's visibility (the prior's kind, its rays and its blockers), and whether
/// the emitter was split by then (a link made to a split emitter weighs its pieces at once:
/// [`Link::shares`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) struct LinkKey {
    receiver: (u64, u8),
    emitter: (u64, u8),
    prior: (u8, u32, StableBlockers),
    emitter_split: bool,
}

/// A kept link (or the word that the pair has none), its blockers named by what they are,
/// with the box around its ends.
#[derive(Clone, Copy, Debug)]
pub(super) struct KeptLink {
    link: Option<Link>,
    blockers: StableBlockers,
    around: Bounds,
}

/// The primitives of one solve's world both ways: what each index is, and the index of each.
struct Primitives {
    keys: Vec<u64>,
    index: FxHashMap<u64, u32>,
}

impl Primitives {
    fn of(visibility: &Visibility) -> Primitives {
        let keys: Vec<u64> = (0..visibility.primitive_count())
            .map(|prim| visibility.primitive_key(prim))
            .collect();
        let index = keys
            .iter()
            .enumerate()
            .map(|(i, &k)| (k, i as u32))
            .collect();
        Primitives { keys, index }
    }

    /// `blockers` named by what they are.
    fn stable(&self, blockers: Blockers) -> StableBlockers {
        let prims = blockers.get()?;
        let mut keys = [0u64; 8];
        for (slot, &prim) in keys.iter_mut().zip(prims) {
            *slot = self.keys[prim as usize];
        }
        keys[..prims.len()].sort_unstable();
        Some((keys, prims.len() as u8))
    }

    /// `stable` as this world's blockers, in the order of their indices (as shaft culling
    /// finds them); `None` when one of them is not in this world.
    fn current(&self, stable: StableBlockers) -> Option<Blockers> {
        let Some((keys, len)) = stable else {
            return Some(Blockers::UNKNOWN);
        };
        let mut prims = keys[..usize::from(len)]
            .iter()
            .map(|k| self.index.get(k).copied())
            .collect::<Option<Vec<u32>>>()?;
        prims.sort_unstable();
        Some(Blockers::of(&prims))
    }

    /// `prior` as a key's: its kind, rays and blockers named by what they are.
    fn prior(&self, prior: Prior) -> (u8, u32, StableBlockers) {
        match prior {
            Prior::Unknown => (0, 0, None),
            Prior::Unoccluded => (1, 0, None),
            Prior::Blocked(rays, blockers) => (2, rays, self.stable(blockers)),
            Prior::Within(blockers) => (3, 0, self.stable(blockers)),
        }
    }
}

/// The patch links of the last hierarchical solve of a scene, kept for its next solve
/// after objects moved (the hierarchical part of [`KeptLinks`]). Empty until a solve has
/// used it.
///
/// [`KeptLinks`]: crate::radiosity::solve::KeptLinks
#[derive(Debug, Default)]
pub(in crate::radiosity::solve) struct PatchLinks {
    basis: Option<Basis>,
    links: FxHashMap<LinkKey, KeptLink>,
    /// What the last solve made (and took, where the merge would drop it), not yet merged
    /// into `links` ([`PatchLinks::settle`]).
    unsettled: Option<Unsettled>,
    reused: u64,
    computed: u64,
}

impl PatchLinks {
    /// Patch links the last solve took from the one before.
    pub(in crate::radiosity::solve) fn reused(&self) -> u64 {
        self.reused
    }

    /// Patch links the last solve computed.
    pub(in crate::radiosity::solve) fn computed(&self) -> u64 {
        self.computed
    }

    /// What a solve of `scene` meshed as `mesh` with `options` may take: the links kept
    /// where nothing moved since they were made (none when the scene changed otherwise).
    pub(super) fn begin(
        &mut self,
        scene: &Scene,
        options: &SystemOptions,
        mesh: &PatchMesh,
        visibility: &Visibility,
    ) -> KeptView {
        self.settle();
        let now = Basis::of(scene, options, mesh);
        let moved = self.basis.as_ref().and_then(|before| before.moved_to(&now));
        // Taken out either way: a solve that fails before `end` leaves none behind to be
        // taken later for a scene they were not made for.
        let links = std::mem::take(&mut self.links);
        let links = if moved.is_some() {
            links
        } else {
            FxHashMap::default()
        };
        self.basis = Some(now);
        KeptView {
            links,
            primitives: Primitives::of(visibility),
            moved: moved.unwrap_or_default(),
            made: Mutex::new(Vec::new()),
            reused: AtomicU64::new(0),
            computed: AtomicU64::new(0),
        }
    }

    /// Takes back what the solve that read `view` made (and took, where the merge would drop
    /// it), and the links it was given,
    /// to be merged by [`PatchLinks::settle`] (by the next solve's start at the latest): the
    /// merge costs a final solve of the Cornell box about 10 ms, which a
    /// caller in a hurry spends after showing the solution.
    pub(super) fn end(&mut self, view: KeptView) {
        let made = view.made.into_inner().unwrap_or_else(|e| e.into_inner());
        self.reused = view.reused.into_inner();
        self.computed = view.computed.into_inner();
        self.links = view.links;
        self.unsettled = Some(Unsettled {
            made,
            moved: view.moved,
        });
    }

    /// Merges what the last solve made (and took, where this would drop it) into the links
    /// kept, with the links it was
    /// given that no move since they were made can have reached (the box around their ends
    /// meets no moved object's): a coarse preview takes few of the links, and the solve
    /// after it finds the others still kept. Nothing to do when merged already.
    pub(in crate::radiosity::solve) fn settle(&mut self) {
        let Some(Unsettled { made, moved }) = self.unsettled.take() else {
            return;
        };
        self.links
            .retain(|_, kept| !moved.iter().any(|b| b.overlaps(&kept.around)));
        self.links.extend(made);
    }
}

/// What a solve made, and took where the merge would drop it ([`KeptView::keep`]), in the
/// order it asked for them, and where objects had moved before it.
#[derive(Debug)]
struct Unsettled {
    made: Vec<(LinkKey, KeptLink)>,
    moved: Vec<Bounds>,
}

/// The kept links as one solve reads them, and what it makes.
pub(super) struct KeptView {
    links: FxHashMap<LinkKey, KeptLink>,
    primitives: Primitives,
    /// Where objects moved since the links were made.
    moved: Vec<Bounds>,
    /// The links the solve made, and those it took that the merge would drop, in the order
    /// it asked for them.
    made: Mutex<Vec<(LinkKey, KeptLink)>>,
    reused: AtomicU64,
    computed: AtomicU64,
}

impl KeptView {
    /// The link from node `emitter` to node `receiver` of `mesh` under `prior`: the kept
    /// one where there is one and nothing moved between its ends, else `make()`'s; with
    /// what to keep of it where the links kept do not hold it already (a link made, or one
    /// taken whose box meets a moved object's, which the merge drops: [`PatchLinks::settle`]).
    pub(super) fn link(
        &self,
        mesh: &PatchMesh,
        (receiver, emitter, prior): (usize, usize, Prior),
        make: impl FnOnce() -> Option<Link>,
    ) -> (Option<Link>, Option<(LinkKey, KeptLink)>) {
        let end = |n: usize| {
            let (patch, side) = split_node(n);
            (mesh.patch_key(patch), side.index() as u8)
        };
        let (r, e) = (split_node(receiver).0, split_node(emitter).0);
        let key = LinkKey {
            receiver: end(receiver),
            emitter: end(emitter),
            prior: self.primitives.prior(prior),
            emitter_split: mesh.patch(e).children.is_some(),
        };
        let (r, e) = (mesh.patch(r).corners(), mesh.patch(e).corners());
        let around = Bounds::from_points(r.iter().chain(e).copied());
        // Whether the merge would drop it (a moved box meets the box around its ends).
        let reached = self.moved.iter().any(|b| b.overlaps(&around));
        let kept = self
            .links
            .get(&key)
            .filter(|_| !reached || !reaches(&self.moved, &around, r, e))
            .and_then(|kept| match kept.link {
                None => Some(None),
                Some(link) => self.primitives.current(kept.blockers).map(|blockers| {
                    Some(Link {
                        receiver: receiver as u32,
                        emitter: emitter as u32,
                        blockers,
                        ..link
                    })
                }),
            });
        let (link, taken) = match kept {
            Some(link) => {
                self.reused.fetch_add(1, Ordering::Relaxed);
                (link, true)
            }
            None => {
                self.computed.fetch_add(1, Ordering::Relaxed);
                (make(), false)
            }
        };
        let keep = (!taken || reached).then(|| {
            let blockers = link.and_then(|l| self.primitives.stable(l.blockers));
            let kept = KeptLink {
                link,
                blockers,
                around,
            };
            (key, kept)
        });
        (link, keep)
    }

    /// Keeps `made` (links made, or taken and about to be dropped by the merge, in order)
    /// for the next solve.
    pub(super) fn keep(&self, made: Vec<(LinkKey, KeptLink)>) {
        self.made
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .extend(made);
    }
}
