//! The Sun's position in the sky of an observer at a date and time: NREL's Solar Position
//! Algorithm (I. Reda and A. Andreas, "Solar position algorithm for solar radiation
//! applications", Solar Energy 76 (2004) 577–589; NREL/TP-560-34302, revised 2008),
//! written from the published algorithm and its tables. Its uncertainty is ±0.0003° for
//! the years −2000 to 6000 given the right ΔT; this implementation reproduces the paper's
//! example to within 10⁻⁵° (the tests below).

mod earth;
mod earth_terms;
mod nutation;
mod nutation_terms;
mod observer;
mod time;

use glam::DVec3;

use super::direction::direction_from_angles;

/// The total solar irradiance at one astronomical unit, W·m⁻² (Kopp & Lean 2011, the value
/// IAU 2015 Resolution B3 adopts as nominal).
pub const SOLAR_CONSTANT: f64 = 1361.0;

/// A date and time as a civil clock shows it, with what turns that clock's time into the
/// two time scales the algorithm needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalTime {
    /// Year (astronomical numbering: 0 is 1 BC); the algorithm holds for −2000 to 6000.
    pub year: i32,
    /// Month, 1 to 12.
    pub month: u32,
    /// Day of the month, from 1.
    pub day: u32,
    /// Hour, 0 to 23, on the clock of `utc_offset_hours`.
    pub hour: u32,
    /// Minute, 0 to 59.
    pub minute: u32,
    /// Seconds, with their fraction.
    pub second: f64,
    /// The clock's offset from UTC in hours, positive east of Greenwich (−7 for US Mountain
    /// Standard Time, +1 for Central European Time).
    pub utc_offset_hours: f64,
    /// UT1 − UTC in seconds (|ΔUT1| < 0.9 s; the IERS Bulletin A gives it, 0 is the usual
    /// choice: one second of time is 0.004° of the Sun's hour angle).
    pub delta_ut1_s: f64,
    /// ΔT = TT − UT1 in seconds, the difference between the Earth's rotation time and
    /// terrestrial time (64 s in 2000, 69 s from 2017 to 2025; the IERS and USNO publish it).
    pub delta_t_s: f64,
}

impl LocalTime {
    /// The Julian day (UT1) of this time.
    fn julian_day(&self) -> f64 {
        let hours = f64::from(self.hour) - self.utc_offset_hours
            + (f64::from(self.minute) + (self.second + self.delta_ut1_s) / 60.0) / 60.0;
        time::julian_day(self.year, self.month, f64::from(self.day) + hours / 24.0)
    }
}

/// ΔT = TT − UT1, seconds, to assume when none is given (its value from 2017 to 2025).
pub const DEFAULT_DELTA_T_S: f64 = 69.0;
/// Air pressure to assume when none is given, millibars (the standard atmosphere).
pub const STANDARD_PRESSURE_MBAR: f64 = 1013.25;
/// Air temperature to assume when none is given, °C (the standard atmosphere).
pub const STANDARD_TEMPERATURE_C: f64 = 15.0;
/// Atmospheric refraction at sunrise and sunset, degrees (NREL's usual value).
pub const SUNRISE_REFRACTION_DEG: f64 = 0.5667;

/// Where the Sun is seen from, and the air it is seen through.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Observer {
    /// Geodetic latitude in degrees, positive north.
    pub latitude_deg: f64,
    /// Longitude in degrees, positive east of Greenwich.
    pub longitude_deg: f64,
    /// Elevation above mean sea level, metres.
    pub elevation_m: f64,
    /// Mean annual local pressure, millibars (hPa), for atmospheric refraction.
    pub pressure_mbar: f64,
    /// Mean annual local temperature, °C, for atmospheric refraction.
    pub temperature_c: f64,
    /// Atmospheric refraction at sunrise and sunset, degrees (0.5667 is typical): refraction
    /// is applied while the Sun's centre is above `−(0.26667° + refraction_deg)`.
    pub refraction_deg: f64,
}

/// The Sun as an observer sees it (topocentric, with atmospheric refraction).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunPosition {
    /// Topocentric zenith angle of the Sun's centre, degrees from straight up (above 90 when
    /// the Sun is below the horizon).
    pub zenith_deg: f64,
    /// Topocentric azimuth, degrees in `[0, 360)` clockwise from north (90 is east).
    pub azimuth_deg: f64,
    /// Geocentric declination of the Sun, degrees.
    pub declination_deg: f64,
    /// Earth–Sun distance (the Earth's heliocentric radius vector), astronomical units.
    pub distance_au: f64,
}

