//! Geometry: vectors (from `glam`), rays, bounds, transforms, frames and the ray
//! intersections of every primitive.
//!
//! Intersection runs in two stages (seed 002 §4.5.1): a cheap first stage that finds only the
//! ray parameter `t` (plus a few numbers to finish the job), and a second stage that describes
//! the hit (point, normals, surface parameters, tangents) only for the closest hit. Analytic
//! shapes are intersected in their object space, with the world ray carried there by the
//! inverse transform.

pub mod angle;
mod bounds;
pub mod convex2;
pub mod cuboid;
mod dvec3x4;
mod frame;
pub mod frustum;
mod local_hit;
pub mod plane;
mod ray;
pub mod sphere;
mod transform;
mod triangle;
mod triangle8;

pub use bounds::Aabb;
pub use dvec3x4::DVec3x4;
pub use frame::{Frame, to_world_about};
pub use local_hit::LocalHit;
pub use ray::{
    OFFSET_ABSOLUTE, OFFSET_RELATIVE, Ray, offset_origin, offset_origin_lanes, spawn_ray,
    spawn_ray_to, spawn_ray_to_lanes, surface_offset, surface_offset_lanes,
};
pub use transform::Transform;
pub use triangle::Triangle;
pub use triangle8::{Hits8, Ray8, TRIANGLE_LANES, Triangle8};
