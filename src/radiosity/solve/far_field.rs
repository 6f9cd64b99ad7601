//! The field beyond the margin: the light a periodic plot's endless field reflects from
//! farther away than the copies of the unrolled world reach ([`World::unrolled`]), for every
//! radiosity solver.
//!
//! The links (form factors) join the patches of the plot and its copies within the margin;
//! the sun and the sky reach every patch across the endless field, but what the field beyond
//! the margin reflects had no link. It is not small where the plot is small against its
//! height: the plant example's upper leaves (a 1 m plot, leaves up to 0.5 m high, a margin of
//! 0.75 m) see the ground beyond the margin under every direction more than 56° from the
//! vertical, a third of what the ground sends them, and took 11–17 % too little reflected
//! light.
//!
//! Here every patch of a list (the hierarchical solvers' root patches, the flat solvers'
//! leaves) casts cosine-distributed rays from both sides, once ([`side_ray`], as the near
//! field's; [`RAYS_PER_SIDE`] to [`MAX_RAYS_PER_SIDE`] a side, about [`RAYS`] in all). A ray
//! that meets one of the patches is the links' to carry and is dropped; one that meets none is
//! traced on through the endless field (the periodic world), and where it meets a surface
//! there the patch under that point (of the plot or a copy, the same surface) is kept, with
//! the side met. Each gather brings every side the mean over its rays of the radiosity they
//! meet: the irradiance `H = ∫ B cos θ dω/π` from beyond the margin by cosine sampling,
//! visibility and all — in the flat solvers a coupling `F·V` added to the pair's
//! ([`FarField::share`]); in hierarchical shooting each shot brings the sides whose rays
//! meet the shooter its unshot radiosity times their share ([`FarField::sent_by`]). A root
//! patch's radiosity is its mean: the far field is seen from far, each patch's light spread
//! thin.

use crate::accel::AccelKind;
use crate::color::Rgb64;
use crate::geometry::Ray;
use crate::progress::{Cancel, ProgressListener};
use crate::radiosity::element::Side;
use crate::radiosity::mesh::{PatchId, PatchMesh};
use crate::radiosity::solve::patch_triangles::{PatchTriangles, hit_in_field, side_ray};
use crate::world::World;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// About how many rays all patch sides cast together.
pub const RAYS: u64 = 1 << 21;

/// Rays a side at least.
pub const RAYS_PER_SIDE: u32 = 16;

/// Rays a side at most.
pub const MAX_RAYS_PER_SIDE: u32 = 1024;

/// What the patch sides receive from beyond the margin.
pub struct FarField {
    /// Per side receiving light from beyond the margin, in the order of their ids: the id and
    /// the range of its sources in `sources`.
    receivers: Vec<(u32, std::ops::Range<u32>)>,
    /// Per source: the side met (its id) and its share of the receiver's rays.
    sources: Vec<(u32, f64)>,
    /// The same turned round, for shooting: per side met, in the order of their ids, the id
    /// and the range of what it sends in `sent`.
    emitters: Vec<(u32, std::ops::Range<u32>)>,
    /// Per receiver of an emitter: the receiving side's id and the share of its rays that
    /// meet the emitter.
    sent: Vec<(u32, f64)>,
}

