//! MGF colours and materials in strahl's terms.
//!
//! **Colours.** MGF gives a colour as a CIE 1931 xy chromaticity (`cxy`; `cspec`, `cct` and
//! `cmix` are reduced to one) and the intensity separately, as a photometric quantity of the
//! material field that uses the colour: `rd 0.5` is a diffuse reflectance whose luminance `Y`
//! is 0.5. xy and `Y` give CIE XYZ, and XYZ becomes linear RGB through the RGB space the MGF
//! specification's application notes recommend: the nominal CRT primaries R (0.640, 0.330),
//! G (0.290, 0.600), B (0.150, 0.060) with the equal-energy white (1/3, 1/3). Its red and blue
//! primaries are Rec.709's and its green differs by 0.01 in x; its white is MGF's neutral
//! colour, so an uncoloured `rd 0.5` is the grey (0.5, 0.5, 0.5), as strahl's spectra give
//! grey for a flat spectrum. It is the space RenderPark reads MGF in and the one
//! `scripts/cornell-mgf.py` writes for, so a file that script writes reads back to strahl's
//! RGB to within 10⁻⁶.
//!
//! **Emission.** `ed` is a diffuse emittance in lm/m². strahl's photometry is 683 lm/W
//! times the luminance of its linear RGB ([`LUMINOUS_EFFICACY`]), so the exitance is
//! E = ed / 683 W/m² in luminance, and a Lambertian emitter of exitance E has radiance
//! L = E/π W·sr⁻¹·m⁻²: `emission = ed / (683 · π)` in luminance, with the colour's
//! chromaticity. A report then gives back the file's lumens. (RenderPark divides by the
//! efficacy of equal-energy white, 183.07 lm/W, instead: its watts are 683/183.07 = 3.73 times
//! strahl's for the same lumens; `scripts/cornell-mgf.py` writes for RenderPark.)

use super::mgf_syntax::number;
use crate::color::{LUMINOUS_EFFICACY, Rgb};
use crate::scene::builtin::spectrum::spectrum_to_xyz;
use crate::scene::{ENERGY_TOLERANCE, MAX_COLOUR, Material};
use glam::{DMat3, DVec3};

/// The visible range MGF spectra are taken over, nanometres.
const VISIBLE_NM: (f64, f64) = (380.0, 780.0);

/// Chromaticities with `y` below this are black, as RenderPark takes them (its `cy >
/// EPSILON`): XYZ is luminance over `y`, which for `y` near 0 overflows to infinity and makes
/// the RGB conversion non-finite.
const MIN_Y: f64 = 1e-6;

/// The largest Phong exponent a rough `rs` becomes (roughness below 0.0006).
const MAX_SHININESS: f64 = 1e6;

/// Wavelength step of the grid spectra are resampled on, nanometres.
const STEP_NM: f64 = 5.0;

/// A colour without intensity: a CIE 1931 xy chromaticity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Chroma {
    /// CIE x.
    pub x: f64,
    /// CIE y.
    pub y: f64,
}

impl Chroma {
    /// MGF's neutral colour: the equal-energy white.
    pub const NEUTRAL: Chroma = Chroma {
        x: 1.0 / 3.0,
        y: 1.0 / 3.0,
    };

    /// The chromaticity `(x, y)`: both at least 0 with `x + y` at most 1, as MGF's reference
    /// parser takes them (RenderPark's `corridor.mgf` and `office2.mgf` have `cxy 0 …`, its
    /// hospital `cxy 0.4 0`). Such colours lie outside every RGB gamut: `x = 0` is clipped to
    /// the gamut, and `y = 0` (below [`MIN_Y`]), which has no luminance, is black (as
    /// RenderPark makes it).
    pub fn from_xy(x: f64, y: f64) -> Result<Chroma, String> {
        if x >= 0.0 && y >= 0.0 && x + y <= 1.0 {
            Ok(Chroma { x, y })
        } else {
            Err(format!(
                "({x}, {y}) is not a chromaticity: x ≥ 0 and y ≥ 0 with x + y ≤ 1 expected"
            ))
        }
    }