impl SunPosition {
    /// The unit direction toward the Sun in strahl's world frame: y up, −z north, +x east
    /// ([`direction_from_angles`](super::direction_from_angles) of the zenith and azimuth).
    pub fn direction(&self) -> DVec3 {
        direction_from_angles(self.zenith_deg, self.azimuth_deg)
    }

    /// The extraterrestrial irradiance on a plane normal to the Sun's rays at this Earth–Sun
    /// distance, W·m⁻²: [`SOLAR_CONSTANT`] / R².
    pub fn extraterrestrial_irradiance(&self) -> f64 {
        SOLAR_CONSTANT / (self.distance_au * self.distance_au)
    }

    /// The angle of incidence of the Sun's rays on a surface, degrees (Reda & Andreas,
    /// §3.16): `slope_deg` from the horizontal, its downhill side facing
    /// `azimuth_rotation_deg` measured from south, positive toward west (0 faces south, −90
    /// faces east).
    pub fn incidence_deg(&self, slope_deg: f64, azimuth_rotation_deg: f64) -> f64 {
        let (zenith, slope) = (self.zenith_deg.to_radians(), slope_deg.to_radians());
        let astronomers_azimuth = self.azimuth_deg - 180.0;
        let relative = (astronomers_azimuth - azimuth_rotation_deg).to_radians();
        (zenith.cos() * slope.cos() + slope.sin() * zenith.sin() * relative.cos())
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    }
}

/// The Sun's position for `observer` at `time` by NREL's Solar Position Algorithm.
pub fn sun_position(time: &LocalTime, observer: &Observer) -> SunPosition {
    let jd = time.julian_day();
    let jde = jd + time.delta_t_s / 86_400.0;
    let (jc, jce) = (time::centuries(jd), time::centuries(jde));
    let jme = jce / 10.0;
    let (l, b, r) = earth::heliocentric(jme);
    let (theta, beta) = earth::geocentric(l, b);
    let (delta_psi, delta_epsilon) = nutation::nutation(jce);
    let epsilon = nutation::true_obliquity(jme, delta_epsilon);
    // The apparent longitude: nutation and the aberration of light.
    let lambda = theta + delta_psi - 20.4898 / (3600.0 * r);
    let nu = mean_sidereal_time(jd, jc) + delta_psi * epsilon.to_radians().cos();
    let (alpha, delta) = equatorial(lambda, epsilon, beta);
    let h = (nu + observer.longitude_deg - alpha).rem_euclid(360.0);
    let (delta_prime, h_prime) =
        observer::topocentric(delta, h, r, observer.latitude_deg, observer.elevation_m);
    let (zenith_deg, azimuth_deg) = observer::horizon(
        delta_prime,
        h_prime,
        observer.latitude_deg,
        observer.pressure_mbar,
        observer.temperature_c,
        observer.refraction_deg,
    );
    SunPosition {
        zenith_deg,
        azimuth_deg,
        declination_deg: delta,
        distance_au: r,
    }
}

/// The mean sidereal time at Greenwich, degrees in `[0, 360)`, at Julian day `jd` (UT1),
/// `jc` Julian centuries from J2000.0.
fn mean_sidereal_time(jd: f64, jc: f64) -> f64 {
    (280.460_618_37 + 360.985_647_366_29 * (jd - time::J2000) + 0.000_387_933 * jc * jc
        - jc * jc * jc / 38_710_000.0)
        .rem_euclid(360.0)
}

/// The geocentric right ascension α (degrees, in `[0, 360)`) and declination δ (degrees) of
/// apparent ecliptic longitude `lambda` and latitude `beta` with obliquity `epsilon`
/// (degrees).
fn equatorial(lambda: f64, epsilon: f64, beta: f64) -> (f64, f64) {
    let (lambda, epsilon, beta) = (lambda.to_radians(), epsilon.to_radians(), beta.to_radians());
    let alpha = (lambda.sin() * epsilon.cos() - beta.tan() * epsilon.sin()).atan2(lambda.cos());
    let delta = (beta.sin() * epsilon.cos() + beta.cos() * epsilon.sin() * lambda.sin()).asin();
    (alpha.to_degrees().rem_euclid(360.0), delta.to_degrees())
}

#[cfg(test)]
mod tests;
