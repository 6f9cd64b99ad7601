//! What an integrator evaluates at a surface point: the [`ShadingPoint`] (the hit seen from
//! the viewer, material textured), the BSDF as the path tracer samples it ([`bsdf`]) and the
//! choice of one light for next-event estimation ([`light_sampling`]).

pub mod bsdf;
pub mod light_sampling;
mod point;

pub use point::ShadingPoint;
