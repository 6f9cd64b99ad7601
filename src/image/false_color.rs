//! False-colour images: a photometric value per pixel (lux or cd·m⁻², [`ValueImage`]) shown
//! on a colour scale from dark blue (the range's low end) through cyan, green and yellow to
//! red (its high end), with isolines where the value crosses evenly spaced levels and a
//! legend to the right: the unit, a colour bar, and the levels' values. Written as 8-bit
//! sRGB PNG; the colours are display colours, not radiance.

use super::error::ImageError;
use super::glyphs::{ADVANCE, Canvas, GLYPH_HEIGHT};
use super::output::{FileFormat, write_png};
use crate::measure::ValueImage;
use std::path::Path;

/// The colour scale's stops (position on the scale, sRGB colour), between which
/// [`scale_colour`] interpolates.
pub const STOPS: [(f32, [u8; 3]); 6] = [
    (0.0, [20, 16, 96]),
    (0.2, [0, 92, 230]),
    (0.4, [0, 190, 190]),
    (0.6, [90, 216, 50]),
    (0.8, [250, 216, 26]),
    (1.0, [216, 26, 12]),
];

/// Where a pixel sees no surface.
const NO_SURFACE: [u8; 3] = [48, 48, 48];
/// The legend's background.
const PANEL: [u8; 3] = [28, 28, 28];
/// The legend's text and tick marks.
const INK: [u8; 3] = [235, 235, 235];
/// Isolines over the image.
const ISOLINE: [u8; 3] = [0, 0, 0];
/// Most isolines accepted.
pub const MAX_ISOLINES: u32 = 50;
/// Width of the legend, pixels at text scale 1.
const LEGEND_WIDTH: u32 = 72;
/// Levels labelled when no isolines are drawn.
const PLAIN_INTERVALS: u32 = 4;

/// How values become colours.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FalseColor {
    /// The values at the scale's low and high ends (lux or cd·m⁻²); values outside take
    /// the end colours. `None`: from 0 to the image's largest value rounded up to 1, 2, 2.5
    /// or 5 times a power of ten.
    pub range: Option<(f32, f32)>,
    /// Isolines drawn at this many levels evenly spaced inside the range (0 to
    /// [`MAX_ISOLINES`]); the legend labels them.
    pub isolines: u32,
}

impl FalseColor {
    /// The range used for `image`: the one asked for, or from 0 to the largest value
    /// rounded up (1 where the image holds nothing above 0).
    pub fn range_for(&self, image: &ValueImage) -> (f32, f32) {
        self.range
            .unwrap_or_else(|| (0.0, nice_ceiling(image.max())))
    }
}

/// The colour at `t` on the scale (0 low end, 1 high end; clamped).
pub fn scale_colour(t: f32) -> [u8; 3] {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let k = STOPS
        .iter()
        .rposition(|s| s.0 <= t)
        .unwrap_or(0)
        .min(STOPS.len() - 2);
    let ((t0, a), (t1, b)) = (STOPS[k], STOPS[k + 1]);
    let f = (t - t0) / (t1 - t0);
    std::array::from_fn(|c| {
        (f32::from(a[c]) + f * (f32::from(b[c]) - f32::from(a[c]))).round() as u8
    })
}

/// `image` in false colour with isolines and, to its right, the legend (72 pixels wide, 144
/// from 240 pixels of height on, where its text is drawn twice as large).
pub fn false_color(image: &ValueImage, settings: &FalseColor) -> Canvas {
    let (low, high) = settings.range_for(image);
    let span = (high - low).max(f32::MIN_POSITIVE);
    let scale = if image.height >= 240 { 2 } else { 1 };
    let legend = LEGEND_WIDTH * scale;
    let mut canvas = Canvas::new(image.width + legend, image.height, PANEL);
    let bands = settings.isolines.min(MAX_ISOLINES) + 1;
    let band =
        |v: f32| (((v - low) / span * bands as f32).floor() as i64).clamp(0, i64::from(bands) - 1);
    for y in 0..image.height {
        for x in 0..image.width {
            let colour = match image.at(x, y) {
                None => NO_SURFACE,
                Some(v) => {
                    let crossed = settings.isolines > 0
                        && [(x + 1, y), (x, y + 1)]
                            .into_iter()
                            .filter_map(|(nx, ny)| image.at(nx, ny))
                            .any(|n| band(n) != band(v));
                    if crossed {
                        ISOLINE
                    } else {
                        scale_colour((v - low) / span)
                    }
                }
            };
            canvas.set(i64::from(x), i64::from(y), colour);
        }
    }
    draw_legend(&mut canvas, image, settings, (low, high), scale);
    canvas
}

