//! Spectra over wavelength and the bands they are integrated over: what a scene with bands
//! says of its lights (emission spectra) and materials (reflectance and transmittance
//! spectra), and the conversion of a band's power into photon flux (µmol s⁻¹).
//!
//! Wavelengths are in nanometres. A sampled spectrum is linear between its samples and zero
//! outside them; a black body is Planck's law. Integrals split a band at every sample and
//! use 4-point Gauss–Legendre on pieces of at most [`PIECE_NM`]: exact for products of two
//! sampled spectra (quadratics), and within 10⁻⁹ relative for Planck's smooth curve.

/// Planck's constant, J·s (exact, SI 2019).
const PLANCK: f64 = 6.626_070_15e-34;
/// Speed of light, m·s⁻¹ (exact).
const LIGHT_SPEED: f64 = 299_792_458.0;
/// Boltzmann's constant, J·K⁻¹ (exact).
const BOLTZMANN: f64 = 1.380_649e-23;
/// Avogadro's number, mol⁻¹ (exact).
const AVOGADRO: f64 = 6.022_140_76e23;
/// Stefan–Boltzmann constant, W·m⁻²·K⁻⁴ (from the exact constants above).
const STEFAN_BOLTZMANN: f64 = 5.670_374_419e-8;

/// Energy of a mole of photons times their wavelength, J·nm·mol⁻¹: `h·c·N_A` with the
/// wavelength in nm. A joule of light at λ nm is `λ / MOLAR_PHOTON_ENERGY_NM` mol of photons.
pub const MOLAR_PHOTON_ENERGY_NM: f64 = PLANCK * LIGHT_SPEED * AVOGADRO * 1e9;

/// The longest wavelength a spectrum or band may reach, nm (1 mm, the far infrared's end):
/// integrals take pieces of at most 5 nm, so a wavelength without bound would never
/// finish.
pub const MAX_WAVELENGTH_NM: f64 = 1e6;

/// Longest piece of a band one Gauss–Legendre rule integrates, nm.
const PIECE_NM: f64 = 5.0;

/// A named wavelength interval `[from_nm, to_nm)` a scene reports light in (PAR 400–700 nm,
/// red 655–665 nm, far red 725–735 nm, near infrared …).
#[derive(Clone, Debug, PartialEq)]
pub struct Band {
    /// The band's name in reports.
    pub name: String,
    /// Shortest wavelength, nm.
    pub from_nm: f64,
    /// Longest wavelength, nm (greater than `from_nm`).
    pub to_nm: f64,
}

/// A spectrum: a quantity per nanometre of wavelength (spectral radiance, irradiance or
/// power for lights; a dimensionless reflectance or transmittance for materials).
#[derive(Clone, Debug, PartialEq)]
pub enum Spectrum {
    /// Samples `(wavelength nm, value)` in increasing wavelength, linear between them, zero
    /// outside.
    Sampled(Vec<(f64, f64)>),
    /// A black body at this temperature, K: Planck's spectral radiance,
    /// W·sr⁻¹·m⁻²·nm⁻¹.
    Blackbody {
        /// Temperature, K.
        kelvin: f64,
    },
}

/// Why a list of samples is not a spectrum.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SpectrumError {
    /// Fewer than two samples.
    #[error("a spectrum needs at least two samples (wavelength nm, value)")]
    TooFewSamples,
    /// Wavelengths not strictly increasing, or not in (0, [`MAX_WAVELENGTH_NM`]].
    #[error("wavelengths must be positive, at most 10⁶ nm and strictly increasing (sample {0})")]
    Wavelengths(usize),
    /// A negative or non-finite value.
    #[error("values must be finite and ≥ 0 (sample {0})")]
    Value(usize),
    /// A black body's temperature not positive and finite.
    #[error("a black body's temperature must be a positive number of kelvin")]
    Temperature,
}

