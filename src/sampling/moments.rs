//! Running sums of Monte Carlo samples, for a mean and the standard error of it.

use crate::color::Rgb64;

/// The count, sum and sum of squares of samples, per channel.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Moments {
    /// Samples added.
    pub n: u64,
    sum: Rgb64,
    squares: Rgb64,
}

impl Moments {
    /// Adds one sample.
    pub fn add(&mut self, x: Rgb64) {
        self.n += 1;
        self.sum += x;
        self.squares += x * x;
    }

    /// The mean of the samples (zero for none).
    pub fn mean(&self) -> Rgb64 {
        self.sum / self.n.max(1) as f64
    }

    /// The spread (standard deviation) of one sample, per channel (zero for fewer than two).
    pub fn spread(&self) -> Rgb64 {
        (self.variance_of_mean() * self.n as f64).map(f64::sqrt)
    }

    /// The variance of the mean, per channel (zero for fewer than two samples).
    pub fn variance_of_mean(&self) -> Rgb64 {
        if self.n < 2 {
            return Rgb64::BLACK;
        }
        let n = self.n as f64;
        let mean = self.mean();
        ((self.squares / n - mean * mean) / (n - 1.0)).map(|v| v.max(0.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mean_and_variance_of_the_mean_are_those_of_the_samples() {
        let mut m = Moments::default();
        for x in [1.0, 2.0, 3.0, 6.0] {
            m.add(Rgb64::new(x, 2.0 * x, 0.0));
        }
        // Mean 3, sample variance (4 + 1 + 0 + 9) / 3 = 14/3, of the mean 14/12.
        assert_eq!(m.mean(), Rgb64::new(3.0, 6.0, 0.0));
        let v = m.variance_of_mean();
        assert!((v.r - 14.0 / 12.0).abs() < 1e-12 && (v.g - 4.0 * 14.0 / 12.0).abs() < 1e-12);
        assert_eq!(v.b, 0.0);
        assert!((m.spread().r - (14.0f64 / 3.0).sqrt()).abs() < 1e-12);
        let mut one = Moments::default();
        one.add(Rgb64::splat(5.0));
        assert_eq!(one.variance_of_mean(), Rgb64::BLACK);
    }
}
