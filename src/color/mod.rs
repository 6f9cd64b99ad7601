//! Linear RGB colour triples used for radiance, irradiance, reflectance and power: one type,
//! [`Color`], over two channel types — [`Rgb`] (`f32`) where images are rendered, [`Rgb64`]
//! (`f64`) where radiosity and reports add up many small terms.
//!
//! All values are linear Rec.709 (sRGB primaries, no transfer curve). The sRGB transfer
//! curve ([`linear_to_srgb`], [`srgb_to_linear`]) is applied only when writing 8-bit images
//! and undone when reading 8-bit textures.

mod spectrum;
mod srgb;
mod standard_spectra;

pub use spectrum::{Band, MAX_WAVELENGTH_NM, MOLAR_PHOTON_ENERGY_NM, Spectrum, SpectrumError};
pub use srgb::{linear_to_srgb, srgb_to_linear};
pub use standard_spectra::StandardSpectrum;

use serde::{Deserialize, Serialize};
use std::ops::{Add, AddAssign, Div, DivAssign, Index, Mul, MulAssign, Neg, Sub, SubAssign};

/// Luminous efficacy used for photometric values: 683 lm/W applied to the luminance `Y`.
pub const LUMINOUS_EFFICACY: f64 = 683.0;

/// A channel type of [`Color`]: `f32` or `f64`.
pub trait Channel:
    Copy
    + PartialEq
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// Zero.
    const ZERO: Self;
    /// One.
    const ONE: Self;
    /// The Rec.709 luminance weights of red, green and blue (they sum to 1).
    const LUMINANCE_WEIGHTS: [Self; 3];
    /// The larger of two values.
    fn max(self, other: Self) -> Self;
    /// True unless NaN or infinite.
    fn is_finite(self) -> bool;
}

impl Channel for f32 {
    const ZERO: f32 = 0.0;
    const ONE: f32 = 1.0;
    const LUMINANCE_WEIGHTS: [f32; 3] = [0.2126, 0.7152, 0.0722];
    #[inline(always)]
    fn max(self, other: f32) -> f32 {
        f32::max(self, other)
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        f32::is_finite(self)
    }
}

impl Channel for f64 {
    const ZERO: f64 = 0.0;
    const ONE: f64 = 1.0;
    const LUMINANCE_WEIGHTS: [f64; 3] = [0.2126, 0.7152, 0.0722];
    #[inline(always)]
    fn max(self, other: f64) -> f64 {
        f64::max(self, other)
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        f64::is_finite(self)
    }
}

/// A linear Rec.709 RGB triple. Its unit depends on use: radiance (W·sr⁻¹·m⁻²),
/// irradiance/radiosity (W·m⁻²), power (W) or a dimensionless reflectance in `[0, 1]`.
/// Serialised as the array `[r, g, b]`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(from = "[T; 3]", into = "[T; 3]")]
#[serde(bound(
    serialize = "T: Channel + Serialize",
    deserialize = "T: Channel + Deserialize<'de>"
))]
pub struct Color<T> {
    /// Red channel.
    pub r: T,
    /// Green channel.
    pub g: T,
    /// Blue channel.
    pub b: T,
}

/// Colour in `f32`, for rendering.
pub type Rgb = Color<f32>;
/// Colour in `f64`, for radiosity and reports.
pub type Rgb64 = Color<f64>;

impl<T: Channel> Color<T> {
    /// All channels zero.
    pub const BLACK: Self = Color::splat(T::ZERO);
    /// All channels one.
    pub const WHITE: Self = Color::splat(T::ONE);

    /// A colour from its three channels.
    pub const fn new(r: T, g: T, b: T) -> Self {
        Color { r, g, b }
    }

    /// The same value in all three channels.
    pub const fn splat(v: T) -> Self {
        Color { r: v, g: v, b: v }
    }

    /// Relative luminance `Y` of linear Rec.709 RGB (same unit as the colour).
    #[inline]
    pub fn luminance(self) -> T {
        let [wr, wg, wb] = T::LUMINANCE_WEIGHTS;
        wr * self.r + wg * self.g + wb * self.b
    }

    /// Largest of the three channels.
    #[inline]
    pub fn max_channel(self) -> T {
        self.r.max(self.g).max(self.b)
    }

    /// True when every channel is exactly zero.
    #[inline]
    pub fn is_black(self) -> bool {
        self.r == T::ZERO && self.g == T::ZERO && self.b == T::ZERO
    }

    /// True when every channel is finite (no NaN or infinity).
    pub fn is_finite(self) -> bool {
        self.r.is_finite() && self.g.is_finite() && self.b.is_finite()
    }

