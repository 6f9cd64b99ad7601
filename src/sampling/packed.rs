//! Integers packed into one string, so that the fixed-point sums of a batch (a render's
//! per-pixel sums, the light model's tallies) travel in JSON in a few bytes each rather than
//! as long decimal numbers: every value a zigzag LEB128 varint
//! (seven bits a byte, low bits first, the sign in the lowest bit, so a magnitude below
//! 2⁶³ takes at most 9 bytes and any `i128` at most 19), the bytes in standard base64
//! (RFC 4648, padded).

/// `values` as one base64 string of zigzag varints.
pub fn pack(values: impl Iterator<Item = i128>) -> String {
    let mut bytes = Vec::new();
    for v in values {
        let mut z = ((v << 1) ^ (v >> 127)) as u128;
        while z >= 0x80 {
            bytes.push((z as u8 & 0x7f) | 0x80);
            z >>= 7;
        }
        bytes.push(z as u8);
    }
    base64::encode(&bytes)
}

/// The values [`pack`] made of `text`; `None` when it is not such a string.
pub fn unpack(text: &str) -> Option<Vec<i128>> {
    let bytes = base64::decode(text).ok()?;
    let mut values = Vec::new();
    let (mut z, mut shift) = (0u128, 0u32);
    for &b in &bytes {
        let bits = u128::from(b & 0x7f);
        if shift >= 128 || (bits << shift) >> shift != bits {
            return None;
        }
        z |= bits << shift;
        shift += 7;
        if b & 0x80 == 0 {
            values.push((z >> 1) as i128 ^ -((z & 1) as i128));
            (z, shift) = (0, 0);
        }
    }
    (shift == 0).then_some(values)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_come_back_as_they_went() {
        let values = [0, 1, -1, 63, -64, 1 << 62, -(1 << 70), i128::MAX, i128::MIN];
        for n in 0..values.len() {
            // Every length, so that every padding of the base64 groups occurs.
            let packed = pack(values[..n].iter().copied());
            assert_eq!(unpack(&packed).unwrap(), values[..n], "{packed}");
        }
        assert_eq!(pack([0, -1, 1].into_iter()), "AAEC");
    }

    #[test]
    fn other_text_is_refused() {
        for text in [
            "A",
            "A===",
            "AA=A",
            "AA==AAAA",
            "gA==",
            "*AAA",
            "////////////////////////////",
        ] {
            assert_eq!(unpack(text), None, "{text}");
        }
    }
}
