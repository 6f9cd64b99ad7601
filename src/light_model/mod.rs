//! The light model (seed 002 §1.2, like the "enviro" light model of plant modelling): photons
//! traced from all lights and the sky in proportion to their power, followed through
//! reflections and transmissions with Russian roulette, accumulating per object (or per face)
//! the incident, absorbed, emitted and reflected power.
//!
//! Estimator. Source s (power Φₛ, see [`sources`]) sends exactly Nₛ of the N
//! photons, Nₛ ≈ N·Φₛ/ΣΦ: photon i takes the source whose cumulative power interval holds
//! the radical inverse (base 2) of i, so every prefix of the photon sequence, and so every
//! partial run, is stratified over the sources. Each photon emits power Φₛ/Nₛ (exactly so
//! for untextured sources, so the emitted totals are exact; a CIE sky's photons each carry
//! Φₛ/Nₛ times a weight near 1 that corrects its tabulated directions) and starts with it (aimed
//! directional and sky photons with a part of it, the rest escaping at once, see
//! [`sources`]), and scatters as `scatter.rs` describes. The error falls as 1/√N.
//!
//! Exact bookkeeping. Powers are tallied in 128-bit fixed point (2⁶² units for the total
//! emitted power), and at every hit `absorbed = incident − carried on` in those units, so
//! Σ absorbed + escaped = Σ emitted holds exactly per photon, and integer sums do not depend
//! on the order of addition: a fixed seed gives identical reports for any thread count.
//! Each photon draws its random numbers from its own stream (seed, photon index).
//!
//! Figures carry their standard error: per photon, the power it brought to each reported
//! surface (over all its hits) and the irradiance it gave each sensor are squared and summed
//! in fixed point too, and the standard error of a total `S = Σ xᵢ` over the `n` photons
//! traced is `√(Σ xᵢ² − S²/n)` (treating the photons as independent draws; the stratification
//! over sources only lowers the true error, so the figure is on the safe side).
//!
//! Sensors read the light by next-event estimation at every vertex of every photon (see
//! `sensors.rs`); their direct part is what arrives straight from emitters, their indirect
//! part what surfaces reflect. The same split is kept per surface: `direct` is the incident
//! power of the photons' first hits.
//!
//! Photons stop after `max_bounces` scattering events (the last hit absorbs them; counted as
//! `truncated_paths`), which only matters for scenes of near-perfect mirrors.

mod scatter;
mod sensors;
pub mod sources;
mod tally;
mod trace;

pub use trace::{
    LightTraceError, LightTraceOutput, LightTracePartial, LightTraceSettings, merge_light_batches,
    trace_light, trace_light_batch, trace_light_groups,
};
