//! From the Sun's geocentric equatorial position to what an observer on the ground sees:
//! parallax (Reda & Andreas, §3.12–3.13), elevation with atmospheric refraction (§3.14) and
//! azimuth (§3.15).

/// The Earth's equatorial radius in metres, as the algorithm takes it.
const EARTH_RADIUS_M: f64 = 6_378_140.0;
/// The Earth's polar radius over its equatorial radius.
const POLAR_RATIO: f64 = 0.996_647_19;
/// The Sun's angular radius, degrees: with the refraction at the horizon, how far below the
/// horizon the Sun's centre may be while its upper limb still shows (refraction applies).
const SUN_RADIUS_DEG: f64 = 0.26667;

/// The topocentric declination δ′ and local hour angle H′ (degrees) of the Sun of
/// geocentric declination `delta` and local hour angle `h` (degrees) at Earth–Sun distance
/// `r` (AU), seen by an observer at geodetic latitude `latitude` (degrees) and `elevation`
/// metres above sea level.
pub(super) fn topocentric(delta: f64, h: f64, r: f64, latitude: f64, elevation: f64) -> (f64, f64) {
    // The equatorial horizontal parallax of the Sun.
    let xi = (8.794 / (3600.0 * r)).to_radians();
    let phi = latitude.to_radians();
    let u = (POLAR_RATIO * phi.tan()).atan();
    let x = u.cos() + elevation / EARTH_RADIUS_M * phi.cos();
    let y = POLAR_RATIO * u.sin() + elevation / EARTH_RADIUS_M * phi.sin();
    let (delta, h) = (delta.to_radians(), h.to_radians());
    let denominator = delta.cos() - x * xi.sin() * h.cos();
    // The parallax in right ascension.
    let delta_alpha = (-x * xi.sin() * h.sin()).atan2(denominator);
    let delta_prime = ((delta.sin() - y * xi.sin()) * delta_alpha.cos()).atan2(denominator);
    (delta_prime.to_degrees(), (h - delta_alpha).to_degrees())
}

/// The topocentric zenith angle and azimuth (degrees; azimuth in `[0, 360)` clockwise from
/// north) of the Sun of topocentric declination `delta` and local hour angle `h` (degrees)
/// at latitude `latitude` (degrees), with the refraction of an atmosphere of `pressure_mbar`
/// and `temperature_c` while the Sun is above `−(0.26667° + refraction_deg)` of elevation.
pub(super) fn horizon(
    delta: f64,
    h: f64,
    latitude: f64,
    pressure_mbar: f64,
    temperature_c: f64,
    refraction_deg: f64,
) -> (f64, f64) {
    let (phi, delta, h) = (latitude.to_radians(), delta.to_radians(), h.to_radians());
    let e0 = (phi.sin() * delta.sin() + phi.cos() * delta.cos() * h.cos())
        .asin()
        .to_degrees();
    let refraction = if e0 >= -(SUN_RADIUS_DEG + refraction_deg) {
        (pressure_mbar / 1010.0) * (283.0 / (273.0 + temperature_c)) * 1.02
            / (60.0 * (e0 + 10.3 / (e0 + 5.11)).to_radians().tan())
    } else {
        0.0
    };
    let zenith = 90.0 - (e0 + refraction);
    // The astronomers' azimuth, westward from south, turned into the navigators' one.
    let gamma = h.sin().atan2(h.cos() * phi.sin() - delta.tan() * phi.cos());
    let azimuth = (gamma.to_degrees() + 180.0).rem_euclid(360.0);
    (zenith, azimuth)
}
