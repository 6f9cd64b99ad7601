//! Counts per pixel shown as a grey image.

use crate::color::Rgb;
use crate::measure::Film;

/// `counts` (one per pixel, row by row) as a grey image of `width × height`: black = 0,
/// white = the largest count. `None` when the counts do not fill the image.
pub fn count_map(counts: &[u32], width: u32, height: u32) -> Option<Film> {
    let max = counts.iter().copied().max().unwrap_or(0).max(1) as f32;
    let pixels = counts.iter().map(|&c| Rgb::splat(c as f32 / max)).collect();
    Film::from_pixels(width, height, pixels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_largest_count_is_white() {
        let film = count_map(&[0, 2, 4, 1], 2, 2).unwrap();
        assert_eq!(film.pixels()[0], Rgb::splat(0.0));
        assert_eq!(film.pixels()[2], Rgb::splat(1.0));
        assert_eq!(film.pixels()[1], Rgb::splat(0.5));
        assert!(count_map(&[1, 2], 2, 2).is_none());
    }
}