    /// Whether the colour has no luminance (`y` below [`MIN_Y`]): black whatever its amount.
    fn is_black(self) -> bool {
        self.y < MIN_Y
    }

    /// The chromaticity of CIE XYZ `xyz`.
    fn from_xyz(xyz: DVec3) -> Result<Chroma, String> {
        let sum = xyz.element_sum();
        if !(sum > 0.0 && xyz.y > 0.0 && sum.is_finite()) {
            return Err("the colour has no visible light (its luminance Y is not > 0)".into());
        }
        Chroma::from_xy(xyz.x / sum, xyz.y / sum)
    }

    /// CIE XYZ of this chromaticity with luminance `y_luminance` (zero for a black one).
    fn xyz(self, y_luminance: f64) -> DVec3 {
        if self.is_black() {
            return DVec3::ZERO;
        }
        DVec3::new(self.x / self.y, 1.0, (1.0 - self.x - self.y) / self.y) * y_luminance
    }

    /// The `cspec l_min l_max v1 v2 …` spectrum: `values` evenly spaced from `l_min` to
    /// `l_max` nm, linear in between, zero outside; taken over 380–780 nm. Negative values
    /// (the noise of a measured spectrum: RenderPark's `illums.mgf` has them) are taken as 0,
    /// told to `warn`.
    pub fn from_spectrum(args: &[&str], warn: &mut dyn FnMut(String)) -> Result<Chroma, String> {
        let [l_min, l_max, values @ ..] = args else {
            return Err("l_min and l_max expected".into());
        };
        if values.len() < 2 {
            return Err(format!("at least 2 values expected, got {}", values.len()));
        }
        let l_min = number(l_min, "l_min")?;
        let l_max = number(l_max, "l_max")?;
        if !(l_min > 0.0 && l_min < l_max) {
            return Err(format!(
                "l_min {l_min} and l_max {l_max}: 0 < l_min < l_max nm expected"
            ));
        }
        let mut values = values
            .iter()
            .enumerate()
            .map(|(i, w)| number(w, &format!("value {}", i + 1)))
            .collect::<Result<Vec<f64>, String>>()?;
        let negative: Vec<(usize, f64)> = (values.iter().enumerate())
            .filter(|(_, v)| **v < 0.0)
            .map(|(i, &v)| (i + 1, v))
            .collect();
        if let Some(&(first, v)) = negative.first() {
            warn(format!(
                "cspec: {} negative value(s) taken as 0 (the first: value {first}, {v})",
                negative.len()
            ));
            values.iter_mut().for_each(|v| *v = v.max(0.0));
        }
        let step = (l_max - l_min) / (values.len() - 1) as f64;
        let at = |lambda: f64| {
            if lambda < l_min || lambda > l_max {
                return 0.0;
            }
            let t = (lambda - l_min) / step;
            let i = (t.floor() as usize).min(values.len() - 2);
            let f = t - i as f64;
            values[i] * (1.0 - f) + values[i + 1] * f
        };
        Chroma::from_xyz(visible_xyz(at)?)
    }

    /// The colour of a black body at `kelvin` (`cct`): Planck's law over 380–780 nm.
    pub fn blackbody(kelvin: f64) -> Result<Chroma, String> {
        if kelvin <= 0.0 {
            return Err(format!("temperature {kelvin}: must be > 0 K"));
        }
        // Second radiation constant h·c/k, m·K.
        const C2: f64 = 1.438_776_877e-2;
        let planck = |lambda_nm: f64| {
            let lambda = lambda_nm * 1e-9;
            1.0 / (lambda.powi(5) * ((C2 / (lambda * kelvin)).exp() - 1.0))
        };
        Chroma::from_xyz(visible_xyz(planck)?)
            .map_err(|_| format!("a black body at {kelvin} K gives no visible light"))
    }

