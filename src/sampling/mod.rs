//! Random numbers and the warps that turn them into points and directions: the per-sample
//! [`Sampler`] (Owen-scrambled Sobol points or PCG streams, keyed so that results do not
//! depend on the thread count), the [`warp`] functions every Monte Carlo algorithm draws
//! through, the weights of multiple importance sampling ([`mis`]), and the running
//! [`Moments`] of samples for their mean and its standard error, with the rule of how many
//! more an estimate needs ([`adaptive`]); fixed-point conversions
//! ([`to_fixed`]) for sums that do not depend on the order of addition, and the split of a
//! run's samples into [`Batch`]es with the checks of their merge ([`check_batches`]).

pub mod adaptive;
mod batch;
mod fixed;
pub mod mis;
mod moments;
mod packed;
mod sampler;
pub mod warp;

pub use batch::{Batch, BatchPart, MergeError, NoSuchBatch, check_batches};
pub use fixed::{from_fixed, to_fixed};
pub use moments::Moments;
pub use packed::{pack, unpack};
pub use sampler::{Sampler, SequenceKind, hash64};
