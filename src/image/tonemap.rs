//! Tone mapping: HDR radiance on a [`Film`] to display-linear values in `[0, 1]`.
//!
//! Operators that work on luminance (`log`, `reinhard`) scale each pixel's colour by the
//! ratio of mapped to original luminance, which keeps hue. Pixels whose luminance is zero,
//! negative or not finite, and pixels with a non-finite channel, are shown black; every
//! output channel is clamped to `[0, 1]`.

use crate::color::Rgb;
use crate::measure::Film;

/// The Reinhard (2002) key value: the display luminance of a log-average-luminance pixel
/// before compression.
pub const REINHARD_KEY: f32 = 0.18;

/// A tone-mapping operator.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ToneMap {
    /// Radiance × 2^EV, clamped.
    Linear,
    /// Luminance `Ld = ln(1 + L·2^EV) / ln(1 + Lmax·2^EV)`, `Lmax` the largest luminance.
    Logarithmic,
    /// Global Reinhard (2002): luminance scaled by key 0.18 / log-average luminance and by
    /// 2^EV, then compressed with `L / (1 + L)`. The log-average is taken over pixels with
    /// positive luminance, so black backgrounds do not brighten the rest.
    Reinhard,
    /// Automatic exposure ("average metering"): the image is scaled so that its log-average
    /// luminance (over pixels with positive luminance) becomes the middle grey 0.18, then
    /// × 2^EV, clamped. Light sources saturate instead of darkening the image, whatever share
    /// of the image they cover; a black image stays black.
    #[default]
    Auto,
}

crate::choice::named_values!(ToneMap {
    ToneMap::Linear = "linear", "Radiance × 2^EV, clamped";
    ToneMap::Logarithmic = "log", "Logarithmic luminance up to the brightest pixel";
    ToneMap::Reinhard = "reinhard", "Global Reinhard (2002), key 0.18";
    ToneMap::Auto = "auto", "Automatic exposure: log-average luminance to middle grey 0.18, clamped";
});

/// A tone-mapping operator with an exposure adjustment.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ToneMapping {
    /// The operator.
    pub operator: ToneMap,
    /// Exposure compensation in stops: radiance is scaled by `2^exposure_ev` (0 = none).
    pub exposure_ev: f32,
}

impl ToneMapping {
    /// Display-linear colours in `[0, 1]` (not yet sRGB-encoded), one per film pixel in the
    /// film's order.
    pub fn apply(&self, film: &Film) -> Vec<Rgb> {
        let exposure = self.exposure_ev.exp2();
        let pixels = film.pixels();
        let mapped: Vec<Rgb> = match self.operator {
            ToneMap::Linear => pixels
                .iter()
                .map(|&c| finite_or_black(c) * exposure)
                .collect(),
            ToneMap::Logarithmic => logarithmic(pixels, exposure),
            ToneMap::Reinhard => reinhard(pixels, exposure),
            ToneMap::Auto => auto_exposure(pixels, exposure),
        };
        mapped.into_iter().map(clamp_unit).collect()
    }
}

/// Luminance usable for statistics and ratios: positive and finite, else `None`.
fn usable_luminance(c: Rgb) -> Option<f32> {
    let l = c.luminance();
    (l > 0.0 && l.is_finite()).then_some(l)
}

/// `c` rescaled so that its luminance becomes `f(luminance)`; black when `c` has no usable
/// luminance.
fn scale_luminance(c: Rgb, f: impl Fn(f32) -> f32) -> Rgb {
    match usable_luminance(c) {
        Some(l) => c * (f(l) / l),
        None => Rgb::BLACK,
    }
}

fn logarithmic(pixels: &[Rgb], exposure: f32) -> Vec<Rgb> {
    let l_max = pixels
        .iter()
        .filter_map(|&c| usable_luminance(c))
        .fold(0.0f32, f32::max);
    let denominator = (l_max * exposure).ln_1p();
    if !(denominator > 0.0 && denominator.is_finite()) {
        return vec![Rgb::BLACK; pixels.len()];
    }
    pixels
        .iter()
        .map(|&c| scale_luminance(c, |l| (l * exposure).ln_1p() / denominator))
        .collect()
}

