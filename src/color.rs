//! Linear RGB colour triples used for radiance, irradiance, reflectance and power.
//!
//! All values are linear Rec.709 (sRGB primaries, no transfer curve). The sRGB transfer
//! curve is applied only when writing 8-bit images.

use serde::{Deserialize, Serialize};
use std::ops::{Add, AddAssign, Div, DivAssign, Index, Mul, MulAssign, Sub};

/// Luminous efficacy used for photometric values: 683 lm/W applied to the luminance `Y`.
pub const LUMINOUS_EFFICACY: f64 = 683.0;

/// A linear Rec.709 RGB triple. Its unit depends on use: radiance (W·sr⁻¹·m⁻²),
/// irradiance/radiosity (W·m⁻²), power (W) or a dimensionless reflectance in `[0, 1]`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(from = "[f32; 3]", into = "[f32; 3]")]
pub struct Rgb {
    /// Red channel.
    pub r: f32,
    /// Green channel.
    pub g: f32,
    /// Blue channel.
    pub b: f32,
}

impl Rgb {
    /// All channels zero.
    pub const BLACK: Rgb = Rgb::splat(0.0);
    /// All channels one.
    pub const WHITE: Rgb = Rgb::splat(1.0);

    /// A colour from its three channels.
    pub const fn new(r: f32, g: f32, b: f32) -> Self {
        Rgb { r, g, b }
    }

    /// The same value in all three channels.
    pub const fn splat(v: f32) -> Self {
        Rgb { r: v, g: v, b: v }
    }

    /// Relative luminance `Y` of linear Rec.709 RGB (same unit as the colour).
    pub fn luminance(self) -> f32 {
        0.2126 * self.r + 0.7152 * self.g + 0.0722 * self.b
    }

    /// Largest of the three channels.
    pub fn max_channel(self) -> f32 {
        self.r.max(self.g).max(self.b)
    }

    /// Mean of the three channels.
    pub fn mean(self) -> f32 {
        (self.r + self.g + self.b) / 3.0
    }

    /// True when every channel is exactly zero.
    pub fn is_black(self) -> bool {
        self.r == 0.0 && self.g == 0.0 && self.b == 0.0
    }

    /// True when every channel is finite (no NaN or infinity).
    pub fn is_finite(self) -> bool {
        self.r.is_finite() && self.g.is_finite() && self.b.is_finite()
    }

    /// Channel-wise map.
    pub fn map(self, f: impl Fn(f32) -> f32) -> Self {
        Rgb::new(f(self.r), f(self.g), f(self.b))
    }

    /// Channel-wise minimum with `v`.
    pub fn min(self, v: f32) -> Self {
        self.map(|c| c.min(v))
    }

    /// Channels as an array `[r, g, b]`.
    pub fn to_array(self) -> [f32; 3] {
        [self.r, self.g, self.b]
    }

    /// Channels widened to `f64`.
    pub fn to_f64(self) -> [f64; 3] {
        [self.r as f64, self.g as f64, self.b as f64]
    }
}

impl From<[f32; 3]> for Rgb {
    fn from(a: [f32; 3]) -> Self {
        Rgb::new(a[0], a[1], a[2])
    }
}

impl From<Rgb> for [f32; 3] {
    fn from(c: Rgb) -> Self {
        c.to_array()
    }
}

impl Index<usize> for Rgb {
    type Output = f32;
    fn index(&self, i: usize) -> &f32 {
        match i {
            0 => &self.r,
            1 => &self.g,
            _ => &self.b,
        }
    }
}

impl Add for Rgb {
    type Output = Rgb;
    fn add(self, o: Rgb) -> Rgb {
        Rgb::new(self.r + o.r, self.g + o.g, self.b + o.b)
    }
}

impl AddAssign for Rgb {
    fn add_assign(&mut self, o: Rgb) {
        *self = *self + o;
    }
}

impl Sub for Rgb {
    type Output = Rgb;
    fn sub(self, o: Rgb) -> Rgb {
        Rgb::new(self.r - o.r, self.g - o.g, self.b - o.b)
    }
}

impl Mul for Rgb {
    type Output = Rgb;
    fn mul(self, o: Rgb) -> Rgb {
        Rgb::new(self.r * o.r, self.g * o.g, self.b * o.b)
    }
}

impl MulAssign for Rgb {
    fn mul_assign(&mut self, o: Rgb) {
        *self = *self * o;
    }
}

impl Mul<f32> for Rgb {
    type Output = Rgb;
    fn mul(self, s: f32) -> Rgb {
        Rgb::new(self.r * s, self.g * s, self.b * s)
    }
}

impl Mul<Rgb> for f32 {
    type Output = Rgb;
    fn mul(self, c: Rgb) -> Rgb {
        c * self
    }
}

impl MulAssign<f32> for Rgb {
    fn mul_assign(&mut self, s: f32) {
        *self = *self * s;
    }
}

impl Div<f32> for Rgb {
    type Output = Rgb;
    fn div(self, s: f32) -> Rgb {
        // One division and three products (within an ulp of three divisions, much cheaper).
        self * (1.0 / s)
    }
}

impl DivAssign<f32> for Rgb {
    fn div_assign(&mut self, s: f32) {
        *self = *self / s;
    }
}

impl std::iter::Sum for Rgb {
    fn sum<I: Iterator<Item = Rgb>>(iter: I) -> Rgb {
        iter.fold(Rgb::BLACK, |a, b| a + b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn luminance_of_white_is_one() {
        assert!((Rgb::WHITE.luminance() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn arithmetic_is_channel_wise() {
        let a = Rgb::new(1.0, 2.0, 3.0);
        let b = Rgb::new(0.5, 0.25, 2.0);
        assert_eq!(a * b, Rgb::new(0.5, 0.5, 6.0));
        assert_eq!(a + b, Rgb::new(1.5, 2.25, 5.0));
        assert_eq!(a * 2.0, Rgb::new(2.0, 4.0, 6.0));
        assert_eq!(a / 2.0, Rgb::new(0.5, 1.0, 1.5));
    }
}
