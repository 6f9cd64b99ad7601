//! Portable Float Map (PFM) files: linear 32-bit float RGB, rows stored bottom to top.
//!
//! Written as `PF\n{width} {height}\n-1.0\n` followed by little-endian `f32` triples. Read
//! from colour (`PF`) or greyscale (`Pf`) files of either byte order (negative scale: little
//! endian, positive: big endian); the magnitude of the scale is ignored.

use crate::color::Rgb;
use crate::measure::Film;
use std::io::{self, Write};

/// Writes `film` as a little-endian colour PFM.
pub(super) fn write_pfm(film: &Film, out: &mut impl Write) -> io::Result<()> {
    write!(out, "PF\n{} {}\n-1.0\n", film.width(), film.height())?;
    let width = film.width() as usize;
    let mut row_bytes = Vec::with_capacity(width * 12);
    for row in film.pixels().chunks_exact(width.max(1)).rev() {
        row_bytes.clear();
        for p in row {
            for c in p.to_array() {
                row_bytes.extend_from_slice(&c.to_le_bytes());
            }
        }
        out.write_all(&row_bytes)?;
    }
    Ok(())
}

/// Parses a whole PFM file; the error names what is malformed.
pub(super) fn read_pfm(bytes: &[u8]) -> Result<Film, String> {
    let mut header = HeaderReader { bytes, pos: 0 };
    let channels = match header.token()? {
        b"PF" => 3,
        b"Pf" => 1,
        other => {
            return Err(format!(
                "not a PFM file (magic '{}', expected 'PF' or 'Pf')",
                String::from_utf8_lossy(other)
            ));
        }
    };
    let width: u32 = header.number("width")?;
    let height: u32 = header.number("height")?;
    let scale: f32 = header.number("scale")?;
    if scale == 0.0 || !scale.is_finite() {
        return Err(format!(
            "invalid scale {scale} (must be non-zero and finite)"
        ));
    }
    let little_endian = scale < 0.0;
    header.single_whitespace()?;

    let data = &bytes[header.pos..];
    let pixel_count = width as usize * height as usize;
    let expected = pixel_count
        .checked_mul(channels * 4)
        .ok_or_else(|| format!("image {width}×{height} is too large"))?;
    if data.len() < expected {
        return Err(format!(
            "truncated pixel data: {} bytes for {width}×{height}, expected {expected}",
            data.len()
        ));
    }
    let decode = |b: &[u8]| {
        let word = [b[0], b[1], b[2], b[3]];
        if little_endian {
            f32::from_le_bytes(word)
        } else {
            f32::from_be_bytes(word)
        }
    };
    let mut pixels = vec![Rgb::BLACK; pixel_count];
    let row_len = width as usize * channels * 4;
    for (file_row, bytes_of_row) in data[..expected].chunks_exact(row_len.max(1)).enumerate() {
        let y = height as usize - 1 - file_row;
        let target = &mut pixels[y * width as usize..(y + 1) * width as usize];
        for (p, texel) in target
            .iter_mut()
            .zip(bytes_of_row.chunks_exact(channels * 4))
        {
            *p = if channels == 3 {
                Rgb::new(
                    decode(&texel[0..4]),
                    decode(&texel[4..8]),
                    decode(&texel[8..12]),
                )
            } else {
                Rgb::splat(decode(texel))
            };
        }
    }
    Film::from_pixels(width, height, pixels)
        .ok_or_else(|| format!("pixel count does not match {width}×{height}"))
}

/// Reads the whitespace-separated header fields of a PFM file.
struct HeaderReader<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> HeaderReader<'a> {
    /// The next whitespace-delimited token.
    fn token(&mut self) -> Result<&'a [u8], String> {
        while self.pos < self.bytes.len() && self.bytes[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        let start = self.pos;
        while self.pos < self.bytes.len() && !self.bytes[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        if start == self.pos {
            return Err("header ends early".to_string());
        }
        Ok(&self.bytes[start..self.pos])
    }

    /// The next token parsed as a number; `what` names the field in errors.
    fn number<T: std::str::FromStr>(&mut self, what: &str) -> Result<T, String> {
        let token = self.token()?;
        std::str::from_utf8(token)
            .ok()
            .and_then(|s| s.parse().ok())
            .ok_or_else(|| format!("invalid {what} '{}'", String::from_utf8_lossy(token)))
    }

    /// The one whitespace byte that separates the header from the pixel data.
    fn single_whitespace(&mut self) -> Result<(), String> {
        match self.bytes.get(self.pos) {
            Some(b) if b.is_ascii_whitespace() => {
                self.pos += 1;
                Ok(())
            }
            _ => Err("no whitespace between header and pixel data".to_string()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_by_two() -> Film {
        let mut film = Film::new(2, 2);
        film.set(0, 0, Rgb::new(1.0, 2.0, 3.0));
        film.set(1, 0, Rgb::new(4.0, 5.0, 6.0));
        film.set(0, 1, Rgb::new(7.0, 8.0, 9.0));
        film.set(1, 1, Rgb::new(10.0, 11.0, 12.0));
        film
    }

    fn floats(bytes: &[u8]) -> Vec<f32> {
        bytes
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect()
    }

    #[test]
    fn rows_are_written_bottom_to_top_after_the_header() {
        let mut bytes = Vec::new();
        write_pfm(&two_by_two(), &mut bytes).expect("writing to memory");
        let header = b"PF\n2 2\n-1.0\n";
        assert_eq!(&bytes[..header.len()], header);
        let data = floats(&bytes[header.len()..]);
        let expected: Vec<f32> = (7..=12).chain(1..=6).map(|v| v as f32).collect();
        assert_eq!(data, expected);
    }

    #[test]
    fn reading_inverts_writing_exactly() {
        let mut film = two_by_two();
        film.set(1, 1, Rgb::new(1.0e-30, 3.402_823e38, -0.1));
        let mut bytes = Vec::new();
        write_pfm(&film, &mut bytes).expect("writing to memory");
        assert_eq!(read_pfm(&bytes), Ok(film));
    }

    #[test]
    fn big_endian_greyscale_files_are_read() {
        let mut bytes = b"Pf\n1 2\n1.0\n".to_vec();
        bytes.extend_from_slice(&0.25f32.to_be_bytes());
        bytes.extend_from_slice(&0.75f32.to_be_bytes());
        let film = read_pfm(&bytes).expect("valid file");
        assert_eq!(film.get(0, 0), Rgb::splat(0.75));
        assert_eq!(film.get(0, 1), Rgb::splat(0.25));
    }

    #[test]
    fn malformed_files_are_errors() {
        assert!(
            read_pfm(b"P6\n1 1\n255\n")
                .unwrap_err()
                .contains("not a PFM")
        );
        assert!(read_pfm(b"PF\n2 x\n-1.0\n").unwrap_err().contains("height"));
        assert!(read_pfm(b"PF\n1 1\n0\n").unwrap_err().contains("scale"));
        assert!(
            read_pfm(b"PF\n1 1\n-1.0\n\0\0")
                .unwrap_err()
                .contains("truncated")
        );
        assert!(read_pfm(b"PF\n1 1").unwrap_err().contains("ends early"));
    }
}
