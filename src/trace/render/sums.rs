//! Exact per-pixel sums of radiance samples: every sample's channels in fixed point, added as
//! integers, so that a pixel's sum depends neither on the order of its samples nor on how
//! they were split into passes, threads or batches run apart — sums of batches added give the
//! single run's sums, and its image, bit for bit.
//!
//! Units: 2⁻⁶⁰ W·sr⁻¹·m⁻² (resolution 8.7·10⁻¹⁹, far below a single-precision sample's own
//! rounding at any brightness an image shows; a sample is truncated to whole units, exactly
//! kept from 2⁻³⁷ W·sr⁻¹·m⁻² up). Each channel of a sample is clamped to ±2³⁴ W·sr⁻¹·m⁻²
//! (1.7·10¹⁰, a thousand times the sun's disc) before it is added, so that the sum of
//! `u32::MAX` samples stays within an `i128` (2³² · 2³⁴ · 2⁶⁰ = 2¹²⁶). Memory: 48 bytes per
//! pixel (a progressive render keeps two such images: the finished passes and the pass under
//! way).

use crate::color::Rgb;
use crate::measure::Film;
use crate::sampling::from_fixed;
use crate::sampling::{pack, unpack};

/// Fixed-point units per W·sr⁻¹·m⁻².
const UNITS: f64 = (1u64 << 60) as f64;
/// [`UNITS`] in single precision (a power of two: multiplying by it is exact).
const UNITS_F32: f32 = UNITS as f32;
/// Largest magnitude of one sample's channel in fixed-point units (2³⁴ W·sr⁻¹·m⁻²).
const MAX_SAMPLE: f32 = (1u128 << 94) as f32;
/// Magnitude below which a value in fixed-point units converts through `i64` (2⁶³).
const FITS_I64: f32 = (1u64 << 63) as f32;

/// One channel of a sample, W·sr⁻¹·m⁻², in fixed-point units, truncated toward zero
/// (exact down to 2⁻³⁷ W·sr⁻¹·m⁻², where single precision's spacing reaches the unit) and
/// clamped to ±2³⁴ W·sr⁻¹·m⁻². In single precision throughout, converted through `i64`
/// below 8 W·sr⁻¹·m⁻²: per sample this is the render's only cost over a float sum.
#[inline]
fn fixed(c: f32) -> i128 {
    let y = c * UNITS_F32;
    if y.abs() < FITS_I64 {
        y as i64 as i128
    } else {
        y.clamp(-MAX_SAMPLE, MAX_SAMPLE) as i128
    }
}

/// The sum of one pixel's samples, per channel, in units of 2⁻⁶⁰ W·sr⁻¹·m⁻².
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct PixelSum([i128; 3]);

impl PixelSum {
    /// Adds sample `radiance` (finite, W·sr⁻¹·m⁻²; each channel clamped to ±2³⁴).
    #[inline]
    pub(super) fn add(&mut self, radiance: Rgb) {
        for (sum, c) in self.0.iter_mut().zip(radiance.to_array()) {
            *sum += fixed(c);
        }
    }

    /// The mean radiance of `samples` samples summed, W·sr⁻¹·m⁻² (black for none).
    fn mean(self, samples: u32) -> Rgb {
        if samples == 0 {
            return Rgb::BLACK;
        }
        let per_unit = 1.0 / (UNITS * f64::from(samples));
        Rgb::from(self.0.map(|q| (from_fixed(q) * per_unit) as f32))
    }
}

/// The sums of the samples of every pixel of a `width × height` image (row-major), each
/// pixel with the same number of samples.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PixelSums {
    width: u32,
    height: u32,
    samples: u32,
    sums: Vec<PixelSum>,
}

impl PixelSums {
    /// No samples yet in a `width × height` image.
    pub fn new(width: u32, height: u32) -> Self {
        PixelSums {
            width,
            height,
            samples: 0,
            sums: vec![PixelSum::default(); width as usize * height as usize],
        }
    }

    /// Width and height in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Samples per pixel summed.
    pub fn samples(&self) -> u32 {
        self.samples
    }

    /// Sums of `samples` samples per pixel of a `width × height` image, row-major.
    /// `None` when there are not `width × height` of them.
    pub(super) fn from_sums(
        width: u32,
        height: u32,
        samples: u32,
        sums: Vec<PixelSum>,
    ) -> Option<Self> {
        (sums.len() == width as usize * height as usize).then_some(PixelSums {
            width,
            height,
            samples,
            sums,
        })
    }

    /// Adds `other`'s samples to these, pixel by pixel; `false` (and nothing added) when it
    /// is of another size. Integers: sums added in any order are the same. Saturates
    /// instead of overflowing, which sums of one run's samples never reach.
    pub fn add(&mut self, other: &PixelSums) -> bool {
        if other.size() != self.size() {
            return false;
        }
        for (a, b) in self.sums.iter_mut().zip(&other.sums) {
            for (x, y) in a.0.iter_mut().zip(b.0) {
                *x = x.saturating_add(y);
            }
        }
        self.samples = self.samples.saturating_add(other.samples);
        true
    }

    /// The mean radiance per pixel, W·sr⁻¹·m⁻² (black with no samples); `None` for an empty
    /// image.
    pub fn film(&self) -> Option<Film> {
        let pixels = self.sums.iter().map(|s| s.mean(self.samples)).collect();
        Film::from_pixels(self.width, self.height, pixels)
    }
}

/// [`PixelSums`] as they are serialized: the size, the samples per pixel, and the sums
/// packed into one string (`sampling::pack`: red, green, blue of each pixel in turn, row-major).
#[derive(serde::Serialize, serde::Deserialize)]
struct PackedSums {
    width: u32,
    height: u32,
    samples: u32,
    sums: String,
}

impl serde::Serialize for PixelSums {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        PackedSums {
            width: self.width,
            height: self.height,
            samples: self.samples,
            sums: pack(self.sums.iter().flat_map(|s| s.0)),
        }
        .serialize(serializer)
    }
}

impl<'de> serde::Deserialize<'de> for PixelSums {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let packed = PackedSums::deserialize(deserializer)?;
        let values = unpack(&packed.sums)
            .ok_or_else(|| serde::de::Error::custom("the sums are not packed integers"))?;
        let sums = values
            .chunks_exact(3)
            .map(|c| PixelSum([c[0], c[1], c[2]]))
            .collect();
        PixelSums::from_sums(packed.width, packed.height, packed.samples, sums).ok_or_else(|| {
            serde::de::Error::custom(format!(
                "{} sums for {}×{} pixels (3 each)",
                values.len(),
                packed.width,
                packed.height
            ))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_are_kept_exactly_and_huge_ones_clamped() {
        let mut sum = PixelSum::default();
        for c in [0.1f32, 7.99, 8.0, 3.0e9, 1e-30] {
            sum.add(Rgb::new(c, -c, 0.0));
        }
        let exact = |c: f32| (f64::from(c) * UNITS) as i128;
        let total: i128 = [0.1f32, 7.99, 8.0, 3.0e9].iter().map(|&c| exact(c)).sum();
        assert_eq!(sum.0, [total, -total, 0]);
        // Brighter than the clamp, many times: no overflow, the clamp's mean.
        let mut bright = PixelSum::default();
        for _ in 0..1000 {
            bright.add(Rgb::new(f32::MAX, 1e20, -f32::MAX));
        }
        let most = 2f32.powi(34);
        assert_eq!(bright.mean(1000), Rgb::new(most, most, -most));
    }
}