    /// The mix of `parts` (`cmix w1 c1 w2 c2 …`), each weighted by its relative luminance.
    pub fn mix(parts: &[(f64, Chroma)]) -> Result<Chroma, String> {
        let xyz = parts
            .iter()
            .map(|&(w, c)| c.xyz(w))
            .fold(DVec3::ZERO, |a, b| a + b);
        Chroma::from_xyz(xyz).map_err(|_| "the weights mix to no visible light".to_string())
    }

    /// Linear RGB (module documentation) of this chromaticity with luminance `y_luminance`;
    /// channels below 0 (outside the RGB gamut) are clipped to 0, and `clipped` tells.
    fn rgb(self, y_luminance: f64) -> (DVec3, bool) {
        let rgb = rgb_from_xyz() * self.xyz(y_luminance);
        let clipped = rgb.min_element() < -1e-9 * rgb.max_element().abs().max(1e-300);
        (rgb.max(DVec3::ZERO), clipped)
    }
}

/// The matrix from CIE XYZ to linear RGB with the MGF application notes' nominal CRT
/// primaries and equal-energy white (module documentation).
fn rgb_from_xyz() -> DMat3 {
    let primary = |x: f64, y: f64| DVec3::new(x / y, 1.0, (1.0 - x - y) / y);
    let primaries = DMat3::from_cols(
        primary(0.640, 0.330),
        primary(0.290, 0.600),
        primary(0.150, 0.060),
    );
    let white = primary(1.0 / 3.0, 1.0 / 3.0);
    let scale = primaries.inverse() * white;
    (primaries * DMat3::from_diagonal(scale)).inverse()
}

/// CIE XYZ of the spectrum `value(λ)` (λ in nm) sampled every [`STEP_NM`] over the visible
/// range.
fn visible_xyz(value: impl Fn(f64) -> f64) -> Result<DVec3, String> {
    let steps = ((VISIBLE_NM.1 - VISIBLE_NM.0) / STEP_NM) as usize;
    let samples: Vec<(f64, f64)> = (0..=steps)
        .map(|i| {
            let lambda = VISIBLE_NM.0 + i as f64 * STEP_NM;
            (lambda, value(lambda))
        })
        .collect();
    if samples.iter().any(|s| !s.1.is_finite()) {
        return Err("the spectrum is not finite".into());
    }
    spectrum_to_xyz(&samples).map(DVec3::from)
}

/// A diffuse or specular component of an MGF material: its photometric amount (reflectance,
/// transmittance, or emittance in lm/m²) and the colour current when it was set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Component {
    /// The amount (`rho_d`, `tau_d`, `epsilon_d`, `rho_s`, `tau_s`).
    pub amount: f64,
    /// Its colour.
    pub color: Chroma,
}

impl Default for Component {
    fn default() -> Self {
        Component {
            amount: 0.0,
            color: Chroma::NEUTRAL,
        }
    }
}

/// An MGF material context (defaults: MGF's unnamed material, a two-sided black absorber).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct MgfMaterial {
    /// `sides 1` (false: two-sided, the default).
    pub one_sided: bool,
    /// `rd`.
    pub rd: Component,
    /// `td`.
    pub td: Component,
    /// `ed`, lm/m².
    pub ed: Component,
    /// `rs` with its roughness (RMS facet slope).
    pub rs: (Component, f64),
    /// `ts` with its roughness.
    pub ts: (Component, f64),
    /// `ir`: real and imaginary index of refraction; `None` is MGF's default (1, 0).
    pub ir: Option<(f64, f64)>,
}

/// What identifies an [`MgfMaterial`]: its values as bits ([`MgfMaterial::key`]).
pub(super) type MaterialKey = [u64; 20];

impl MgfMaterial {
    /// The material's values as bits, equal exactly when the values are (`-0` taken as `0`),
    /// to find materials already converted by hashing.
    pub fn key(&self) -> MaterialKey {
        let c = |c: &Component| [c.amount, c.color.x, c.color.y];
        let (n_real, n_imag) = self.ir.unwrap_or((f64::NAN, f64::NAN));
        let values = [
            [f64::from(u8::from(self.one_sided)), self.rs.1, self.ts.1],
            c(&self.rd),
            c(&self.td),
            c(&self.ed),
            c(&self.rs.0),
            c(&self.ts.0),
        ];
        let mut key: MaterialKey = [0; 20];
        for (slot, v) in key
            .iter_mut()
            .zip(values.iter().flatten().chain([&n_real, &n_imag]))
        {
            *slot = (v + 0.0).to_bits();
        }
        key
    }
}

