//! The matrix solver's couplings and solution kept from one solve of a scene for the next
//! after objects moved (the viewer's moves, seed 000 requirement 5.1).
//!
//! A coupling `F_ij V_ij` is a function of its two elements' geometry and sides and of what
//! its visibility rays can meet — the surfaces inside the shaft between the two patches —
//! and the rays are seeded by what the patches are, not by their indices
//! ([`Visibility::seeded_by_geometry`]). So a coupling is taken from the solve before when
//! both its elements are there again bit for bit ([`PatchMesh::patch_key`] and side) and
//! the shaft between them meets neither where a moved object was nor where it is now: the
//! matrix is the one a solve of the moved scene computes in full, entry for entry
//! (`tests/kept_links.rs`). Anything but a move — a changed shape, material, mesh or
//! option, an object more or less — and nothing is kept; on a periodic plot (whose far
//! field every coupling holds) neither.
//!
//! The iteration then starts from the solution before (each element its radiosity there,
//! the elements new to this mesh their source term): a warm-started Gauss–Seidel, which
//! re-converged the Cornell box after its light moved 5 cm in 6 sweeps against 8 from the
//! emission, and 3.2 times as fast as shooting the residual of the solution before
//! (negative shooting; `benches/move_convergence.rs`). It stops at the same tolerance, so the
//! solution is the moved scene's within that tolerance, not the same bits as one started
//! from the emission.
//!
//! [`Visibility::seeded_by_geometry`]: crate::radiosity::visibility::Visibility::seeded_by_geometry
//! [`PatchMesh::patch_key`]: crate::radiosity::mesh::PatchMesh::patch_key

use super::moves::{Basis, reaches};
use super::system::{Couplings, RadiositySystem};
use crate::color::Rgb64;
use crate::radiosity::shaft::Bounds;
use rustc_hash::{FxHashMap, FxHashSet};
use std::sync::atomic::{AtomicU64, Ordering};

/// What an element is, whatever its index: its patch's geometry key and its side.
type ElementKey = (u64, u8);

/// The couplings and the radiosity of the last matrix solve of a scene, kept for its next
/// solve after objects moved (the matrix part of [`super::KeptLinks`]).
#[derive(Debug, Default)]
pub(super) struct KeptCouplings {
    basis: Option<Basis>,
    /// What each element of the last solve was.
    keys: Vec<ElementKey>,
    /// The last solve's coupling matrix, row by row (its elements' indices).
    rows: Vec<Couplings>,
    /// The last solve's radiosity per element, W·m⁻².
    radiosity: Vec<Rgb64>,
    reused: u64,
    computed: u64,
}

impl KeptCouplings {
    /// Couplings (pairs of elements) the last solve took from the one before.
    pub(super) fn reused(&self) -> u64 {
        self.reused
    }

    /// Couplings (pairs of elements) the last solve computed.
    pub(super) fn computed(&self) -> u64 {
        self.computed
    }

    /// What a matrix solve of `system` may take: the couplings no move since the solve
    /// before can have changed and that solve's radiosity (nothing when the scene changed
    /// otherwise, on a periodic plot, or before the first solve).
    pub(super) fn begin(&mut self, system: &RadiositySystem) -> KeptRows {
        let now = Basis::of(&system.world().scene, system.options(), &system.mesh);
        let moved = self.basis.as_ref().and_then(|before| before.moved_to(&now));
        let basis = self.basis.replace(now);
        let keys = element_keys(system);
        // Taken out either way: a solve that fails before `end` leaves nothing behind to be
        // taken later for a scene it was not made for.
        let (old_keys, rows, radiosity) = (
            std::mem::take(&mut self.keys),
            std::mem::take(&mut self.rows),
            std::mem::take(&mut self.radiosity),
        );
        let before = match moved {
            Some(_) if !system.has_far_field() => matching(&old_keys, &keys),
            _ => None,
        };
        let around = (0..system.len())
            .map(|i| Bounds::from_points(system.patch(i).corners().iter().copied()))
            .collect();
        KeptRows {
            before: before.unwrap_or_else(|| vec![None; keys.len()]),
            basis,
            old_keys,
            keys,
            rows,
            radiosity,
            moved: moved.unwrap_or_default(),
            around,
            reused: AtomicU64::new(0),
            computed: AtomicU64::new(0),
        }
    }

