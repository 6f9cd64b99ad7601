//! Random numbers and the warps that turn them into points and directions: the per-sample
//! [`Sampler`] (Owen-scrambled Sobol points or PCG streams, keyed so that results do not
//! depend on the thread count), the [`warp`] functions every Monte Carlo algorithm draws
//! through, and the weights of multiple importance sampling ([`mis`]).

pub mod mis;
mod sampler;
pub mod warp;

pub use sampler::{Sampler, SequenceKind, hash64};
