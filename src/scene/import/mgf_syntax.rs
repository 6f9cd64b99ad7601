//! The text of an MGF file as entities, and the entities' arguments read with errors that name
//! the entity and the field: logical lines (a `\` before the end of a line continues it; `\n`,
//! `\r\n` and `\r` all end lines), words split at blanks, comments (`#`) dropped, numbers and
//! transforms (`xf` arguments) parsed.

use glam::{DAffine3, DVec3};

/// The longest logical line (continued lines together), in bytes. The MGF specification
/// allows 4096 characters; longer lines are accepted up to this bound.
pub const MAX_LINE_BYTES: usize = 65_536;

/// The most array instances one transform (`-a N -a M …`) may make: the product of its
/// `N`s.
pub const MAX_ARRAY_INSTANCES: u64 = 1_000_000;

/// The entities of one file: its logical lines without comments, kept as text (each one's
/// words separated by single spaces) with the line each starts on, so that a file costs
/// little more memory than its text.
#[derive(Debug, Default)]
pub(super) struct Entities {
    text: String,
    /// Per entity: the line it starts on (from 1) and where its words start in `text`.
    starts: Vec<(u32, u32)>,
}

/// One entity: its keyword and arguments, and the line it starts on.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Entity<'a> {
    /// Line (counted from 1) where the entity starts.
    pub line: usize,
    /// The keyword followed by the arguments.
    pub words: Vec<&'a str>,
}

impl Entity<'_> {
    /// The keyword (`f`, `xf`, …).
    pub fn keyword(&self) -> &str {
        self.words.first().copied().unwrap_or("")
    }

    /// The arguments after the keyword.
    pub fn args(&self) -> &[&str] {
        self.words.get(1..).unwrap_or(&[])
    }
}

impl Entities {
    /// The entities of `text` in order, comments and blank lines left out. Errors (`line N:
    /// what is wrong`) for control characters (binary data), logical lines over
    /// [`MAX_LINE_BYTES`], more than `most` entities and text over 4 GiB.
    pub fn parse(text: &str, most: u64) -> Result<Entities, String> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let mut out = Entities::default();
        let mut logical = String::new();
        let mut start = 1;
        let mut line = 0;
        let mut rest = text;
        while !rest.is_empty() {
            line += 1;
            let end = rest.find(['\n', '\r']).unwrap_or(rest.len());
            let physical = &rest[..end];
            rest = match rest.as_bytes().get(end) {
                Some(b'\r') if rest.as_bytes().get(end + 1) == Some(&b'\n') => &rest[end + 2..],
                Some(_) => &rest[end + 1..],
                None => "",
            };
            if logical.is_empty() {
                start = line;
            }
            if let Some(c) = physical.chars().find(|&c| c.is_control() && !is_blank(c)) {
                return Err(format!(
                    "line {line}: control character U+{:04X}: not an MGF text file (binary data?)",
                    c as u32
                ));
            }
            let (body, continued) = match physical.strip_suffix('\\') {
                Some(body) => (body, true),
                None => (physical, false),
            };
            if logical.len() + body.len() + 1 > MAX_LINE_BYTES {
                return Err(format!(
                    "line {start}: the entity is longer than {MAX_LINE_BYTES} bytes"
                ));
            }
            logical.push_str(body);
            logical.push(' ');
            if continued && !rest.is_empty() {
                continue;
            }
            let mut words = logical.split(is_blank).filter(|w| !w.is_empty()).peekable();
            if words.peek().is_some_and(|k| !k.starts_with('#')) {
                if out.starts.len() as u64 >= most {
                    return Err(format!(
                        "line {start}: more entities than the bound leaves ({most})"
                    ));
                }
                let (Ok(at), Ok(first)) = (u32::try_from(out.text.len()), u32::try_from(start))
                else {
                    return Err(format!("line {start}: the file is larger than 4 GiB"));
                };
                out.starts.push((first, at));
                for (k, word) in words.enumerate() {
                    if k > 0 {
                        out.text.push(' ');
                    }
                    out.text.push_str(word);
                }
                out.text.push('\n');
            }
            logical.clear();
        }
        Ok(out)
    }

    /// The number of entities.
    pub fn len(&self) -> usize {
        self.starts.len()
    }

    /// Entity `i` (below [`Entities::len`]; an empty entity otherwise).
    pub fn get(&self, i: usize) -> Entity<'_> {
        let Some(&(line, at)) = self.starts.get(i) else {
            return Entity {
                line: 0,
                words: Vec::new(),
            };
        };
        let text = self.text.get(at as usize..).unwrap_or("");
        let end = text.find('\n').unwrap_or(text.len());
        Entity {
            line: line as usize,
            words: text[..end].split(' ').collect(),
        }
    }
}