/// The legend in the canvas's right `72 × scale` pixels: the unit at the top, the colour
/// bar below it (high end up), a tick on it and a value at the range's ends and at each isoline's
/// level (every [`PLAIN_INTERVALS`]th of the range without isolines), labels that would
/// overlap the one above left out.
fn draw_legend(
    canvas: &mut Canvas,
    image: &ValueImage,
    settings: &FalseColor,
    (low, high): (f32, f32),
    scale: u32,
) {
    let s = i64::from(scale);
    let left = i64::from(image.width) + 4 * s;
    canvas.text(left, 3 * s, image.quantity.unit(), scale, INK);
    let top = 14 * s;
    let bottom = i64::from(image.height) - 1 - 5 * s;
    if bottom <= top {
        return;
    }
    let bar_width = 10 * s;
    let y_of = |t: f32| bottom - ((bottom - top) as f32 * t).round() as i64;
    for y in top..=bottom {
        let t = (bottom - y) as f32 / (bottom - top) as f32;
        canvas.fill(left, y, bar_width as u32, 1, scale_colour(t));
    }
    let intervals = match settings.isolines.min(MAX_ISOLINES) {
        0 => PLAIN_INTERVALS,
        n => n + 1,
    };
    let step = (high - low) / intervals as f32;
    let text_height = i64::from(GLYPH_HEIGHT) * s;
    // The ends first: where levels crowd, theirs are the labels kept.
    let mut levels: Vec<u32> = vec![0, intervals];
    levels.extend(1..intervals);
    let mut labelled: Vec<i64> = Vec::new();
    for k in levels {
        let t = k as f32 / intervals as f32;
        let y = y_of(t);
        // The tick across the bar's right half, so that it does not read as a minus sign.
        canvas.fill(left + bar_width / 2, y, (bar_width / 2) as u32, scale, INK);
        let label_top = (y - text_height / 2).clamp(0, i64::from(canvas.height) - text_height);
        if labelled
            .iter()
            .any(|&l| (l - label_top).abs() < text_height + 2 * s)
        {
            continue;
        }
        labelled.push(label_top);
        let text = level_label(low + step * k as f32, step);
        let text_left = left + bar_width + 3 * s;
        let room = (i64::from(canvas.width) - text_left) / (i64::from(ADVANCE) * s);
        let text: String = text.chars().take(room.max(0) as usize).collect();
        canvas.text(text_left, label_top, &text, scale, INK);
    }
}

/// `value` written with as many decimals as levels `step` apart need (exponent form for
/// very large or very small values).
fn level_label(value: f32, step: f32) -> String {
    let magnitude = value.abs().max(step.abs());
    if magnitude >= 1e6 || (magnitude > 0.0 && magnitude < 1e-3) {
        return format!("{value:.2e}");
    }
    let decimals = if step > 0.0 {
        (1 - step.log10().floor() as i32).clamp(0, 4) as usize
    } else {
        0
    };
    let decimals = if step >= 10.0 { 0 } else { decimals };
    format!("{value:.decimals$}")
}

/// The smallest of 1, 2, 2.5, 5 × 10ᵏ at or above `v`; 1 for `v` ≤ 0: the top of a
/// false-colour range that holds `v`.
pub fn nice_ceiling(v: f32) -> f32 {
    if v.is_nan() || v <= 0.0 || v.is_infinite() {
        return 1.0;
    }
    let power = 10f32.powf(v.log10().floor());
    [1.0, 2.0, 2.5, 5.0, 10.0]
        .into_iter()
        .map(|m| m * power)
        .find(|&c| c >= v * (1.0 - 1e-6))
        .unwrap_or(10.0 * power)
}

