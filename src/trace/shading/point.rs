//! A surface point prepared for shading: the hit, which way it faces the viewer, and its
//! material with textures applied.

use crate::geometry::{spawn_ray, spawn_ray_to};
use crate::world::{SurfaceHit, SurfaceMaterial, World};
use glam::Vec3;

/// A surface point prepared for lighting: where it is, which way it faces the viewer, and its
/// material.
#[derive(Clone, Copy, Debug)]
pub struct ShadingPoint {
    /// The hit.
    pub hit: SurfaceHit,
    /// Unit direction toward the viewer.
    pub wo: Vec3,
    /// Unit shading normal turned toward the viewer.
    pub n: Vec3,
    /// Unit geometric normal turned toward the viewer.
    pub ng: Vec3,
    /// Material with textures applied.
    pub material: SurfaceMaterial,
}

impl ShadingPoint {
    /// Prepares `hit`, found along a ray with direction `dir`.
    #[inline(always)]
    pub fn new(world: &World, hit: SurfaceHit, dir: Vec3) -> Self {
        let side = if hit.front_face { 1.0 } else { -1.0 };
        ShadingPoint {
            hit,
            wo: -dir,
            n: hit.ns * side,
            ng: hit.ng * side,
            material: SurfaceMaterial::at(&world.scene, &hit),
        }
    }

    /// True when nothing blocks the way from this point to `target`.
    #[inline]
    pub fn sees(&self, world: &World, target: Vec3) -> bool {
        let (ray, t_max) = spawn_ray_to(self.hit.p, self.ng, target);
        !world.occluded(&ray, t_max)
    }

    /// True when nothing blocks the way from this point to infinity along `dir`.
    #[inline]
    pub fn sees_along(&self, world: &World, dir: Vec3) -> bool {
        // Over the endless field of an unrolled periodic world.
        !world
            .plot_world()
            .occluded(&spawn_ray(self.hit.p, self.ng, dir), f32::INFINITY)
    }
}
