//! The Solar Position Algorithm against the example of Reda & Andreas (Table A5.1: every
//! intermediate value the paper prints) and against independent published figures (the
//! instants of equinoxes and solstices, the Earth's perihelion and aphelion distances).

use super::*;

/// The paper's example: 2003-10-17 12:30:30 at UTC−7, Golden, Colorado.
const TIME: LocalTime = LocalTime {
    year: 2003,
    month: 10,
    day: 17,
    hour: 12,
    minute: 30,
    second: 30.0,
    utc_offset_hours: -7.0,
    delta_ut1_s: 0.0,
    delta_t_s: 67.0,
};

const OBSERVER: Observer = Observer {
    latitude_deg: 39.742476,
    longitude_deg: -105.1786,
    elevation_m: 1830.14,
    pressure_mbar: 820.0,
    temperature_c: 11.0,
    refraction_deg: 0.5667,
};

fn close(value: f64, expected: f64, tolerance: f64, what: &str) {
    assert!(
        (value - expected).abs() <= tolerance,
        "{what}: {value} against {expected} (off by {:e})",
        (value - expected).abs()
    );
}

#[test]
fn the_papers_example_topocentric_zenith_and_azimuth() {
    let sun = sun_position(&TIME, &OBSERVER);
    // The paper prints five decimals; the issue asks for 0.001°.
    close(sun.zenith_deg, 50.11162, 1e-5, "topocentric zenith angle");
    close(sun.azimuth_deg, 194.34024, 1e-5, "topocentric azimuth");
    close(
        sun.declination_deg,
        -9.31434,
        1e-5,
        "geocentric declination",
    );
    close(sun.distance_au, 0.9965422974, 1e-10, "Earth radius vector");
    close(
        sun.incidence_deg(30.0, -10.0),
        25.18700,
        1e-5,
        "surface incidence",
    );
}

#[test]
fn the_papers_example_step_by_step() {
    let jd = TIME.julian_day();
    close(jd, 2_452_930.312847, 5e-7, "Julian day");
    let jde = jd + TIME.delta_t_s / 86_400.0;
    let (jc, jce) = (time::centuries(jd), time::centuries(jde));
    close(jc, 0.0379277986, 1e-10, "Julian century");
    close(jce, 0.0379278200, 1e-10, "Julian ephemeris century");
    let jme = jce / 10.0;
    let (l, b, r) = earth::heliocentric(jme);
    close(l, 24.0182616917, 1e-9, "heliocentric longitude");
    close(b, -0.0001011219, 1e-10, "heliocentric latitude");
    close(r, 0.9965422974, 1e-10, "radius vector");
    let (theta, beta) = earth::geocentric(l, b);
    close(theta, 204.0182616917, 1e-9, "geocentric longitude");
    close(beta, 0.0001011219, 1e-10, "geocentric latitude");
    let (delta_psi, delta_epsilon) = nutation::nutation(jce);
    close(delta_psi, -0.00399840, 1e-8, "nutation in longitude");
    close(delta_epsilon, 0.00166657, 1e-8, "nutation in obliquity");
    let epsilon = nutation::true_obliquity(jme, delta_epsilon);
    close(epsilon, 23.440465, 1e-6, "true obliquity");
    let lambda = theta + delta_psi - 20.4898 / (3600.0 * r);
    close(lambda, 204.0085519281, 1e-9, "apparent longitude");
    let nu = mean_sidereal_time(jd, jc) + delta_psi * epsilon.to_radians().cos();
    close(nu, 318.5119, 1e-3, "apparent sidereal time");
    let (alpha, delta) = equatorial(lambda, epsilon, beta);
    close(alpha, 202.22741, 1e-5, "geocentric right ascension");
    close(delta, -9.31434, 1e-5, "geocentric declination");
    let h = (nu + OBSERVER.longitude_deg - alpha).rem_euclid(360.0);
    close(h, 11.105900, 1e-5, "local hour angle");
    let (delta_prime, h_prime) =
        observer::topocentric(delta, h, r, OBSERVER.latitude_deg, OBSERVER.elevation_m);
    close(delta_prime, -9.316179, 1e-6, "topocentric declination");
    // The topocentric hour angle H′ enters the zenith angle and azimuth checked above.
    assert!((h_prime - h).abs() < 0.001, "parallax in hour angle");
}

