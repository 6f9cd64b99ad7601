//! A 5 × 7 pixel font for the few characters a legend needs (digits, `.`, `-`, `e` and the
//! letters of `lux` and `cd/m2`), drawn at an integer scale into an 8-bit RGB buffer.

/// Width of a glyph, pixels at scale 1.
pub const GLYPH_WIDTH: u32 = 5;
/// Height of a glyph, pixels at scale 1.
pub const GLYPH_HEIGHT: u32 = 7;
/// Horizontal advance from one character to the next, pixels at scale 1.
pub const ADVANCE: u32 = GLYPH_WIDTH + 1;

/// The rows of `c`, top first, the leftmost pixel in bit 4; blank for characters it lacks.
fn rows(c: char) -> [u8; 7] {
    match c {
        '0' => [0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E],
        '1' => [0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E],
        '2' => [0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F],
        '3' => [0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E],
        '4' => [0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02],
        '5' => [0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E],
        '6' => [0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E],
        '7' => [0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08],
        '8' => [0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E],
        '9' => [0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C],
        '.' => [0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C],
        '-' => [0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00],
        'e' => [0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E],
        'l' => [0x0C, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E],
        'u' => [0x00, 0x00, 0x11, 0x11, 0x11, 0x13, 0x0D],
        'x' => [0x00, 0x00, 0x11, 0x0A, 0x04, 0x0A, 0x11],
        'c' => [0x00, 0x00, 0x0E, 0x10, 0x10, 0x11, 0x0E],
        'd' => [0x01, 0x01, 0x0D, 0x13, 0x11, 0x11, 0x0F],
        '/' => [0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00],
        'm' => [0x00, 0x00, 0x1A, 0x15, 0x15, 0x11, 0x11],
        _ => [0; 7],
    }
}

/// An 8-bit RGB image, rows from the top.
pub struct Canvas {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// Three bytes per pixel, row by row.
    pub bytes: Vec<u8>,
}

impl Canvas {
    /// A canvas of `width × height` filled with `colour`.
    pub fn new(width: u32, height: u32, colour: [u8; 3]) -> Self {
        Canvas {
            width,
            height,
            bytes: colour.repeat(width as usize * height as usize),
        }
    }

    /// Sets pixel (`x`, `y`) to `colour`; nothing outside the canvas.
    pub fn set(&mut self, x: i64, y: i64, colour: [u8; 3]) {
        if (0..i64::from(self.width)).contains(&x) && (0..i64::from(self.height)).contains(&y) {
            let at = 3 * (y as usize * self.width as usize + x as usize);
            self.bytes[at..at + 3].copy_from_slice(&colour);
        }
    }

    /// The colour of pixel (`x`, `y`), which must lie on the canvas.
    pub fn get(&self, x: u32, y: u32) -> [u8; 3] {
        let at = 3 * (y as usize * self.width as usize + x as usize);
        [self.bytes[at], self.bytes[at + 1], self.bytes[at + 2]]
    }

    /// Fills the rectangle from (`x`, `y`), `w × h` pixels, clipped to the canvas.
    pub fn fill(&mut self, x: i64, y: i64, w: u32, h: u32, colour: [u8; 3]) {
        for dy in 0..i64::from(h) {
            for dx in 0..i64::from(w) {
                self.set(x + dx, y + dy, colour);
            }
        }
    }

    /// Writes `text` with its top left corner at (`x`, `y`), each font pixel `scale × scale`.
    pub fn text(&mut self, x: i64, y: i64, text: &str, scale: u32, colour: [u8; 3]) {
        let s = i64::from(scale);
        for (k, c) in text.chars().enumerate() {
            let left = x + k as i64 * i64::from(ADVANCE) * s;
            for (row, bits) in rows(c).into_iter().enumerate() {
                for column in 0..GLYPH_WIDTH {
                    if bits & (0x10 >> column) != 0 {
                        let (px, py) = (left + i64::from(column) * s, y + row as i64 * s);
                        self.fill(px, py, scale, scale, colour);
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_character_of_a_legend_has_a_glyph_and_they_differ() {
        let characters = "0123456789.-eluxcd/m";
        for c in characters.chars() {
            assert_ne!(rows(c), [0; 7], "{c}");
        }
        for (i, a) in characters.chars().enumerate() {
            for b in characters.chars().skip(i + 1) {
                assert_ne!(rows(a), rows(b), "{a} {b}");
            }
        }
    }

    #[test]
    fn text_is_drawn_at_its_scale_and_clipped_at_the_edge() {
        let mut canvas = Canvas::new(20, 20, [0; 3]);
        canvas.text(0, 0, "1", 2, [255; 3]);
        // The foot of the 1 (row 6: three pixels, columns 1–3) at scale 2: y 12–13, x 2–7.
        assert_eq!(canvas.get(2, 12), [255; 3]);
        assert_eq!(canvas.get(7, 13), [255; 3]);
        assert_eq!(canvas.get(8, 12), [0; 3]);
        // Drawn partly off the canvas: no panic, the part inside is there.
        canvas.text(17, 17, "8", 1, [9; 3]);
        assert_eq!(canvas.get(18, 17), [9; 3]);
    }
}
