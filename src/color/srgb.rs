//! The sRGB transfer curve and its inverse: linear values to the encoded values of 8-bit
//! images and textures, and back.

/// The sRGB electro-optical transfer function: encoded value in `[0, 1]` to linear.
pub fn srgb_to_linear(v: f32) -> f32 {
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// The sRGB opto-electronic transfer function: display-linear value to encoded value, both
/// in `[0, 1]`. Inputs are clamped to `[0, 1]` first; NaN encodes as 0.
pub fn linear_to_srgb(v: f32) -> f32 {
    if v.is_nan() || v <= 0.0 {
        0.0
    } else if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.min(1.0).powf(1.0 / 2.4) - 0.055
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decoding_matches_reference_points() {
        assert_eq!(srgb_to_linear(0.0), 0.0);
        assert!((srgb_to_linear(1.0) - 1.0).abs() < 1e-6);
        assert!((srgb_to_linear(0.5) - 0.214_041).abs() < 1e-5);
    }

    #[test]
    fn encoding_matches_reference_points() {
        assert_eq!(linear_to_srgb(0.0), 0.0);
        assert!((linear_to_srgb(1.0) - 1.0).abs() < 1e-6);
        assert!((linear_to_srgb(0.214_041) - 0.5).abs() < 1e-5);
        assert!((linear_to_srgb(0.001) - 0.012_92).abs() < 1e-7);
        assert_eq!(linear_to_srgb(-0.5), 0.0);
        assert_eq!(linear_to_srgb(f32::NAN), 0.0);
        assert!((linear_to_srgb(7.0) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn decoding_inverts_encoding() {
        for i in 0..=1000 {
            let v = i as f32 / 1000.0;
            let back = srgb_to_linear(linear_to_srgb(v));
            assert!((back - v).abs() < 1e-5, "{v} -> {back}");
        }
    }
}
