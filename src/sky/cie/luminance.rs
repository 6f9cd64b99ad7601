//! The relative luminance of a sky element: its luminance over the zenith's.

use glam::DVec3;

use super::parameters::{CieParameters, CieSkyType};

impl CieParameters {
    /// The luminance of the sky element in the unit direction `direction` over the luminance
    /// of the zenith, `L(χ, Z) / L_z = f(χ)·φ(Z) / (f(Z_s)·φ(0))`, for the Sun in the unit
    /// direction `sun` (both pointing away from the observer, y up). Z is the element's
    /// zenith angle, Z_s the Sun's, χ the angle between element and Sun. 0 below the horizon
    /// (y < 0): the sky is the upper hemisphere. The standard defines the skies for the Sun
    /// above the horizon; for a Sun below it the formula is evaluated as written.
    pub fn relative_luminance(&self, sun: DVec3, direction: DVec3) -> f64 {
        debug_assert!(
            (sun.length() - 1.0).abs() < 1e-6,
            "sun direction {sun} not unit"
        );
        debug_assert!(
            (direction.length() - 1.0).abs() < 1e-6,
            "sky direction {direction} not unit"
        );
        if direction.y < 0.0 {
            return 0.0;
        }
        let chi = angle_between(sun, direction);
        let sun_zenith = angle_between(sun, DVec3::Y);
        self.indicatrix(chi) * self.gradation(direction.y)
            / (self.indicatrix(sun_zenith) * self.gradation(1.0))
    }
}

/// The relative luminance `L / L_z` of the sky element in the unit direction `direction`
/// for CIE sky type `sky` and the Sun in the unit direction `sun` (both pointing away from
/// the observer, y up): [`CieParameters::relative_luminance`] with the type's parameters. It
/// is 1 at the zenith and 0 below the horizon.
pub fn relative_luminance(sky: CieSkyType, sun: DVec3, direction: DVec3) -> f64 {
    sky.parameters().relative_luminance(sun, direction)
}

/// The angle between two unit vectors, radians, accurate near 0 and π (unlike `acos`).
fn angle_between(u: DVec3, v: DVec3) -> f64 {
    u.cross(v).length().atan2(u.dot(v))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sky::direction_from_angles;

    #[test]
    fn one_at_the_zenith_and_zero_below_the_horizon() {
        for sky in CieSkyType::ALL {
            for (zenith, azimuth) in [(0.0, 0.0), (35.0, 120.0), (80.0, 300.0)] {
                let sun = direction_from_angles(zenith, azimuth);
                let at_zenith = relative_luminance(sky, sun, DVec3::Y);
                assert!((at_zenith - 1.0).abs() < 1e-14, "{sky:?}: {at_zenith}");
                let below = direction_from_angles(91.0, 10.0);
                assert_eq!(relative_luminance(sky, sun, below), 0.0);
                let horizon = relative_luminance(sky, sun, direction_from_angles(90.0, 10.0));
                assert!(horizon.is_finite() && horizon > 0.0, "{sky:?}: {horizon}");
            }
        }
    }

    #[test]
    fn symmetric_about_the_suns_vertical_plane() {
        let sun_azimuth = 140.0;
        let sun = direction_from_angles(40.0, sun_azimuth);
        for sky in CieSkyType::ALL {
            for zenith in [5.0, 30.0, 60.0, 89.0] {
                for offset in [3.0, 45.0, 100.0, 179.0] {
                    let left = direction_from_angles(zenith, sun_azimuth - offset);
                    let right = direction_from_angles(zenith, sun_azimuth + offset);
                    let (l, r) = (
                        relative_luminance(sky, sun, left),
                        relative_luminance(sky, sun, right),
                    );
                    assert!((l - r).abs() <= 1e-13 * l, "{sky:?}: {l} {r}");
                }
            }
        }
    }

    #[test]
    fn azimuthally_uniform_types_depend_on_the_zenith_angle_alone() {
        // Types 1, 3 and 5 have c = e = 0: f ≡ 1, whatever the Sun.
        let sun = direction_from_angles(50.0, 200.0);
        for sky in [
            CieSkyType::OvercastSteep,
            CieSkyType::OvercastModerate,
            CieSkyType::Uniform,
        ] {
            let p = sky.parameters();
            for zenith in [10.0f64, 45.0, 85.0] {
                let expected = p.gradation(zenith.to_radians().cos()) / p.gradation(1.0);
                for azimuth in [0.0, 77.0, 200.0, 311.0] {
                    let l = relative_luminance(sky, sun, direction_from_angles(zenith, azimuth));
                    assert!((l - expected).abs() < 1e-14, "{sky:?} {zenith} {azimuth}");
                }
            }
        }
        // The uniform sky is 1 everywhere above the horizon.
        let l = relative_luminance(CieSkyType::Uniform, sun, direction_from_angles(70.0, 5.0));
        assert!((l - 1.0).abs() < 1e-15);
    }

    #[test]
    fn hand_computed_and_published_values() {
        // colour-science's examples: element Z = 45°, azimuth 180°; Sun Z = 30°, azimuth 0
        // (so χ = 75°).
        let sun = direction_from_angles(30.0, 0.0);
        let element = direction_from_angles(45.0, 180.0);
        let l1 = relative_luminance(CieSkyType::OvercastSteep, sun, element);
        assert!((l1 - 0.832_584_6).abs() < 1e-7, "{l1}");
        let l12 = relative_luminance(CieSkyType::ClearLowTurbidity, sun, element);
        assert!((l12 - 0.454_452_4).abs() < 1e-7, "{l12}");
        // By hand for type 12 (a = −1, b = −0.32, c = 10, d = −3, e = 0.45):
        // φ(45°) = 1 − e^(−0.32·√2), φ(0) = 1 − e^−0.32, f(75°) and f(30°) from the formula.
        let f = |chi: f64| {
            let chi = chi.to_radians();
            1.0 + 10.0 * ((-3.0 * chi).exp() - (-1.5 * std::f64::consts::PI).exp())
                + 0.45 * chi.cos().powi(2)
        };
        let phi = |z: f64| 1.0 - (-0.32 / z.to_radians().cos()).exp();
        let by_hand = f(75.0) * phi(45.0) / (f(30.0) * phi(0.0));
        assert!((l12 - by_hand).abs() < 1e-14, "{l12} {by_hand}");
        // Toward the Sun itself the clear sky is brightest.
        let at_sun = relative_luminance(CieSkyType::ClearLowTurbidity, sun, sun);
        let beside = direction_from_angles(30.0, 10.0);
        assert!(at_sun > relative_luminance(CieSkyType::ClearLowTurbidity, sun, beside));
    }
}
