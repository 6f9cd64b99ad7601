//! The Julian day of a civil date and time, and the Julian centuries and millennia the
//! series of the Solar Position Algorithm take (Reda & Andreas, §3.1).

/// The Julian day J2000.0 (2000-01-01 12:00 TT).
pub(super) const J2000: f64 = 2_451_545.0;

/// The Julian day of `day` (with its fraction) of `month` of `year`, the Gregorian calendar
/// from 1582-10-15 on and the Julian calendar before (Reda & Andreas, eq. 4). The day's
/// fraction is in whichever time scale the caller means (UT1 for the Julian day, TT for the
/// Julian ephemeris day).
pub(super) fn julian_day(year: i32, month: u32, day: f64) -> f64 {
    let (y, m) = if month <= 2 {
        (f64::from(year) - 1.0, f64::from(month) + 12.0)
    } else {
        (f64::from(year), f64::from(month))
    };
    // INT of the paper is truncation toward zero.
    let jd = (365.25 * (y + 4716.0)).trunc() + (30.6001 * (m + 1.0)).trunc() + day - 1524.5;
    if jd > 2_299_160.0 {
        let a = (y / 100.0).trunc();
        jd + 2.0 - a + (a / 4.0).trunc()
    } else {
        jd
    }
}

/// Julian centuries of 36 525 days from J2000.0 to the Julian day `jd`.
pub(super) fn centuries(jd: f64) -> f64 {
    (jd - J2000) / 36_525.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn julian_days_of_the_papers_examples() {
        // Reda & Andreas, Table 4.
        let close = |jd: f64, expected: f64| assert!((jd - expected).abs() < 1e-6, "{jd}");
        close(julian_day(2000, 1, 1.5), 2_451_545.0);
        close(julian_day(1999, 1, 1.0), 2_451_179.5);
        close(julian_day(1987, 1, 27.0), 2_446_822.5);
        close(julian_day(1987, 6, 19.5), 2_446_966.0);
        close(julian_day(1988, 1, 27.0), 2_447_187.5);
        close(julian_day(1988, 6, 19.5), 2_447_332.0);
        close(julian_day(1900, 1, 1.0), 2_415_020.5);
        close(julian_day(1600, 1, 1.0), 2_305_447.5);
        close(julian_day(1600, 12, 31.0), 2_305_812.5);
        close(julian_day(837, 4, 10.3), 2_026_871.8);
        close(julian_day(-123, 12, 31.0), 1_676_496.5);
        close(julian_day(-122, 1, 1.0), 1_676_497.5);
        close(julian_day(-1000, 7, 12.5), 1_356_001.0);
        close(julian_day(-1000, 2, 29.0), 1_355_866.5);
        close(julian_day(-1001, 8, 17.9), 1_355_671.4);
        close(julian_day(-4712, 1, 1.5), 0.0);
        assert_eq!(centuries(J2000 + 36_525.0), 1.0);
    }
}
