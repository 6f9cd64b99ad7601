//! The nutation in longitude and obliquity and the true obliquity of the ecliptic (Reda &
//! Andreas, §3.4 and §3.5).

use super::nutation_terms::TERMS;

/// The nutation in longitude Δψ and in obliquity Δε, in degrees, at `jce` Julian ephemeris
/// centuries from J2000.0.
pub(super) fn nutation(jce: f64) -> (f64, f64) {
    let t = jce;
    let cubic = |c0: f64, c1: f64, c2: f64, c3_divisor: f64| {
        c0 + c1 * t + c2 * t * t + t * t * t / c3_divisor
    };
    // The fundamental arguments, degrees: the mean elongation of the Moon from the Sun, the
    // mean anomalies of the Sun and the Moon, the Moon's argument of latitude and the
    // longitude of the ascending node of the Moon's mean orbit.
    let x = [
        cubic(297.85036, 445_267.111480, -0.0019142, 189_474.0),
        cubic(357.52772, 35_999.050340, -0.0001603, -300_000.0),
        cubic(134.96298, 477_198.867398, 0.0086972, 56_250.0),
        cubic(93.27191, 483_202.017538, -0.0036825, 327_270.0),
        cubic(125.04452, -1_934.136261, 0.0020708, 450_000.0),
    ];
    let (mut psi, mut epsilon) = (0.0, 0.0);
    for (y, [a, b, c, d]) in TERMS {
        let argument: f64 = x.iter().zip(y).map(|(x, y)| x * f64::from(y)).sum();
        let (sin, cos) = argument.to_radians().sin_cos();
        psi += (a + b * t) * sin;
        epsilon += (c + d * t) * cos;
    }
    // 0.0001″ to degrees.
    (psi / 36_000_000.0, epsilon / 36_000_000.0)
}

/// The true obliquity of the ecliptic ε, in degrees, at `jme` Julian ephemeris millennia
/// from J2000.0 with the nutation in obliquity `delta_epsilon` (degrees): Laskar's mean
/// obliquity (a polynomial in `jme / 10`, for ten thousand years either side of J2000.0)
/// plus Δε.
pub(super) fn true_obliquity(jme: f64, delta_epsilon: f64) -> f64 {
    const ARCSECONDS: [f64; 11] = [
        84_381.448, -4_680.93, -1.55, 1_999.25, -51.38, -249.67, -39.05, 7.12, 27.87, 5.79, 2.45,
    ];
    let u = jme / 10.0;
    let mean = ARCSECONDS.iter().rev().fold(0.0, |acc, c| acc * u + c);
    mean / 3600.0 + delta_epsilon
}
