//! Value types of the scene format with two spellings: a triple that may be written as one
//! number, and a texture that may be written as a path or as a table.

use serde::de::{self, Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};
use std::fmt;

/// Three numbers, written `[a, b, c]` or as one number `s` meaning `[s, s, s]` (colours and
/// scale factors).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Triple(pub [f32; 3]);

impl<'de> Deserialize<'de> for Triple {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(TripleVisitor)
    }
}

struct TripleVisitor;

impl<'de> Visitor<'de> for TripleVisitor {
    type Value = Triple;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a number or an array of 3 numbers")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Triple, E> {
        Ok(Triple([v as f32; 3]))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Triple, E> {
        Ok(Triple([v as f32; 3]))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Triple, E> {
        Ok(Triple([v as f32; 3]))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Triple, A::Error> {
        let mut out = [0.0f32; 3];
        for (i, slot) in out.iter_mut().enumerate() {
            *slot = seq
                .next_element()?
                .ok_or_else(|| de::Error::invalid_length(i, &self))?;
        }
        let mut count = 3;
        while seq.next_element::<de::IgnoredAny>()?.is_some() {
            count += 1;
        }
        if count > 3 {
            return Err(de::Error::invalid_length(count, &self));
        }
        Ok(Triple(out))
    }
}

/// Exactly `N` values written as an array (`toml` alone accepts longer arrays for Rust
/// arrays, silently dropping the rest).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Exact<T, const N: usize>(pub [T; N]);

impl<T: Copy + Default, const N: usize> Default for Exact<T, N> {
    fn default() -> Self {
        Exact([T::default(); N])
    }
}

impl<'de, T: Deserialize<'de> + Copy + Default, const N: usize> Deserialize<'de> for Exact<T, N> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_seq(ExactVisitor::<T, N>(std::marker::PhantomData))
    }
}

struct ExactVisitor<T, const N: usize>(std::marker::PhantomData<T>);

impl<'de, T: Deserialize<'de> + Copy + Default, const N: usize> Visitor<'de>
    for ExactVisitor<T, N>
{
    type Value = Exact<T, N>;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "an array of {N} elements")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Exact<T, N>, A::Error> {
        let mut out = [T::default(); N];
        for (i, slot) in out.iter_mut().enumerate() {
            *slot = seq
                .next_element()?
                .ok_or_else(|| de::Error::invalid_length(i, &self))?;
        }
        let mut count = N;
        while seq.next_element::<de::IgnoredAny>()?.is_some() {
            count += 1;
        }
        if count > N {
            return Err(de::Error::invalid_length(count, &self));
        }
        Ok(Exact(out))
    }
}

/// Three coordinates `[x, y, z]`.
pub(super) type Coords = Exact<f32, 3>;

/// How a texture's 8-bit values are decoded, as written in a scene file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum ColorSpaceName {
    /// Value / 255.
    Linear,
    /// The sRGB transfer curve.
    Srgb,
}

/// What a texture shows outside `[0, 1]²`, as written in a scene file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum WrapName {
    /// The image repeats.
    #[default]
    Repeat,
    /// The edge texels extend outwards.
    Clamp,
}

/// A texture reference: `"path"` or
/// `{ file = "path", colorspace = "linear" | "srgb", wrap = "repeat" | "clamp" }`.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct TextureEntry {
    /// Image path, relative to the scene file.
    pub file: String,
    /// Explicit colour space; `None` means the default for the file type.
    pub colorspace: Option<ColorSpaceName>,
    /// Wrap mode.
    pub wrap: WrapName,
}

/// The table spelling of [`TextureEntry`].
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct TextureTable {
    file: String,
    colorspace: Option<ColorSpaceName>,
    #[serde(default)]
    wrap: WrapName,
}

impl<'de> Deserialize<'de> for TextureEntry {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(TextureVisitor)
    }
}

struct TextureVisitor;

impl<'de> Visitor<'de> for TextureVisitor {
    type Value = TextureEntry;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(
            "a file path or a table { file = \"...\", colorspace = \"linear\" | \"srgb\", \
             wrap = \"repeat\" | \"clamp\" }",
        )
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<TextureEntry, E> {
        Ok(TextureEntry {
            file: v.to_string(),
            colorspace: None,
            wrap: WrapName::Repeat,
        })
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<TextureEntry, A::Error> {
        let t = TextureTable::deserialize(de::value::MapAccessDeserializer::new(map))?;
        Ok(TextureEntry {
            file: t.file,
            colorspace: t.colorspace,
            wrap: t.wrap,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, serde::Deserialize)]
    struct Doc {
        a: Triple,
        b: Triple,
        t: TextureEntry,
        u: TextureEntry,
    }

    #[test]
    fn both_spellings_parse() {
        let doc: Doc = toml::from_str(
            "a = 2\nb = [0.1, 0.2, 3]\nt = \"x.png\"\n\
             u = { file = \"y.ppm\", colorspace = \"srgb\", wrap = \"clamp\" }",
        )
        .unwrap();
        assert_eq!(doc.a, Triple([2.0; 3]));
        assert_eq!(doc.b, Triple([0.1, 0.2, 3.0]));
        assert_eq!(doc.t.file, "x.png");
        assert_eq!(doc.t.colorspace, None);
        assert_eq!(doc.u.colorspace, Some(ColorSpaceName::Srgb));
        assert_eq!(
            (doc.t.wrap, doc.u.wrap),
            (WrapName::Repeat, WrapName::Clamp)
        );
    }

    #[test]
    fn exact_arrays_reject_other_lengths() {
        #[derive(Debug, serde::Deserialize)]
        struct P {
            p: Coords,
            m: Exact<Exact<f32, 2>, 2>,
        }
        let ok: P = toml::from_str("p = [1, 2, 3]\nm = [[1, 2], [3, 4]]").unwrap();
        assert_eq!(ok.p, Exact([1.0, 2.0, 3.0]));
        assert_eq!(ok.m.0[1], Exact([3.0, 4.0]));
        let long = toml::from_str::<P>("p = [1, 2, 3, 4]\nm = [[1, 2], [3, 4]]").unwrap_err();
        assert!(
            long.message()
                .contains("invalid length 4, expected an array of 3 elements")
        );
        assert_eq!(long.span(), Some(4..16));
        let short = toml::from_str::<P>("p = [1, 2, 3]\nm = [[1, 2], [3]]").unwrap_err();
        assert!(short.message().contains("invalid length 1"));
    }

    #[test]
    fn wrong_lengths_and_fields_are_rejected() {
        let two = toml::from_str::<Doc>("a = [1, 2]\nb = 1\nt = \"x\"\nu = \"y\"");
        assert!(two.unwrap_err().message().contains("invalid length 2"));
        let four = toml::from_str::<Doc>("a = [1, 2, 3, 4]\nb = 1\nt = \"x\"\nu = \"y\"");
        assert!(four.unwrap_err().message().contains("invalid length 4"));
        let typo = toml::from_str::<Doc>("a = 1\nb = 1\nt = { fiel = \"x\" }\nu = \"y\"");
        assert!(typo.unwrap_err().message().contains("unknown field `fiel`"));
    }
}
