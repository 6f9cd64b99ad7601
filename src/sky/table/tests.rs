//! The tabulated sky's sampling against its density and against the sky it tabulates.

use super::*;
use crate::sky::{CieSky, CieSkyType, direction_from_angles};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64Mcg;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// A clear sky (type 12) with the Sun 35° from the zenith in the south-east, 100 W·m⁻².
fn clear_sky() -> CieSky {
    CieSky::standard(
        CieSkyType::ClearLowTurbidity,
        direction_from_angles(35.0, 135.0),
        100.0,
    )
}

fn uniforms(rng: &mut Pcg64Mcg) -> [f64; 2] {
    [rng.random::<f64>(), rng.random::<f64>()]
}

#[test]
fn the_density_integrates_to_one() {
    let sky = clear_sky();
    let table = SkyTable::new(32, 64, |d| sky.radiance(d));
    // Exactly, over the cells.
    let (row_width, column_width) = (FRAC_PI_2 / 32.0, TAU / 64.0);
    let mut total = 0.0;
    for (cell, density) in table.densities.iter().enumerate() {
        let (top, bottom) = mu_bounds(cell / 64, row_width);
        total += density * column_width * (top - bottom);
    }
    assert!((total - 1.0).abs() < 1e-12, "{total}");
    // And through `pdf`, by Monte Carlo over directions uniform in the hemisphere: the mean
    // of 2π·pdf is 1, within four standard errors.
    let mut rng = Pcg64Mcg::seed_from_u64(7);
    let n = 200_000;
    let (mut sum, mut squares) = (0.0, 0.0);
    for _ in 0..n {
        let [a, b] = uniforms(&mut rng);
        let x = TAU * table.pdf(direction(a, TAU * b));
        sum += x;
        squares += x * x;
    }
    let mean = sum / n as f64;
    let error = ((squares / n as f64 - mean * mean) / (n - 1) as f64).sqrt();
    assert!((mean - 1.0).abs() < 4.0 * error, "{mean} ± {error}");
    // Nothing below the horizon.
    assert_eq!(table.pdf(direction_from_angles(91.0, 0.0)), 0.0);
}

#[test]
fn sampled_directions_carry_the_density_of_their_cell() {
    let sky = clear_sky();
    let table = SkyTable::new(16, 32, |d| sky.radiance(d));
    let mut rng = Pcg64Mcg::seed_from_u64(11);
    for _ in 0..10_000 {
        let sample = table.sample(uniforms(&mut rng)).unwrap();
        assert!((sample.direction.length() - 1.0).abs() < 1e-14);
        assert!(sample.direction.y >= 0.0 && sample.pdf > 0.0);
        assert_eq!(table.pdf(sample.direction), sample.pdf);
    }
    // The table's irradiance is the sky's, to the tabulation's accuracy.
    let relative = table.irradiance() / 100.0 - 1.0;
    assert!(relative.abs() < 2e-3, "{relative:e}");
}

/// `∫ L cos θ dω` over the zenith angles `[θ0, θ1]` and azimuths `[φ0, φ1]` (radians), by a
/// fine midpoint rule.
fn bin_irradiance(sky: &CieSky, theta: (f64, f64), phi: (f64, f64)) -> f64 {
    let n = 48;
    let (dt, dp) = ((theta.1 - theta.0) / n as f64, (phi.1 - phi.0) / n as f64);
    let mut sum = 0.0;
    for i in 0..n {
        let t = theta.0 + (i as f64 + 0.5) * dt;
        for j in 0..n {
            let p = phi.0 + (j as f64 + 0.5) * dp;
            sum += sky.radiance(direction(t.cos(), p)) * t.cos() * t.sin();
        }
    }
    sum * dt * dp
}

