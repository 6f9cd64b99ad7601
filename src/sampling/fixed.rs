//! Fixed-point conversions for sums that must not depend on the order of addition: a value
//! scaled to the sum's units and rounded to an `i128`, so that integer sums of samples or
//! photons are the same however the work was split or scheduled.

/// Magnitude below which a fixed-point value fits an `i64` (2⁶³ with room to spare).
const FITS_I64: f64 = 9.0e18;

/// `x` (already in fixed-point units) rounded to the nearest integer, as `round() as i128`
/// does (saturating beyond `i128`'s range); through `i64` (one machine instruction instead of
/// a library call) whenever the value fits, which a single sample or photon almost always
/// does.
#[inline]
pub fn to_fixed(x: f64) -> i128 {
    let r = x.round();
    if r.abs() < FITS_I64 {
        r as i64 as i128
    } else {
        r as i128
    }
}

/// `q as f64` (fixed-point units, rounded to the nearest `f64`), through `i64` whenever it
/// fits (the same rounding, without a library call).
#[inline]
pub fn from_fixed(q: i128) -> f64 {
    match i64::try_from(q) {
        Ok(v) => v as f64,
        Err(_) => q as f64,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed_point_conversions_match_the_wide_ones() {
        let mut x = 0.37f64;
        for _ in 0..2000 {
            for v in [x, -x, x + 0.5, (x * 1e3).floor() + 0.5] {
                assert_eq!(to_fixed(v), v.round() as i128, "{v}");
                let q = v.round() as i128;
                assert_eq!(from_fixed(q).to_bits(), (q as f64).to_bits(), "{q}");
            }
            x *= 1.037;
        }
        assert!(x > 1e30, "the values cover more than i64's range");
    }
}
