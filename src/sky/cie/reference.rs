//! strahl's CIE skies against the table `reference.csv` of a second implementation: a
//! transcription of the standard's formulas in Python, which `scripts/check-cie-sky.py`
//! writes and checks against `colour-science` where that package is installed.

use super::{CieSkyType, relative_luminance};
use crate::sky::direction_from_angles;

#[test]
fn relative_luminance_matches_the_second_implementation() {
    let table = include_str!("reference.csv");
    let mut rows = 0;
    for line in table.lines().skip(1) {
        let fields: Vec<f64> = line.split(',').map(|f| f.parse().unwrap()).collect();
        let [sky, sun_zenith, sun_azimuth, zenith, azimuth, expected] = fields[..] else {
            panic!("malformed row {line}");
        };
        let sky = CieSkyType::from_number(sky as u8).unwrap();
        let sun = direction_from_angles(sun_zenith, sun_azimuth);
        let value = relative_luminance(sky, sun, direction_from_angles(zenith, azimuth));
        assert!(
            (value - expected).abs() <= 1e-12 * expected,
            "{line}: strahl gives {value}"
        );
        rows += 1;
    }
    // 15 types × 4 Sun positions × 20 sky elements.
    assert_eq!(rows, 1200);
}