/// Log-average of the usable luminances (black pixels do not pull the key towards zero);
/// `None` when there are none.
fn log_average_luminance(pixels: &[Rgb]) -> Option<f64> {
    let (sum, count) = pixels
        .iter()
        .filter_map(|&c| usable_luminance(c))
        .fold((0.0f64, 0usize), |(s, n), l| (s + (l as f64).ln(), n + 1));
    (count > 0).then(|| (sum / count as f64).exp())
}

fn reinhard(pixels: &[Rgb], exposure: f32) -> Vec<Rgb> {
    let Some(l_avg) = log_average_luminance(pixels) else {
        return vec![Rgb::BLACK; pixels.len()];
    };
    let scale = (REINHARD_KEY as f64 / l_avg) as f32 * exposure;
    pixels
        .iter()
        .map(|&c| {
            scale_luminance(c, |l| {
                let scaled = l * scale;
                scaled / (1.0 + scaled)
            })
        })
        .collect()
}

fn auto_exposure(pixels: &[Rgb], exposure: f32) -> Vec<Rgb> {
    let Some(l_avg) = log_average_luminance(pixels) else {
        return vec![Rgb::BLACK; pixels.len()];
    };
    let scale = (REINHARD_KEY as f64 / l_avg) as f32 * exposure;
    pixels.iter().map(|&c| finite_or_black(c) * scale).collect()
}

/// `c` itself when all its channels are finite, else black.
fn finite_or_black(c: Rgb) -> Rgb {
    if c.is_finite() { c } else { Rgb::BLACK }
}

