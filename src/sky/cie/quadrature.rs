//! Integrals over the upper hemisphere of functions symmetric about the Sun's vertical
//! plane, by Gauss–Legendre rules on panels graded toward the Sun, where the CIE indicatrix
//! has its cusp (`exp(d·χ)` is not smooth at χ = 0): in the zenith angle θ and the azimuth
//! from the Sun ψ, the cusp sits on a corner of the panels.

use glam::DVec3;

/// Gauss–Legendre points per panel.
const ORDER: usize = 24;
/// Panels per interval, graded by factors of four toward the interval's singular end.
const PANELS: usize = 5;

/// `∫ g(ω) cos θ dω` over the upper hemisphere (θ from +y), in the units of `g` times
/// steradians, for a `g` symmetric about the vertical plane through the unit direction
/// `sun` (every CIE sky is). Integrates `g·cos θ·sin θ` over θ ∈ [0, π/2] and the azimuth
/// from the Sun ψ ∈ [0, π] (doubled), with the θ-interval split at the Sun's zenith angle
/// and both variables graded toward the Sun (θ toward the horizon as well).
pub(super) fn hemisphere_cosine_integral(sun: DVec3, g: impl Fn(DVec3) -> f64) -> f64 {
    integral(ORDER, PANELS, sun, g)
}

/// [`hemisphere_cosine_integral`] with `order` points on each of `panels` panels per
/// interval.
fn integral(order: usize, panels: usize, sun: DVec3, g: impl Fn(DVec3) -> f64) -> f64 {
    let (nodes, weights) = gauss_legendre(order);
    let rule = |a: f64, b: f64| {
        nodes
            .iter()
            .zip(&weights)
            .map(move |(x, w)| (a + (b - a) * 0.5 * (x + 1.0), w * 0.5 * (b - a)))
    };
    // The horizontal frame of the Sun's azimuth (any for a Sun at the zenith).
    let horizontal = DVec3::new(sun.x, 0.0, sun.z);
    let toward = if horizontal.length() > 1e-12 {
        horizontal.normalize()
    } else {
        DVec3::NEG_Z
    };
    let side = DVec3::Y.cross(toward);
    let sun_theta = sun.y.clamp(0.0, 1.0).acos();
    // Below the Sun, graded toward the Sun and toward the horizon too: where b is small the
    // gradation 1 + a·exp(b / cos θ) changes fast just above the horizon.
    let horizon = std::f64::consts::FRAC_PI_2;
    let middle = 0.5 * (sun_theta + horizon);
    let mut theta_panels = graded(sun_theta, 0.0, panels);
    theta_panels.extend(graded(sun_theta, middle, panels));
    theta_panels.extend(graded(horizon, middle, panels));
    let psi_panels = graded(0.0, std::f64::consts::PI, panels);
    let mut total = 0.0;
    for &(theta0, theta1) in &theta_panels {
        for (theta, w_theta) in rule(theta0, theta1) {
            let (sin_theta, mu) = theta.sin_cos();
            let mut ring = 0.0;
            for &(psi0, psi1) in &psi_panels {
                for (psi, w_psi) in rule(psi0, psi1) {
                    let (sin_psi, cos_psi) = psi.sin_cos();
                    let direction = mu * DVec3::Y + sin_theta * (cos_psi * toward + sin_psi * side);
                    ring += w_psi * g(direction);
                }
            }
            total += w_theta * mu * sin_theta * ring;
        }
    }
    2.0 * total
}

/// `panels` panels of the interval from `singular` to `other` (either order), widths
/// growing by four away from `singular`; none if the interval is empty.
fn graded(singular: f64, other: f64, panels: usize) -> Vec<(f64, f64)> {
    if singular == other {
        return Vec::new();
    }
    let mut cuts = vec![singular];
    for k in (1..panels).rev() {
        cuts.push(singular + (other - singular) * 0.25f64.powi(k as i32));
    }
    cuts.push(other);
    cuts.windows(2)
        .map(|w| (w[0].min(w[1]), w[0].max(w[1])))
        .collect()
}