/// The blanks that separate words: space, tab, vertical tab and form feed.
fn is_blank(c: char) -> bool {
    matches!(c, ' ' | '\t' | '\u{b}' | '\u{c}')
}

/// Checks that an entity has between `least` and `most` arguments, naming what they are.
pub(super) fn arity(
    args: &[&str],
    least: usize,
    most: usize,
    synopsis: &str,
) -> Result<(), String> {
    if (least..=most).contains(&args.len()) {
        return Ok(());
    }
    let expected = match (least, most) {
        (l, m) if l == m => format!("{l} argument{}", if l == 1 { "" } else { "s" }),
        (l, usize::MAX) => format!("at least {l} arguments"),
        (l, m) => format!("{l} to {m} arguments"),
    };
    Err(format!(
        "{expected} expected ({synopsis}), got {}",
        args.len()
    ))
}

/// The number `word`, which is the field `field`: finite, or an error naming the field.
pub(super) fn number(word: &str, field: &str) -> Result<f64, String> {
    match word.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(format!("{field}: \"{word}\" is not a finite number")),
        Err(_) => Err(format!("{field}: \"{word}\" is not a number")),
    }
}

/// The three numbers `words[..3]` (the fields `x`, `y`, `z` of `what`) as a vector.
pub(super) fn vector(words: &[&str], what: &str) -> Result<DVec3, String> {
    let [x, y, z] = [0, 1, 2].map(|i| {
        words
            .get(i)
            .ok_or_else(|| format!("{what}: 3 numbers expected, got {}", words.len()))
            .and_then(|w| number(w, &format!("{what} {}", ["x", "y", "z"][i])))
    });
    Ok(DVec3::new(x?, y?, z?))
}

/// A whole number `word` in `0..=most` (the field `field`).
fn count(word: &str, field: &str, most: u64) -> Result<u64, String> {
    match word.parse::<u64>() {
        Ok(n) if n <= most => Ok(n),
        Ok(n) => Err(format!("{field}: {n} is more than the {most} allowed")),
        Err(_) => Err(format!("{field}: \"{word}\" is not a whole number ≥ 0")),
    }
}

/// How often a part of a transform applies.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Repeat {
    /// A fixed number of times (`-i N`; once for the arguments before the first `-i`/`-a`).
    Fixed(u64),
    /// As often as the instance's index along this array dimension (`-a N`: N instances).
    Array(u64),
}

/// The arguments of an `xf` entity (or of an `i` entity after the file name): rigid
/// transforms with uniform scaling, applied to the geometry in the order given, in parts that
/// repeat (`-i N`) or make arrays (`-a N`).
#[derive(Clone, Debug, PartialEq)]
pub(super) struct XfSpec {
    /// Each part with the transform of its arguments, applied in order.
    parts: Vec<(Repeat, DAffine3)>,
}

