//! Per-sample random numbers that depend only on the seed, the pixel and the sample index,
//! never on thread scheduling, so a fixed seed gives the same image for any thread count.

use glam::Vec2;
use rand::Rng;
use rand_pcg::Pcg32;

/// Which sequence a [`Sampler`] draws from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SequenceKind {
    /// Independent pseudo-random numbers (PCG32).
    #[default]
    Random,
    /// Owen-scrambled Sobol points (Burley 2020), one point per sample index, falling back to
    /// pseudo-random numbers beyond the tabulated dimensions or sample indices.
    Sobol,
}

/// Largest sample index the Sobol tables cover.
const SOBOL_MAX_SAMPLES: u32 = 1 << 16;

/// The random numbers of one camera sample.
#[derive(Clone, Debug)]
pub struct Sampler {
    kind: SequenceKind,
    sample_index: u32,
    scramble: u32,
    dimension: u32,
    rng: Pcg32,
    /// The four Sobol dimensions of set `sobol_set` (computed together with SIMD).
    sobol_block: [f32; 4],
    sobol_set: u32,
}

/// Mixes integers into a well-distributed 64-bit value (SplitMix64 finaliser).
pub fn hash64(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

impl Sampler {
    /// The sampler of sample `sample_index` of the pixel (or other stream) `stream`, for the
    /// image seed `seed`.
    pub fn new(kind: SequenceKind, seed: u64, stream: u64, sample_index: u32) -> Self {
        let pixel_key = hash64(seed ^ hash64(stream));
        let state = hash64(pixel_key ^ (sample_index as u64).wrapping_mul(0x2545_f491_4f6c_dd1d));
        Sampler {
            kind,
            sample_index,
            scramble: (pixel_key >> 32) as u32,
            dimension: 0,
            rng: Pcg32::new(state, pixel_key | 1),
            sobol_block: [0.0; 4],
            sobol_set: u32::MAX,
        }
    }

    /// A uniform number in `[0, 1)`.
    #[inline]
    pub fn next_1d(&mut self) -> f32 {
        let dim = self.dimension;
        self.dimension += 1;
        if self.kind == SequenceKind::Sobol
            && dim < sobol_burley::NUM_DIMENSIONS
            && self.sample_index < SOBOL_MAX_SAMPLES
        {
            // Four dimensions at a time: the same values as one by one, about 4× cheaper.
            let set = dim / 4;
            if set != self.sobol_set {
                self.sobol_block = sobol_burley::sample_4d(self.sample_index, set, self.scramble);
                self.sobol_set = set;
            }
            return self.sobol_block[(dim % 4) as usize];
        }
        self.random_1d()
    }

    /// A uniform number in `[0, 1)` from the sample's pseudo-random stream, whatever the
    /// sequence kind (for decisions where stratification does not pay, such as deep bounces).
    #[inline]
    pub fn random_1d(&mut self) -> f32 {
        // 24 random bits give every representable value in [0, 1) with equal spacing.
        (self.rng.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }

    /// A uniform point in `[0, 1)²` from the sample's pseudo-random stream.
    #[inline]
    pub fn random_2d(&mut self) -> Vec2 {
        Vec2::new(self.random_1d(), self.random_1d())
    }

    /// A uniform point in `[0, 1)²`.
    #[inline]
    pub fn next_2d(&mut self) -> Vec2 {
        Vec2::new(self.next_1d(), self.next_1d())
    }

    /// A uniform index in `0..n` (`n > 0`).
    pub fn next_index(&mut self, n: usize) -> usize {
        ((self.next_1d() * n as f32) as usize).min(n.saturating_sub(1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_inputs_same_numbers_different_streams_differ() {
        let a: Vec<f32> = {
            let mut s = Sampler::new(SequenceKind::Random, 1, 2, 3);
            (0..8).map(|_| s.next_1d()).collect()
        };
        let b: Vec<f32> = {
            let mut s = Sampler::new(SequenceKind::Random, 1, 2, 3);
            (0..8).map(|_| s.next_1d()).collect()
        };
        let c: Vec<f32> = {
            let mut s = Sampler::new(SequenceKind::Random, 1, 3, 3);
            (0..8).map(|_| s.next_1d()).collect()
        };
        assert_eq!(a, b);
        assert_ne!(a, c);
        assert!(a.iter().all(|v| (0.0..1.0).contains(v)));
    }

    #[test]
    fn sobol_values_come_from_the_sequence_dimension_by_dimension() {
        let mut s = Sampler::new(SequenceKind::Sobol, 4, 7, 11);
        let scramble = s.scramble;
        for dim in 0..12 {
            assert_eq!(s.next_1d(), sobol_burley::sample(11, dim, scramble));
        }
    }

    #[test]
    fn sobol_points_stratify_the_unit_square() {
        // 16 consecutive Sobol points put exactly one point in each 4×4 cell.
        let mut cells = [0u32; 16];
        for i in 0..16 {
            let mut s = Sampler::new(SequenceKind::Sobol, 9, 5, i);
            let p = s.next_2d();
            cells[(p.y * 4.0) as usize * 4 + (p.x * 4.0) as usize] += 1;
        }
        assert!(cells.iter().all(|&c| c == 1), "{cells:?}");
    }

    #[test]
    fn random_numbers_have_the_right_mean() {
        let mut s = Sampler::new(SequenceKind::Random, 0, 0, 0);
        let n = 100_000;
        let mean: f64 = (0..n).map(|_| s.next_1d() as f64).sum::<f64>() / n as f64;
        // Standard error of the mean is sqrt(1/12/n) ≈ 0.0009; allow 5 sigma.
        assert!((mean - 0.5).abs() < 0.0046, "{mean}");
    }
}
