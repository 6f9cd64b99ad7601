//! The 15 sky types of the CIE standard general sky and their parameters.

/// The parameters of a CIE general sky: the gradation `φ(Z) = 1 + a·exp(b / cos Z)` (1 at
/// the horizon) and the indicatrix `f(χ) = 1 + c·(exp(d·χ) − exp(d·π/2)) + e·cos²χ`, Z the
/// zenith angle of a sky element and χ its angle from the Sun, both in radians. Any set of
/// numbers may be given (a fitted sky, say); [`CieSkyType::parameters`] gives the standard's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CieParameters {
    /// Gradation parameter a.
    pub a: f64,
    /// Gradation parameter b (negative).
    pub b: f64,
    /// Indicatrix parameter c.
    pub c: f64,
    /// Indicatrix parameter d (negative).
    pub d: f64,
    /// Indicatrix parameter e.
    pub e: f64,
}

impl CieParameters {
    /// The gradation φ at an element whose zenith angle has cosine `cos_zenith` (0 at the
    /// horizon, where φ = 1, to 1 at the zenith).
    pub fn gradation(&self, cos_zenith: f64) -> f64 {
        if cos_zenith <= 0.0 {
            return 1.0;
        }
        1.0 + self.a * (self.b / cos_zenith).exp()
    }

    /// The scattering indicatrix f at an angular distance `chi` (radians) from the Sun.
    pub fn indicatrix(&self, chi: f64) -> f64 {
        let cos = chi.cos();
        1.0 + self.c * ((self.d * chi).exp() - (self.d * std::f64::consts::FRAC_PI_2).exp())
            + self.e * cos * cos
    }
}

/// The 15 sky types of CIE S 011/E:2003 (ISO 15469:2004), Table 1, numbered 1 to 15 by
/// their discriminants.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CieSkyType {
    /// 1: CIE standard overcast sky, steep luminance gradation toward the zenith, azimuthal
    /// uniformity.
    OvercastSteep = 1,
    /// 2: overcast, steep luminance gradation and slight brightening toward the Sun.
    OvercastSteepBrighterTowardSun = 2,
    /// 3: overcast, moderately graded, azimuthal uniformity.
    OvercastModerate = 3,
    /// 4: overcast, moderately graded and slight brightening toward the Sun.
    OvercastModerateBrighterTowardSun = 4,
    /// 5: sky of uniform luminance.
    Uniform = 5,
    /// 6: partly cloudy, no gradation toward the zenith, slight brightening toward the Sun.
    PartlyCloudyBrighterTowardSun = 6,
    /// 7: partly cloudy, no gradation toward the zenith, brighter circumsolar region.
    PartlyCloudyCircumsolar = 7,
    /// 8: partly cloudy, no gradation toward the zenith, distinct solar corona.
    PartlyCloudyCorona = 8,
    /// 9: partly cloudy, the Sun obscured.
    PartlyCloudyObscuredSun = 9,
    /// 10: partly cloudy, brighter circumsolar region.
    PartlyCloudyGradedCircumsolar = 10,
    /// 11: white-blue sky with a distinct solar corona.
    WhiteBlueCorona = 11,
    /// 12: CIE standard clear sky, low luminance turbidity.
    ClearLowTurbidity = 12,
    /// 13: CIE standard clear sky, polluted atmosphere.
    ClearPolluted = 13,
    /// 14: cloudless turbid sky with a broad solar corona.
    TurbidBroadCorona = 14,
    /// 15: white-blue turbid sky with a broad solar corona.
    WhiteBlueTurbidBroadCorona = 15,
}

/// The six gradation groups I–VI of the standard's Table 1, `(a, b)`.
const GRADATIONS: [(f64, f64); 6] = [
    (4.0, -0.70),
    (1.1, -0.8),
    (0.0, -1.0),
    (-1.0, -0.55),
    (-1.0, -0.32),
    (-1.0, -0.15),
];

/// The six indicatrix groups 1–6 of the standard's Table 1, `(c, d, e)`.
const INDICATRICES: [(f64, f64, f64); 6] = [
    (0.0, -1.0, 0.0),
    (2.0, -1.5, 0.15),
    (5.0, -2.5, 0.30),
    (10.0, -3.0, 0.45),
    (16.0, -3.0, 0.30),
    (24.0, -2.8, 0.15),
];

impl CieSkyType {
    /// All 15 types, in the standard's order.
    pub const ALL: [CieSkyType; 15] = [
        CieSkyType::OvercastSteep,
        CieSkyType::OvercastSteepBrighterTowardSun,
        CieSkyType::OvercastModerate,
        CieSkyType::OvercastModerateBrighterTowardSun,
        CieSkyType::Uniform,
        CieSkyType::PartlyCloudyBrighterTowardSun,
        CieSkyType::PartlyCloudyCircumsolar,
        CieSkyType::PartlyCloudyCorona,
        CieSkyType::PartlyCloudyObscuredSun,
        CieSkyType::PartlyCloudyGradedCircumsolar,
        CieSkyType::WhiteBlueCorona,
        CieSkyType::ClearLowTurbidity,
        CieSkyType::ClearPolluted,
        CieSkyType::TurbidBroadCorona,
        CieSkyType::WhiteBlueTurbidBroadCorona,
    ];

    /// The type of the standard's number `1..=15`, `None` for any other.
    pub fn from_number(number: u8) -> Option<CieSkyType> {
        Self::ALL.get(usize::from(number).checked_sub(1)?).copied()
    }

    /// The standard's number of this type, 1 to 15.
    pub fn number(self) -> u8 {
        self as u8
    }