/// `m` to strahl's material named `name`: `rd` → `diffuse`, `td` → `translucency`, `ed` →
/// `emission` (radiance, [`LUMINOUS_EFFICACY`] and π; from the front side only, as MGF's "the
/// lumen output of a convex emitter is its area times its emittance" implies and RenderPark
/// does), `rs` → `mirror` when smooth, else `specular` with the Phong `shininess`
/// (0.6/roughness)² the MGF notes give (at most 10⁶), `ts` → `transmission` with `ior` from
/// `ir` (its real part; default 1), `sides 1` → `one_sided`. Problems that do not stop the
/// import are passed to `warn`: amounts that add up to more than 1 (RenderPark's `cube.mgf`
/// has rd + rs = 1.1) are scaled down to 1, as RenderPark scales them.
pub(super) fn to_strahl(
    name: &str,
    m: &MgfMaterial,
    warn: &mut dyn FnMut(String),
) -> Result<Material, String> {
    let total = m.rd.amount + m.td.amount + m.rs.0.amount + m.ts.0.amount;
    let amount_scale = if total > 1.0 + f64::from(ENERGY_TOLERANCE) {
        warn(format!(
            "material \"{name}\" reflects and transmits more than it receives: rd + td + rs + \
             ts = {total}; each was scaled down by 1/{total}"
        ));
        1.0 / total
    } else {
        1.0
    };
    let (mut clipped, mut blackened) = (false, false);
    let mut rgb = |c: &Component, scale: f64| {
        let (v, clip) = c.color.rgb(c.amount * scale);
        clipped |= clip && c.amount > 0.0;
        blackened |= c.color.is_black() && c.amount > 0.0;
        v
    };
    let diffuse = rgb(&m.rd, amount_scale);
    let translucency = rgb(&m.td, amount_scale);
    let specular = rgb(&m.rs.0, amount_scale);
    let transmission = rgb(&m.ts.0, amount_scale);
    let emission = rgb(&m.ed, 1.0 / (LUMINOUS_EFFICACY * std::f64::consts::PI));
    if emission.max_element() > f64::from(MAX_COLOUR) {
        return Err(format!(
            "material \"{name}\": ed {:e} lm/m² is a radiance of {:e} W·sr⁻¹·m⁻², beyond \
             {MAX_COLOUR:e}, where the renderers' 32-bit sums overflow",
            m.ed.amount,
            emission.max_element()
        ));
    }
    if clipped {
        warn(format!(
            "material \"{name}\": a colour outside the RGB gamut was clipped to it"
        ));
    }
    if blackened {
        warn(format!(
            "material \"{name}\": a colour with y = 0 (below {MIN_Y}) has no luminance: that part \
             is black"
        ));
    }
    let sum = diffuse + translucency + specular + transmission;
    let scale = if sum.max_element() > 1.0 + f64::from(ENERGY_TOLERANCE) {
        warn(format!(
            "material \"{name}\": its colours give {:.4} > 1 in one RGB channel; its \
             reflectances and transmittances were scaled down to 1",
            sum.max_element()
        ));
        1.0 / sum.max_element()
    } else {
        1.0
    };
    let weight = |v: DVec3| to_rgb(v * scale);
    let (ior, n_imag) = m.ir.unwrap_or((1.0, 0.0));
    if n_imag != 0.0 && m.ts.0.amount > 0.0 {
        warn(format!(
            "material \"{name}\": the imaginary index of refraction {n_imag} is ignored"
        ));
    }
    if m.ts.0.amount > 0.0 && m.ts.1 > 0.0 {
        warn(format!(
            "material \"{name}\": rough specular transmission (ts roughness {}) is taken as \
             smooth refraction",
            m.ts.1
        ));
    }
    let one_sided = m.one_sided && m.td.amount == 0.0;
    if m.one_sided && !one_sided {
        warn(format!(
            "material \"{name}\": one-sided with diffuse transmittance is taken as two-sided \
             (strahl's one-sided surfaces absorb on their back)"
        ));
    }
    let smooth = m.rs.1 == 0.0;
    Ok(Material {
        name: name.to_string(),
        diffuse: weight(diffuse),
        translucency: weight(translucency),
        emission: to_rgb(emission),
        two_sided: false,
        specular: if smooth { Rgb::BLACK } else { weight(specular) },
        shininess: if smooth {
            0.0
        } else {
            (0.6 / m.rs.1).powi(2).min(MAX_SHININESS) as f32
        },
        mirror: if smooth { weight(specular) } else { Rgb::BLACK },
        transmission: weight(transmission),
        ior: ior as f32,
        one_sided,
        ..Material::default()
    })
}

