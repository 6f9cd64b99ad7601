//! Spectra strahl ships, by name: the ASTM G173-03 reference solar spectra (NREL's tables,
//! `astm_g173.csv`, see `ASTM-G173-SOURCE.md`), for suns and skies whose spectrum a user
//! does not measure.

use super::Spectrum;
use std::sync::OnceLock;

/// One of the spectra strahl ships. Values are spectral irradiance, W·m⁻²·nm⁻¹, at 2002
/// wavelengths from 280 to 4000 nm (0.5 nm apart below 400 nm, 1 nm to 1700 nm, 5 nm above).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StandardSpectrum {
    /// ASTM G173-03 extraterrestrial: the sun above the atmosphere (1347.9 W·m⁻² in all).
    AstmG173Extraterrestrial,
    /// ASTM G173-03 global tilt: sun and sky on a plane tilted 37° toward the sun at air mass
    /// 1.5 (1000.4 W·m⁻²).
    AstmG173Global,
    /// ASTM G173-03 direct normal with circumsolar, air mass 1.5 (900.1 W·m⁻²): the sun.
    AstmG173Direct,
    /// The global tilt less the direct, at least 0 at each wavelength (above 2725 nm the
    /// direct is the larger by up to 1.5·10⁻⁴ W·m⁻²·nm⁻¹; 100.3 W·m⁻² in all): the light of
    /// the sky and the ground, a stand-in for a clear sky's spectrum.
    AstmG173Diffuse,
}

impl StandardSpectrum {
    /// Every standard spectrum, in the order of [`StandardSpectrum::name`]'s list.
    pub const ALL: [StandardSpectrum; 4] = [
        StandardSpectrum::AstmG173Extraterrestrial,
        StandardSpectrum::AstmG173Global,
        StandardSpectrum::AstmG173Direct,
        StandardSpectrum::AstmG173Diffuse,
    ];

    /// The name a scene file gives it (`astm-g173-direct` …).
    pub fn name(self) -> &'static str {
        match self {
            StandardSpectrum::AstmG173Extraterrestrial => "astm-g173-extraterrestrial",
            StandardSpectrum::AstmG173Global => "astm-g173-global",
            StandardSpectrum::AstmG173Direct => "astm-g173-direct",
            StandardSpectrum::AstmG173Diffuse => "astm-g173-diffuse",
        }
    }

    /// The standard spectrum named `name`, if there is one.
    pub fn from_name(name: &str) -> Option<StandardSpectrum> {
        Self::ALL.into_iter().find(|s| s.name() == name)
    }

    /// The spectrum, W·m⁻²·nm⁻¹.
    pub fn spectrum(self) -> Spectrum {
        let column = |row: &[f64; 4]| match self {
            StandardSpectrum::AstmG173Extraterrestrial => row[1],
            StandardSpectrum::AstmG173Global => row[2],
            StandardSpectrum::AstmG173Direct => row[3],
            StandardSpectrum::AstmG173Diffuse => (row[2] - row[3]).max(0.0),
        };
        Spectrum::Sampled(astm_g173().iter().map(|r| (r[0], column(r))).collect())
    }
}

/// The rows of `astm_g173.csv`: nm, extraterrestrial, global tilt, direct, read once.
fn astm_g173() -> &'static [[f64; 4]] {
    static ROWS: OnceLock<Vec<[f64; 4]>> = OnceLock::new();
    ROWS.get_or_init(|| {
        include_str!("astm_g173.csv")
            .lines()
            .filter(|line| !line.starts_with('#'))
            .map(|line| {
                let mut row = [0.0; 4];
                for (x, field) in row.iter_mut().zip(line.split(',')) {
                    // The file is part of the build and checked by the tests below.
                    *x = field.parse().unwrap_or(f64::NAN);
                }
                row
            })
            .collect()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table reads whole: 2002 rows of finite, non-negative values in increasing
    /// wavelength, so every standard spectrum passes [`Spectrum::sampled`]'s checks.
    #[test]
    fn the_table_is_whole_and_valid() {
        assert_eq!(astm_g173().len(), 2002);
        for s in StandardSpectrum::ALL {
            let Spectrum::Sampled(samples) = s.spectrum() else {
                panic!("{} is not sampled", s.name());
            };
            assert_eq!(samples.first().map(|x| x.0), Some(280.0));
            assert_eq!(samples.last().map(|x| x.0), Some(4000.0));
            assert!(Spectrum::sampled(samples).is_ok(), "{}", s.name());
            assert_eq!(StandardSpectrum::from_name(s.name()), Some(s));
        }
        assert_eq!(StandardSpectrum::from_name("astm-g173"), None);
    }

    /// The totals NREL states for the three columns (1347.9, 1000.4, 900.1 W·m⁻², to the
    /// 0.1 W·m⁻² they are given in), and the diffuse's, 100.288 348 W·m⁻² by the trapezoids
    /// of the clamped differences (computed apart from strahl from NREL's file).
    #[test]
    fn totals_match_the_published_ones() {
        let total = |s: StandardSpectrum| s.spectrum().total();
        assert!((total(StandardSpectrum::AstmG173Extraterrestrial) - 1347.9).abs() < 0.05);
        assert!((total(StandardSpectrum::AstmG173Global) - 1000.4).abs() < 0.05);
        assert!((total(StandardSpectrum::AstmG173Direct) - 900.1).abs() < 0.05);
        let diffuse = total(StandardSpectrum::AstmG173Diffuse);
        assert!((diffuse - 100.288_348).abs() < 1e-5, "{diffuse}");
    }
}
