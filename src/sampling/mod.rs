//! Random numbers and the warps that turn them into points and directions: the per-sample
//! [`Sampler`] (Owen-scrambled Sobol points or PCG streams, keyed so that results do not
//! depend on the thread count) and the [`warp`] functions every Monte Carlo algorithm draws
//! through.

mod sampler;
pub mod warp;

pub use sampler::{Sampler, SequenceKind, hash64};
