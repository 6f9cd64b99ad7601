//! A discrete distribution over bins by its cumulative table, sampled by inverting it.

/// The cumulative sums of bin weights, normalised to end at 1: `cdf[0] = 0`,
/// `cdf[i + 1] − cdf[i]` the probability of bin `i`. All zeros when the weights sum to 0.
pub(super) fn cumulative(weights: &[f64]) -> (Vec<f64>, f64) {
    let mut cdf = Vec::with_capacity(weights.len() + 1);
    let mut sum = 0.0;
    cdf.push(0.0);
    for &w in weights {
        sum += w;
        cdf.push(sum);
    }
    if sum > 0.0 {
        for c in &mut cdf {
            *c /= sum;
        }
        // Exactly 1, whatever the rounding, so every u < 1 falls in a bin.
        *cdf.last_mut().unwrap() = 1.0;
    }
    (cdf, sum)
}

/// The bin of `cdf` that `u ∈ [0, 1)` falls in (never one of probability 0) and where in it,
/// as a fraction in `[0, 1)`: the fraction is uniform when `u` is.
pub(super) fn invert(cdf: &[f64], u: f64) -> (usize, f64) {
    let bins = cdf.len() - 1;
    let bin = (cdf.partition_point(|&c| c <= u) - 1).min(bins - 1);
    let width = cdf[bin + 1] - cdf[bin];
    let fraction = ((u - cdf[bin]) / width).clamp(0.0, 1.0 - f64::EPSILON / 2.0);
    (bin, fraction)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverting_skips_empty_bins_and_spreads_uniformly_within_a_bin() {
        let (cdf, sum) = cumulative(&[1.0, 0.0, 3.0, 0.0]);
        assert_eq!(sum, 4.0);
        assert_eq!(cdf, [0.0, 0.25, 0.25, 1.0, 1.0]);
        assert_eq!(invert(&cdf, 0.0), (0, 0.0));
        assert_eq!(invert(&cdf, 0.125), (0, 0.5));
        assert_eq!(invert(&cdf, 0.25), (2, 0.0));
        assert_eq!(invert(&cdf, 0.625), (2, 0.5));
        let (bin, fraction) = invert(&cdf, 1.0 - f64::EPSILON);
        assert!(bin == 2 && fraction < 1.0);
        let (zeros, sum) = cumulative(&[0.0, 0.0]);
        assert_eq!((zeros, sum), (vec![0.0; 3], 0.0));
    }
}
