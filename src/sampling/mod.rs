//! Random numbers and the warps that turn them into points and directions: the per-sample
//! [`Sampler`] (Owen-scrambled Sobol points or PCG streams, keyed so that results do not
//! depend on the thread count), the [`warp`] functions every Monte Carlo algorithm draws
//! through, the weights of multiple importance sampling ([`mis`]), and the running
//! [`Moments`] of samples for their mean and its standard error.

pub mod mis;
mod moments;
mod sampler;
pub mod warp;

pub use moments::Moments;
pub use sampler::{Sampler, SequenceKind, hash64};