/// The nodes on `[−1, 1]` and weights of the `n`-point Gauss–Legendre rule: the roots of
/// the Legendre polynomial Pₙ by Newton's method from Tricomi's approximation.
fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut nodes = Vec::with_capacity(n);
    let mut weights = Vec::with_capacity(n);
    let nf = n as f64;
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
        let mut derivative = 0.0;
        for _ in 0..100 {
            // P_n(x) and P_{n−1}(x) by the three-term recurrence.
            let (mut p, mut p_previous) = (1.0, 0.0);
            for k in 1..=n {
                let kf = k as f64;
                (p, p_previous) = (((2.0 * kf - 1.0) * x * p - (kf - 1.0) * p_previous) / kf, p);
            }
            derivative = nf * (x * p - p_previous) / (x * x - 1.0);
            let step = p / derivative;
            x -= step;
            if step.abs() < 1e-16 {
                break;
            }
        }
        nodes.push(x);
        weights.push(2.0 / ((1.0 - x * x) * derivative * derivative));
    }
    (nodes, weights)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sky::{CieSkyType, direction_from_angles};
    use std::f64::consts::PI;

    #[test]
    fn gauss_legendre_integrates_polynomials_of_degree_2n_minus_1_exactly() {
        let (x, w) = gauss_legendre(ORDER);
        assert!((w.iter().sum::<f64>() - 2.0).abs() < 1e-14);
        for degree in [2, 10, 46] {
            let sum: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(degree)).sum();
            let exact = 2.0 / (degree as f64 + 1.0);
            assert!((sum - exact).abs() < 1e-14, "x^{degree}: {sum} {exact}");
        }
    }

    #[test]
    fn graded_panels_tile_the_interval() {
        let panels = graded(0.3, 0.0, PANELS);
        assert_eq!(panels.len(), PANELS);
        assert_eq!(panels[0].1, 0.3);
        assert_eq!(panels.last().unwrap().0, 0.0);
        assert!(graded(1.0, 1.0, PANELS).is_empty());
    }

    #[test]
    fn cosine_weighted_hemisphere_integrals_of_known_functions() {
        let sun = DVec3::new(0.3, 0.8, -0.5).normalize();
        // ∫ cos θ dω = π; ∫ cos² θ dω = 2π/3.
        let one = hemisphere_cosine_integral(sun, |_| 1.0);
        assert!((one - PI).abs() < 1e-13, "{one}");
        let cos = hemisphere_cosine_integral(sun, |d| d.y);
        assert!((cos - 2.0 * PI / 3.0).abs() < 1e-13, "{cos}");
        // A function with a cusp at the Sun, the Sun at the zenith: the cosine-weighted
        // integral of e^(−3χ) is 2π ∫₀^{π/2} e^(−3θ) sin 2θ / 2 dθ
        // = 2π·(1/2)·(2 + 2e^(−3π/2)) / (3² + 4).
        let zenith = hemisphere_cosine_integral(DVec3::Y, |d| (-3.0 * d.y.acos()).exp());
        let exact = 2.0 * PI * 0.5 * (2.0 + 2.0 * (-1.5 * PI).exp()) / 13.0;
        assert!((zenith - exact).abs() < 1e-12 * exact, "{zenith} {exact}");
    }

    #[test]
    fn converged_for_every_cie_sky() {
        // The rule against one of 48 points on 8 panels per interval, all 15 skies, the
        // Sun from the zenith to the horizon.
        let mut worst: f64 = 0.0;
        for sky in CieSkyType::ALL {
            let p = sky.parameters();
            for zenith in [0.0, 10.0, 45.0, 75.0, 89.0] {
                let sun = direction_from_angles(zenith, 30.0);
                let g = |d| p.relative_luminance(sun, d);
                let fine = integral(48, 8, sun, g);
                let coarse = hemisphere_cosine_integral(sun, g);
                worst = worst.max((coarse / fine - 1.0).abs());
            }
        }
        // 4·10⁻¹⁴ when written.
        assert!(worst < 1e-12, "{worst:e}");
    }
}
