//! Radiosity geometry: the patch mesh (quadtrees over every planar face), form factors,
//! the facing test and support-plane split, visibility by stratified rays with shaft
//! culling, and the emitter-only links from point (isotropic or Lambertian), spot and
//! directional lights and the sky.
//!
//! All radiosity geometry is `f64` (`glam::DVec3`) in world space and scene units.

pub mod clip;
pub mod contact;
pub mod element;
pub mod form_factor;
pub mod light_links;
pub mod mesh;
pub mod shaft;
pub mod solid_angle;
pub mod solve;
pub mod surface;
pub mod visibility;

pub use clip::{Facing, Plane, Polygon, SplitPolygon, facing, needs_split, split};
pub use element::{Element, Side};
pub use form_factor::{
    FormFactorMethod, FormFactorOptions, form_factor, point_to_point, point_to_polygon, reciprocal,
};
pub use light_links::light_irradiance;
pub use mesh::{MeshError, MeshOptions, MeshSize, Patch, PatchId, PatchMesh};
pub use visibility::{VisRays, Visibility, VisibilityEstimate, VisibilityOptions};