/// An `f64` colour as strahl's `f32` RGB.
fn to_rgb(v: DVec3) -> Rgb {
    Rgb::new(v.x as f32, v.y as f32, v.z as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn words(s: &str) -> Vec<&str> {
        s.split_whitespace().collect()
    }

    #[test]
    fn neutral_colours_are_grey_and_the_primaries_are_pure() {
        let (grey, clipped) = Chroma::NEUTRAL.rgb(0.5);
        assert!(!clipped && (grey - DVec3::splat(0.5)).abs().max_element() < 1e-12);
        let (red, _) = Chroma::from_xy(0.64, 0.33).unwrap().rgb(1.0);
        assert!(red.y.abs() < 1e-9 && red.z.abs() < 1e-9 && red.x > 0.0);
        // A pure spectral green lies outside the gamut: red is clipped.
        let (_, clipped) = Chroma::from_xy(0.07, 0.83).unwrap().rgb(1.0);
        assert!(clipped);
        assert!(Chroma::from_xy(0.7, 0.4).is_err());
        assert!(Chroma::from_xy(-0.1, 0.4).is_err());
        // What MGF's reference parser takes: x = 0 (clipped to the gamut) and y = 0 (black).
        let (_, clipped) = Chroma::from_xy(0.0, 0.38).unwrap().rgb(0.5);
        assert!(clipped);
        let (black, _) = Chroma::from_xy(0.4, 0.0).unwrap().rgb(0.5);
        assert_eq!(black, DVec3::ZERO);
        // Nearly 0 too: luminance over y would overflow, and the colour come out non-finite.
        let (black, _) = Chroma::from_xy(0.3, 1e-310).unwrap().rgb(0.5);
        assert_eq!(black, DVec3::ZERO);
    }

    #[test]
    fn spectra_black_bodies_and_mixes_give_their_chromaticity() {
        // A flat spectrum over the visible range is (nearly) the equal-energy white.
        let flat = Chroma::from_spectrum(&words("380 780 1 1 1"), &mut |w| panic!("{w}")).unwrap();
        assert!(
            (flat.x - 1.0 / 3.0).abs() < 2e-3 && (flat.y - 1.0 / 3.0).abs() < 2e-3,
            "{flat:?}"
        );
        // CIE illuminant A (2856 K) is at (0.4476, 0.4074).
        let a = Chroma::blackbody(2856.0).unwrap();
        assert!(
            (a.x - 0.4476).abs() < 2e-3 && (a.y - 0.4074).abs() < 2e-3,
            "{a:?}"
        );
        assert!(
            Chroma::blackbody(10.0)
                .unwrap_err()
                .contains("no visible light")
        );
        // The specification's cmix example mixes its primaries to (nearly) white.
        let parts = [
            (0.265, (0.64, 0.33)),
            (0.670, (0.29, 0.60)),
            (0.065, (0.15, 0.06)),
        ]
        .map(|(w, (x, y))| (w, Chroma::from_xy(x, y).unwrap()));
        let white = Chroma::mix(&parts).unwrap();
        assert!((white.x - 1.0 / 3.0).abs() < 5e-3 && (white.y - 1.0 / 3.0).abs() < 5e-3);
        for (args, says) in [
            ("700 400 1 1", "0 < l_min < l_max"),
            ("400 700 0 0", "no visible light"),
            ("400 700 -1 -2", "no visible light"),
            ("400 700 1 x", "value 2: \"x\" is not a number"),
        ] {
            let e = Chroma::from_spectrum(&words(args), &mut |_| ()).unwrap_err();
            assert!(e.contains(says), "{args}: {e}");
        }
        // The noise of a measured spectrum: negative values are taken as 0, with a warning.
        let mut warnings = Vec::new();
        let noisy =
            Chroma::from_spectrum(&words("380 780 1 1 -0.001 1 1"), &mut |w| warnings.push(w))
                .unwrap();
        let clean = Chroma::from_spectrum(&words("380 780 1 1 0 1 1"), &mut |w| panic!("{w}"));
        assert_eq!(Ok(noisy), clean);
        assert_eq!(
            warnings,
            ["cspec: 1 negative value(s) taken as 0 (the first: value 3, -0.001)"]
        );
    }

    #[test]
    fn materials_map_to_strahl_lobes_and_emission_units() {
        let mut warnings = Vec::new();
        let mut warn = |w: String| warnings.push(w);
        let grey = |amount| Component {
            amount,
            color: Chroma::NEUTRAL,
        };
        let m = MgfMaterial {
            one_sided: true,
            rd: grey(0.5),
            rs: (grey(0.04), 0.06),
            ed: grey(LUMINOUS_EFFICACY * std::f64::consts::PI),
            ..MgfMaterial::default()
        };
        let s = to_strahl("paint", &m, &mut warn).unwrap();
        assert!((s.diffuse.g - 0.5).abs() < 1e-6 && (s.specular.r - 0.04).abs() < 1e-6);
        assert!((s.shininess - 100.0).abs() < 1e-3 && s.mirror.is_black());
        // ed = 683·π lm/m² is a radiance of 1 W·sr⁻¹·m⁻² per channel.
        assert!((s.emission.b - 1.0).abs() < 1e-6);
        assert!(s.one_sided && !s.two_sided);
        let glass = MgfMaterial {
            rs: (grey(0.08), 0.0),
            ts: (grey(0.9), 0.0),
            ir: Some((1.52, 0.0)),
            ..MgfMaterial::default()
        };
        let s = to_strahl("glass", &glass, &mut warn).unwrap();
        assert!((s.mirror.r - 0.08).abs() < 1e-6 && (s.transmission.g - 0.9).abs() < 1e-6);
        assert!((s.ior - 1.52).abs() < 1e-6 && !s.one_sided);
        let too_much = MgfMaterial {
            rd: grey(0.7),
            ts: (grey(0.4), 0.1),
            ..MgfMaterial::default()
        };
        // More than 1 in all: every lobe scaled down by the sum, with a warning.
        let s = to_strahl("x", &too_much, &mut warn).unwrap();
        assert!(
            (s.diffuse.g - 0.7 / 1.1).abs() < 1e-6 && (s.transmission.g - 0.4 / 1.1).abs() < 1e-6
        );
        // A saturated red at Y = 0.9 needs more than 1 in red: scaled down, with a warning.
        let red = MgfMaterial {
            rd: Component {
                amount: 0.9,
                color: Chroma::from_xy(0.6, 0.32).unwrap(),
            },
            ..MgfMaterial::default()
        };
        let s = to_strahl("red", &red, &mut warn).unwrap();
        assert!(s.albedo_bound() <= 1.0 + ENERGY_TOLERANCE);
        for says in [
            "\"x\" reflects and transmits more than it receives: rd + td + rs + ts = 1.1",
            "\"red\": its colours give",
        ] {
            assert!(warnings.iter().any(|w| w.contains(says)), "{warnings:?}");
        }
    }
}
