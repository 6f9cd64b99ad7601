//! Turning TOML parse and type errors into scene errors: the field path at the error's
//! position and a shorter message with a spelling suggestion for unknown names.

use super::error::{SceneError, Source};
use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// The scene error for a `toml` deserialisation error in `src`.
pub(super) fn toml_error(src: Source<'_>, err: &toml::de::Error) -> SceneError {
    let span = err.span().unwrap_or(0..0);
    let message = err.message();
    if message.starts_with("duplicate key") {
        // The document does not parse, so the key's path is read off the text.
        let line_start = src.text[..span.start.min(src.text.len())]
            .rfind('\n')
            .map_or(0, |i| i + 1);
        if src.text[line_start..].trim_start().starts_with('[') {
            let line_end = src.text[line_start..]
                .find('\n')
                .map_or(src.text.len(), |i| line_start + i);
            let table = header(src.text, line_end).unwrap_or_default();
            return src.error(span, &table, "this table is given twice");
        }
        let key = src.text.get(span.clone()).unwrap_or("").trim();
        let field = match header(src.text, line_start) {
            Some(t) => format!("{t}.{key}"),
            None => key.to_string(),
        };
        return src.error(span, &field, "this key is given twice in its table");
    }
    let field = field_path(src.text, span.start).unwrap_or_else(|| "(document)".to_string());
    let message = if message.starts_with("wanted exactly 1 element") && field.contains("transform[")
    {
        "a transform step is a table of exactly one of translate, rotate, scale or matrix \
         (write one step per transformation)"
            .to_string()
    } else {
        polish_message(message)
    };
    src.error(span, &field, message)
}

/// The path of the `[table]` or `[[array]]` header on the last header line that starts
/// before byte `offset` of `text` (`objects[2]` for the third `[[objects]]`).
fn header(text: &str, offset: usize) -> Option<String> {
    let headers: Vec<&str> = text
        .get(..=offset.min(text.len().saturating_sub(1)))?
        .lines()
        .map(str::trim)
        .filter(|l| l.starts_with('['))
        .collect();
    let last = *headers.last()?;
    let name = |line: &str| {
        line.trim_start_matches('[')
            .split(']')
            .next()
            .unwrap_or("")
            .trim()
            .to_string()
    };
    let table = name(last);
    if !last.starts_with("[[") {
        return Some(table);
    }
    let index = headers
        .iter()
        .filter(|l| l.starts_with("[[") && name(l) == table)
        .count()
        - 1;
    Some(format!("{table}[{index}]"))
}

/// Dotted path (`objects[2].radius`) of the smallest key or value of `text` whose span
/// contains byte `offset`; on a tie the deeper one. Works on the part of a broken document
/// that could be parsed.
pub(super) fn field_path(text: &str, offset: usize) -> Option<String> {
    let (root, _) = DeTable::parse_recoverable(text);
    let mut best: Option<(usize, usize, String)> = None;
    let mut path = Vec::new();
    visit_table(root.get_ref(), offset, &mut path, &mut best);
    best.map(|(_, _, p)| p)
}

/// One step of a field path.
enum Step<'a> {
    Key(&'a str),
    Index(usize),
}

