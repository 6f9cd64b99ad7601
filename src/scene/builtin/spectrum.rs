//! Spectra to linear Rec.709 RGB, for the measured data of the built-in scenes.
//!
//! The conversion, for a spectrum `S(λ)` sampled at wavelengths `λᵢ` in nanometres:
//!
//! 1. **CIE XYZ under an equal-energy illuminant.** `X = Σ wᵢ S(λᵢ) x̄(λᵢ) / Σ wᵢ ȳ(λᵢ)` (and
//!    likewise `Y`, `Z`), with trapezoid weights `wᵢ` and the CIE 1931 2° colour matching
//!    functions `x̄, ȳ, z̄` of the multi-lobe analytic fit of Wyman, Sloan & Shirley (2013),
//!    "Simple Analytic Approximations to the CIE XYZ Color Matching Functions", JCGT 2(2).
//!    The division by `Σ wᵢ ȳ(λᵢ)` makes a spectrum of constant 1 give `Y = 1`, so a
//!    reflectance spectrum gives the reflected fraction of luminance.
//! 2. **Chromatic adaptation** with the Bradford transform from the white of illuminant E to
//!    the D65 white of Rec.709. The source white is the XYZ of a constant-1 spectrum on the
//!    same wavelengths (illuminant E seen through the same truncated range and fitted
//!    matching functions), so a flat spectrum `c` maps exactly onto D65 white times `c`.
//! 3. **XYZ → linear Rec.709**, with the matrix derived from the Rec.709 primaries
//!    (0.64, 0.33), (0.30, 0.60), (0.15, 0.06) and the D65 white point (0.3127, 0.3290).
//!
//! Hence a flat spectrum `c` gives the grey `(c, c, c)` up to rounding.

use crate::color::Rgb;
use glam::{DMat3, DVec3};

/// One lobe of the Wyman–Sloan–Shirley fit: a Gaussian around `mu` (nm) with standard
/// deviation `sigma_below` left of the peak and `sigma_above` right of it.
fn lobe(lambda_nm: f64, mu: f64, sigma_below: f64, sigma_above: f64) -> f64 {
    let sigma = if lambda_nm < mu {
        sigma_below
    } else {
        sigma_above
    };
    let t = (lambda_nm - mu) / sigma;
    (-0.5 * t * t).exp()
}

/// The CIE 1931 2° colour matching functions `[x̄, ȳ, z̄]` at `lambda_nm` nanometres, from
/// the multi-lobe fit of Wyman, Sloan & Shirley (2013), equation 2 (peak `ȳ(555 nm) ≈ 1`).
pub fn color_matching(lambda_nm: f64) -> [f64; 3] {
    let l = lambda_nm;
    let x = 1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7)
        - 0.065 * lobe(l, 501.1, 20.4, 26.2);
    let y = 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1);
    let z = 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8);
    [x, y, z]
}

/// Trapezoid integration weights (nm) for increasing wavelengths.
fn trapezoid_weights(wavelengths_nm: &[f64]) -> Vec<f64> {
    let n = wavelengths_nm.len();
    (0..n)
        .map(|i| {
            let lo = wavelengths_nm[i.saturating_sub(1)];
            let hi = wavelengths_nm[(i + 1).min(n - 1)];
            0.5 * (hi - lo)
        })
        .collect()
}

/// XYZ of the spectrum `samples` (`(wavelength nm, value)`, strictly increasing wavelengths)
/// under an equal-energy illuminant, normalised so that the constant spectrum 1 on the same
/// wavelengths has `Y = 1`. Errors when there are fewer than two samples, a value is not
/// finite or the wavelengths do not increase.
pub fn spectrum_to_xyz(samples: &[(f64, f64)]) -> Result<[f64; 3], String> {
    if samples.len() < 2 {
        return Err(format!(
            "a spectrum needs at least 2 samples, got {}",
            samples.len()
        ));
    }
    if samples
        .iter()
        .any(|&(l, v)| !l.is_finite() || !v.is_finite())
    {
        return Err("a spectrum sample is not a finite number".into());
    }
    if samples.windows(2).any(|w| w[1].0 <= w[0].0) {
        return Err("spectrum wavelengths must increase strictly".into());
    }
    let wavelengths: Vec<f64> = samples.iter().map(|s| s.0).collect();
    let weights = trapezoid_weights(&wavelengths);
    let mut xyz = [0.0; 3];
    let mut y_norm = 0.0;
    for (&(lambda, value), w) in samples.iter().zip(weights) {
        let cmf = color_matching(lambda);
        for (acc, c) in xyz.iter_mut().zip(cmf) {
            *acc += w * value * c;
        }
        y_norm += w * cmf[1];
    }
    Ok(xyz.map(|v| v / y_norm))
}

/// The Bradford cone-response matrix (rows map XYZ to the sharpened LMS responses).
fn bradford() -> DMat3 {
    DMat3::from_cols_array(&[
        0.8951, -0.7502, 0.0389, // column 1
        0.2664, 1.7135, -0.0685, // column 2
        -0.1614, 0.0367, 1.0296, // column 3
    ])
}

/// XYZ of the colour with chromaticity `(x, y)` and luminance `Y = 1`.
fn xyz_from_chromaticity(x: f64, y: f64) -> DVec3 {
    DVec3::new(x / y, 1.0, (1.0 - x - y) / y)
}

/// The D65 white point of Rec.709, `Y = 1`.
fn d65() -> DVec3 {
    xyz_from_chromaticity(0.3127, 0.3290)
}

/// The Bradford chromatic adaptation matrix taking colours seen under white `from` to the
/// corresponding colours under white `to` (both XYZ).
fn bradford_adaptation(from: DVec3, to: DVec3) -> DMat3 {
    let m = bradford();
    let scale = (m * to) / (m * from);
    m.inverse() * DMat3::from_diagonal(scale) * m
}