    /// Channel-wise map.
    #[inline]
    pub fn map(self, f: impl Fn(T) -> T) -> Self {
        Color::new(f(self.r), f(self.g), f(self.b))
    }

    /// Channels as an array `[r, g, b]`.
    #[inline]
    pub fn to_array(self) -> [T; 3] {
        [self.r, self.g, self.b]
    }
}

impl Rgb {
    /// Mean of the three channels.
    pub fn mean(self) -> f32 {
        (self.r + self.g + self.b) / 3.0
    }

    /// Channel-wise minimum with `v`.
    pub fn min(self, v: f32) -> Self {
        self.map(|c| c.min(v))
    }

    /// Channels widened to `f64`.
    pub fn to_f64(self) -> Rgb64 {
        Rgb64::new(self.r as f64, self.g as f64, self.b as f64)
    }
}

impl Rgb64 {
    /// Channels narrowed to `f32`.
    pub fn to_f32(self) -> Rgb {
        Rgb::new(self.r as f32, self.g as f32, self.b as f32)
    }
}

impl<T> From<[T; 3]> for Color<T> {
    fn from([r, g, b]: [T; 3]) -> Self {
        Color { r, g, b }
    }
}

impl<T> From<Color<T>> for [T; 3] {
    fn from(c: Color<T>) -> Self {
        [c.r, c.g, c.b]
    }
}

impl<T> Index<usize> for Color<T> {
    type Output = T;
    fn index(&self, i: usize) -> &T {
        match i {
            0 => &self.r,
            1 => &self.g,
            _ => &self.b,
        }
    }
}

impl<T: Channel> Add for Color<T> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Color::new(self.r + o.r, self.g + o.g, self.b + o.b)
    }
}

impl<T: Channel> AddAssign for Color<T> {
    #[inline]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl<T: Channel> Sub for Color<T> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Color::new(self.r - o.r, self.g - o.g, self.b - o.b)
    }
}

impl<T: Channel> SubAssign for Color<T> {
    #[inline]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}

impl<T: Channel> Mul for Color<T> {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        Color::new(self.r * o.r, self.g * o.g, self.b * o.b)
    }
}

impl<T: Channel> MulAssign for Color<T> {
    #[inline]
    fn mul_assign(&mut self, o: Self) {
        *self = *self * o;
    }
}

impl<T: Channel> Mul<T> for Color<T> {
    type Output = Self;
    #[inline]
    fn mul(self, s: T) -> Self {
        Color::new(self.r * s, self.g * s, self.b * s)
    }
}

impl Mul<Rgb> for f32 {
    type Output = Rgb;
    #[inline]
    fn mul(self, c: Rgb) -> Rgb {
        c * self
    }
}

impl Mul<Rgb64> for f64 {
    type Output = Rgb64;
    #[inline]
    fn mul(self, c: Rgb64) -> Rgb64 {
        c * self
    }
}

impl<T: Channel> MulAssign<T> for Color<T> {
    #[inline]
    fn mul_assign(&mut self, s: T) {
        *self = *self * s;
    }
}

impl<T: Channel> Div<T> for Color<T> {
    type Output = Self;
    #[inline]
    fn div(self, s: T) -> Self {
        // One division and three products (within an ulp of three divisions, much cheaper).
        self * (T::ONE / s)
    }
}

impl<T: Channel> DivAssign<T> for Color<T> {
    #[inline]
    fn div_assign(&mut self, s: T) {
        *self = *self / s;
    }
}

impl<T: Channel> std::iter::Sum for Color<T> {
    fn sum<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::BLACK, |a, b| a + b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn luminance_of_white_is_one() {
        assert!((Rgb::WHITE.luminance() - 1.0).abs() < 1e-6);
        assert!((Rgb64::WHITE.luminance() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn arithmetic_is_channel_wise() {
        let a = Rgb::new(1.0, 2.0, 3.0);
        let b = Rgb::new(0.5, 0.25, 2.0);
        assert_eq!(a * b, Rgb::new(0.5, 0.5, 6.0));
        assert_eq!(a + b, Rgb::new(1.5, 2.25, 5.0));
        assert_eq!(a * 2.0, Rgb::new(2.0, 4.0, 6.0));
        assert_eq!(a / 2.0, Rgb::new(0.5, 1.0, 1.5));
        assert_eq!(a.to_f64() - b.to_f64(), Rgb64::new(0.5, 1.75, 1.0));
    }

    #[test]
    fn serialised_as_an_array() {
        let c = Rgb64::new(1.0, 0.5, 0.25);
        let text = serde_json::to_string(&c).unwrap();
        assert_eq!(text, "[1.0,0.5,0.25]");
        assert_eq!(serde_json::from_str::<Rgb64>(&text).unwrap(), c);
    }
}