#[test]
fn sampled_directions_follow_l_cos_theta() {
    // Histogram of 100 000 draws over 8 × 16 bins (each 4 × 4 cells of the table) against
    // the probabilities ∫_bin L cos θ dω / E_dh of the sky itself: Pearson's χ² with 127
    // degrees of freedom (mean 127, standard deviation √254 ≈ 16) under six deviations
    // above its mean.
    let sky = clear_sky();
    let table = SkyTable::new(32, 64, |d| sky.radiance(d));
    let (bin_rows, bin_columns) = (8, 16);
    let n = 100_000;
    let mut counts = vec![0u32; bin_rows * bin_columns];
    let mut rng = Pcg64Mcg::seed_from_u64(3);
    for _ in 0..n {
        let d = table.sample(uniforms(&mut rng)).unwrap().direction;
        let (zenith, azimuth) = angles_from_direction(d);
        let row = ((zenith.to_radians() / FRAC_PI_2 * bin_rows as f64) as usize).min(7);
        let column = ((azimuth.to_radians() / TAU * bin_columns as f64) as usize).min(15);
        counts[row * bin_columns + column] += 1;
    }
    let (tw, pw) = (FRAC_PI_2 / bin_rows as f64, TAU / bin_columns as f64);
    let mut chi_square = 0.0;
    let mut probability_sum = 0.0;
    for row in 0..bin_rows {
        for column in 0..bin_columns {
            let theta = (row as f64 * tw, (row + 1) as f64 * tw);
            let phi = (column as f64 * pw, (column + 1) as f64 * pw);
            let p = bin_irradiance(&sky, theta, phi) / 100.0;
            probability_sum += p;
            let expected = p * n as f64;
            assert!(
                expected > 20.0,
                "bin ({row}, {column}) too small for χ²: {expected}"
            );
            let observed = f64::from(counts[row * bin_columns + column]);
            chi_square += (observed - expected).powi(2) / expected;
        }
    }
    assert!((probability_sum - 1.0).abs() < 1e-4, "{probability_sum}");
    let dof = (bin_rows * bin_columns - 1) as f64;
    assert!(
        chi_square < dof + 6.0 * (2.0 * dof).sqrt(),
        "χ² = {chi_square}"
    );
}

#[test]
fn importance_sampled_estimate_of_the_irradiance_is_unbiased_and_smooth() {
    // E_dh = E[L cos θ / pdf] over the table's draws, for any table: the estimate must be
    // 100 W·m⁻² within four standard errors, and the table close enough to L·cos θ that one
    // draw's relative spread is small.
    let sky = clear_sky();
    let table = SkyTable::new(32, 64, |d| sky.radiance(d));
    let mut rng = Pcg64Mcg::seed_from_u64(5);
    let n = 50_000;
    let (mut sum, mut squares) = (0.0, 0.0);
    for _ in 0..n {
        let s = table.sample(uniforms(&mut rng)).unwrap();
        let x = sky.radiance(s.direction) * s.direction.y / s.pdf;
        sum += x;
        squares += x * x;
    }
    let mean = sum / n as f64;
    let spread = (squares / n as f64 - mean * mean).sqrt();
    let error = spread / ((n - 1) as f64).sqrt();
    assert!((mean - 100.0).abs() < 4.0 * error, "{mean} ± {error}");
    assert!(spread / mean < 0.1, "relative spread {}", spread / mean);
}

#[test]
fn a_uniform_sky_samples_the_cosine_distribution() {
    // L constant: the density on a cell is the cell's mean of cos θ / π, (μ_top + μ_bottom)
    // / 2π (the mean of μ over a cell, uniform in μ, is exact at the 4 midpoints), and the
    // table's irradiance is exactly π·L.
    let rows = 64;
    let table = SkyTable::new(rows, 4, |_| 2.0);
    assert!(
        (table.irradiance() - 2.0 * PI).abs() < 1e-12,
        "{}",
        table.irradiance()
    );
    for zenith in [5.0f64, 40.0, 80.0] {
        let pdf = table.pdf(direction_from_angles(zenith, 100.0));
        let row = (zenith / 90.0 * rows as f64) as usize;
        let (top, bottom) = mu_bounds(row, FRAC_PI_2 / rows as f64);
        let expected = (top + bottom) / (2.0 * PI);
        assert!((pdf - expected).abs() < 1e-12, "{zenith}: {pdf} {expected}");
    }
}

#[test]
fn a_dark_sky_draws_nothing() {
    let table = SkyTable::new(4, 8, |_| 0.0);
    assert_eq!(table.irradiance(), 0.0);
    assert_eq!(table.sample([0.5, 0.5]), None);
    assert_eq!(table.pdf(DVec3::Y), 0.0);
}
