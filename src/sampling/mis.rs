//! Multiple importance sampling: weights that combine two strategies sampling the same
//! light (Veach's power heuristic, β = 2), lane by lane.

use crate::lanes::Real;

/// Power heuristic weight of the strategy with density `a` against one with density `b`:
/// `a² / (a² + b²)`, 0 when both densities are 0.
#[inline(always)]
pub fn power_heuristic<R: Real>(a: R, b: R) -> R {
    let (a2, b2) = (a * a, b * b);
    let sum = a2 + b2;
    let zero = R::splat(0.0);
    R::select_with(sum.gt(zero), || a2 / sum, || zero)
}

/// Weight of a light sample with solid-angle density `light_pdf` against BSDF sampling,
/// whose density `bsdf_pdf` is asked for only where needed: the power heuristic, or 1 for a
/// delta light (`light_pdf = 0`), which BSDF sampling cannot hit.
#[inline(always)]
pub fn light_sample_weight<R: Real>(light_pdf: R, bsdf_pdf: impl FnOnce() -> R) -> R {
    R::select_with(
        light_pdf.gt(R::splat(0.0)),
        || power_heuristic(light_pdf, bsdf_pdf()),
        || R::splat(1.0),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_of_two_strategies_sum_to_one() {
        for (a, b) in [(1.0f32, 3.0f32), (0.2, 0.2), (5.0, 0.0)] {
            assert!((power_heuristic(a, b) + power_heuristic(b, a) - 1.0).abs() < 1e-6);
        }
        assert_eq!(power_heuristic(0.0f32, 0.0), 0.0);
        assert_eq!(light_sample_weight(0.0f32, || panic!("not asked")), 1.0);
        assert_eq!(light_sample_weight(1.0f32, || 1.0), 0.5);
    }
}