impl Spectrum {
    /// The sampled spectrum of `samples` `(nm, value)`, checked.
    pub fn sampled(samples: Vec<(f64, f64)>) -> Result<Spectrum, SpectrumError> {
        if samples.len() < 2 {
            return Err(SpectrumError::TooFewSamples);
        }
        for (i, &(nm, v)) in samples.iter().enumerate() {
            let previous = if i == 0 { 0.0 } else { samples[i - 1].0 };
            if !(nm > previous && nm <= MAX_WAVELENGTH_NM) {
                return Err(SpectrumError::Wavelengths(i));
            }
            if !(v.is_finite() && v >= 0.0) {
                return Err(SpectrumError::Value(i));
            }
        }
        Ok(Spectrum::Sampled(samples))
    }

    /// The black body at `kelvin`, checked.
    pub fn blackbody(kelvin: f64) -> Result<Spectrum, SpectrumError> {
        if kelvin.is_finite() && kelvin > 0.0 {
            Ok(Spectrum::Blackbody { kelvin })
        } else {
            Err(SpectrumError::Temperature)
        }
    }

    /// The value at `nm`.
    pub fn value(&self, nm: f64) -> f64 {
        match self {
            Spectrum::Sampled(s) => {
                let i = s.partition_point(|&(x, _)| x <= nm);
                if i == 0 || i == s.len() {
                    // Outside, or exactly the last sample.
                    return if nm == s[s.len() - 1].0 {
                        s[s.len() - 1].1
                    } else {
                        0.0
                    };
                }
                let ((x0, y0), (x1, y1)) = (s[i - 1], s[i]);
                y0 + (y1 - y0) * (nm - x0) / (x1 - x0)
            }
            Spectrum::Blackbody { kelvin } => planck(nm, *kelvin),
        }
    }

    /// The wavelengths `[first, last]` a sampled spectrum covers (`None` for a black body,
    /// which covers every wavelength).
    pub fn range(&self) -> Option<(f64, f64)> {
        match self {
            Spectrum::Sampled(s) => Some((s[0].0, s[s.len() - 1].0)),
            Spectrum::Blackbody { .. } => None,
        }
    }

    /// The integral over all wavelengths: a light's total (W·sr⁻¹·m⁻² of a black body,
    /// `σT⁴/π`).
    pub fn total(&self) -> f64 {
        match self {
            Spectrum::Sampled(s) => integrate(s[0].0, s[s.len() - 1].0, &[self], |_, v| v[0]),
            Spectrum::Blackbody { kelvin } => {
                STEFAN_BOLTZMANN * kelvin.powi(4) / std::f64::consts::PI
            }
        }
    }

    /// `∫ S(λ) dλ` over `band`.
    pub fn integral(&self, band: &Band) -> f64 {
        integrate(band.from_nm, band.to_nm, &[self], |_, v| v[0])
    }

    /// Moles of photons per joule of this spectrum's light within `band`, µmol·J⁻¹:
    /// `∫ S λ dλ / (h c N_A ∫ S dλ)`; `None` when it has no light there.
    pub fn micromoles_per_joule(&self, band: &Band) -> Option<f64> {
        let energy = self.integral(band);
        let photons = integrate(band.from_nm, band.to_nm, &[self], |nm, v| v[0] * nm);
        (energy > 0.0).then(|| photons / energy / MOLAR_PHOTON_ENERGY_NM * 1e6)
    }

    /// The mean of this spectrum over `band` weighted by the sum of `weights` (lights'
    /// spectra, each with a factor): `∫ S w dλ / ∫ w dλ`, `w = Σ kᵢ Wᵢ`; the plain mean where
    /// the weights have no light in the band.
    pub fn weighted_mean(&self, band: &Band, weights: &[(&Spectrum, f64)]) -> f64 {
        let w: f64 = weights.iter().map(|&(s, k)| k * s.integral(band)).sum();
        if w > 0.0 {
            let product =
                |s: &Spectrum| integrate(band.from_nm, band.to_nm, &[self, s], |_, v| v[0] * v[1]);
            weights.iter().map(|&(s, k)| k * product(s)).sum::<f64>() / w
        } else {
            self.integral(band) / (band.to_nm - band.from_nm)
        }
    }
}