/// A UTC instant anywhere (the declination does not depend on the place).
fn declination_at_utc(year: i32, month: u32, day: u32, hour: u32, minute: u32) -> f64 {
    let time = LocalTime {
        year,
        month,
        day,
        hour,
        minute,
        second: 0.0,
        utc_offset_hours: 0.0,
        delta_ut1_s: 0.0,
        delta_t_s: 69.4,
    };
    sun_position(&time, &OBSERVER).declination_deg
}

#[test]
fn declination_is_zero_at_the_equinoxes_and_the_obliquity_at_the_solstices() {
    // The 2020 equinoxes and solstices to the minute (US Naval Observatory). Near an
    // equinox the declination moves 0.4° a day, 0.0003° a minute.
    close(
        declination_at_utc(2020, 3, 20, 3, 50),
        0.0,
        0.001,
        "March equinox",
    );
    close(
        declination_at_utc(2020, 9, 22, 13, 31),
        0.0,
        0.001,
        "September equinox",
    );
    // At a solstice |δ| is the obliquity of the ecliptic, 23.4366° in 2020 (IAU 2006 mean
    // obliquity 23°26′11.6″), give or take the nutation (< 0.003°).
    close(
        declination_at_utc(2020, 6, 20, 21, 44),
        23.4366,
        0.004,
        "June solstice",
    );
    close(
        declination_at_utc(2020, 12, 21, 10, 2),
        -23.4366,
        0.004,
        "December solstice",
    );
}

#[test]
fn the_earth_sun_distance_at_perihelion_and_aphelion() {
    let distance = |month, day, hour, minute| {
        let time = LocalTime {
            year: 2020,
            month,
            day,
            hour,
            minute,
            second: 0.0,
            utc_offset_hours: 0.0,
            delta_ut1_s: 0.0,
            delta_t_s: 69.4,
        };
        sun_position(&time, &OBSERVER)
    };
    // 2020: perihelion 5 January 07:48 UTC at 147 091 144 km, aphelion 4 July 11:35 UTC at
    // 152 095 295 km; 1 AU = 149 597 870.7 km.
    let au = 149_597_870.7;
    let perihelion = distance(1, 5, 7, 48);
    close(
        perihelion.distance_au,
        147_091_144.0 / au,
        2e-5,
        "perihelion",
    );
    let aphelion = distance(7, 4, 11, 35);
    close(aphelion.distance_au, 152_095_295.0 / au, 2e-5, "aphelion");
    // The extraterrestrial irradiance swings ±3.3 % about the solar constant.
    close(
        perihelion.extraterrestrial_irradiance(),
        1361.0 * 1.0344,
        1.0,
        "E0 at perihelion",
    );
    close(
        aphelion.extraterrestrial_irradiance(),
        1361.0 * 0.9674,
        1.0,
        "E0 at aphelion",
    );
}

#[test]
fn the_direction_points_at_the_sun_in_the_world_frame() {
    let sun = sun_position(&TIME, &OBSERVER);
    let d = sun.direction();
    assert!((d.length() - 1.0).abs() < 1e-15);
    close(
        d.y,
        sun.zenith_deg.to_radians().cos(),
        1e-15,
        "up component",
    );
    // An October afternoon in Colorado: the Sun is south (+z) and a little west (−x).
    assert!(d.z > 0.0 && d.x < 0.0 && d.y > 0.0, "{d}");
    // A surface facing the Sun sees it at normal incidence.
    close(
        sun.incidence_deg(sun.zenith_deg, sun.azimuth_deg - 180.0),
        0.0,
        1e-6,
        "facing",
    );
}
