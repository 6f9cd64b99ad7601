//! Radiosity geometry: the patch mesh (quadtrees over every planar face), form factors,
//! the facing test and support-plane split, visibility by stratified rays with shaft
//! culling, and the emitter-only links from point (isotropic or Lambertian), spot and
//! directional lights and the sky.
//!
//! All radiosity geometry is `f64` (`glam::DVec3`) in world space and scene units.

mod box_tree;
mod clip;
mod contact;
mod element;
mod facing;
mod form_factor;
mod light_links;
mod mesh;
mod overlap;
mod shaft;
mod solid_angle;
pub mod solve;
mod surface;
mod visibility;

pub use clip::{Plane, Polygon, SplitPolygon, split};
pub use element::{Element, Side};
pub use facing::{Facing, facing, needs_split};
pub use form_factor::{
    FormFactorMethod, FormFactorOptions, form_factor, point_to_point, point_to_polygon, reciprocal,
};
pub use light_links::{light_irradiance, solid_angle};
pub use mesh::{MeshError, MeshOptions, MeshSize, Patch, PatchId, PatchMesh};
pub use overlap::{Overlap, coplanar_overlaps};
pub use surface::non_diffuse_materials;
pub use visibility::{VisRays, Visibility, VisibilityEstimate, VisibilityOptions};
