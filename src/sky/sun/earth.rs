//! The Earth's heliocentric position from the periodic terms (Reda & Andreas, §3.2) and the
//! Sun's geocentric position from it (§3.3).

use super::earth_terms;

/// The Earth's heliocentric longitude L (degrees, in `[0, 360)`), latitude B (degrees) and
/// radius vector R (AU) at `jme` Julian ephemeris millennia from J2000.0.
pub(super) fn heliocentric(jme: f64) -> (f64, f64, f64) {
    let longitude = series(&earth_terms::L, jme).to_degrees().rem_euclid(360.0);
    let latitude = series(&earth_terms::B, jme).to_degrees();
    let radius = series(&earth_terms::R, jme);
    (longitude, latitude, radius)
}

/// The Sun's geocentric longitude Θ (degrees, in `[0, 360)`) and latitude β (degrees) seen
/// from the Earth at heliocentric longitude and latitude `(l, b)`.
pub(super) fn geocentric(l: f64, b: f64) -> (f64, f64) {
    ((l + 180.0).rem_euclid(360.0), -b)
}

/// `Σₖ τᵏ·Σ A·cos(B + C·τ)` over the tables of the powers `k`, scaled from 10⁻⁸.
fn series(tables: &[&[[f64; 3]]], tau: f64) -> f64 {
    let sums = tables.iter().map(|terms| {
        terms
            .iter()
            .map(|[a, b, c]| a * (b + c * tau).cos())
            .sum::<f64>()
    });
    // Horner's scheme from the highest power down.
    let total = sums.rev().fold(0.0, |acc, sum| acc * tau + sum);
    total / 1e8
}
