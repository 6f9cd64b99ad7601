//! Per-sample random numbers that depend only on the seed, the pixel and the sample index,
//! never on thread scheduling, so a fixed seed gives the same image for any thread count.
//!
//! The Sobol sequence is Owen-scrambled in Burley's (2020) manner, built from the parts of
//! the `sobol_burley` crate: per pixel a hashed shuffle of the sample index (so every pixel
//! draws its own randomised sequence) and per dimension a hashed Owen scramble of the point.
//! The generator matrices of the first dimensions are tabulated as XOR tables over the
//! index's four-bit digits, so a point costs four loads instead of a loop over index bits.

use glam::Vec2;
use rand::Rng;
use rand_pcg::Pcg32;
use sobol_burley::parts::{self, Int4};
use std::sync::LazyLock;

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

/// Largest sample index the Sobol generator covers (it uses 16 index bits).
const SOBOL_MAX_SAMPLES: u32 = 1 << 16;

/// Sets of four Sobol dimensions whose generator matrices are tabulated; later sets are
/// generated bit by bit.
const TABULATED_SETS: usize = 4;

/// Per tabulated set of four dimensions and per four-bit digit of the (bit-reversed) index's
/// upper 16 bits, the Sobol points of all sixteen digit values: the generator is linear over
/// XOR, so a point is the XOR of four table entries.
type SobolTables = [[[Int4; 16]; 4]; TABULATED_SETS];

static SOBOL_TABLES: LazyLock<SobolTables> = LazyLock::new(|| {
    std::array::from_fn(|set| {
        std::array::from_fn(|digit| {
            std::array::from_fn(|value| {
                parts::sobol_int4_rev((value as u32) << (16 + 4 * digit), set as u32)
            })
        })
    })
});

/// Sobol dimensions `4·set .. 4·set + 4` (bit-reversed, unscrambled) of the point with
/// bit-reversed index `index_rev`.
#[inline]
fn sobol_set_rev(index_rev: u32, set: u32) -> Int4 {
    match SOBOL_TABLES.get(set as usize) {
        Some(table) => {
            let digit = |k: usize| table[k][((index_rev >> (16 + 4 * k)) & 15) as usize];
            digit(0) ^ digit(1) ^ digit(2) ^ digit(3)
        }
        None => parts::sobol_int4_rev(index_rev, set),
    }
}

/// The random numbers of one camera sample.
#[derive(Clone, Debug)]
pub struct Sampler {
    kind: SequenceKind,
    sample_index: u32,
    /// The sample index, bit-reversed and shuffled by the pixel's nested uniform scramble.
    shuffled_index: u32,
    /// The pixel's key for the per-dimension Owen scrambles.
    scramble: u32,
    dimension: u32,
    rng: Pcg32,
    /// The four Sobol dimensions of set `sobol_set` (computed together with SIMD).
    sobol_block: [f32; 4],
    sobol_set: u32,
}

/// Mixes integers into a well-distributed 64-bit value (SplitMix64 finaliser).
#[inline]
pub fn hash64(mut x: u64) -> u64 {
    x = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

impl Sampler {
    /// The sampler of sample `sample_index` of the pixel (or other stream) `stream`, for the
    /// image seed `seed`.
    #[inline]
    pub fn new(kind: SequenceKind, seed: u64, stream: u64, sample_index: u32) -> Self {
        let pixel_key = hash64(seed ^ hash64(stream));
        let state = hash64(pixel_key ^ (sample_index as u64).wrapping_mul(0x2545_f491_4f6c_dd1d));
        Sampler {
            kind,
            sample_index,
            shuffled_index: parts::owen_scramble_rev(sample_index.reverse_bits(), pixel_key as u32),
            scramble: (pixel_key >> 32) as u32,
            dimension: 0,
            rng: Pcg32::new(state, pixel_key | 1),
            sobol_block: [0.0; 4],
            sobol_set: u32::MAX,
        }
    }

    /// Sobol dimensions `4·set .. 4·set + 4` of this sample, Owen-scrambled.
    fn sobol_4d(&self, set: u32) -> [f32; 4] {
        // One independent scramble per dimension, hashed from the pixel key and the
        // dimension (Weyl steps by the golden ratio keep neighbouring dimensions apart).
        let dimension =
            |lane: u32| self.scramble ^ (4 * set + lane).wrapping_mul(0x9e37_79b9).rotate_left(16);
        let scrambles = parts::hash_int4(Int4::from(std::array::from_fn(|lane| {
            dimension(lane as u32)
        })));
        let sobol = sobol_set_rev(self.shuffled_index, set);
        parts::owen_scramble_int4_rev(sobol, scrambles)
            .reverse_bits()
            .to_f32_norm()
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
            // Four dimensions at a time (one SIMD scramble), kept for the next three draws.
            let set = dim / 4;
            if set != self.sobol_set {
                self.sobol_block = self.sobol_4d(set);
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
    fn sobol_tables_give_the_generator_points() {
        // Tabulated sets (and the generated ones beyond) must equal the crate's generator for
        // any index: the tables rely on its linearity over XOR.
        let mut rng = Pcg32::new(7, 9);
        for set in 0..TABULATED_SETS as u32 + 2 {
            for _ in 0..500 {
                let index_rev = rng.next_u32();
                let expected: [u32; 4] = parts::sobol_int4_rev(index_rev, set).into();
                let got: [u32; 4] = sobol_set_rev(index_rev, set).into();
                assert_eq!(got, expected, "set {set}, index {index_rev:#x}");
            }
        }
    }

    #[test]
    fn every_sobol_dimension_stratifies_the_unit_interval() {
        // 64 samples of one pixel put exactly one value in each 1/64 of [0, 1), in every
        // dimension, tabulated or not.
        let mut cells = vec![[0u32; 64]; 24];
        for i in 0..64 {
            let mut s = Sampler::new(SequenceKind::Sobol, 3, 12, i);
            for cell in cells.iter_mut() {
                cell[(s.next_1d() * 64.0) as usize] += 1;
            }
        }
        for (dim, cell) in cells.iter().enumerate() {
            assert!(cell.iter().all(|&c| c == 1), "dimension {dim}: {cell:?}");
        }
    }

    #[test]
    fn sobol_dimensions_and_pixels_are_decorrelated() {
        // Different dimensions of one sample, and one dimension of neighbouring pixels, are
        // scrambled independently: their values differ.
        let mut a = Sampler::new(SequenceKind::Sobol, 3, 12, 5);
        let mut b = Sampler::new(SequenceKind::Sobol, 3, 13, 5);
        let da: Vec<f32> = (0..8).map(|_| a.next_1d()).collect();
        let db: Vec<f32> = (0..8).map(|_| b.next_1d()).collect();
        for i in 0..8 {
            assert_ne!(da[i], db[i]);
            for j in 0..i {
                assert_ne!(da[i], da[j]);
            }
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
