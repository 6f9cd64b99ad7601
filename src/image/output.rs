//! Image files chosen by extension: tone-mapped sRGB PNG, linear OpenEXR and linear PFM.

use super::error::ImageError;
use super::pfm::{read_pfm, write_pfm};
use crate::atomic_file::AtomicFile;
use crate::measure::Film;

use super::tonemap::ToneMapping;
use crate::color::Rgb;
use crate::color::{linear_to_srgb, srgb_to_linear};
use std::path::Path;

/// An image file format, chosen by file extension (case-insensitive).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileFormat {
    /// `.png`: tone-mapped, sRGB-encoded 8-bit RGB.
    Png,
    /// `.exr`: linear 32-bit float RGB radiance, not tone-mapped.
    Exr,
    /// `.pfm`: linear 32-bit float RGB radiance (Portable Float Map), not tone-mapped.
    Pfm,
}

impl FileFormat {
    /// The format named by the extension of `path`; an error names the extension and the
    /// supported ones.
    pub fn from_path(path: &Path) -> Result<FileFormat, ImageError> {
        let extension = path.extension().map(|e| e.to_string_lossy().into_owned());
        match extension.as_deref().map(str::to_ascii_lowercase).as_deref() {
            Some("png") => Ok(FileFormat::Png),
            Some("exr") => Ok(FileFormat::Exr),
            Some("pfm") => Ok(FileFormat::Pfm),
            _ => Err(ImageError::UnsupportedExtension {
                path: path.to_path_buf(),
                extension,
            }),
        }
    }
}

/// Writes `film` to `path` in the format of its extension. Only PNG applies `tone_mapping`;
/// EXR and PFM store the film's linear radiance unchanged.
pub fn save(film: &Film, path: &Path, tone_mapping: &ToneMapping) -> Result<(), ImageError> {
    let format = FileFormat::from_path(path)?;
    if film.pixels().is_empty() {
        return Err(ImageError::EmptyImage {
            path: path.to_path_buf(),
            width: film.width(),
            height: film.height(),
        });
    }
    match format {
        FileFormat::Png => save_png(film, path, tone_mapping),
        FileFormat::Exr => save_exr(film, path),
        FileFormat::Pfm => save_pfm(film, path),
    }
}

/// Reads an image file into a film of linear values: EXR and PFM as stored, PNG decoded
/// from sRGB. The format is chosen by the extension.
pub fn load(path: &Path) -> Result<Film, ImageError> {
    match FileFormat::from_path(path)? {
        FileFormat::Png => load_png(path),
        FileFormat::Exr => load_exr(path),
        FileFormat::Pfm => load_pfm(path),
    }
}

fn save_png(film: &Film, path: &Path, tone_mapping: &ToneMapping) -> Result<(), ImageError> {
    write_png(
        &srgb_bytes(film, tone_mapping),
        film.width(),
        film.height(),
        path,
    )
}

/// `film` tone-mapped by `tone_mapping` as 8-bit sRGB, three bytes per pixel, rows from the
/// top.
fn srgb_bytes(film: &Film, tone_mapping: &ToneMapping) -> Vec<u8> {
    tone_mapping
        .apply(film)
        .into_iter()
        .flat_map(Rgb::to_array)
        .map(|v| (linear_to_srgb(v) * 255.0).round() as u8)
        .collect()
}

/// `film` as the bytes of a PNG file, tone-mapped by `tone_mapping` (what [`save`] writes
/// to a `.png`), for a program that sends it rather than stores it.
pub fn encode_png(film: &Film, tone_mapping: &ToneMapping) -> Result<Vec<u8>, ImageError> {
    let mut out = Vec::new();
    ::image::write_buffer_with_format(
        &mut std::io::Cursor::new(&mut out),
        &srgb_bytes(film, tone_mapping),
        film.width(),
        film.height(),
        ::image::ExtendedColorType::Rgb8,
        ::image::ImageFormat::Png,
    )
    .map_err(|source| ImageError::Png {
        path: "(in memory)".into(),
        source,
    })?;
    Ok(out)
}

/// Writes `bytes` (8-bit sRGB, three per pixel, rows from the top) as a PNG of `width ×
/// height` to `path`, in place of any file there only once it is complete.
pub(super) fn write_png(
    bytes: &[u8],
    width: u32,
    height: u32,
    path: &Path,
) -> Result<(), ImageError> {
    let io_error = |source| ImageError::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut out = AtomicFile::create(path).map_err(io_error)?;
    ::image::write_buffer_with_format(
        &mut out,
        bytes,
        width,
        height,
        ::image::ExtendedColorType::Rgb8,
        ::image::ImageFormat::Png,
    )
    .map_err(|source| ImageError::Png {
        path: path.to_path_buf(),
        source,
    })?;
    out.commit().map_err(io_error)
}

