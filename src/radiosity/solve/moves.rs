//! What changed between two solves of a scene: where objects moved, or that something else
//! changed (shapes, materials, options), which the solvers that keep their work between
//! solves (`hierarchical/kept.rs`, `kept_couplings.rs`) read to tell what they may keep.

use crate::radiosity::mesh::PatchMesh;
use crate::radiosity::shaft::{Bounds, Shaft};
use crate::radiosity::solve::SystemOptions;
use crate::scene::{Material, Object, Scene};
use glam::DVec3;

/// How far a moved object's bounding box is widened on every side, a share of the scene's
/// diagonal: rays leave their surfaces a little off them, and the shaft test takes boxes.
const MOVED_MARGIN: f64 = 1e-3;

/// What a solve was made for, to tell what changed by the next solve: the objects, materials
/// and options, and where each object's patches lie.
#[derive(Clone, Debug)]
pub(in crate::radiosity::solve) struct Basis {
    objects: Vec<Object>,
    materials: Vec<Material>,
    textures: usize,
    options: SystemOptions,
    /// Per object, the bounding box of its root patches (`None`: it has none).
    bounds: Vec<Option<Bounds>>,
}

impl Basis {
    pub(in crate::radiosity::solve) fn of(
        scene: &Scene,
        options: &SystemOptions,
        mesh: &PatchMesh,
    ) -> Basis {
        let mut bounds: Vec<Option<Bounds>> = vec![None; scene.objects.len()];
        for &root in &mesh.roots {
            let patch = mesh.patch(root);
            let corners = Bounds::from_points(patch.corners().iter().copied());
            let slot = &mut bounds[patch.object as usize];
            *slot = Some(slot.map_or(corners, |b| b.union(corners)));
        }
        Basis {
            objects: scene.objects.clone(),
            materials: scene.materials.clone(),
            textures: scene.textures.len(),
            options: *options,
            bounds,
        }
    }

    /// Where objects moved from `self` to `now`, widened by [`MOVED_MARGIN`] (each moved
    /// object's box before and after); `None` when `now` differs by anything but moves.
    pub(in crate::radiosity::solve) fn moved_to(&self, now: &Basis) -> Option<Vec<Bounds>> {
        if self.options != now.options
            || self.materials != now.materials
            || self.textures != now.textures
            || self.objects.len() != now.objects.len()
        {
            return None;
        }
        let all = now.bounds.iter().flatten().copied().reduce(Bounds::union)?;
        let margin = DVec3::splat(MOVED_MARGIN * (all.max - all.min).length());
        let mut moved = Vec::new();
        for (k, (before, after)) in self.objects.iter().zip(&now.objects).enumerate() {
            if before == after {
                continue;
            }
            let only_moved = Object {
                transform: after.transform,
                ..before.clone()
            } == *after;
            let (Some(from), Some(to)) = (self.bounds[k], now.bounds[k]) else {
                return None;
            };
            if !only_moved {
                return None;
            }
            for b in [from, to] {
                moved.push(Bounds {
                    min: b.min - margin,
                    max: b.max + margin,
                });
            }
        }
        Some(moved)
    }
}

/// Whether a move whose boxes are `moved` ([`Basis::moved_to`]) may have changed what passes
/// between the polygons with corners `r` and `e`, the box around both `around`: a moved box
/// meets that box and the shaft between them (which lies inside it, so the box is tried
/// first).
pub(in crate::radiosity::solve) fn reaches(
    moved: &[Bounds],
    around: &Bounds,
    r: &[DVec3],
    e: &[DVec3],
) -> bool {
    let mut near = moved.iter().filter(|b| b.overlaps(around)).peekable();
    near.peek().is_some() && {
        let shaft = Shaft::between_polygons(r, e);
        near.any(|b| shaft.may_intersect(b))
    }
}
