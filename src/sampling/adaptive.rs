//! How many more samples an estimate needs: the rule shared by the measurements that go on
//! in rounds until each estimate's standard error is at most a given share of its value (the
//! final gather at the reported surfaces, the surface tracer).

use crate::color::Rgb64;

/// Channels below this share of an estimate's brightest channel do not hold it back.
pub const DIM_CHANNEL: f64 = 0.01;

/// The channels of `value` not below [`DIM_CHANNEL`] of its brightest.
pub fn lit_channels(value: Rgb64) -> impl Iterator<Item = usize> {
    let brightest = value.max_channel();
    (0..3).filter(move |&c| value[c] > DIM_CHANNEL * brightest)
}

/// The largest relative standard error `√variance / value` over the lit channels of
/// `value`, and its channel (0 and channel 0 when none is lit).
pub fn worst_relative_error(value: Rgb64, variance: Rgb64) -> (f64, usize) {
    lit_channels(value)
        .map(|c| (variance[c].sqrt() / value[c], c))
        .fold((0.0, 0), |a, b| if b.0 > a.0 { b } else { a })
}

/// The samples an estimate of `n` samples with relative error `relative` is to have in all
/// for `target`: the error falls as one over the root of the samples, so as many more as it
/// says, a tenth over lest the next round fall just short, in a power of two — 2 to 16 times
/// `n`, at most `max`.
pub fn samples_for(n: u64, relative: f64, target: f64, max: u64) -> u64 {
    let doublings = (1.1 * (relative / target).powi(2))
        .log2()
        .ceil()
        .clamp(1.0, 4.0);
    (n << doublings as u32).min(max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_dim_channel_does_not_count_and_the_samples_grow_by_the_error() {
        let value = Rgb64::new(100.0, 0.5, 10.0);
        assert_eq!(lit_channels(value).collect::<Vec<_>>(), [0, 2]);
        let variance = Rgb64::new(4.0, 1.0, 1.0);
        assert_eq!(worst_relative_error(value, variance), (0.1, 2));
        // Twice the error asked for: 4.4 × the samples, rounded up to 8 ×.
        assert_eq!(samples_for(100, 0.02, 0.01, 1 << 20), 800);
        // Barely over: at least twice; far over: at most 16 ×; never past the cap.
        assert_eq!(samples_for(100, 0.0101, 0.01, 1 << 20), 200);
        assert_eq!(samples_for(100, 1.0, 0.01, 1 << 20), 1600);
        assert_eq!(samples_for(100, 1.0, 0.01, 1000), 1000);
    }
}