/// The matrix from XYZ (D65 white) to linear Rec.709 RGB, derived from the primaries.
fn xyz_to_rec709() -> DMat3 {
    let primaries = DMat3::from_cols(
        xyz_from_chromaticity(0.64, 0.33),
        xyz_from_chromaticity(0.30, 0.60),
        xyz_from_chromaticity(0.15, 0.06),
    );
    let scale = primaries.inverse() * d65();
    (primaries * DMat3::from_diagonal(scale)).inverse()
}

/// Linear Rec.709 RGB of the spectrum `samples` (`(wavelength nm, value)`): XYZ under an
/// equal-energy illuminant ([`spectrum_to_xyz`]), Bradford-adapted from that illuminant's
/// white to D65, then converted to Rec.709. A reflectance spectrum gives an RGB reflectance;
/// an emission spectrum gives a relative RGB radiance (rescale it as needed). Channels can be
/// slightly negative for colours outside the Rec.709 gamut.
pub fn spectrum_to_rgb(samples: &[(f64, f64)]) -> Result<Rgb, String> {
    let xyz = DVec3::from(spectrum_to_xyz(samples)?);
    let flat: Vec<(f64, f64)> = samples.iter().map(|&(l, _)| (l, 1.0)).collect();
    let white = DVec3::from(spectrum_to_xyz(&flat)?);
    let rgb = xyz_to_rec709() * bradford_adaptation(white, d65()) * xyz;
    Ok(Rgb::new(rgb.x as f32, rgb.y as f32, rgb.z as f32))
}

/// The piecewise-linear spectrum through `points` (`(wavelength nm, value)`, increasing
/// wavelengths) sampled at `wavelengths_nm`; outside the points the end values are held.
/// Errors when `points` is empty.
pub fn resample_linear(
    points: &[(f64, f64)],
    wavelengths_nm: &[f64],
) -> Result<Vec<(f64, f64)>, String> {
    let (first, last) = match (points.first(), points.last()) {
        (Some(f), Some(l)) => (*f, *l),
        _ => return Err("cannot resample an empty spectrum".into()),
    };
    Ok(wavelengths_nm
        .iter()
        .map(|&lambda| {
            let value = if lambda <= first.0 {
                first.1
            } else if lambda >= last.0 {
                last.1
            } else {
                let i = points.partition_point(|p| p.0 <= lambda);
                let (a, b) = (points[i - 1], points[i]);
                a.1 + (b.1 - a.1) * (lambda - a.0) / (b.0 - a.0)
            };
            (lambda, value)
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid() -> Vec<f64> {
        (0..76).map(|i| 400.0 + 4.0 * i as f64).collect()
    }

    #[test]
    fn flat_spectrum_gives_equal_grey() {
        for c in [0.0, 0.18, 0.5, 0.8, 1.0] {
            let s: Vec<(f64, f64)> = grid().into_iter().map(|l| (l, c)).collect();
            let rgb = spectrum_to_rgb(&s).unwrap();
            for ch in rgb.to_array() {
                assert!((ch as f64 - c).abs() < 1e-3, "c = {c}: {rgb:?}");
            }
        }
    }

    #[test]
    fn color_matching_fit_matches_cie_table_at_reference_wavelengths() {
        // CIE 1931 2° table values; the fit is accurate to about 0.02 near the peaks.
        let table = [
            (450.0, [0.3362, 0.0380, 1.7721]),
            (555.0, [0.5121, 1.0000, 0.0057]),
            (600.0, [1.0622, 0.6310, 0.0008]),
        ];
        for (lambda, expected) in table {
            let got = color_matching(lambda);
            for (g, e) in got.iter().zip(expected) {
                assert!((g - e).abs() < 0.03, "{lambda} nm: {got:?} vs {expected:?}");
            }
        }
    }

    #[test]
    fn rec709_matrix_maps_d65_to_white_and_red_primary_to_red() {
        let m = xyz_to_rec709();
        let white = m * d65();
        assert!((white - DVec3::ONE).abs().max_element() < 1e-12);
        // Published sRGB matrix, first row: 3.2404542, −1.5371385, −0.4985314.
        let row = m.row(0);
        assert!(
            (row - DVec3::new(3.2404542, -1.5371385, -0.4985314))
                .abs()
                .max_element()
                < 2e-3
        );
    }

    #[test]
    fn bradford_adaptation_maps_source_white_to_destination_white() {
        let e = DVec3::ONE;
        let adapted = bradford_adaptation(e, d65()) * e;
        assert!((adapted - d65()).abs().max_element() < 1e-12);
    }

    #[test]
    fn resampling_interpolates_linearly_and_holds_ends() {
        let points = [(400.0, 0.0), (500.0, 8.0), (600.0, 15.6), (700.0, 18.4)];
        let s = resample_linear(&points, &[380.0, 400.0, 452.0, 548.0, 700.0, 720.0]).unwrap();
        let values: Vec<f64> = s.iter().map(|p| p.1).collect();
        let expected = [0.0, 0.0, 4.16, 11.648, 18.4, 18.4];
        for (v, e) in values.iter().zip(expected) {
            assert!((v - e).abs() < 1e-9, "{values:?}");
        }
        assert!(resample_linear(&[], &[500.0]).is_err());
    }

    #[test]
    fn bad_spectra_are_errors() {
        assert!(spectrum_to_rgb(&[(500.0, 1.0)]).is_err());
        assert!(spectrum_to_rgb(&[(500.0, 1.0), (500.0, 1.0)]).is_err());
        assert!(spectrum_to_rgb(&[(500.0, f64::NAN), (510.0, 1.0)]).is_err());
    }
}