/// Writes `image` in false colour with its legend to `path`, which must name a PNG file.
pub fn save_false_color(
    image: &ValueImage,
    settings: &FalseColor,
    path: &Path,
) -> Result<(), ImageError> {
    if FileFormat::from_path(path)? != FileFormat::Png {
        return Err(ImageError::FalseColorNotPng {
            path: path.to_path_buf(),
        });
    }
    let canvas = false_color(image, settings);
    write_png(&canvas.bytes, canvas.width, canvas.height, path)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::Photometric;

    /// A horizontal ramp from 0 at the left to `top` at the right, the last `blank` rows
    /// seeing no surface.
    fn ramp(width: u32, height: u32, top: f32, blank: u32) -> ValueImage {
        let values = (0..height)
            .flat_map(|y| {
                (0..width)
                    .map(move |x| (y < height - blank).then(|| top * x as f32 / (width - 1) as f32))
            })
            .collect();
        ValueImage {
            width,
            height,
            quantity: Photometric::Illuminance,
            values,
        }
    }

    #[test]
    fn the_scale_runs_from_its_first_stop_to_its_last_and_clamps() {
        assert_eq!(scale_colour(0.0), STOPS[0].1);
        assert_eq!(scale_colour(1.0), STOPS[5].1);
        assert_eq!(scale_colour(-3.0), STOPS[0].1);
        assert_eq!(scale_colour(7.0), STOPS[5].1);
        assert_eq!(scale_colour(f32::NAN), STOPS[0].1);
        assert_eq!(scale_colour(0.4), STOPS[2].1);
        // Half-way between two stops, half-way between their colours.
        assert_eq!(scale_colour(0.7), [170, 216, 38]);
    }

    #[test]
    fn the_default_range_ends_at_a_round_value_above_the_largest() {
        for (max, ceiling) in [(0.0, 1.0), (0.7, 1.0), (1.0, 1.0), (1.3, 2.0), (2.2, 2.5)] {
            assert_eq!(nice_ceiling(max), ceiling, "{max}");
        }
        assert_eq!(nice_ceiling(431.0), 500.0);
        assert_eq!(nice_ceiling(7200.0), 10000.0);
        assert_eq!(
            FalseColor::default().range_for(&ramp(8, 2, 431.0, 0)),
            (0.0, 500.0)
        );
        let asked = FalseColor {
            range: Some((10.0, 20.0)),
            isolines: 0,
        };
        assert_eq!(asked.range_for(&ramp(8, 2, 431.0, 0)), (10.0, 20.0));
    }

    #[test]
    fn labels_carry_the_decimals_their_spacing_needs() {
        assert_eq!(level_label(125.0, 25.0), "125");
        assert_eq!(level_label(2.5, 2.5), "2.5");
        assert_eq!(level_label(0.75, 0.25), "0.75");
        assert_eq!(level_label(0.0, 100.0), "0");
        assert_eq!(level_label(2.0e6, 5.0e5), "2.00e6");
        assert_eq!(level_label(2.0e-4, 5.0e-5), "2.00e-4");
    }

    #[test]
    fn isolines_cross_a_ramp_where_it_passes_each_level_and_the_legend_is_drawn() {
        // 0 … 400 lux over 401 pixels, range 0–400: three isolines at 100, 200, 300 lux.
        let image = ramp(401, 60, 400.0, 10);
        let settings = FalseColor {
            range: Some((0.0, 400.0)),
            isolines: 3,
        };
        let canvas = false_color(&image, &settings);
        assert_eq!((canvas.width, canvas.height), (401 + LEGEND_WIDTH, 60));
        let dark: Vec<u32> = (0..401).filter(|&x| canvas.get(x, 20) == ISOLINE).collect();
        assert_eq!(dark, vec![99, 199, 299]);
        // Colours from the scale elsewhere; no surface where nothing is seen.
        assert_eq!(canvas.get(0, 20), STOPS[0].1);
        assert_eq!(canvas.get(400, 20), STOPS[5].1);
        assert_eq!(canvas.get(150, 20), scale_colour(150.0 / 400.0));
        assert_eq!(canvas.get(150, 55), NO_SURFACE);
        // The legend: the bar's ends in the scale's end colours, text in ink.
        let bar_x = 401 + 4 + 2;
        assert_eq!(canvas.get(bar_x, 14), STOPS[5].1);
        assert_eq!(canvas.get(bar_x, 60 - 1 - 5), STOPS[0].1);
        let ink = (401 + 20..canvas.width)
            .flat_map(|x| (0..60).map(move |y| (x, y)))
            .filter(|&(x, y)| canvas.get(x, y) == INK)
            .count();
        assert!(ink > 100, "{ink}");
        // Without isolines none are drawn.
        let plain = false_color(&image, &FalseColor::default());
        assert!((0..401).all(|x| plain.get(x, 20) != ISOLINE));
    }
}