fn render(path: &[Step<'_>]) -> String {
    let mut out = String::new();
    for step in path {
        match step {
            Step::Key(k) => {
                if !out.is_empty() {
                    out.push('.');
                }
                out.push_str(k);
            }
            Step::Index(i) => out.push_str(&format!("[{i}]")),
        }
    }
    out
}

/// Records `path` as the best candidate when `span` contains `offset` and is smaller than
/// (or as small as but deeper than) the current best.
fn consider(
    span: std::ops::Range<usize>,
    offset: usize,
    path: &[Step<'_>],
    best: &mut Option<(usize, usize, String)>,
) {
    let contains = span.contains(&offset) || (span.is_empty() && span.start == offset);
    if !contains || path.is_empty() {
        return;
    }
    let len = span.len();
    let better = match best {
        None => true,
        Some((best_len, best_depth, _)) => {
            len < *best_len || (len == *best_len && path.len() > *best_depth)
        }
    };
    if better {
        *best = Some((len, path.len(), render(path)));
    }
}

fn visit_table<'a>(
    table: &'a DeTable<'a>,
    offset: usize,
    path: &mut Vec<Step<'a>>,
    best: &mut Option<(usize, usize, String)>,
) {
    for (key, value) in table {
        path.push(Step::Key(key.get_ref()));
        consider(key.span(), offset, path, best);
        visit_value(value, offset, path, best);
        path.pop();
    }
}

fn visit_value<'a>(
    value: &'a Spanned<DeValue<'a>>,
    offset: usize,
    path: &mut Vec<Step<'a>>,
    best: &mut Option<(usize, usize, String)>,
) {
    consider(value.span(), offset, path, best);
    match value.get_ref() {
        DeValue::Table(t) => visit_table(t, offset, path, best),
        DeValue::Array(a) => {
            for (i, element) in a.iter().enumerate() {
                path.push(Step::Index(i));
                visit_value(element, offset, path, best);
                path.pop();
            }
        }
        _ => {}
    }
}

/// Shortens `toml`'s messages for unknown fields and variants: with a close known name the
/// long list of expected names becomes a suggestion.
pub(super) fn polish_message(message: &str) -> String {
    let kinds = ["unknown field `", "unknown variant `"];
    let Some(prefix) = kinds.iter().find(|k| message.starts_with(**k)) else {
        return message.to_string();
    };
    let rest = &message[prefix.len()..];
    let Some(end) = rest.find('`') else {
        return message.to_string();
    };
    let unknown = &rest[..end];
    let expected: Vec<&str> = rest[end + 1..].split('`').skip(1).step_by(2).collect();
    match closest(unknown, &expected) {
        Some(near) => format!("{prefix}{unknown}` (did you mean `{near}`?)"),
        None => message.to_string(),
    }
}

/// The name in `known` within edit distance 2 of `word` (and less than half its length),
/// the closest first.
pub(super) fn closest<'a>(word: &str, known: &[&'a str]) -> Option<&'a str> {
    known
        .iter()
        .map(|k| (edit_distance(word, k), *k))
        .filter(|&(d, _)| d <= 2 && d * 2 < word.chars().count().max(2))
        .min_by_key(|&(d, _)| d)
        .map(|(_, k)| k)
}

/// Levenshtein distance in characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitute = diagonal + usize::from(ca != cb);
            diagonal = row[j + 1];
            row[j + 1] = substitute.min(row[j] + 1).min(diagonal + 1);
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    const DOC: &str = "[camera]\nfov = 40\n\n[[objects]]\ntype = \"box\"\n\n[[objects]]\n\
                       type = \"sphere\"\nradius = 2\ntransform = [{ translate = [1, 2, 3] }]\n";

    fn at(needle: &str) -> Option<String> {
        field_path(DOC, DOC.find(needle).unwrap())
    }

    #[test]
    fn paths_name_keys_array_elements_and_tables() {
        assert_eq!(at("fov").as_deref(), Some("camera.fov"));
        assert_eq!(at("40").as_deref(), Some("camera.fov"));
        assert_eq!(at("radius").as_deref(), Some("objects[1].radius"));
        assert_eq!(at("2\n").as_deref(), Some("objects[1].radius"));
        assert_eq!(
            at("3]").as_deref(),
            Some("objects[1].transform[0].translate[2]")
        );
        assert_eq!(at("\"box\"").as_deref(), Some("objects[0].type"));
    }

    #[test]
    fn unknown_names_get_a_suggestion_when_close() {
        let m = "unknown field `radiuss`, expected one of `type`, `radius`, `center`";
        assert_eq!(
            polish_message(m),
            "unknown field `radiuss` (did you mean `radius`?)"
        );
        let far = "unknown field `zzz`, expected `type` or `radius`";
        assert_eq!(polish_message(far), far);
        assert_eq!(edit_distance("sphre", "sphere"), 1);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(closest("whte", &["white", "red"]), Some("white"));
        assert_eq!(closest("x", &["y"]), None);
    }
}