fn load_png(path: &Path) -> Result<Film, ImageError> {
    let png_error = |source| ImageError::Png {
        path: path.to_path_buf(),
        source,
    };
    let decoded = ::image::ImageReader::open(path)
        .map_err(|source| ImageError::Io {
            path: path.to_path_buf(),
            source,
        })?
        .decode()
        .map_err(png_error)?
        .to_rgb32f();
    let mut film = Film::new(decoded.width(), decoded.height());
    for (pixel, encoded) in film.pixels_mut().iter_mut().zip(decoded.pixels()) {
        *pixel = Rgb::new(encoded[0], encoded[1], encoded[2]).map(srgb_to_linear);
    }
    Ok(film)
}

fn save_exr(film: &Film, path: &Path) -> Result<(), ImageError> {
    use exr::prelude::{Encoding, Image, LineOrder, SpecificChannels, Vec2, WritableImage};
    let width = film.width() as usize;
    let channels = SpecificChannels::rgb(|Vec2(x, y): Vec2<usize>| {
        let p = film.pixels()[y * width + x];
        (p.r, p.g, p.b)
    });
    let io_error = |source| ImageError::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut out = AtomicFile::create(path).map_err(io_error)?;
    // The tiles in increasing order: compressed in parallel, they were written in the order
    // they came done, so the same image made files that differed from run to run.
    let encoding = Encoding {
        line_order: LineOrder::Increasing,
        ..Encoding::FAST_LOSSLESS
    };
    Image::from_encoded_channels((width, film.height() as usize), encoding, channels)
        .write()
        .to_buffered(&mut out)
        .map_err(|source| ImageError::Exr {
            path: path.to_path_buf(),
            source,
        })?;
    out.commit().map_err(io_error)
}