    /// Keeps the matrix `rows` of the solve that read `view` and its `radiosity` for the
    /// next solve; `None` when the solve did not assemble its matrix (it was cancelled: a
    /// move came), and what was kept before stays, for the solve of the scene moved again.
    pub(super) fn end(&mut self, view: KeptRows, solved: Option<(Vec<Couplings>, Vec<Rgb64>)>) {
        self.reused = view.reused.into_inner();
        self.computed = view.computed.into_inner();
        match solved {
            Some((rows, radiosity)) => {
                self.keys = view.keys;
                self.rows = rows;
                self.radiosity = radiosity;
            }
            None => {
                self.basis = view.basis;
                self.keys = view.old_keys;
                self.rows = view.rows;
                self.radiosity = view.radiosity;
            }
        }
    }
}

/// The couplings and radiosity kept as one solve reads them.
pub(super) struct KeptRows {
    /// Per element of this solve: its index in the solve before, where it was there.
    before: Vec<Option<u32>>,
    /// What the solve before was made for.
    basis: Option<Basis>,
    /// What each element of the solve before was.
    old_keys: Vec<ElementKey>,
    /// What each element of this solve is.
    keys: Vec<ElementKey>,
    /// The solve before's matrix, row by row.
    rows: Vec<Couplings>,
    /// The solve before's radiosity per element, W·m⁻².
    radiosity: Vec<Rgb64>,
    /// Where objects moved since (each moved object's box before and after).
    moved: Vec<Bounds>,
    /// Per element of this solve: the box around its patch's corners.
    around: Vec<Bounds>,
    reused: AtomicU64,
    computed: AtomicU64,
}

impl KeptRows {
    /// Row `i` of `system`'s coupling matrix: each coupling kept where it was kept and no
    /// move reached it, else computed. `scratch` holds zeros as long as the solve before
    /// had elements, and is left so.
    pub(super) fn row(&self, system: &RadiositySystem, i: usize, scratch: &mut [f64]) -> Couplings {
        let n = system.len();
        let Some(old_i) = self.before[i] else {
            self.computed.fetch_add(n as u64, Ordering::Relaxed);
            return system.row(i);
        };
        let old = &self.rows[old_i as usize];
        for (&j, &f) in old.leaves.iter().zip(&old.values) {
            scratch[j as usize] = f;
        }
        let mut reused = 0;
        let row = Couplings::of_entries((0..n).map(|j| {
            let value = match self.before[j] {
                Some(old_j) if !self.reached(system, i, j) => {
                    reused += 1;
                    scratch[old_j as usize]
                }
                _ => system.coupling(i, j),
            };
            (j, value)
        }));
        for &j in &old.leaves {
            scratch[j as usize] = 0.0;
        }
        self.reused.fetch_add(reused, Ordering::Relaxed);
        self.computed
            .fetch_add(n as u64 - reused, Ordering::Relaxed);
        row
    }

    /// Zeros for [`KeptRows::row`]: one per element of the solve before.
    pub(super) fn scratch(&self) -> Vec<f64> {
        vec![0.0; self.rows.len()]
    }

    /// Whether a move may have changed the coupling of elements `i` and `j`: the box around
    /// both patches meets a moved object's box and so does the shaft between them.
    fn reached(&self, system: &RadiositySystem, i: usize, j: usize) -> bool {
        let around = self.around[i].union(self.around[j]);
        let (r, e) = (system.patch(i).corners(), system.patch(j).corners());
        reaches(&self.moved, &around, r, e)
    }

    /// The radiosity the iteration starts from: each element's in the solve before, the
    /// source term where it was not there, W·m⁻².
    pub(super) fn start(&self, system: &RadiositySystem) -> Vec<Rgb64> {
        (0..system.len())
            .map(|i| match self.before[i] {
                Some(old) => self.radiosity[old as usize],
                None => system.source(i),
            })
            .collect()
    }
}

/// What each element of `system` is.
fn element_keys(system: &RadiositySystem) -> Vec<ElementKey> {
    system
        .elements
        .iter()
        .map(|e| (system.mesh.patch_key(e.patch), e.side.index() as u8))
        .collect()
}

/// Per element of `now`: its index in `before`, where it is there; `None` when an element
/// is there twice on either side (two patches alike bit for bit), so that no index is
/// taken for another.
fn matching(before: &[ElementKey], now: &[ElementKey]) -> Option<Vec<Option<u32>>> {
    let index: FxHashMap<ElementKey, u32> = before
        .iter()
        .enumerate()
        .map(|(i, &k)| (k, i as u32))
        .collect();
    let mut seen = FxHashSet::default();
    if index.len() != before.len() || now.iter().any(|&k| !seen.insert(k)) {
        return None;
    }
    Some(now.iter().map(|k| index.get(k).copied()).collect())
}
