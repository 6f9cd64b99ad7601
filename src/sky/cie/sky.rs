//! A CIE sky in absolute units: its relative luminance distribution scaled so that the sky
//! sends a given diffuse irradiance onto a horizontal plane.

use glam::DVec3;

use super::parameters::{CieParameters, CieSkyType};
use super::quadrature::hemisphere_cosine_integral;

/// A CIE general sky with the Sun in a given direction, scaled to a diffuse horizontal
/// irradiance `E_dh`: its radiance is `L(ω) = L_z · L(ω)/L_z` with the zenith radiance
/// `L_z = E_dh / ∫ (L/L_z) cos θ dω` (the integral over the upper hemisphere, in sr, by
/// Gauss–Legendre panels graded toward the Sun: relative error about 10⁻¹², checked against
/// closed forms and finer rules). Radiance is in
/// the unit of `E_dh` per steradian: W·m⁻²·sr⁻¹ for W·m⁻² (or per band, in a band's unit),
/// cd·m⁻² for lux. The Sun's disc itself is not part of the sky.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CieSky {
    parameters: CieParameters,
    sun: DVec3,
    zenith_radiance: f64,
}

impl CieSky {
    /// The sky of `parameters` for the Sun in the unit direction `sun` (y up), sending
    /// `diffuse_horizontal` (≥ 0; W·m⁻² or lux) onto a horizontal plane.
    pub fn new(parameters: CieParameters, sun: DVec3, diffuse_horizontal: f64) -> CieSky {
        let relative = hemisphere_cosine_integral(sun, |d| parameters.relative_luminance(sun, d));
        CieSky {
            parameters,
            sun,
            zenith_radiance: diffuse_horizontal / relative,
        }
    }

    /// The standard sky of type `sky` ([`CieSky::new`] with its parameters).
    pub fn standard(sky: CieSkyType, sun: DVec3, diffuse_horizontal: f64) -> CieSky {
        CieSky::new(sky.parameters(), sun, diffuse_horizontal)
    }

    /// The radiance of the zenith, `L_z` (the diffuse horizontal irradiance's unit per sr).
    pub fn zenith_radiance(&self) -> f64 {
        self.zenith_radiance
    }