impl FarField {
    /// The far field of the patches `patches` of the unrolled world `world` meshed as `mesh`,
    /// each side known by `id(index in patches, side)` (`None` for a world that
    /// unrolls nothing); `progress` hears the phase "far-field rays" and counts the patches.
    /// Once `cancel` is requested the patches left cast nothing. Returns it with the number
    /// of rays cast.
    pub fn cast(
        world: &World,
        mesh: &PatchMesh,
        patches: &[PatchId],
        id: impl Fn(usize, Side) -> u32 + Sync,
        progress: &dyn ProgressListener,
        cancel: &Cancel,
    ) -> Option<(FarField, u64)> {
        let plot = world.plot_world();
        plot.field()?;
        progress.phase("far-field rays");
        let sides = 2 * patches.len() as u64;
        let per_side = (RAYS / sides.max(1))
            .clamp(u64::from(RAYS_PER_SIDE), u64::from(MAX_RAYS_PER_SIDE))
            as u32;
        let triangles = PatchTriangles::new(mesh, patches);
        let accel = AccelKind::Bvh.build(&triangles);
        let (triangles, accel) = (&triangles, &accel);
        // The patch and side met beyond the margin by a ray that met none within it.
        let beyond = |ray: &Ray| -> Option<u32> {
            if accel.any_hit(triangles, ray, f32::INFINITY) {
                return None;
            }
            let hit = hit_in_field(plot, triangles, accel.as_ref(), ray)?;
            let met = triangles.owners[hit.prim as usize].0 as usize;
            let side = Side::hit_by(mesh.patch(patches[met]), ray.dir.as_dvec3());
            Some(id(met, side))
        };
        progress.start(patches.len() as u64);
        let cast = AtomicU64::new(0);
        let per_patch: Vec<[Vec<(u32, f64)>; 2]> = patches
            .par_iter()
            .enumerate()
            .map(|(place, &p)| {
                progress.advance(1);
                let patch = mesh.patch(p);
                let mut met: Vec<u32> = Vec::new();
                Side::BOTH.map(|side| {
                    met.clear();
                    if !cancel.is_requested() {
                        cast.fetch_add(u64::from(per_side), Ordering::Relaxed);
                        let first = side.index() as u32 * per_side;
                        met.extend(
                            (first..first + per_side)
                                .filter_map(|k| beyond(&side_ray(patch, place, k, per_side))),
                        );
                    }
                    met.sort_unstable();
                    let share = 1.0 / f64::from(per_side);
                    met.chunk_by(|a, b| a == b)
                        .map(|run| (run[0], share * run.len() as f64))
                        .collect()
                })
            })
            .collect();
        progress.finish();
        let mut far = FarField {
            receivers: Vec::new(),
            sources: Vec::new(),
            emitters: Vec::new(),
            sent: Vec::new(),
        };
        for (k, sides) in per_patch.into_iter().enumerate() {
            for (side, sources) in Side::BOTH.into_iter().zip(sides) {
                if sources.is_empty() {
                    continue;
                }
                let start = far.sources.len() as u32;
                far.sources.extend(sources);
                let range = start..far.sources.len() as u32;
                far.receivers.push((id(k, side), range));
            }
        }
        far.receivers
            .sort_unstable_by_key(|(receiver, _)| *receiver);
        let mut turned: Vec<(u32, u32, f64)> = far
            .receivers
            .iter()
            .flat_map(|(receiver, range)| {
                far.sources[range.start as usize..range.end as usize]
                    .iter()
                    .map(|&(met, share)| (met, *receiver, share))
            })
            .collect();
        turned.sort_unstable_by_key(|&(met, receiver, _)| (met, receiver));
        for run in turned.chunk_by(|a, b| a.0 == b.0) {
            let start = far.sent.len() as u32;
            far.sent
                .extend(run.iter().map(|&(_, receiver, share)| (receiver, share)));
            far.emitters.push((run[0].0, start..far.sent.len() as u32));
        }
        Some((far, cast.into_inner()))
    }

    /// The share of the rays of side `receiver` that meet side `emitter` beyond the margin
    /// (their ids): the coupling `F·V` through the endless field.
    pub fn share(&self, receiver: usize, emitter: usize) -> f64 {
        let Ok(k) = self
            .receivers
            .binary_search_by_key(&(receiver as u32), |(side, _)| *side)
        else {
            return 0.0;
        };
        let range = &self.receivers[k].1;
        let sources = &self.sources[range.start as usize..range.end as usize];
        match sources.binary_search_by_key(&(emitter as u32), |&(met, _)| met) {
            Ok(k) => sources[k].1,
            Err(_) => 0.0,
        }
    }

    /// What side `emitter` (its id) sends beyond the margin: each receiving side's id with
    /// the share of its rays that meet the emitter (its irradiance per W·m⁻² of the
    /// emitter's radiosity).
    pub fn sent_by(&self, emitter: usize) -> &[(u32, f64)] {
        match self
            .emitters
            .binary_search_by_key(&(emitter as u32), |(side, _)| *side)
        {
            Ok(k) => {
                let range = &self.emitters[k].1;
                &self.sent[range.start as usize..range.end as usize]
            }
            Err(_) => &[],
        }
    }

    /// Adds to `gathered` (per id) the irradiance the field beyond the margin sends each
    /// side, for the radiosity `radiosity` per id, W·m⁻².
    pub fn gather(&self, radiosity: &[Rgb64], gathered: &mut [Rgb64]) {
        let sums: Vec<Rgb64> = self
            .receivers
            .par_iter()
            .map(|(_, range)| {
                self.sources[range.start as usize..range.end as usize]
                    .iter()
                    .fold(Rgb64::BLACK, |sum, &(met, share)| {
                        sum + radiosity[met as usize] * share
                    })
            })
            .collect();
        for ((receiver, _), sum) in self.receivers.iter().zip(sums) {
            gathered[*receiver as usize] += sum;
        }
    }
}