fn load_exr(path: &Path) -> Result<Film, ImageError> {
    // OpenEXR sizes are bounded by i32, so they fit u32.
    let image = exr::prelude::read_first_rgba_layer_from_file(
        path,
        |size, _| Film::new(size.width() as u32, size.height() as u32),
        |film: &mut Film, position, (r, g, b, _alpha): (f32, f32, f32, f32)| {
            film.set(position.x() as u32, position.y() as u32, Rgb::new(r, g, b));
        },
    )
    .map_err(|source| ImageError::Exr {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(image.layer_data.channel_data.pixels)
}

fn save_pfm(film: &Film, path: &Path) -> Result<(), ImageError> {
    let io_error = |source| ImageError::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut out = AtomicFile::create(path).map_err(io_error)?;
    write_pfm(film, &mut out).map_err(io_error)?;
    out.commit().map_err(io_error)
}

fn load_pfm(path: &Path) -> Result<Film, ImageError> {
    let bytes = std::fs::read(path).map_err(|source| ImageError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    read_pfm(&bytes).map_err(|reason| ImageError::Pfm {
        path: path.to_path_buf(),
        reason,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image::ToneMap;
    use std::path::PathBuf;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// A temporary file that is removed when dropped.
    struct TempFile(PathBuf);

    impl TempFile {
        fn new(extension: &str) -> Self {
            static COUNTER: AtomicUsize = AtomicUsize::new(0);
            let n = COUNTER.fetch_add(1, Ordering::Relaxed);
            let name = format!("strahl-image-{}-{n}.{extension}", std::process::id());
            TempFile(std::env::temp_dir().join(name))
        }
    }

    impl Drop for TempFile {
        fn drop(&mut self) {
            let _ = std::fs::remove_file(&self.0);
        }
    }

    /// A 5×3 film with distinct HDR values, including values above 1 and tiny ones.
    fn test_film() -> Film {
        let mut film = Film::new(5, 3);
        for y in 0..3 {
            for x in 0..5 {
                let i = (y * 5 + x) as f32;
                film.set(
                    x,
                    y,
                    Rgb::new(0.013 * i, 1.7 + 0.31 * i, 1.0e-4 * (i + 1.0)),
                );
            }
        }
        film
    }

    fn linear(exposure_ev: f32) -> ToneMapping {
        ToneMapping {
            operator: ToneMap::Linear,
            exposure_ev,
        }
    }

    #[test]
    fn exr_round_trip_is_exact() {
        let file = TempFile::new("exr");
        let film = test_film();
        save(&film, &file.0, &linear(-5.0)).expect("write EXR");
        assert_eq!(load(&file.0).expect("read EXR"), film);
    }

    #[test]
    fn an_exr_file_is_the_same_every_time() {
        // Many tiles of 64 × 64 pixels, compressed in parallel.
        let mut film = Film::new(640, 320);
        for y in 0..320 {
            for x in 0..640 {
                film.set(x, y, Rgb::new(x as f32, y as f32, ((x * y) % 7) as f32));
            }
        }
        let bytes = |_| {
            let file = TempFile::new("exr");
            save(&film, &file.0, &linear(0.0)).expect("write EXR");
            std::fs::read(&file.0).expect("read back")
        };
        let first = bytes(0);
        assert!((1..8).all(|k| bytes(k) == first));
        let file = TempFile::new("exr");
        std::fs::write(&file.0, &first).unwrap();
        assert_eq!(load(&file.0).expect("read EXR"), film);
    }

    #[test]
    fn pfm_round_trip_is_exact() {
        let file = TempFile::new("PFM");
        let film = test_film();
        save(&film, &file.0, &linear(-5.0)).expect("write PFM");
        assert_eq!(load(&file.0).expect("read PFM"), film);
    }

    #[test]
    fn png_round_trip_is_within_8_bit_quantisation() {
        let file = TempFile::new("png");
        // Linear tone mapping at 0 EV leaves values in [0, 1] unchanged.
        let mut film = Film::new(64, 2);
        for x in 0..64 {
            let v = x as f32 / 63.0;
            film.set(x, 0, Rgb::new(v, 1.0 - v, v * v));
            film.set(x, 1, Rgb::splat(v * 0.01));
        }
        save(&film, &file.0, &linear(0.0)).expect("write PNG");
        let back = load(&file.0).expect("read PNG");
        assert_eq!((back.width(), back.height()), (64, 2));
        for (a, b) in film.pixels().iter().zip(back.pixels()) {
            for c in 0..3 {
                // Half an 8-bit step in sRGB space, measured in sRGB space.
                let error = (linear_to_srgb(a[c]) - linear_to_srgb(b[c])).abs();
                assert!(error <= 0.5 / 255.0 + 1e-6, "{a:?} came back as {b:?}");
            }
        }
    }

    #[test]
    fn a_png_in_memory_is_the_file_save_writes() {
        let file = TempFile::new("png");
        let film = test_film();
        save(&film, &file.0, &linear(-5.0)).expect("write PNG");
        let bytes = encode_png(&film, &linear(-5.0)).expect("encode PNG");
        assert_eq!(bytes, std::fs::read(&file.0).unwrap());
    }

    #[test]
    fn png_applies_the_tone_mapping() {
        let file = TempFile::new("png");
        let film = Film::from_pixels(2, 1, vec![Rgb::splat(0.25), Rgb::splat(4.0)])
            .expect("2 pixels fit 2×1");
        save(&film, &file.0, &linear(1.0)).expect("write PNG");
        let back = load(&file.0).expect("read PNG");
        // 0.25 × 2 = 0.5 survives to within 8-bit precision; 4 × 2 clamps to 1.
        assert!(
            (back.get(0, 0).g - 0.5).abs() < 0.005,
            "{:?}",
            back.get(0, 0)
        );
        assert_eq!(back.get(1, 0), Rgb::WHITE);
    }

    #[test]
    fn unknown_or_missing_extension_is_an_error_naming_it() {
        let film = test_film();
        let err = save(&film, Path::new("out.tiff"), &linear(0.0)).unwrap_err();
        let message = err.to_string();
        assert!(matches!(err, ImageError::UnsupportedExtension { .. }));
        assert!(
            message.contains("out.tiff") && message.contains("'.tiff'"),
            "{message}"
        );
        assert!(message.contains(".png, .exr, .pfm"), "{message}");
        let message = load(Path::new("picture")).unwrap_err().to_string();
        assert!(message.contains("(none)"), "{message}");
    }

    #[test]
    fn empty_films_and_missing_files_are_errors_naming_the_file() {
        let file = TempFile::new("exr");
        let err = save(&Film::new(0, 4), &file.0, &linear(0.0)).unwrap_err();
        assert!(matches!(
            err,
            ImageError::EmptyImage {
                width: 0,
                height: 4,
                ..
            }
        ));
        for extension in ["png", "exr", "pfm"] {
            let missing = TempFile::new(extension);
            let message = load(&missing.0).unwrap_err().to_string();
            assert!(message.contains(&*missing.0.to_string_lossy()), "{message}");
        }
    }
}