impl XfSpec {
    /// Parses the transform arguments `args` (`-t dx dy dz`, `-rx|-ry|-rz degrees`, `-s
    /// factor`, `-mx|-my|-mz`, `-i N`, `-a N`); the error names the argument at fault.
    pub fn parse(args: &[&str]) -> Result<XfSpec, String> {
        let mut parts = vec![(Repeat::Fixed(1), DAffine3::IDENTITY)];
        let mut i = 0;
        while i < args.len() {
            let flag = args[i];
            let operand = |k: usize| -> Result<&str, String> {
                args.get(i + k)
                    .copied()
                    .ok_or_else(|| format!("{flag}: {k} argument(s) expected after it"))
            };
            let (step, used) = match flag {
                "-t" => {
                    let words = args.get(i + 1..(i + 4).min(args.len())).unwrap_or(&[]);
                    (DAffine3::from_translation(vector(words, "-t")?), 3)
                }
                "-rx" | "-ry" | "-rz" => {
                    let angle = number(operand(1)?, &format!("{flag} degrees"))?.to_radians();
                    let rotation = match flag {
                        "-rx" => DAffine3::from_rotation_x(angle),
                        "-ry" => DAffine3::from_rotation_y(angle),
                        _ => DAffine3::from_rotation_z(angle),
                    };
                    (rotation, 1)
                }
                "-s" => {
                    let factor = number(operand(1)?, "-s factor")?;
                    if factor == 0.0 {
                        return Err("-s factor: the scale must not be 0".into());
                    }
                    (DAffine3::from_scale(DVec3::splat(factor)), 1)
                }
                "-mx" => (DAffine3::from_scale(DVec3::new(-1.0, 1.0, 1.0)), 0),
                "-my" => (DAffine3::from_scale(DVec3::new(1.0, -1.0, 1.0)), 0),
                "-mz" => (DAffine3::from_scale(DVec3::new(1.0, 1.0, -1.0)), 0),
                "-i" | "-a" => {
                    let n = count(operand(1)?, &format!("{flag} N"), u64::from(u32::MAX))?;
                    let repeat = if flag == "-i" {
                        Repeat::Fixed(n)
                    } else if n == 0 {
                        return Err("-a N: an array needs at least 1 instance".into());
                    } else {
                        Repeat::Array(n)
                    };
                    parts.push((repeat, DAffine3::IDENTITY));
                    i += 2;
                    continue;
                }
                _ => {
                    return Err(format!(
                        "unknown transform argument \"{flag}\" (expected -t, -rx, -ry, -rz, -s, \
                         -mx, -my, -mz, -i or -a)"
                    ));
                }
            };
            if let Some(last) = parts.last_mut() {
                last.1 = step * last.1;
            }
            i += 1 + used;
        }
        let spec = XfSpec { parts };
        let instances = spec.array_sizes().iter().try_fold(1u64, |total, &n| {
            total.checked_mul(n).filter(|&t| t <= MAX_ARRAY_INSTANCES)
        });
        if instances.is_none() {
            return Err(format!(
                "-a: the arrays make more than {MAX_ARRAY_INSTANCES} instances"
            ));
        }
        Ok(spec)
    }

    /// The number of instances along each array dimension (`-a N`), in order; empty when the
    /// transform makes no array.
    pub fn array_sizes(&self) -> Vec<u64> {
        self.parts
            .iter()
            .filter_map(|(repeat, _)| match repeat {
                Repeat::Array(n) => Some(*n),
                Repeat::Fixed(_) => None,
            })
            .collect()
    }

    /// The transform of the array instance `index` (one index per array dimension, each below
    /// its size; empty for a transform without arrays).
    pub fn transform(&self, index: &[u64]) -> DAffine3 {
        let mut dimension = 0;
        self.parts
            .iter()
            .fold(DAffine3::IDENTITY, |total, &(repeat, step)| {
                let times = match repeat {
                    Repeat::Fixed(n) => n,
                    Repeat::Array(_) => {
                        dimension += 1;
                        index.get(dimension - 1).copied().unwrap_or(0)
                    }
                };
                power(step, times) * total
            })
    }
}

