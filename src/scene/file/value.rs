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
        if seq.next_element::<de::IgnoredAny>()?.is_some() {
            return Err(de::Error::invalid_length(4, &self));
        }
        Ok(Triple(out))
    }
}

/// How a texture's 8-bit values are decoded, as written in a scene file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum ColorSpaceName {
    /// Value / 255.
    Linear,
    /// The sRGB transfer curve.
    Srgb,
}

/// A texture reference: `"path"` or `{ file = "path", colorspace = "linear" | "srgb" }`.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct TextureEntry {
    /// Image path, relative to the scene file.
    pub file: String,
    /// Explicit colour space; `None` means the default for the file type.
    pub colorspace: Option<ColorSpaceName>,
}

/// The table spelling of [`TextureEntry`].
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct TextureTable {
    file: String,
    colorspace: Option<ColorSpaceName>,
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
        f.write_str("a file path or a table { file = \"...\", colorspace = \"linear\" | \"srgb\" }")
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<TextureEntry, E> {
        Ok(TextureEntry {
            file: v.to_string(),
            colorspace: None,
        })
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<TextureEntry, A::Error> {
        let t = TextureTable::deserialize(de::value::MapAccessDeserializer::new(map))?;
        Ok(TextureEntry {
            file: t.file,
            colorspace: t.colorspace,
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
            "a = 2\nb = [0.1, 0.2, 3]\nt = \"x.png\"\nu = { file = \"y.ppm\", colorspace = \"srgb\" }",
        )
        .unwrap();
        assert_eq!(doc.a, Triple([2.0; 3]));
        assert_eq!(doc.b, Triple([0.1, 0.2, 3.0]));
        assert_eq!(doc.t.file, "x.png");
        assert_eq!(doc.t.colorspace, None);
        assert_eq!(doc.u.colorspace, Some(ColorSpaceName::Srgb));
    }

    #[test]
    fn wrong_lengths_and_fields_are_rejected() {
        let two = toml::from_str::<Doc>("a = [1, 2]\nb = 1\nt = \"x\"\nu = \"y\"");
        assert!(two.unwrap_err().message().contains("invalid length 2"));
        let four = toml::from_str::<Doc>("a = [1, 2, 3, 4]\nb = 1\nt = \"x\"\nu = \"y\"");
        assert!(four.is_err());
        let typo = toml::from_str::<Doc>("a = 1\nb = 1\nt = { fiel = \"x\" }\nu = \"y\"");
        assert!(typo.unwrap_err().message().contains("unknown field `fiel`"));
    }
}
