//! The film: a rectangle of linear HDR radiance values, one per pixel.

use crate::color::{Rgb, Rgb64};

/// Linear HDR radiance per pixel (W·sr⁻¹·m⁻², linear Rec.709 RGB), row-major, row 0 at the
/// top of the image and column 0 at the left.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    pixels: Vec<Rgb>,
}

impl Film {
    /// A black film of `width × height` pixels.
    pub fn new(width: u32, height: u32) -> Self {
        Film {
            width,
            height,
            pixels: vec![Rgb::BLACK; width as usize * height as usize],
        }
    }

    /// A film from row-major pixels (row 0 on top); `None` when `pixels.len()` is not
    /// `width × height`.
    pub fn from_pixels(width: u32, height: u32, pixels: Vec<Rgb>) -> Option<Self> {
        (pixels.len() == width as usize * height as usize).then_some(Film {
            width,
            height,
            pixels,
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// All pixels, row-major, row 0 on top.
    pub fn pixels(&self) -> &[Rgb] {
        &self.pixels
    }

    /// All pixels for writing, row-major, row 0 on top (e.g. one row per parallel task).
    pub fn pixels_mut(&mut self) -> &mut [Rgb] {
        &mut self.pixels
    }

    /// The radiance at column `x`, row `y` (row 0 on top).
    ///
    /// # Panics
    /// When `x >= width` or `y >= height`, like slice indexing.
    pub fn get(&self, x: u32, y: u32) -> Rgb {
        self.pixels[self.index(x, y)]
    }

    /// Sets the radiance at column `x`, row `y` (row 0 on top).
    ///
    /// # Panics
    /// When `x >= width` or `y >= height`, like slice indexing.
    pub fn set(&mut self, x: u32, y: u32, rgb: Rgb) {
        let i = self.index(x, y);
        self.pixels[i] = rgb;
    }

    /// Mean radiance over all pixels (black for an empty film), accumulated in `f64`.
    pub fn mean(&self) -> Rgb {
        if self.pixels.is_empty() {
            return Rgb::BLACK;
        }
        let sum: Rgb64 = self.pixels.iter().map(|p| p.to_f64()).sum();
        let n = self.pixels.len() as f64;
        sum.map(|c| c / n).to_f32()
    }

    /// Root-mean-square difference to `other` over all pixels and all three channels, in the
    /// films' radiance unit; `None` when the sizes differ. Two empty films differ by 0.
    pub fn rms_difference(&self, other: &Film) -> Option<f64> {
        if self.width != other.width || self.height != other.height {
            return None;
        }
        if self.pixels.is_empty() {
            return Some(0.0);
        }
        let sum_sq: f64 = self
            .pixels
            .iter()
            .zip(&other.pixels)
            .flat_map(|(a, b)| a.to_f64().to_array().into_iter().zip(b.to_f64().to_array()))
            .map(|(a, b)| (a - b) * (a - b))
            .sum();
        Some((sum_sq / (3.0 * self.pixels.len() as f64)).sqrt())
    }

    fn index(&self, x: u32, y: u32) -> usize {
        assert!(
            x < self.width && y < self.height,
            "pixel ({x}, {y}) outside a {}×{} film",
            self.width,
            self.height
        );
        y as usize * self.width as usize + x as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn set_and_get_address_row_major_with_row_zero_on_top() {
        let mut film = Film::new(3, 2);
        film.set(2, 1, Rgb::new(1.0, 2.0, 3.0));
        assert_eq!(film.get(2, 1), Rgb::new(1.0, 2.0, 3.0));
        assert_eq!(film.pixels()[5], Rgb::new(1.0, 2.0, 3.0));
        assert_eq!(film.get(0, 0), Rgb::BLACK);
        assert_eq!(
            (film.width(), film.height(), film.pixels().len()),
            (3, 2, 6)
        );
    }

    #[test]
    fn from_pixels_checks_the_pixel_count() {
        assert!(Film::from_pixels(2, 2, vec![Rgb::WHITE; 3]).is_none());
        let film = Film::from_pixels(2, 2, vec![Rgb::WHITE; 4]).expect("4 pixels fit 2×2");
        assert_eq!(film.get(1, 1), Rgb::WHITE);
    }

    #[test]
    fn mean_averages_every_channel() {
        let film = Film::from_pixels(2, 1, vec![Rgb::new(1.0, 0.0, 4.0), Rgb::new(3.0, 2.0, 0.0)])
            .expect("2 pixels fit 2×1");
        assert_eq!(film.mean(), Rgb::new(2.0, 1.0, 2.0));
        assert_eq!(Film::new(0, 0).mean(), Rgb::BLACK);
    }

    #[test]
    fn rms_difference_is_over_pixels_and_channels() {
        let a = Film::new(2, 1);
        let mut b = Film::new(2, 1);
        // One channel of one pixel differs by 6: sqrt(36 / 6) = sqrt(6).
        b.set(1, 0, Rgb::new(0.0, 6.0, 0.0));
        let rms = a.rms_difference(&b).expect("same size");
        assert!((rms - 6.0f64.sqrt()).abs() < 1e-12, "rms = {rms}");
        assert_eq!(a.rms_difference(&a), Some(0.0));
        assert_eq!(a.rms_difference(&Film::new(1, 2)), None);
    }
}
