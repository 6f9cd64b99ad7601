//! A photometric value per pixel: what a false-colour image shows.

use crate::choice::named_values;

/// Which photometric quantity a [`ValueImage`] holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Photometric {
    /// Illuminance on the surface seen, on the side the camera sees, lux (683 lm/W × the
    /// luminance weighting of the irradiance).
    Illuminance,
    /// Luminance of the surface seen (its radiance `B/π` weighted), cd·m⁻².
    Luminance,
}

named_values!(Photometric {
    Photometric::Illuminance = "lux", "Illuminance on the surface seen, lux";
    Photometric::Luminance = "luminance", "Luminance of the surface seen, cd/m²";
});

impl Photometric {
    /// The unit as a legend writes it (ASCII).
    pub fn unit(self) -> &'static str {
        match self {
            Photometric::Illuminance => "lux",
            Photometric::Luminance => "cd/m2",
        }
    }
}

/// One value per pixel, rows from the top: the quantity where the pixel sees a surface,
/// `None` where it sees none.
#[derive(Clone, Debug, PartialEq)]
pub struct ValueImage {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// What the values are.
    pub quantity: Photometric,
    /// Per pixel, row by row: lux or cd·m⁻² (see `quantity`), finite and non-negative.
    pub values: Vec<Option<f32>>,
}

impl ValueImage {
    /// The value at pixel (`x`, `y`), `None` where no surface is seen or outside the image.
    pub fn at(&self, x: u32, y: u32) -> Option<f32> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.values[(y * self.width + x) as usize]
    }

    /// The largest value, 0 when no pixel sees a surface.
    pub fn max(&self) -> f32 {
        self.values.iter().flatten().fold(0.0, |a, &b| a.max(b))
    }
}
