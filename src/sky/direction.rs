//! Between a (zenith, azimuth) pair and a direction in strahl's world frame: y up, −z north,
//! +x east.

use glam::DVec3;

/// The unit direction of zenith angle `zenith_deg` (from straight up, +y) and azimuth
/// `azimuth_deg` (clockwise seen from above: from north, −z, toward east, +x), both in
/// degrees: `(sin Z·sin A, cos Z, −sin Z·cos A)`. The sun's [`SunPosition`](super::SunPosition)
/// and the CIE skies use these angles; zenith 0 is +y, azimuth 0 is −z, azimuth 90° is +x.
pub fn direction_from_angles(zenith_deg: f64, azimuth_deg: f64) -> DVec3 {
    let (sin_z, cos_z) = zenith_deg.to_radians().sin_cos();
    let (sin_a, cos_a) = azimuth_deg.to_radians().sin_cos();
    DVec3::new(sin_z * sin_a, cos_z, -sin_z * cos_a)
}

/// The zenith angle in `[0°, 180°]` and the azimuth in `[0°, 360°)` (clockwise from north,
/// −z, toward east, +x) of a unit direction: the inverse of [`direction_from_angles`]. The
/// azimuth of straight up or down is 0.
pub fn angles_from_direction(direction: DVec3) -> (f64, f64) {
    let horizontal = direction.x.hypot(direction.z);
    let zenith = horizontal.atan2(direction.y).to_degrees();
    if horizontal == 0.0 {
        return (zenith, 0.0);
    }
    let azimuth = direction
        .x
        .atan2(-direction.z)
        .to_degrees()
        .rem_euclid(360.0);
    // rem_euclid may round a tiny negative angle up to 360 itself.
    (zenith, if azimuth >= 360.0 { 0.0 } else { azimuth })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn north_is_minus_z_east_is_plus_x_up_is_plus_y() {
        let close = |a: DVec3, b: DVec3| (a - b).length() < 1e-15;
        assert!(close(direction_from_angles(0.0, 123.0), DVec3::Y));
        assert!(close(direction_from_angles(90.0, 0.0), DVec3::NEG_Z));
        assert!(close(direction_from_angles(90.0, 90.0), DVec3::X));
        assert!(close(direction_from_angles(90.0, 180.0), DVec3::Z));
        assert!(close(direction_from_angles(90.0, 270.0), DVec3::NEG_X));
        // The frame is right-handed: east × up = south (+z).
        assert!(close(DVec3::X.cross(DVec3::Y), DVec3::Z));
    }

    #[test]
    fn angles_and_direction_are_inverse() {
        for zenith in [1.0, 30.0, 50.11162, 89.9, 120.0] {
            for azimuth in [0.0, 10.0, 194.34024, 359.5] {
                let d = direction_from_angles(zenith, azimuth);
                assert!((d.length() - 1.0).abs() < 1e-15);
                let (z, a) = angles_from_direction(d);
                assert!((z - zenith).abs() < 1e-12, "{z} {zenith}");
                assert!((a - azimuth).abs() < 1e-12, "{a} {azimuth}");
            }
        }
        assert_eq!(angles_from_direction(DVec3::Y), (0.0, 0.0));
    }
}
