//! The sRGB transfer curve for 8-bit output (its inverse lives with the textures).

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
    use crate::scene::srgb_to_linear;

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