/// Every channel clamped to `[0, 1]`; NaN becomes 0.
fn clamp_unit(c: Rgb) -> Rgb {
    c.map(|v| if v > 0.0 { v.min(1.0) } else { 0.0 })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn film(pixels: Vec<Rgb>) -> Film {
        Film::from_pixels(pixels.len() as u32, 1, pixels).expect("one row")
    }

    fn mapping(operator: ToneMap, exposure_ev: f32) -> ToneMapping {
        ToneMapping {
            operator,
            exposure_ev,
        }
    }

    fn assert_close(a: Rgb, b: Rgb, tol: f32) {
        let ok = (a.r - b.r).abs() <= tol && (a.g - b.g).abs() <= tol && (a.b - b.b).abs() <= tol;
        assert!(ok, "{a:?} differs from {b:?} by more than {tol}");
    }

    #[test]
    fn linear_plus_one_ev_doubles_and_clamps() {
        let f = film(vec![Rgb::new(0.1, 0.2, 0.3), Rgb::new(0.4, 0.6, -1.0)]);
        let out = mapping(ToneMap::Linear, 1.0).apply(&f);
        assert_close(out[0], Rgb::new(0.2, 0.4, 0.6), 1e-7);
        assert_close(out[1], Rgb::new(0.8, 1.0, 0.0), 1e-7);
        let out = mapping(ToneMap::Linear, 0.0).apply(&f);
        assert_close(out[0], Rgb::new(0.1, 0.2, 0.3), 1e-7);
    }

    #[test]
    fn logarithmic_maps_the_brightest_to_one_and_black_to_zero() {
        let f = film(vec![Rgb::splat(0.0), Rgb::splat(3.0), Rgb::splat(15.0)]);
        let out = mapping(ToneMap::Logarithmic, 0.0).apply(&f);
        assert_eq!(out[0], Rgb::BLACK);
        assert_close(out[2], Rgb::WHITE, 1e-6);
        // ln(1 + 3) / ln(1 + 15) = 0.5 for a grey pixel.
        assert_close(out[1], Rgb::splat(0.5), 1e-6);
        // +1 EV: ln(1 + 6) / ln(1 + 30).
        let out = mapping(ToneMap::Logarithmic, 1.0).apply(&f);
        assert_close(out[1], Rgb::splat(7.0f32.ln() / 31.0f32.ln()), 1e-6);
        assert_close(out[2], Rgb::WHITE, 1e-6);
    }

    #[test]
    fn logarithmic_keeps_the_colour_ratio() {
        let f = film(vec![Rgb::new(1.0, 2.0, 0.5), Rgb::splat(100.0)]);
        let out = mapping(ToneMap::Logarithmic, 0.0).apply(&f);
        assert!((out[0].g / out[0].r - 2.0).abs() < 1e-5, "{:?}", out[0]);
        assert!((out[0].b / out[0].r - 0.5).abs() < 1e-5, "{:?}", out[0]);
    }

    #[test]
    fn reinhard_maps_the_log_average_pixel_to_key_over_one_plus_key() {
        // Usable luminances 1, 2, 4: log-average 2. The black pixel is excluded.
        let f = film(vec![
            Rgb::splat(1.0),
            Rgb::splat(2.0),
            Rgb::splat(4.0),
            Rgb::BLACK,
        ]);
        let out = mapping(ToneMap::Reinhard, 0.0).apply(&f);
        assert_close(out[1], Rgb::splat(0.18 / 1.18), 1e-6);
        assert_close(out[2], Rgb::splat(0.36 / 1.36), 1e-6);
        assert_eq!(out[3], Rgb::BLACK);
        let out = mapping(ToneMap::Reinhard, 1.0).apply(&f);
        assert_close(out[1], Rgb::splat(0.36 / 1.36), 1e-6);
    }

    #[test]
    fn auto_puts_the_log_average_at_middle_grey() {
        // Luminances 1, 2 and 4 (log-average 2) plus black pixels that do not count.
        let f = film(vec![
            Rgb::splat(1.0),
            Rgb::splat(2.0),
            Rgb::splat(4.0),
            Rgb::BLACK,
        ]);
        let out = mapping(ToneMap::Auto, 0.0).apply(&f);
        assert_close(out[1], Rgb::splat(0.18), 1e-6);
        assert_close(out[2], Rgb::splat(0.36), 1e-6);
        assert_eq!(out[3], Rgb::BLACK);
        let out = mapping(ToneMap::Auto, -1.0).apply(&f);
        assert_close(out[1], Rgb::splat(0.09), 1e-6);
    }

    #[test]
    fn auto_is_hardly_moved_by_a_bright_light() {
        // 199 pixels of luminance 1 and one light of 1e6: the log-average is 1e6^(1/200) ≈
        // 1.07, so the rest stays within 7 % of middle grey and the light saturates.
        let mut pixels = vec![Rgb::WHITE; 199];
        pixels.push(Rgb::splat(1.0e6));
        let out = mapping(ToneMap::Auto, 0.0).apply(&film(pixels));
        let expected = 0.18 / 1.0e6f32.powf(1.0 / 200.0);
        assert_close(out[0], Rgb::splat(expected), 1e-5);
        assert_close(out[199], Rgb::WHITE, 0.0);
    }

    #[test]
    fn black_and_invalid_pixels_stay_black_without_nan() {
        let black = film(vec![Rgb::BLACK; 4]);
        let odd = film(vec![
            Rgb::BLACK,
            Rgb::splat(f32::NAN),
            Rgb::new(-1.0, 0.0, 0.0),
            Rgb::splat(f32::INFINITY),
            Rgb::splat(0.5),
        ]);
        for op in [
            ToneMap::Linear,
            ToneMap::Logarithmic,
            ToneMap::Reinhard,
            ToneMap::Auto,
        ] {
            for ev in [-2.0, 0.0, 3.0] {
                let out = mapping(op, ev).apply(&black);
                assert!(out.iter().all(|&c| c == Rgb::BLACK), "{op:?} {ev}: {out:?}");
                let out = mapping(op, ev).apply(&odd);
                assert!(
                    out.iter()
                        .all(|c| c.to_array().iter().all(|v| (0.0..=1.0).contains(v))),
                    "{op:?} {ev}: {out:?}"
                );
                assert_eq!(out[0], Rgb::BLACK, "{op:?} {ev}");
                assert_eq!(out[1], Rgb::BLACK, "{op:?} {ev}");
                assert_eq!(out[3], Rgb::BLACK, "{op:?} {ev}");
                assert!(out[4].r > 0.0, "{op:?} {ev}: {out:?}");
            }
        }
    }

    #[test]
    fn command_line_names() {
        use crate::choice::Choice;
        let names: Vec<&str> = ToneMap::VALUES.iter().map(|v| v.1).collect();
        assert_eq!(names, ["linear", "log", "reinhard", "auto"]);
        assert_eq!("log".parse(), Ok(ToneMap::Logarithmic));
    }
}