    /// The gradation group (1 to 6 for I to VI) and indicatrix group (1 to 6) of the
    /// standard's Table 1.
    pub fn groups(self) -> (u8, u8) {
        match self.number() {
            n @ 1..=4 => (n.div_ceil(2), 2 - n % 2),
            n @ 5..=8 => (3, n - 4),
            n @ 9..=11 => (4, n - 7),
            12 => (5, 4),
            13 => (5, 5),
            14 => (6, 5),
            _ => (6, 6),
        }
    }

    /// The parameters a, b, c, d, e of this type.
    pub fn parameters(self) -> CieParameters {
        let (gradation, indicatrix) = self.groups();
        let (a, b) = GRADATIONS[usize::from(gradation) - 1];
        let (c, d, e) = INDICATRICES[usize::from(indicatrix) - 1];
        CieParameters { a, b, c, d, e }
    }

    /// The standard's description of this type.
    pub fn name(self) -> &'static str {
        match self {
            CieSkyType::OvercastSteep => {
                "CIE standard overcast sky, steep gradation toward the zenith, azimuthal uniformity"
            }
            CieSkyType::OvercastSteepBrighterTowardSun => {
                "overcast, steep gradation and slight brightening toward the sun"
            }
            CieSkyType::OvercastModerate => "overcast, moderately graded, azimuthal uniformity",
            CieSkyType::OvercastModerateBrighterTowardSun => {
                "overcast, moderately graded and slight brightening toward the sun"
            }
            CieSkyType::Uniform => "sky of uniform luminance",
            CieSkyType::PartlyCloudyBrighterTowardSun => {
                "partly cloudy, no gradation toward the zenith, slight brightening toward the sun"
            }
            CieSkyType::PartlyCloudyCircumsolar => {
                "partly cloudy, no gradation toward the zenith, brighter circumsolar region"
            }
            CieSkyType::PartlyCloudyCorona => {
                "partly cloudy, no gradation toward the zenith, distinct solar corona"
            }
            CieSkyType::PartlyCloudyObscuredSun => "partly cloudy, the sun obscured",
            CieSkyType::PartlyCloudyGradedCircumsolar => {
                "partly cloudy, brighter circumsolar region"
            }
            CieSkyType::WhiteBlueCorona => "white-blue sky with distinct solar corona",
            CieSkyType::ClearLowTurbidity => "CIE standard clear sky, low luminance turbidity",
            CieSkyType::ClearPolluted => "CIE standard clear sky, polluted atmosphere",
            CieSkyType::TurbidBroadCorona => "cloudless turbid sky with broad solar corona",
            CieSkyType::WhiteBlueTurbidBroadCorona => {
                "white-blue turbid sky with broad solar corona"
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fifteen_types_have_the_standards_parameters() {
        // CIE S 011/E:2003 Table 1, row by row: (a, b, c, d, e).
        let table: [(f64, f64, f64, f64, f64); 15] = [
            (4.0, -0.70, 0.0, -1.0, 0.00),
            (4.0, -0.70, 2.0, -1.5, 0.15),
            (1.1, -0.8, 0.0, -1.0, 0.00),
            (1.1, -0.8, 2.0, -1.5, 0.15),
            (0.0, -1.0, 0.0, -1.0, 0.00),
            (0.0, -1.0, 2.0, -1.5, 0.15),
            (0.0, -1.0, 5.0, -2.5, 0.30),
            (0.0, -1.0, 10.0, -3.0, 0.45),
            (-1.0, -0.55, 2.0, -1.5, 0.15),
            (-1.0, -0.55, 5.0, -2.5, 0.30),
            (-1.0, -0.55, 10.0, -3.0, 0.45),
            (-1.0, -0.32, 10.0, -3.0, 0.45),
            (-1.0, -0.32, 16.0, -3.0, 0.30),
            (-1.0, -0.15, 16.0, -3.0, 0.30),
            (-1.0, -0.15, 24.0, -2.8, 0.15),
        ];
        for (i, (a, b, c, d, e)) in table.into_iter().enumerate() {
            let sky = CieSkyType::from_number(i as u8 + 1).unwrap();
            assert_eq!(sky.number(), i as u8 + 1);
            assert_eq!(sky, CieSkyType::ALL[i]);
            assert_eq!(
                sky.parameters(),
                CieParameters { a, b, c, d, e },
                "type {}",
                i + 1
            );
            assert!(!sky.name().is_empty());
        }
        assert_eq!(CieSkyType::from_number(0), None);
        assert_eq!(CieSkyType::from_number(16), None);
        // The groups as the standard names them: type 12 is gradation V, indicatrix 4.
        assert_eq!(CieSkyType::ClearLowTurbidity.groups(), (5, 4));
        assert_eq!(
            CieSkyType::OvercastModerateBrighterTowardSun.groups(),
            (2, 2)
        );
        assert!(CieSkyType::ClearLowTurbidity.name().contains("clear sky"));
    }

    #[test]
    fn gradation_and_indicatrix_at_published_values() {
        let overcast = CieSkyType::OvercastSteep.parameters();
        // φ(0) = 1 + 4·e^−0.7 = 2.98634…; φ(90°) = 1.
        assert!((overcast.gradation(1.0) - 2.986_341_2).abs() < 1e-7);
        assert_eq!(overcast.gradation(0.0), 1.0);
        // f(30°) for c = 10, d = −3, e = 0.45: 3.3264628… (colour-science's example).
        let clear = CieSkyType::ClearLowTurbidity.parameters();
        assert!((clear.indicatrix(30f64.to_radians()) - 3.326_462_8).abs() < 1e-7);
        // f(90°) = 1 for every type: the indicatrix is normalised at right angles to the Sun.
        for sky in CieSkyType::ALL {
            let f = sky.parameters().indicatrix(std::f64::consts::FRAC_PI_2);
            assert!((f - 1.0).abs() < 1e-15, "{sky:?}");
        }
    }
}