    /// The radiance of the sky in the unit direction `direction` (pointing away from the
    /// observer, y up), per sr; 0 below the horizon.
    pub fn radiance(&self, direction: DVec3) -> f64 {
        self.zenith_radiance * self.parameters.relative_luminance(self.sun, direction)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sky::direction_from_angles;
    use std::f64::consts::PI;

    #[test]
    fn a_uniform_sky_of_radiance_l_gives_pi_l() {
        for sun in [DVec3::Y, direction_from_angles(70.0, 33.0)] {
            let sky = CieSky::standard(CieSkyType::Uniform, sun, 100.0);
            assert!((sky.zenith_radiance() * PI - 100.0).abs() < 1e-12);
            let at = direction_from_angles(80.0, 250.0);
            assert!((sky.radiance(at) - 100.0 / PI).abs() < 1e-12);
        }
    }

    /// The exponential integral E₃(x) for 0 < x ≤ 2, from the series of E₁ and the
    /// recurrence Eₙ₊₁(x) = (e⁻ˣ − x·Eₙ(x)) / n.
    fn e3(x: f64) -> f64 {
        const EULER_GAMMA: f64 = 0.577_215_664_901_532_9;
        let mut series = 0.0;
        let mut term = 1.0;
        for k in 1..60 {
            term *= -x / k as f64;
            series += term / k as f64;
        }
        let e1 = -EULER_GAMMA - x.ln() - series;
        let e2 = (-x).exp() - x * e1;
        ((-x).exp() - x * e2) / 2.0
    }

    #[test]
    fn overcast_sky_against_its_closed_form() {
        // Type 1 (c = e = 0) depends on Z alone: with μ = cos Z,
        // ∫ L/L_z cos θ dω = 2π ∫₀¹ (1 + a·e^(b/μ)) μ dμ / (1 + a·e^b)
        //                  = 2π (1/2 + a·E₃(−b)) / (1 + a·e^b),
        // since ∫₀¹ μ e^(b/μ) dμ = ∫₁^∞ e^(bt) t⁻³ dt = E₃(−b).
        let CieParameters { a, b, .. } = CieSkyType::OvercastSteep.parameters();
        let exact = 2.0 * PI * (0.5 + a * e3(-b)) / (1.0 + a * b.exp());
        // E₃ itself against Simpson's rule on ∫₀¹ μ e^(−0.7/μ) dμ.
        let n = 100_000;
        let simpson: f64 = (0..=n)
            .map(|i| {
                let mu = i as f64 / n as f64;
                let g = if mu == 0.0 { 0.0 } else { mu * (b / mu).exp() };
                let weight = if i == 0 || i == n {
                    1.0
                } else {
                    [4.0, 2.0][(i + 1) % 2]
                };
                weight * g
            })
            .sum::<f64>()
            / (3.0 * n as f64);
        assert!((e3(-b) - simpson).abs() < 1e-12, "{} {simpson}", e3(-b));
        for sun in [DVec3::Y, direction_from_angles(45.0, 100.0)] {
            let sky = CieSky::standard(CieSkyType::OvercastSteep, sun, 250.0);
            let integral = 250.0 / sky.zenith_radiance();
            assert!(
                (integral - exact).abs() < 1e-12 * exact,
                "{integral} against {exact}"
            );
        }
        // Type 1 stands for Moon & Spencer's traditional overcast sky, (1 + 2 cos Z)/3, whose
        // integral is 2π(1/2 + 2/3)/3 = 7π/9: within a percent.
        assert!((exact / (7.0 * PI / 9.0) - 1.0).abs() < 0.01, "{exact}");
    }

    #[test]
    fn sun_at_the_zenith_against_a_one_dimensional_integral() {
        // With the Sun at the zenith χ = Z, and ∫ L/L_z cos θ dω = 2π ∫₀^{π/2} f(Z)φ(Z)
        // cos Z sin Z dZ / (f(0)φ(0)): composite Simpson, smooth in Z.
        for sky in CieSkyType::ALL {
            let p = sky.parameters();
            let n = 20_000;
            let h = PI / 2.0 / n as f64;
            let g = |z: f64| p.indicatrix(z) * p.gradation(z.cos()) * z.cos() * z.sin();
            let simpson: f64 = (0..=n)
                .map(|i| {
                    let weight = if i == 0 || i == n {
                        1.0
                    } else {
                        [4.0, 2.0][(i + 1) % 2]
                    };
                    weight * g(i as f64 * h)
                })
                .sum::<f64>()
                * h
                / 3.0;
            let exact = 2.0 * PI * simpson / (p.indicatrix(0.0) * p.gradation(1.0));
            let integral = 1.0 / CieSky::standard(sky, DVec3::Y, 1.0).zenith_radiance();
            assert!(
                (integral - exact).abs() < 1e-11 * exact,
                "{sky:?}: {integral} against {exact}"
            );
        }
    }

    #[test]
    fn every_type_and_sun_against_a_fine_midpoint_rule() {
        // An independent rule: midpoints of a fine grid in (θ, azimuth), absolute azimuth,
        // whose own error (O(h²), largest for a low Sun over the horizon's steep gradation)
        // is 6·10⁻⁶ at most here.
        let (rows, columns) = (500, 1000);
        let (dt, dp) = (PI / 2.0 / rows as f64, 2.0 * PI / columns as f64);
        for sky in CieSkyType::ALL {
            for (zenith, azimuth) in [(20.0, 10.0), (60.0, 200.0), (85.0, 300.0)] {
                let sun = direction_from_angles(zenith, azimuth);
                let p = sky.parameters();
                let mut midpoint = 0.0;
                for i in 0..rows {
                    let theta = (i as f64 + 0.5) * dt;
                    let (sin, cos) = theta.sin_cos();
                    for j in 0..columns {
                        let phi = (j as f64 + 0.5) * dp;
                        let d = DVec3::new(sin * phi.sin(), cos, -sin * phi.cos());
                        midpoint += p.relative_luminance(sun, d) * cos * sin;
                    }
                }
                midpoint *= dt * dp;
                let integral = 1.0 / CieSky::standard(sky, sun, 1.0).zenith_radiance();
                assert!(
                    (integral - midpoint).abs() < 2e-5 * midpoint,
                    "{sky:?} sun ({zenith}, {azimuth}): {integral} against {midpoint}"
                );
            }
        }
    }

    #[test]
    fn radiance_is_the_zenith_radiance_times_the_relative_luminance() {
        let sun = direction_from_angles(35.0, 160.0);
        let sky = CieSky::standard(CieSkyType::ClearLowTurbidity, sun, 120.0);
        assert!((sky.radiance(DVec3::Y) - sky.zenith_radiance()).abs() < 1e-12);
        let d = direction_from_angles(60.0, 10.0);
        let expected = sky.zenith_radiance()
            * crate::sky::relative_luminance(CieSkyType::ClearLowTurbidity, sun, d);
        assert!((sky.radiance(d) - expected).abs() < 1e-12);
        assert_eq!(sky.radiance(direction_from_angles(95.0, 10.0)), 0.0);
    }
}
