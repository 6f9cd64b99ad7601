//! The texture reader (PPM, PGM, PNG, JPEG by content), then lookups on what it read.

#![no_main]

mod common;

use glam::Vec2;
use libfuzzer_sys::fuzz_target;
use strahl::scene::{ColorSpace, MAX_TEXELS, Texture};

fuzz_target!(|data: &[u8]| {
    let path = common::scratch().join("fuzz.ppm");
    std::fs::write(&path, data).expect("cannot write the texture input");
    if let Ok(texture) = Texture::load(&path, ColorSpace::Srgb, MAX_TEXELS) {
        let mean = texture.mean_color();
        assert!(mean.is_finite(), "mean colour {mean:?}");
        for uv in [Vec2::ZERO, Vec2::splat(0.5), Vec2::new(-3.7, 12.25)] {
            let _ = texture.sample(uv);
        }
    }
});