/// `step` applied `times` times (by squaring, so a huge `-i N` costs little).
fn power(step: DAffine3, mut times: u64) -> DAffine3 {
    let (mut result, mut base) = (DAffine3::IDENTITY, step);
    while times > 0 {
        if times & 1 == 1 {
            result = base * result;
        }
        base = base * base;
        times >>= 1;
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    fn words(s: &str) -> Vec<&str> {
        s.split_whitespace().collect()
    }

    #[test]
    fn lines_continue_comments_drop_and_every_line_ending_counts() {
        let text = "# comment \\\nstill comment\nv a =\r\n\tp 1 2 \\\n 3\rf a b c\n\n#x\ncxy .3 .3";
        let entities = Entities::parse(text, 10).unwrap();
        let got: Vec<(usize, String)> = (0..entities.len())
            .map(|i| entities.get(i))
            .map(|e| (e.line, e.words.join(" ")))
            .collect();
        assert_eq!(
            got,
            vec![
                (3, "v a =".to_string()),
                (4, "p 1 2 3".to_string()),
                (6, "f a b c".to_string()),
                (9, "cxy .3 .3".to_string()),
            ]
        );
        assert_eq!(entities.get(1).keyword(), "p");
        assert_eq!(entities.get(1).args(), &words("1 2 3")[..]);
        assert!(entities.get(4).words.is_empty());
        let e = Entities::parse("v a =\np 0 0 \u{0}\n", 10).unwrap_err();
        assert!(e.starts_with("line 2: control character U+0000"), "{e}");
        let long = format!("f {}\n", "v ".repeat(MAX_LINE_BYTES));
        assert!(
            Entities::parse(&long, 10)
                .unwrap_err()
                .contains("line 1: the entity is longer")
        );
        let many = Entities::parse("c\n# no\nc\nc\n", 2).unwrap_err();
        assert_eq!(many, "line 4: more entities than the bound leaves (2)");
    }

    #[test]
    fn numbers_and_arity_name_the_field() {
        assert_eq!(number("-.5e1", "rd"), Ok(-5.0));
        assert_eq!(number("x", "rd").unwrap_err(), "rd: \"x\" is not a number");
        assert!(
            number("inf", "rd")
                .unwrap_err()
                .contains("not a finite number")
        );
        assert_eq!(vector(&words("1 2 3"), "p"), Ok(DVec3::new(1.0, 2.0, 3.0)));
        assert!(
            vector(&words("1 q 3"), "p")
                .unwrap_err()
                .starts_with("p y:")
        );
        assert!(
            arity(&words("a b"), 1, 1, "rd rho_d")
                .unwrap_err()
                .contains("1 argument expected")
        );
        assert!(
            arity(&words("a"), 3, usize::MAX, "f v1 v2 v3 …")
                .unwrap_err()
                .contains("at least 3")
        );
    }

    #[test]
    fn transforms_apply_in_order_and_arrays_repeat_their_part() {
        let p = DVec3::new(1.0, 0.0, 0.0);
        // Rotate a quarter turn about z, then move: (1,0,0) → (0,1,0) → (5,1,0).
        let spec = XfSpec::parse(&words("-rz 90 -t 5 0 0")).unwrap();
        assert!(
            spec.transform(&[])
                .transform_point3(p)
                .distance(DVec3::new(5.0, 1.0, 0.0))
                < 1e-12
        );
        // The spec's example: 3 × 4 instances, then moved to (15, 30, 45).
        let spec = XfSpec::parse(&words("-a 3 -t 1 0 0 -a 4 -t 0 1 0 -i 1 -t 15 30 45")).unwrap();
        assert_eq!(spec.array_sizes(), vec![3, 4]);
        let q = spec.transform(&[2, 3]).transform_point3(DVec3::ZERO);
        assert!(q.distance(DVec3::new(17.0, 33.0, 45.0)) < 1e-12);
        // Mirrors flip the determinant; scales multiply: −2³ · (2³)³.
        let spec = XfSpec::parse(&words("-mx -s 2 -i 3 -s 2")).unwrap();
        assert!((spec.transform(&[]).matrix3.determinant() + 4096.0).abs() < 1e-9);
        for (args, says) in [
            ("-t 1 2", "-t: 3 numbers expected"),
            ("-rx", "-rx: 1 argument(s) expected"),
            ("-s 0", "must not be 0"),
            ("-q 1", "unknown transform argument \"-q\""),
            ("-a 0", "at least 1 instance"),
            ("-a x", "-a N: \"x\" is not a whole number"),
            ("-a 1000 -a 1001", "more than 1000000 instances"),
        ] {
            let e = XfSpec::parse(&words(args)).unwrap_err();
            assert!(e.contains(says), "{args}: {e}");
        }
    }
}