/// Planck's spectral radiance of a black body at `kelvin`, W·sr⁻¹·m⁻²·nm⁻¹, at `nm`.
fn planck(nm: f64, kelvin: f64) -> f64 {
    let m = nm * 1e-9;
    let x = PLANCK * LIGHT_SPEED / (m * BOLTZMANN * kelvin);
    if x > 700.0 {
        return 0.0;
    }
    2.0 * PLANCK * LIGHT_SPEED * LIGHT_SPEED / m.powi(5) / x.exp_m1() * 1e-9
}

/// `∫ f(λ, [S₁(λ), …]) dλ` over `[from, to]` nm for an `f` that is zero where a sampled
/// spectrum is (all of this module's): over the part of the interval every sampled spectrum
/// covers, split at every sample, then 4-point Gauss–Legendre on pieces of at most
/// [`PIECE_NM`].
fn integrate(from: f64, to: f64, spectra: &[&Spectrum], f: impl Fn(f64, &[f64]) -> f64) -> f64 {
    let (mut from, mut to) = (from, to.min(MAX_WAVELENGTH_NM));
    for s in spectra {
        if let Some((first, last)) = s.range() {
            (from, to) = (from.max(first), to.min(last));
        }
    }
    if to.partial_cmp(&from) != Some(std::cmp::Ordering::Greater) {
        return 0.0;
    }
    let mut cuts = vec![from, to];
    for s in spectra {
        if let Spectrum::Sampled(samples) = s {
            cuts.extend(
                samples
                    .iter()
                    .map(|&(nm, _)| nm)
                    .filter(|&nm| nm > from && nm < to),
            );
        }
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    // Nodes and weights of the 4-point rule on [-1, 1].
    const NODES: [f64; 4] = [
        -0.861_136_311_594_052_6,
        -0.339_981_043_584_856_3,
        0.339_981_043_584_856_3,
        0.861_136_311_594_052_6,
    ];
    const WEIGHTS: [f64; 4] = [
        0.347_854_845_137_453_9,
        0.652_145_154_862_546_1,
        0.652_145_154_862_546_1,
        0.347_854_845_137_453_9,
    ];
    let mut values = vec![0.0; spectra.len()];
    let mut sum = 0.0;
    for piece in cuts.windows(2) {
        let (a, b) = (piece[0], piece[1]);
        let steps = ((b - a) / PIECE_NM).ceil().max(1.0) as usize;
        let h = (b - a) / steps as f64;
        for k in 0..steps {
            let (lo, hi) = (a + h * k as f64, a + h * (k + 1) as f64);
            let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
            for (x, w) in NODES.iter().zip(WEIGHTS) {
                let nm = mid + half * x;
                for (v, s) in values.iter_mut().zip(spectra) {
                    *v = s.value(nm);
                }
                sum += w * half * f(nm, &values);
            }
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    fn band(from_nm: f64, to_nm: f64) -> Band {
        Band {
            name: "b".into(),
            from_nm,
            to_nm,
        }
    }

    #[test]
    fn sampled_spectra_integrate_exactly() {
        // 0 at 400 nm rising to 2 at 500 nm, flat to 700 nm.
        let s = Spectrum::sampled(vec![(400.0, 0.0), (500.0, 2.0), (700.0, 2.0)]).unwrap();
        assert_eq!(s.value(450.0), 1.0);
        assert_eq!(s.value(700.0), 2.0);
        assert_eq!(s.value(399.0), 0.0);
        assert_eq!(s.value(701.0), 0.0);
        // By hand: a triangle of 100 and a rectangle of 400.
        assert!((s.total() - 500.0).abs() < 1e-9);
        assert!((s.integral(&band(450.0, 550.0)) - (75.0 + 100.0)).abs() < 1e-9);
        // Outside its samples a spectrum is zero.
        assert!((s.integral(&band(300.0, 800.0)) - 500.0).abs() < 1e-9);
        // ∫₅₀₀⁷⁰⁰ 2·λ dλ = 480,000 for 400 J, so mean 600 nm: 600 / 119.6266 µmol/J.
        let photons = s.micromoles_per_joule(&band(500.0, 700.0)).unwrap();
        assert!((photons - 600.0 / MOLAR_PHOTON_ENERGY_NM * 1e6).abs() < 1e-12);
        assert!(s.micromoles_per_joule(&band(100.0, 300.0)).is_none());
    }

    #[test]
    fn a_joule_of_light_holds_the_photons_of_its_wavelength() {
        // h·c·N_A = 0.119 626 566 J·m·mol⁻¹: a joule at 550 nm is 4.5977 µmol.
        assert!((MOLAR_PHOTON_ENERGY_NM - 1.196_265_66e8).abs() < 1.0);
        let flat = Spectrum::sampled(vec![(400.0, 1.0), (700.0, 1.0)]).unwrap();
        let par = flat.micromoles_per_joule(&band(400.0, 700.0)).unwrap();
        assert!((par - 550.0 / 119.626_566).abs() < 1e-6, "{par}");
    }

    #[test]
    fn weighted_means_weight_by_the_light() {
        let reflectance = Spectrum::sampled(vec![(400.0, 0.0), (600.0, 1.0)]).unwrap();
        let flat = Spectrum::sampled(vec![(300.0, 1.0), (800.0, 1.0)]).unwrap();
        let b = band(400.0, 600.0);
        assert!((reflectance.weighted_mean(&b, &[(&flat, 1.0)]) - 0.5).abs() < 1e-12);
        // Weight rising as the reflectance: ∫x² / ∫x over [0, 1] = 2/3.
        let rising = Spectrum::sampled(vec![(400.0, 0.0), (600.0, 3.0)]).unwrap();
        let mean = reflectance.weighted_mean(&b, &[(&rising, 1.0)]);
        assert!((mean - 2.0 / 3.0).abs() < 1e-12, "{mean}");
        // Both, the flat one counted twice: (2·100 + 200) / (2·200 + 300) = 4/7.
        let mean = reflectance.weighted_mean(&b, &[(&flat, 2.0), (&rising, 1.0)]);
        assert!((mean - 4.0 / 7.0).abs() < 1e-12, "{mean}");
        // No light in the band: the plain mean.
        let dark = Spectrum::sampled(vec![(700.0, 1.0), (800.0, 1.0)]).unwrap();
        assert!((reflectance.weighted_mean(&b, &[(&dark, 1.0)]) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn a_black_body_follows_planck_and_stefan_boltzmann() {
        let sun = Spectrum::blackbody(5778.0).unwrap();
        // Wien's displacement law: the peak at b/T, b = 2.897 771 955e6 nm·K.
        let peak = 2.897_771_955e6 / 5778.0;
        assert!(sun.value(peak) > sun.value(peak - 1.0) && sun.value(peak) > sun.value(peak + 1.0));
        // The integral over 10 nm … 100 µm holds all but 1e-5 of σT⁴/π.
        let all = sun.integral(&band(10.0, 100_000.0));
        assert!(
            (all / sun.total() - 1.0).abs() < 1e-5,
            "{}",
            all / sun.total()
        );
        // The fraction of a 5778 K body's light within 400–700 nm, 0.366 659 443: the
        // fractional function F(λT) = 15/π⁴ Σₙ e^{−nx}/n (x³ + 3x²/n + 6x/n² + 6/n³),
        // x = hc/λkT, summed to 200 terms at 400 and 700 nm (0.122 245 490, 0.488 904 933).
        let par = sun.integral(&band(400.0, 700.0)) / sun.total();
        assert!((par - 0.366_659_443).abs() < 1e-8, "{par}");
        assert!(Spectrum::blackbody(0.0).is_err());
    }

    #[test]
    fn bad_samples_are_refused() {
        assert_eq!(
            Spectrum::sampled(vec![(400.0, 1.0)]),
            Err(SpectrumError::TooFewSamples)
        );
        assert_eq!(
            Spectrum::sampled(vec![(400.0, 1.0), (400.0, 1.0)]),
            Err(SpectrumError::Wavelengths(1))
        );
        assert_eq!(
            Spectrum::sampled(vec![(400.0, 1.0), (500.0, -1.0)]),
            Err(SpectrumError::Value(1))
        );
        // A wavelength without bound would take pieces without end.
        assert_eq!(
            Spectrum::sampled(vec![(400.0, 1.0), (1e12, 1.0)]),
            Err(SpectrumError::Wavelengths(1))
        );
    }
}
